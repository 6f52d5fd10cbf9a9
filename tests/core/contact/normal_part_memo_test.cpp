// Tests of normal_part_memo.h: a solve that continues from the kept normal part gives the full
// solve's result bit for bit at another pitch velocity, only on the geometry it was kept for; a
// warm memo's balance (started from the last balanced state) gives it to the balance's and the
// normal solver's tolerances, in fewer normal solves.
#include "core/contact/normal_part_memo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_forces.h"
#include "core/contact/contact_solver.h"
#include "core/contact/normal_tangential_stage.h"
#include "core/contact/placement_stage.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/contact/same_result.h"

namespace railwear::internal {
namespace {

using testing::ExpectSameResult;

// An S1002 wheel rolling on UIC60 at 1:40 under a prescribed load (so the vertical balance with
// the creep forces runs and changes the normal problem), conformal draft, near the gauge corner.
ContactProblem Rolling(double lateral_m) {
  ContactProblem p;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.load.vertical_force_N = 60e3;
  p.model = MakeModelOptions(ModelKind::kAuto);
  p.model.accuracy = AccuracyPreset::kDraft;
  p.placement.lateral_shift_m = lateral_m;
  p.placement.rolling_radius_m = 0.46;
  RollingOptions r;
  r.friction = 0.35;
  r.motion.speed_m_s = 20.0;
  r.motion.pitch_velocity_rad_s = -20.0 / 0.46;
  p.rolling = r;
  return p;
}

bool HasStage(const ContactResult& r, const std::string& name) {
  for (const auto& s : r.stages) {
    if (s.name == name) return true;
  }
  return false;
}

TEST(NormalPartMemo, ContinuedSolvesEqualFullSolvesBitForBit) {
  ContactProblem p = Rolling(-6e-3);
  const WheelRailGeometry geom = PlaceWheel(p);
  NormalPartMemo memo;
  const ContactResult first = SolveContact(p, geom, 0.0, &memo);
  ASSERT_EQ(first.status, SolverStatus::kConverged) << first.message;
  EXPECT_EQ(memo.reuses(), 0);
  ExpectSameResult(first, SolveContact(p, geom));
  // Creepages of a few per mille either way (the axle-force search's trials).
  for (double creep : {-4e-3, 1e-3, 0.0, 6e-3}) {
    p.rolling->motion.pitch_velocity_rad_s = -20.0 / 0.46 * (1.0 + creep);
    const ContactResult continued = SolveContact(p, geom, 0.0, &memo);
    const ContactResult full = SolveContact(p, geom);
    ExpectSameResult(continued, full);
    EXPECT_TRUE(HasStage(continued, "normal reused"));
    EXPECT_FALSE(HasStage(continued, "grid"));
    EXPECT_TRUE(HasStage(full, "grid"));
    EXPECT_TRUE(HasStage(continued, "balance"));  // the balance ran on the kept problem's copy
  }
  EXPECT_EQ(memo.reuses(), 4);
}

// The largest relative difference of the forces a caller reads from a wheel's result: every
// patch's normal force and creep forces against the patch's normal force, and the wheel's
// vertical and lateral forces against its vertical force.
double LargestForceDifference(const ContactResult& a, const ContactResult& b) {
  double d = std::max(std::abs(a.vertical_force_N - b.vertical_force_N),
                      std::abs(a.lateral_force_N - b.lateral_force_N)) /
             std::abs(b.vertical_force_N);
  for (size_t k = 0; k < a.patches.size() && k < b.patches.size(); ++k) {
    const PatchResult& p = a.patches[k];
    const PatchResult& q = b.patches[k];
    const double n = q.normal_force_N;
    d = std::max(d, std::abs(p.normal_force_N - n) / n);
    if (p.rolling && q.rolling) {
      d = std::max(d,
                   std::abs(p.rolling->tangential.force_x_N - q.rolling->tangential.force_x_N) / n);
      d = std::max(d,
                   std::abs(p.rolling->tangential.force_s_N - q.rolling->tangential.force_s_N) / n);
    }
  }
  return d;
}

// A warm memo (SolveWheelset's): the first solve is the full one bit for bit; each later one
// starts its vertical balance from the last balanced state and ends balanced to the same
// tolerance, with the forces of the full solve to kWarmForceTolerance, in fewer of the
// balance's normal solves (at the same pitch velocity none at all).
TEST(NormalPartMemo, WarmBalanceGivesTheFullSolveToTheBalanceTolerance) {
  // The balance stops at |V_p + V_c - Q| <= 1e-9 Q (kBalanceTolerance) and each normal solve at
  // 1e-10 of the gap scale (NormalSolverOptions::tolerance), from different starts: the forces
  // may differ by the balance's tolerance. The bound is 10x that; measured on this wheel: 1.7e-11
  // (printed below).
  constexpr double kWarmForceTolerance = 1e-8;
  ContactProblem p = Rolling(-6e-3);
  const WheelRailGeometry geom = PlaceWheel(p);
  NormalPartMemo memo(NormalPartMemo::kWarmBalance);
  const ContactResult first = SolveContact(p, geom, 0.0, &memo);
  ASSERT_EQ(first.status, SolverStatus::kConverged) << first.message;
  ExpectSameResult(first, SolveContact(p, geom));
  ASSERT_NE(memo.Balanced(geom), nullptr);
  int warm_balance_solves = 0, full_balance_solves = 0;
  double largest = 0.0;
  for (double creep : {-4e-3, -3e-3, 1e-3, 0.0, 6e-3}) {
    p.rolling->motion.pitch_velocity_rad_s = -20.0 / 0.46 * (1.0 + creep);
    const ContactResult warm = SolveContact(p, geom, 0.0, &memo);
    const ContactResult full = SolveContact(p, geom);
    ASSERT_EQ(warm.status, SolverStatus::kConverged) << warm.message;
    ASSERT_EQ(warm.patches.size(), full.patches.size());
    EXPECT_LE(warm.balance_residual, kBalanceTolerance);
    const double d = LargestForceDifference(warm, full);
    EXPECT_LE(d, kWarmForceTolerance) << "creepage " << creep;
    largest = std::max(largest, d);
    warm_balance_solves += warm.balance_iterations;
    full_balance_solves += full.balance_iterations;
  }
  std::printf(
      "warm balance: largest relative force difference %.1e; balance solves %d warm, %d "
      "from the load\n",
      largest, warm_balance_solves, full_balance_solves);
  EXPECT_EQ(memo.reuses(), 5);
  EXPECT_EQ(memo.warm_balances(), 5);
  EXPECT_LT(warm_balance_solves, full_balance_solves);
}

// The warm state belongs to the kept part: another geometry's solve replaces both, and an exact
// memo or a coupled problem never starts warm (their results stay the full solve's bit for bit).
TEST(NormalPartMemo, WarmStateIsReplacedWithThePartAndNotUsedWithCoupling) {
  ContactProblem a = Rolling(-6e-3), b = Rolling(-2e-3);
  const WheelRailGeometry geom_a = PlaceWheel(a), geom_b = PlaceWheel(b);
  NormalPartMemo memo(NormalPartMemo::kWarmBalance);
  SolveContact(a, geom_a, 0.0, &memo);
  ASSERT_NE(memo.Balanced(geom_a), nullptr);
  ExpectSameResult(SolveContact(b, geom_b, 0.0, &memo), SolveContact(b, geom_b));
  EXPECT_EQ(memo.Balanced(geom_a), nullptr);
  EXPECT_NE(memo.Balanced(geom_b), nullptr);
  EXPECT_EQ(memo.warm_balances(), 0);

  NormalPartMemo exact;
  SolveContact(a, geom_a, 0.0, &exact);
  EXPECT_EQ(exact.Balanced(geom_a), nullptr);

  ContactProblem coupled = Rolling(-6e-3);
  coupled.rolling->coupling = true;
  NormalPartMemo warm(NormalPartMemo::kWarmBalance);
  SolveContact(coupled, geom_a, 0.0, &warm);
  EXPECT_EQ(warm.Balanced(geom_a), nullptr);
  coupled.rolling->motion.pitch_velocity_rad_s = -20.0 / 0.46 * (1.0 + 2e-3);
  ExpectSameResult(SolveContact(coupled, geom_a, 0.0, &warm), SolveContact(coupled, geom_a));
  EXPECT_EQ(warm.warm_balances(), 0);
}

TEST(NormalPartMemo, AnotherGeometryIsSolvedInFullAndKeptInstead) {
  ContactProblem a = Rolling(-6e-3), b = Rolling(-2e-3);
  const WheelRailGeometry geom_a = PlaceWheel(a), geom_b = PlaceWheel(b);
  NormalPartMemo memo;
  SolveContact(a, geom_a, 0.0, &memo);
  ExpectSameResult(SolveContact(b, geom_b, 0.0, &memo), SolveContact(b, geom_b));
  EXPECT_EQ(memo.reuses(), 0);
  EXPECT_EQ(memo.Find(geom_a), nullptr);  // replaced by b's part
  EXPECT_NE(memo.Find(geom_b), nullptr);
  ExpectSameResult(SolveContact(b, geom_b, 0.0, &memo), SolveContact(b, geom_b));
  EXPECT_EQ(memo.reuses(), 1);
}

TEST(NormalPartMemo, NormalOnlySolvesKeepNothing) {
  ContactProblem p = Rolling(-6e-3);
  p.rolling.reset();  // normal contact: nothing to continue
  const WheelRailGeometry geom = PlaceWheel(p);
  NormalPartMemo memo;
  ExpectSameResult(SolveContact(p, geom, 0.0, &memo), SolveContact(p, geom));
  EXPECT_EQ(memo.Find(geom), nullptr);
}

}  // namespace
}  // namespace railwear::internal
