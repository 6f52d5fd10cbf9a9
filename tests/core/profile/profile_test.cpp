// Profile: arc length, tangent, normal and curvature of its spline on circles (analytic), the
// Mirrored/Transformed operations, validation messages, and the spline's power form against its
// knot form.
#include "core/profile/profile.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/numerics/cubic_spline.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/numerics/knot_form_spline.h"

namespace railwear {
namespace {

constexpr double kPi = std::numbers::pi;

// Points on a circle of radius r (m) centred at c, from angle a0 to a1 (rad), n intervals.
// Angle measured in the (y, z) plane: point = c + r (cos a, sin a).
std::vector<Eigen::Vector2d> Arc(const Eigen::Vector2d& c, double r, double a0, double a1, int n) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    pts.push_back(c + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return pts;
}

// A 10 mm circle sampled every 1 degree: spline errors O(h^4) ~ r (pi/180)^4 / 384 for position
// (about 2e-11 m); arc length follows; curvature is O(h^2): (pi/180)^2 ~ 3e-4 relative. Natural
// end conditions spoil the two end intervals, so interior checks stay away from them.
constexpr double kR = 10e-3;
constexpr int kIntervals = 120;  // 120 degrees, 1 degree each
constexpr double kLengthTol_m = 1e-11;
constexpr double kEndLengthTol_m = 5e-9;
constexpr double kTangentTol = 1e-6;
constexpr double kCurvatureRelTol = 1e-3;

TEST(Profile, ArcLengthOfACircle) {
  // Convex rail-crown-like arc: centre below (z down means +z is into the rail), points from
  // angle 210 to 330 degrees (top of the circle is at 270 degrees, z = -r).
  const Profile p(Arc({0, 0}, kR, 210 * kPi / 180, 330 * kPi / 180, kIntervals), "arc");
  // The natural end conditions bend the two end intervals slightly (measured 1.8e-9 m of the
  // 2.1e-2 m total); the interior intervals are arc lengths to O(h^4).
  EXPECT_NEAR(p.Length(), kR * 120 * kPi / 180, kEndLengthTol_m);
  for (int i = 10; i <= kIntervals - 10; i += 10) {
    EXPECT_NEAR(p.KnotS(i) - p.KnotS(10), kR * (i - 10) * kPi / 180, kLengthTol_m) << "knot " << i;
  }
  // Position at an arc-length parameter lies on the circle at the matching angle.
  const double s = 0.5 * p.Length();
  EXPECT_NEAR(p.Position(s).x(), 0.0, 1e-10);
  EXPECT_NEAR(p.Position(s).y(), -kR, 1e-10);
  const double s40 = p.KnotS(10) + kR * 30 * kPi / 180;  // 250 degrees
  EXPECT_NEAR(p.Position(s40).x(), kR * std::cos(250 * kPi / 180), 1e-10);
  EXPECT_NEAR(p.Position(s40).y(), kR * std::sin(250 * kPi / 180), 1e-10);
}

TEST(Profile, TangentNormalAndCurvatureSign) {
  // Same arc, counter-clockwise in (y, z): y increases from left to right over the top, like
  // the convex crown of a rail (z down). LeftNormal = (-t_z, t_y) points to +z at the top:
  // toward the centre, so the curve turns toward the left normal: curvature = +1/r.
  const Profile p(Arc({0, 0}, kR, 210 * kPi / 180, 330 * kPi / 180, kIntervals), "arc");
  for (int deg = 230; deg <= 310; deg += 20) {
    const double a = deg * kPi / 180;
    const double s = kR * (a - 210 * kPi / 180);
    const Eigen::Vector2d t = p.Tangent(s);
    EXPECT_NEAR(t.x(), -std::sin(a), kTangentTol) << deg;
    EXPECT_NEAR(t.y(), std::cos(a), kTangentTol) << deg;
    EXPECT_NEAR(t.norm(), 1.0, 1e-12);
    const Eigen::Vector2d n = p.LeftNormal(s);
    EXPECT_NEAR(n.x(), -std::cos(a), kTangentTol) << deg;  // toward the centre
    EXPECT_NEAR(n.y(), -std::sin(a), kTangentTol) << deg;
    EXPECT_NEAR(n.dot(t), 0.0, 1e-12);
    EXPECT_NEAR(p.Curvature(s) * kR, 1.0, kCurvatureRelTol) << deg;
  }
  // Traversed the other way, the curvature changes sign.
  auto pts = p.points();
  std::reverse(pts.begin(), pts.end());
  const Profile q(pts, "reversed arc");
  EXPECT_NEAR(q.Curvature(0.5 * q.Length()) * kR, -1.0, kCurvatureRelTol);
  // Evaluate agrees with the single calls.
  Eigen::Vector2d pos, d1, d2;
  p.Evaluate(0.3 * p.Length(), &pos, &d1, &d2);
  EXPECT_EQ(pos, p.Position(0.3 * p.Length()));
  EXPECT_EQ(d1, p.Derivative(0.3 * p.Length()));
  EXPECT_NEAR(d1.norm(), 1.0, kTangentTol);  // s is an arc length
}

TEST(Profile, Bounds) {
  const Profile p({{-1e-3, 2e-3}, {0, 0}, {1e-3, 1e-3}, {3e-3, 4e-3}});
  const auto b = p.bounds();
  EXPECT_EQ(b.y_min, -1e-3);
  EXPECT_EQ(b.y_max, 3e-3);
  EXPECT_EQ(b.z_min, 0.0);
  EXPECT_EQ(b.z_max, 4e-3);
}

// A copy shares the original's data (O(1), no 100 kB block per copy); set_source gives the copy
// its own, leaving the original as it was; a default Profile is empty.
TEST(Profile, CopiesShareTheirDataAndSetSourceCopiesIt) {
  const Profile p({{-1e-3, 2e-3}, {0, 0}, {1e-3, 1e-3}, {3e-3, 4e-3}}, "original");
  Profile q = p;
  EXPECT_EQ(&q.points(), &p.points());
  EXPECT_EQ(q.Position(0.5 * p.Length()), p.Position(0.5 * p.Length()));
  q.set_source("renamed");
  EXPECT_EQ(q.source(), "renamed");
  EXPECT_EQ(p.source(), "original");
  EXPECT_NE(&q.points(), &p.points());
  EXPECT_EQ(q.points(), p.points());
  EXPECT_EQ(q.Length(), p.Length());
  EXPECT_EQ(Profile().size(), 0);
  EXPECT_TRUE(Profile().points().empty());
}

TEST(Profile, MirroredFlipsYAndKeepsTheSenseOfTraversal) {
  const Profile p(Arc({1e-3, 0}, kR, 200 * kPi / 180, 300 * kPi / 180, 100), "arc");
  const Profile m = p.Mirrored();
  ASSERT_EQ(m.size(), p.size());
  EXPECT_EQ(m.source(), "arc");
  for (int i = 0; i < p.size(); ++i) {
    const auto& a = p.points()[i];
    const auto& b = m.points()[p.size() - 1 - i];
    EXPECT_EQ(b.x(), -a.x());
    EXPECT_EQ(b.y(), a.y());
  }
  EXPECT_NEAR(m.Length(), p.Length(), 1e-15);
  // A mirror image traversed in reverse turns the same way: curvature keeps its sign.
  EXPECT_NEAR(m.Curvature(0.4 * m.Length()), p.Curvature(0.6 * p.Length()), 1e-6 / kR);
  EXPECT_GT(m.Curvature(0.5 * m.Length()), 0.0);
}

TEST(Profile, TransformedRotatesYTowardZThenShifts) {
  const Profile p({{0, 0}, {1e-3, 0}, {2e-3, 0}, {3e-3, 0}}, "line");
  const Profile q = p.Transformed(kPi / 2, Eigen::Vector2d(0.5e-3, -1e-3));
  // +90 degrees turns +y into +z.
  EXPECT_NEAR(q.points()[3].x(), 0.5e-3, 1e-15);
  EXPECT_NEAR(q.points()[3].y(), 3e-3 - 1e-3, 1e-15);
  EXPECT_EQ(q.source(), "line");
  // Rigid motion: length and curvature unchanged.
  const Profile arc(Arc({0, 0}, kR, 210 * kPi / 180, 330 * kPi / 180, kIntervals));
  const Profile moved = arc.Transformed(0.3, Eigen::Vector2d(2e-3, 5e-3));
  EXPECT_NEAR(moved.Length(), arc.Length(), 1e-12);
  EXPECT_NEAR(moved.Curvature(0.5 * moved.Length()), arc.Curvature(0.5 * arc.Length()), 1e-6);
}

void ExpectProfileError(std::vector<Eigen::Vector2d> pts,
                        std::initializer_list<std::string> parts) {
  try {
    Profile p(std::move(pts), "test.csv");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.csv"), std::string::npos) << msg;
    for (const auto& part : parts) EXPECT_NE(msg.find(part), std::string::npos) << msg;
  }
}

TEST(Profile, ValidationErrors) {
  ExpectProfileError({{0, 0}, {1, 0}, {2, 0}}, {"3 point(s)", "at least 4"});
  ExpectProfileError({{0, 0}, {1e-3, 0}, {2e-3, std::nan("")}, {3e-3, 0}},
                     {"point 3", "non-finite"});
  ExpectProfileError({{0, 0}, {1e-3, 0}, {1e-3, 0}, {3e-3, 0}}, {"point 3", "duplicates point 2"});
  ExpectProfileError({{0, 0}, {1e-3, 0}, {2e-3, 0}, {1.5e-3, 1e-5}, {3e-3, 0}},
                     {"point 4", "turn back"});
  // A sharp but legal turn (120 degrees) is accepted.
  EXPECT_NO_THROW(Profile({{0, 0}, {1e-3, 0}, {2e-3, 0}, {1.5e-3, 0.866e-3}, {1e-3, 1.732e-3}}));
  // Without a source the message still says what failed.
  try {
    Profile({{0, 0}});
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("profile: 1 point(s)"), std::string::npos) << e.what();
  }
}

// Profile::Evaluate (the power form of core/numerics/cubic_spline.h) against the knot form of
// the built-in profiles' splines (tests/core/numerics/knot_form_spline.h), whose knots are the
// points at their arc lengths (no segment is subdivided: a subdivided one would put the
// difference at the spline's own error, far above the bound). At the points the position and both
// derivatives are the knot form's bit for bit; at 20 000 random s between them the position is
// within 1e-14 of the profile's size (0.15 to 0.2 m: some 1e-15 m), the tangent within 1e-14
// (it has unit length) and the second derivative within 1e-14 of its largest value: rounding, a
// few ulps of each (measured at most 1.3e-16, 3.1e-16 and 1.9e-16: a margin of 30).
constexpr double kPowerFormRelTol = 1e-14;

TEST(ProfileSpline, IsTheKnotFormOfItsPointsWithinRounding) {
  std::mt19937 rng(20);  // fixed seed
  for (const Profile& p : {MakeS1002(), MakeUic60()}) {
    const int n = p.size();
    std::vector<double> s(n), y(n), z(n);
    for (int i = 0; i < n; ++i) {
      s[i] = p.KnotS(i);
      y[i] = p.points()[i].x();
      z[i] = p.points()[i].y();
    }
    const CubicSpline sy(s, y), sz(s, z);
    testing::KnotFormSpline ky{s, y, std::vector<double>(n)}, kz{s, z, std::vector<double>(n)};
    for (int i = 0; i < n; ++i) {
      ky.m[i] = sy.SecondDerivative(s[i]);
      kz.m[i] = sz.SecondDerivative(s[i]);
    }
    const auto knot_form = [&](double x, Eigen::Vector2d* q, Eigen::Vector2d* d1,
                               Eigen::Vector2d* d2) {
      ky.Evaluate(x, &q->x(), &d1->x(), &d2->x());
      kz.Evaluate(x, &q->y(), &d1->y(), &d2->y());
    };
    for (int i = 0; i < n; ++i) {
      Eigen::Vector2d a0, a1, a2, b0, b1, b2;
      p.Evaluate(s[i], &a0, &a1, &a2);
      knot_form(s[i], &b0, &b1, &b2);
      ASSERT_EQ(a0, b0) << p.source() << " point " << i;
      ASSERT_EQ(a1, b1) << p.source() << " point " << i;
      ASSERT_EQ(a2, b2) << p.source() << " point " << i;
    }
    std::uniform_real_distribution<double> u(0.0, p.Length());
    std::vector<double> queries;
    for (int k = 0; k < 20000; ++k) queries.push_back(u(rng));
    const Profile::Bounds b = p.bounds();
    const double size = std::max(b.y_max - b.y_min, b.z_max - b.z_min);
    double max_d2 = 0.0;
    for (double x : queries) {
      Eigen::Vector2d b0, b1, b2;
      knot_form(x, &b0, &b1, &b2);
      max_d2 = std::max(max_d2, b2.norm());
    }
    double value = 0.0, d1 = 0.0, d2 = 0.0;
    for (double x : queries) {
      Eigen::Vector2d a0, a1, a2, b0, b1, b2;
      p.Evaluate(x, &a0, &a1, &a2);
      knot_form(x, &b0, &b1, &b2);
      value = std::max(value, (a0 - b0).norm() / size);
      d1 = std::max(d1, (a1 - b1).norm());
      d2 = std::max(d2, (a2 - b2).norm() / max_d2);
    }
    EXPECT_LE(value, kPowerFormRelTol) << p.source();
    EXPECT_LE(d1, kPowerFormRelTol) << p.source();
    EXPECT_LE(d2, kPowerFormRelTol) << p.source();
  }
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

TEST(ProfileSpline, FollowsACoarselySampledWallWithoutOvershoot) {
  // A flat shoulder meeting a steep wall sampled at a fixed lateral step, as in the shared
  // groove files: segments of 0.1 mm next to one of 1.26 mm. A natural spline through these
  // points swings 0.22 mm out from the wall; subdividing the long chord keeps it within 0.03 mm
  // of the polyline — what remains is the rounding of a C2 curve through the 83-degree corner,
  // about a fifth of the 0.1 mm point spacing there.
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 6; ++i) pts.emplace_back(-10.54e-3 + 1e-4 * i, -10.02e-3);  // shoulder
  for (double y : {-9.94, -9.84, -9.74, -9.64, -9.54, -9.44}) {
    const double R = 10.02;
    pts.emplace_back(y * 1e-3, -(R - std::sqrt(R * R - y * y)) * 1e-3);  // groove arc
  }
  const Profile p(pts, "wall");
  double worst = 0.0;
  for (double s = 0.0; s <= p.Length(); s += 1e-6) {
    const Eigen::Vector2d q = p.Position(s);
    double d = 1e9;
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      const Eigen::Vector2d a = pts[k], b = pts[k + 1];
      const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      d = std::min(d, (a + t * (b - a) - q).norm());
    }
    worst = std::max(worst, d);
  }
  EXPECT_LT(worst, 3e-5);
  // Point arc lengths still name the points.
  for (int i = 0; i < p.size(); ++i)
    EXPECT_NEAR((p.Position(p.KnotS(i)) - pts[i]).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace railwear
