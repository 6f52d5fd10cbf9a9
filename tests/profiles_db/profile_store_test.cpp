// Tests of ProfileStore: create/open/reopen, schema version, runs, steps in order, exact profile
// round trip, all-or-nothing steps, refusal of files that are not railwear databases (with the
// file left byte-for-byte untouched), and the read-only query helper. Mostly on ":memory:".
#include "profiles_db/profile_store.h"

#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "tests/sqlite_test_support.h"

namespace railwear {
namespace {

namespace fs = std::filesystem;

// A temporary folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("railwear_db_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string File(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

// RawExec (tests/sqlite_test_support.h) builds foreign or future databases.
using test::RawExec;

// An SQL BLOB literal X'..' of doubles as little-endian IEEE-754 float64 (SCHEMA.md layout).
std::string BlobLiteral(const std::vector<double>& values) {
  static const char* kHex = "0123456789ABCDEF";
  std::string out = "X'";
  for (double v : values) {
    const auto bits = std::bit_cast<uint64_t>(v);
    for (int i = 0; i < 8; ++i) {
      const unsigned byte = (bits >> (8 * i)) & 0xffu;
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    }
  }
  return out + "'";
}

// The schema of railwear's version 1, verbatim (what MigrateTo1 created), with one run, one step,
// its profile, a load case and a distribution: a database as version 1 left it.
std::string Version1Database() {
  const std::vector<double> yz = {-0.02, 0.0016, -0.01,  0.0004, 0.0,
                                  0.0,   0.01,   0.0004, 0.02,   0.0016};
  return std::string(R"sql(
PRAGMA application_id = 1381450818;
CREATE TABLE meta(
  key   TEXT PRIMARY KEY,
  value TEXT NOT NULL);
CREATE TABLE runs(
  id              INTEGER PRIMARY KEY,
  name            TEXT NOT NULL UNIQUE,
  created_utc     TEXT NOT NULL,
  program_version TEXT NOT NULL,
  scene_text      TEXT NOT NULL,
  wear_law_json   TEXT NOT NULL,
  state           TEXT NOT NULL CHECK (state IN ('running', 'complete', 'aborted')));
CREATE TABLE steps(
  run_id               INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  step                 INTEGER NOT NULL CHECK (step >= 0),
  passes               REAL NOT NULL,
  mgt                  REAL NOT NULL,
  worn_area_mm2        REAL NOT NULL,
  max_depth_mm         REAL NOT NULL,
  max_depth_y_mm       REAL NOT NULL,
  w1_mm                REAL NOT NULL,
  w2_mm                REAL NOT NULL,
  w3_mm                REAL NOT NULL,
  smoothing_area_error REAL NOT NULL,
  created_utc          TEXT NOT NULL,
  PRIMARY KEY (run_id, step));
CREATE TABLE profiles(
  run_id   INTEGER NOT NULL,
  step     INTEGER NOT NULL,
  n_points INTEGER NOT NULL,
  yz       BLOB NOT NULL CHECK (length(yz) = 16 * n_points),
  PRIMARY KEY (run_id, step),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
CREATE TABLE load_cases(
  run_id     INTEGER NOT NULL,
  step       INTEGER NOT NULL,
  case_index INTEGER NOT NULL,
  json       TEXT NOT NULL,
  PRIMARY KEY (run_id, step, case_index),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
CREATE TABLE distributions(
  run_id INTEGER NOT NULL,
  step   INTEGER NOT NULL,
  kind   TEXT NOT NULL,
  y      BLOB NOT NULL,
  value  BLOB NOT NULL CHECK (length(value) = length(y)),
  PRIMARY KEY (run_id, step, kind),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
INSERT INTO meta(key, value) VALUES ('format', 'railwear-profile-history'),
                                    ('schema_doc', 'profiles_db/SCHEMA.md in the railwear sources');
INSERT INTO runs VALUES (1, 'old', '2024-05-01T12:00:00.000Z', '0.0.9', 'scene', '{}', 'complete');
INSERT INTO steps VALUES (1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, '2024-05-01T12:00:01.000Z');
INSERT INTO load_cases VALUES (1, 0, 0, '{"case":0}');
)sql") + "INSERT INTO profiles VALUES (1, 0, 5, " +
         BlobLiteral(yz) + ");\n" + "INSERT INTO distributions VALUES (1, 0, 'wear_depth_mm', " +
         BlobLiteral({-0.01, 0.0, 0.01}) + ", " + BlobLiteral({0.0, 0.25, 0.5}) + ");\n" +
         "PRAGMA user_version = 1;\n";
}

// A database as version 2 left it: version 1's, distributions.s added (MigrateTo2, verbatim),
// and a step-1 distribution that has s.
std::string Version2Database() {
  std::string sql = Version1Database();
  sql.replace(sql.find("PRAGMA user_version = 1;"), 24,
              "ALTER TABLE distributions ADD COLUMN s BLOB "
              "CHECK (s IS NULL OR length(s) = length(value));\n"
              "INSERT INTO steps VALUES (1, 1, 100, 0.002, 0.5, 0.01, -0.03, 0, 0.1, 0.2, 1e-6, "
              "'2024-05-02T12:00:00.000Z');\n"
              "INSERT INTO profiles VALUES (1, 1, 4, " +
                  BlobLiteral({-0.02, 0.0016, -0.01, 0.0004, 0.0, 0.0, 0.01, 0.0004}) + ");\n" +
                  "INSERT INTO distributions VALUES (1, 1, 'wear_depth_mm', " + BlobLiteral({0.0}) +
                  ", " + BlobLiteral({0.125}) + ", " + BlobLiteral({0.5}) + ");\n" +
                  "PRAGMA user_version = 2;");
  return sql;
}

CalibrationRecord TestCalibration() {
  CalibrationRecord c;
  c.name = "paper experiment";
  c.program_version = "0.1.0";
  c.config_path = "calibrate.toml";
  c.config_text = "[calibration]\nname = \"paper experiment\"\n";
  c.status = "converged";
  c.well_conditioned = false;
  c.constants_json = R"([{"name":"c_f","value":1.05,"standard_error":0.001}])";
  c.correlation_json = "[[1.0]]";
  c.residuals_json = R"({"curves":[]})";
  c.ceres_report = "Solver Summary ...";
  c.constants_toml = "[influence_constants]\nc_f = 1.05\n";
  c.inputs = {{"config", "calibrate.toml", c.config_text},
              {"displacement_curves", "r15.csv", "# railwear displacement curves v1\n\xc3\xa9"}};
  return c;
}

// A rail-like profile whose coordinates use all 53 mantissa bits (and one negative zero).
Profile TestProfile(int n = 40, double shift_m = 0.0) {
  std::vector<Eigen::Vector2d> p(n);
  for (int i = 0; i < n; ++i) {
    const double t = -0.6 + 1.2 * i / (n - 1);
    p[i] = {0.3 * std::sin(t) + shift_m, 0.3 * (1.0 - std::cos(t)) / 3.0};
  }
  p[0].y() = -0.0;
  return Profile(std::move(p), "test");
}

RunInfo TestRun(const std::string& name) {
  RunInfo r;
  r.name = name;
  r.program_version = "0.1.0";
  r.scene_text = "[wheel]\nprofile = \"builtin:S1002\"\n# \xc3\xa9t\xc3\xa9\n";
  r.wear_law_json = R"({"law":"archard","k":1e-4})";
  return r;
}

StepRecord TestStep(int step) {
  StepRecord s;
  s.step = step;
  s.passes = 1000.0 * step;
  s.mgt = 0.02 * step;
  s.worn_area_mm2 = 0.5 * step;
  s.max_depth_mm = 0.01 * step;
  s.max_depth_y_mm = -31.25;
  s.w1_mm = 0.1;
  s.w2_mm = 0.2;
  s.w3_mm = 0.3;
  s.smoothing_area_error = 1e-4;
  s.profile = TestProfile(40, 1e-5 * step);
  s.load_cases_json = {R"({"case":0,"T_gamma":12.5})", R"({"case":1,"T_gamma":3.25})"};
  s.distributions = {{"wear_depth_mm", {-0.01, 0.0, 0.01}, {0.0, 1e-3, 2e-3}},
                     {"damage", {-0.01, 0.0, 0.01}, {1e-7, 2e-7, 3e-7}}};
  return s;
}

// Expects `f` to throw InputError whose message contains every one of `parts`.
template <typename F>
void ExpectInputError(F f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const auto& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message '" << e.what() << "' lacks '" << part << "'";
    }
  }
}

TEST(ProfileStore, CreatesSchemaInMemory) {
  ProfileStore db = ProfileStore::Open(":memory:");
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  EXPECT_TRUE(db.Runs().empty());
  const QueryResult tables =
      db.Query("SELECT name FROM sqlite_schema WHERE type = 'table' ORDER BY name");
  std::vector<std::string> names;
  for (const auto& row : tables.rows) names.push_back(row[0]);
  EXPECT_EQ(names, (std::vector<std::string>{
                       "calibration_inputs", "calibrations", "curving_starts", "distributions",
                       "load_cases", "low_rail_distributions", "low_rail_steps", "meta", "profiles",
                       "run_failures", "runs", "step_warnings", "steps", "wheel_steps"}));
  EXPECT_EQ(db.Query("PRAGMA application_id").rows[0][0],
            std::to_string(ProfileStore::kApplicationId));
}

TEST(ProfileStore, DistributionsHaveANullableArcLengthColumn) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const QueryResult cols = db.Query(
      "SELECT name, type, \"notnull\" FROM pragma_table_info("
      "'distributions') WHERE name = 's'");
  ASSERT_EQ(cols.rows.size(), 1u);
  EXPECT_EQ(cols.rows[0], (std::vector<std::string>{"s", "BLOB", "0"}));
}

TEST(ProfileStore, DistributionArcLengthRoundTripsExactly) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("r"));
  StepRecord step = TestStep(0);
  // Values that use all mantissa bits, a negative zero and a subnormal.
  step.distributions[0].s_m = {-0.0, 1.0 / 3.0, 4.9e-324};
  db.AppendStep(run, step);
  const StepRecord back = db.LoadStep(run, 0);
  ASSERT_EQ(back.distributions.size(), 2u);
  const Distribution& wear = back.distributions[1];  // ordered by kind: damage, wear_depth_mm
  ASSERT_EQ(wear.kind, "wear_depth_mm");
  ASSERT_EQ(wear.s_m.size(), 3u);
  EXPECT_EQ(std::memcmp(wear.s_m.data(), step.distributions[0].s_m.data(), 3 * sizeof(double)), 0);
  EXPECT_TRUE(std::signbit(wear.s_m[0]));
  EXPECT_TRUE(back.distributions[0].s_m.empty());  // "damage" was given no s
  EXPECT_EQ(db.Query("SELECT kind, s IS NULL, length(s) FROM distributions ORDER BY kind").rows,
            (std::vector<std::vector<std::string>>{{"damage", "1", "NULL"},
                                                   {"wear_depth_mm", "0", "24"}}));
  // s of another length than value is refused, naming the distribution.
  StepRecord bad = TestStep(1);
  bad.distributions[1].s_m = {0.0, 1.0};
  ExpectInputError([&] { db.AppendStep(run, bad); },
                   {"distribution 'damage'", "2 arc lengths s, 3 values", "one s per value"});
  EXPECT_EQ(db.LastStep(run), 0);
}

TEST(ProfileStore, MigratesVersion1KeepingItsData) {
  TempDir tmp;
  const std::string path = tmp.File("v1.rwdb");
  RawExec(path, Version1Database());
  {
    ProfileStore db = ProfileStore::Open(path);
    EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
    const auto run = db.FindRun("old");
    ASSERT_TRUE(run.has_value());
    EXPECT_EQ(run->program_version, "0.0.9");
    EXPECT_EQ(run->state, RunState::kComplete);
    const StepRecord old = db.LoadStep(run->id, 0);
    EXPECT_EQ(old.created_utc, "2024-05-01T12:00:01.000Z");
    EXPECT_EQ(old.profile.size(), 5);
    EXPECT_EQ(old.profile.points()[4], Eigen::Vector2d(0.02, 0.0016));
    EXPECT_EQ(old.load_cases_json, (std::vector<std::string>{R"({"case":0})"}));
    ASSERT_EQ(old.distributions.size(), 1u);
    EXPECT_EQ(old.distributions[0].y_m, (std::vector<double>{-0.01, 0.0, 0.01}));
    EXPECT_EQ(old.distributions[0].value, (std::vector<double>{0.0, 0.25, 0.5}));
    EXPECT_TRUE(old.distributions[0].s_m.empty());  // NULL after the migration
    EXPECT_EQ(db.Query("SELECT count(*) FROM distributions WHERE s IS NULL").rows[0][0], "1");

    // New rows get s.
    StepRecord next = TestStep(1);
    next.distributions[0].s_m = {0.0, 0.1 / 3.0, 0.2};
    db.AppendStep(run->id, next);
  }
  ProfileStore db = ProfileStore::Open(path);  // reopening a current file migrates nothing
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  const StepRecord back = db.LoadStep(db.FindRun("old")->id, 1);
  ASSERT_EQ(back.distributions.size(), 2u);
  EXPECT_EQ(back.distributions[1].kind, "wear_depth_mm");
  const std::vector<double> want = {0.0, 0.1 / 3.0, 0.2};
  EXPECT_EQ(std::memcmp(back.distributions[1].s_m.data(), want.data(), 3 * sizeof(double)), 0);
}

TEST(ProfileStore, MigratesVersion2KeepingItsDataAndAddsCalibrations) {
  TempDir tmp;
  const std::string path = tmp.File("v2.rwdb");
  RawExec(path, Version2Database());
  {
    ProfileStore db = ProfileStore::Open(path);
    EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
    const auto run = db.FindRun("old");
    ASSERT_TRUE(run.has_value());
    EXPECT_EQ(run->scene_text, "scene");
    ASSERT_EQ(db.LastStep(run->id), 1);
    // Version 4's low-rail tables exist and are empty: an old run is a single-rail run.
    for (const StepRecord& s : db.Steps(run->id)) EXPECT_FALSE(s.low_rail.has_value());
    EXPECT_FALSE(db.LoadStep(run->id, 1).low_rail.has_value());
    EXPECT_EQ(db.Query("SELECT count(*) FROM low_rail_steps").rows[0][0], "0");
    // Version 5's curving starts: none for an old run (its steps start from the unworn rails).
    EXPECT_EQ(db.Query("SELECT count(*) FROM curving_starts").rows[0][0], "0");
    EXPECT_TRUE(db.LoadStep(run->id, 1).curving_starts.empty());
    const StepRecord one = db.LoadStep(run->id, 1);
    EXPECT_EQ(one.passes, 100.0);
    ASSERT_EQ(one.distributions.size(), 1u);
    EXPECT_EQ(one.distributions[0].s_m, (std::vector<double>{0.5}));
    EXPECT_EQ(db.LoadStep(run->id, 0).load_cases_json, (std::vector<std::string>{R"({"case":0})"}));
    EXPECT_TRUE(db.Calibrations().empty());
    db.AddCalibration(TestCalibration());
  }
  ProfileStore db = ProfileStore::Open(path);
  ASSERT_EQ(db.Calibrations().size(), 1u);
  EXPECT_EQ(db.Runs().size(), 1u);
}

RailStepRecord TestLowRail(int step) {
  RailStepRecord low;
  low.worn_area_mm2 = 0.25 * step;
  low.max_depth_mm = 0.005 * step;
  low.max_depth_y_mm = -12.5;
  low.w1_mm = 0.05;
  low.w2_mm = 1.0 / 3.0;
  low.w3_mm = 0.125;
  low.smoothing_area_error = -2e-4;
  low.profile = TestProfile(30, -1e-5 * step);
  low.distributions = {{"wear_depth_mm", {-0.02, 0.0}, {1e-3, 0.0}, {0.0, 0.02}}};
  return low;
}

TEST(ProfileStore, TheLowRailRoundTripsNextToTheHighRail) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("two rails"));
  for (int k = 0; k < 2; ++k) {
    StepRecord step = TestStep(k);
    step.low_rail = TestLowRail(k);
    db.AppendStep(run, step);
  }
  const std::vector<StepRecord> steps = db.Steps(run);
  ASSERT_EQ(steps.size(), 2u);
  ASSERT_TRUE(steps[1].low_rail.has_value());
  EXPECT_EQ(steps[1].low_rail->w2_mm, 1.0 / 3.0);
  EXPECT_EQ(steps[1].low_rail->max_depth_mm, 0.005);
  EXPECT_EQ(steps[1].low_rail->smoothing_area_error, -2e-4);
  EXPECT_EQ(steps[1].low_rail->profile.size(), 0);  // summaries only
  EXPECT_EQ(steps[1].w2_mm, 0.2);                   // the high rail's unchanged
  const StepRecord back = db.LoadStep(run, 1);
  ASSERT_TRUE(back.low_rail.has_value());
  const RailStepRecord want = TestLowRail(1);
  ASSERT_EQ(back.low_rail->profile.size(), want.profile.size());
  EXPECT_EQ(std::memcmp(back.low_rail->profile.points().data(), want.profile.points().data(),
                        sizeof(Eigen::Vector2d) * want.profile.size()),
            0);
  EXPECT_EQ(db.LoadLowRailProfile(run, 1).points(), want.profile.points());
  ASSERT_EQ(back.low_rail->distributions.size(), 1u);
  EXPECT_EQ(back.low_rail->distributions[0].value, want.distributions[0].value);
  EXPECT_EQ(back.low_rail->distributions[0].s_m, want.distributions[0].s_m);
  EXPECT_EQ(back.distributions.size(), 2u);  // the high rail's, as before
  EXPECT_EQ(back.profile.points(), TestProfile(40, 1e-5).points());

  // A single-rail step has no low rail; asking for its low-rail profile names the step.
  const int64_t single = db.CreateRun(TestRun("one rail"));
  db.AppendStep(single, TestStep(0));
  EXPECT_FALSE(db.LoadStep(single, 0).low_rail.has_value());
  ExpectInputError([&] { db.LoadLowRailProfile(single, 0); }, {"no low rail at step 0"});
  // A low-rail distribution given twice rolls back the whole step.
  StepRecord bad = TestStep(2);
  bad.low_rail = TestLowRail(2);
  bad.low_rail->distributions.push_back(bad.low_rail->distributions[0]);
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"low-rail distribution kind"});
  EXPECT_EQ(db.LastStep(run), 1);
}

