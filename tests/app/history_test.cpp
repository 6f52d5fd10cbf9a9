// `railwear history` end to end: a study database built with ProfileStore (a run of three steps
// of progressively worn UIC60 — a gauge-corner wear bump 0.5 mm then 1 mm deep — with
// distributions and load-case JSON, and a run without steps), then the built binary
// (RAILWEAR_BINARY) runs each subcommand: tables, the profile round trip through CSV/BAN/JSON, the
// wear between steps against hand calculations, plots, read-only SQL, and the exit code 2 cases
// (unknown run, a step not stored (also across a gap), write statements, a missing database that
// must not be created, foreign files left untouched).
#include <sqlite3.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/history_plot.h"
#include "core/geometry/curve_locator.h"
#include "core/profile/builtin_profiles.h"
#include "core/profile/profile_io.h"
#include "profiles_db/profile_store.h"
#include "wear/wear_measures.h"

#include "core/numerics/units.h"
#include "tests/app/cli_runner.h"

namespace railwear {
namespace {

namespace fs = std::filesystem;

// UIC60 R13 arc (reference README §5, mm) and its gauge point 14 mm below the crown.
constexpr double kR13CentreY_mm = 23.016030, kR13CentreZ_mm = 14.949147, kR13_mm = 13.0;
constexpr double kGaugePointY_mm = 35.981335;
// Depths and crossings on spline profiles against analytic arcs: wear/wear_measures_test.cpp
// measured at most 5e-8 m; 2e-7 m = 2e-4 mm.
constexpr double kSplineTol_mm = 2e-4;
// The text tables print mm with 4 decimals: half a unit of the last place.
constexpr double kTableTol = 0.5e-4 + 1e-12;
// Profile files hold mm with 6 decimals: half a unit of the last place, in metres.
constexpr double kFileTol_m = 0.5e-9 + 1e-15;

using railwear::test::Contains;
using railwear::test::Outcome;
using railwear::test::ReadFile;

// The worn profile C(s) + depth(s) * inward normal, points every 0.05 mm along the original.
Profile OffsetProfile(const Profile& original, const std::function<double(double)>& depth) {
  const CurveLocator locator(original, true);
  const int n = static_cast<int>(std::ceil(original.Length() / 0.05e-3));
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k <= n; ++k) {
    const double s = original.Length() * k / n;
    points.push_back(original.Position(s) - depth(s) * locator.OutwardNormal(s));
  }
  return Profile(std::move(points), "offset");
}

double R13Arc(const Profile& uic60, double deg) {
  const double a = deg * M_PI / 180.0;
  const Eigen::Vector2d q(-(kR13CentreY_mm + kR13_mm * std::sin(a)) * kMm,
                          (kR13CentreZ_mm - kR13_mm * std::cos(a)) * kMm);
  return CurveLocator(uic60, true).Project(q).s;
}

// Gauge-corner wear: depth D from 3 mm down the flank (below R13's end at 87 degrees) up to 30
// degrees on R13, cos^2 tapers 3 mm long. In the flat part the worn surface is the circle of
// radius 13 - D about the R13 centre, so W3 = D and W2 follows from that circle.
std::function<double(double)> GaugeBump(const Profile& rail, double depth_m) {
  const double s0 = R13Arc(rail, 87.0) - 3e-3, s1 = R13Arc(rail, 30.0), taper = 3e-3;
  return [=](double s) {
    if (s >= s0 && s <= s1) return depth_m;
    const double off = s < s0 ? s0 - s : s - s1;
    if (off >= taper) return 0.0;
    const double c = std::cos(0.5 * M_PI * off / taper);
    return depth_m * c * c;
  };
}

// W2 of the bump of depth D (mm): the gauge face at z = 14 mm moves from the R13 circle to the
// R(13 - D) circle.
double HandW2_mm(double depth_mm) {
  const double dz = kR13CentreZ_mm - 14.0;
  return kGaugePointY_mm - kR13CentreY_mm - std::sqrt(std::pow(kR13_mm - depth_mm, 2) - dz * dz);
}

class HistoryTest : public railwear::test::CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    BuildStudy((dir_ / "study.rwdb").string());
  }

  // Run "baseline": step 0 the unworn UIC60, steps 1 and 2 the gauge bump 0.5 and 1.0 mm deep,
  // with the summary columns from CompareProfiles. Step 1's wear_depth_mm has no s (as a
  // schema-1 row), step 2's has it. Run "empty" has no steps.
  void BuildStudy(const std::string& path) {
    ProfileStore db = ProfileStore::Open(path);
    RunInfo info;
    info.name = "baseline";
    info.program_version = "0.1.0";
    info.scene_text = "[wear]\nlaw = \"archard\"\n";
    info.wear_law_json = R"({"law":"archard","k":1e-4})";
    const int64_t run = db.CreateRun(info);
    const Profile rail = MakeUic60();
    WearMeasureOptions options;
    options.gauge = MakeWearGauge(rail);
    const double depths_mm[] = {0.0, 0.5, 1.0};
    for (int k = 0; k < 3; ++k) {
      StepRecord step;
      step.step = k;
      step.passes = 50000.0 * k;
      step.mgt = 0.5 * k;
      step.profile = k == 0 ? rail : OffsetProfile(rail, GaugeBump(rail, depths_mm[k] * kMm));
      const WearMeasures m = CompareProfiles(rail, step.profile, options);
      step.worn_area_mm2 = m.worn_area_m2 * 1e6;
      step.max_depth_mm = m.max_depth_m * 1e3;
      step.max_depth_y_mm = m.max_depth_y_m * 1e3;
      step.w1_mm = m.vertical_wear_m * 1e3;
      step.w2_mm = m.side_wear_m * 1e3;
      step.w3_mm = m.wear_45_m * 1e3;
      step.smoothing_area_error = 1e-4 * k;
      step.load_cases_json = {LoadCaseJson(k, 0), LoadCaseJson(k, 1)};
      if (k > 0) {
        Distribution depth{"wear_depth_mm", {}, {}};
        for (size_t i = 0; i < m.s_m.size(); i += 10) {
          depth.y_m.push_back(rail.Position(m.s_m[i]).x());
          depth.value.push_back(m.depth_m[i] * 1e3);
          if (k == 2) depth.s_m.push_back(m.s_m[i]);
        }
        step.distributions.push_back(depth);
        step.distributions.push_back(
            {"damage", depth.y_m, std::vector<double>(depth.y_m.size(), 1e-6 * k)});
      }
      db.AppendStep(run, step);
      stored_.push_back(step);
    }
    db.SetRunState(run, RunState::kComplete);
    RunInfo empty = info;
    empty.name = "empty";
    db.CreateRun(empty);
  }
  static std::string LoadCaseJson(int step, int index) {
    return "{\"case\":" + std::to_string(index) +
           ",\"T_gamma_J_per_m\":" + std::to_string(10 * step + index) + "}";
  }

  // Data rows of an aligned table (after the header and the rule), split on blanks.
  static std::vector<std::vector<std::string>> TableRows(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    std::vector<std::vector<std::string>> rows;
    for (int n = 0; std::getline(in, line); ++n) {
      if (n < 2) continue;
      std::istringstream cells(line);
      std::vector<std::string> row;
      for (std::string cell; cells >> cell;) row.push_back(cell);
      rows.push_back(row);
    }
    return rows;
  }

  std::vector<StepRecord> stored_;
};

