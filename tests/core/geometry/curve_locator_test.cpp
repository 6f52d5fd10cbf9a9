#include "core/geometry/curve_locator.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"
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

// Fast path against the naive reference: the block-skipping scan and the sample-by-sample one
// give the same projections and crossings bit for bit (the skipped blocks only hold samples that
// lose their comparisons), on real profiles, near and far from them, over whole profiles and
// windows, on lines in every direction and through the profile's own samples, and for NaN.
TEST(CurveLocator, BlockScanEqualsSampleScanBitForBit) {
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  const Profile rail_profile = MakeUic60();
  const Profile wheel_profile = MakeS1002();
  const Profile arc = testing::ArcProfile(0.01, +1.0);
  struct Case {
    const Profile* profile;
    bool rail;
  };
  std::mt19937 rng(18);
  for (const Case& c : {Case{&rail_profile, true}, Case{&wheel_profile, false}, Case{&arc, true}}) {
    const CurveLocator fast(*c.profile, c.rail);
    const CurveLocator naive(*c.profile, c.rail, 2e-5, CurveLocator::Scan::kEverySample);
    const double length = fast.length();
    std::uniform_real_distribution<double> along(-0.1 * length, 1.1 * length);
    std::uniform_real_distribution<double> offset(-3e-3, 3e-3);
    std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
    std::uniform_real_distribution<double> window(0.0, 0.3 * length);
    int crossings = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      // A point near the profile (at a sample exactly every tenth trial), then far away.
      const double s = std::clamp(along(rng), 0.0, length);
      Eigen::Vector2d q = c.profile->Position(s);
      if (trial % 10 != 0) q += Eigen::Vector2d(offset(rng), offset(rng));
      if (trial % 97 == 0) q *= 20.0;
      const double lo = along(rng), hi = lo + window(rng);
      const bool whole = trial % 3 == 0;
      const auto pf = whole ? fast.Project(q) : fast.Project(q, lo, hi);
      const auto pn = whole ? naive.Project(q) : naive.Project(q, lo, hi);
      ASSERT_EQ(pf.s, pn.s) << trial;
      ASSERT_EQ(pf.signed_distance, pn.signed_distance) << trial;
      const double phi =
          trial % 7 == 0 ? 0.5 * std::numbers::pi : angle(rng);  // vertical lines too
      const Eigen::Vector2d n(std::cos(phi), std::sin(phi));
      const auto xf = fast.IntersectLine(q, n, whole ? 0.0 : lo, whole ? 1.0 : hi);
      const auto xn = naive.IntersectLine(q, n, whole ? 0.0 : lo, whole ? 1.0 : hi);
      ASSERT_EQ(xf.has_value(), xn.has_value()) << trial;
      if (xf) {
        ++crossings;
        ASSERT_EQ(xf->s, xn->s) << trial;
        ASSERT_EQ(xf->lambda, xn->lambda) << trial;
      }
    }
    EXPECT_GT(crossings, 1000);  // the lines do meet the profile
    const Eigen::Vector2d nan_point(kNaN, 0.0);
    EXPECT_EQ(fast.Project(nan_point).s, naive.Project(nan_point).s);
    EXPECT_EQ(fast.IntersectLine(nan_point, {0.0, 1.0}, 0.0, 1.0).has_value(),
              naive.IntersectLine(nan_point, {0.0, 1.0}, 0.0, 1.0).has_value());
  }
}

}  // namespace
}  // namespace railwear