// A vehicle entry's curving solution is the next step's start: stored bit for bit (a resumed
// run continues from exactly it), per traffic entry, with or without its Jacobian; a malformed
// one rolls the whole step back.
TEST(ProfileStore, CurvingStartsRoundTripExactly) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("vehicles"));
  db.AppendStep(run, TestStep(0));
  StepRecord step = TestStep(1);
  const std::vector<double> state = {1.0 / 3.0, -2e-3, 5.5e-3, 1e-300};
  std::vector<double> jacobian(16);
  for (size_t k = 0; k < jacobian.size(); ++k) jacobian[k] = std::ldexp(1.0 / 7.0, int(k) - 8);
  step.curving_starts = {{0, state, jacobian}, {2, {0.25, -0.125}, {}}};
  db.AppendStep(run, step);
  const StepRecord back = db.LoadStep(run, 1);
  ASSERT_EQ(back.curving_starts.size(), 2u);
  EXPECT_EQ(back.curving_starts[0].traffic_index, 0);
  EXPECT_EQ(back.curving_starts[0].state, state);
  EXPECT_EQ(back.curving_starts[0].jacobian, jacobian);
  EXPECT_EQ(back.curving_starts[1].traffic_index, 2);
  EXPECT_EQ(back.curving_starts[1].state, (std::vector<double>{0.25, -0.125}));
  EXPECT_TRUE(back.curving_starts[1].jacobian.empty());
  EXPECT_TRUE(db.LoadStep(run, 0).curving_starts.empty());
  EXPECT_TRUE(db.Steps(run)[1].curving_starts.empty());  // summaries only

  StepRecord bad = TestStep(2);
  bad.curving_starts = {{0, state, {1.0, 2.0}}};
  ExpectInputError([&] { db.AppendStep(run, bad); },
                   {"curving start of traffic entry 0", "4 state values and 2 Jacobian values"});
  bad.curving_starts = {{1, state, {}}, {1, state, {}}};
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"traffic entry 1 given twice"});
  bad.curving_starts = {{0, {std::nan("")}, {}}};
  EXPECT_ANY_THROW(db.AppendStep(run, bad));
  EXPECT_EQ(db.LastStep(run), 1);
}

