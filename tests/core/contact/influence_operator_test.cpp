// Tests of the influence kernels and operators: Love's closed form against analytic values and
// brute-force quadrature, the cell kernel's physical properties, the far-field rule's error, and
// the FFT operators against the dense reference.
#include "core/contact/influence_operator.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "core/contact/influence_kernels.h"
#include "core/contact/normal_solver.h"
#include "core/numerics/check.h"
#include "core/numerics/fft_size.h"
#include "core/numerics/input_error.h"
#include "core/numerics/pooled_buffer.h"
#include "tests/core/contact/hertz_grid.h"
#include "tests/core/contact/same_result.h"

namespace railwear {
namespace {

// Love's value and other closed-form identities: rounding of a few asinh/atan evaluations.
constexpr double kClosedFormTolerance = 1e-12;
// Closed forms against brute-force quadrature; the quadrature below converges to ~1e-13, the
// brief asks for 1e-8.
constexpr double kQuadratureTolerance = 1e-8;
// Far-field rule (corrected midpoint) against the closed forms beyond kFarFieldDiagonals: the
// accuracy the project requires before it may replace the closed forms (DESIGN.md §1.3).
constexpr double kFarFieldRuleTolerance = 1e-4;
// ... and, on 1/R and on the seed kernel's combination (which the operators use), no worse than
// the second-order rule was at its 8.5 diagonals before 2026-11-30 (2e-6 and 2.4e-6, printed by
// FarFieldRuleIsWithinToleranceBeyondItsSwitch at that switch): the fourth-order rule at 3.5
// diagonals keeps the operators' accuracy while it leaves a fifth of the pairs to the closed forms.
constexpr double kFarFieldKernelTolerance = 2e-6;
// FFT operators against the dense matrix: FFT rounding grows like eps log N on these
// positive kernels; 1e-12 leaves two orders of margin on the grids below.
constexpr double kFastVersusDenseTolerance = 1e-12;
// Symmetry and ratio checks on assembled matrices: rounding of the offsets (P_i - P_j) . t_j.
constexpr double kMatrixRoundingTolerance = 1e-12;

const double kLoveFactor = 4.0 * std::log(1.0 + std::sqrt(2.0));  // 3.525494348 (README §2)

// ----- brute-force quadrature ----------------------------------------------------------------

struct GaussRule {
  std::vector<double> x, w;  // nodes and weights on [0, 1]
};

// Gauss-Legendre rule by Newton iteration on P_n.
GaussRule MakeGaussLegendre(int n) {
  GaussRule rule;
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    rule.x.push_back(0.5 * (1.0 - z));
    rule.w.push_back(1.0 / ((1.0 - z * z) * dp * dp));
  }
  return rule;
}

using Integrand = std::function<double(double xi, double eta)>;

// Integral of f over [0, a] x [0, b] (a, b > 0) with a possible (near-)singularity at the
// origin: two Duffy triangles, geometric panels toward the origin in the radial variable u.
double CornerQuadrature(const Integrand& f, double a, double b) {
  static const GaussRule g = MakeGaussLegendre(16);
  std::vector<double> u_edges = {0.0};
  for (int m = 30; m >= 1; --m) u_edges.push_back(std::pow(0.3, m));
  u_edges.push_back(1.0);
  constexpr int kVPanels = 4;
  double sum = 0.0;
  for (size_t pu = 0; pu + 1 < u_edges.size(); ++pu) {
    const double u0 = u_edges[pu], hu = u_edges[pu + 1] - u_edges[pu];
    for (size_t iu = 0; iu < g.x.size(); ++iu) {
      const double u = u0 + hu * g.x[iu];
      for (int pv = 0; pv < kVPanels; ++pv) {
        for (size_t iv = 0; iv < g.x.size(); ++iv) {
          const double v = (pv + g.x[iv]) / kVPanels;
          const double w = hu * g.w[iu] * g.w[iv] / kVPanels * a * b * u;
          sum += w * (f(u * a, u * v * b) + f(u * v * a, u * b));
        }
      }
    }
  }
  return sum;
}

// Integral of f(xi, eta) over the offsets from the field point to the rectangle, by signed
// corner integrals (f even in xi and eta) — for field points near or inside the rectangle.
double NearQuadrature(const Integrand& f, double x, double s, double hx, double hs) {
  double sum = 0.0;
  for (int ix = 0; ix < 2; ++ix) {
    for (int is = 0; is < 2; ++is) {
      const double xi = x + (ix == 0 ? -0.5 : 0.5) * hx;
      const double eta = s + (is == 0 ? -0.5 : 0.5) * hs;
      if (xi == 0.0 || eta == 0.0) continue;
      const double sign = (ix == is ? 1.0 : -1.0) * (xi > 0 ? 1.0 : -1.0) * (eta > 0 ? 1.0 : -1.0);
      sum += sign * CornerQuadrature(f, std::abs(xi), std::abs(eta));
    }
  }
  return sum;
}

// Plain tensor Gauss over the rectangle, for field points away from it (smooth integrand).
double TensorQuadrature(const Integrand& f, double x, double s, double hx, double hs) {
  static const GaussRule g = MakeGaussLegendre(20);
  constexpr int kPanels = 4;
  double sum = 0.0;
  for (int px = 0; px < kPanels; ++px) {
    for (int ps = 0; ps < kPanels; ++ps) {
      for (size_t i = 0; i < g.x.size(); ++i) {
        for (size_t j = 0; j < g.x.size(); ++j) {
          const double xs = -0.5 * hx + hx * (px + g.x[i]) / kPanels;
          const double ss = -0.5 * hs + hs * (ps + g.x[j]) / kPanels;
          sum += g.w[i] * g.w[j] * f(x - xs, s - ss);
        }
      }
    }
  }
  return sum * hx * hs / (kPanels * kPanels);
}

Integrand InvR(double n) {
  return [n](double xi, double eta) { return 1.0 / std::sqrt(xi * xi + eta * eta + n * n); };
}
Integrand N2R3(double n) {
  return [n](double xi, double eta) {
    const double r = std::sqrt(xi * xi + eta * eta + n * n);
    return n * n / (r * r * r);
  };
}

double RelativeError(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// ----- rectangle integrals -------------------------------------------------------------------

TEST(RectangleIntegral, ReproducesLovesCentreValue) {
  for (double h : {1.0, 2.5e-4}) {
    EXPECT_NEAR(RectangleIntegralInvR(0.0, 0.0, 0.0, h, h) / (kLoveFactor * h), 1.0,
                kClosedFormTolerance);
    EXPECT_EQ(RectangleIntegralN2R3(0.0, 0.0, 0.0, h, h), 0.0);
  }
  // Love's value for a rectangle a x b at its centre: 2 [a asinh(b/a) + b asinh(a/b)].
  const double a = 3e-4, b = 1e-4;
  const double love = 2.0 * (a * std::asinh(b / a) + b * std::asinh(a / b));
  EXPECT_NEAR(RectangleIntegralInvR(0.0, 0.0, 0.0, a, b) / love, 1.0, kClosedFormTolerance);
}

TEST(RectangleIntegral, MatchesQuadratureNearAndInside) {
  struct Case {
    double x, s, n, hx, hs;
  };
  const Case cases[] = {
      {0.1, 0.2, 0.0, 1.0, 1.0},    // inside, off centre
      {0.45, -0.3, 0.0, 1.0, 1.0},  // inside, near an edge
      {0.5, 0.2, 0.0, 1.0, 1.0},    // on an edge
      {0.5, 0.5, 0.0, 1.0, 1.0},    // on a corner
      {0.7, 0.1, 0.0, 1.0, 1.0},    // just outside
      {0.1, 0.2, 0.05, 1.0, 1.0},   // above the inside, near-singular
      {0.1, -0.2, -0.3, 1.0, 1.0},  // below the inside
      {1.2, 0.9, 0.4, 1.0, 1.0},    // outside and off the plane
      {0.3, 0.1, 1e-3, 2.0, 0.5},   // elongated cell, very close to the plane
      {-0.8, 0.2, 0.2, 2.0, 0.5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "x=" << c.x << " s=" << c.s << " n=" << c.n);
    EXPECT_LT(RelativeError(RectangleIntegralInvR(c.x, c.s, c.n, c.hx, c.hs),
                            NearQuadrature(InvR(c.n), c.x, c.s, c.hx, c.hs)),
              kQuadratureTolerance);
    if (c.n != 0.0) {
      EXPECT_LT(RelativeError(RectangleIntegralN2R3(c.x, c.s, c.n, c.hx, c.hs),
                              NearQuadrature(N2R3(c.n), c.x, c.s, c.hx, c.hs)),
                kQuadratureTolerance);
    } else {
      EXPECT_EQ(RectangleIntegralN2R3(c.x, c.s, c.n, c.hx, c.hs), 0.0);
    }
  }
}

TEST(RectangleIntegral, MatchesQuadratureFarAway) {
  struct Case {
    double x, s, n, hx, hs;
  };
  const Case cases[] = {
      {3.0, 0.0, 0.0, 1.0, 1.0},    {5.0, -7.0, 0.0, 1.0, 1.0},   {4.0, 2.0, 1.5, 1.0, 1.0},
      {-20.0, 13.0, 2.0, 1.0, 1.0}, {60.0, 80.0, 30.0, 1.0, 1.0}, {0.0, 9.0, 4.0, 2.0, 0.5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "x=" << c.x << " s=" << c.s << " n=" << c.n);
    EXPECT_LT(RelativeError(RectangleIntegralInvR(c.x, c.s, c.n, c.hx, c.hs),
                            TensorQuadrature(InvR(c.n), c.x, c.s, c.hx, c.hs)),
              kQuadratureTolerance);
    if (c.n != 0.0) {
      EXPECT_LT(RelativeError(RectangleIntegralN2R3(c.x, c.s, c.n, c.hx, c.hs),
                              TensorQuadrature(N2R3(c.n), c.x, c.s, c.hx, c.hs)),
                kQuadratureTolerance);
    }
  }
}

TEST(RectangleIntegral, IsEvenInEachOffset) {
  const double hx = 1.3, hs = 0.7;
  for (double x : {0.0, 0.2, 0.9, 4.0}) {
    for (double s : {0.0, 0.1, 0.5, 3.0}) {
      for (double n : {0.0, 0.05, 1.0}) {
        const double i = RectangleIntegralInvR(x, s, n, hx, hs);
        const double j = RectangleIntegralN2R3(x, s, n, hx, hs);
        for (double sx : {-1.0, 1.0}) {
          for (double ss : {-1.0, 1.0}) {
            for (double sn : {-1.0, 1.0}) {
              EXPECT_NEAR(RectangleIntegralInvR(sx * x, ss * s, sn * n, hx, hs), i,
                          kClosedFormTolerance * i);
              EXPECT_NEAR(RectangleIntegralN2R3(sx * x, ss * s, sn * n, hx, hs), j,
                          kClosedFormTolerance * std::max(j, i));
            }
          }
        }
      }
    }
  }
}

TEST(RectangleIntegral, FarFieldRuleIsWithinToleranceBeyondItsSwitch) {
  // Scan directions and elevations on the sphere just beyond the switch distance, for square and
  // elongated cells; record the worst relative errors of both integrals and of the golubenko
  // combination (a = 0.75 (3 - 4 nu) b, b = 1, nu = 0.28 per unit k_d).
  double worst_inv_r = 0.0, worst_n2_r3 = 0.0, worst_combined = 0.0;
  for (double aspect : {1.0, 2.0, 0.5, 4.0}) {
    const double hx = 1.0, hs = 1.0 / aspect;
    const double rho = internal::kFarFieldDiagonals * std::hypot(hx, hs) * (1.0 + 1e-9);
    for (int it = 0; it < 48; ++it) {
      const double theta = 2.0 * std::numbers::pi * it / 48.0;
      for (int ip = 0; ip <= 12; ++ip) {
        const double phi = 0.5 * std::numbers::pi * ip / 12.0;
        const double x = rho * std::cos(phi) * std::cos(theta);
        const double s = rho * std::cos(phi) * std::sin(theta);
        const double n = rho * std::sin(phi);
        double i_exact, j_exact, i_far, j_far, i_used, j_used;
        internal::RectangleIntegralsClosedForm(x, s, n, hx, hs, &i_exact, &j_exact);
        internal::RectangleIntegralsFarField(x, s, n, hx, hs, &i_far, &j_far);
        internal::RectangleIntegrals(x, s, n, hx, hs, &i_used, &j_used);
        EXPECT_EQ(i_used, i_far);  // the switch is where the header says
        worst_inv_r = std::max(worst_inv_r, RelativeError(i_far, i_exact));
        if (ip > 0) worst_n2_r3 = std::max(worst_n2_r3, RelativeError(j_far, j_exact));
        const double a = 0.75 * (3.0 - 4.0 * 0.28);
        worst_combined =
            std::max(worst_combined, RelativeError(a * i_far + j_far, a * i_exact + j_exact));
      }
    }
  }
  std::cout << "far-field rule at " << internal::kFarFieldDiagonals
            << " diagonals: worst relative error 1/R " << worst_inv_r << ", n^2/R^3 " << worst_n2_r3
            << ", golubenko " << worst_combined << "\n";
  EXPECT_LT(worst_inv_r, kFarFieldKernelTolerance);
  EXPECT_LT(worst_n2_r3, kFarFieldRuleTolerance);
  EXPECT_LT(worst_combined, kFarFieldKernelTolerance);
}

// ----- grids ---------------------------------------------------------------------------------

// Straight cross-section through origin_yz with direction angle_rad (0: along +y).
PatchGrid MakePlanarGrid(int nx, int ns, double dx, double ds, double angle_rad = 0.0,
                         Eigen::Vector2d origin_yz = {0.0, 0.0}) {
  PatchGrid g;
  g.nx = nx;
  g.ns = ns;
  g.dx_m = dx;
  g.ds_m = ds;
  g.x0_m = -0.5 * (nx - 1) * dx;
  g.s0_m = -0.5 * (ns - 1) * ds;
  g.planar = true;
  const Eigen::Vector2d t(std::cos(angle_rad), std::sin(angle_rad));
  const Eigen::Vector2d n(t.y(), -t.x());  // out of the rail (z downward)
  for (int j = 0; j < ns; ++j) {
    g.point_yz_m.push_back(origin_yz + (g.s0_m + j * ds) * t);
    g.tangent_yz.push_back(t);
    g.normal_yz.push_back(n);
  }
  g.gap_m = Eigen::VectorXd::Zero(nx * ns);
  return g;
}

// Circular-arc cross-section of the given radius, centre below the surface (inside the rail),
// arc length 0 at the top.
PatchGrid MakeArcGrid(int nx, int ns, double dx, double ds, double radius) {
  PatchGrid g = MakePlanarGrid(nx, ns, dx, ds);
  g.planar = false;
  const Eigen::Vector2d centre(0.0, radius);
  for (int j = 0; j < ns; ++j) {
    const double theta = g.S(j) / radius;
    g.normal_yz[j] = {std::sin(theta), -std::cos(theta)};
    g.tangent_yz[j] = {std::cos(theta), std::sin(theta)};
    g.point_yz_m[j] = centre + radius * g.normal_yz[j];
  }
  return g;
}

// A cross-section of varying curvature: the parabola z = y^2 / (2 * 8 mm) through the points of
// MakePlanarGrid's flat section (arc-length spaced approximately), with its tangents and normals.
PatchGrid MakeParabolaGrid(int nx, int ns, double dx, double ds) {
  PatchGrid g = MakePlanarGrid(nx, ns, dx, ds);
  g.planar = false;
  for (int j = 0; j < g.ns; ++j) {
    const double y = g.S(j);
    const double slope = y / 8e-3;
    g.point_yz_m[j] = {y, y * y / (2.0 * 8e-3)};
    g.tangent_yz[j] = Eigen::Vector2d(1.0, slope).normalized();
    g.normal_yz[j] = {g.tangent_yz[j].y(), -g.tangent_yz[j].x()};
  }
  return g;
}

InfluenceSettings MakeSettings(KernelModel kernel, double nu = 0.28) {
  InfluenceSettings s;
  s.kernel = kernel;
  s.wheel = {210e9, nu};
  s.rail = {210e9, nu};
  return s;
}

InfluenceSettings MakeDissimilarSettings(KernelModel kernel) {
  InfluenceSettings s = MakeSettings(kernel);
  s.wheel = {210e9, 0.28};
  s.rail = {180e9, 0.3};
  s.constants = {0.7, 1.3, 0.25};
  return s;
}

// ----- cell kernel ---------------------------------------------------------------------------

TEST(CellKernel, BoussinesqSelfTermIsLovesValue) {
  const double h = 2e-4;
  const InfluenceSettings settings = MakeDissimilarSettings(KernelModel::kBoussinesq);
  const Eigen::MatrixXd c = AssembleDenseInfluence(MakePlanarGrid(3, 3, h, h), settings);
  const double expected =
      (settings.wheel.Compliance() + settings.rail.Compliance()) * kLoveFactor * h;
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(c(k, k) / expected, 1.0, kClosedFormTolerance);
}

TEST(CellKernel, GolubenkoOverBoussinesqOnFlatPatchIsTheReadmeRatio) {
  // README §2: 0.75 (3 - 4 nu) / (4 (1 - nu)^2) = 0.680 (nu = 0.28), 0.689 (nu = 0.3).
  const PatchGrid grid = MakePlanarGrid(5, 4, 2e-4, 3e-4, 0.4);
  for (double nu : {0.28, 0.3}) {
    const double expected = 0.75 * (3.0 - 4.0 * nu) / (4.0 * (1.0 - nu) * (1.0 - nu));
    EXPECT_NEAR(expected, nu == 0.28 ? 0.680 : 0.689, 5e-4);  // the README's three digits
    const Eigen::MatrixXd b =
        AssembleDenseInfluence(grid, MakeSettings(KernelModel::kBoussinesq, nu));
    const Eigen::MatrixXd g =
        AssembleDenseInfluence(grid, MakeSettings(KernelModel::kGolubenko, nu));
    EXPECT_LT(((g.array() / b.array()) - expected).abs().maxCoeff(), kMatrixRoundingTolerance);
  }
}

TEST(CellKernel, IsSymmetricAndPositiveForIdenticalMaterials) {
  const PatchGrid grids[] = {MakePlanarGrid(6, 5, 2e-4, 2.5e-4, 0.7),
                             MakeArcGrid(6, 9, 2e-4, 4e-4, 10e-3),
                             MakeArcGrid(4, 30, 3e-4, 5e-4, 10e-3)};  // 86 degrees of arc
  for (const PatchGrid& grid : grids) {
    for (KernelModel kernel : {KernelModel::kBoussinesq, KernelModel::kGolubenko}) {
      SCOPED_TRACE(::testing::Message() << "ns=" << grid.ns << " " << ToString(kernel));
      const Eigen::MatrixXd c = AssembleDenseInfluence(grid, MakeSettings(kernel));
      EXPECT_GT(c.minCoeff(), 0.0);
      EXPECT_LT((c - c.transpose()).cwiseAbs().maxCoeff(),
                kMatrixRoundingTolerance * c.cwiseAbs().maxCoeff());
    }
  }
}

TEST(CellKernel, CurvatureTermRaisesGolubenkoAboveItsFlatValue) {
  // On the arc dn != 0 between distinct s rows, and the c_z term adds a positive amount; rows
  // at equal s (dn = 0) are unchanged.
  const PatchGrid arc = MakeArcGrid(3, 6, 2e-4, 5e-4, 10e-3);
  const PatchGrid flat = MakePlanarGrid(3, 6, 2e-4, 5e-4);
  const InfluenceSettings s = MakeSettings(KernelModel::kGolubenko);
  InfluenceSettings no_cz = s;
  no_cz.constants.c_z = 0.0;
  const Eigen::MatrixXd c = AssembleDenseInfluence(arc, s);
  const Eigen::MatrixXd c0 = AssembleDenseInfluence(arc, no_cz);
  EXPECT_GE((c - c0).minCoeff(), 0.0);
  EXPECT_GT((c - c0).maxCoeff(), 0.0);
  EXPECT_LT(
      (AssembleDenseInfluence(flat, s) - AssembleDenseInfluence(flat, no_cz)).cwiseAbs().maxCoeff(),
      kMatrixRoundingTolerance * c.maxCoeff());
}

// Separate convex and concave sets: the kernel sums each body with its own set,
// a = c_f(wheel's set) k_f,wheel + c_f(rail's set) k_f,rail (and b likewise with c_z).
TEST(CellKernel, SeparateSetsWeighEachBodyWithItsOwnSet) {
  const PatchGrid arc = MakeArcGrid(3, 6, 2e-4, 5e-4, 10e-3);
  InfluenceSettings wheel_only = MakeDissimilarSettings(KernelModel::kGolubenko);
  InfluenceSettings rail_only = wheel_only;
  wheel_only.rail.youngs_modulus_Pa *= 1e12;  // rigid: its share vanishes
  rail_only.wheel.youngs_modulus_Pa *= 1e12;
  InfluenceSettings both = MakeDissimilarSettings(KernelModel::kGolubenko);
  both.constants.separate = SeparateInfluenceConstants{{0.9, 1.2, 0.1}, {0.6, 0.8, 0.3}};
  both.wheel_curvature_sign = -1;  // a convex wheel in a concave groove
  both.rail_curvature_sign = +1;
  wheel_only.constants = {0.9, 1.2, 0.1};
  rail_only.constants = {0.6, 0.8, 0.3};
  const Eigen::MatrixXd sum =
      AssembleDenseInfluence(arc, wheel_only) + AssembleDenseInfluence(arc, rail_only);
  const Eigen::MatrixXd c = AssembleDenseInfluence(arc, both);
  EXPECT_LT((c - sum).cwiseAbs().maxCoeff(), 1e-9 * c.cwiseAbs().maxCoeff());
  // Equal sets are the one set, bit for bit.
  InfluenceSettings one = MakeDissimilarSettings(KernelModel::kGolubenko);
  InfluenceSettings equal = one;
  const InfluenceConstantSet set{one.constants.c_f, one.constants.c_z, one.constants.c_s};
  equal.constants.separate = SeparateInfluenceConstants{set, set};
  equal.wheel_curvature_sign = -1;
  equal.rail_curvature_sign = +1;
  EXPECT_EQ(AssembleDenseInfluence(arc, equal), AssembleDenseInfluence(arc, one));
}

TEST(CellKernel, RejectsBadMaterialWithMessage) {
  InfluenceSettings s = MakeSettings(KernelModel::kBoussinesq);
  s.rail.poisson_ratio = 0.5;
  try {
    MakeInfluenceOperator(MakePlanarGrid(2, 2, 1e-4, 1e-4), s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rail material"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nu = 0.5"), std::string::npos) << e.what();
  }
}

// ----- fast operators versus dense -----------------------------------------------------------

void ExpectFastEqualsDense(const PatchGrid& grid, const InfluenceSettings& settings,
                           OperatorProducts products) {
  SCOPED_TRACE(::testing::Message()
               << "nx=" << grid.nx << " ns=" << grid.ns << " planar=" << grid.planar << " "
               << ToString(settings.kernel)
               << " dense products=" << (products == OperatorProducts::kDense));
  const auto fast = MakeInfluenceOperator(grid, settings, products);
  const auto dense = MakeDenseInfluenceOperator(grid, settings);
  ASSERT_EQ(fast->size(), grid.cells());
  ASSERT_EQ(dense->size(), grid.cells());
  std::mt19937 rng(20240611);  // fixed seed
  std::uniform_real_distribution<double> pressure(0.0, 2e9);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd p(grid.cells());
    for (int k = 0; k < p.size(); ++k) p[k] = pressure(rng);
    if (trial == 2) p.head(p.size() / 2).setZero();  // a partly unloaded patch
    Eigen::VectorXd u_fast, u_dense;
    fast->Apply(p, &u_fast);
    dense->Apply(p, &u_dense);
    ASSERT_EQ(u_fast.size(), u_dense.size());
    EXPECT_LT((u_fast - u_dense).cwiseAbs().maxCoeff(),
              kFastVersusDenseTolerance * u_dense.cwiseAbs().maxCoeff());
    // A second Apply on the same operator (reused scratch) gives the same answer.
    Eigen::VectorXd u_again;
    fast->Apply(p, &u_again);
    EXPECT_EQ((u_again - u_fast).cwiseAbs().maxCoeff(), 0.0);
  }
  for (int k = 0; k < grid.cells(); ++k) {
    EXPECT_NEAR(fast->Diagonal(k), dense->Diagonal(k),
                kFastVersusDenseTolerance * dense->Diagonal(k));
  }
}