TEST_F(HistoryTest, HelpListsTheSubcommands) {
  const Outcome o = Run("history --help");
  EXPECT_EQ(o.exit_code, 0);
  for (const char* sub : {"runs", "steps", "profile", "diff", "plot", "sql", "--db"}) {
    EXPECT_TRUE(Contains(o.out, sub));
  }
  EXPECT_EQ(Run("history").exit_code, 2);  // a subcommand is required
}

TEST_F(HistoryTest, RunsTable) {
  const Outcome o = Run("history --db study.rwdb runs");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "name"));
  EXPECT_TRUE(Contains(o.out, "program_version"));
  const auto rows = TableRows(o.out);
  ASSERT_EQ(rows.size(), 2u);
  // name, state, created, steps, last MGT, program version
  EXPECT_EQ(rows[0][0], "baseline");
  EXPECT_EQ(rows[0][1], "complete");
  EXPECT_EQ(rows[0][2].size(), std::string("2024-01-01T00:00:00.000Z").size());
  EXPECT_EQ(rows[0][3], "3");
  EXPECT_EQ(rows[0][4], "1.0000");
  EXPECT_EQ(rows[0][5], "0.1.0");
  EXPECT_EQ(rows[1][0], "empty");
  EXPECT_EQ(rows[1][1], "running");
  EXPECT_EQ(rows[1][3], "0");
  EXPECT_EQ(rows[1][4], "NULL");
  // --db may also follow the subcommand.
  const Outcome after = Run("history runs --db study.rwdb");
  EXPECT_EQ(after.exit_code, 0) << after.err;
  EXPECT_EQ(after.out, o.out);
}

