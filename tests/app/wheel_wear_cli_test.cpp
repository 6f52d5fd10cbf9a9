// Wheel wear and wheel populations (issue 16 point 6) through the railwear binary:
// - a co-evolution run stores the rail's and the wheel's profile at every step (wheel_steps),
//   and `history steps/profile/diff --wheel` and the summary show the wheel;
// - a run stopped with --steps and resumed is bit-identical to an uninterrupted one (the kills
//   at every fsync are in wear_interrupt_test.cpp);
// - a traffic entry drawing from the measured wheels in ../shared (skipped without them), inline
//   or from a population file: one load case per wheel, weighted by its share.
#include <cmath>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/run_fingerprint.h"
#include "tests/app/wear_scenes.h"

namespace railwear::test {
namespace {

using WheelWearCliTest = CliFixture;

// kSmallWearStudy at one node with an R8 wheel that wears over 3 m per pass (about one
// revolution): 3 steps of at most 0.05 mm, wheel and rail wearing alike.
std::string CoEvolutionStudy() {
  std::string s = kSmallWearStudy;
  const auto replace = [&s](const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
  };
  replace("wheel = { E_MPa = 210000, nu = 0.28 }", "wheel = { grade = \"R8\" }");
  replace("quadrature_points = 3", "quadrature_points = 1");
  replace("total_passes = 4e5", "total_passes = 2e4");
  return s + "name = \"freight\"\nwheel_wear = { distance_per_pass_m = 3.0 }\n";
}

TEST_F(WheelWearCliTest, CoEvolutionRunStoresBothProfilesPerStep) {
  Write("study.toml", CoEvolutionStudy());
  const Outcome run = Run("wear study.toml --db w.sqlite --threads 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(Contains(run.err, "wheel of 'freight': max depth"));
  EXPECT_TRUE(Contains(run.out, "wheel of 'freight' (traffic entry 0) at step"));

  const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "w.sqlite").string());
  const RunInfo info = *store.FindRun("small study");
  const int last = *store.LastStep(info.id);
  ASSERT_GE(last, 2);
  EXPECT_TRUE(Contains(info.wear_law_json, "\"wheel_wear\""));
  const auto before_sd = [&](int k) {
    return store.LoadStep(info.id, k - 1).wheels.at(0).flange_thickness_mm;
  };
  for (int k = 0; k <= last; ++k) {
    SCOPED_TRACE(k);
    const StepRecord step = store.LoadStep(info.id, k);
    ASSERT_EQ(step.wheels.size(), 1u);  // both profiles, every step
    EXPECT_EQ(step.wheels[0].name, "freight");
    EXPECT_GT(step.profile.size(), 0);
    ASSERT_TRUE(step.wheels[0].flange_thickness_mm.has_value());
    if (k == 0) {
      EXPECT_EQ(step.wheels[0].worn_area_mm2, 0.0);
      EXPECT_NEAR(*step.wheels[0].flange_thickness_mm, 32.5, 0.05);  // the new S1002's Sd
      EXPECT_NEAR(*step.wheels[0].flange_height_mm, 28.0, 0.05);
      continue;
    }
    // Stored at every step (the library test checks that flank wear thins the flange; here the
    // wheel wears on its flange root below the Sd height, which stays within 0.1 mm).
    EXPECT_NEAR(*step.wheels[0].flange_thickness_mm, *before_sd(k), 0.1);
    const StepRecord before = store.LoadStep(info.id, k - 1);
    EXPECT_NE(step.profile.points(), before.profile.points());
    EXPECT_NE(step.wheels[0].profile.points(), before.wheels[0].profile.points());
    EXPECT_GT(step.wheels[0].worn_area_mm2, before.wheels[0].worn_area_mm2);
    EXPECT_LE(step.wheels[0].max_depth_mm, 0.05 * k * 1.05);  // the step limit holds for it
    const nlohmann::json c = nlohmann::json::parse(step.load_cases_json.at(0));
    EXPECT_GT(c["wheel_worn_area_per_pass_mm2"].get<double>(), 0.0);
  }

