#include "core/geometry/yawed_wheel.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"
#include "core/profile/profile_io.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// Golden-section maximisation of f on [a, b] (an independent brute force for the outline).
template <typename F>
double ArgMax(F&& f, double a, double b) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  while (b - a > 1e-13) {
    if (f(c) > f(d)) {
      b = d;
    } else {
      a = c;
    }
    c = b - g * (b - a);
    d = a + g * (b - a);
  }
  return 0.5 * (a + b);
}

// The outline's Z at lateral position Y (bisection on the outline's arc length; Y increases
// along a cone profile sampled with increasing y).
double OutlineZAt(const Profile& outline, double Y) {
  double lo = 0.0, hi = outline.Length();
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (lo + hi);
    (outline.Position(m).x() < Y ? lo : hi) = m;
  }
  return outline.Position(0.5 * (lo + hi)).y();
}

TEST(YawedWheelSection, ZeroYawOutlineIsTheProfile) {
  const Profile wheel = testing::ArcProfile(0.01, -1.0, 1.2, 401);
  const YawedWheelSection yawed(wheel, 0.46, 0.0);
  for (double s = 0.0; s <= wheel.Length(); s += wheel.Length() / 37) {
    const auto src = yawed.SourceAt(s * yawed.outline().Length() / wheel.Length());
    EXPECT_NEAR(src.x_m, 0.0, 1e-15);
    EXPECT_NEAR((yawed.outline().Position(s) - wheel.Position(s)).norm(), 0.0, 1e-9);
  }
}

// A conical wheel (slope angle gamma, flange side at negative y) yawed by psi: the outline
// against a brute-force maximisation of the 3-D surface's depth at fixed lateral position, and
// the lead of the contact point against the closed form r tan(gamma) tan(psi) / cos(psi), up to
// 70 degrees and 20 mrad (the issue asks for 1 %; the outline is exact, so the bound here is the
// spline's and the brute force's accuracy).
TEST(YawedWheelSection, ConeOutlineAndLeadMatchTheClosedForm) {
  const double r0 = 0.46;
  for (double gamma_deg : {3.0, 30.0, 50.0, 70.0}) {
    const double tg = std::tan(gamma_deg * M_PI / 180.0);
    // z rises toward negative y (toward the flange): r = r0 - tg y.
    const Profile cone =
        testing::FunctionProfile([tg](double y) { return -tg * y; }, -0.01, 0.01, 201);
    for (double psi : {-0.02, 0.002, 0.0156, 0.02}) {
      const YawedWheelSection yawed(cone, r0, psi);
      EXPECT_NEAR(
          YawedWheelSection::SinTheta({std::sin(std::atan(tg)), std::cos(std::atan(tg))}, psi),
          tg * std::tan(psi), 1e-15);
      for (double y_w : {-0.004, 0.0, 0.005}) {
        // Brute force: at the lateral position of the outline point of y_w, the deepest point of
        // the surface, over theta (y_w follows from the lateral position, Y linear in y_w).
        const double r_w = r0 - tg * y_w;
        const double sin_t = tg * std::tan(psi);
        const double Y = r_w * sin_t * std::sin(psi) + y_w * std::cos(psi);
        auto y_of_theta = [&](double th) {
          // Y = (r0 - tg y) sin(th) sin(psi) + y cos(psi)  ->  y
          return (Y - r0 * std::sin(th) * std::sin(psi)) /
                 (std::cos(psi) - tg * std::sin(th) * std::sin(psi));
        };
        auto depth = [&](double th) { return (r0 - tg * y_of_theta(th)) * std::cos(th) - r0; };
        const double th = ArgMax(depth, -0.5, 0.5);
        const double x_brute = (r0 - tg * y_of_theta(th)) * std::sin(th) * std::cos(psi) -
                               y_of_theta(th) * std::sin(psi);
        EXPECT_NEAR(OutlineZAt(yawed.outline(), Y), depth(th), 1e-10)
            << "gamma " << gamma_deg << " psi " << psi << " y " << y_w;
        const auto src = yawed.SourceOf({Y, depth(th)});
        // Golden section finds a flat maximum's theta to about sqrt(machine epsilon), 1.5e-8
        // rad, so the brute force's x is good to about r 1.5e-8 = 7e-9 m.
        constexpr double kBruteForceX_m = 5e-8;
        EXPECT_NEAR(src.x_m, x_brute, kBruteForceX_m);
        // Lead of the point over the axle line through it (x_axle = -Y tan(psi)).
        const double lead = src.x_m + Y * std::tan(psi);
        const double closed = r_w * tg * std::tan(psi) / std::cos(psi);
        EXPECT_NEAR(lead, closed, 1e-3 * std::abs(closed) + 1e-9)
            << "gamma " << gamma_deg << " psi " << psi;
      }
    }
  }
}