// Both product paths of the fast operators (FFT, and the dense matrix expanded from the same
// Toeplitz coefficients) against the dense reference assembled cell by cell.
void ExpectFastEqualsDense(const PatchGrid& grid, const InfluenceSettings& settings) {
  for (OperatorProducts products : {OperatorProducts::kFft, OperatorProducts::kDense}) {
    ExpectFastEqualsDense(grid, settings, products);
  }
}

TEST(InfluenceOperator, AutoProductsAreDenseOnTinyGridsAndFftAbove) {
  // The paths agree only to rounding, so which one ran shows in the last bits. On either path
  // the preconditioner is the same FFT-based inverse, bit for bit.
  const InfluenceSettings settings = MakeDissimilarSettings(KernelModel::kGolubenko);
  for (bool planar : {true, false}) {
    for (int n : {11, 20}) {
      SCOPED_TRACE(::testing::Message() << "planar=" << planar << " n=" << n);
      const PatchGrid grid = planar ? MakePlanarGrid(n, n, 2e-4, 3e-4, 0.3, {1e-3, -2e-3})
                                    : MakeArcGrid(n, n, 2e-4, 4e-4, 10e-3);
      const bool tiny = grid.cells() <= kDenseProductMaxCells;
      ASSERT_EQ(tiny, n == 11);
      const auto automatic = MakeInfluenceOperator(grid, settings);
      const auto fft = MakeInfluenceOperator(grid, settings, OperatorProducts::kFft);
      const auto dense = MakeInfluenceOperator(grid, settings, OperatorProducts::kDense);
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> pressure(0.0, 2e9);
      Eigen::VectorXd p(grid.cells());
      for (int k = 0; k < p.size(); ++k) p[k] = pressure(rng);
      Eigen::VectorXd u_auto, u_fft, u_dense;
      automatic->Apply(p, &u_auto);
      fft->Apply(p, &u_fft);
      dense->Apply(p, &u_dense);
      EXPECT_NE(u_fft, u_dense);  // rounding differs somewhere
      EXPECT_EQ(u_auto, tiny ? u_dense : u_fft);
      Eigen::VectorXd z_fft, z_dense;
      ASSERT_TRUE(fft->ApplyPreconditioner(u_fft, &z_fft));
      ASSERT_TRUE(dense->ApplyPreconditioner(u_fft, &z_dense));
      EXPECT_EQ(z_fft, z_dense);
    }
  }
}

