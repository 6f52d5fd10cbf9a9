// Tests of kalker_coefficients.h against Kalker's table (reference README §4) and linear theory.
#include "core/contact/kalker_coefficients.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace railwear {
namespace {

// Table nodes must come back to the printed digits; 1e-12 is round-off in the interpolants.
constexpr double kNodeTol = 1e-12;

TEST(KalkerCoefficients, TableNodesAreExact) {
  // reference README §4: a/b = 0.5 row, a/b = 1 row and b/a = 0.5 row (a/b = 2).
  struct Node {
    double a_over_b, nu, c11, c22, c23;
  };
  const Node nodes[] = {
      {0.5, 0.0, 2.88, 2.88, 0.827}, {0.5, 0.25, 3.62, 3.01, 0.929}, {0.5, 0.5, 4.83, 3.14, 1.07},
      {1.0, 0.25, 4.12, 3.67, 1.47}, {2.0, 0.25, 5.10, 4.90, 2.62},  {2.0, 0.5, 6.11, 5.56, 2.96},
      {0.1, 0.0, 2.51, 2.51, 0.334}, {10.0, 0.5, 12.9, 16.0, 18.0},
  };
  for (const Node& n : nodes) {
    const CreepCoefficients c = KalkerCoefficients(n.a_over_b, n.nu);
    EXPECT_NEAR(c.c11, n.c11, kNodeTol) << n.a_over_b << " " << n.nu;
    EXPECT_NEAR(c.c22, n.c22, kNodeTol) << n.a_over_b << " " << n.nu;
    EXPECT_NEAR(c.c23, n.c23, kNodeTol) << n.a_over_b << " " << n.nu;
  }
}

TEST(KalkerCoefficients, InterpolatesBetweenNodes) {
  // Between a/b = 0.5 and 0.6 at nu = 0.25, C11 lies between 3.62 and 3.72 and, on this nearly
  // straight stretch, within 0.01 of the chord's midpoint.
  const CreepCoefficients mid = KalkerCoefficients(0.55, 0.25);
  EXPECT_GT(mid.c11, 3.62);
  EXPECT_LT(mid.c11, 3.72);
  EXPECT_NEAR(mid.c11, 0.5 * (3.62 + 3.72), 0.01);
  // In nu: at a/b = 1 between 0 and 0.25, between the two nodes.
  const CreepCoefficients n = KalkerCoefficients(1.0, 0.125);
  EXPECT_GT(n.c11, 3.40);
  EXPECT_LT(n.c11, 4.12);
  // Monotone in a/b across the whole table (every column of the table is increasing).
  double prev = 0.0;
  for (double r = 0.1; r <= 10.0; r *= 1.05) {
    const double c23 = KalkerCoefficients(r, 0.28).c23;
    EXPECT_GT(c23, prev) << r;
    prev = c23;
  }
}

TEST(KalkerCoefficients, HalvesMeetAtCircle) {
  // The two halves of the table (a/b rows and b/a rows) join at a/b = 1: the interpolant is
  // continuous there from both sides.
  for (double nu : {0.0, 0.28, 0.5}) {
    const CreepCoefficients lo = KalkerCoefficients(1.0 - 1e-9, nu);
    const CreepCoefficients hi = KalkerCoefficients(1.0 / (1.0 - 1e-9), nu);
    EXPECT_NEAR(lo.c11, hi.c11, 1e-7);
    EXPECT_NEAR(lo.c22, hi.c22, 1e-7);
    EXPECT_NEAR(lo.c23, hi.c23, 1e-7);
  }
  // At nu = 0 the longitudinal and lateral problems coincide: C11 = C22 on every row.
  for (double r = 0.1; r <= 10.0; r *= 1.1) {
    const CreepCoefficients c = KalkerCoefficients(r, 0.0);
    EXPECT_NEAR(c.c11, c.c22, kNodeTol) << r;
  }
}

TEST(KalkerCoefficients, ClampsOutsideTable) {
  const CreepCoefficients thin = KalkerCoefficients(0.01, 0.25);
  const CreepCoefficients edge = KalkerCoefficients(0.1, 0.25);
  EXPECT_EQ(thin.c11, edge.c11);
  EXPECT_EQ(KalkerCoefficients(100.0, 0.25).c23, KalkerCoefficients(10.0, 0.25).c23);
}

TEST(KalkerCoefficients, RejectsBadInput) {
  try {
    KalkerCoefficients(1.0, 0.6);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nu = 0.6"), std::string::npos) << e.what();
  }
  EXPECT_THROW(KalkerCoefficients(-1.0, 0.3), std::invalid_argument);
  EXPECT_THROW(CalcLinearCreepForces(0.0, 1e-3, 8e10, 0.3, 0, 0, 0), std::invalid_argument);
}

TEST(LinearCreepForces, SignsAndMagnitudes) {
  // a = 8, b = 4 mm (a/b = 2, the b/a = 0.5 row), G = 82 GPa, nu = 0.25: hand calculation
  // Fx = -G ab C11 xi = -82e9 * 32e-6 * 5.10 * 1e-3 = -13382.4 N.
  const double a = 8e-3, b = 4e-3, g = 82e9;
  const LinearCreepForces f = CalcLinearCreepForces(a, b, g, 0.25, 1e-3, 0.0, 0.0);
  EXPECT_NEAR(f.force_x_N, -13382.4, 1e-6);
  EXPECT_EQ(f.force_y_N, 0.0);
  const double c = std::sqrt(a * b);
  const LinearCreepForces s = CalcLinearCreepForces(a, b, g, 0.25, 0.0, -1e-3, 0.5);
  EXPECT_NEAR(s.force_y_N, g * c * c * 4.90 * 1e-3 - g * c * c * c * 2.62 * 0.5, 1e-6);
}

}  // namespace
}  // namespace railwear
