// Tests of normal_part_memo.h: a solve that continues from the kept normal part gives the full
// solve's result bit for bit at another pitch velocity, only on the geometry it was kept for.
#include "core/contact/normal_part_memo.h"

#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_solver.h"
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