TEST(InfluenceOperator, PlanarFftEqualsDense) {
  const int sizes[][2] = {{7, 6}, {8, 5}, {1, 9}, {10, 1}, {1, 1}, {13, 12}};
  for (const auto& n : sizes) {
    for (KernelModel kernel : {KernelModel::kBoussinesq, KernelModel::kGolubenko}) {
      ExpectFastEqualsDense(MakePlanarGrid(n[0], n[1], 2e-4, 3e-4, 0.3, {1e-3, -2e-3}),
                            MakeDissimilarSettings(kernel));
    }
  }
}

TEST(InfluenceOperator, CurvedFftEqualsDense) {
  const int sizes[][2] = {{7, 6}, {8, 5}, {1, 9}, {10, 1}, {1, 1}, {12, 17}};
  for (const auto& n : sizes) {
    for (KernelModel kernel : {KernelModel::kBoussinesq, KernelModel::kGolubenko}) {
      ExpectFastEqualsDense(MakeArcGrid(n[0], n[1], 2e-4, 4e-4, 10e-3),
                            MakeDissimilarSettings(kernel));
    }
  }
}

TEST(InfluenceOperator, CurvedFftEqualsDenseOnFlatSectionNotFlaggedPlanar) {
  PatchGrid g = MakePlanarGrid(6, 7, 2e-4, 3e-4, -0.5);
  g.planar = false;
  ExpectFastEqualsDense(g, MakeDissimilarSettings(KernelModel::kBoussinesq));
}