// A wearing wheel (co-evolution, schema 7): its measures and profile per step and traffic entry,
// bit for bit; summaries by entry then step; a malformed one rolls the whole step back.
WheelStepRecord TestWheel(int traffic_index, const std::string& name, double area_mm2,
                          double depth_mm, double y_mm, double smoothing, const Profile& profile,
                          std::optional<double> sd_mm = std::nullopt) {
  WheelStepRecord w;
  w.traffic_index = traffic_index;
  w.name = name;
  w.worn_area_mm2 = area_mm2;
  w.max_depth_mm = depth_mm;
  w.max_depth_y_mm = y_mm;
  w.smoothing_area_error = smoothing;
  w.flange_thickness_mm = sd_mm;
  if (sd_mm) {
    w.flange_height_mm = 28.0;
    w.flange_slope_mm = 1.0 / 3.0;
  }
  w.profile = profile;
  return w;
}

TEST(ProfileStore, WheelStepsRoundTripExactly) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("wheels"));
  const Profile wheel({{-0.07, 0.0}, {-0.02, 1e-3}, {0.0, 1.0 / 3.0 * 1e-3}, {0.05, 2e-300}}, "w");
  StepRecord zero = TestStep(0);
  zero.wheels = {TestWheel(2, "freight", 0.0, 0.0, 0.0, 0.0, wheel, 32.5)};
  db.AppendStep(run, zero);
  StepRecord one = TestStep(1);
  const Profile worn({{-0.07, -1e-6}, {-0.02, 1e-3}, {0.0, 1.0 / 7.0 * 1e-3}, {0.05, 0.0}}, "w");
  one.wheels = {TestWheel(2, "freight", 0.125, 1.0 / 3.0, -0.5, 1e-9, worn, 32.25),
                TestWheel(0, "passenger", 0.5, 0.25, 1.5, 0.0, wheel)};
  db.AppendStep(run, one);
  const StepRecord back = db.LoadStep(run, 1);
  ASSERT_EQ(back.wheels.size(), 2u);
  EXPECT_EQ(back.wheels[0].traffic_index, 0);  // by traffic entry
  EXPECT_EQ(back.wheels[1].traffic_index, 2);
  EXPECT_EQ(back.wheels[1].name, "freight");
  EXPECT_EQ(back.wheels[1].max_depth_mm, 1.0 / 3.0);
  EXPECT_EQ(back.wheels[1].smoothing_area_error, 1e-9);
  EXPECT_EQ(back.wheels[1].profile.points(), worn.points());
  EXPECT_EQ(back.wheels[1].flange_thickness_mm, 32.25);
  EXPECT_EQ(back.wheels[1].flange_height_mm, 28.0);
  EXPECT_EQ(back.wheels[1].flange_slope_mm, 1.0 / 3.0);
  EXPECT_FALSE(back.wheels[0].flange_thickness_mm.has_value());  // NULL: no flange measured
  EXPECT_EQ(db.LoadWheelProfile(run, 0, 2).points(), wheel.points());
  const std::vector<WheelStepRecord> summaries = db.WheelSteps(run);
  ASSERT_EQ(summaries.size(), 3u);
  EXPECT_EQ(summaries[0].traffic_index, 0);
  EXPECT_EQ(summaries[1].step, 0);
  EXPECT_EQ(summaries[2].step, 1);
  EXPECT_EQ(summaries[2].worn_area_mm2, 0.125);
  EXPECT_EQ(summaries[1].flange_thickness_mm, 32.5);
  EXPECT_EQ(summaries[2].profile.size(), 0);  // summaries only
  EXPECT_TRUE(db.Steps(run)[1].wheels.empty());
  ExpectInputError([&] { db.LoadWheelProfile(run, 1, 1); },
                   {"wheel of traffic entry 1", "not stored"});

  StepRecord bad = TestStep(2);
  bad.wheels = {TestWheel(1, "a", 0.0, 0.0, 0.0, 0.0, wheel),
                TestWheel(1, "b", 0.0, 0.0, 0.0, 0.0, wheel)};
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"wheel of traffic entry 1 given twice"});
  bad.wheels = {TestWheel(1, "a", 0.0, 0.0, 0.0, 0.0, Profile())};
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"traffic entry 1 ('a') has 0 profile"});
  bad.wheels = {TestWheel(1, "a", std::nan(""), 0.0, 0.0, 0.0, wheel)};
  EXPECT_ANY_THROW(db.AppendStep(run, bad));
  EXPECT_EQ(db.LastStep(run), 1);
}

// A version-6 file (before wheel_steps): read-only commands read it as it is (no wheels), and a
// writing open migrates it to 7 keeping its data, its runs without wheels.
TEST(ProfileStore, MigratesVersion6AndReadsItUnmigrated) {
  TempDir tmp;
  const std::string path = tmp.File("v6.rwdb");
  {
    ProfileStore db = ProfileStore::Open(path);
    const int64_t run = db.CreateRun(TestRun("old"), TestStep(0));
    db.AppendStep(run, TestStep(1));
  }
  RawExec(path,
          "DROP TABLE wheel_steps; DROP TABLE step_warnings; DROP TABLE run_failures; "
          "PRAGMA user_version = 6;");
  {
    const ProfileStore ro = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(ro.SchemaVersion(), 6);
    const auto run = ro.FindRun("old");
    ASSERT_TRUE(run.has_value());
    EXPECT_TRUE(ro.WheelSteps(run->id).empty());
    EXPECT_TRUE(ro.LoadStep(run->id, 1).wheels.empty());
    EXPECT_EQ(ro.LoadStep(run->id, 1).passes, TestStep(1).passes);
    ExpectInputError([&] { ro.LoadWheelProfile(run->id, 1, 0); }, {"not stored"});
  }
  ProfileStore db = ProfileStore::Open(path);
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  const auto run = db.FindRun("old");
  ASSERT_TRUE(run.has_value());
  EXPECT_EQ(db.LastStep(run->id), 1);
  EXPECT_EQ(db.Query("SELECT count(*) FROM wheel_steps").rows[0][0], "0");
  StepRecord two = TestStep(2);
  two.wheels = {TestWheel(0, "w", 0.0, 0.0, 0.0, 0.0, TestStep(2).profile)};
  db.AppendStep(run->id, two);
  EXPECT_EQ(db.WheelSteps(run->id).size(), 1u);
}