TEST_F(HistoryTest, StepsTableHasTheStoredNumbers) {
  const Outcome o = Run("history --db study.rwdb steps baseline");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "worn_area_mm2"));
  EXPECT_TRUE(Contains(o.err, "run 'baseline' (complete), 3 step(s)"));
  const auto rows = TableRows(o.out);
  ASSERT_EQ(rows.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const StepRecord& s = stored_[k];
    ASSERT_EQ(rows[k].size(), 12u);
    EXPECT_EQ(std::stoi(rows[k][0]), k);
    EXPECT_DOUBLE_EQ(std::stod(rows[k][1]), s.passes);
    EXPECT_NEAR(std::stod(rows[k][2]), s.mgt, kTableTol);
    EXPECT_NEAR(std::stod(rows[k][3]), s.worn_area_mm2, kTableTol);
    EXPECT_NEAR(std::stod(rows[k][4]), s.max_depth_mm, kTableTol);
    EXPECT_NEAR(std::stod(rows[k][6]), s.w1_mm, kTableTol);
    EXPECT_NEAR(std::stod(rows[k][7]), s.w2_mm, kTableTol);
    EXPECT_NEAR(std::stod(rows[k][8]), s.w3_mm, kTableTol);
    // W2 and W3 rates since the previous stored step [mm/MGT] (issue 15).
    if (k == 0) {
      EXPECT_EQ(rows[k][10], "NULL");
      EXPECT_EQ(rows[k][11], "NULL");
    } else {
      const StepRecord& p = stored_[k - 1];
      EXPECT_NEAR(std::stod(rows[k][10]), (s.w2_mm - p.w2_mm) / (s.mgt - p.mgt), kTableTol);
      EXPECT_NEAR(std::stod(rows[k][11]), (s.w3_mm - p.w3_mm) / (s.mgt - p.mgt), kTableTol);
    }
  }
  // The stored values themselves are the hand-calculated ones (wear/wear_measures.h).
  EXPECT_NEAR(std::stod(rows[2][8]), 1.0, kSplineTol_mm + kTableTol);
  EXPECT_NEAR(std::stod(rows[2][7]), HandW2_mm(1.0), kSplineTol_mm + kTableTol);
  EXPECT_NEAR(std::stod(rows[1][8]), 0.5, kSplineTol_mm + kTableTol);
}