// What a failed internal check throws (core/numerics/check.h): an InternalError naming the
// broken condition, never an InputError (bad input is the caller's, a broken invariant a bug).
void ExpectInternalError(const std::function<void()>& f, const std::string& condition) {
  try {
    f();
    ADD_FAILURE() << "no InternalError";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("internal check failed: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.expression()).find(condition), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.file()).find("influence_operator.cpp"), std::string::npos);
  }
}

TEST(InfluenceOperator, PlanarFlagOnCurvedSectionFailsAnInternalCheck) {
  // grid.planar promises a straight, uniformly spaced cross-section; breaking it is a bug in
  // the grid builder, not bad input.
  PatchGrid g = MakeArcGrid(4, 5, 2e-4, 4e-4, 10e-3);
  g.planar = true;
  ExpectInternalError([&] { MakeInfluenceOperator(g, MakeSettings(KernelModel::kBoussinesq)); },
                      "kPlanarGridTolerance");
}

TEST(InfluenceOperator, CurvedFftEqualsDenseOnNonCircularSection) {
  // A cross-section of varying curvature (parabola z = y^2 / (2 * 8 mm), arc-length spaced
  // approximately): nothing in the curved operator may rely on constant curvature.
  const PatchGrid g = MakeParabolaGrid(9, 11, 2.5e-4, 4e-4);
  ExpectFastEqualsDense(g, MakeDissimilarSettings(KernelModel::kGolubenko));
  ExpectFastEqualsDense(g, MakeDissimilarSettings(KernelModel::kBoussinesq));
}

TEST(InfluenceOperator, FarCellsUseTheFarFieldRuleInsideTheOperators) {
  // A grid long enough that most pairs lie beyond the switch, so the fast-versus-dense check
  // also covers the far-field branch.
  const PatchGrid planar = MakePlanarGrid(40, 24, 1e-4, 1e-4);
  const PatchGrid arc = MakeArcGrid(40, 24, 1e-4, 2e-4, 10e-3);
  ExpectFastEqualsDense(planar, MakeDissimilarSettings(KernelModel::kBoussinesq));
  ExpectFastEqualsDense(arc, MakeDissimilarSettings(KernelModel::kGolubenko));
}

// CellInfluenceRow (the FFT operators' kernel rows, corner terms shared between neighbouring x
// offsets where they round alike) against CellInfluence cell by cell, bit for bit, for every pair
// of s indices, on a planar, a circular and a non-circular section, near and far cells (40
// columns reach past the far-field switch), both kernels.
TEST(CellInfluenceRow, EqualsCellInfluenceBitForBit) {
  const PatchGrid grids[] = {
      MakePlanarGrid(40, 12, 1e-4, 1.5e-4, 0.3, {1e-3, -2e-3}),
      MakeArcGrid(40, 24, 1.1e-4, 2e-4, 10e-3), MakeParabolaGrid(40, 11, 2.5e-4, 4e-4),
      MakeArcGrid(1, 3, 2e-4, 4e-4, 10e-3), MakeArcGrid(33, 30, 0.7141e-3, 0.8107e-3, 40e-3)};
  int far = 0, shared = 0;
  for (const PatchGrid& grid : grids) {
    for (KernelModel kernel : {KernelModel::kBoussinesq, KernelModel::kGolubenko}) {
      const internal::KernelCoefficients c =
          internal::MakeKernelCoefficients(MakeDissimilarSettings(kernel));
      std::vector<double> row(grid.nx);
      for (int js = 0; js < grid.ns; ++js) {
        for (int is = 0; is < grid.ns; ++is) {
          internal::CellInfluenceRow(grid, c, is, js, row.data());
          for (int d = 0; d < grid.nx; ++d) {
            ASSERT_EQ(row[d], internal::CellInfluence(grid, c, d, is, 0, js))
                << "nx " << grid.nx << " ns " << grid.ns << " d " << d << " is " << is << " js "
                << js;
            const Eigen::Vector2d d_yz = grid.point_yz_m[is] - grid.point_yz_m[js];
            const double r = std::hypot(d * grid.dx_m, d_yz.norm());
            const double h = std::hypot(grid.dx_m, grid.ds_m);
            if (r > internal::kFarFieldDiagonals * h) ++far;
            // A near offset after a near one whose corners round alike: a shared corner.
            const double x = d * grid.dx_m, x_prev = (d - 1) * grid.dx_m;
            if (d > 0 && r < internal::kFarFieldDiagonals * h &&
                x - 0.5 * grid.dx_m == x_prev + 0.5 * grid.dx_m) {
              ++shared;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(far, 1000);     // the far branch is covered
  EXPECT_GT(shared, 1000);  // and so is the sharing
}

// ----- uniform arcs: Toeplitz in s as well (issue 18 point 3) -----------------------------------

// A fixed pseudo-random pressure field, a quarter of it unloaded.
Eigen::VectorXd RandomPressure(int cells, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pressure(0.0, 2e9);
  Eigen::VectorXd p(cells);
  for (int k = 0; k < p.size(); ++k) p[k] = pressure(rng);
  p.head(p.size() / 4).setZero();
  return p;
}

TEST(InfluenceOperator, UniformArcToeplitzEqualsBlocks) {
  // On an arc the 2-D FFT (nx ns coefficients, from row 0's frame) and the per-frequency blocks
  // (nx ns^2 coefficients, each from its source row's frame) are the same operator: products
  // within kFastVersusDenseTolerance of each other (both are within it of the dense reference),
  // the same diagonal.
  struct Case {
    int nx, ns;
    double ds, radius;
  };
  const Case cases[] = {{12, 17, 4e-4, 10e-3},  // the curved FFT test's arc
                        {40, 24, 2e-4, 10e-3},  // far-field pairs
                        {20, 45, 1e-4, -5e-3},  // the other curvature sign, 52 degrees
                        {11, 11, 2e-4, 10e-3},  // dense products (kAuto at 121 cells)
                        {7, 2, 2e-4, 10e-3}};   // two rows
  double worst = 0.0;
  for (const Case& c : cases) {
    const PatchGrid grid = MakeArcGrid(c.nx, c.ns, 2e-4, c.ds, c.radius);
    ASSERT_EQ(ChooseSectionStructure(grid), SectionStructure::kToeplitzXs);
    for (KernelModel kernel : {KernelModel::kBoussinesq, KernelModel::kGolubenko}) {
      SCOPED_TRACE(::testing::Message() << "nx=" << c.nx << " ns=" << c.ns << " R=" << c.radius
                                        << " " << ToString(kernel));
      const InfluenceSettings settings = MakeDissimilarSettings(kernel);
      const auto toeplitz = MakeInfluenceOperator(grid, settings);
      const auto blocks =
          MakeInfluenceOperator(grid, settings, OperatorProducts::kAuto, SectionStructure::kBlocks);
      for (unsigned seed : {1u, 2u}) {
        const Eigen::VectorXd p = RandomPressure(grid.cells(), seed);
        Eigen::VectorXd u_toeplitz, u_blocks;
        toeplitz->Apply(p, &u_toeplitz);
        blocks->Apply(p, &u_blocks);
        const double difference =
            (u_toeplitz - u_blocks).cwiseAbs().maxCoeff() / u_blocks.cwiseAbs().maxCoeff();
        worst = std::max(worst, difference);
        EXPECT_LT(difference, kFastVersusDenseTolerance);
      }
      for (int k = 0; k < grid.cells(); ++k) {
        EXPECT_NEAR(toeplitz->Diagonal(k), blocks->Diagonal(k),
                    kFastVersusDenseTolerance * blocks->Diagonal(k));
      }
    }
  }
  std::cout << "[ figures  ] uniform arcs: largest relative difference of the 2-D FFT's products "
               "from the blocks' "
            << worst << "\n";
}

TEST(InfluenceOperator, NonCircularSectionKeepsTheBlockPath) {
  // The parabola of CurvedFftEqualsDenseOnNonCircularSection: kAuto builds the blocks, bit for
  // bit the operator that kBlocks forces.
  PatchGrid g = MakePlanarGrid(16, 14, 2.5e-4, 4e-4);
  g.planar = false;
  for (int j = 0; j < g.ns; ++j) {
    const double y = g.S(j);
    g.point_yz_m[j] = {y, y * y / (2.0 * 8e-3)};
    g.tangent_yz[j] = Eigen::Vector2d(1.0, y / 8e-3).normalized();
    g.normal_yz[j] = {g.tangent_yz[j].y(), -g.tangent_yz[j].x()};
  }
  EXPECT_EQ(ChooseSectionStructure(g), SectionStructure::kBlocks);
  const InfluenceSettings settings = MakeDissimilarSettings(KernelModel::kGolubenko);
  const auto automatic = MakeInfluenceOperator(g, settings);
  const auto blocks =
      MakeInfluenceOperator(g, settings, OperatorProducts::kAuto, SectionStructure::kBlocks);
  const Eigen::VectorXd p = RandomPressure(g.cells(), 3);
  Eigen::VectorXd u_auto, u_blocks, z_auto, z_blocks;
  automatic->Apply(p, &u_auto);
  blocks->Apply(p, &u_blocks);
  EXPECT_EQ(u_auto, u_blocks);
  ASSERT_TRUE(automatic->ApplyPreconditioner(u_auto, &z_auto));
  ASSERT_TRUE(blocks->ApplyPreconditioner(u_auto, &z_blocks));
  EXPECT_EQ(z_auto, z_blocks);
  // An arc off by one point moved 1e-9 of a cell is off the 2-D path too.
  PatchGrid arc = MakeArcGrid(16, 14, 2e-4, 4e-4, 10e-3);
  ASSERT_EQ(ChooseSectionStructure(arc), SectionStructure::kToeplitzXs);
  arc.point_yz_m[6] += 1e-9 * arc.ds_m * arc.normal_yz[6];
  EXPECT_EQ(ChooseSectionStructure(arc), SectionStructure::kBlocks);
  // One row is a uniform arc but keeps its 1 x 1 blocks (the patch builder makes such grids).
  const PatchGrid row = MakeArcGrid(9, 1, 2e-4, 4e-4, 10e-3);
  EXPECT_EQ(ChooseSectionStructure(row), SectionStructure::kBlocks);
  EXPECT_EQ(ChooseSectionStructure(row, SectionStructure::kToeplitzXs),
            SectionStructure::kToeplitzXs);
  // Planar grids keep the 2-D path; kBlocks is honoured on any grid.
  const PatchGrid flat = MakePlanarGrid(6, 7, 2e-4, 3e-4, -0.5);
  EXPECT_EQ(ChooseSectionStructure(flat), SectionStructure::kToeplitzXs);
  EXPECT_EQ(ChooseSectionStructure(flat, SectionStructure::kBlocks), SectionStructure::kBlocks);
}

TEST(InfluenceOperator, ToeplitzInSOnANonCircularSectionFailsAnInternalCheck) {
  PatchGrid g = MakeArcGrid(4, 5, 2e-4, 4e-4, 10e-3);
  g.point_yz_m[2].y() += 1e-6;  // off the arc
  ExpectInternalError(
      [&] {
        MakeInfluenceOperator(g, MakeSettings(KernelModel::kBoussinesq), OperatorProducts::kAuto,
                              SectionStructure::kToeplitzXs);
      },
      "IsUniformArc(grid)");
}

// ----- approximate inverses ------------------------------------------------------------------

// |C M r - r| / |r| for a smooth displacement field r supported on the central half of the grid.
// M inverts the circulant embedding exactly; C M r differs from r only through the pressure M
// puts in the zero padding (cropped), which decays away from r's support. Measured on the grids
// below: 0.083-0.093 (planar, Boussinesq) and 0.054-0.062 (arc, seed kernel; the curved
// operator's blocks, 2026-11-30; the uniform arcs' 2-D FFT operator 0.077-0.082), the same on
// every grid size; 0.15 leaves margin and still fails for a wrongly scaled or transposed M (>= 1).
constexpr double kInverseResidualTolerance = 0.15;
// Symmetry of M: rounding of the FFTs and of the blocks' explicit inverses.
constexpr double kPreconditionerSymmetryTolerance = 1e-12;

// sin^2 in each direction on the central half of the grid, 0 elsewhere [m].
Eigen::VectorXd SmoothDisplacement(const PatchGrid& g) {
  Eigen::VectorXd r(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = 2.0 * (i + 0.5) / g.nx - 0.5, s = 2.0 * (j + 0.5) / g.ns - 0.5;
      const bool inside = x > 0.0 && x < 1.0 && s > 0.0 && s < 1.0;
      const double a = std::sin(std::numbers::pi * x), b = std::sin(std::numbers::pi * s);
      r[g.Index(i, j)] = inside ? 1e-5 * a * a * b * b : 0.0;
    }
  }
  return r;
}

void ExpectApproximateInverse(const PatchGrid& grid, const InfluenceSettings& settings,
                              SectionStructure structure = SectionStructure::kAuto) {
  SCOPED_TRACE(::testing::Message() << "nx=" << grid.nx << " ns=" << grid.ns
                                    << " planar=" << grid.planar << " " << ToString(settings.kernel)
                                    << (structure == SectionStructure::kBlocks ? " blocks" : ""));
  const auto op = MakeInfluenceOperator(grid, settings, OperatorProducts::kAuto, structure);
  const Eigen::VectorXd r = SmoothDisplacement(grid);
  Eigen::VectorXd z, cz;
  ASSERT_TRUE(op->ApplyPreconditioner(r, &z));
  ASSERT_EQ(z.size(), grid.cells());
  op->Apply(z, &cz);
  EXPECT_LT((cz - r).norm() / r.norm(), kInverseResidualTolerance);

  // Symmetric positive definite (what preconditioned CG needs), on random vectors.
  std::mt19937 rng(20240612);  // fixed seed
  std::uniform_real_distribution<double> value(-1e-6, 1e-6);
  Eigen::VectorXd a(grid.cells()), b(grid.cells()), ma, mb;
  for (int k = 0; k < a.size(); ++k) {
    a[k] = value(rng);
    b[k] = value(rng);
  }
  ASSERT_TRUE(op->ApplyPreconditioner(a, &ma));
  ASSERT_TRUE(op->ApplyPreconditioner(b, &mb));
  EXPECT_NEAR(a.dot(mb), b.dot(ma), kPreconditionerSymmetryTolerance * a.norm() * mb.norm());
  EXPECT_GT(a.dot(ma), 0.0);
  EXPECT_GT(b.dot(mb), 0.0);
}

TEST(InfluenceOperator, PreconditionerInvertsApplyOnSmoothFields) {
  for (int n : {16, 32, 64}) {
    ExpectApproximateInverse(MakePlanarGrid(n, n + 3, 1e-4, 1.2e-4),
                             MakeSettings(KernelModel::kBoussinesq));
    ExpectApproximateInverse(MakeArcGrid(n, n + 3, 1e-4, 1.2e-4, 10e-3),
                             MakeSettings(KernelModel::kGolubenko));
    // The curved operator on the same arcs (an ns x ns block per x frequency, every grid the
    // patch builder makes that is not planar or a uniform arc): its preconditioner symmetric to
    // double's rounding too (measured 2e-17 to 3e-17; its substitutions in float, a trial of
    // issue 20, gave 1e-9 to 9e-9: docs/library.md, "The curved operator's products in one
    // pass").
    ExpectApproximateInverse(MakeArcGrid(n, n + 3, 1e-4, 1.2e-4, 10e-3),
                             MakeSettings(KernelModel::kGolubenko), SectionStructure::kBlocks);
  }
  // Dissimilar materials, a tilted planar section, non-square cells, a tighter arc. (The
  // bound needs r resolved: with 4-5 cells across its support the residual reaches 0.5.)
  ExpectApproximateInverse(MakePlanarGrid(32, 48, 2e-4, 1e-4, 0.3, {1e-3, -2e-3}),
                           MakeDissimilarSettings(KernelModel::kGolubenko));
  ExpectApproximateInverse(MakeArcGrid(24, 40, 2e-4, 1e-4, 5e-3),
                           MakeDissimilarSettings(KernelModel::kGolubenko));
}

// The planar (and uniform-arc) operator's preconditioner is the exact inverse of Strang's
// circulant of period px = NextFftSize(nx, 2) by ps = NextFftSize(ns, 1): the kernel at the
// offsets |d| <= px / 2, |e| <= ps / 2, wrapped (influence_operator.cpp). Against that circulant
// assembled densely on the whole period (from the operator's own column of cell (0, 0)), solved by
// LU, the padded r, cropped: fast lengths equal to n and above it, square and long cells.
// Tolerance: rounding of the FFTs and of the solve times the circulant's condition number (below
// 1e2 here; the floor of its symbol, 0.1 C_kk, is not reached on these grids).
constexpr double kStrangInverseTolerance = 1e-11;

TEST(InfluenceOperator, PlanarPreconditionerInvertsStrangsCirculant) {
  for (const PatchGrid& grid :
       {MakePlanarGrid(8, 9, 1e-4, 1e-4), MakePlanarGrid(11, 13, 1e-4, 1.2e-4),
        MakePlanarGrid(17, 6, 2e-4, 1e-4)}) {
    SCOPED_TRACE(::testing::Message() << grid.nx << " x " << grid.ns);
    const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kBoussinesq));
    const int nx = grid.nx, ns = grid.ns;
    const int px = internal::NextFftSize(nx, 2), ps = internal::NextFftSize(ns, 1);
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(grid.cells()), column;
    unit[grid.Index(0, 0)] = 1.0;
    op->Apply(unit, &column);  // c(d, e) at cell (d, e)
    auto wrapped = [&](int d, int e) {
      d = std::abs(d) % px;
      e = std::abs(e) % ps;
      d = std::min(d, px - d);
      e = std::min(e, ps - e);
      return d < nx && e < ns ? column[grid.Index(d, e)] : 0.0;
    };
    const int n = px * ps;
    Eigen::MatrixXd circulant(n, n);
    for (int is = 0; is < ps; ++is) {
      for (int ix = 0; ix < px; ++ix) {
        for (int js = 0; js < ps; ++js) {
          for (int jx = 0; jx < px; ++jx)
            circulant(is * px + ix, js * px + jx) = wrapped(ix - jx, is - js);
        }
      }
    }
    std::mt19937 rng(nx * 100 + ns);
    std::uniform_real_distribution<double> value(-1e-6, 1e-6);
    Eigen::VectorXd r(grid.cells()), padded = Eigen::VectorXd::Zero(n), z;
    for (int k = 0; k < r.size(); ++k) r[k] = value(rng);
    for (int is = 0; is < ns; ++is) {
      for (int ix = 0; ix < nx; ++ix) padded[is * px + ix] = r[grid.Index(ix, is)];
    }
    const Eigen::VectorXd solved = circulant.partialPivLu().solve(padded);
    ASSERT_TRUE(op->ApplyPreconditioner(r, &z));
    double error = 0.0, scale = 0.0;
    for (int is = 0; is < ns; ++is) {
      for (int ix = 0; ix < nx; ++ix) {
        error = std::max(error, std::abs(z[grid.Index(ix, is)] - solved[is * px + ix]));
        scale = std::max(scale, std::abs(solved[is * px + ix]));
      }
    }
    EXPECT_LE(error, kStrangInverseTolerance * scale);
  }
}

// The curved operator's preconditioner solves with the Cholesky factor of sym K_k per x frequency
// by plain substitutions (influence_operator.cpp, SolveFactored). On a single column of cells
// (nx = 1) every frequency's block is the cross-section's matrix C itself, so M = (sym C)^-1
// exactly: against an LLT solve of the dense matrix, on a circular and a non-circular section,
// several ns (odd and even: the backward pass's two partial sums). Tolerance: rounding of the
// substitutions and of the kernel's two evaluations (CellInfluenceRow against CellInfluence,
// 1e-13) times the blocks' condition number (below 1e2 on these grids: 1e-10 leaves margin).
constexpr double kFactoredSolveTolerance = 1e-10;

TEST(InfluenceOperator, PreconditionerSolvesEachFrequencysBlockExactly) {
  for (int ns : {1, 2, 7, 30}) {
    for (const PatchGrid& grid :
         {MakeArcGrid(1, ns, 2e-4, 4e-4, 10e-3), MakeParabolaGrid(1, ns, 2.5e-4, 4e-4)}) {
      const InfluenceSettings settings = MakeDissimilarSettings(KernelModel::kGolubenko);
      const auto op =
          MakeInfluenceOperator(grid, settings, OperatorProducts::kFft, SectionStructure::kBlocks);
      const Eigen::MatrixXd c = AssembleDenseInfluence(grid, settings);
      const Eigen::MatrixXd sym = 0.5 * (c + c.transpose());
      std::mt19937 rng(ns);
      std::uniform_real_distribution<double> value(-1e-6, 1e-6);
      Eigen::VectorXd r(grid.cells()), z;
      for (int k = 0; k < r.size(); ++k) r[k] = value(rng);
      ASSERT_TRUE(op->ApplyPreconditioner(r, &z));
      const Eigen::VectorXd expected = sym.llt().solve(r);
      EXPECT_LT((z - expected).cwiseAbs().maxCoeff(),
                kFactoredSolveTolerance * expected.cwiseAbs().maxCoeff())
          << "ns " << ns;
    }
  }
}

TEST(InfluenceOperator, HighestFrequencySymbolIsAboutHalfTheSelfTerm) {
  // The half-space symbol is smallest at the highest frequency (pi/dx, pi/ds); there it is
  // sum_j (-1)^(i_x + i_s) C_0j, about 0.5 C_00 for square cells on any grid. The inverses'
  // floor (0.1 C_kk, influence_operator.cpp) must stay well below it. Sum over a 61 x 61
  // neighbourhood (the alternating tail beyond is negligible).
  const PatchGrid grid = MakePlanarGrid(61, 61, 1e-4, 1e-4);
  const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kBoussinesq));
  Eigen::VectorXd e = Eigen::VectorXd::Zero(grid.cells()), u;
  e[grid.Index(30, 30)] = 1.0;
  op->Apply(e, &u);
  double symbol = 0.0;
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      symbol += ((i + j) % 2 == 0 ? 1.0 : -1.0) * u[grid.Index(i, j)];
    }
  }
  EXPECT_GT(symbol / op->Diagonal(0), 0.4);
  EXPECT_LT(symbol / op->Diagonal(0), 0.6);
}

