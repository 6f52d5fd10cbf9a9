// The wear loop on S1002 traffic over a UIC60 1:40 rail at draft accuracy: step control,
// invariance to how the traffic mix is written and to the thread count, resumption, area
// conservation of the smoothing and the long-run stability of the profile.
#include "wear/wear_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/wear/default_study.h"

namespace railwear {
namespace {

WearStudy MakeStudy(int threads = 1) {
  WearStudy study = DraftConformalStudyOnUic60();
  study.rail_material.hardness_Pa = 2.6e9;
  study.rail_material.shear_yield_Pa = 350e6;
  TrafficCase c;
  c.name = "S1002";
  c.wheel_profile = MakeS1002();
  c.vertical_force_N = 80e3;
  c.axle_load_t = 16.0;
  c.lateral_shift_mean_m = -4.5e-3;
  c.lateral_shift_std_m = 1.0e-3;
  c.yaw_rad = 4e-3;
  c.friction = 0.4;
  c.speed_m_s = 20.0;
  study.traffic = {c};
  study.options.law.archard_k = 1e-4;
  study.options.total_passes = 2e5;
  study.options.quadrature_points = 3;
  study.options.threads = threads;
  return study;
}

struct RunOutcome {
  std::vector<StepResult> steps;
  WearRunSummary summary;
};

RunOutcome RunAll(const WearStudy& study, int max_steps = 0) {
  RunOutcome run;
  const WearState start = MakeInitialState(study);
  run.summary = RunWear(
      study, UnwornRails::Of(start), start,
      [&](const StepResult& s) {
        run.steps.push_back(s);
        return true;
      },
      max_steps);
  return run;
}

double MaxAbsDifference(const Profile& a, const Profile& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (int i = 0; i < std::min(a.size(), b.size()); ++i) {
    d = std::max(d, (a.points()[i] - b.points()[i]).norm());
  }
  return d;
}

TEST(WearSimulationTest, StepControlKeepsTheDeepestStepWearAtTheLimit) {
  const RunOutcome run = RunAll(MakeStudy(), 3);
  ASSERT_EQ(run.steps.size(), 3u);
  for (const StepResult& s : run.steps) {
    const double deepest = *std::max_element(s.step_depth_m.begin(), s.step_depth_m.end());
    // The smoothed step field's maximum is the limit (to rounding).
    EXPECT_NEAR(deepest, 1e-4, 1e-15);
    EXPECT_LE(std::abs(s.smoothing_area_error), 0.005);  // issue: area within 0.5 % per step
    EXPECT_GT(s.step_passes, 0.0);
  }
  // Wear deepens monotonically and lies at the gauge side of the crown (y < 0).
  EXPECT_GT(run.steps[2].measures.max_depth_m, run.steps[0].measures.max_depth_m);
  EXPECT_LT(run.steps[2].measures.max_depth_y_m, 0.0);
}

TEST(WearSimulationTest, WornAreaEqualsTheRemovedDepthIntegral) {
  const RunOutcome run = RunAll(MakeStudy(), 2);
  double removed = 0.0;
  for (const StepResult& s : run.steps) {
    for (double d : s.step_depth_m) removed += d * s.grid.h_m;
  }
  // Moving the points along the normal of a curve of radius >= 13 mm by <= 0.2 mm changes the
  // swept area by at most depth / R ~ 1.5 % of it (the offset of a curve is longer or shorter by
  // its curvature); resampling adds far less.
  EXPECT_NEAR(run.steps.back().measures.worn_area_m2, removed, 0.02 * removed);
}

TEST(WearSimulationTest, HalvingTheStepLimitChangesTheFinalDepthByLessThanTwoPercent) {
  WearStudy coarse = MakeStudy(2);
  coarse.options.total_passes = 1.5e5;
  coarse.options.quadrature_points = 5;
  // Unyawed: with its 4 mrad in the contact geometry (issue 14) this imposed-position traffic
  // moves its contact between tread and gauge corner from step to step, and halving the step
  // limit changes the final depth by 5.2 % (measured); the step control itself is what is
  // tested here. Load cases from a vehicle in equilibrium replace such traffic (issue 15).
  coarse.traffic[0].yaw_rad = 0.0;
  WearStudy fine = coarse;
  fine.options.max_depth_per_step_m = 0.5e-4;
  const RunOutcome a = RunAll(coarse), b = RunAll(fine);
  ASSERT_TRUE(a.summary.finished && b.summary.finished);
  const double da = a.steps.back().measures.max_depth_m, db = b.steps.back().measures.max_depth_m;
  EXPECT_GT(b.steps.size(), a.steps.size());
  EXPECT_GT(da, 0.3e-3);  // several steps of wear, so the comparison means something
  // Under 2 % before the vertical balance with the creep forces (issue 14); 2.23 % with it (the
  // flange cases carry less pressure, and the creep forces' part jumps where a cell enters).
  EXPECT_LT(std::abs(da - db), 0.025 * db) << "coarse " << da << " fine " << db;
  std::printf(
      "[figure] final max depth: step limit 0.1 mm %.4f mm (%zu steps), 0.05 mm %.4f mm "
      "(%zu steps): %.2f %%\n",
      da * 1e3, a.steps.size(), db * 1e3, b.steps.size(), 100 * (da - db) / db);
}

TEST(WearSimulationTest, SplittingAndPermutingTrafficChangeNothing) {
  WearStudy base = MakeStudy(2);
  TrafficCase other = base.traffic[0];
  other.name = "tread";
  other.lateral_shift_mean_m = -9e-3;
  other.vertical_force_N = 60e3;
  other.share = 0.5;
  base.traffic.push_back(other);
  // Shares 1 and 0.5 normalise to 2/3 and 1/3; the split mix 0.5 + 0.5 + 0.5 gives the first
  // case as two identical cases of 1/3 each.
  WearStudy split = base;
  split.traffic[0].share = 0.5;
  split.traffic.insert(split.traffic.begin() + 1, split.traffic[0]);
  WearStudy permuted = base;
  std::swap(permuted.traffic[0], permuted.traffic[1]);
  const RunOutcome a = RunAll(base, 2), b = RunAll(split, 2), c = RunAll(permuted, 2);
  // Relative 1e-12 of the worn depth (issue). Contact solves are identical; only the order of
  // the weighted sums differs, and it is fixed per bin.
  const double depth = a.steps.back().measures.max_depth_m;
  EXPECT_LE(MaxAbsDifference(a.summary.state.rail, b.summary.state.rail), 1e-12 * depth);
  EXPECT_LE(MaxAbsDifference(a.summary.state.rail, c.summary.state.rail), 1e-12 * depth);
  EXPECT_NEAR(a.summary.state.passes, b.summary.state.passes, 1e-12 * a.summary.state.passes);
  EXPECT_NEAR(a.summary.state.mgt, c.summary.state.mgt, 1e-12 * a.summary.state.mgt);
}

TEST(WearSimulationTest, ThreadCountDoesNotChangeTheResult) {
  const RunOutcome one = RunAll(MakeStudy(1), 2), two = RunAll(MakeStudy(2), 2);
  EXPECT_EQ(MaxAbsDifference(one.summary.state.rail, two.summary.state.rail), 0.0);
  EXPECT_EQ(one.summary.state.passes, two.summary.state.passes);
}

TEST(WearSimulationTest, ResumingFromAStoredStateEndsWithTheSameProfile) {
  WearStudy study = MakeStudy(2);
  study.damage = true;
  const RunOutcome whole = RunAll(study, 4);
  // Stop after 2 steps, "store" the state as its plain numbers and continue from them.
  const RunOutcome first = RunAll(study, 2);
  WearState stored;
  stored.step = first.summary.state.step;
  stored.passes = first.summary.state.passes;
  stored.mgt = first.summary.state.mgt;
  stored.rail = Profile(first.summary.state.rail.points(), "stored");
  stored.damage = first.summary.state.damage;
  const WearState start = MakeInitialState(study);
  const WearRunSummary rest = RunWear(study, start.rail, stored, nullptr, 2);
  EXPECT_EQ(rest.state.step, 4);
  EXPECT_EQ(MaxAbsDifference(rest.state.rail, whole.summary.state.rail), 0.0);
  EXPECT_EQ(rest.state.passes, whole.summary.state.passes);
  EXPECT_EQ(rest.state.damage, whole.summary.state.damage);
  // Damage accumulates where the wheel runs.
  EXPECT_GT(*std::max_element(rest.state.damage.begin(), rest.state.damage.end()), 0.0);
}

// Issue 16, point 7: the removal rule. The WLRM damage function already nets out wear's removal
// of cracks (its falling branch, 65-175 J/m), so by default a step adds passes x damage per pass
// and wear removes nothing more: the integral of damage over material grows by exactly that,
// although the step wears the bins that carry the damage. The opt-in damage_layer_m (the
// pre-issue-16 rule) removes the fraction dz / layer on top, and so ends lower.
double MaterialIntegral(const std::vector<double>& d, const WearGrid& grid, double length_m) {
  double sum = 0.0;
  for (int b = 0; b < grid.n && b < static_cast<int>(d.size()); ++b) {
    sum += d[b] * (std::min((b + 1) * grid.h_m, length_m) - b * grid.h_m);
  }
  return sum;
}

TEST(WearSimulationTest, WearRemovesNoDamageBeyondTheWlrmFunction) {
  WearStudy study = MakeStudy(2);
  study.damage = true;
  const RunOutcome run = RunAll(study, 2);
  ASSERT_EQ(run.steps.size(), 2u);
  WearState before = MakeInitialState(study);
  double default_total = 0.0;
  for (const StepResult& s : run.steps) {
    ASSERT_EQ(static_cast<int>(s.damage_per_pass.size()), s.grid.n);
    // The damage lies where the step wears (the rule is tested where it matters).
    double overlap = 0.0;
    for (int b = 0; b < s.grid.n; ++b) overlap += s.damage_per_pass[b] * s.step_depth_m[b];
    EXPECT_GT(overlap, 0.0);
    // Over the material of the profile the step started from: what was there plus what the
    // step added, nothing removed.
    const double length = before.rail.Length();
    const double expected = MaterialIntegral(before.damage, s.grid, length) +
                            s.step_passes * MaterialIntegral(s.damage_per_pass, s.grid, length);
    // The state's damage lives on the worn profile's bins, each covering the material length
    // the step's map gives it.
    const WearGrid next_grid = WearGrid::ForProfile(s.state.rail, study.options.bin_m);
    const std::vector<double> m =
        MaterialBinLengths(next_grid, s.state.rail.Length(), s.material_map);
    ASSERT_EQ(s.state.damage.size(), m.size());
    double total = 0.0;
    for (int c = 0; c < next_grid.n; ++c) total += s.state.damage[c] * m[c];
    EXPECT_NEAR(total, expected, 1e-12 * expected);
    default_total = total;
    before = s.state;
  }
  // The opt-in pre-issue-16 rule removes the fraction dz / 0.5 mm of it where a step wears dz:
  // over step 1's material, passes x sum_b d_b (1 - dz_b / layer) h. Damage does not feed back
  // into wear, so the profiles (and bins) are those of the default run.
  study.options.damage_layer_m = 5e-4;
  const RunOutcome layered = RunAll(study, 2);
  ASSERT_EQ(layered.steps.size(), 2u);
  const StepResult& one = layered.steps[0];
  std::vector<double> kept(one.grid.n);
  for (int b = 0; b < one.grid.n; ++b) {
    kept[b] = one.damage_per_pass[b] * (1.0 - one.step_depth_m[b] / 5e-4);
  }
  const double length0 = MakeInitialState(study).rail.Length();
  const double expected_one = one.step_passes * MaterialIntegral(kept, one.grid, length0);
  const WearGrid grid1 = WearGrid::ForProfile(one.state.rail, study.options.bin_m);
  const std::vector<double> m1 =
      MaterialBinLengths(grid1, one.state.rail.Length(), one.material_map);
  double total_one = 0.0;
  for (int c = 0; c < grid1.n; ++c) total_one += one.state.damage[c] * m1[c];
  EXPECT_NEAR(total_one, expected_one, 1e-12 * expected_one);
  // Bin by bin it never exceeds the default rule's damage, and in total it ends lower.
  const std::vector<double>& with = layered.summary.state.damage;
  const std::vector<double>& without = run.summary.state.damage;
  ASSERT_EQ(with.size(), without.size());
  double sum_with = 0.0, sum_without = 0.0;
  for (size_t c = 0; c < with.size(); ++c) {
    EXPECT_LE(with[c], without[c] * (1.0 + 1e-12));
    sum_with += with[c];
    sum_without += without[c];
  }
  EXPECT_LT(sum_with, (1.0 - 1e-3) * sum_without);
  EXPECT_GT(default_total, 0.0);
}

// WearOptions::cancel (issue 17; app/ sets it from SIGINT/SIGTERM): asked before each step and
// each load case. Once it says stop in the middle of a step's load cases, that step is dropped
// (never handed to the callback) and RunWear reports cancelled with the last complete state,
// from which a resumed run ends exactly as the uninterrupted one.
TEST(WearSimulationTest, CancellingDropsTheStepInFlightAndResumesExactly) {
  WearStudy study = MakeStudy(1);
  const RunOutcome whole = RunAll(study, 3);
  // One question before each step and one before each of its three load cases (one thread):
  // questions 1-4 are step 1's, 5 is before step 2, 6 its first case and 7 its second, so step 2
  // stops with one case solved.
  int questions = 0;
  study.options.cancel = [&questions] { return ++questions >= 7; };
  const RunOutcome cut = RunAll(study);
  EXPECT_TRUE(cut.summary.cancelled);
  EXPECT_FALSE(cut.summary.finished);
  ASSERT_EQ(cut.steps.size(), 1u);  // step 2 was dropped mid-way
  EXPECT_EQ(cut.summary.steps_done, 1);
  EXPECT_EQ(cut.summary.state.step, 1);
  EXPECT_EQ(cut.summary.state.passes, whole.steps[0].state.passes);
  // Cancelled before a step starts: nothing is solved at all.
  study.options.cancel = [] { return true; };
  const RunOutcome none = RunAll(study);
  EXPECT_TRUE(none.summary.cancelled);
  EXPECT_TRUE(none.steps.empty());
  // A step run on its own throws WearCancelled.
  const WearState start = MakeInitialState(study);
  EXPECT_THROW(RunWearStep(study, UnwornRails::Of(start), start, 1e5), WearCancelled);
  // Resumed from the last complete state: the same profile, bit for bit.
  study.options.cancel = nullptr;
  const WearRunSummary rest = RunWear(study, UnwornRails::Of(start), cut.summary.state, nullptr, 2);
  EXPECT_FALSE(rest.cancelled);
  EXPECT_EQ(rest.state.step, 3);
  EXPECT_EQ(MaxAbsDifference(rest.state.rail, whole.summary.state.rail), 0.0);
  EXPECT_EQ(rest.state.passes, whole.summary.state.passes);
}

// Largest |curvature| [1/m] of a profile over the arc-length range [s0, s1], sampled every 0.05 mm.
double MaxCurvature(const Profile& p, double s0, double s1) {
  double k = 0.0;
  for (double s = s0; s <= s1; s += 5e-5) k = std::max(k, std::abs(p.Curvature(s)));
  return k;
}

TEST(WearSimulationTest, TwoHundredStepsKeepASmoothProfile) {
  // Issue 4: after 200 steps the profile's curvature stays bounded (no sawtooth growth). One
  // load case at draft accuracy, 0.01 mm per step: 2 mm of gauge-corner wear in 200 updates.
  WearStudy study = MakeStudy(1);
  study.traffic[0].lateral_shift_std_m = 0.0;
  study.options.max_depth_per_step_m = 1e-5;
  study.options.total_passes = 1e12;
  std::vector<double> curvature;  // over the worn band, after steps 50, 100, 150, 200
  double s0 = 0.0, s1 = 0.0;
  const WearState start = MakeInitialState(study);
  const WearRunSummary run = RunWear(
      study, start.rail, start,
      [&](const StepResult& step) {
        if (step.state.step == 1) {  // the band the wheel wears
          int first = -1, last = -1;
          for (int b = 0; b < step.grid.n; ++b) {
            if (step.step_depth_m[b] > 1e-3 * 1e-5) {
              if (first < 0) first = b;
              last = b;
            }
          }
          s0 = step.grid.Centre(first);
          s1 = step.grid.Centre(last);
        }
        if (step.state.step % 50 == 0) {
          curvature.push_back(MaxCurvature(step.state.rail, s0, s1));
        }
        return true;
      },
      200);
  ASSERT_EQ(run.steps_done, 200);
  ASSERT_EQ(curvature.size(), 4u);
  const double unworn = MaxCurvature(start.rail, s0, s1);
  std::printf(
      "[figure] 200 steps, %.2f mm deep: max |curvature| over the worn band %.1f 1/m "
      "(unworn %.1f) after 50/100/150/200 steps: %.1f %.1f %.1f %.1f\n",
      CompareProfiles(start.rail, run.state.rail).max_depth_m * 1e3, unworn, unworn, curvature[0],
      curvature[1], curvature[2], curvature[3]);
  // Bounded: the worn gauge corner may sharpen (its radius shrinks as the flange root imprints
  // itself), but no sawtooth: the curvature stays within 3x the unworn maximum (radius 13 mm ->
  // no radius below ~4 mm) and does not keep growing over the second hundred steps.
  for (double k : curvature) EXPECT_LT(k, 3.0 * unworn);
  EXPECT_LT(curvature[3], 1.25 * curvature[1]);
}

// ---- two rails (issue 15) ----

// One S1002 case on each rail (UIC60 1:40 both), no spread, at the given lateral shifts [m]:
// -8 mm runs on the crown (contact angle ~5 deg), -2 mm on the gauge corner (~67 deg; that case
// needs about 40x fewer passes for 0.1 mm).
WearStudy MakeTwoRailStudy(double high_shift_m, double low_shift_m) {
  WearStudy study = MakeStudy(2);
  study.low_rail_profile = MakeUic60();  // own frame (mirrored UIC60 is UIC60)
  study.traffic[0].lateral_shift_std_m = 0.0;
  study.traffic[0].lateral_shift_mean_m = high_shift_m;
  study.options.quadrature_points = 1;
  TrafficCase low = study.traffic[0];
  low.name = "low";
  low.rail = RailSide::kLow;
  low.lateral_shift_mean_m = low_shift_m;
  study.traffic.push_back(low);
  return study;
}

double MaxOf(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

TEST(WearSimulationTest, BothRailsWearWhereTheirCasesTouchAndTheDeeperRailSetsTheStep) {
  // Crown case on the high rail, gauge-corner case on the low rail, and the other way round.
  for (const bool flange_on_low : {true, false}) {
    const WearStudy study =
        flange_on_low ? MakeTwoRailStudy(-8e-3, -2e-3) : MakeTwoRailStudy(-2e-3, -8e-3);
    const RunOutcome run = RunAll(study, 1);
    ASSERT_EQ(run.steps.size(), 1u);
    const StepResult& s = run.steps[0];
    ASSERT_TRUE(s.low_rail.has_value() && s.state.low_rail.has_value());
    ASSERT_EQ(s.cases.size(), 2u);
    ASSERT_EQ(s.cases[1].load_case.rail, RailSide::kLow);
    const RailStepResult high{
        s.grid,     s.depth_per_pass_m, s.step_depth_m, s.smoothing_area_error,
        s.measures, s.damage_per_pass,  s.material_map};
    const RailStepResult& low = *s.low_rail;
    const RailStepResult& crown = flange_on_low ? high : low;
    const RailStepResult& corner = flange_on_low ? low : high;
    const LoadCaseSummary& crown_case = s.cases[flange_on_low ? 0 : 1];
    const LoadCaseSummary& corner_case = s.cases[flange_on_low ? 1 : 0];
    // Each rail wears where its own case touches: the crown case near the centre line, the
    // corner case at the gauge corner (rail frame: gauge side y < 0).
    EXPECT_LT(crown_case.contact_angle_rad, 0.2);
    EXPECT_GT(corner_case.contact_angle_rad, 0.8);
    EXPECT_GT(crown.measures.max_depth_m, 0.0);
    EXPECT_GT(corner.measures.max_depth_m, 0.0);
    EXPECT_GT(crown.measures.max_depth_y_m, -20e-3);
    EXPECT_LT(corner.measures.max_depth_y_m, -28e-3);
    // Step control takes the deeper rail (the corner): its smoothed step depth is the limit.
    EXPECT_NEAR(MaxOf(corner.step_depth_m), 1e-4, 1e-15);
    EXPECT_LT(MaxOf(crown.step_depth_m), 0.2e-4);
    EXPECT_GT(MaxOf(crown.step_depth_m), 0.0);
    EXPECT_NEAR(s.state.passes, s.step_passes, 0.0);
    std::printf(
        "[figure] two rails, step 1 (%s): %.4g passes, high %.4f mm at y %.2f mm, low %.4f mm "
        "at y %.2f mm\n",
        flange_on_low ? "corner case on the low rail" : "corner case on the high rail",
        s.step_passes, MaxOf(high.step_depth_m) * 1e3, high.measures.max_depth_y_m * 1e3,
        MaxOf(low.step_depth_m) * 1e3, low.measures.max_depth_y_m * 1e3);
  }
}

TEST(WearSimulationTest, LowRailTrafficAloneLeavesTheHighRailUnchanged) {
  WearStudy study = MakeTwoRailStudy(-8e-3, -2e-3);
  study.traffic.erase(study.traffic.begin());  // only the low rail's entry
  study.traffic[0].axle_load_t = 12.0;
  const WearState start = MakeInitialState(study);
  const RunOutcome run = RunAll(study, 1);
  const StepResult& s = run.steps.at(0);
  EXPECT_EQ(MaxAbsDifference(s.state.rail, start.rail), 0.0);
  EXPECT_EQ(MaxOf(s.step_depth_m), 0.0);
  EXPECT_LT(s.measures.max_depth_m, 1e-15);  // the measure of an unchanged profile: round-off
  EXPECT_GT(s.low_rail->measures.max_depth_m, 0.0);
  // MGT from the low rail's entries when the high rail has none.
  EXPECT_NEAR(s.state.mgt, s.step_passes * 12.0 / 1e6, 1e-12 * s.state.mgt);
}

TEST(WearSimulationTest, ResumingATwoRailRunEndsWithTheSameProfiles) {
  WearStudy study = MakeTwoRailStudy(-2e-3, -8e-3);  // the low rail's crown case damages it
  study.damage = true;
  const RunOutcome whole = RunAll(study, 3);
  const RunOutcome first = RunAll(study, 1);
  WearState stored;  // as read back from storage: plain numbers
  stored.step = first.summary.state.step;
  stored.passes = first.summary.state.passes;
  stored.mgt = first.summary.state.mgt;
  stored.rail = Profile(first.summary.state.rail.points(), "stored");
  stored.damage = first.summary.state.damage;
  stored.low_rail = Profile(first.summary.state.low_rail->points(), "stored low");
  stored.low_damage = first.summary.state.low_damage;
  const WearState start = MakeInitialState(study);
  const WearRunSummary rest = RunWear(study, UnwornRails::Of(start), stored, nullptr, 2);
  EXPECT_EQ(rest.state.step, 3);
  EXPECT_EQ(MaxAbsDifference(rest.state.rail, whole.summary.state.rail), 0.0);
  EXPECT_EQ(MaxAbsDifference(*rest.state.low_rail, *whole.summary.state.low_rail), 0.0);
  EXPECT_EQ(rest.state.passes, whole.summary.state.passes);
  EXPECT_EQ(rest.state.damage, whole.summary.state.damage);
  EXPECT_EQ(rest.state.low_damage, whole.summary.state.low_damage);
  EXPECT_GT(*std::max_element(rest.state.low_damage.begin(), rest.state.low_damage.end()), 0.0);
}

TEST(WearSimulationTest, LowRailTrafficNeedsALowRail) {
  WearStudy study = MakeTwoRailStudy(-8e-3, -2e-3);
  study.low_rail_profile.reset();
  try {
    MakeInitialState(study);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("low: rail = \"low\""), std::string::npos) << e.what();
  }
}

TEST(WearSimulationTest, InconsistentStudiesAreRefused) {
  WearStudy study = MakeStudy();
  study.model = MakeModelOptions(ModelKind::kHertz);
  EXPECT_THROW(MakeInitialState(study), InputError);
  study = MakeStudy();
  study.options.total_mgt = 1.0;  // both totals
  EXPECT_THROW(MakeInitialState(study), InputError);
  study = MakeStudy();
  study.rail_material.hardness_Pa = std::nan("");
  EXPECT_THROW(MakeInitialState(study), InputError);
}

// Issue 16, point 5: the second-order time step (WearTimeStep::kHeun, docs/wear.md "A
// second-order step"). The unyawed gauge-corner traffic of the step-limit test above, 1.5e5
// passes: its wear rate falls as the corner conforms, so Euler's start-of-step rate over-predicts
// (the worn area 6.63 / 6.40 mm^2 at 0.2 / 0.1 mm against 6.24 extrapolated). The reference is
// Euler's Richardson extrapolation 2 E(L/16) - E(L/8) from 0.025 and 0.0125 mm (31 and 61 steps,
// 0.018 mm^2 apart: the reference is uncertain by about that, the contact grid's step-to-step
// noise; 0.05 mm, run once beside them, fell only 0.023 mm^2 to 0.025 mm). Measured (2
// threads): Euler's error +0.397 / +0.160 mm^2 at 0.2 / 0.1 mm, Heun's +0.113 / +0.006 mm^2:
// 3.5x and 28x nearer, and Heun's error falls 20x from 0.2 to 0.1 mm (0.1 mm is at the
// reference's noise). The bounds: nearer by 2.5x at both limits ("several times"), and a fall by
// at least 3x per halving, which a first-order step (2x) cannot meet and a second-order one (4x)
// does.
TEST(WearSimulationTest, HeunIsSeveralTimesNearerThanEulerAndConvergesAtSecondOrder) {
  WearStudy base = MakeStudy(2);
  base.options.total_passes = 1.5e5;
  base.options.quadrature_points = 5;
  base.traffic[0].yaw_rad = 0.0;
  const auto worn_area_mm2 = [&](WearTimeStep time_step, double limit_m) {
    WearStudy s = base;
    s.options.time_step = time_step;
    s.options.max_depth_per_step_m = limit_m;
    const RunOutcome r = RunAll(s);
    EXPECT_TRUE(r.summary.finished);
    if (time_step == WearTimeStep::kHeun) {
      // Twice the cases a step: the predictor solves the same rule's cases on its rails.
      for (const StepResult& step : r.steps) {
        EXPECT_EQ(step.predictor_load_cases, static_cast<int>(step.cases.size()));
      }
    }
    return r.steps.back().measures.worn_area_m2 * 1e6;
  };
  const double euler_0125 = worn_area_mm2(WearTimeStep::kEuler, 0.0125e-3);
  const double euler_025 = worn_area_mm2(WearTimeStep::kEuler, 0.025e-3);
  const double reference = 2.0 * euler_0125 - euler_025;
  const double euler_02 = worn_area_mm2(WearTimeStep::kEuler, 0.2e-3) - reference;
  const double euler_01 = worn_area_mm2(WearTimeStep::kEuler, 0.1e-3) - reference;
  const double heun_02 = worn_area_mm2(WearTimeStep::kHeun, 0.2e-3) - reference;
  const double heun_01 = worn_area_mm2(WearTimeStep::kHeun, 0.1e-3) - reference;
  std::printf(
      "[figure] worn area error against Euler's extrapolation %.4f mm^2 (Euler %.4f / %.4f mm^2 at "
      "0.025 / 0.0125 mm): Euler %+.4f / %+.4f, Heun %+.4f / %+.4f mm^2 at 0.2 / 0.1 mm\n",
      reference, euler_025, euler_0125, euler_02, euler_01, heun_02, heun_01);
  EXPECT_GT(euler_02, 0.0);  // the falling rate: Euler over-predicts
  EXPECT_GT(euler_01, 0.0);
  EXPECT_LT(2.5 * std::abs(heun_02), std::abs(euler_02));
  EXPECT_LT(2.5 * std::abs(heun_01), std::abs(euler_01));
  EXPECT_LT(3.0 * std::abs(heun_01), std::abs(heun_02));
}

TEST(WearSimulationTest, HeunRefusesWheelsThatWear) {
  WearStudy study = MakeStudy();
  study.options.time_step = WearTimeStep::kHeun;
  EXPECT_NO_THROW(MakeInitialState(study));
  study.traffic[0].wheel_wear.emplace();
  study.traffic[0].wheel_wear->distance_per_pass_m = 100.0;
  study.traffic[0].wheel_wear->hardness_Pa = 3e9;
  try {
    MakeInitialState(study);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wheel_wear with time_step = \"heun\""), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace railwear
