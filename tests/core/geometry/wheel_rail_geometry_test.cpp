#include "core/geometry/wheel_rail_geometry.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

constexpr double kGeomTolerance_m = 1e-9;  // spline and golden-section accuracy

TEST(WheelRailGeometry, FlatWheelLowersOntoCrown) {
  // A laterally straight wheel tread over a 300 mm crown shifted by 4 mm: first contact at the
  // crown top, whatever the shift; the gap there is zero and grows as y^2/(2R).
  const double R = 0.3;
  const Profile rail = testing::ArcProfile(R, +1.0, 0.15);
  const Profile wheel = testing::FunctionProfile([](double) { return 0.002; }, -0.05, 0.05, 201);
  WheelPose pose;
  pose.lateral_shift_m = 0.004;
  pose.rolling_radius_m = 0.46;
  const WheelRailGeometry g(wheel, rail, pose);
  ASSERT_TRUE(g.has_overlap());
  EXPECT_NEAR(g.dz_m(), -0.002, kGeomTolerance_m);  // the wheel's z = 2 mm line lands on z = 0
  const auto cands = g.FindCandidates(1e-4);
  ASSERT_EQ(cands.size(), 1u);
  const auto& c = cands[0];
  EXPECT_NEAR(c.y_m, 0.0, 1e-7);
  EXPECT_NEAR(c.gap_m, 0.0, kGeomTolerance_m);  // first contact: zero gap after lowering
  EXPECT_NEAR(c.rail_point_m.norm(), 0.0, 1e-6);
  EXPECT_NEAR(c.rail_lateral_curvature, 1.0 / R, 1e-6 / R);
  EXPECT_NEAR(c.wheel_lateral_curvature, 0.0, 1e-6);
  EXPECT_NEAR(c.wheel_radius_m, 0.462, 1e-9);
  EXPECT_NEAR(c.normal.y(), -1.0, 1e-9);
  // Interval where y^2/(2R) < 1e-4: |y| < sqrt(2 R 1e-4) = 7.746 mm.
  EXPECT_NEAR(c.y_lo_m, -std::sqrt(2 * R * 1e-4), 3e-5);
  EXPECT_NEAR(c.y_hi_m, std::sqrt(2 * R * 1e-4), 3e-5);
}

TEST(WheelRailGeometry, TwoPointContactGivesTwoCandidates) {
  // A wheel with two lobes over a flat rail: two separate candidates; the deeper lobe touches.
  const Profile rail = testing::FunctionProfile([](double) { return 0.0; }, -0.05, 0.05, 201);
  auto lobes = [](double y) {
    return -std::min(100.0 * (y + 0.02) * (y + 0.02), 30.0 * (y - 0.02) * (y - 0.02) + 5e-5);
  };
  const Profile wheel = testing::FunctionProfile(lobes, -0.045, 0.045, 901);
  const WheelRailGeometry g(wheel, rail, WheelPose{});
  const auto one = g.FindCandidates(2e-5);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].y_m, -0.02, 2e-5);
  const auto two = g.FindCandidates(1e-4);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[1].y_m, 0.02, 2e-5);
  EXPECT_NEAR(two[1].gap_m, 5e-5, 1e-7);
}

TEST(WheelRailGeometry, MeridianOfABodyOfRevolution) {
  // Rotating a wheel point about the axle keeps its meridian coordinates.
  const Profile rail = testing::ArcProfile(0.3, +1.0, 0.15);
  const Profile wheel =
      testing::FunctionProfile([](double y) { return 0.01 * y; }, -0.05, 0.05, 11);
  WheelPose pose;
  pose.roll_rad = 0.01;
  pose.lateral_shift_m = 0.003;
  const WheelRailGeometry g(wheel, rail, pose);
  const double r0 = pose.rolling_radius_m;
  const Eigen::Vector2d pw(0.007, 0.0005);       // in the wheel profile frame
  const Eigen::Vector2d pr = g.WheelToRail(pw);  // x = 0 cross-section, rail frame
  EXPECT_NEAR((g.RailToWheel(pr) - pw).norm(), 0.0, 1e-15);
  // Rotate about the axle by 0.1 rad: the axle is along the wheel's y axis at z_W = -r0.
  const double a = 0.1, rr = r0 + pw.y();
  const Eigen::Vector2d pw_rot_yz(pw.x(), rr * std::cos(a) - r0);
  const Eigen::Vector2d pr_rot = g.WheelToRail(pw_rot_yz);
  const Eigen::Vector3d p3(rr * std::sin(a), pr_rot.x(), pr_rot.y());
  EXPECT_NEAR((g.Meridian(p3) - pw).norm(), 0.0, 1e-12);
}

