// Tests of kalker_coefficients.h against Kalker's table (reference README §4) and linear theory.
#include "core/contact/kalker_coefficients.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/tangential_exact.h"
#include "tests/core/contact/hertz_grid.h"

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

// Beyond the table (issue 16): extended, not clamped. The extension meets Kalker's end rows,
// keeps growing (b/a -> 0) or settles (a/b -> 0) as the slender-ellipse limits say, and is
// monotone like the table.
TEST(KalkerCoefficients, ExtendsBeyondTheTable) {
  for (double nu : {0.0, 0.28, 0.5}) {
    for (double end : {0.1, 10.0}) {
      const CreepCoefficients at = KalkerCoefficients(end, nu);
      const double step = end < 1.0 ? 1.0 - 1e-9 : 1.0 + 1e-9;  // just outside
      const CreepCoefficients out = KalkerCoefficients(end * step, nu);
      EXPECT_NEAR(out.c11, at.c11, 1e-6 * at.c11) << end << " " << nu;
      EXPECT_NEAR(out.c22, at.c22, 1e-6 * at.c22) << end << " " << nu;
      EXPECT_NEAR(out.c23, at.c23, 1e-6 * at.c23) << end << " " << nu;
    }
    // Long patches (b/a -> 0): every coefficient grows with a/b, past the table's end.
    CreepCoefficients prev = KalkerCoefficients(10.0, nu);
    for (double r = 10.5; r <= 200.0; r *= 1.05) {
      const CreepCoefficients c = KalkerCoefficients(r, nu);
      EXPECT_GT(c.c11, prev.c11) << r;
      EXPECT_GT(c.c22, prev.c22) << r;
      EXPECT_GT(c.c23, prev.c23) << r;
      prev = c;
    }
    // Short patches (a/b -> 0): C23 falls like sqrt(a/b); C11, C22 settle (limits below).
    double prev23 = KalkerCoefficients(0.1, nu).c23;
    for (double r = 0.095; r >= 0.005; r *= 0.95) {
      const double c23 = KalkerCoefficients(r, nu).c23;
      EXPECT_LT(c23, prev23) << r;
      prev23 = c23;
    }
  }
  // At nu = 0 the longitudinal and lateral problems coincide on the extension too.
  for (double r : {0.01, 0.03, 30.0, 100.0}) {
    const CreepCoefficients c = KalkerCoefficients(r, 0.0);
    EXPECT_NEAR(c.c11, c.c22, 1e-12 * c.c11) << r;
  }
}

// Kalker's asymptotic expressions for slender ellipses (Kalker 1967 / 1990, with his table; the
// same as those printed under Table E.3), g the small axis ratio, Lambda = ln(16/g^2):
//   a/b = g -> 0:  C11 -> pi^2/(4(1-nu)),  C22 -> pi^2/4,
//                  C23 = pi sqrt(g) / (3(1-nu)) (1 + nu (Lambda/2 + ln 4 - 5)),
//   b/a = g -> 0:  C23 = 2 pi / (3 g^(3/2) ((1-nu) Lambda - 2 + 4 nu)).
// Leading order in 1/Lambda, so they hold to O(1/Lambda^2) (1 % at g = 0.02, where Lambda = 10.6,
// the limits of C11, C22 to O(g)); the extension (exact solver, scaled to Kalker's end rows) is
// within 0.02-1.4 % of them at its last row and below, where the tolerance 2 % allows the
// scaling's 1.4 % (our solver and Kalker's table differ by that at nu = 0.5, a/b = 0.1).
constexpr double kAsymptoticTolerance = 0.02;
// C11, C22 against their a/b -> 0 limits: O(g) terms and the scaling to Kalker's end row (his
// C11 = 4.85 at a/b = 0.1, nu = 0.5, against our solver's 4.87) leave 0.5 % at g = 0.02.
constexpr double kLimitTolerance = 0.01;
TEST(KalkerCoefficients, ExtensionAgreesWithKalkersAsymptotics) {
  const double pi = 3.14159265358979;
  for (double nu : {0.0, 0.25, 0.5}) {
    for (double g : {0.02, 0.01}) {
      const double lambda = std::log(16.0 / (g * g));
      const CreepCoefficients thin = KalkerCoefficients(g, nu);
      const double c23_thin = pi * std::sqrt(g) / (3.0 * (1.0 - nu)) *
                              (1.0 + nu * (0.5 * lambda + std::log(4.0) - 5.0));
      EXPECT_NEAR(thin.c23, c23_thin, kAsymptoticTolerance * c23_thin) << g << " " << nu;
      EXPECT_NEAR(thin.c11, pi * pi / (4.0 * (1.0 - nu)), kLimitTolerance * thin.c11) << g << nu;
      EXPECT_NEAR(thin.c22, pi * pi / 4.0, kLimitTolerance * thin.c22) << g << " " << nu;
      const CreepCoefficients slender = KalkerCoefficients(1.0 / g, nu);
      const double c23_long =
          2.0 * pi / (3.0 * std::pow(g, 1.5) * ((1.0 - nu) * lambda - 2.0 + 4.0 * nu));
      EXPECT_NEAR(slender.c23, c23_long, kAsymptoticTolerance * c23_long) << g << " " << nu;
      std::printf("[ measured ] g %.2f nu %.2f: C23 a/b=g %.4f (asymptotic %.4f), b/a=g %.2f "
                  "(%.2f); C11, C22 at a/b=g %.4f %.4f (limits %.4f %.4f)\n",
                  g, nu, thin.c23, c23_thin, slender.c23, c23_long, thin.c11, thin.c22,
                  pi * pi / (4.0 * (1.0 - nu)), pi * pi / 4.0);
    }
  }
}