// The outline follows the surface normal, so ripples in a profile's slope move its points round
// the wheel: on a steep face yawed far enough they fold the outline back on itself, which the
// profile's own check refuses ("turns back on itself"). Samples that step back against the
// profile's direction are hidden behind the rest of the silhouette and dropped. Here a 76 deg
// flange face with a 1 um ripple of 60 um wavelength (a measured profile's noise) at 20 mrad.
TEST(YawedWheelSection, RippledSteepFaceBuildsWithoutFolding) {
  const double tg = std::tan(76.0 * M_PI / 180.0), amplitude = 1e-6, wavelength = 60e-6;
  const Profile face = testing::FunctionProfile(
      [&](double y) { return -tg * y + amplitude * std::sin(2.0 * M_PI * y / wavelength); },
      -2e-3, 2e-3, 801);
  const double psi = 0.02, r0 = 0.46;
  const YawedWheelSection yawed(face, r0, psi);
  const Profile& outline = yawed.outline();
  const int samples = static_cast<int>(std::ceil(face.Length() / 2e-5)) + 1;
  std::printf("[ measured ] rippled face: %d of %d samples kept\n", outline.size(), samples);
  EXPECT_LT(outline.size(), samples);  // the ripple did fold the outline
  EXPECT_GT(outline.size(), samples / 2);
  // Every kept point steps forward along the profile, and is the exact outline point of its
  // source (the closed form of yawed_wheel.h at the source's normal).
  // Outward: the normal with +z at the face's deepest end (its start, y = -2 mm).
  const double outward = face.LeftNormal(0.0).y() > 0 ? 1.0 : -1.0;
  for (int k = 0; k < outline.size(); ++k) {
    const auto src = yawed.SourceAt(outline.KnotS(k));
    const Eigen::Vector2d p = face.Position(src.wheel_s_m);
    const double sin_t =
        YawedWheelSection::SinTheta(outward * face.LeftNormal(src.wheel_s_m), psi);
    const double r = r0 + p.y();
    const Eigen::Vector2d expected(r * sin_t * std::sin(psi) + p.x() * std::cos(psi),
                                   r * std::sqrt(1.0 - sin_t * sin_t) - r0);
    EXPECT_NEAR((outline.points()[k] - expected).norm(), 0.0, 1e-12) << k;
    if (k > 0) {
      EXPECT_GT((outline.points()[k] - outline.points()[k - 1]).dot(face.Tangent(src.wheel_s_m)), 0.0)
          << k;
    }
  }
}

// A smooth profile keeps every sample, so the outline is what it was before folds were dropped
// (the S1002 wheel at the yaw of curving and beyond).
TEST(YawedWheelSection, SmoothProfileKeepsEverySample) {
  const Profile s1002 = MakeS1002();
  const int samples = static_cast<int>(std::ceil(s1002.Length() / 2e-5)) + 1;
  for (double psi : {-0.02, 0.001, 0.005, 0.02}) {
    const YawedWheelSection yawed(s1002, 0.46, psi);
    EXPECT_EQ(yawed.outline().size(), samples) << psi;
  }
}

// The measured wheels of ../shared at the yaw of curving: avg_wheel.whl's flange-face slope
// noise folded its outline near y = -43.5 mm (turned back), Car7216_0001r.whl's nearly vertical
// flange back crossed itself near y = -54 mm, and the yawed contact refused both wheels.
TEST(YawedWheelSection, MeasuredWheelsBuildAtYaw) {
  for (const char* name : {"avg_wheel.whl", "Car7216_0001r.whl"}) {
    const std::filesystem::path file =
        std::filesystem::path(RAILWEAR_SHARED_DIR) / "data/profiles" / name;
    if (!std::filesystem::exists(file)) {
      GTEST_SKIP() << file << " is absent (../shared beside the checkout): the measured-wheel "
                      "case needs it";
    }
    const Profile wheel = ReadProfileFile(file.string()).profile;
    for (double psi : {-0.005, 0.004, 0.005, 0.02}) {
      const YawedWheelSection yawed(wheel, 0.46, psi);
      EXPECT_GT(yawed.outline().size(), 1000) << name << " " << psi;
    }
  }
}

TEST(YawedWheelSection, SteepFacesAreHeldAtTheBound) {
  // A vertical face (n_z = 0) has no outline point: theta is held at the bound, sign by n_y psi.
  EXPECT_DOUBLE_EQ(YawedWheelSection::SinTheta({1.0, 0.0}, 0.01), YawedWheelSection::kMaxSinTheta);
  EXPECT_DOUBLE_EQ(YawedWheelSection::SinTheta({-1.0, 0.0}, 0.01),
                   -YawedWheelSection::kMaxSinTheta);
  EXPECT_DOUBLE_EQ(YawedWheelSection::SinTheta({1.0, 0.0}, 0.0), 0.0);
}

TEST(YawedWheelSection, SinThetaFromTanIsSinThetaBitForBit) {
  // The fast tread path takes tan(yaw) once per pose (core/contact/hertz_tread.cpp): the same
  // value as SinTheta's, exactly, for normals all round (steep faces at the bound included) and
  // yaws of either sign up to the constructor's bound.
  for (double yaw : {-0.4, -0.02, -5e-3, -1e-6, 0.0, 1e-6, 5e-3, 0.02, 0.4}) {
    for (int k = 0; k < 360; ++k) {
      const double a = k * 3.14159265358979323846 / 180.0;
      const Eigen::Vector2d n(std::sin(a), std::cos(a));
      EXPECT_EQ(YawedWheelSection::SinThetaFromTan(n, std::tan(yaw)),
                YawedWheelSection::SinTheta(n, yaw))
          << "yaw " << yaw << " normal angle " << k << " deg";
    }
  }
}

}  // namespace
}  // namespace railwear