// Schema 9 (issue 16, a vehicle entry's wheels wear): wheel_steps.wheel tells the wheels of one
// entry apart (0 an entry's one wheel, 1 + 2 x wheelset + side a vehicle's); each round-trips bit
// for bit and the same wheel twice in a step is refused. A schema-8 file (wheel_steps without the
// column) reads as it is, every wheel as wheel 0, and a writing open rebuilds the table keeping
// every row.
TEST(ProfileStore, VehicleWheelsRoundTripAndVersion9ReadsUnmigrated) {
  TempDir tmp;
  const std::string path = tmp.File("v9.rwdb");
  const Profile wheel({{-0.07, 0.0}, {-0.02, 1e-3}, {0.0, 1.0 / 3.0 * 1e-3}, {0.05, 2e-300}}, "w");
  const Profile worn({{-0.07, -1e-6}, {-0.02, 1e-3}, {0.0, 1.0 / 7.0 * 1e-3}, {0.05, 0.0}}, "w");
  {
    ProfileStore db = ProfileStore::Open(path);
    StepRecord zero = TestStep(0);
    zero.wheels = {TestWheel(1, "freight", 0.0, 0.0, 0.0, 0.0, wheel, 32.5)};
    const int64_t run = db.CreateRun(TestRun("old"), zero);
    StepRecord one = TestStep(1);
    one.wheels = {TestWheel(1, "freight", 0.125, 0.25, -0.5, 0.0, worn, 32.25)};
    db.AppendStep(run, one);
  }
  // Back to schema 9's wheel_steps (MigrateTo7's table, rows kept).
  RawExec(path, R"sql(
CREATE TABLE wheel_steps_v8(
  run_id INTEGER NOT NULL, step INTEGER NOT NULL,
  traffic_index INTEGER NOT NULL CHECK (traffic_index >= 0), name TEXT NOT NULL,
  worn_area_mm2 REAL NOT NULL, max_depth_mm REAL NOT NULL, max_depth_y_mm REAL NOT NULL,
  smoothing_area_error REAL NOT NULL, sh_mm REAL, sd_mm REAL, qr_mm REAL,
  n_points INTEGER NOT NULL, yz BLOB NOT NULL CHECK (length(yz) = 16 * n_points),
  PRIMARY KEY (run_id, step, traffic_index),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
INSERT INTO wheel_steps_v8 SELECT run_id, step, traffic_index, name, worn_area_mm2, max_depth_mm,
  max_depth_y_mm, smoothing_area_error, sh_mm, sd_mm, qr_mm, n_points, yz FROM wheel_steps;
DROP TABLE wheel_steps;
ALTER TABLE wheel_steps_v8 RENAME TO wheel_steps;
PRAGMA user_version = 9;)sql");
  {
    const ProfileStore ro = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(ro.SchemaVersion(), 9);
    const int64_t run = ro.FindRun("old")->id;
    const std::vector<WheelStepRecord> summaries = ro.WheelSteps(run);
    ASSERT_EQ(summaries.size(), 2u);
    EXPECT_EQ(summaries[1].wheel, 0);
    EXPECT_EQ(summaries[1].worn_area_mm2, 0.125);
    EXPECT_EQ(ro.LoadStep(run, 1).wheels.at(0).profile.points(), worn.points());
    EXPECT_EQ(ro.LoadWheelProfile(run, 1, 1).points(), worn.points());
  }
  ProfileStore db = ProfileStore::Open(path);
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  const int64_t run = db.FindRun("old")->id;
  EXPECT_EQ(db.LoadWheelProfile(run, 1, 1, 0).points(), worn.points());  // kept, as wheel 0
  StepRecord two = TestStep(2);
  WheelStepRecord high = TestWheel(0, "coach / wheelset 1 high", 0.5, 0.25, 1.5, 0.0, worn);
  high.wheel = 3;
  WheelStepRecord low = TestWheel(0, "coach / wheelset 1 low", 0.25, 0.125, 1.5, 0.0, wheel);
  low.wheel = 4;
  two.wheels = {TestWheel(1, "freight", 0.25, 0.5, -0.5, 0.0, worn), low, high};
  db.AppendStep(run, two);
  const StepRecord back = db.LoadStep(run, 2);
  ASSERT_EQ(back.wheels.size(), 3u);  // by entry, then wheel
  EXPECT_EQ(back.wheels[0].wheel, 3);
  EXPECT_EQ(back.wheels[0].name, "coach / wheelset 1 high");
  EXPECT_EQ(back.wheels[0].profile.points(), worn.points());
  EXPECT_EQ(back.wheels[1].wheel, 4);
  EXPECT_EQ(back.wheels[1].profile.points(), wheel.points());
  EXPECT_EQ(back.wheels[2].traffic_index, 1);
  EXPECT_EQ(db.LoadWheelProfile(run, 2, 0, 4).points(), wheel.points());
  ExpectInputError([&] { db.LoadWheelProfile(run, 2, 0, 5); },
                   {"wheel 5 of traffic entry 0", "not stored"});
  StepRecord bad = TestStep(3);
  bad.wheels = {high, high};
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"wheel 3 of traffic entry 0 given twice"});
  EXPECT_EQ(db.LastStep(run), 2);
}

// Schema 8 (issue 17): a step's warnings round-trip in order through Steps() and LoadStep(); a
// kind outside the schema's is refused with the step rolled back; a schema-7 file is read as it
// is (no warnings) and migrated by the next read-write open.
TEST(ProfileStore, StepWarningsRoundTripAndVersion7ReadsUnmigrated) {
  TempDir tmp;
  const std::string path = tmp.File("v7.rwdb");
  {
    ProfileStore db = ProfileStore::Open(path);
    const int64_t run = db.CreateRun(TestRun("old"), TestStep(0));
    db.AppendStep(run, TestStep(1));
  }
  RawExec(path, "DROP TABLE step_warnings; DROP TABLE run_failures; PRAGMA user_version = 7;");
  {
    const ProfileStore ro = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(ro.SchemaVersion(), 7);
    const auto run = ro.FindRun("old");
    ASSERT_TRUE(run.has_value());
    EXPECT_TRUE(ro.LoadStep(run->id, 1).warnings.empty());
    EXPECT_TRUE(ro.Steps(run->id)[1].warnings.empty());
  }
  ProfileStore db = ProfileStore::Open(path);
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  EXPECT_EQ(ProfileStore::kSchemaVersion, 10);
  const int64_t run = db.FindRun("old")->id;
  StepRecord two = TestStep(2);
  two.warnings = {{"hardness", "p_max beyond the hardness in 2 of 3 load cases"},
                  {"flange_climb", "flange climb possible in 1 of 3 load cases"}};
  db.AppendStep(run, two);
  EXPECT_EQ(db.LoadStep(run, 2).warnings, two.warnings);
  const std::vector<StepRecord> steps = db.Steps(run);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_TRUE(steps[1].warnings.empty());
  EXPECT_EQ(steps[2].warnings, two.warnings);
  StepRecord bad = TestStep(3);
  bad.warnings = {{"noise", "?"}};
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"warning kind 'noise'", "'hardness'"});
  EXPECT_EQ(db.LastStep(run), 2);  // rolled back
}

TEST(ProfileStore, CalibrationsRoundTripWithTheirInputs) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const CalibrationRecord in = TestCalibration();
  const int64_t a = db.AddCalibration(in);
  const int64_t b = db.AddCalibration(in);  // the same name again: a new calibration
  EXPECT_NE(a, b);
  const std::vector<CalibrationRecord> all = db.Calibrations();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].id, a);
  EXPECT_TRUE(all[0].inputs.empty());  // listed without inputs
  const CalibrationRecord back = db.LoadCalibration(a);
  EXPECT_EQ(back.name, in.name);
  EXPECT_FALSE(back.created_utc.empty());
  EXPECT_EQ(back.config_text, in.config_text);
  EXPECT_EQ(back.status, "converged");
  EXPECT_FALSE(back.well_conditioned);
  EXPECT_EQ(back.constants_json, in.constants_json);
  EXPECT_EQ(back.correlation_json, in.correlation_json);
  EXPECT_EQ(back.residuals_json, in.residuals_json);
  EXPECT_EQ(back.ceres_report, in.ceres_report);
  EXPECT_EQ(back.constants_toml, in.constants_toml);
  ASSERT_EQ(back.inputs.size(), 2u);
  EXPECT_EQ(back.inputs[1].kind, "displacement_curves");
  EXPECT_EQ(back.inputs[1].path, "r15.csv");
  EXPECT_EQ(back.inputs[1].text, in.inputs[1].text);
  ExpectInputError([&] { db.LoadCalibration(99); }, {"no calibration with id 99"});
  CalibrationRecord unnamed = in;
  unnamed.name.clear();
  ExpectInputError([&] { db.AddCalibration(unnamed); }, {"calibration name is empty"});
  // A bad input rolls the whole calibration back.
  CalibrationRecord bad = in;
  bad.inputs.push_back({"scene", "", "x"});
  ExpectInputError([&] { db.AddCalibration(bad); }, {"an input without kind or path"});
  EXPECT_EQ(db.Calibrations().size(), 2u);
  EXPECT_EQ(db.Query("SELECT count(*) FROM calibration_inputs").rows[0][0], "4");
}

TEST(ProfileStore, FailedMigrationLeavesVersion1) {
  TempDir tmp;
  const std::string path = tmp.File("v1_clash.rwdb");
  // A version-1 file that (against the rules) already has a column named s: ALTER TABLE fails,
  // and the whole migration must roll back.
  RawExec(path, Version1Database() + "ALTER TABLE distributions ADD COLUMN s TEXT;");
  EXPECT_THROW(ProfileStore::Open(path), std::runtime_error);
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open_v2(path.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(raw, "PRAGMA user_version", -1, &stmt, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(stmt), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(stmt, 0), 1);
  sqlite3_finalize(stmt);
  ASSERT_EQ(sqlite3_prepare_v2(raw, "SELECT count(*) FROM steps", -1, &stmt, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(stmt), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(stmt, 0), 1);
  sqlite3_finalize(stmt);
  sqlite3_close(raw);
}

TEST(ProfileStore, RunsAreUniqueAndFound) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t a = db.CreateRun(TestRun("baseline"));
  const int64_t b = db.CreateRun(TestRun("dry"));
  EXPECT_NE(a, b);
  ExpectInputError([&] { db.CreateRun(TestRun("baseline")); },
                   {":memory:", "'baseline' already exists", "expected a new run name"});
  ExpectInputError([&] { db.CreateRun(TestRun("")); }, {"run name is empty"});
  const auto found = db.FindRun("dry");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->id, b);
  EXPECT_EQ(found->scene_text, TestRun("dry").scene_text);
  EXPECT_EQ(found->wear_law_json, TestRun("dry").wear_law_json);
  EXPECT_EQ(found->program_version, "0.1.0");
  EXPECT_EQ(found->state, RunState::kRunning);
  EXPECT_EQ(found->created_utc.size(), std::string("2024-01-01T00:00:00.000Z").size());
  EXPECT_FALSE(db.FindRun("wet").has_value());
  ASSERT_EQ(db.Runs().size(), 2u);
  EXPECT_EQ(db.Runs()[0].name, "baseline");
  db.SetRunState(a, RunState::kComplete);
  EXPECT_EQ(db.FindRun("baseline")->state, RunState::kComplete);
  ExpectInputError([&] { db.SetRunState(999, RunState::kAborted); }, {"no run with id 999"});
}