  const Outcome steps = Run("history --db w.sqlite steps 'small study' --wheel freight");
  ASSERT_EQ(steps.exit_code, 0) << steps.err;
  EXPECT_TRUE(Contains(steps.out, "worn_area_mm2"));
  EXPECT_TRUE(Contains(steps.out, "Sd_mm"));
  EXPECT_TRUE(Contains(steps.err, "wheel of traffic entry 0 ('freight'"));
  const Outcome rail_steps = Run("history --db w.sqlite steps 'small study'");
  ASSERT_EQ(rail_steps.exit_code, 0) << rail_steps.err;
  EXPECT_TRUE(Contains(rail_steps.err, "its wheels wear too"));
  const Outcome csv = Run("history --db w.sqlite profile 'small study' --wheel 0 --step 1");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_TRUE(Contains(csv.err, "wheel of 'freight'"));
  const Outcome json =
      Run("history --db w.sqlite profile 'small study' --wheel freight --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["wheel"]["traffic"], "freight");
  EXPECT_EQ(j["points"].get<int>(),
            store.LoadWheelProfile(info.id, last, 0).size());
  const Outcome diff =
      Run("history --db w.sqlite diff 'small study' 0 " + std::to_string(last) + " --wheel 0");
  ASSERT_EQ(diff.exit_code, 0) << diff.err;
  EXPECT_TRUE(Contains(diff.out, "wheel         of 'freight'"));
  EXPECT_TRUE(Contains(diff.out, "worn area"));
  // From step 0 the diff measures as the run did (CompareWheelWithUnworn, issue 16): the same
  // worn area and max depth as the stored step, to the stored profiles' round trip (bit for bit).
  const Outcome diff_json = Run("history --db w.sqlite diff 'small study' 0 " +
                                std::to_string(last) + " --wheel 0 --json");
  ASSERT_EQ(diff_json.exit_code, 0) << diff_json.err;
  const nlohmann::json dj = nlohmann::json::parse(diff_json.out);
  const StepRecord last_step = store.LoadStep(info.id, last);
  EXPECT_NEAR(dj["max_depth_mm"].get<double>(), last_step.wheels.at(0).max_depth_mm, 1e-12);
  EXPECT_NEAR(dj["worn_area_mm2"].get<double>(), last_step.wheels.at(0).worn_area_mm2, 1e-12);

  // The plots: a fourth PNG, each wearing wheel's depth (gnuplot is optional).
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    const Outcome plot = Run("history --db w.sqlite plot 'small study' --out p");
    ASSERT_EQ(plot.exit_code, 0) << plot.err;
    for (const char* png : {"p_profiles.png", "p_depth.png", "p_measures.png", "p_wheels.png"}) {
      EXPECT_TRUE(fs::exists(dir_ / png)) << png;
    }
  }

  // Bad --wheel uses: exit 2 naming the run and what there is.
  const Outcome unknown = Run("history --db w.sqlite steps 'small study' --wheel 7");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(Contains(unknown.err, "has no wearing wheel '7'"));
  EXPECT_TRUE(Contains(unknown.err, "0 ('freight')"));
  const Outcome ban = Run("history --db w.sqlite profile 'small study' --wheel 0 --format ban");
  EXPECT_EQ(ban.exit_code, 2);
  EXPECT_TRUE(Contains(ban.err, "expected csv or json"));
  const Outcome both = Run("history --db w.sqlite diff 'small study' 0 1 --wheel 0 --rail low");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_TRUE(Contains(both.err, "expected one of the two"));
}

// A run without wearing wheels says so when asked for one.
TEST_F(WheelWearCliTest, HistoryWheelOfARunWithoutWheelsExitsTwo) {
  std::string s = kSmallWearStudy;
  s.replace(s.find("total_passes = 4e5"), 18, "total_passes = 1e4");
  Write("study.toml", s);
  ASSERT_EQ(Run("wear study.toml --db w.sqlite --threads 1").exit_code, 0);
  const Outcome o = Run("history --db w.sqlite profile 'small study' --wheel 0");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "the run's wheels do not wear"));
}

