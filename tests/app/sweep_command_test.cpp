// `railwear sweep` and `railwear merge` end to end (issue 19): a plan's manifest and run ids, a
// small plan run serially (twice: the second run skips every finished line), one line by
// --index and by SLURM_ARRAY_TASK_ID, the per-run databases merged (twice: nothing changes) and
// read by `history`; merge refusing a conflicting run, a foreign SQLite file, a file that is not
// SQLite and a newer schema, with exit 2 and every input byte for byte as it was (-wal included,
// also for an input read through a pending WAL).
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/sweep_test_support.h"
#include "tests/app/wear_scenes.h"
#include "tests/sqlite_test_support.h"

namespace railwear::test {
namespace {

// The small study of wear_scenes.h, shortened to a few steps (a run takes about a second).
std::string ShortStudy() { return SmallStudyOfPasses("5e4"); }

// Two lines: the Archard coefficient at two values.
const char* const kPlan = R"(# a sweep of the wear coefficient
[sweep]
scene = "base.toml"
out_dir = "runs"

[[axis]]
key = "wear.k"
values = [1.0e-4, 2.0e-4]
)";

// The bytes of a database and its -wal and -journal (those that exist).
std::map<std::string, std::string> DatabaseBytes(const fs::path& path) {
  std::map<std::string, std::string> out;
  for (const char* suffix : {"", "-wal", "-journal"}) {
    const fs::path p = path.string() + suffix;
    if (fs::exists(p)) out[suffix] = ReadFile(p);
  }
  return out;
}

class SweepCommandTest : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    Write("base.toml", ShortStudy());
    Write("plan.toml", kPlan);
  }
  // The manifest's run ids, in order.
  std::vector<std::string> Ids() const {
    const Outcome o = Run("sweep plan.toml --list");
    EXPECT_EQ(o.exit_code, 0) << o.err;
    return ManifestIds(o.out);
  }
};

TEST_F(SweepCommandTest, ListPrintsOneLinePerRunWithAStableIdAndItsValues) {
  Write("plan3.toml", std::string(kPlan) + R"(
[[axis]]
key = "traffic[0].friction"
range = { start = 0.2, stop = 0.4, step = 0.1 }
)");
  const Outcome o = Run("sweep plan3.toml --list");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::regex line(
      R"((\d{4})-[0-9a-f]{8}  wear\.k=(0\.0001|0\.0002) traffic\[0\]\.friction=0\.[234])");
  std::istringstream in(o.out);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 6u) << o.out;
  for (size_t i = 0; i < lines.size(); ++i) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(lines[i], m, line)) << lines[i];
    EXPECT_EQ(std::stoi(m[1].str()), static_cast<int>(i));
  }
  // The first axis varies slowest; the range has no rounding noise (0.1 + 0.1 is 0.2).
  EXPECT_TRUE(Contains(lines[0], "wear.k=0.0001 traffic[0].friction=0.2"));
  EXPECT_TRUE(Contains(lines[5], "wear.k=0.0002 traffic[0].friction=0.4"));
  // The same plan read from another folder gives the same ids.
  fs::create_directories(dir_ / "elsewhere");
  const Outcome again = Run("sweep ../plan3.toml --list", "cd elsewhere &&");
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(again.out, o.out);
}