TEST_F(HistoryTest, ProfileRoundTripsThroughCsvBanAndJson) {
  const Profile& want = stored_[1].profile;
  const Outcome csv = Run("history --db study.rwdb profile baseline --step 1 --out p1.csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out, "");
  EXPECT_TRUE(Contains(csv.err, "written to p1.csv"));
  for (const char* name : {"p1.csv", "p1.ban"}) {
    SCOPED_TRACE(name);
    if (std::string(name) == "p1.ban") {
      const Outcome ban =
          Run("history --db study.rwdb profile baseline --step 1 --format ban "
              "--out p1.ban");
      ASSERT_EQ(ban.exit_code, 0) << ban.err;
    }
    const Profile back = ReadProfileFile((dir_ / name).string()).profile;
    ASSERT_EQ(back.size(), want.size());
    for (int i = 0; i < want.size(); ++i) {
      ASSERT_NEAR(back.points()[i].x(), want.points()[i].x(), kFileTol_m) << i;
      ASSERT_NEAR(back.points()[i].y(), want.points()[i].y(), kFileTol_m) << i;
    }
  }
  // Without --out: CSV on stdout, the same bytes as the file; default step = the last one.
  const Outcome out = Run("history --db study.rwdb profile baseline --step 1");
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_EQ(out.out, ReadFile(dir_ / "p1.csv"));
  EXPECT_EQ(out.out.rfind("y_mm,z_mm\n", 0), 0u);
  const Outcome last = Run("history --db study.rwdb profile baseline --format json");
  ASSERT_EQ(last.exit_code, 0) << last.err;
  const nlohmann::json j = nlohmann::json::parse(last.out);
  EXPECT_EQ(j["run"], "baseline");
  EXPECT_EQ(j["step"], 2);
  EXPECT_DOUBLE_EQ(j["mgt"].get<double>(), 1.0);
  EXPECT_EQ(j["points"], stored_[2].profile.size());
  ASSERT_EQ(j["y_mm"].size(), static_cast<size_t>(stored_[2].profile.size()));
  EXPECT_DOUBLE_EQ(j["y_mm"][7].get<double>(), stored_[2].profile.points()[7].x() * 1e3);
  EXPECT_DOUBLE_EQ(j["z_mm"][7].get<double>(), stored_[2].profile.points()[7].y() * 1e3);
  // A .json --out chooses JSON by itself.
  ASSERT_EQ(Run("history --db study.rwdb profile baseline --out last.json").exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(ReadFile(dir_ / "last.json")), j);
}

TEST_F(HistoryTest, ProfileBadStepAndFormatExitTwo) {
  const Outcome step = Run("history --db study.rwdb profile baseline --step 7");
  EXPECT_EQ(step.exit_code, 2);
  EXPECT_TRUE(Contains(step.err,
                       "railwear: error: database 'study.rwdb': run 'baseline' has no step 7 "
                       "(--step); expected one of its stored steps: 0-2"));
  EXPECT_EQ(step.out, "");
  const Outcome format = Run("history --db study.rwdb profile baseline --format xml");
  EXPECT_EQ(format.exit_code, 2);
  EXPECT_TRUE(Contains(format.err, "--format 'xml': expected csv, ban or json"));
  const Outcome mismatch = Run("history --db study.rwdb profile baseline --format ban --out a.csv");
  EXPECT_EQ(mismatch.exit_code, 2);
  EXPECT_TRUE(Contains(mismatch.err, "does not match --format ban"));
  EXPECT_FALSE(fs::exists(dir_ / "a.csv"));
  const Outcome empty = Run("history --db study.rwdb profile empty");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_TRUE(Contains(empty.err, "run 'empty' has no steps yet"));
}

TEST_F(HistoryTest, DiffMatchesHandCalculationAndAddsUp) {
  const Outcome full = Run("history --db study.rwdb diff baseline 0 2 --json");
  ASSERT_EQ(full.exit_code, 0) << full.err;
  const nlohmann::json a = nlohmann::json::parse(full.out);
  EXPECT_EQ(a["from"]["step"], 0);
  EXPECT_EQ(a["to"]["step"], 2);
  EXPECT_NEAR(a["w1_mm"].get<double>(), 0.0, kSplineTol_mm);
  EXPECT_NEAR(a["w2_mm"].get<double>(), HandW2_mm(1.0), kSplineTol_mm);
  EXPECT_NEAR(a["w3_mm"].get<double>(), 1.0, kSplineTol_mm);
  EXPECT_NEAR(a["max_depth_mm"].get<double>(), 1.0, kSplineTol_mm);
  EXPECT_LT(a["max_depth_y_mm"].get<double>(), -20.0);  // on the gauge side
  EXPECT_NEAR(a["worn_area_mm2"].get<double>(), stored_[2].worn_area_mm2, 1e-9);
  EXPECT_EQ(a["unmatched_samples"], 0);

  // Step 1 -> 2: measured on the step-0 gauge, so W(1 -> 2) = W(0 -> 2) - W(0 -> 1).
  const Outcome part = Run("history --db study.rwdb diff baseline 1 2 --json");
  ASSERT_EQ(part.exit_code, 0) << part.err;
  const nlohmann::json b = nlohmann::json::parse(part.out);
  EXPECT_NEAR(b["w3_mm"].get<double>(), 0.5, 2 * kSplineTol_mm);
  EXPECT_NEAR(b["w3_mm"].get<double>(), stored_[2].w3_mm - stored_[1].w3_mm, 1e-9);
  EXPECT_NEAR(b["w2_mm"].get<double>(), stored_[2].w2_mm - stored_[1].w2_mm, 1e-9);
  EXPECT_NEAR(b["w2_mm"].get<double>(), HandW2_mm(1.0) - HandW2_mm(0.5), 2 * kSplineTol_mm);

  const Outcome text = Run("history --db study.rwdb diff baseline 0 2");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_TRUE(Contains(text.out, "to step       2 (1.0000 MGT, 100000 passes)"));
  EXPECT_TRUE(Contains(text.out, "W3 45 deg     1.0000 mm"));
  EXPECT_TRUE(Contains(text.out, "W1 vertical   0.0000 mm"));
  EXPECT_TRUE(Contains(text.out, "worn area"));

  const Outcome bad = Run("history --db study.rwdb diff baseline 0 3");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err,
                       "run 'baseline' has no step 3 (step B); expected one of its "
                       "stored steps: 0-2"));
}