TEST(ProfileStore, StepsAppendInOrder) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("r"));
  EXPECT_FALSE(db.LastStep(run).has_value());
  ExpectInputError([&] { db.AppendStep(run, TestStep(1)); }, {"run 1 step 1", "expected step 0"});
  db.AppendStep(run, TestStep(0));
  db.AppendStep(run, TestStep(1));
  ExpectInputError([&] { db.AppendStep(run, TestStep(1)); }, {"expected step 2"});
  ExpectInputError([&] { db.AppendStep(run, TestStep(3)); }, {"expected step 2"});
  ExpectInputError([&] { db.AppendStep(run + 7, TestStep(0)); }, {"no run with id"});
  db.AppendStep(run, TestStep(2));
  EXPECT_EQ(db.LastStep(run), 2);

  const auto steps = db.Steps(run);
  ASSERT_EQ(steps.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const StepRecord want = TestStep(i);
    EXPECT_EQ(steps[i].step, i);
    EXPECT_EQ(steps[i].passes, want.passes);
    EXPECT_EQ(steps[i].mgt, want.mgt);
    EXPECT_EQ(steps[i].worn_area_mm2, want.worn_area_mm2);
    EXPECT_EQ(steps[i].max_depth_mm, want.max_depth_mm);
    EXPECT_EQ(steps[i].max_depth_y_mm, want.max_depth_y_mm);
    EXPECT_EQ(steps[i].w3_mm, want.w3_mm);
    EXPECT_EQ(steps[i].smoothing_area_error, want.smoothing_area_error);
    EXPECT_FALSE(steps[i].created_utc.empty());
    EXPECT_EQ(steps[i].profile.size(), 0);  // summaries only
    EXPECT_TRUE(steps[i].load_cases_json.empty());
  }

  const StepRecord full = db.LoadStep(run, 1);
  EXPECT_EQ(full.load_cases_json, TestStep(1).load_cases_json);
  ASSERT_EQ(full.distributions.size(), 2u);
  EXPECT_EQ(full.distributions[0].kind, "damage");  // ordered by kind
  EXPECT_EQ(full.distributions[0].value, TestStep(1).distributions[1].value);
  EXPECT_EQ(full.distributions[1].y_m, TestStep(1).distributions[0].y_m);
  ExpectInputError([&] { db.LoadStep(run, 9); }, {"has no step 9"});
}

TEST(ProfileStore, ProfileBlobRoundTripIsExact) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("r"));
  StepRecord s = TestStep(0);
  s.profile = TestProfile(257, 1.0 / 3.0);
  db.AppendStep(run, s);
  const Profile back = db.LoadProfile(run, 0);
  ASSERT_EQ(back.size(), s.profile.size());
  // Bit-for-bit: memcmp also tells -0.0 from 0.0.
  EXPECT_EQ(std::memcmp(back.points().data(), s.profile.points().data(),
                        sizeof(Eigen::Vector2d) * back.points().size()),
            0);
  EXPECT_TRUE(std::signbit(back.points()[0].y()));
  // Layout documented in SCHEMA.md: 16 bytes a point.
  EXPECT_EQ(db.Query("SELECT n_points, length(yz) FROM profiles").rows[0],
            (std::vector<std::string>{"257", "4112"}));
  ExpectInputError([&] { db.LoadProfile(run, 1); }, {"has no step 1"});
}

TEST(ProfileStore, FailedStepLeavesNothing) {
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("r"));
  db.AppendStep(run, TestStep(0));
  // The duplicate distribution kind fails after the step row, its profile and its load cases
  // have been written: the transaction must take all of them back.
  StepRecord bad = TestStep(1);
  bad.distributions.push_back(bad.distributions[0]);
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"'wear_depth_mm' given twice"});
  EXPECT_EQ(db.LastStep(run), 0);
  for (const char* table : {"steps", "profiles", "load_cases", "distributions"}) {
    EXPECT_EQ(db.Query(std::string("SELECT count(*) FROM ") + table + " WHERE step = 1").rows[0][0],
              "0")
        << table;
  }
  // Malformed input is refused before anything is written.
  bad = TestStep(1);
  bad.distributions[0].value.pop_back();
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"3 positions, 2 values"});
  bad = TestStep(1);
  bad.profile = Profile();
  ExpectInputError([&] { db.AppendStep(run, bad); }, {"the profile is empty"});
  // And the store is still usable.
  db.AppendStep(run, TestStep(1));
  EXPECT_EQ(db.LastStep(run), 1);
}

// Issue 17: a run and its step 0 are one transaction. A step 0 that fails leaves no run, so the
// name is free for the next attempt (before, a kill between the two commits left a run without
// steps that could neither be resumed nor created again).
TEST(ProfileStore, CreateRunWithItsFirstStepIsAllOrNothing) {
  ProfileStore db = ProfileStore::Open(":memory:");
  StepRecord bad = TestStep(0);
  bad.profile = Profile();
  ExpectInputError([&] { db.CreateRun(TestRun("r"), bad); }, {"the profile is empty"});
  EXPECT_FALSE(db.FindRun("r").has_value());
  ExpectInputError([&] { db.CreateRun(TestRun("r"), TestStep(1)); }, {"expected step 0"});
  EXPECT_FALSE(db.FindRun("r").has_value());
  const int64_t run = db.CreateRun(TestRun("r"), TestStep(0));
  EXPECT_EQ(db.LastStep(run), 0);
  EXPECT_EQ(db.LoadProfile(run, 0).points(), TestStep(0).profile.points());
  ExpectInputError([&] { db.CreateRun(TestRun("r"), TestStep(0)); }, {"already exists"});
  EXPECT_EQ(db.Runs().size(), 1u);
}