// The serial sweep, run twice, merged twice, and read by history.
TEST_F(SweepCommandTest, SerialSweepThenMergeThenHistory) {
  const std::vector<std::string> ids = Ids();
  ASSERT_EQ(ids.size(), 2u);
  const Outcome first = Run("sweep plan.toml");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  for (const std::string& id : ids) {
    EXPECT_TRUE(fs::exists(dir_ / "runs" / (id + ".sqlite")));
    EXPECT_TRUE(fs::exists(dir_ / "runs" / (id + ".toml")));
    EXPECT_TRUE(Contains(first.out, "run '" + id + "' in runs/" + id + ".sqlite")) << first.out;
  }
  // Run twice: every line is complete, so nothing runs and no database changes.
  std::map<std::string, std::string> before;
  for (const std::string& id : ids) {
    ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "runs" / (id + ".sqlite")).string());
    before[id] = std::to_string(store.Steps(store.FindRun(id)->id).size());
    EXPECT_EQ(store.FindRun(id)->state, RunState::kComplete);
  }
  const Outcome second = Run("sweep plan.toml");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  for (const std::string& id : ids) {
    EXPECT_TRUE(Contains(second.err, "(" + id + "): complete in runs/" + id + ".sqlite; skipped"));
    ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "runs" / (id + ".sqlite")).string());
    EXPECT_EQ(std::to_string(store.Steps(store.FindRun(id)->id).size()), before[id]);
  }

  const std::string inputs = "runs/" + ids[0] + ".sqlite runs/" + ids[1] + ".sqlite";
  const Outcome merge = Run("merge study.sqlite " + inputs);
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  EXPECT_TRUE(Contains(merge.out, "runs/" + ids[0] + ".sqlite: 1 run(s) copied, 0 already"));
  const std::string all_rows =
      "history --db study.sqlite sql \"SELECT r.name, s.step, s.passes, s.w2_mm, "
      "hex(p.yz) FROM runs r JOIN steps s ON s.run_id = r.id JOIN profiles p ON "
      "p.run_id = s.run_id AND p.step = s.step ORDER BY 1, 2\"";
  const Outcome rows = Run(all_rows);
  ASSERT_EQ(rows.exit_code, 0) << rows.err;
  // Merging again changes nothing.
  const Outcome again = Run("merge study.sqlite " + inputs);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(Contains(again.out, "0 run(s) copied, 1 already in study.sqlite (same content)"));
  EXPECT_EQ(Run(all_rows).out, rows.out);

  // history reads the merged file like any other.
  const Outcome runs = Run("history --db study.sqlite runs");
  ASSERT_EQ(runs.exit_code, 0) << runs.err;
  for (const std::string& id : ids) EXPECT_TRUE(Contains(runs.out, id));
  EXPECT_TRUE(Contains(runs.out, "complete"));
  for (const std::string& id : ids) {
    const Outcome merged = Run("history --db study.sqlite steps " + id);
    const Outcome own = Run("history --db runs/" + id + ".sqlite steps " + id);
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    EXPECT_EQ(merged.out, own.out);  // the same steps, to the last digit printed
  }
  // A larger coefficient wears more: the two lines really differ.
  const Outcome w =
      Run("history --db study.sqlite sql \"SELECT r.name, max(s.worn_area_mm2) / max(s.mgt) FROM "
          "runs r JOIN steps s ON s.run_id = r.id GROUP BY r.name ORDER BY r.name\"");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const std::regex rates(R"(([0-9.e+-]+)\s*\n[^\n]*?([0-9.e+-]+)\s*\n?$)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(w.out, m, rates)) << w.out;
  EXPECT_GT(std::stod(m[2].str()), 1.5 * std::stod(m[1].str())) << w.out;
}

