#include "core/contact/placement_cache.h"

#include <gtest/gtest.h>

#include "core/contact/contact_case.h"
#include "core/geometry/wheelset.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/contact/same_result.h"

namespace railwear {
namespace {

// An S1002 wheel rolling on UIC60 at 1:40 (draft, FASTSIM), at a lateral shift and yaw.
ContactCase Rolling(double lateral_m, double yaw_rad, double lateral_velocity_m_s = 0.0) {
  ContactCase c;
  ContactProblem& p = c.problem;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.load.vertical_force_N = 100e3;
  p.model = MakeModelOptions(ModelKind::kHalfspace);
  p.model.accuracy = AccuracyPreset::kDraft;
  p.placement.lateral_shift_m = lateral_m;
  p.placement.yaw_rad = yaw_rad;
  RollingOptions r;
  r.friction = 0.3;
  r.motion.speed_m_s = 20.0;
  r.motion.lateral_velocity_m_s = lateral_velocity_m_s;
  p.rolling = r;
  return c;
}

using testing::ExpectSameResult;

TEST(PlacementCache, ReusesTheGeometryOnlyAtTheSamePoseAndProfiles) {
  PlacementCache cache;
  const ContactCase a = Rolling(-10.4e-3, 5e-3);
  SolveContactCase(a, &cache);
  SolveContactCase(a, &cache);
  EXPECT_EQ(cache.misses(), 1);
  EXPECT_EQ(cache.hits(), 1);
  SolveContactCase(Rolling(-10.4e-3, 5e-3, 0.01), &cache);  // a velocity: the same placement
  EXPECT_EQ(cache.hits(), 2);
  SolveContactCase(Rolling(-10.3e-3, 5e-3), &cache);  // another position
  EXPECT_EQ(cache.misses(), 2);
  ContactCase other_rail = a;
  other_rail.problem.rail_profile = ApplyCant(MakeUic60(), 1.0 / 20.0);
  SolveContactCase(other_rail, &cache);
  EXPECT_EQ(cache.misses(), 3);
}

TEST(PlacementCache, CachedSolvesEqualFreshOnesBitForBit) {
  // A time loop on one cache: the same pose twice, a new velocity, a new pose, the first again.
  PlacementCache cache;
  const ContactCase steps[] = {Rolling(-10.4e-3, 5e-3), Rolling(-10.4e-3, 5e-3),
                               Rolling(-10.4e-3, 5e-3, 0.02), Rolling(-5.6e-3, 0.0),
                               Rolling(-10.4e-3, 5e-3)};
  for (const ContactCase& c : steps) {
    ExpectSameResult(SolveContactCase(c, &cache).wheel, SolveContactCase(c).wheel);
  }
  EXPECT_EQ(cache.hits(), 2);
}

TEST(PlacementCache, WheelsetSolvesEqualFreshOnesBitForBit) {
  ContactCase c = Rolling(0.0, 0.0);
  c.problem.placement = {};
  WheelsetProblem& w = c.wheelset.emplace();
  w.wheelset.lateral_displacement_m = 3e-3;
  w.wheelset.yaw_rad = 1e-3;
  w.curvature_per_m = 1.0 / 800.0;
  PlacementCache cache;
  for (int step = 0; step < 2; ++step) {
    const ContactCaseResult cached = SolveContactCase(c, &cache);
    const ContactCaseResult fresh = SolveContactCase(c);
    ExpectSameResult(cached.wheelset->right, fresh.wheelset->right);
    ExpectSameResult(cached.wheelset->left, fresh.wheelset->left);
  }
  EXPECT_EQ(cache.misses(), 2);  // both wheels placed once
  EXPECT_EQ(cache.hits(), 2);    // and reused by the second step
}

// A wheelset's gauge points kept per slot: RailGaugePoint's, bit for bit, for the kept rail and
// height; another rail (one point moved by 1 um) or height is computed anew.
TEST(PlacementCache, KeepsGaugePointsOnlyForTheSameRailAndHeight) {
  PlacementCache cache;
  const Profile rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  const Eigen::Vector2d fresh = RailGaugePoint(rail, 14e-3);
  EXPECT_EQ(cache.GaugePoint(PlacementCache::kRight, rail, 14e-3), fresh);
  EXPECT_EQ(cache.GaugePoint(PlacementCache::kRight, rail, 14e-3), fresh);
  EXPECT_EQ(cache.GaugePoint(PlacementCache::kRight, rail, 15e-3), RailGaugePoint(rail, 15e-3));
  std::vector<Eigen::Vector2d> points = rail.points();
  for (Eigen::Vector2d& p : points) {
    if (p.y() > fresh.y() - 1e-3 && p.y() < fresh.y() + 1e-3) p.x() -= 1e-6;  // gauge face
  }
  const Profile moved(points, "moved");
  const Eigen::Vector2d other = cache.GaugePoint(PlacementCache::kRight, moved, 14e-3);
  EXPECT_EQ(other, RailGaugePoint(moved, 14e-3));
  EXPECT_NE(other.x(), fresh.x());
  // The other slot is its own.
  EXPECT_EQ(cache.GaugePoint(PlacementCache::kLeft, rail, 14e-3), fresh);
}

}  // namespace
}  // namespace railwear