// Schema 5: the state 'interrupted' (a run stopped by SIGINT/SIGTERM) round-trips; a version-1
// file migrated to 5 keeps its runs, and its foreign keys still cascade after runs was rebuilt.
TEST(ProfileStore, InterruptedStateRoundTripsAfterMigratingTheRunsTable) {
  EXPECT_EQ(ToString(RunState::kInterrupted), "interrupted");
  EXPECT_EQ(RunStateFromString("interrupted"), RunState::kInterrupted);
  ExpectInputError([] { RunStateFromString("paused"); }, {"'paused'", "interrupted"});
  TempDir tmp;
  const std::string path = tmp.File("v1.rwdb");
  RawExec(path, Version1Database());
  ProfileStore db = ProfileStore::Open(path);
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  const auto old = db.FindRun("old");
  ASSERT_TRUE(old.has_value());
  EXPECT_EQ(old->state, RunState::kComplete);
  EXPECT_EQ(old->created_utc, "2024-05-01T12:00:00.000Z");
  db.SetRunState(old->id, RunState::kInterrupted);
  EXPECT_EQ(db.FindRun("old")->state, RunState::kInterrupted);
  EXPECT_EQ(db.Query("PRAGMA foreign_key_check").rows.size(), 0u);
  // The CHECK still refuses other states (written by hand, as another program would).
  RawExec(path, "PRAGMA foreign_keys = ON; DELETE FROM runs WHERE name = 'old'");
  EXPECT_EQ(db.Query("SELECT count(*) FROM steps").rows[0][0], "0");  // cascaded
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &raw), SQLITE_OK);
  EXPECT_NE(sqlite3_exec(raw,
                         "INSERT INTO runs(name, created_utc, program_version, scene_text, "
                         "wear_law_json, state) VALUES ('x', 't', 'v', 's', '{}', 'paused')",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(raw);
}

// A database file deleted, or replaced by another file, under an open store: the next write
// rolls back and throws a failure (exit 1 in the CLI) saying which, instead of writing on into a
// file nobody can open any more.
TEST(ProfileStore, WritesStopWhenTheFileIsDeletedOrReplaced) {
  TempDir tmp;
  const std::string path = tmp.File("study.rwdb");
  {
    ProfileStore db = ProfileStore::Open(path);
    const int64_t run = db.CreateRun(TestRun("r"), TestStep(0));
    db.AppendStep(run, TestStep(1));
    fs::remove(path);
    try {
      db.AppendStep(run, TestStep(2));
      ADD_FAILURE() << "no error after the file was deleted";
    } catch (const InputError& e) {
      ADD_FAILURE() << "a deleted file is a failure, not bad input: " << e.what();
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("database '" + path + "': the file was deleted"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(db.LastStep(run), 1);  // rolled back
    EXPECT_THROW(db.SetRunState(run, RunState::kComplete), std::runtime_error);
    EXPECT_THROW(db.CreateRun(TestRun("s"), TestStep(0)), std::runtime_error);
  }
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(path + suffix);
  ProfileStore db = ProfileStore::Open(path);
  const int64_t run = db.CreateRun(TestRun("r"), TestStep(0));
  const std::string other = tmp.File("other.bin");
  WriteBytes(other, "not the study\n");
  fs::rename(other, path);  // another file renamed over the study
  try {
    db.AppendStep(run, TestStep(1));
    ADD_FAILURE() << "no error after the file was replaced";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("replaced by another file"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ReadBytes(path), "not the study\n");  // the new file is never written
}

TEST(ProfileStore, NonFiniteValuesAreNeverStored) {
  // Issue 6: no NaN or infinity reaches the database, whether a scalar column, a profile point
  // or an element of a distribution; the step's transaction rolls back, the store stays usable.
  ProfileStore db = ProfileStore::Open(":memory:");
  const int64_t run = db.CreateRun(TestRun("r"));
  db.AppendStep(run, TestStep(0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::function<void(StepRecord*)>> corrupt = {
      [&](StepRecord* r) { r->max_depth_mm = nan; },
      [&](StepRecord* r) { r->w3_mm = inf; },
      [&](StepRecord* r) { r->distributions[0].value[1] = nan; },
  };
  for (const auto& c : corrupt) {
    StepRecord bad = TestStep(1);
    c(&bad);
    try {
      db.AppendStep(run, bad);
      ADD_FAILURE() << "a non-finite value was stored";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("refusing to store a non-finite value"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(db.LastStep(run), 0);
    EXPECT_EQ(db.Query("SELECT count(*) FROM steps WHERE step = 1").rows[0][0], "0");
  }
  db.AppendStep(run, TestStep(1));
  EXPECT_EQ(db.LastStep(run), 1);
}

TEST(ProfileStore, ReopensFileInWalMode) {
  TempDir tmp;
  const std::string path = tmp.File("study.rwdb");
  int64_t run = 0;
  {
    ProfileStore db = ProfileStore::Open(path);
    run = db.CreateRun(TestRun("r"));
    db.AppendStep(run, TestStep(0));
    db.AppendStep(run, TestStep(1));
  }
  // File header bytes 18 and 19 (write and read format versions) are 2 in WAL mode.
  const std::string header = ReadBytes(path).substr(0, 20);
  EXPECT_EQ(header.substr(0, 16), std::string("SQLite format 3\0", 16));
  EXPECT_EQ(header[18], 2);
  EXPECT_EQ(header[19], 2);
  ProfileStore db = ProfileStore::Open(path);
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  EXPECT_EQ(db.FindRun("r")->id, run);
  EXPECT_EQ(db.LastStep(run), 1);
  const Profile p = db.LoadProfile(run, 1);
  EXPECT_EQ(p.points(), TestStep(1).profile.points());
  db.AppendStep(run, TestStep(2));
  EXPECT_EQ(db.Steps(run).size(), 3u);
}

TEST(ProfileStore, EmptyFilesBecomeNewDatabases) {
  TempDir tmp;
  const std::string empty_file = tmp.File("empty.rwdb");
  WriteBytes(empty_file, "");
  const std::string empty_db = tmp.File("empty.db");
  RawExec(empty_db, "PRAGMA page_size = 4096; VACUUM;");
  for (const std::string& path : {empty_file, empty_db, tmp.File("new.rwdb")}) {
    SCOPED_TRACE(path);
    {
      ProfileStore db = ProfileStore::Open(path);
      EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
      db.CreateRun(TestRun("r"));
    }
    EXPECT_EQ(ProfileStore::Open(path).Runs().size(), 1u);
  }
  // Two in-memory stores are independent.
  ProfileStore a = ProfileStore::Open(":memory:");
  ProfileStore b = ProfileStore::Open(":memory:");
  a.CreateRun(TestRun("r"));
  EXPECT_TRUE(b.Runs().empty());
}

// Several connections opening one new file at once (a `wear` run and a poller or a `history`
// query started together): each inspects an empty file, then takes the write lock in turn;
// only the first may create the schema, the others must find it there under the lock. Before
// the version was read again under the lock, the later ones re-ran the migrations and failed
// ("table ... already exists"). Threads stand in for processes: each has its own connection.
TEST(ProfileStore, ConcurrentOpensOfANewFileAllSucceed) {
  TempDir tmp;
  for (int round = 0; round < 20; ++round) {
    const std::string path = tmp.File("new" + std::to_string(round) + ".rwdb");
    std::vector<std::thread> threads;
    std::atomic<int> failures{0};
    for (int k = 0; k < 4; ++k) {
      threads.emplace_back([&] {
        try {
          ProfileStore db = ProfileStore::Open(path);
          if (db.SchemaVersion() != ProfileStore::kSchemaVersion) ++failures;
        } catch (const std::exception& e) {
          ADD_FAILURE() << e.what();
          ++failures;
        }
      });
    }
    for (auto& t : threads) t.join();
    ASSERT_EQ(failures.load(), 0) << "round " << round;
  }
}

TEST(ProfileStore, RefusesNonSqliteFileUntouched) {
  TempDir tmp;
  const std::string path = tmp.File("profile.csv");
  std::string bytes = "y_mm,z_mm\n";
  for (int i = 0; i < 500; ++i) bytes += std::to_string(i) + ",0.5\n";
  WriteBytes(path, bytes);
  ExpectInputError([&] { ProfileStore::Open(path); },
                   {path, "not an SQLite database", "expected a railwear profile-history"});
  EXPECT_EQ(ReadBytes(path), bytes);
  EXPECT_FALSE(fs::exists(path + "-wal"));
  EXPECT_FALSE(fs::exists(path + "-journal"));
}

TEST(ProfileStore, RefusesForeignSqliteDatabaseUntouched) {
  TempDir tmp;
  const std::string path = tmp.File("other.db");
  RawExec(path,
          "CREATE TABLE accounts(id INTEGER PRIMARY KEY, owner TEXT);"
          "INSERT INTO accounts(owner) VALUES ('x');");
  const std::string before = ReadBytes(path);
  ExpectInputError([&] { ProfileStore::Open(path); },
                   {path, "another application", "application_id 0x00000000",
                    "expected a railwear profile-history database"});
  EXPECT_EQ(ReadBytes(path), before);

  // The railwear application_id without the meta table is refused too.
  RawExec(path, "PRAGMA application_id = " + std::to_string(ProfileStore::kApplicationId));
  const std::string before2 = ReadBytes(path);
  ExpectInputError([&] { ProfileStore::Open(path); }, {path, "no meta table"});
  EXPECT_EQ(ReadBytes(path), before2);
}

TEST(ProfileStore, RefusesNewerSchemaUntouched) {
  TempDir tmp;
  const std::string path = tmp.File("future.rwdb");
  {
    ProfileStore db = ProfileStore::Open(path);
    db.CreateRun(TestRun("r"));
  }
  RawExec(path, "PRAGMA user_version = " + std::to_string(ProfileStore::kSchemaVersion + 1));
  const std::string before = ReadBytes(path);
  ExpectInputError(
      [&] { ProfileStore::Open(path); },
      {path, "newer railwear", "schema version " + std::to_string(ProfileStore::kSchemaVersion + 1),
       "up to " + std::to_string(ProfileStore::kSchemaVersion)});
  EXPECT_EQ(ReadBytes(path), before);
}

TEST(ProfileStore, RefusesUnopenablePaths) {
  TempDir tmp;
  ExpectInputError([&] { ProfileStore::Open(tmp.File("no/such/folder/x.rwdb")); },
                   {"no/such/folder/x.rwdb", "cannot open"});
  ExpectInputError([&] { ProfileStore::Open(tmp.File("")); }, {"is a directory"});
}

TEST(ProfileStore, QueryIsReadOnly) {
  TempDir tmp;
  for (const std::string& path : {std::string(":memory:"), tmp.File("q.rwdb")}) {
    SCOPED_TRACE(path);
    ProfileStore db = ProfileStore::Open(path);
    const int64_t run = db.CreateRun(TestRun("r"));
    db.AppendStep(run, TestStep(0));
    db.AppendStep(run, TestStep(1));
    const QueryResult q = db.Query(
        "SELECT r.name, s.step, s.mgt, p.yz, NULL AS empty FROM steps s JOIN runs r "
        "ON r.id = s.run_id JOIN profiles p USING (run_id, step) ORDER BY s.step;");
    EXPECT_EQ(q.columns, (std::vector<std::string>{"name", "step", "mgt", "yz", "empty"}));
    ASSERT_EQ(q.rows.size(), 2u);
    EXPECT_EQ(q.rows[1], (std::vector<std::string>{"r", "1", "0.02", "<blob 640 bytes>", "NULL"}));

    for (const char* sql :
         {"DELETE FROM steps", "UPDATE runs SET name = 'x'", "DROP TABLE runs",
          "INSERT INTO meta VALUES ('a', 'b')", "PRAGMA user_version = 7", "CREATE TABLE t(x)",
          "BEGIN", "SAVEPOINT a", "ATTACH 'other.db' AS other", "DETACH main"}) {
      ExpectInputError([&] { db.Query(sql); }, {"query on", "read-only"});
    }
    ExpectInputError([&] { db.Query("SELECT 1; DELETE FROM steps"); }, {"more than one"});
    ExpectInputError([&] { db.Query("SELEC nonsense"); }, {"syntax error"});
    EXPECT_EQ(db.Steps(run).size(), 2u);
    EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
    // The store still writes after a query (query_only is switched back off).
    db.AppendStep(run, TestStep(2));
  }
}

// ---------------------------------------------------------------------------------------------
// Read-only opens (issue 17): OpenReadOnly never writes the database, its -wal or its -journal,
// and refuses foreign files before SQLite could recover or checkpoint them.

// The files of a database: name -> bytes, for those that exist.
std::map<std::string, std::string> DatabaseFiles(const std::string& path) {
  std::map<std::string, std::string> out;
  for (const char* suffix : {"", "-wal", "-journal"}) {
    if (fs::exists(path + suffix)) out[suffix] = ReadBytes(path + suffix);
  }
  return out;
}

// In a child process: runs `sql` on `path` and exits without closing the connection (as a
// killed program would), leaving a pending WAL or a hot rollback journal behind.
void RawExecAndDie(const std::string& path, const std::string& sql) {
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    sqlite3* db = nullptr;
    if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) _exit(1);
    _exit(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK ? 0 : 2);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
}

// A clean railwear database (no -wal): read without creating any file, bytes unchanged. This is
// what makes `history` work in a read-only folder or on read-only media: the immutable open
// needs no lock file, -shm or -wal (the test runs as any user; as root a chmod 0555 folder would
// not refuse writes, so the absence of created files is what it checks).
TEST(ProfileStoreReadOnly, ReadsACleanDatabaseWithoutCreatingOrChangingAnyFile) {
  TempDir tmp;
  const std::string path = tmp.File("study.rwdb");
  int64_t run = 0;
  {
    ProfileStore db = ProfileStore::Open(path);
    run = db.CreateRun(TestRun("r"));
    db.AppendStep(run, TestStep(0));
    db.AppendStep(run, TestStep(1));
  }
  ASSERT_FALSE(fs::exists(path + "-wal"));
  const std::string before = ReadBytes(path);
  {
    ProfileStore db = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(db.FindRun("r")->id, run);
    EXPECT_EQ(db.Steps(run).size(), 2u);
    EXPECT_EQ(db.LoadProfile(run, 1).points(), TestStep(1).profile.points());
    EXPECT_EQ(db.Query("SELECT count(*) FROM steps").rows[0][0], "2");
    ExpectInputError([&] { db.Query("DELETE FROM steps"); }, {"read-only"});
    EXPECT_THROW(db.CreateRun(TestRun("new")), std::exception);
    for (const char* suffix : {"-wal", "-shm", "-journal"}) {
      EXPECT_FALSE(fs::exists(path + suffix)) << suffix << " created while open";
    }
  }
  EXPECT_EQ(ReadBytes(path), before);
  for (const char* suffix : {"-wal", "-shm", "-journal"}) EXPECT_FALSE(fs::exists(path + suffix));
  // In a folder without write permission (a real test when not run as root).
  fs::permissions(tmp.File(""), fs::perms::owner_read | fs::perms::owner_exec |
                                    fs::perms::group_read | fs::perms::group_exec |
                                    fs::perms::others_read | fs::perms::others_exec);
  {
    ProfileStore db = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(db.Steps(run).size(), 2u);
  }
  fs::permissions(tmp.File(""), fs::perms::owner_all);
  EXPECT_EQ(ReadBytes(path), before);
}

// A railwear database with a pending WAL (a run writing now, or killed before its checkpoint):
// read through the WAL; the database and its -wal keep their bytes.
TEST(ProfileStoreReadOnly, ReadsThroughAPendingWalWithoutCheckpointing) {
  TempDir tmp;
  const std::string path = tmp.File("study.rwdb");
  ProfileStore writer = ProfileStore::Open(path);
  const int64_t run = writer.CreateRun(TestRun("r"));
  writer.AppendStep(run, TestStep(0));
  ASSERT_TRUE(fs::exists(path + "-wal"));
  const auto before = DatabaseFiles(path);
  {
    ProfileStore db = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(db.Steps(run).size(), 1u);
  }
  EXPECT_EQ(DatabaseFiles(path), before);
}

TEST(ProfileStoreReadOnly, RefusesAForeignFileWithAPendingWalByteIdentical) {
  TempDir tmp;
  const std::string path = tmp.File("other.db");
  // Main file with a schema, newer rows only in the WAL (never checkpointed).
  RawExecAndDie(path,
                "PRAGMA journal_mode = WAL; CREATE TABLE t(x); INSERT INTO t VALUES (1);"
                "PRAGMA wal_checkpoint(TRUNCATE); INSERT INTO t VALUES (2);");
  ASSERT_TRUE(fs::exists(path + "-wal"));
  ASSERT_GT(fs::file_size(path + "-wal"), 0u);
  const auto before = DatabaseFiles(path);
  ExpectInputError([&] { ProfileStore::OpenReadOnly(path); }, {path, "another application"});
  EXPECT_EQ(DatabaseFiles(path), before);
  ExpectInputError([&] { ProfileStore::Open(path); }, {path, "another application"});
  EXPECT_EQ(DatabaseFiles(path), before);
}

TEST(ProfileStoreReadOnly, RefusesAForeignFileWhoseSchemaIsOnlyInItsWalByteIdentical) {
  TempDir tmp;
  const std::string path = tmp.File("other.db");
  RawExecAndDie(path, "PRAGMA journal_mode = WAL; CREATE TABLE t(x); INSERT INTO t VALUES (1);");
  const auto before = DatabaseFiles(path);
  ASSERT_EQ(before.count("-wal"), 1u);
  ExpectInputError([&] { ProfileStore::OpenReadOnly(path); }, {path, "another application"});
  EXPECT_EQ(DatabaseFiles(path), before);
  // The read-write open too: no checkpoint on close before the file is accepted.
  ExpectInputError([&] { ProfileStore::Open(path); }, {path, "another application"});
  EXPECT_EQ(DatabaseFiles(path), before);
}

TEST(ProfileStoreReadOnly, RefusesAForeignFileWithAHotJournalByteIdentical) {
  TempDir tmp;
  const std::string path = tmp.File("other.db");
  RawExec(path, "CREATE TABLE t(x); INSERT INTO t VALUES (randomblob(100000));");
  // A transaction larger than the page cache spills into the file, then the writer dies.
  RawExecAndDie(path,
                "PRAGMA cache_size = 2; BEGIN; UPDATE t SET x = randomblob(100000); "
                "INSERT INTO t VALUES (randomblob(200000));");
  ASSERT_TRUE(fs::exists(path + "-journal"));
  const auto before = DatabaseFiles(path);
  ExpectInputError([&] { ProfileStore::OpenReadOnly(path); }, {path, "another application"});
  EXPECT_EQ(DatabaseFiles(path), before);
  ExpectInputError([&] { ProfileStore::Open(path); }, {path, "another application"});
  EXPECT_EQ(DatabaseFiles(path), before);
}

// A railwear database with a hot journal (an older rollback-mode file): a read-only open does
// not roll it back.
TEST(ProfileStoreReadOnly, RefusesARailwearFileWithAHotJournalUntouched) {
  TempDir tmp;
  const std::string path = tmp.File("old.rwdb");
  RawExec(path, Version2Database());
  RawExecAndDie(path,
                "PRAGMA cache_size = 2; BEGIN; INSERT INTO load_cases SELECT run_id, step, "
                "case_index + 1000, hex(randomblob(300000)) FROM load_cases;");
  ASSERT_TRUE(fs::exists(path + "-journal"));
  const auto before = DatabaseFiles(path);
  ExpectInputError([&] { ProfileStore::OpenReadOnly(path); },
                   {path, "rollback journal", "--resume"});
  EXPECT_EQ(DatabaseFiles(path), before);
}

// Schema 9 (issue 19): a failed run's message and last step are stored with its aborted state,
// cleared when the run is resumed (a new state), copied by merge with the run; a schema-8 file
// reads as having none and is migrated by the next read-write open.
TEST(ProfileStore, RunFailuresRoundTripClearOnResumeAndMerge) {
  TempDir tmp;
  const std::string path = tmp.File("f.rwdb");
  {
    ProfileStore db = ProfileStore::Open(path);
    const int64_t run = db.CreateRun(TestRun("failed"), TestStep(0));
    db.AppendStep(run, TestStep(1));
    EXPECT_FALSE(db.FindRunFailure(run).has_value());
    db.SetRunFailed(run, "wear: the contact solution did not converge");
    EXPECT_EQ(db.FindRun("failed")->state, RunState::kAborted);
    const std::optional<RunFailure> f = db.FindRunFailure(run);
    ASSERT_TRUE(f.has_value());
    EXPECT_EQ(f->step, 1);
    EXPECT_EQ(f->message, "wear: the contact solution did not converge");
    // Resumed: running again, the failure gone; failed again: the new message.
    db.SetRunState(run, RunState::kRunning);
    EXPECT_FALSE(db.FindRunFailure(run).has_value());
    db.SetRunFailed(run, "second");
    EXPECT_EQ(db.FindRunFailure(run)->message, "second");
    ExpectInputError([&] { db.SetRunFailed(run + 7, "x"); }, {"no run with id"});
  }
  // Merge copies the failure with its run; merging again changes nothing.
  const std::string merged = tmp.File("m.rwdb");
  {
    ProfileStore out = ProfileStore::Open(merged);
    const ProfileStore in = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(out.MergeRunsFrom(in).runs_copied, 1);
    EXPECT_EQ(out.MergeRunsFrom(in).runs_identical, 1);
    const RunInfo run = *out.FindRun("failed");
    EXPECT_EQ(run.state, RunState::kAborted);
    EXPECT_EQ(out.FindRunFailure(run.id)->message, "second");
  }
  // Schema 8: no table, no failure; migrated on write.
  RawExec(path, "DROP TABLE run_failures; PRAGMA user_version = 8;");
  {
    const ProfileStore ro = ProfileStore::OpenReadOnly(path);
    EXPECT_EQ(ro.SchemaVersion(), 8);
    EXPECT_FALSE(ro.FindRunFailure(ro.FindRun("failed")->id).has_value());
  }
  ProfileStore db = ProfileStore::Open(path);
  EXPECT_EQ(db.SchemaVersion(), ProfileStore::kSchemaVersion);
  EXPECT_FALSE(db.FindRunFailure(db.FindRun("failed")->id).has_value());
}

// Version 4 differs from 5 only in the CHECK on runs.state: read-only commands read it as it is.
TEST(ProfileStoreReadOnly, ReadsVersion4AsItIs) {
  TempDir tmp;
  const std::string path = tmp.File("v4.rwdb");
  {
    ProfileStore db = ProfileStore::Open(path);
    db.CreateRun(TestRun("r"), TestStep(0));
  }
  RawExec(path, "PRAGMA user_version = 4");
  const auto before = DatabaseFiles(path);
  const ProfileStore db = ProfileStore::OpenReadOnly(path);
  EXPECT_EQ(db.SchemaVersion(), 4);
  EXPECT_EQ(db.LastStep(db.FindRun("r")->id), 0);
  EXPECT_EQ(DatabaseFiles(path), before);
}

// An older schema is neither migrated nor switched to WAL by a read-only open: refused with the
// commands that migrate it, every byte unchanged.
TEST(ProfileStoreReadOnly, RefusesAnOlderSchemaWithoutMigratingIt) {
  TempDir tmp;
  const std::string path = tmp.File("old.rwdb");
  RawExec(path, Version2Database());
  const auto before = DatabaseFiles(path);
  ExpectInputError([&] { ProfileStore::OpenReadOnly(path); },
                   {path, "schema version 2", "never migrate", "railwear wear SCENE --db"});
  EXPECT_EQ(DatabaseFiles(path), before);
  EXPECT_EQ(ReadBytes(path)[18], 1);  // still rollback-journal mode (WAL would be 2)
  ExpectInputError([&] { ProfileStore::OpenReadOnly(tmp.File("missing.rwdb")); }, {"no such file"});
  EXPECT_FALSE(fs::exists(tmp.File("missing.rwdb")));
}

// ---------------------------------------------------------------------------------------------
// Merging study databases (issue 19, `railwear merge`).

// A study file with runs `names`, each with two steps of both rails and a curving start (every
// run-rows table gets rows), and one calibration (not run data).
void WriteStudy(const std::string& path, const std::vector<std::string>& names) {
  ProfileStore db = ProfileStore::Open(path);
  for (const std::string& name : names) {
    StepRecord first = TestStep(0);
    first.low_rail = TestLowRail(0);
    const int64_t run = db.CreateRun(TestRun(name), first);
    StepRecord second = TestStep(1);
    second.low_rail = TestLowRail(1);
    second.curving_starts = {{0, {0.25, -1.0 / 3.0}, {1.0, 2.0, 3.0, 4.0}}};
    db.AppendStep(run, second);
    db.SetRunState(run, RunState::kComplete);
  }
  db.AddCalibration(TestCalibration());
}

// Every row of every run-rows table of `db`, by run name and without ids or timestamps, as text
// (the rows of run `except` left out).
std::string RunContent(const ProfileStore& db, const std::string& except = "") {
  std::string out;
  for (const auto& [table, role] : db.MergeTableRoles()) {
    if (role != MergeTableRole::kRunRows) continue;
    const QueryResult columns = db.Query("SELECT name FROM pragma_table_info('" + table +
                                         "') WHERE name NOT IN "
                                         "('run_id', 'created_utc')");
    std::string select = "r.name";
    for (const auto& c : columns.rows) select += ", quote(t." + c[0] + ")";
    // By the run and up to three more columns (run_failures has two besides the run).
    std::string order = "1";
    for (size_t k = 2; k <= std::min<size_t>(4, columns.rows.size() + 1); ++k) {
      order += ", " + std::to_string(k);
    }
    const QueryResult rows = db.Query("SELECT " + select + " FROM " + table +
                                      " t JOIN runs r ON r.id = t.run_id WHERE r.name != '" +
                                      except + "' ORDER BY " + order);
    out += table + ":\n";
    for (const auto& row : rows.rows) {
      for (const auto& v : row) out += v + "|";
      out += "\n";
    }
  }
  return out;
}

// Every table of the schema has a merge role, and every table whose rows belong to runs is
// copied: a table added later without a role is refused, never skipped.
TEST(ProfileStoreMerge, EveryTableHasARoleAndARunTableIsNeverSkipped) {
  TempDir tmp;
  const std::string path = tmp.File("study.rwdb");
  ProfileStore db = ProfileStore::Open(path);
  const QueryResult tables = db.Query(
      "SELECT name FROM sqlite_schema WHERE type = 'table' AND name NOT LIKE 'sqlite_%' "
      "ORDER BY name");
  const auto roles = db.MergeTableRoles();
  ASSERT_EQ(roles.size(), tables.rows.size());
  std::vector<std::string> run_rows;
  for (size_t i = 0; i < roles.size(); ++i) {
    EXPECT_EQ(roles[i].first, tables.rows[i][0]);
    if (roles[i].second == MergeTableRole::kRunRows) run_rows.push_back(roles[i].first);
  }
  EXPECT_EQ(run_rows,
            (std::vector<std::string>{"curving_starts", "distributions", "load_cases",
                                      "low_rail_distributions", "low_rail_steps", "profiles",
                                      "run_failures", "step_warnings", "steps", "wheel_steps"}));
  // A table merge does not know (no run_id, not one of the known others) is refused by name.
  RawExec(path, "CREATE TABLE run_notes(note TEXT)");
  ExpectInputError([&] { db.MergeTableRoles(); }, {path, "table 'run_notes' is unknown to merge"});
}

TEST(ProfileStoreMerge, CopiesEveryRowOfEveryRunWithNewIdsBitForBit) {
  TempDir tmp;
  const std::string a = tmp.File("a.rwdb"), out_path = tmp.File("out.rwdb");
  WriteStudy(a, {"r1", "r2"});
  ProfileStore out = ProfileStore::Open(out_path);
  out.CreateRun(TestRun("already there"), TestStep(0));  // so the copied runs get other ids
  const auto before = DatabaseFiles(a);
  const ProfileStore in = ProfileStore::OpenReadOnly(a);
  const MergeSummary s = out.MergeRunsFrom(in);
  EXPECT_EQ(s.runs_copied, 2);
  EXPECT_EQ(s.runs_identical, 0);
  EXPECT_EQ(s.calibrations_left, 1);
  // Every run row of the input is in the output, under the run's name.
  EXPECT_EQ(RunContent(out, "already there"), RunContent(in));
  EXPECT_NE(RunContent(in).find("r1|"), std::string::npos);
  const std::optional<RunInfo> r2 = out.FindRun("r2");
  ASSERT_TRUE(r2.has_value());
  EXPECT_EQ(r2->id, 3);
  EXPECT_EQ(r2->state, RunState::kComplete);
  EXPECT_EQ(r2->scene_text, TestRun("r2").scene_text);
  const StepRecord step = out.LoadStep(r2->id, 1);
  EXPECT_EQ(step.profile.points(), TestStep(1).profile.points());
  ASSERT_TRUE(step.low_rail.has_value());
  EXPECT_EQ(step.low_rail->profile.points(), TestLowRail(1).profile.points());
  ASSERT_EQ(step.curving_starts.size(), 1u);
  EXPECT_EQ(step.curving_starts[0].state, (std::vector<double>{0.25, -1.0 / 3.0}));
  EXPECT_TRUE(out.Calibrations().empty());  // not run data
  EXPECT_EQ(DatabaseFiles(a), before);      // the input only read
}

TEST(ProfileStoreMerge, MergingTheSameRunsTwiceChangesNothing) {
  TempDir tmp;
  const std::string a = tmp.File("a.rwdb"), b = tmp.File("b.rwdb");
  WriteStudy(a, {"r1", "r2"});
  WriteStudy(b, {"r2"});  // the same run r2, written again (other timestamps)
  ProfileStore out = ProfileStore::Open(tmp.File("out.rwdb"));
  EXPECT_EQ(out.MergeRunsFrom(ProfileStore::OpenReadOnly(a)).runs_copied, 2);
  const std::string once = RunContent(out);
  const QueryResult ids_once = out.Query("SELECT id, name, created_utc FROM runs ORDER BY id");
  for (const std::string& input : {a, b, a}) {
    const MergeSummary s = out.MergeRunsFrom(ProfileStore::OpenReadOnly(input));
    EXPECT_EQ(s.runs_copied, 0);
    EXPECT_EQ(s.rows_copied, 0);
    EXPECT_EQ(s.runs_identical, input == a ? 2 : 1);
  }
  EXPECT_EQ(RunContent(out), once);
  EXPECT_EQ(out.Query("SELECT id, name, created_utc FROM runs ORDER BY id").rows, ids_once.rows);
}

TEST(ProfileStoreMerge, RefusesAConflictingRunMergingNothingOfItsInput) {
  TempDir tmp;
  const std::string a = tmp.File("a.rwdb"), b = tmp.File("b.rwdb");
  WriteStudy(a, {"r1"});
  WriteStudy(b, {"new", "r1"});
  {
    ProfileStore db = ProfileStore::Open(b);  // r1 of b: one value of one step differs
    StepRecord third = TestStep(2);
    third.low_rail = TestLowRail(2);
    db.AppendStep(db.FindRun("r1")->id, third);
  }
  ProfileStore out = ProfileStore::Open(tmp.File("out.rwdb"));
  out.MergeRunsFrom(ProfileStore::OpenReadOnly(a));
  const std::string before = RunContent(out);
  const auto files_before = DatabaseFiles(b);
  ExpectInputError([&] { out.MergeRunsFrom(ProfileStore::OpenReadOnly(b)); },
                   {b, "run 'r1' conflicts",
                    "table 'distributions' holds more rows of it in the input (the output has 4)",
                    "nothing of"});
  EXPECT_EQ(RunContent(out), before);  // "new" was not merged either
  EXPECT_FALSE(out.FindRun("new").has_value());
  EXPECT_EQ(DatabaseFiles(b), files_before);
}

}  // namespace
}  // namespace railwear