TEST_F(SweepCommandTest, IndexAndSlurmArrayTaskIdRunOneLine) {
  const std::vector<std::string> ids = Ids();
  ASSERT_EQ(ids.size(), 2u);
  const Outcome one = Run("sweep plan.toml", "SLURM_ARRAY_TASK_ID=1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_TRUE(fs::exists(dir_ / "runs" / (ids[1] + ".sqlite")));
  EXPECT_FALSE(fs::exists(dir_ / "runs" / (ids[0] + ".sqlite")));
  const Outcome zero = Run("sweep plan.toml --index 0 --threads 1");
  ASSERT_EQ(zero.exit_code, 0) << zero.err;
  EXPECT_TRUE(fs::exists(dir_ / "runs" / (ids[0] + ".sqlite")));

  const Outcome far = Run("sweep plan.toml --index 2");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_TRUE(Contains(far.err, "--index 2: the plan plan.toml has 2 line(s); expected 0 to 1"));
  const Outcome bad = Run("sweep plan.toml", "SLURM_ARRAY_TASK_ID=x1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "SLURM_ARRAY_TASK_ID = 'x1'"));
}

// A database of a line whose scene changed since (the base scene edited) is refused, not resumed.
TEST_F(SweepCommandTest, ALineWhoseSceneChangedIsRefused) {
  ASSERT_EQ(Run("sweep plan.toml --index 0").exit_code, 0);
  const std::string id = Ids()[0];
  const fs::path db = dir_ / "runs" / (id + ".sqlite");
  const auto bytes = DatabaseBytes(db);
  // Same index and hash only if the scene is the same: force the old id onto a new scene by
  // copying the old database to the new id.
  std::string edited = ShortStudy();
  edited.replace(edited.find("friction = 0.4"), 14, "friction = 0.35");
  Write("base.toml", edited);
  const std::string new_id = Ids()[0];
  EXPECT_NE(new_id, id);  // the id follows the scene
  fs::copy_file(db, dir_ / "runs" / (new_id + ".sqlite"));
  RawExec((dir_ / "runs" / (new_id + ".sqlite")).string(),
          "UPDATE runs SET name = '" + new_id + "' WHERE name = '" + id + "'");
  const Outcome o = Run("sweep plan.toml --index 0");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "was started from another scene than line 0 of plan.toml"));
  EXPECT_EQ(DatabaseBytes(db), bytes);
}

TEST_F(SweepCommandTest, ARejectedValueNamesThePlanLineTheAxisAndTheValue) {
  Write("bad.toml", R"([sweep]
scene = "base.toml"

[[axis]]
key = "wear.k"
values = [1.0e-4, -2.0e-4]
)");
  const Outcome o = Run("sweep bad.toml --list");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "bad.toml:6: axis 'wear.k' = -0.0002 (run 0001-"));
  EXPECT_TRUE(Contains(o.err, "rejects it: key 'wear.k' = -0.0002: expected"));
  EXPECT_FALSE(Contains(o.err, "base.toml:"));  // no line of the generated scene text
  EXPECT_TRUE(o.out.empty());
  EXPECT_FALSE(fs::exists(dir_ / "bad_runs"));
}

// A cases file is one axis: its rows, combined with the other axes.
TEST_F(SweepCommandTest, CasesFileRowsAreLines) {
  Write("cases.csv",
        "# friction and speed of the one traffic entry\n"
        "traffic[0].friction, traffic[0].speed_m_s\n0.3, 20\n0.5, 25\n");
  Write("cases.toml", std::string(kPlan) + "\n[[axis]]\ncases = \"cases.csv\"\n");
  const Outcome o = Run("sweep cases.toml --list");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "-"));
  EXPECT_TRUE(Contains(o.out, "wear.k=0.0001 traffic[0].friction=0.3 traffic[0].speed_m_s=20\n"));
  EXPECT_TRUE(Contains(o.out, "wear.k=0.0002 traffic[0].friction=0.5 traffic[0].speed_m_s=25\n"));
  Write("cases.csv", "traffic[0].friction\n0.3\n9.5\n");
  const Outcome bad = Run("sweep cases.toml --list");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "cases.csv:3: axis 'traffic[0].friction' = 9.5"));
}

// ---------------------------------------------------------------------------------------------
// merge refusals: exit 2, a clear message, every input byte for byte as it was.

