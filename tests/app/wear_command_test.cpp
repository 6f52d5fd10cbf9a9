// `railwear wear` end to end: a small wear study stored step by step, killed with SIGKILL in the
// middle and resumed to the same final profile as an uninterrupted run; bad databases refused
// and left untouched; wrong scenes and run names refused with exit code 2.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"
#include "wear/spread_integration.h"

namespace railwear::test {
namespace {

const char* const kStudy = kSmallWearStudy;

using WearCommandTest = CliFixture;

Profile LastProfile(const fs::path& db, const std::string& run) {
  ProfileStore store = ProfileStore::Open(db.string());
  const auto info = store.FindRun(run);
  EXPECT_TRUE(info.has_value());
  return store.LoadProfile(info->id, *store.LastStep(info->id));
}

TEST_F(WearCommandTest, RunStoresEveryStepAndPrintsASummary) {
  Write("study.toml", kStudy);
  const Outcome o = Run("wear study.toml --db a.sqlite --steps 3");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "run 'small study' in a.sqlite: 3 steps (not complete: --resume)"));
  EXPECT_TRUE(Contains(o.err, "railwear: step 1: "));  // plain log lines: stderr is no terminal
  ProfileStore store = ProfileStore::Open((dir_ / "a.sqlite").string());
  const auto run = store.FindRun("small study");
  ASSERT_TRUE(run.has_value());
  const std::vector<StepRecord> steps = store.Steps(run->id);
  ASSERT_EQ(steps.size(), 4u);  // step 0 (unworn) + 3
  for (int i = 1; i < 4; ++i) {
    EXPECT_GT(steps[i].passes, steps[i - 1].passes);
    EXPECT_GT(steps[i].max_depth_mm, steps[i - 1].max_depth_mm);
    EXPECT_GT(steps[i].worn_area_mm2, 0.0);
  }
  const StepRecord last = store.LoadStep(run->id, 3);
  EXPECT_EQ(last.load_cases_json.size(), 3u);  // three quadrature nodes
  bool has_depth = false, has_damage = false;
  for (const Distribution& d : last.distributions) {
    has_depth = has_depth || d.kind == "wear_depth_mm";
    has_damage = has_damage || d.kind == "rcf_damage";
  }
  EXPECT_TRUE(has_depth);
  EXPECT_TRUE(has_damage);
  // The same name again is refused; the database keeps its steps.
  const Outcome again = Run("wear study.toml --db a.sqlite --steps 1");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_TRUE(Contains(again.err, "run 'small study' exists already"));
  EXPECT_EQ(ProfileStore::Open((dir_ / "a.sqlite").string()).Steps(run->id).size(), 4u);
}