// Stopped after one step and resumed: the same database as an uninterrupted run, wheels included.
TEST_F(WheelWearCliTest, StoppedAndResumedRunIsBitIdentical) {
  Write("study.toml", CoEvolutionStudy());
  ASSERT_EQ(Run("wear study.toml --db whole.sqlite --threads 1").exit_code, 0);
  const Outcome first = Run("wear study.toml --db cut.sqlite --threads 1 --steps 1");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const Outcome rest = Run("wear study.toml --db cut.sqlite --threads 1 --resume");
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  const std::string whole = RunFingerprint(dir_ / "whole.sqlite");
  EXPECT_TRUE(Contains(whole, "wheel 0 freight"));
  EXPECT_EQ(RunFingerprint(dir_ / "cut.sqlite"), whole);
}

// A vehicle entry's wheels wear too (issue 16): kWheelsetCurveScene's wheelset with R8 wheels
// over 300 m per pass, 3 steps of at most 0.02 mm. Every step stores both rails and both wheels
// of the wheelset (wheel_steps.wheel 1 high, 2 low), `history steps --wheel` finds each by name
// or INDEX:WHEEL, and a run stopped after one step and resumed is the uninterrupted one, bit for
// bit.
TEST_F(WheelWearCliTest, VehicleWheelsCoEvolveAndResumeBitIdentically) {
  std::string s = kWheelsetCurveScene;
  s.replace(s.find("wheel = { E_MPa = 210000, nu = 0.28 }"), 37, "wheel = { grade = \"R8\" }");
  s.replace(s.find("total_passes = 1e5"), 18, "total_passes = 1e5\nmax_depth_per_step_mm = 0.02");
  s += "name = \"wheelset\"\nwheel_wear = { distance_per_pass_m = 300.0 }\n";
  Write("study.toml", s);
  const Outcome whole = Run("wear study.toml --db whole.sqlite --threads 1 --steps 3");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_TRUE(Contains(whole.err, "wheel of 'wheelset / wheelset 0 high': max depth"));
  EXPECT_TRUE(Contains(whole.out, "wheel of 'wheelset / wheelset 0 low' (traffic entry 0)"));
  const Outcome first = Run("wear study.toml --db cut.sqlite --threads 1 --steps 1");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const Outcome rest = Run("wear study.toml --db cut.sqlite --threads 1 --steps 2 --resume");
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  const std::string fingerprint = RunFingerprint(dir_ / "whole.sqlite", "wheelset on R1500");
  EXPECT_TRUE(Contains(fingerprint, "wheel 0:2 wheelset / wheelset 0 low"));
  EXPECT_EQ(RunFingerprint(dir_ / "cut.sqlite", "wheelset on R1500"), fingerprint);

  const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "whole.sqlite").string());
  const RunInfo info = *store.FindRun("wheelset on R1500");
  ASSERT_EQ(*store.LastStep(info.id), 3);
  for (int k = 0; k <= 3; ++k) {
    SCOPED_TRACE(k);
    const StepRecord step = store.LoadStep(info.id, k);
    ASSERT_TRUE(step.low_rail.has_value());
    ASSERT_EQ(step.wheels.size(), 2u);
    EXPECT_EQ(step.wheels[0].wheel, 1);
    EXPECT_EQ(step.wheels[1].wheel, 2);
    if (k == 0) continue;
    const StepRecord before = store.LoadStep(info.id, k - 1);
    EXPECT_NE(step.profile.points(), before.profile.points());
    EXPECT_NE(step.low_rail->profile.points(), before.low_rail->profile.points());
    for (int w = 0; w < 2; ++w) {
      EXPECT_NE(step.wheels[w].profile.points(), before.wheels[w].profile.points()) << w;
      EXPECT_GT(step.wheels[w].worn_area_mm2, before.wheels[w].worn_area_mm2) << w;
    }
  }
  const Outcome by_name =
      Run("history --db whole.sqlite steps 'wheelset on R1500' --wheel 'wheelset / wheelset 0 low'");
  ASSERT_EQ(by_name.exit_code, 0) << by_name.err;
  const Outcome by_index = Run("history --db whole.sqlite steps 'wheelset on R1500' --wheel 0:2");
  ASSERT_EQ(by_index.exit_code, 0) << by_index.err;
  EXPECT_EQ(by_name.out, by_index.out);
  const Outcome unknown = Run("history --db whole.sqlite steps 'wheelset on R1500' --wheel 0");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(Contains(unknown.err, "0:1 ('wheelset / wheelset 0 high')"));
}

