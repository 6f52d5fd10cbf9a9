// Vehicle traffic in a wear step: a single S1002 wheelset on UIC60 1:40 rails in a curve gives
// both rails their load cases from its curving equilibrium, and both rails wear.
#include "wear/vehicle_traffic.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"
#include "tests/wear/default_study.h"

namespace railwear {
namespace {

WearStudy VehicleStudy(double spread_m) {
  WearStudy study = VehicleCurveStudy(1500.0, VehicleKind::kWheelset, 0.3, 25.0);
  study.traffic[0].name = "one wheelset";
  study.traffic[0].lateral_shift_std_m = spread_m;
  study.options.quadrature_points = 3;
  return study;
}

TEST(VehicleTrafficTest, BothWheelsOfTheEquilibriumAreCases) {
  const WearStudy study = VehicleStudy(0.0);
  ValidateWearStudy(study);
  const WearState s0 = MakeInitialState(study);
  const std::vector<LoadCase> cases =
      VehicleLoadCases(study, 0, RailInTrack(study, s0.rail, s0.rail),
                       RailInTrack(study, *s0.low_rail, *s0.low_rail));
  ASSERT_EQ(cases.size(), 2u);
  const LoadCase& high = cases[0];
  const LoadCase& low = cases[1];
  EXPECT_EQ(high.rail, RailSide::kHigh);
  EXPECT_EQ(low.rail, RailSide::kLow);
  EXPECT_DOUBLE_EQ(high.weight, 1.0);
  EXPECT_DOUBLE_EQ(low.weight, 1.0);
  // A 25 m/s run on R 1500 m without cant is deficient: the load moves to the high wheel.
  EXPECT_GT(high.vertical_force_N, low.vertical_force_N);
  EXPECT_NEAR(high.vertical_force_N + low.vertical_force_N, study.vehicles[0].axle_load_N,
              1e-6 * study.vehicles[0].axle_load_N);
  // One axle: one pitch velocity; the outer wheel runs the longer way.
  ASSERT_TRUE(high.motion.pitch_velocity_rad_s && low.motion.pitch_velocity_rad_s);
  EXPECT_EQ(*high.motion.pitch_velocity_rad_s, *low.motion.pitch_velocity_rad_s);
  EXPECT_GT(high.motion.speed_m_s, low.motion.speed_m_s);
  EXPECT_NEAR(high.motion.yaw_velocity_rad_s, -25.0 / 1500.0, 1e-12);
  // Mirrored yaw in the low rail's frame.
  EXPECT_DOUBLE_EQ(high.placement.yaw_rad, -low.placement.yaw_rad);
}

TEST(VehicleTrafficTest, SpreadNodesAndBothRailsWear) {
  const WearStudy study = VehicleStudy(1.0e-3);
  const WearState s0 = MakeInitialState(study);
  const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  ASSERT_EQ(step.cases.size(), 6u);  // 3 nodes x 2 rails
  double high_weight = 0.0, low_weight = 0.0;
  for (const LoadCaseSummary& c : step.cases) {
    (c.load_case.rail == RailSide::kHigh ? high_weight : low_weight) += c.load_case.weight;
  }
  EXPECT_NEAR(high_weight, 1.0, 1e-12);
  EXPECT_NEAR(low_weight, 1.0, 1e-12);
  ASSERT_TRUE(step.low_rail);
  EXPECT_GT(step.measures.worn_area_m2, 0.0);
  EXPECT_GT(step.low_rail->measures.worn_area_m2, 0.0);
  EXPECT_GT(step.step_passes, 0.0);
}

// A spread wider than the flangeway (nodes at +-10.4 mm around a wheelset near the centre) never
// pushes a wheel onto its flange: the nodes stop at the flange's onset, where the rigid contact
// reaches 45 degrees, so no case is an imposed wheel climb.
TEST(VehicleTrafficTest, SpreadNodesStopAtTheFlangesOnset) {
  const WearStudy study = VehicleStudy(6.0e-3);
  const WearState s0 = MakeInitialState(study);
  const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  ASSERT_EQ(step.cases.size(), 6u);
  const double onset_rad = kFlangeContactAngle_rad;
  for (const LoadCaseSummary& c : step.cases) {
    std::printf("[ measured ] node %d %s rail: shift %.2f mm, contact angle %.1f deg, L/V %.3f\n",
                c.load_case.node, ToString(c.load_case.rail).data(),
                c.load_case.placement.lateral_shift_m * 1e3, c.contact_angle_rad * 180 / M_PI,
                c.climb.l_over_v);
    // The loaded patch sits at the rigid contact's 45 degrees to within the patch's spread.
    EXPECT_LT(c.contact_angle_rad, onset_rad + 0.1) << "node " << c.load_case.node;
    EXPECT_FALSE(c.climb.exceeded) << "node " << c.load_case.node;
  }
  // The outer nodes were clipped: they lie closer together than the +-10.4 mm imposed.
  const double spread_high = step.cases[4].load_case.placement.lateral_shift_m -
                             step.cases[0].load_case.placement.lateral_shift_m;
  EXPECT_LT(std::abs(spread_high), 2.0 * std::sqrt(3.0) * 6.0e-3 - 1e-3);
}

// The flange onset is found once per wheelset and side (FlangeOnsetOffset), not per node: with
// 5 Gauss-Hermite nodes over an 8 mm spread (+-10.8 and +-22.9 mm, both beyond the onset on each
// side), the two outer nodes of a side are the same wheelset position, so their cases and their
// solved responses (worn area and depth field per pass) are equal to the bit, and the held
// offset is the onset's.
TEST(VehicleTrafficTest, NodesBeyondTheFlangeOnsetAreHeldAtOneOffset) {
  WearStudy study = VehicleStudy(8.0e-3);
  study.options.quadrature_points = 5;
  const WearState s0 = MakeInitialState(study);
  const Profile high = RailInTrack(study, s0.rail, s0.rail);
  const Profile low = RailInTrack(study, *s0.low_rail, *s0.low_rail);
  const VehicleEquilibrium eq = SolveVehicleEquilibrium(study, 0, high, low);
  ASSERT_EQ(eq.flange_onset_m.size(), 1u);
  const double std_m = study.traffic[0].lateral_shift_std_m;
  for (const int side : {0, 1}) {
    const double onset_m = eq.flange_onset_m[0][side];
    std::printf("[ measured ] flange onset toward the %s rail: %.3f mm from the equilibrium\n",
                side == 0 ? "high" : "low", onset_m * 1e3);
    EXPECT_GT(onset_m, 0.0);
    EXPECT_LT(onset_m, 1.35 * std_m);  // both outer nodes beyond it
    const RailSide rail = side == 0 ? RailSide::kHigh : RailSide::kLow;
    EXPECT_EQ(FlangeOnsetOffset(study, 0, eq, 0, rail), onset_m);  // deterministic
    // The elastic contact's onset: at or below the rigid first contact's 45 degrees.
    EXPECT_LE(onset_m, RigidFlangeOnsetOffset(eq, 0, rail, std_m));
  }
  const auto shift = [&](double x) {
    return VehicleNodeCases(study, 0, eq, 0, x, 0, 1.0)[0].placement.lateral_shift_m;
  };
  // A node below the onset keeps its own offset; every node beyond it is at the onset.
  const double at_onset = eq.flange_onset_m[0][0] / std_m;
  EXPECT_NE(shift(0.5 * at_onset), shift(0.0));
  EXPECT_NE(shift(0.5 * at_onset), shift(at_onset + 0.5));
  EXPECT_EQ(shift(at_onset + 0.5), shift(3.0));
  EXPECT_EQ(shift(3.0), shift(16.9));

  const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  ASSERT_EQ(step.cases.size(), 10u);  // 5 nodes x 2 rails, node by node
  // Gauss-Hermite nodes in increasing order: cases 0-1 and 2-3 the two nodes toward the low rail,
  // 6-7 and 8-9 toward the high rail.
  for (const auto& [a, b] : {std::pair{0, 2}, std::pair{1, 3}, std::pair{6, 8}, std::pair{7, 9}}) {
    const LoadCaseSummary& ca = step.cases[a];
    const LoadCaseSummary& cb = step.cases[b];
    ASSERT_EQ(ca.load_case.rail, cb.load_case.rail);
    ASSERT_NE(ca.load_case.spread_x, cb.load_case.spread_x);
    EXPECT_EQ(ca.load_case.placement.lateral_shift_m, cb.load_case.placement.lateral_shift_m);
    EXPECT_EQ(ca.worn_area_per_pass_m2, cb.worn_area_per_pass_m2) << a << " " << b;
    EXPECT_EQ(ca.depth_per_pass_m, cb.depth_per_pass_m) << a << " " << b;
    EXPECT_EQ(ca.contact_angle_rad, cb.contact_angle_rad) << a << " " << b;
  }
}

// The onset search stops at the rule's outermost node (FlangeOnsetOffset's enough_m): with 3
// Gauss-Hermite nodes (+-1.73 std) over a 1 mm spread, a side whose onset lies beyond 1.73 std
// keeps only a lower bound at or beyond that node, found with fewer contact solves, and every
// node's case is the same, bit for bit, as with the onset itself.
TEST(VehicleTrafficTest, TheOnsetSearchStopsAtTheRulesOutermostNode) {
  const WearStudy study = VehicleStudy(1.0e-3);
  const std::array<double, 2> outermost = OutermostSpreadNodes(study.options);
  EXPECT_NEAR(outermost[0], std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(outermost[1], std::sqrt(3.0), 1e-12);
  const WearState s0 = MakeInitialState(study);
  const VehicleEquilibrium eq =
      SolveVehicleEquilibrium(study, 0, RailInTrack(study, s0.rail, s0.rail),
                              RailInTrack(study, *s0.low_rail, *s0.low_rail));
  const double std_m = study.traffic[0].lateral_shift_std_m;
  VehicleEquilibrium full = eq;  // the onsets without the bound
  int bounded = 0;
  for (const int side : {0, 1}) {
    const RailSide rail = side == 0 ? RailSide::kHigh : RailSide::kLow;
    const double onset_m = FlangeOnsetOffset(study, 0, eq, 0, rail);
    const double kept_m = eq.flange_onset_m[0][side];
    full.flange_onset_m[0][side] = onset_m;
    std::printf("[ measured ] toward the %s rail: onset %.4f std, kept %.4f std\n",
                side == 0 ? "high" : "low", onset_m / std_m, kept_m / std_m);
    if (kept_m == onset_m) continue;
    ++bounded;
    EXPECT_GE(kept_m, outermost[side] * std_m);
    EXPECT_LE(kept_m, onset_m);
  }
  EXPECT_GE(bounded, 1);  // the bound is exercised here
  // Nodes of the rule itself (and any within its outermost ones): the same cases.
  std::vector<double> nodes, weights;
  GaussHermiteProbabilists(study.options.quadrature_points, &nodes, &weights);
  nodes.push_back(0.99 * std::sqrt(3.0));
  nodes.push_back(-0.99 * std::sqrt(3.0));
  for (const double x : nodes) {
    const std::vector<LoadCase> a = VehicleNodeCases(study, 0, eq, 0, x, 0, 1.0);
    const std::vector<LoadCase> b = VehicleNodeCases(study, 0, full, 0, x, 0, 1.0);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].placement.lateral_shift_m, b[k].placement.lateral_shift_m) << x;
      EXPECT_EQ(a[k].placement.roll_rad, b[k].placement.roll_rad) << x;
      EXPECT_EQ(a[k].vertical_force_N, b[k].vertical_force_N) << x;
    }
  }
}