TEST(InfluenceOperator, DenseOperatorHasNoPreconditioner) {
  const auto dense = MakeDenseInfluenceOperator(MakePlanarGrid(3, 4, 1e-4, 1e-4),
                                                MakeSettings(KernelModel::kBoussinesq));
  Eigen::VectorXd z = Eigen::VectorXd::Constant(2, 7.0);
  EXPECT_FALSE(dense->ApplyPreconditioner(Eigen::VectorXd::Ones(12), &z));
  EXPECT_EQ(z.size(), 2);  // untouched
  EXPECT_FALSE(dense->HasPreconditioner());
}

// The normal solver asks HasPreconditioner once per solve; the FFT operators answer it without
// applying their inverse (issue 20), and the answer is the one an application gives.
TEST(InfluenceOperator, FftOperatorsSayTheyHaveTheirPreconditioner) {
  const InfluenceSettings settings = MakeSettings(KernelModel::kBoussinesq);
  for (OperatorProducts products : {OperatorProducts::kFft, OperatorProducts::kDense}) {
    for (const auto& [grid, structure] :
         {std::pair{MakePlanarGrid(3, 4, 1e-4, 1e-4), SectionStructure::kAuto},
          std::pair{MakeArcGrid(5, 7, 2e-4, 4e-4, 10e-3), SectionStructure::kBlocks},
          std::pair{MakeParabolaGrid(5, 7, 2.5e-4, 4e-4), SectionStructure::kAuto}}) {
      const auto op = MakeInfluenceOperator(grid, settings, products, structure);
      EXPECT_TRUE(op->HasPreconditioner());
      Eigen::VectorXd z;
      EXPECT_TRUE(op->ApplyPreconditioner(Eigen::VectorXd::Ones(grid.cells()), &z));
      EXPECT_EQ(z.size(), grid.cells());
    }
  }
}