// Issue 17: steps are addressed by their stored number, not their position. With step 1 deleted
// by hand (rows of another program), `diff 0 2` compares step 0 with step 2 (it read past the end
// of the vector before), and step 1 is an error naming the steps there are.
TEST_F(HistoryTest, StepsAreAddressedByStoredNumberAcrossAGap) {
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open((dir_ / "study.rwdb").c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw,
                         "PRAGMA foreign_keys = ON; DELETE FROM steps WHERE step = 1 AND run_id = "
                         "(SELECT id FROM runs WHERE name = 'baseline')",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(raw);

  const Outcome diff = Run("history --db study.rwdb diff baseline 0 2 --json");
  ASSERT_EQ(diff.exit_code, 0) << diff.err;
  const nlohmann::json j = nlohmann::json::parse(diff.out);
  EXPECT_EQ(j["from"]["step"], 0);
  EXPECT_EQ(j["to"]["step"], 2);
  EXPECT_EQ(j["to"]["mgt"].get<double>(), stored_[2].mgt);
  EXPECT_NEAR(j["w3_mm"].get<double>(), 1.0, kSplineTol_mm);  // step 2's 1 mm bump

  const Outcome profile = Run("history --db study.rwdb profile baseline --step 2 --format json");
  ASSERT_EQ(profile.exit_code, 0) << profile.err;
  EXPECT_EQ(nlohmann::json::parse(profile.out)["mgt"].get<double>(), stored_[2].mgt);

  for (const char* args : {"diff baseline 0 1", "diff baseline 1 2", "profile baseline --step 1"}) {
    const Outcome gap = Run(std::string("history --db study.rwdb ") + args);
    EXPECT_EQ(gap.exit_code, 2) << args;
    EXPECT_TRUE(Contains(gap.err, "run 'baseline' has no step 1"));
    EXPECT_TRUE(Contains(gap.err, "expected one of its stored steps: 0, 2"));
    EXPECT_EQ(gap.out, "");
  }
}

TEST_F(HistoryTest, PlotWritesThreePngs) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  const Outcome o = Run("history --db study.rwdb plot baseline --out wear");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  for (const char* name : {"wear_profiles.png", "wear_depth.png", "wear_measures.png"}) {
    const std::string png = ReadFile(dir_ / name);
    ASSERT_GT(png.size(), 1000u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
    EXPECT_TRUE(Contains(o.err, std::string("wrote wear") + (name + 4)));
  }
  EXPECT_EQ(o.out, "");
  // Default prefix: the run name.
  ASSERT_EQ(Run("history --db study.rwdb plot baseline").exit_code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "baseline_depth.png"));
}

TEST_F(HistoryTest, DepthCurvesUseStoredArcLengthsElseProfiles) {
  ProfileStore db = ProfileStore::Open((dir_ / "study.rwdb").string());
  const int64_t run = db.FindRun("baseline")->id;
  std::vector<StepRecord> steps;
  for (int k = 0; k < 3; ++k) steps.push_back(db.LoadStep(run, k));
  const std::vector<app::DepthCurve> curves = app::WearDepthCurves(steps);
  ASSERT_EQ(curves.size(), 2u);
  // Step 1's distribution has no s: computed from the profiles, every 0.1 mm.
  EXPECT_EQ(curves[0].source, app::DepthSource::kFromProfiles);
  // Step 2's has s: taken as stored (every 10th sample).
  EXPECT_EQ(curves[1].source, app::DepthSource::kStoredWithS);
  EXPECT_EQ(curves[1].s_mm.size(), steps[2].distributions[1].s_m.size());
  double max1 = 0.0, max2 = 0.0;
  for (double d : curves[0].depth_mm) max1 = std::max(max1, d);
  for (double d : curves[1].depth_mm) max2 = std::max(max2, d);
  EXPECT_NEAR(max1, 0.5, kSplineTol_mm);
  EXPECT_NEAR(max2, 1.0, kSplineTol_mm);
}