// The stored rows are the exact solver's ratios C(r)/C(0.1): recomputed on a coarser grid (20
// cells per semi-axis instead of 40) at a/b and b/a = 0.05 they agree within 0.5 % (measured:
// the ratios at 20 and 40 cells differ by at most 0.17 %, since the solver's discretisation
// error cancels in them; at 10 cells C23 of short patches is 1.4 % off at a/b = 0.02).
constexpr double kRatioTolerance = 0.005;
CreepCoefficients ExactSolverCoefficients(double a_over_b, double nu, int cells_per_semi_axis) {
  const double c = 5e-3, a = c * std::sqrt(a_over_b), b = c / std::sqrt(a_over_b);
  const PatchGrid g = testing::MakeHertzGrid(a, b, 2 * cells_per_semi_axis, 2 * cells_per_semi_axis);
  const Eigen::VectorXd p = testing::HertzPressure(g, a, b, 1e5);
  const double shear = 80e9;
  const Material m{2.0 * shear * (1.0 + nu), nu};
  constexpr double kCreep = 1e-7;  // full stick: linear theory
  const double phi = kCreep / c;
  auto solve = [&](double xi, double eta, double spin) {
    const TangentialSolution s = SolveTangentialExact(
        g, p, testing::KalkerCreepage(g, xi, eta, spin, 1.0, 0.3), m, m);
    EXPECT_EQ(s.status, SolverStatus::kConverged) << s.message;
    return s;
  };
  return {-solve(kCreep, 0, 0).force_x_N / (shear * c * c * kCreep),
          -solve(0, kCreep, 0).force_s_N / (shear * c * c * kCreep),
          -solve(0, 0, phi).force_s_N / (shear * c * c * c * phi)};
}

TEST(KalkerCoefficientsExtension, StoredRowsAreTheExactSolversRatios) {
  constexpr double kNu = 0.25;
  for (double g : {0.05}) {
    for (bool thin : {true, false}) {
      const double end = thin ? 0.1 : 10.0, r = thin ? g : 1.0 / g;
      const CreepCoefficients se = ExactSolverCoefficients(end, kNu, 20);
      const CreepCoefficients sr = ExactSolverCoefficients(r, kNu, 20);
      const CreepCoefficients ke = KalkerCoefficients(end, kNu), kr = KalkerCoefficients(r, kNu);
      EXPECT_NEAR(kr.c11 / ke.c11, sr.c11 / se.c11, kRatioTolerance * kr.c11 / ke.c11) << r;
      EXPECT_NEAR(kr.c22 / ke.c22, sr.c22 / se.c22, kRatioTolerance * kr.c22 / ke.c22) << r;
      EXPECT_NEAR(kr.c23 / ke.c23, sr.c23 / se.c23, kRatioTolerance * kr.c23 / ke.c23) << r;
    }
  }
}

// The generator of the stored rows (kalker_coefficients.cpp): the exact solver at 40 cells per
// semi-axis, nu = 0, 0.25, 0.4999, each row as C11, C22, C23 per nu. About 5 minutes on one core:
//   build/tests/core_tests --gtest_also_run_disabled_tests
//     --gtest_filter='KalkerCoefficientsExtension.DISABLED_GenerateRows'
TEST(KalkerCoefficientsExtension, DISABLED_GenerateRows) {
  for (bool thin : {true, false}) {
    for (double g : {0.1, 0.08, 0.06, 0.05, 0.04, 0.03, 0.025, 0.02}) {
      std::printf("%s %.3f:", thin ? "a/b" : "b/a", g);
      for (double nu : {0.0, 0.25, 0.4999}) {
        const CreepCoefficients c = ExactSolverCoefficients(thin ? g : 1.0 / g, nu, 40);
        std::printf("  %.5g %.5g %.5g", c.c11, c.c22, c.c23);
      }
      std::printf("\n");
    }
  }
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