TEST(WheelRailGeometry, NoLateralOverlap) {
  const Profile rail = testing::ArcProfile(0.3, +1.0, 0.05);
  const Profile wheel = testing::FunctionProfile([](double) { return 0.0; }, -0.01, 0.01, 11);
  WheelPose pose;
  pose.lateral_shift_m = 0.5;
  const WheelRailGeometry g(wheel, rail, pose);
  EXPECT_FALSE(g.has_overlap());
  EXPECT_TRUE(g.FindCandidates(1.0).empty());
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

TEST(WheelRailGeometry, SaddleBelowThresholdSplitsCandidates) {
  // Two lobes 6 mm apart whose saddle (gap 45 um above the deeper lobe) lies below the
  // threshold: separate candidates while the saddle rises by more than a tenth of the
  // threshold above both minima, one candidate when the threshold dwarfs it.
  const Profile rail = testing::FunctionProfile([](double) { return 0.0; }, -0.05, 0.05, 201);
  auto lobes = [](double y) {
    return -std::min(10.0 * (y + 0.003) * (y + 0.003), 10.0 * (y - 0.003) * (y - 0.003) + 1e-5);
  };
  const Profile wheel = testing::FunctionProfile(lobes, -0.03, 0.03, 1201);
  const WheelRailGeometry g(wheel, rail, WheelPose{});
  const auto two = g.FindCandidates(2e-4);  // saddle ~ 90 um: prominence 80 um > 20 um
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[0].y_m, -0.003, 1e-6);
  EXPECT_NEAR(two[1].y_m, 0.003, 1e-6);
  EXPECT_NEAR(two[1].gap_m, 1e-5, 1e-8);
  EXPECT_TRUE(two[0].split_hi);
  EXPECT_TRUE(two[1].split_lo);
  EXPECT_NEAR(two[0].y_hi_m, two[1].y_lo_m, 2e-5);  // they meet at the saddle
  const auto one = g.FindCandidates(2e-3);          // prominence 80 um < 200 um: one basin
  ASSERT_EQ(one.size(), 1u);
  EXPECT_FALSE(one[0].split_lo || one[0].split_hi);
}