// Without quadrature_points a scene integrates its spreads by the adaptive rule (issue 16
// point 5): the log names each step's nodes per entry, the summary their range over the run,
// the run's parameters the rule, and every stored load case its node and its entry's nodes.
TEST_F(WearCommandTest, AdaptiveSpreadNodesAreLoggedSummarisedAndStored) {
  std::string scene = kStudy;
  scene.erase(scene.find("quadrature_points = 3\n"), std::string("quadrature_points = 3\n").size());
  Write("study.toml", scene);
  const Outcome o = Run("wear study.toml --db a.sqlite --steps 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.err, "railwear: step 1: spread nodes: traffic[0] ")) << o.err;
  EXPECT_TRUE(Contains(o.err, "(adaptive, ")) << o.err;
  EXPECT_TRUE(Contains(o.out,
                       "spread integration: adaptive to 0.5 % of the step's worn area and 2 % "
                       "of its depth field, nodes per step: traffic[0] "))
      << o.out;
  ProfileStore store = ProfileStore::Open((dir_ / "a.sqlite").string());
  const auto run = store.FindRun("small study");
  ASSERT_TRUE(run.has_value());
  EXPECT_TRUE(Contains(run->wear_law_json, R"("rule":"adaptive")")) << run->wear_law_json;
  EXPECT_TRUE(Contains(run->wear_law_json, R"("tolerance":0.005)")) << run->wear_law_json;
  const StepRecord step = store.LoadStep(run->id, 1);
  ASSERT_GE(step.load_cases_json.size(), kSpreadInitialNodes.size());  // at least the first nodes
  const std::string nodes = "\"entry_nodes\":" + std::to_string(step.load_cases_json.size());
  for (const std::string& j : step.load_cases_json) {
    EXPECT_TRUE(Contains(j, nodes)) << j;
    EXPECT_TRUE(Contains(j, R"("spread_x":)")) << j;
  }
}

// The fixed piecewise-linear rule by name (spread_rule = "piecewise_linear", spread_nodes = 8:
// 8 nodes within +-3 std and one per tail, 10 per spread): the log and the summary name the
// rule, the run's parameters store it with its node count, and the step has a case per node.
TEST_F(WearCommandTest, PiecewiseLinearSpreadRuleIsNamedAndStored) {
  std::string scene = kStudy;
  const std::string gh = "quadrature_points = 3\n";
  scene.replace(scene.find(gh), gh.size(),
                "spread_rule = \"piecewise_linear\"\nspread_nodes = 8\n");
  Write("study.toml", scene);
  const Outcome o = Run("wear study.toml --db a.sqlite --steps 1");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(
      Contains(o.err, "railwear: step 1: spread nodes: traffic[0] 10 (fixed piecewise-linear)"))
      << o.err;
  EXPECT_TRUE(Contains(o.out,
                       "spread integration: fixed piecewise-linear rule, nodes per step: "
                       "traffic[0] 10"))
      << o.out;
  ProfileStore store = ProfileStore::Open((dir_ / "a.sqlite").string());
  const auto run = store.FindRun("small study");
  ASSERT_TRUE(run.has_value());
  EXPECT_TRUE(Contains(run->wear_law_json, R"("rule":"piecewise-linear")")) << run->wear_law_json;
  EXPECT_TRUE(Contains(run->wear_law_json, R"("spread_nodes":8)")) << run->wear_law_json;
  EXPECT_TRUE(Contains(run->wear_law_json, R"("nodes":10)")) << run->wear_law_json;
  EXPECT_EQ(store.LoadStep(run->id, 1).load_cases_json.size(), 10u);
}

TEST_F(WearCommandTest, KilledRunResumesToTheSameProfile) {
  Write("study.toml", kStudy);
  const Outcome whole = Run("wear study.toml --db whole.sqlite --threads 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const Profile expected = LastProfile(dir_ / "whole.sqlite", "small study");

  // Start the same run in the background and kill it with SIGKILL once two steps are stored.
  const std::string pid_file = (dir_ / "pid").string();
  const std::string start = Command("wear study.toml --db killed.sqlite --threads 1") +
                            " > /dev/null 2>&1 & echo $! > '" + pid_file + "'";
  ASSERT_EQ(std::system(start.c_str()), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  pid_t pid = 0;
  int stored = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (pid == 0) pid = std::atoi(ReadFile(pid_file).c_str());
    if (pid == 0 || !fs::exists(dir_ / "killed.sqlite")) continue;
    try {
      const QueryResult q =
          ProfileStore::Open((dir_ / "killed.sqlite").string()).Query("SELECT COUNT(*) FROM steps");
      stored = std::stoi(q.rows.at(0).at(0));
    } catch (const std::exception&) {
      continue;  // the database is still being created
    }
    if (stored >= 3) break;
  }
  ASSERT_GT(pid, 0);
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_GE(stored, 3);
  ProfileStore killed = ProfileStore::Open((dir_ / "killed.sqlite").string());
  const auto run = killed.FindRun("small study");
  ASSERT_TRUE(run.has_value());
  EXPECT_NE(run->state, RunState::kComplete);  // it was killed before the end
  const int steps_at_kill = *killed.LastStep(run->id);

  const Outcome resumed = Run("wear study.toml --db killed.sqlite --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_TRUE(Contains(resumed.err, "resuming run 'small study' from step"));
  const Profile got = LastProfile(dir_ / "killed.sqlite", "small study");
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_EQ(got.points(), expected.points());  // bit for bit
  ProfileStore after = ProfileStore::Open((dir_ / "killed.sqlite").string());
  EXPECT_EQ(after.FindRun("small study")->state, RunState::kComplete);
  EXPECT_GT(*after.LastStep(run->id), steps_at_kill);
}

// The second-order time step (time_step = "heun", docs/wear.md "A second-order step") on vehicle
// traffic: the next step's curving starts from the predictor's solution, which the stored state
// carries, so a run stopped after a step (--steps) and resumed ends bit for bit as the whole run.
TEST_F(WearCommandTest, HeunRunStoppedAndResumedEndsBitIdentically) {
  std::string scene = kWheelsetCurveScene;
  scene.replace(scene.find("total_passes = 1e5"), 18,
                "total_passes = 1e6\nmax_depth_per_step_mm = 0.005\ntime_step = \"heun\"");
  Write("curve.toml", scene);
  const Outcome whole = Run("wear curve.toml --db whole.sqlite --threads 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  ProfileStore store = ProfileStore::Open((dir_ / "whole.sqlite").string());
  const int steps = *store.LastStep(store.FindRun("wheelset on R1500")->id);
  ASSERT_GE(steps, 3);  // the resumed part has a step that continues a stored curving
  const Outcome first = Run("wear curve.toml --db cut.sqlite --threads 1 --steps 1");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const Outcome rest = Run("wear curve.toml --db cut.sqlite --threads 1 --resume");
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  const Profile expected = LastProfile(dir_ / "whole.sqlite", "wheelset on R1500");
  const Profile got = LastProfile(dir_ / "cut.sqlite", "wheelset on R1500");
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_EQ(got.points(), expected.points());  // bit for bit
  const std::string passes = "SELECT passes, w2_mm FROM steps ORDER BY step";
  EXPECT_EQ(ProfileStore::Open((dir_ / "cut.sqlite").string()).Query(passes).rows,
            store.Query(passes).rows);
}

TEST_F(WearCommandTest, ForeignOrCorruptDatabaseIsRefusedAndUntouched) {
  Write("study.toml", kStudy);
  const std::string junk = "this is not a database\n";
  Write("notes.sqlite", junk);
  const Outcome o = Run("wear study.toml --db notes.sqlite --steps 1");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "notes.sqlite"));
  EXPECT_EQ(ReadFile(dir_ / "notes.sqlite"), junk);
  EXPECT_FALSE(fs::exists(dir_ / "notes.sqlite-wal"));
}

TEST_F(WearCommandTest, BadInvocationsExitTwo) {
  Write("study.toml", kStudy);
  const Outcome resume = Run("wear study.toml --db new.sqlite --resume");
  EXPECT_EQ(resume.exit_code, 2);
  EXPECT_TRUE(Contains(resume.err, "no run 'small study' to resume"));
  // A contact scene is not a wear scene, and the other way round.
  Write("contact.toml",
        "[wheel]\nprofile = \"builtin:S1002\"\nrolling_radius_mm = 460\n"
        "[rail]\nprofile = \"builtin:UIC60\"\n[load]\nvertical_N = 1e5\n");
  const Outcome contact = Run("wear contact.toml --db c.sqlite");
  EXPECT_EQ(contact.exit_code, 2);
  EXPECT_TRUE(Contains(contact.err, "scene.effects has no \"wear\""));
  const Outcome wear_as_contact = Run("contact study.toml");
  EXPECT_EQ(wear_as_contact.exit_code, 2);
  EXPECT_TRUE(Contains(wear_as_contact.err, "run it with `railwear wear study.toml`"));
  // Resuming with a changed scene is refused.
  ASSERT_EQ(Run("wear study.toml --db s.sqlite --steps 1").exit_code, 0);
  std::string changed = kStudy;
  changed.replace(changed.find("k = 1e-4"), 8, "k = 2e-4");
  Write("study.toml", changed);
  const Outcome mismatch = Run("wear study.toml --db s.sqlite --resume");
  EXPECT_EQ(mismatch.exit_code, 2);
  EXPECT_TRUE(Contains(mismatch.err, "was started from a different scene"));
}

}  // namespace
}  // namespace railwear::test

namespace railwear::test {
namespace {

TEST_F(WearCommandTest, DefaultStudyExampleRunsTwoSteps) {
  // The imposed-position study (the README's earlier main job), cut to two steps.
  const Outcome o =
      Run("wear '" RAILWEAR_SOURCE_DIR "/examples/wear_high_rail.toml' --db demo.sqlite --steps 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "run 'UIC60 high rail' in demo.sqlite: 2 steps"));
  ProfileStore store = ProfileStore::Open((dir_ / "demo.sqlite").string());
  const auto run = store.FindRun("UIC60 high rail");
  ASSERT_TRUE(run.has_value());
  const std::vector<StepRecord> steps = store.Steps(run->id);
  ASSERT_EQ(steps.size(), 3u);
  // Gauge-corner wear: the deepest point lies on the gauge side of the crown (y < -25 mm).
  EXPECT_NEAR(steps[2].max_depth_mm, 0.2, 0.02);
  EXPECT_LT(steps[2].max_depth_y_mm, -25.0);
}

}  // namespace
}  // namespace railwear::test