// One operator serves many normal solves on its grid (a creep table's cases, contact_reference_
// bench's reuse): after solves of other problems with it (its products' scratch reused), a solve
// equals, bit for bit, the solve with a freshly built operator. Dense products (11 x 11) and FFT
// products (16 x 16), prescribed load and approach.
TEST(InfluenceOperator, ReusedOperatorGivesTheFreshNormalSolveBitForBit) {
  Material steel;
  steel.youngs_modulus_Pa = 210e9;
  steel.poisson_ratio = 0.28;
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, steel, steel};
  for (const int mx : {11, 16}) {
    const PatchGrid g = testing::MakeHertzGrid(6e-3, 4e-3, mx, mx);
    auto problem = [&](const InfluenceOperator* op, double curvature_x_per_m, bool load) {
      NormalProblem np;
      np.blocks = {op};
      np.gap_m.resize(g.cells());
      for (int j = 0; j < g.ns; ++j) {
        for (int i = 0; i < g.nx; ++i) {
          np.gap_m[g.Index(i, j)] = 0.5 * (curvature_x_per_m * g.X(i) * g.X(i) +
                                           20.0 * g.S(j) * g.S(j));
        }
      }
      np.approach_weight = Eigen::VectorXd::Ones(g.cells());
      np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
      if (load) {
        np.force_N = 50e3;
      } else {
        np.approach_m = 40e-6;
      }
      return np;
    };
    const auto reused = MakeInfluenceOperator(g, settings);
    for (const bool load : {true, false}) {
      SolveNormal(problem(reused.get(), 5.0, !load));
      SolveNormal(problem(reused.get(), 12.0, load));
      const NormalSolution again = SolveNormal(problem(reused.get(), 8.0, load));
      const auto fresh = MakeInfluenceOperator(g, settings);
      SCOPED_TRACE(::testing::Message() << mx << " x " << mx << (load ? ", load" : ", approach"));
      ASSERT_EQ(again.status, SolverStatus::kConverged) << again.message;
      testing::ExpectSameNormal(again, SolveNormal(problem(fresh.get(), 8.0, load)));
    }
  }
}