// RunWear starts the first step's curving from the equilibrium on the unworn rails and every
// later one from the step before's (WearState::curving, with its Jacobian): a run stopped after
// one step and resumed from its state ends exactly where the uninterrupted run does.
// The same with the adaptive spread rule (issue 16 point 5) over a 1 mm spread: its nodes are
// chosen afresh in every step from the step's own solutions, so the resumed run is bit-identical
// too.
void ExpectResumedRunEqualsUninterrupted(WearStudy study) {
  study.options.max_depth_per_step_m = 1e-6;  // steps far shorter than the run
  const WearState s0 = MakeInitialState(study);
  const UnwornRails unworn = UnwornRails::Of(s0);
  const WearRunSummary whole = RunWear(study, unworn, s0, nullptr, 2);
  const WearRunSummary first = RunWear(study, unworn, s0, nullptr, 1);
  const WearRunSummary rest = RunWear(study, unworn, first.state, nullptr, 1);
  ASSERT_EQ(whole.state.step, 2);
  ASSERT_EQ(rest.state.step, 2);
  ASSERT_EQ(first.state.curving.size(), 1u);
  EXPECT_EQ(first.state.curving[0].state.size(), 2);  // the wheelset's (y, psi)
  EXPECT_EQ(first.state.curving[0].jacobian.rows(), 2);
  EXPECT_EQ(whole.state.passes, rest.state.passes);
  EXPECT_EQ(whole.state.rail.points(), rest.state.rail.points());
  EXPECT_EQ(whole.state.low_rail->points(), rest.state.low_rail->points());
}