TEST_F(HistoryTest, PlotWithoutGnuplotExitsOneNamingIt) {
  const Outcome o = Run("history --db study.rwdb plot baseline", "PATH=/nonexistent");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_TRUE(Contains(o.err, "railwear: error: history plot needs the program 'gnuplot'"));
}

TEST_F(HistoryTest, SqlIsReadOnly) {
  const Outcome o =
      Run("history --db study.rwdb sql \"SELECT step, mgt, length(yz) AS bytes "
          "FROM profiles JOIN steps USING (run_id, step) ORDER BY step\"");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const auto rows = TableRows(o.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[2][0], "2");
  EXPECT_EQ(rows[2][1], "1.0");
  EXPECT_EQ(rows[2][2], std::to_string(16 * stored_[2].profile.size()));
  EXPECT_EQ(o.out.substr(0, o.out.find('\n')).find("step"), 0u);

  const Outcome tsv =
      Run("history --db study.rwdb sql --tsv \"SELECT name, state FROM runs "
          "ORDER BY id\"");
  ASSERT_EQ(tsv.exit_code, 0) << tsv.err;
  EXPECT_EQ(tsv.out, "name\tstate\nbaseline\tcomplete\nempty\trunning\n");

  for (const char* sql : {"DELETE FROM steps", "UPDATE runs SET name = 'x'", "DROP TABLE runs"}) {
    const Outcome w = Run(std::string("history --db study.rwdb sql \"") + sql + "\"");
    EXPECT_EQ(w.exit_code, 2) << sql;
    EXPECT_TRUE(Contains(w.err, "railwear: error: query on 'study.rwdb'"));
    EXPECT_TRUE(Contains(w.err, "read-only"));
  }
  EXPECT_EQ(ProfileStore::Open((dir_ / "study.rwdb").string()).Runs().size(), 2u);
  EXPECT_EQ(ProfileStore::Open((dir_ / "study.rwdb").string()).Steps(1).size(), 3u);
}

TEST_F(HistoryTest, UnknownRunExitsTwoNamingIt) {
  for (const char* cmd : {"steps nope", "profile nope", "diff nope 0 1", "plot nope"}) {
    const Outcome o = Run(std::string("history --db study.rwdb ") + cmd);
    EXPECT_EQ(o.exit_code, 2) << cmd;
    EXPECT_TRUE(Contains(o.err,
                         "railwear: error: database 'study.rwdb': no run named 'nope'; "
                         "expected one of 'baseline', 'empty'"))
        << cmd;
    EXPECT_EQ(o.out, "");
  }
}

TEST_F(HistoryTest, MissingDatabaseExitsTwoAndIsNotCreated) {
  for (const char* cmd : {"runs", "steps baseline", "sql \"SELECT 1\""}) {
    const Outcome o = Run(std::string("history --db missing.rwdb ") + cmd);
    EXPECT_EQ(o.exit_code, 2) << cmd;
    EXPECT_TRUE(Contains(o.err, "railwear: error: database 'missing.rwdb': no such file"));
    EXPECT_FALSE(fs::exists(dir_ / "missing.rwdb"));
    EXPECT_FALSE(fs::exists(dir_ / "missing.rwdb-wal"));
  }
  // The default database is wear.sqlite in the working directory; it is not created either.
  const Outcome def = Run("history runs");
  EXPECT_EQ(def.exit_code, 2);
  EXPECT_TRUE(Contains(def.err, "database 'wear.sqlite': no such file"));
  EXPECT_FALSE(fs::exists(dir_ / "wear.sqlite"));
}

TEST_F(HistoryTest, ForeignAndEmptyFilesAreRefusedUntouched) {
  std::ofstream(dir_ / "profile.csv") << "y_mm,z_mm\n0,0\n1,1\n2,4\n3,9\n";
  const std::string before = ReadFile(dir_ / "profile.csv");
  const Outcome o = Run("history --db profile.csv runs");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "database 'profile.csv': not an SQLite database"));
  EXPECT_EQ(ReadFile(dir_ / "profile.csv"), before);

  std::ofstream(dir_ / "empty.rwdb").flush();
  const Outcome e = Run("history --db empty.rwdb runs");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_TRUE(Contains(e.err, "database 'empty.rwdb': empty file"));
  EXPECT_EQ(fs::file_size(dir_ / "empty.rwdb"), 0u);
}

}  // namespace
}  // namespace railwear