// The curved operator's matrices live on memory recycled from earlier operators of the thread
// (core/numerics/pooled_buffer.h), whose contents are left over from them: an operator built
// after others (on their memory) equals, bit for bit, one built on a thread whose pool is empty
// (fresh memory), in its products, preconditioner and diagonal. Grids of decreasing size, so
// each takes over a larger earlier operator's memory.
TEST(InfluenceOperator, AnOperatorOnRecycledMemoryEqualsAFreshOneBitForBit) {
  const InfluenceSettings settings = MakeDissimilarSettings(KernelModel::kGolubenko);
  const std::vector<PatchGrid> grids = {MakeParabolaGrid(30, 25, 2.5e-4, 4e-4),
                                        MakeArcGrid(24, 20, 2e-4, 4e-4, 10e-3),
                                        MakeParabolaGrid(13, 12, 3e-4, 3e-4)};
  struct Outputs {
    Eigen::VectorXd u, z, diagonal;
  };
  auto outputs = [&](const PatchGrid& grid) {
    const auto op =
        MakeInfluenceOperator(grid, settings, OperatorProducts::kFft, SectionStructure::kBlocks);
    std::mt19937 rng(grid.cells());
    std::uniform_real_distribution<double> pressure(0.0, 2e9);
    Eigen::VectorXd p(grid.cells());
    for (int k = 0; k < p.size(); ++k) p[k] = pressure(rng);
    Outputs o;
    op->Apply(p, &o.u);
    EXPECT_TRUE(op->ApplyPreconditioner(o.u, &o.z));
    o.diagonal.resize(grid.cells());
    for (int k = 0; k < grid.cells(); ++k) o.diagonal[k] = op->Diagonal(k);
    return o;
  };
  std::vector<Outputs> recycled;
  for (const PatchGrid& grid : grids) recycled.push_back(outputs(grid));  // (each on the last's)
  ASSERT_GT(PooledBuffer::PooledCount(), 0u);
  for (size_t g = 0; g < grids.size(); ++g) {
    SCOPED_TRACE(::testing::Message() << "grid " << g);
    Outputs fresh;
    std::thread([&] { fresh = outputs(grids[g]); }).join();  // (a new thread: an empty pool)
    EXPECT_EQ(recycled[g].u, fresh.u);
    EXPECT_EQ(recycled[g].z, fresh.z);
    EXPECT_EQ(recycled[g].diagonal, fresh.diagonal);
  }
}

}  // namespace
}  // namespace railwear