TEST(VehicleTrafficTest, ResumedRunEqualsUninterrupted) {
  ExpectResumedRunEqualsUninterrupted(VehicleStudy(0.0));
}

TEST(VehicleTrafficTest, AdaptiveSpreadResumedRunEqualsUninterrupted) {
  WearStudy study = VehicleStudy(1.0e-3);
  study.options.integration_tolerance = 0.05;
  ExpectResumedRunEqualsUninterrupted(study);
}

// Issue 17: WearOptions::cancel reaches the curving solve. Cancelled at its 3rd question, which
// falls inside the vehicle's equilibrium on the unworn rails (RunWear solves it before step 1),
// the run ends cancelled with no step; cancelled inside step 2's curving, step 2 is dropped. A
// run on from the states left behind ends exactly where the uninterrupted run does.
TEST(VehicleTrafficTest, CancelInTheCurvingSolveDropsTheStepAndResumesExactly) {
  WearStudy study = VehicleStudy(0.0);
  study.options.max_depth_per_step_m = 1e-6;  // steps far shorter than the run
  const WearState s0 = MakeInitialState(study);
  const UnwornRails unworn = UnwornRails::Of(s0);
  const WearRunSummary whole = RunWear(study, unworn, s0, nullptr, 2);
  ASSERT_EQ(whole.state.step, 2);

  int asked = 0;
  study.options.cancel = [&asked] { return ++asked >= 3; };
  const WearRunSummary before_step_1 = RunWear(study, unworn, s0, nullptr, 2);
  EXPECT_TRUE(before_step_1.cancelled);
  EXPECT_EQ(before_step_1.steps_done, 0);
  EXPECT_EQ(asked, 3);  // no question after the cancel: the solve stopped at once

  // Step 1 whole, then a cancel in step 2's curving: the questions RunWear asks before step 2
  // and SolveCurving's first ones pass, the next one (before a contact evaluation) cancels.
  study.options.cancel = {};
  const WearRunSummary first = RunWear(study, unworn, s0, nullptr, 1);
  asked = 0;
  study.options.cancel = [&asked] { return ++asked >= 3; };
  const WearRunSummary cut = RunWear(study, unworn, first.state, nullptr, 1);
  EXPECT_TRUE(cut.cancelled);
  EXPECT_EQ(cut.steps_done, 0);
  EXPECT_EQ(cut.state.step, 1);
  study.options.cancel = {};
  const WearRunSummary rest = RunWear(study, unworn, cut.state, nullptr, 1);
  ASSERT_EQ(rest.state.step, 2);
  EXPECT_EQ(whole.state.passes, rest.state.passes);
  EXPECT_EQ(whole.state.rail.points(), rest.state.rail.points());
  EXPECT_EQ(whole.state.low_rail->points(), rest.state.low_rail->points());
}