// A conical wheel (slope angle gamma toward the flange side) yawed by psi on a cylindrical rail
// crown: the contact point leads the axle by r tan(gamma) tan(psi) / cos(psi), r the wheel's
// radius at the contact (yawed_wheel.h), within 1 % up to 70 degrees and 20 mrad; without yaw
// it lies under the axle. The contact's lateral position agrees with a brute-force search of
// the 3-D surfaces' smallest vertical distance.
TEST(WheelRailGeometry, YawedConeOnCylinderLeadsByTheClosedForm) {
  const double R = 0.3, r0 = 0.46;
  const Profile rail = testing::ArcProfile(R, +1.0, 1.35, 1601);
  for (double gamma_deg : {10.0, 45.0, 70.0}) {
    const double tg = std::tan(gamma_deg * M_PI / 180.0);
    // Around the rail point at angle gamma: y_c = -R sin(gamma) (the gauge side of the crown).
    const double y_c = -R * std::sin(gamma_deg * M_PI / 180.0);
    const Profile cone =
        testing::FunctionProfile([tg](double y) { return -tg * y; }, -0.02, 0.02, 401);
    for (double psi : {0.0, 0.005, 0.0156, -0.02}) {
      WheelPose pose;
      pose.lateral_shift_m = y_c;
      pose.rolling_radius_m = r0;
      pose.yaw_rad = psi;
      const WheelRailGeometry g(cone, rail, pose);
      ASSERT_TRUE(g.has_overlap());
      const auto cands = g.FindCandidates(1e-5);
      ASSERT_EQ(cands.size(), 1u) << gamma_deg << " " << psi;
      const ContactCandidate& c = cands[0];
      const double closed = c.wheel_radius_m * tg * std::tan(psi) / std::cos(psi);
      EXPECT_NEAR(c.lead_m, closed, 0.01 * std::abs(closed) + 1e-12)
          << "gamma " << gamma_deg << " psi " << psi;
      if (psi == 0.0) {
        EXPECT_EQ(c.x_m, 0.0);
      }
      // Brute force on the 3-D surfaces: the cone point (y_w, theta) whose vertical distance to
      // the cylinder is smallest (nested golden sections), against the contact's x and y.
      auto gap = [&](double y_w, double th, double* x, double* y) {
        const double r = r0 - tg * y_w;
        *x = r * std::sin(th) * std::cos(psi) - y_w * std::sin(psi);
        *y = y_c + r * std::sin(th) * std::sin(psi) + y_w * std::cos(psi);
        return (R - std::sqrt(R * R - *y * *y)) - (r * std::cos(th) - r0);
      };
      auto golden = [](auto&& f, double a, double b) {
        const double k = 0.5 * (std::sqrt(5.0) - 1.0);
        while (b - a > 1e-12) {
          const double c1 = b - k * (b - a), d1 = a + k * (b - a);
          if (f(c1) < f(d1)) {
            b = d1;
          } else {
            a = c1;
          }
        }
        return 0.5 * (a + b);
      };
      double x = 0.0, y = 0.0;
      auto best_theta = [&](double y_w) {
        return golden([&](double th) { return gap(y_w, th, &x, &y); }, -0.2, 0.2);
      };
      const double y_w =
          golden([&](double yw) { return gap(yw, best_theta(yw), &x, &y); }, -0.015, 0.015);
      gap(y_w, best_theta(y_w), &x, &y);
      // The candidate's contact point is the projection of the sampled rail top (20 um samples)
      // onto the rail, which on a 70 degree face lands within about 1e-6 m of the exact point
      // along the profile; x follows the point along the wheel at a slope of about 0.2.
      constexpr double kContactPointTolerance_m = 2e-6;
      EXPECT_NEAR(c.x_m, x, kContactPointTolerance_m) << "gamma " << gamma_deg << " psi " << psi;
      EXPECT_NEAR(c.y_m, y, kContactPointTolerance_m) << "gamma " << gamma_deg << " psi " << psi;
    }
  }
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

// CandidateAt: at the smallest gap it is FindCandidates' candidate; elsewhere the rail point and
// normal of the crown at that lateral position (the planar grid's plane is moved there,
// core/contact/potential_area.h), clamped to the candidate's interval.
TEST(WheelRailGeometry, CandidateAtMovesTheContactPointAlongTheInterval) {
  const double R = 0.3;
  const Profile rail = testing::ArcProfile(R, +1.0, 0.15);
  const Profile wheel = testing::FunctionProfile([](double) { return 0.002; }, -0.05, 0.05, 201);
  WheelPose pose;
  pose.rolling_radius_m = 0.46;
  const WheelRailGeometry g(wheel, rail, pose);
  const auto cands = g.FindCandidates(1e-4);
  ASSERT_EQ(cands.size(), 1u);
  const ContactCandidate& c = cands[0];
  const ContactCandidate same = g.CandidateAt(c, c.y_m);
  EXPECT_NEAR(same.gap_m, c.gap_m, kGeomTolerance_m);
  EXPECT_NEAR((same.rail_point_m - c.rail_point_m).norm(), 0.0, kGeomTolerance_m);
  EXPECT_NEAR((same.normal - c.normal).norm(), 0.0, 1e-9);
  EXPECT_EQ(same.y_lo_m, c.y_lo_m);
  EXPECT_EQ(same.y_hi_m, c.y_hi_m);
  // 3 mm off the crown: the arc's height and tilted normal there; the smallest gap it is found
  // by stays the interval's.
  const double y = 0.003, z = R - std::sqrt(R * R - y * y);
  const ContactCandidate moved = g.CandidateAt(c, y);
  EXPECT_EQ(moved.y_m, c.y_m);
  EXPECT_EQ(moved.gap_m, c.gap_m);
  EXPECT_NEAR(moved.rail_point_m.x(), y, 1e-7);
  EXPECT_NEAR(moved.rail_point_m.y(), z, 1e-8);
  EXPECT_NEAR(moved.normal.x(), y / R, 1e-6);
  EXPECT_NEAR(moved.rail_lateral_curvature, 1.0 / R, 1e-6 / R);
  EXPECT_NEAR(moved.wheel_radius_m, 0.462, 1e-9);
  EXPECT_NEAR(g.CandidateAt(c, 1.0).rail_point_m.x(), c.y_hi_m, 1e-7);
}

// The yawed outline is shared between geometries of the same wheel, rolling radius and yaw
// (issue 18 point 3), and only then: a lateral shift keeps it, another yaw or radius, or a wheel
// one ulp different in one point, gets its own. Shared or not, a geometry's answers are those of
// one built alone (the shared outline is the one it would build).
TEST(WheelRailGeometry, YawedOutlineSharedOnlyForTheSameWheelRadiusAndYaw) {
  const Profile rail = testing::ArcProfile(0.3, +1.0, 0.2);
  const Profile wheel =
      testing::FunctionProfile([](double y) { return -0.05 * y; }, -0.02, 0.02, 401);
  std::vector<Eigen::Vector2d> moved = wheel.points();
  moved[200].y() = std::nextafter(moved[200].y(), 1.0);
  const Profile wheel_ulp(moved, wheel.source());
  WheelPose pose;
  pose.yaw_rad = 0.004;
  const WheelRailGeometry a(wheel, rail, pose);
  WheelPose shifted = pose;
  shifted.lateral_shift_m = 1e-3;
  const WheelRailGeometry b(wheel, rail, shifted);
  EXPECT_EQ(&a.wheel().profile(), &b.wheel().profile());
  WheelPose other_yaw = pose;
  other_yaw.yaw_rad = std::nextafter(pose.yaw_rad, 1.0);
  EXPECT_NE(&WheelRailGeometry(wheel, rail, other_yaw).wheel().profile(), &a.wheel().profile());
  WheelPose other_radius = pose;
  other_radius.rolling_radius_m = 0.45;
  EXPECT_NE(&WheelRailGeometry(wheel, rail, other_radius).wheel().profile(), &a.wheel().profile());
  EXPECT_NE(&WheelRailGeometry(wheel_ulp, rail, pose).wheel().profile(), &a.wheel().profile());
  // b's answers, from the shared outline, equal those of a geometry built after the cache has
  // been cycled through other yaws (so built anew).
  for (int k = 1; k <= 20; ++k) {
    WheelPose p = pose;
    p.yaw_rad = 0.001 * k;
    const WheelRailGeometry cycle(wheel, rail, p);
  }
  const WheelRailGeometry fresh(wheel, rail, shifted);
  EXPECT_NE(&fresh.wheel().profile(), &b.wheel().profile());
  const auto cb = b.FindCandidates(1e-5), cf = fresh.FindCandidates(1e-5);
  ASSERT_EQ(cb.size(), cf.size());
  ASSERT_FALSE(cb.empty());
  for (size_t i = 0; i < cb.size(); ++i) {
    EXPECT_EQ(cb[i].y_m, cf[i].y_m);
    EXPECT_EQ(cb[i].wheel_s_m, cf[i].wheel_s_m);
    EXPECT_EQ(cb[i].lead_m, cf[i].lead_m);
  }
  EXPECT_EQ(b.dz_m(), fresh.dz_m());
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

TEST(WheelRailGeometry, APlacementFromTheSharedSamplesIsTheFirstOnesBitForBit) {
  // The profiles' samples are shared by every later placement of the same profiles (a time
  // loop's new positions): a placement at a shift whose samples were made by another placement
  // is the placement that made them itself, bit for bit. Profiles no other test builds (a crown
  // radius of 0.2837 m), so that the first placement here samples them.
  const Profile rail = testing::ArcProfile(0.2837, +1.0, 0.15);
  const Profile wheel =
      testing::FunctionProfile([](double y) { return 0.002 + 0.05 * y * y; }, -0.05, 0.05, 201);
  auto place = [&](double shift_m) {
    WheelPose pose;
    pose.lateral_shift_m = shift_m;
    pose.roll_rad = 2e-3;
    return WheelRailGeometry(wheel, rail, pose);
  };
  const WheelRailGeometry first = place(0.003);  // samples both profiles
  const WheelRailGeometry other = place(-0.004);
  const WheelRailGeometry again = place(0.003);  // from the shared samples
  ASSERT_TRUE(first.has_overlap() && other.has_overlap());
  EXPECT_NE(first.dz_m(), other.dz_m());
  EXPECT_EQ(again.dz_m(), first.dz_m());
  const auto a = first.FindCandidates(1e-4), b = again.FindCandidates(1e-4);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].y_m, b[k].y_m);
    EXPECT_EQ(a[k].y_lo_m, b[k].y_lo_m);
    EXPECT_EQ(a[k].y_hi_m, b[k].y_hi_m);
    EXPECT_EQ(a[k].gap_m, b[k].gap_m);
    EXPECT_EQ(a[k].rail_point_m, b[k].rail_point_m);
  }
}

}  // namespace
}  // namespace railwear
