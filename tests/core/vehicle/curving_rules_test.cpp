// The Newton rules of the curving solve (docs/curving.md, "The Newton rules") on analytic wheelset
// forces (core/vehicle/curving_internal.h): a single wheelset on tangent track (no unbalanced
// force), its lateral force a stiff flange's piecewise-linear force with a step in value at a
// lateral position or angle of attack, its yaw moment linear. Each case starts a few micrometres
// before the step (CurvingOptions::start), where the rule under test is the first to act, and
// checks the rule's named ending (CurvingResult::ending), its message and the Newton events that
// led to it. No contact is solved: the whole file runs in milliseconds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/vehicle/curving.h"
#include "core/vehicle/curving_internal.h"
#include "tests/core/vehicle/curving_cases.h"

namespace railwear {
namespace {
using internal::NewtonEvent;
using internal::WheelsetForces;
using namespace test;

// The scales of the tolerance: the static wheel load of BaseProblem's 100 kN axle on tangent
// track, and the position tolerances of CurvingOptions.
constexpr double kQ0_N = 50e3;
constexpr double kTolerance = 3e-3;      // CurvingOptions::tolerance
constexpr double kPositionTol_m = 5e-5;  // CurvingOptions::position_tolerance_m
constexpr double kYawTol_rad = 5e-5;     // CurvingOptions::yaw_tolerance_rad
constexpr double kStepAt_m = 5e-3;       // where the flange's force steps
constexpr double kTreadStiffness = 1e6;  // N/m, the order of a tread's gravitational stiffness
constexpr double kYawStiffness = 1e6;    // N m/rad

// A wheelset problem on tangent track, one phase (the predictor is the contact model, which the
// force model replaces anyway), started at (y, psi) without a Jacobian.
CurvingProblem StartedAt(double y_m, double psi_rad) {
  CurvingProblem p = BaseProblem(MakeCone(0.1), 0.0);
  p.options.predictor = p.contact.model;
  p.options.threads = 1;
  CurvingStart start;
  start.state = Eigen::Vector2d(y_m, psi_rad);
  p.options.start = start;
  return p;
}

// A flange reached at kStepAt_m: the residual force (lateral force on the wheelset, with a push
// `push_N` toward the flange) is push - k y before it and drops by `step_N` at it; the yaw
// moment restores psi = 0.
internal::WheelsetForceModel FlangeStep(double push_N, double step_N) {
  return [=](int, double y, double psi) {
    WheelsetForces f;
    f.lateral_N = push_N - kTreadStiffness * y - (y >= kStepAt_m ? step_N : 0.0);
    f.yaw_moment_Nm = -kYawStiffness * psi;
    return f;
  };
}

// The pattern of the coach's leading wheelset on step 105's worn rails (docs/curving.md, "A step
// in the lateral force in flange contact"), scaled down: a stiff flange (1e8 N/m) whose lateral
// force steps by 1.5 kN (10x the force tolerance) when the angle of attack falls below 0.97
// mrad, the yaw moment's root at 0 (a soft 1e6 N m/rad). From psi = 1 mrad every trial toward
// the root crosses the step and has a larger residual (line search and Levenberg-Marquardt
// refused), but the lateral force's own equilibrium is 15 um away in y there (0.3 of the
// position tolerance) while the step moved 1 mrad: the natural-level test takes it. (Forward
// differences in psi do not cross a step behind the start: the Jacobian is the slopes.)
internal::WheelsetForceModel YawStepInFlangeContact() {
  return [](int, double y, double psi) {
    WheelsetForces f;
    f.lateral_N = -1e8 * y + (psi < 0.97e-3 ? 1.5e3 : 0.0);
    f.yaw_moment_Nm = -kYawStiffness * psi;
    return f;
  };
}

bool Has(const std::vector<NewtonEvent>& events, NewtonEvent e) {
  return std::find(events.begin(), events.end(), e) != events.end();
}

// ProbeForceStep, the fifth rule: the lateral residual is +1 kN (6.7x the tolerance) just before
// the flange and -2 kN past it; there is no root, the equilibrium is the step itself. From 1 um
// before it, the fresh Jacobian's differences (0.2 mm) straddle the step, the Newton step (62 um)
// and all its halvings land past it with a larger residual (line search refused), the
// natural-level test refuses them (in one dimension its correction with the same Jacobian is
// shorter than the step only where the residual is smaller, which the line search would have
// taken), so do the Levenberg-Marquardt trials (down to 1/22 of it), the Newton correction is above
// the position tolerance; the probe a position tolerance along the Newton direction reverses
// the residual's sign: converged in position at the step.
TEST(CurvingRulesTest, ForceStepProbeFindsTheFlangesStepWhereTheOtherRulesFail) {
  const double push_N = kTreadStiffness * kStepAt_m + 1e3;
  CurvingProblem p = StartedAt(kStepAt_m - 1e-6, 0.0);
  std::vector<NewtonEvent> events;
  const CurvingResult r = internal::SolveCurvingWith(p, FlangeStep(push_N, 3e3), &events);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_EQ(r.ending, CurvingEnding::kForceStepProbe) << r.message;
  EXPECT_NE(r.message.find("converged in position at a step in the contact forces"),
            std::string::npos)
      << r.message;
  const std::vector<NewtonEvent> expected = {
      NewtonEvent::kSolve,
      NewtonEvent::kFreshJacobian,
      NewtonEvent::kLineSearchFailed,
      NewtonEvent::kNaturalLevelFailed,
      NewtonEvent::kLevenbergMarquardtFailed,
      NewtonEvent::kEnded,
  };
  EXPECT_EQ(events, expected);
  // At the step, within the position tolerance: the returned state is the better of the two
  // sides (here the start, +1 kN).
  EXPECT_NEAR(r.wheelsets[0].lateral_m, kStepAt_m, kPositionTol_m);
  // The start's residual, +1 kN and the tread's 1 N over the micrometre (rounding only).
  EXPECT_NEAR(r.largest_scaled_residual, (1e3 + kTreadStiffness * 1e-6) / kQ0_N, 1e-12);
  EXPECT_EQ(r.contact_solves, 1 + 2 + 4 + 3 + 8 + 1);  // start, Jacobian, LS, NL, LM, probe
}

// The same flange from 3 um before the step: the smallest Levenberg-Marquardt trial (1/22 of
// the Newton step, 2.8 um) stays short of the step and is taken; the next iteration's Newton
// steps all cross it again, and the probe ends the solve there.
TEST(CurvingRulesTest, LevenbergMarquardtTakesAShortStepThenTheProbeEnds) {
  const double push_N = kTreadStiffness * kStepAt_m + 1e3;
  CurvingProblem p = StartedAt(kStepAt_m - 3e-6, 0.0);
  std::vector<NewtonEvent> events;
  const CurvingResult r = internal::SolveCurvingWith(p, FlangeStep(push_N, 3e3), &events);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_TRUE(Has(events, NewtonEvent::kLevenbergMarquardt));
  EXPECT_EQ(r.ending, CurvingEnding::kForceStepProbe) << r.message;
  EXPECT_NEAR(r.wheelsets[0].lateral_m, kStepAt_m, kPositionTol_m);
}

// From the centred start (the flange 5 mm away) the line search walks up to the step, by chords
// and fresh Jacobians, and the probe ends the solve at it, within the position tolerance: the
// rule is reached on the way, not only from a start placed for it.
TEST(CurvingRulesTest, FromTheCentredStartTheSolveEndsAtTheFlangesStep) {
  const double push_N = kTreadStiffness * kStepAt_m + 1e3;
  CurvingProblem p = StartedAt(0.0, 0.0);
  std::vector<NewtonEvent> events;
  const CurvingResult r = internal::SolveCurvingWith(p, FlangeStep(push_N, 3e3), &events);
  std::printf("flange step from the centre: %s (%s), %d solves\n",
              std::string(ToString(r.ending)).c_str(), r.message.c_str(), r.contact_solves);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_EQ(r.ending, CurvingEnding::kForceStepProbe) << r.message;
  EXPECT_NEAR(r.wheelsets[0].lateral_m, kStepAt_m, kPositionTol_m);
  EXPECT_LE(r.largest_scaled_residual, 20.0 * kTolerance);
}

// Every rule that ends a solve names itself (CurvingResult::ending) and says so in the message.
TEST(CurvingRulesTest, EachRuleReportsItsNamedEnding) {
  // Linear forces: Newton reaches the tolerance.
  {
    CurvingProblem p = StartedAt(0.0, 0.0);
    const CurvingResult r = internal::SolveCurvingWith(p, FlangeStep(1e3, 0.0));
    ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
    EXPECT_EQ(r.ending, CurvingEnding::kTolerance);
    EXPECT_TRUE(r.message.empty()) << r.message;
    EXPECT_LE(r.largest_scaled_residual, kTolerance);
  }
  // Within 3x the tolerance no step helps (+300 N before the step, -400 N past it, from 1 um
  // before): the grid's noise floor.
  {
    CurvingProblem p = StartedAt(kStepAt_m - 1e-6, 0.0);
    const CurvingResult r =
        internal::SolveCurvingWith(p, FlangeStep(kTreadStiffness * kStepAt_m + 300.0, 700.0));
    ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
    EXPECT_EQ(r.ending, CurvingEnding::kGridNoise);
    EXPECT_NE(r.message.find("stopped at the contact grid's noise"), std::string::npos);
    EXPECT_LE(r.largest_scaled_residual, 3.0 * kTolerance);
  }
  // A step so large against the residual (+1 kN, -9 kN) that the fresh Jacobian's Newton
  // correction (differences across the step: 20 um) is within the position tolerance.
  {
    CurvingProblem p = StartedAt(kStepAt_m - 1e-6, 0.0);
    const CurvingResult r =
        internal::SolveCurvingWith(p, FlangeStep(kTreadStiffness * kStepAt_m + 1e3, 1e4));
    ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
    EXPECT_EQ(r.ending, CurvingEnding::kPosition);
    EXPECT_NE(r.message.find("converged in position: the Newton correction"), std::string::npos)
        << r.message;
  }
  // The natural-level step (YawStepInFlangeContact): it ends the solve in position.
  {
    CurvingProblem p = StartedAt(0.0, 1e-3);
    const CurvingResult r = internal::SolveCurvingWith(p, YawStepInFlangeContact());
    ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
    EXPECT_EQ(r.ending, CurvingEnding::kNaturalLevel) << r.message;
    EXPECT_NE(r.message.find("converged in position across a step"), std::string::npos)
        << r.message;
    EXPECT_NEAR(r.wheelsets[0].yaw_rad, 0.0, kYawTol_rad);
    EXPECT_LE(r.largest_scaled_residual, 20.0 * kTolerance);
  }
  // The probe: the first test. A step far above the near-stall bound (+5 kN, -15 kN: 33x the
  // tolerance) has no rule that ends it: not converged, no ending, the residual reported.
  {
    CurvingProblem p = StartedAt(kStepAt_m - 1e-6, 0.0);
    const CurvingResult r =
        internal::SolveCurvingWith(p, FlangeStep(kTreadStiffness * kStepAt_m + 5e3, 2e4));
    EXPECT_EQ(r.status, CurvingStatus::kNotConverged) << r.message;
    EXPECT_EQ(r.ending, CurvingEnding::kNone);
    EXPECT_FALSE(r.message.empty());
    EXPECT_GT(r.largest_scaled_residual, 20.0 * kTolerance);
  }
}

// Within the near-stall band (3x to 20x the tolerance) the natural-level step is tried before
// the Levenberg-Marquardt trials: at a step in the contact forces every Levenberg-Marquardt
// trial also crosses the step (they are refused, or take a step too short to matter), and each
// trial costs a solve of every wheelset. On step 105's rails the coach's stored start spent 64
// of its 232 wheelset solves in two rounds of Levenberg-Marquardt trials there before the
// natural-level step crossed (CurvingCommandTest.ForceStepInFlangeContactIsCrossed).
// Here the natural-level step follows the failed line search directly: 8 force evaluations
// (start, Jacobian, 4 line-search trials, the natural-level trial) where the order
// Levenberg-Marquardt first took 16 (its 8 refused trials, measured with the old order).
TEST(CurvingRulesTest, NaturalLevelStepComesBeforeLevenbergMarquardtNearTheEquilibrium) {
  CurvingProblem p = StartedAt(0.0, 1e-3);
  std::vector<NewtonEvent> events;
  const CurvingResult r = internal::SolveCurvingWith(p, YawStepInFlangeContact(), &events);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_EQ(r.ending, CurvingEnding::kNaturalLevel) << r.message;
  const std::vector<NewtonEvent> expected = {
      NewtonEvent::kSolve,        NewtonEvent::kFreshJacobian, NewtonEvent::kLineSearchFailed,
      NewtonEvent::kNaturalLevel, NewtonEvent::kEnded,
  };
  EXPECT_EQ(events, expected);
  EXPECT_EQ(r.contact_solves, 1 + 2 + 4 + 1);
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

// A start stalled far from the equilibrium gives up for the next one. A worn tread whose
// lateral stiffness has the wrong sign about the centre (the residual 20 kN + 10 kN tanh(y / 2 mm)
// + 2e4 N/m y: Newton from the centre steps away from the flange, 2 mm an iteration, toward a
// residual that falls 40 N a step and never below 0.2 Q0) and a flange of 1e7 N/m from 6 mm (the
// equilibrium at 9 mm). Without the stall rule the centred start walked to the 20 mm lateral
// limit and the solve ended `no_equilibrium` (measured with the rule disabled, 2026-11-29),
// although the wheelset has one on its flange; with it the centred start gives up after 6
// iterations (kStalled), and the relaxed centred start (the last) moves the wheelset along its
// residual onto the flange.
double WornTreadLateral_N(double y) {
  return 20e3 + 10e3 * std::tanh(y / 2e-3) + 2e4 * y - (y > 6e-3 ? 1e7 * (y - 6e-3) : 0.0);
}

internal::WheelsetForceModel WornTreadWithFlange() {
  return [](int, double y, double psi) {
    WheelsetForces f;
    f.lateral_N = WornTreadLateral_N(y);
    f.yaw_moment_Nm = -kYawStiffness * psi;
    return f;
  };
}

// The equilibrium on the flange of WornTreadWithFlange: the lateral force's root beyond 6 mm.
double WornTreadRoot_m() {
  double root = 9e-3;
  for (int k = 0; k < 20; ++k) root -= WornTreadLateral_N(root) / (-1e7 + 2e4);
  return root;
}

// A wheelset start (y, psi) without a Jacobian, labelled.
CurvingStart WheelsetStart(double y_m, const std::string& label) {
  CurvingStart s;
  s.state = Eigen::Vector2d(y_m, 0.0);
  s.label = label;
  return s;
}

TEST(CurvingRulesTest, CentredStartStalledFarOffGivesUpForTheRelaxedStart) {
  CurvingProblem p = BaseProblem(MakeCone(0.1), 0.0);
  p.options.predictor = p.contact.model;
  p.options.threads = 1;
  std::vector<NewtonEvent> events;
  const CurvingResult r = internal::SolveCurvingWith(p, WornTreadWithFlange(), &events);
  std::printf("stalled centred start: %s (%s), %d evaluations\n",
              std::string(ToString(r.status)).c_str(), r.message.c_str(), r.contact_solves);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_TRUE(Has(events, NewtonEvent::kStalled));
  EXPECT_NE(r.message.find("relaxed"), std::string::npos) << r.message;
  // The flange's root, to the force tolerance over the flange's stiffness (150 N / 1e7 N/m =
  // 15 um).
  const double root = WornTreadRoot_m();
  EXPECT_NEAR(WornTreadLateral_N(root), 0.0, 1e-6);
  EXPECT_NEAR(r.wheelsets[0].lateral_m, root, 2e-5);
  // Two starts, each with its count: the centred one gave up, the relaxed one converged.
  ASSERT_EQ(r.attempts.size(), 2u);
  EXPECT_EQ(r.attempts[0].start, "the centred start");
  EXPECT_FALSE(r.attempts[0].converged);
  EXPECT_EQ(r.attempts[1].start, "the centred start relaxed");
  EXPECT_TRUE(r.attempts[1].converged);
  EXPECT_EQ(r.attempts[0].contact_solves + r.attempts[1].contact_solves, r.contact_solves);
}

// The start sequence (issue 15, docs/curving.md "The start sequence"): the given start, then the
// fallback starts, then the centred one (and its relaxed retry). On WornTreadWithFlange a
// "previous step's solution" at the centre stalls as the centred start does and gives up; the
// fallback near the flange (8 mm, an "unworn rails' equilibrium" 1 mm off) converges, the
// centred start is not tried, and the message says which start converged and why the one
// before it failed. A fallback equal to the start is skipped. The whole costs fewer evaluations
// than the centred start's relaxation path (the test above).
TEST(CurvingRulesTest, FailedStartFallsBackToTheNextStartBeforeTheCentredOne) {
  CurvingProblem p = BaseProblem(MakeCone(0.1), 0.0);
  p.options.predictor = p.contact.model;
  p.options.threads = 1;
  const CurvingResult centred = internal::SolveCurvingWith(p, WornTreadWithFlange());
  p.options.start = WheelsetStart(0.0, "the previous step's solution");
  p.options.fallback_starts = {WheelsetStart(0.0, "a copy of it"),
                               WheelsetStart(8e-3, "the unworn rails' equilibrium")};
  std::vector<NewtonEvent> events;
  const CurvingResult r = internal::SolveCurvingWith(p, WornTreadWithFlange(), &events);
  std::printf("fallback: %s (%s), %d evaluations (centred start: %d)\n",
              std::string(ToString(r.status)).c_str(), r.message.c_str(), r.contact_solves,
              centred.contact_solves);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_TRUE(Has(events, NewtonEvent::kStalled));
  EXPECT_NEAR(r.wheelsets[0].lateral_m, WornTreadRoot_m(), 2e-5);
  ASSERT_EQ(r.attempts.size(), 2u);  // the copy skipped, the centred start not reached
  EXPECT_EQ(r.attempts[0].start, "the previous step's solution");
  EXPECT_FALSE(r.attempts[0].converged);
  EXPECT_GT(r.attempts[0].largest_scaled_residual, 20 * kTolerance);  // stalled far off
  EXPECT_NE(r.attempts[0].message.find("stalled far from the equilibrium"), std::string::npos);
  EXPECT_EQ(r.attempts[1].start, "the unworn rails' equilibrium");
  EXPECT_TRUE(r.attempts[1].converged);
  EXPECT_LE(r.attempts[1].largest_scaled_residual, kTolerance);
  EXPECT_EQ(r.attempts[0].contact_solves + r.attempts[1].contact_solves, r.contact_solves);
  EXPECT_EQ(r.message.rfind("from the unworn rails' equilibrium (before it: the previous step's "
                            "solution: ",
                            0),
            0u)
      << r.message;
  EXPECT_LT(r.contact_solves, centred.contact_solves);
  // A start that converges at once keeps its message: no start is named.
  p.options.start = WheelsetStart(WornTreadRoot_m(), "the previous step's solution");
  const CurvingResult at_once = internal::SolveCurvingWith(p, WornTreadWithFlange());
  ASSERT_EQ(at_once.status, CurvingStatus::kConverged) << at_once.message;
  EXPECT_EQ(at_once.attempts.size(), 1u);
  EXPECT_EQ(at_once.message.find("from "), std::string::npos) << at_once.message;
}

// A fallback start that fails too still reaches the centred start and its relaxed retry: the
// given start at -3 mm and the fallback at -5 mm (both on the worn tread's side away from the
// flange, where Newton walks away from it) give up stalled, the centred start too, and the
// relaxed centred start converges on the flange; the message names it and every start before.
TEST(CurvingRulesTest, FallbackThatAlsoFailsStillReachesTheCentredStart) {
  CurvingProblem p = BaseProblem(MakeCone(0.1), 0.0);
  p.options.predictor = p.contact.model;
  p.options.threads = 1;
  p.options.start = WheelsetStart(-3e-3, "the previous step's solution");
  p.options.fallback_starts = {WheelsetStart(-5e-3, "the unworn rails' equilibrium")};
  const CurvingResult r = internal::SolveCurvingWith(p, WornTreadWithFlange());
  std::printf("failed fallback: %s (%s), %d evaluations\n", std::string(ToString(r.status)).c_str(),
              r.message.c_str(), r.contact_solves);
  ASSERT_EQ(r.status, CurvingStatus::kConverged) << r.message;
  EXPECT_NEAR(r.wheelsets[0].lateral_m, WornTreadRoot_m(), 2e-5);
  ASSERT_EQ(r.attempts.size(), 4u);
  const char* expected[] = {"the previous step's solution", "the unworn rails' equilibrium",
                            "the centred start", "the centred start relaxed"};
  int solves = 0;
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(r.attempts[k].start, expected[k]);
    EXPECT_EQ(r.attempts[k].converged, k == 3) << expected[k];
    EXPECT_NE(r.message.find(expected[k]), std::string::npos) << r.message;
    solves += r.attempts[k].contact_solves;
  }
  EXPECT_EQ(solves, r.contact_solves);
  EXPECT_EQ(r.message.rfind("from the centred start relaxed", 0), 0u) << r.message;
}

// A lazy fallback (CurvingStart::lazy: `railwear curving --db`'s unworn rails' equilibrium, a
// solve of its own) is found only when the starts before it fail: with a given start that
// converges it is never called; with one that stalls it is called once, and the solve is bit
// for bit the one with that fallback given (the same attempts, solves, state and message). One
// that finds nothing (cancelled, or no equilibrium: an empty state) is skipped for the centred
// start.
TEST(CurvingRulesTest, LazyFallbackIsFoundOnlyWhenTheStartBeforeItFails) {
  CurvingProblem p = BaseProblem(MakeCone(0.1), 0.0);
  p.options.predictor = p.contact.model;
  p.options.threads = 1;
  int calls = 0;
  CurvingStart lazy;
  lazy.lazy = [&calls] {
    ++calls;
    return WheelsetStart(8e-3, "the unworn rails' equilibrium");
  };
  p.options.fallback_starts = {lazy};
  p.options.start = WheelsetStart(WornTreadRoot_m(), "the previous step's solution");
  const CurvingResult at_once = internal::SolveCurvingWith(p, WornTreadWithFlange());
  ASSERT_EQ(at_once.status, CurvingStatus::kConverged) << at_once.message;
  EXPECT_EQ(calls, 0);  // the first start converged: the fallback was not solved
  ASSERT_EQ(at_once.attempts.size(), 1u);

  p.options.start = WheelsetStart(0.0, "the previous step's solution");
  const CurvingResult lazily = internal::SolveCurvingWith(p, WornTreadWithFlange());
  EXPECT_EQ(calls, 1);
  CurvingProblem given = p;
  given.options.fallback_starts = {WheelsetStart(8e-3, "the unworn rails' equilibrium")};
  const CurvingResult eager = internal::SolveCurvingWith(given, WornTreadWithFlange());
  ASSERT_EQ(eager.status, CurvingStatus::kConverged) << eager.message;
  EXPECT_EQ(lazily.status, eager.status);
  EXPECT_EQ(lazily.state, eager.state);
  EXPECT_EQ(lazily.message, eager.message);
  EXPECT_EQ(lazily.contact_solves, eager.contact_solves);
  ASSERT_EQ(lazily.attempts.size(), eager.attempts.size());
  for (size_t k = 0; k < eager.attempts.size(); ++k) {
    EXPECT_EQ(lazily.attempts[k].start, eager.attempts[k].start);
    EXPECT_EQ(lazily.attempts[k].contact_solves, eager.attempts[k].contact_solves);
  }

  // A lazy start that finds nothing: the centred start follows, as without it.
  p.options.fallback_starts[0].lazy = [&calls] {
    ++calls;
    return CurvingStart{};
  };
  const CurvingResult none = internal::SolveCurvingWith(p, WornTreadWithFlange());
  EXPECT_EQ(calls, 2);
  CurvingProblem without = p;
  without.options.fallback_starts.clear();
  const CurvingResult reference = internal::SolveCurvingWith(without, WornTreadWithFlange());
  EXPECT_EQ(none.state, reference.state);
  EXPECT_EQ(none.contact_solves, reference.contact_solves);
  ASSERT_EQ(none.attempts.size(), reference.attempts.size());
  EXPECT_EQ(none.attempts[1].start, reference.attempts[1].start);
}

}  // namespace
}  // namespace railwear