// The measured wheels next to the checkout (../shared/data/profiles, never copied into the
// repository); empty when they are absent.
std::string SharedProfiles() {
  const fs::path dir = fs::path(RAILWEAR_SHARED_DIR) / "data" / "profiles";
  return fs::exists(dir / "avg_wheel.whl") && fs::exists(dir / "Car7216_0001r.whl")
             ? fs::canonical(dir).string()
             : std::string();
}

// A population of a new S1002 and the two measured worn wheels, weights 2 : 1 : 1, inline and
// as a population file: one load case per wheel with its share of the entry's passes, and the
// two forms give the same run.
TEST_F(WheelWearCliTest, EntryDrawsFromAMeasuredWheelPopulation) {
  const std::string shared = SharedProfiles();
  if (shared.empty()) {
    GTEST_SKIP() << "../shared/data/profiles (avg_wheel.whl, Car7216_0001r.whl) is absent next "
                    "to the checkout: the measured-wheel population test needs them";
  }
  std::string base = kSmallWearStudy;
  base.replace(base.find("quadrature_points = 3"), 21, "quadrature_points = 1");
  base.replace(base.find("total_passes = 4e5"), 18, "total_passes = 1e4");
  // At the study's 4 mrad of yaw: the yawed outline of avg_wheel.whl used to fold near its
  // flange tip (slope noise; core/geometry/yawed_wheel.h now drops the hidden samples).
  base += "name = \"fleet\"\n";
  const std::string wheels =
      "{ name = \"new\", profile = \"builtin:S1002\", weight = 2 },\n"
      "  { name = \"avg\", profile = \"" + shared + "/avg_wheel.whl\", weight = 1 },\n"
      "  { name = \"car7216\", profile = \"" + shared + "/Car7216_0001r.whl\", weight = 1 }";
  Write("inline.toml", base + "wheel_population = [\n  " + wheels + "\n]\n");
  Write("file.toml", base + "wheel_population = \"fleet.toml\"\n");
  Write("fleet.toml",
        "[[wheel]]\nname = \"new\"\nprofile = \"builtin:S1002\"\nweight = 2\n"
        "[[wheel]]\nname = \"avg\"\nprofile = \"" + shared + "/avg_wheel.whl\"\nweight = 1\n"
        "[[wheel]]\nname = \"car7216\"\nprofile = \"" + shared + "/Car7216_0001r.whl\"\n"
        "weight = 1\n");
  const Outcome a = Run("wear inline.toml --db a.sqlite --threads 1 --steps 1");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const Outcome b = Run("wear file.toml --db b.sqlite --threads 1 --steps 1");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "a.sqlite").string());
  const RunInfo info = *store.FindRun("small study");
  const StepRecord step = store.LoadStep(info.id, 1);
  ASSERT_EQ(step.load_cases_json.size(), 3u);  // one per wheel
  const std::vector<std::pair<std::string, double>> expected = {
      {"fleet / new", 0.5}, {"fleet / avg", 0.25}, {"fleet / car7216", 0.25}};
  double area = 0.0;
  for (size_t k = 0; k < 3; ++k) {
    const nlohmann::json c = nlohmann::json::parse(step.load_cases_json[k]);
    EXPECT_EQ(c["traffic"], expected[k].first);
    EXPECT_DOUBLE_EQ(c["weight"].get<double>(), expected[k].second);
    area += c["weight"].get<double>() * c["worn_area_per_pass_mm2"].get<double>();
  }
  EXPECT_GT(area, 0.0);
  // The population file gives the same run (its scene text differs, its results not).
  const ProfileStore other = ProfileStore::OpenReadOnly((dir_ / "b.sqlite").string());
  const StepRecord same = other.LoadStep(other.FindRun("small study")->id, 1);
  EXPECT_EQ(same.profile.points(), step.profile.points());
  EXPECT_EQ(same.load_cases_json, step.load_cases_json);
  std::cerr << "[figure] population step 1: worn area per pass " << area << " mm2 (weighted)\n";
}

}  // namespace
}  // namespace railwear::test