class MergeRefusalTest : public CliFixture {
 protected:
  // Two study files with a run of the same name and different content.
  void WriteConflict() {
    Write("a.toml", ShortStudy());
    std::string other = ShortStudy();
    other.replace(other.find("k = 1e-4"), 8, "k = 3e-4");
    Write("b.toml", other);
    ASSERT_EQ(Run("wear a.toml --db a.sqlite --run same --steps 1").exit_code, 0);
    ASSERT_EQ(Run("wear b.toml --db b.sqlite --run same --steps 1").exit_code, 0);
  }
  // Runs `merge ARGS`; expects exit 2, `message` in stderr and `inputs` unchanged.
  void ExpectRefused(const std::string& args, const std::vector<std::string>& inputs,
                     const std::string& message) {
    std::map<std::string, std::map<std::string, std::string>> before;
    for (const std::string& in : inputs) before[in] = DatabaseBytes(dir_ / in);
    const Outcome o = Run("merge " + args);
    EXPECT_EQ(o.exit_code, 2) << o.err;
    EXPECT_TRUE(Contains(o.err, message));
    for (const std::string& in : inputs) EXPECT_EQ(DatabaseBytes(dir_ / in), before[in]) << in;
  }
};

TEST_F(MergeRefusalTest, RefusesAConflictingRun) {
  WriteConflict();
  ASSERT_EQ(Run("merge out.sqlite a.sqlite").exit_code, 0);
  const auto out_before = Run("history --db out.sqlite steps same").out;
  ExpectRefused("out.sqlite b.sqlite", {"a.sqlite", "b.sqlite"},
                "database 'b.sqlite': run 'same' conflicts with the run of that name in "
                "'out.sqlite' (table 'runs', row 0 (in primary-key order), column "
                "'scene_text' differs)");
  EXPECT_EQ(Run("history --db out.sqlite steps same").out, out_before);
}

TEST_F(MergeRefusalTest, RefusesForeignNonSqliteAndNewerFilesBeforeWritingAnything) {
  WriteConflict();
  RawExec((dir_ / "foreign.db").string(), "CREATE TABLE t(x); INSERT INTO t VALUES (1);");
  Write("notes.txt", "not a database\n");
  fs::copy_file(dir_ / "a.sqlite", dir_ / "newer.sqlite");
  RawExec((dir_ / "newer.sqlite").string(),
          "PRAGMA user_version = " + std::to_string(ProfileStore::kSchemaVersion + 1));
  ExpectRefused("out.sqlite a.sqlite foreign.db", {"a.sqlite", "foreign.db"},
                "database 'foreign.db': an SQLite database of another application");
  ExpectRefused("out.sqlite a.sqlite notes.txt", {"a.sqlite", "notes.txt"},
                "database 'notes.txt': not an SQLite database");
  ExpectRefused("out.sqlite newer.sqlite", {"newer.sqlite"}, "written by a newer railwear");
  ExpectRefused("a.sqlite a.sqlite", {"a.sqlite"}, "input 'a.sqlite' is the output");
  EXPECT_FALSE(fs::exists(dir_ / "out.sqlite"));  // every input is checked before the output
}

// An input being written (a line still running: its rows partly in a -wal) is read through its
// WAL, and neither it nor its -wal changes; a conflicting input with a pending WAL neither.
TEST_F(MergeRefusalTest, ReadsAnInputThroughItsPendingWalWithoutChangingIt) {
  WriteConflict();
  sqlite3* writer = nullptr;  // another process's connection, kept open: the WAL stays pending
  ASSERT_EQ(sqlite3_open((dir_ / "b.sqlite").c_str(), &writer), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(writer, "PRAGMA wal_autocheckpoint = 0; UPDATE runs SET state = 'complete'",
                   nullptr, nullptr, nullptr),
      SQLITE_OK);
  ASSERT_GT(fs::file_size(dir_ / "b.sqlite-wal"), 0u);
  const auto before = DatabaseBytes(dir_ / "b.sqlite");
  const Outcome o = Run("merge out.sqlite b.sqlite");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(Run("history --db out.sqlite runs").out, "complete"));  // the WAL's row
  EXPECT_EQ(DatabaseBytes(dir_ / "b.sqlite"), before);
  ExpectRefused("out.sqlite a.sqlite b.sqlite", {"a.sqlite", "b.sqlite"},
                "database 'a.sqlite': run 'same' conflicts");
  EXPECT_EQ(DatabaseBytes(dir_ / "b.sqlite"), before);
  sqlite3_close(writer);
}

}  // namespace
}  // namespace railwear::test