// The adaptive rule applies to vehicle traffic: each wheelset's spread around its equilibrium is
// refined on its own (more nodes than the first seven), what it used is recorded, and both rails'
// case weights sum to 1. The step's worn area per pass is printed against the fixed 20-node
// Gauss-Hermite rule's but not compared: this wheelset runs on its treads (1e-6 mm^2 per pass)
// where the draft grid's worn area jumps by up to 2.7x between positions 0.05 std apart (measured
// at the 1.6-3.6 degree contact switch), so neither rule is within 1 % of the other at draft;
// the default study's gauge-corner traffic is (tests/wear/spread_integration_test.cpp).
TEST(VehicleTrafficTest, AdaptiveSpreadRefinesEachWheelset) {
  WearStudy study = VehicleStudy(1.0e-3);
  study.options.quadrature_points = 20;
  const WearState s0 = MakeInitialState(study);
  const StepResult fixed = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  study.options.integration_tolerance = 0.02;
  const StepResult adaptive = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  ASSERT_TRUE(fixed.low_rail && adaptive.low_rail);
  const auto area = [](const std::vector<double>& depth, const WearGrid& grid) {
    double a = 0.0;
    for (const double d : depth) a += d * grid.h_m;
    return a;
  };
  std::printf(
      "[ measured ] vehicle step 1 worn area per pass, 20 fixed / adaptive (%d nodes, %d "
      "rounds): high %.4e / %.4e mm2, low %.4e / %.4e mm2\n",
      adaptive.integration.nodes[0], adaptive.integration.rounds,
      area(fixed.depth_per_pass_m, fixed.grid) * 1e6,
      area(adaptive.depth_per_pass_m, adaptive.grid) * 1e6,
      area(fixed.low_rail->depth_per_pass_m, fixed.low_rail->grid) * 1e6,
      area(adaptive.low_rail->depth_per_pass_m, adaptive.low_rail->grid) * 1e6);
  EXPECT_TRUE(adaptive.integration.adaptive);
  EXPECT_GT(adaptive.integration.rounds, 0);
  EXPECT_GT(adaptive.integration.nodes[0], static_cast<int>(kSpreadInitialNodes.size()));
  EXPECT_EQ(static_cast<int>(adaptive.cases.size()), 2 * adaptive.integration.nodes[0]);
  double high_weight = 0.0, low_weight = 0.0;
  for (const LoadCaseSummary& c : adaptive.cases) {
    (c.load_case.rail == RailSide::kHigh ? high_weight : low_weight) += c.load_case.weight;
    EXPECT_EQ(c.load_case.wheelset, 0);
  }
  EXPECT_NEAR(high_weight, 1.0, 1e-12);
  EXPECT_NEAR(low_weight, 1.0, 1e-12);
  EXPECT_GT(area(adaptive.depth_per_pass_m, adaptive.grid), 0.0);
  // The fixed rule records its nodes too.
  EXPECT_EQ(fixed.integration.nodes, std::vector<int>{20});
  EXPECT_FALSE(fixed.integration.adaptive);
}

}  // namespace
}  // namespace railwear
