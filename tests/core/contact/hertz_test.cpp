// Tests of hertz.h against the computed cases and exact checks of reference README §1.
#include "core/contact/hertz.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

namespace railwear {
namespace {

// The reference table prints 5 significant figures: half a unit in the 5th figure is up to
// 5e-5 relative for leading digit 1 (e.g. 1237.6); 2e-4 leaves room for the rounding of the
// inputs and is still far tighter than any modelling error.
constexpr double kTableRelTol = 2e-4;
// Exact identities (round trips, scaling laws): limited by the root finder's 1e-14 and the
// elliptic integrals' double precision.
constexpr double kExactRelTol = 1e-10;
// Check values K(m = 0.5), E(m = 0.5) are printed to 11 significant figures.
constexpr double kEllipticAbsTol = 1e-10;

double ContactModulusSame(double E, double nu) { return E / (2.0 * (1.0 - nu * nu)); }

struct HertzCase {
  const char* name;
  double force_N;
  double nu;
  double r_wheel_mm;  // rolling radius, curvature along x
  double r_rail_mm;   // rail lateral radius, curvature along y (wheel laterally flat)
  double a_mm, b_mm, area_mm2, p0_MPa, delta_um;
};

// reference README §1, "Computed cases" (E = 210 GPa).
constexpr HertzCase kCases[] = {
    {"H1", 100e3, 0.30, 460, 300, 7.1617, 5.3872, 121.21, 1237.6, 104.12},
    {"H2", 125e3, 0.30, 460, 300, 7.7147, 5.8032, 140.65, 1333.1, 120.82},
    {"H3", 100e3, 0.30, 460, 80, 8.5419, 2.7008, 72.48, 2069.6, 124.90},
    {"H4", 10e3, 0.28, 460, 300, 3.3382, 2.5111, 26.33, 569.6, 22.62},
};

void ExpectRel(double actual, double expected, double rel, const char* what, const char* name) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << name << " " << what;
}

TEST(Hertz, ComputedCasesH1ToH4) {
  for (const HertzCase& c : kCases) {
    const double A = 1.0 / (2.0 * c.r_wheel_mm * 1e-3);
    const double B = 1.0 / (2.0 * c.r_rail_mm * 1e-3);
    const HertzSolution s = SolveHertz(A, B, ContactModulusSame(210e9, c.nu), c.force_N);
    ExpectRel(s.semi_axis_x_m * 1e3, c.a_mm, kTableRelTol, "a", c.name);
    ExpectRel(s.semi_axis_y_m * 1e3, c.b_mm, kTableRelTol, "b", c.name);
    ExpectRel(s.area_m2 * 1e6, c.area_mm2, kTableRelTol, "area", c.name);
    ExpectRel(s.p0_Pa * 1e-6, c.p0_MPa, kTableRelTol, "p0", c.name);
    ExpectRel(s.approach_m * 1e6, c.delta_um, kTableRelTol, "delta", c.name);
    EXPECT_EQ(s.force_N, c.force_N);
  }
}

TEST(Hertz, IndependentCodeCase) {
  // reference README §1 "Code": G = 82 000 MPa, nu = 0.28; A, B printed to 6 figures.
  const double nu = 0.28;
  const double E = 2.0 * 82000e6 * (1.0 + nu);
  const HertzSolution s =
      SolveHertz(8.46419e-4 * 1e3, 2.40616e-3 * 1e3, ContactModulusSame(E, nu), 82000.0);
  ExpectRel(s.semi_axis_x_m * 1e3, 8.0, kTableRelTol, "a", "code");
  ExpectRel(s.semi_axis_y_m * 1e3, 4.0, kTableRelTol, "b", "code");
  ExpectRel(s.p0_Pa * 1e-6, 1223.5, kTableRelTol, "p0", "code");
  ExpectRel(s.approach_m * 1e3, 0.09267, kTableRelTol, "delta", "code");
}

TEST(Hertz, EllipticIntegralCheckValues) {
  // reference README §1: at e^2 = 0.5, K = 1.8540746773, E = 1.3506438810.
  EXPECT_NEAR(internal::CompleteEllipticK(0.5), 1.8540746773, kEllipticAbsTol);
  EXPECT_NEAR(internal::CompleteEllipticE(0.5), 1.3506438810, kEllipticAbsTol);
  EXPECT_NEAR(internal::CompleteEllipticK(0.0), std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(internal::CompleteEllipticE(0.0), std::numbers::pi / 2, 1e-15);
}

TEST(Hertz, CircleMatchesSphereFormula) {
  // A = B = 1/(2R): a^3 = 3 P R / (4 E*), delta = a^2 / R (exact).
  const double R = 0.05, Estar = 1.2e11, P = 3000.0;
  const HertzSolution s = SolveHertz(1.0 / (2 * R), 1.0 / (2 * R), Estar, P);
  const double a = std::cbrt(3.0 * P * R / (4.0 * Estar));
  EXPECT_NEAR(s.semi_axis_x_m, a, kExactRelTol * a);
  EXPECT_NEAR(s.semi_axis_y_m, a, kExactRelTol * a);
  EXPECT_NEAR(s.approach_m, a * a / R, kExactRelTol * a * a / R);
  EXPECT_NEAR(s.p0_Pa, 3.0 * P / (2.0 * std::numbers::pi * a * a), 1e-6);
}

TEST(Hertz, NearCircleIsContinuous) {
  // Across the series/closed-form switch at B/A - 1 = 1e-6 the solution must not jump.
  const double Estar = 1.2e11, P = 1000.0, A = 10.0;
  const HertzSolution s1 = SolveHertz(A, A * (1 + 0.9e-6), Estar, P);
  const HertzSolution s2 = SolveHertz(A, A * (1 + 1.1e-6), Estar, P);
  EXPECT_NEAR(s1.semi_axis_x_m, s2.semi_axis_x_m, 1e-7 * s1.semi_axis_x_m);
  EXPECT_NEAR(s1.semi_axis_y_m, s2.semi_axis_y_m, 1e-7 * s1.semi_axis_y_m);
  EXPECT_GT(s1.semi_axis_x_m, s1.semi_axis_y_m);
}

TEST(Hertz, SwappingCurvaturesSwapsAxes) {
  const double Estar = 1.1e11, P = 5e4;
  const HertzSolution s = SolveHertz(1.0, 3.0, Estar, P);
  const HertzSolution t = SolveHertz(3.0, 1.0, Estar, P);
  EXPECT_GT(s.semi_axis_x_m, s.semi_axis_y_m);  // major axis along the smaller curvature
  EXPECT_DOUBLE_EQ(s.semi_axis_x_m, t.semi_axis_y_m);
  EXPECT_DOUBLE_EQ(s.semi_axis_y_m, t.semi_axis_x_m);
  EXPECT_DOUBLE_EQ(s.p0_Pa, t.p0_Pa);
  EXPECT_DOUBLE_EQ(s.approach_m, t.approach_m);
}

TEST(Hertz, ExtremeRatiosSatisfyTheAxisEquation) {
  // B/A from 1e-4 to 1e4: the axis ratio found must reproduce B/A through the exact relation,
  // and p0 = 3P/(2 pi a b) must hold.
  const double Estar = 1.15e11, P = 2e4;
  for (double ratio : {1e-4, 1e-3, 0.1, 0.5, 2.0, 10.0, 1e3, 1e4}) {
    const double A = 2.0, B = A * ratio;
    const HertzSolution s = SolveHertz(A, B, Estar, P);
    const double a = std::max(s.semi_axis_x_m, s.semi_axis_y_m);
    const double b = std::min(s.semi_axis_x_m, s.semi_axis_y_m);
    const double g = b / a;
    const double m = 1.0 - g * g;
    const double K = internal::CompleteEllipticK(m), E = internal::CompleteEllipticE(m);
    const double r = ((a / b) * (a / b) * E - K) / (K - E);
    const double expected = std::max(ratio, 1.0 / ratio);
    EXPECT_NEAR(r, expected, 1e-8 * expected) << "B/A = " << ratio;
    EXPECT_NEAR(s.p0_Pa, 3 * P / (2 * std::numbers::pi * a * b), 1e-10 * s.p0_Pa);
    // The major axis lies along the smaller curvature.
    if (ratio > 1) {
      EXPECT_GT(s.semi_axis_x_m, s.semi_axis_y_m);
    } else {
      EXPECT_LT(s.semi_axis_x_m, s.semi_axis_y_m);
    }
  }
}

TEST(Hertz, ForceApproachRoundTrip) {
  const double A = 1.0 / 0.92, B = 1.0 / 0.16, Estar = ContactModulusSame(210e9, 0.3);
  for (double P : {1.0, 1e3, 1e5}) {
    const HertzSolution s = SolveHertz(A, B, Estar, P);
    const HertzSolution t = SolveHertzForApproach(A, B, Estar, s.approach_m);
    EXPECT_NEAR(t.force_N, P, kExactRelTol * P);
    EXPECT_NEAR(t.semi_axis_x_m, s.semi_axis_x_m, kExactRelTol * s.semi_axis_x_m);
    EXPECT_NEAR(t.p0_Pa, s.p0_Pa, kExactRelTol * s.p0_Pa);
  }
  // delta ~ P^(2/3): doubling P multiplies delta by 2^(2/3).
  const double d1 = SolveHertz(A, B, Estar, 1e4).approach_m;
  const double d2 = SolveHertz(A, B, Estar, 2e4).approach_m;
  EXPECT_NEAR(d2 / d1, std::cbrt(4.0), kExactRelTol);
}

TEST(Hertz, ZeroLoadAndBadInput) {
  const HertzSolution s = SolveHertz(1.0, 2.0, 1e11, 0.0);
  EXPECT_EQ(s.area_m2, 0.0);
  EXPECT_EQ(s.p0_Pa, 0.0);
  EXPECT_EQ(SolveHertzForApproach(1.0, 2.0, 1e11, 0.0).force_N, 0.0);
  try {
    SolveHertz(0.0, 2.0, 1e11, 1.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("curvature A"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SolveHertz(1.0, -2.0, 1e11, 1.0), std::invalid_argument);
  EXPECT_THROW(SolveHertz(1.0, 2.0, 1e11, -1.0), std::invalid_argument);
}

// SolveHertz's arithmetic as it was before HertzShape kept the axis ratio (issue 18): the ratio
// and the elliptic integrals found inside every call. The reference of the bit-for-bit tests.
HertzSolution SolveHertzFoundPerCall(double A, double B, double Estar, double P) {
  HertzSolution s;
  s.force_N = P;
  if (P == 0.0) return s;
  const double g = internal::HertzAxisRatio(std::max(A, B) / std::min(A, B));
  const double m = (1.0 - g) * (1.0 + g);
  const double k = internal::CompleteEllipticK(m);
  const double e = internal::CompleteEllipticE(m);
  const double pi = std::numbers::pi;
  const double c = std::cbrt(3.0 * P * e / (2.0 * pi * Estar * (A + B) * std::sqrt(g)));
  const double a = c / std::sqrt(g);
  const double b = c * std::sqrt(g);
  s.p0_Pa = 3.0 * P / (2.0 * pi * a * b);
  s.approach_m = s.p0_Pa * b * k / Estar;
  s.area_m2 = pi * a * b;
  s.semi_axis_x_m = A <= B ? a : b;
  s.semi_axis_y_m = A <= B ? b : a;
  return s;
}

void ExpectSameBits(const HertzSolution& s, const HertzSolution& t) {
  EXPECT_EQ(s.semi_axis_x_m, t.semi_axis_x_m);
  EXPECT_EQ(s.semi_axis_y_m, t.semi_axis_y_m);
  EXPECT_EQ(s.p0_Pa, t.p0_Pa);
  EXPECT_EQ(s.approach_m, t.approach_m);
  EXPECT_EQ(s.area_m2, t.area_m2);
  EXPECT_EQ(s.force_N, t.force_N);
}

TEST(HertzShape, KeptShapeSolvesBitForBitAsAShapeFoundPerCall) {
  const double Estar = ContactModulusSame(210e9, 0.3);
  // Circular, the near-circle series, moderate and extreme ratios, either curvature larger.
  const double curvatures[][2] = {{1.0, 1.0},        {1.0, 1.0 + 5e-7}, {1.0 / 0.92, 1.0 / 0.16},
                                  {1.0 / 0.16, 1.0 / 0.92}, {0.5, 2e3},   {3.0, 3.0 * 1.0001}};
  for (const auto& ab : curvatures) {
    const HertzShape shape(ab[0], ab[1]);
    for (double P : {0.0, 1.0, 1e3, 1e5, 1.2345678e5}) {
      SCOPED_TRACE(testing::Message() << "A " << ab[0] << " B " << ab[1] << " P " << P);
      const HertzSolution reference = SolveHertzFoundPerCall(ab[0], ab[1], Estar, P);
      ExpectSameBits(shape.Solve(Estar, P), reference);
      ExpectSameBits(SolveHertz(ab[0], ab[1], Estar, P), reference);
      // For an approach: the unit-force scaling, once from the kept shape and once per call.
      const HertzSolution unit = SolveHertzFoundPerCall(ab[0], ab[1], Estar, 1.0);
      const double delta = reference.approach_m;
      HertzSolution by_approach =
          SolveHertzFoundPerCall(ab[0], ab[1], Estar, std::pow(delta / unit.approach_m, 1.5));
      by_approach.approach_m = delta;
      ExpectSameBits(shape.SolveForApproach(Estar, delta), by_approach);
      ExpectSameBits(SolveHertzForApproach(ab[0], ab[1], Estar, delta), by_approach);
    }
  }
}

TEST(HertzShape, BadInputThrowsAsSolveHertz) {
  EXPECT_THROW(HertzShape(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(HertzShape(1.0, std::nan("")), std::invalid_argument);
  const HertzShape shape(1.0, 2.0);
  EXPECT_THROW(shape.Solve(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(shape.Solve(1e11, -1.0), std::invalid_argument);
  EXPECT_THROW(shape.SolveForApproach(1e11, -1e-6), std::invalid_argument);
  // A zero force needs no axis ratio: SolveHertz returns the empty patch without one.
  EXPECT_EQ(SolveHertz(1.0, 1e300, 1e11, 0.0).area_m2, 0.0);
}

TEST(Hertz, LineContact) {
  // a = sqrt(4 P' R / (pi E*)), p0 = 2 P' / (pi a); check p0 = sqrt(P' E* / (pi R)) (exact).
  const double Pp = 1e6, R = 0.2, Estar = 1.15e11;
  const LineContactSolution s = SolveLineContact(Pp, R, Estar);
  EXPECT_NEAR(s.half_width_m, std::sqrt(4 * Pp * R / (std::numbers::pi * Estar)), 1e-18);
  EXPECT_NEAR(s.p0_Pa, std::sqrt(Pp * Estar / (std::numbers::pi * R)), 1e-9 * s.p0_Pa);
  // Load balance: the semi-elliptic distribution integrates to P' = pi a p0 / 2.
  EXPECT_NEAR(std::numbers::pi * s.half_width_m * s.p0_Pa / 2, Pp, 1e-9 * Pp);
  EXPECT_THROW(SolveLineContact(Pp, 0.0, Estar), std::invalid_argument);
}

}  // namespace
}  // namespace railwear
