// Two-rail wear studies (issue 15) end to end: the [track] scene table and the `rail` key of
// traffic entries, `railwear wear` storing and resuming both rails and printing their wear
// rates, and `history steps/profile/diff/plot` reading the low rail.
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/history_plot.h"
#include "app/scene.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"

namespace railwear::test {
namespace {

using TwoRailWearTest = CliFixture;

// The data rows of an aligned table (after the header and the rule), split at blanks.
std::vector<std::vector<std::string>> Rows(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::vector<std::string>> rows;
  int n = 0;
  for (std::string line; std::getline(in, line); ++n) {
    if (n < 2) continue;
    std::istringstream cells(line);
    std::vector<std::string> row;
    for (std::string cell; cells >> cell;) row.push_back(cell);
    rows.push_back(row);
  }
  return rows;
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// ParseScene's InputError message for `text` ("" when it parses).
std::string SceneError(const std::string& text) {
  try {
    app::ParseScene(text, "two.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TwoRailSceneTest, TrackTableGivesBothRailsAndTrafficItsRail) {
  const app::Scene s = app::ParseScene(kTwoRailWearStudy, "two.toml");
  ASSERT_TRUE(s.wear.has_value());
  ASSERT_TRUE(s.wear->low_rail_profile.has_value());
  EXPECT_EQ(s.low_rail_profile_spec, "builtin:UIC60");  // default: the high rail
  EXPECT_EQ(s.cant, "1:40");
  EXPECT_DOUBLE_EQ(s.wear->cant_ratio, 0.025);
  ASSERT_EQ(s.wear->traffic.size(), 2u);
  EXPECT_EQ(s.wear->traffic[0].rail, RailSide::kHigh);  // default
  EXPECT_EQ(s.wear->traffic[1].rail, RailSide::kLow);
  // A [rail] scene is a single-rail study.
  const app::Scene one = app::ParseScene(kSmallWearStudy, "one.toml");
  EXPECT_FALSE(one.wear->low_rail_profile.has_value());
}

TEST(TwoRailSceneTest, BadRailsAndTracksAreInputErrors) {
  const std::string two = kTwoRailWearStudy;
  EXPECT_NE(SceneError(Replace(two, "rail = \"low\"", "rail = \"left\""))
                .find("traffic[1].rail' = \"left\": expected one of 'high', 'low'"),
            std::string::npos)
      << SceneError(Replace(two, "rail = \"low\"", "rail = \"left\""));
  EXPECT_NE(SceneError(Replace(two, "rail = \"low\"", "rail = 1")).find("traffic[1].rail"),
            std::string::npos);
  // A low-rail entry needs [track]; [rail] and [track] together are refused.
  const std::string one_rail = Replace(two, "[track]\nhigh_rail = \"builtin:UIC60\"\ninclination",
                                       "[rail]\nprofile = \"builtin:UIC60\"\ncant");
  EXPECT_NE(SceneError(one_rail).find("traffic[1].rail' = \"low\": expected \"high\" in a scene "
                                      "with [rail]"),
            std::string::npos)
      << SceneError(one_rail);
  const std::string both = Replace(two, "[wheel]", "[rail]\nprofile = \"builtin:UIC60\"\n[wheel]");
  EXPECT_NE(SceneError(both).find("either [rail] (one rail) or [track] (both rails)"),
            std::string::npos)
      << SceneError(both);
  const std::string neither =
      Replace(two, "[track]\nhigh_rail = \"builtin:UIC60\"\ninclination = \"1:40\"\n", "");
  EXPECT_NE(SceneError(neither).find("'rail' is missing"), std::string::npos)
      << SceneError(neither);
  // The curve's radius must be one a vehicle can run (at least 50 m).
  EXPECT_NE(
      SceneError(Replace(two, "inclination", "radius_m = 20\ninclination")).find("track.radius_m"),
      std::string::npos);
  EXPECT_NE(SceneError(Replace(two, "high_rail", "low_rail = \"builtin:UIC99\"\nhigh_rail"))
                .find("track.low_rail"),
            std::string::npos);
}

TEST(WearRatesTest, RatesBetweenStepsAndOverTheLastHalf) {
  std::vector<StepRecord> steps(4);
  const double mgt[] = {0.0, 1.0, 3.0, 4.0}, w2[] = {0.0, 1.0, 2.0, 4.0}, w3[] = {0, 2, 2, 2};
  for (int k = 0; k < 4; ++k) {
    steps[k].step = k;
    steps[k].mgt = mgt[k];
    steps[k].w2_mm = w2[k];
    steps[k].w3_mm = w3[k];
  }
  const app::WearRates run = app::RatesBetween(steps.front(), steps.back());
  EXPECT_DOUBLE_EQ(run.w2_mm_per_mgt, 1.0);
  EXPECT_DOUBLE_EQ(run.w3_mm_per_mgt, 0.5);
  // Half of 4 MGT is 2 MGT, between steps 1 and 2: W2 = 1.5, W3 = 2 there.
  const app::WearRates last = app::LastHalfRates(steps);
  EXPECT_DOUBLE_EQ(last.w2_mm_per_mgt, (4.0 - 1.5) / 2.0);
  EXPECT_DOUBLE_EQ(last.w3_mm_per_mgt, 0.0);
  EXPECT_TRUE(std::isnan(app::RatesBetween(steps[1], steps[1]).w2_mm_per_mgt));  // no traffic
}

TEST_F(TwoRailWearTest, BothRailsAreStoredResumedAndReportedWithRates) {
  Write("two.toml", kTwoRailWearStudy);
  const Outcome o = Run("wear two.toml --db a.sqlite --threads 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "run 'two rails' in a.sqlite: 2 steps (complete)")) << o.out;
  EXPECT_TRUE(Contains(o.out, "high rail:\n")) << o.out;
  EXPECT_TRUE(Contains(o.out, "low rail:\n")) << o.out;
  EXPECT_TRUE(Contains(o.out, "wear rates [mm/MGT], over the run (MGT 0 to ")) << o.out;
  EXPECT_TRUE(Contains(o.out, "\n  high rail  W2 ")) << o.out;
  EXPECT_TRUE(Contains(o.out, "\n  low rail   W2 ")) << o.out;
  EXPECT_TRUE(Contains(o.err, "(high rail), ")) << o.err;

  ProfileStore store = ProfileStore::Open((dir_ / "a.sqlite").string());
  const int64_t run = store.FindRun("two rails")->id;
  const std::vector<StepRecord> steps = store.Steps(run);
  ASSERT_EQ(steps.size(), 3u);
  for (const StepRecord& s : steps) ASSERT_TRUE(s.low_rail.has_value()) << s.step;
  // Both rails wear where their wheels run: the high rail at its gauge corner, the low rail on
  // its crown (own frames, gauge side y < 0); the high rail's case sets the steps.
  EXPECT_GT(steps[2].max_depth_mm, steps[1].max_depth_mm);
  EXPECT_NEAR(steps[1].max_depth_mm, 0.1, 0.01);
  EXPECT_LT(steps[2].max_depth_y_mm, -25.0);
  EXPECT_GT(steps[2].low_rail->max_depth_mm, 0.0);
  EXPECT_LT(steps[2].low_rail->max_depth_mm, steps[2].max_depth_mm);
  EXPECT_GT(steps[2].low_rail->max_depth_y_mm, -20.0);
  const StepRecord last = store.LoadStep(run, 2);
  ASSERT_EQ(last.load_cases_json.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(last.load_cases_json[0])["rail"], "high");
  EXPECT_EQ(nlohmann::json::parse(last.load_cases_json[1])["rail"], "low");
  bool low_damage = false;
  for (const Distribution& d : last.low_rail->distributions) {
    low_damage = low_damage || d.kind == "rcf_damage";
  }
  EXPECT_TRUE(low_damage);
  EXPECT_NE(last.low_rail->profile.points(), store.LoadLowRailProfile(run, 0).points());

  // Stopped after one step and resumed: the same two rails, bit for bit.
  ASSERT_EQ(Run("wear two.toml --db b.sqlite --steps 1").exit_code, 0);
  const Outcome resumed = Run("wear two.toml --db b.sqlite --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  ProfileStore b = ProfileStore::Open((dir_ / "b.sqlite").string());
  const int64_t run_b = b.FindRun("two rails")->id;
  ASSERT_EQ(b.LastStep(run_b), 2);
  EXPECT_EQ(b.LoadProfile(run_b, 2).points(), store.LoadProfile(run, 2).points());
  EXPECT_EQ(b.LoadLowRailProfile(run_b, 2).points(), store.LoadLowRailProfile(run, 2).points());
  EXPECT_EQ(b.Steps(run_b)[2].low_rail->w2_mm, steps[2].low_rail->w2_mm);

  // history steps: both rails, each with its W2 / W3 rates between stored steps.
  const Outcome h = Run("history --db a.sqlite steps \"two rails\"");
  ASSERT_EQ(h.exit_code, 0) << h.err;
  EXPECT_TRUE(Contains(h.out, "low_W2_mm_per_MGT")) << h.out;
  EXPECT_TRUE(Contains(h.err, "high and low rail")) << h.err;
  const auto rows = Rows(h.out);
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_EQ(rows[2].size(), 21u);  // 12 columns + the low rail's 9
  EXPECT_EQ(rows[0][10], "NULL");  // no rate before step 0
  for (int k = 1; k <= 2; ++k) {
    const double mgt = steps[k].mgt - steps[k - 1].mgt;
    const StepRecord &a = steps[k - 1], &z = steps[k];
    EXPECT_NEAR(std::stod(rows[k][10]), (z.w2_mm - a.w2_mm) / mgt, 1e-4);
    EXPECT_NEAR(std::stod(rows[k][11]), (z.w3_mm - a.w3_mm) / mgt, 1e-4);
    EXPECT_NEAR(std::stod(rows[k][15]), z.low_rail->w1_mm, 1e-4);
    EXPECT_NEAR(std::stod(rows[k][19]), (z.low_rail->w2_mm - a.low_rail->w2_mm) / mgt, 1e-4);
    EXPECT_NEAR(std::stod(rows[k][20]), (z.low_rail->w3_mm - a.low_rail->w3_mm) / mgt, 1e-4);
  }
  EXPECT_GT(std::stod(rows[2][11]), 0.0);  // the high rail's gauge corner wears

  // history profile and diff select the rail.
  const Outcome low_json =
      Run("history --db a.sqlite profile \"two rails\" --rail low --format json");
  ASSERT_EQ(low_json.exit_code, 0) << low_json.err;
  const nlohmann::json lj = nlohmann::json::parse(low_json.out);
  EXPECT_EQ(lj["rail"], "low");
  const Profile low_last = store.LoadLowRailProfile(run, 2);
  ASSERT_EQ(lj["points"], low_last.size());
  EXPECT_NEAR(lj["y_mm"][10].get<double>(), low_last.points()[10].x() * 1e3, 1e-9);
  const Outcome diff = Run("history --db a.sqlite diff \"two rails\" 0 2 --rail low --json");
  ASSERT_EQ(diff.exit_code, 0) << diff.err;
  const nlohmann::json dj = nlohmann::json::parse(diff.out);
  EXPECT_EQ(dj["rail"], "low");
  EXPECT_NEAR(dj["w2_mm"].get<double>(), steps[2].low_rail->w2_mm, 1e-9);
  EXPECT_NEAR(dj["max_depth_mm"].get<double>(), steps[2].low_rail->max_depth_mm, 1e-6);
  const Outcome high_diff = Run("history --db a.sqlite diff \"two rails\" 0 2 --json");
  EXPECT_NEAR(nlohmann::json::parse(high_diff.out)["w3_mm"].get<double>(), steps[2].w3_mm, 1e-9);
  const Outcome bad = Run("history --db a.sqlite profile \"two rails\" --rail left");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "--rail 'left': expected high or low")) << bad.err;

  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    const Outcome plot = Run("history --db a.sqlite plot \"two rails\" --out two");
    ASSERT_EQ(plot.exit_code, 0) << plot.err;
    for (const char* png : {"two_profiles.png", "two_depth.png", "two_measures.png"}) {
      EXPECT_GT(fs::file_size(dir_ / png), 1000u) << png;
    }
  }
}

TEST_F(TwoRailWearTest, SingleRailRunHasNoLowRailButRates) {
  Write("one.toml", kSmallWearStudy);
  const Outcome o = Run("wear one.toml --db one.sqlite --steps 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_FALSE(Contains(o.out, "low rail")) << o.out;
  EXPECT_TRUE(Contains(o.out, "  rail       W2 ")) << o.out;
  const Outcome low = Run("history --db one.sqlite profile \"small study\" --rail low");
  EXPECT_EQ(low.exit_code, 2);
  EXPECT_TRUE(Contains(low.err, "has one rail only")) << low.err;
  const Outcome h = Run("history --db one.sqlite steps \"small study\"");
  ASSERT_EQ(h.exit_code, 0);
  EXPECT_FALSE(Contains(h.out, "low_"));
  EXPECT_EQ(Rows(h.out).at(1).size(), 12u);
}

TEST_F(TwoRailWearTest, BadRailValueExitsTwo) {
  Write("bad.toml", Replace(kTwoRailWearStudy, "rail = \"low\"", "rail = \"inner\""));
  const Outcome o = Run("wear bad.toml --db bad.sqlite");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "traffic[1].rail")) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.sqlite"));
}

}  // namespace
}  // namespace railwear::test
