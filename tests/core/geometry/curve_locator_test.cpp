#include "core/geometry/curve_locator.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// Spline of 801 points on a 10 mm arc: position error of the C2 spline ~1e-12 m; projections
// converge to the spline, so distances agree with the exact circle to this level.
constexpr double kSplineTolerance_m = 1e-10;

TEST(CurveLocator, ProjectsOntoCircleWithSignedDistance) {
  const double R = 0.01;
  const Profile crown = testing::ArcProfile(R, +1.0);  // rail crown, centre at (0, R)
  const CurveLocator rail(crown, /*material_toward_plus_z=*/true);
  const Eigen::Vector2d centre(0.0, R);
  for (double angle : {-0.9, -0.3, 0.0, 0.4, 1.0}) {
    const Eigen::Vector2d dir(std::sin(angle), -std::cos(angle));
    for (double d : {-2e-3, -1e-5, 1e-6, 3e-3}) {
      const Eigen::Vector2d q = centre + (R + d) * dir;
      const auto p = rail.Project(q);
      EXPECT_NEAR(p.signed_distance, d, kSplineTolerance_m) << angle << " " << d;
      EXPECT_NEAR((p.point - (centre + R * dir)).norm(), 0.0, 1e-9);
      // Outward normal points away from the material (up, along dir).
      EXPECT_GT(rail.OutwardNormal(p.s).dot(dir), 0.999);
    }
  }
}

TEST(CurveLocator, WheelOrientationAndMirroredOrder) {
  // A convex wheel (material above) gives positive distance below its surface, whatever the
  // order of its points.
  const double R = 0.01;
  const Profile wheel = testing::ArcProfile(R, -1.0);
  const Profile reversed = wheel.Mirrored();  // same circle, points in the other order
  for (const Profile* p : {&wheel, &reversed}) {
    const CurveLocator loc(*p, /*material_toward_plus_z=*/false);
    EXPECT_NEAR(loc.Project({0.0, 1e-4}).signed_distance, 1e-4, kSplineTolerance_m);
    EXPECT_NEAR(loc.Project({0.0, -1e-4}).signed_distance, -1e-4, kSplineTolerance_m);
    EXPECT_GT(loc.OutwardNormal(loc.Project({0.0, 0.0}).s).y(), 0.999);
  }
}

TEST(CurveLocator, IntersectsLine) {
  const double R = 0.3;
  const Profile crown = testing::ArcProfile(R, +1.0, 0.2);
  const CurveLocator rail(crown, true);
  for (double y : {-0.02, 0.0, 0.013}) {
    const auto c = rail.IntersectLine({y, -0.001}, {0.0, 1.0}, 0.0, 1.0);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(-0.001 + c->lambda, R - std::sqrt(R * R - y * y), kSplineTolerance_m);
  }
  EXPECT_FALSE(rail.IntersectLine({1.0, 0.0}, {0.0, 1.0}, 0.0, 1.0).has_value());
}

}  // namespace
}  // namespace railwear
