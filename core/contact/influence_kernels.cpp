// Cell-integrated influence kernels (Love's closed forms, seed eq. 4) and the dense reference
// operator. See influence_operator.h for the conventions.
#include "core/contact/influence_kernels.h"

#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "core/contact/seed_kernel.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"

namespace railwear {
namespace internal {
namespace {

// xi * asinh(eta / sqrt(xi^2 + n^2)), with its limit 0 at xi = 0 (also when n = 0). This is the
// form of xi ln(eta + R) that stays finite and accurate when eta + R -> 0.
double XiAsinh(double xi, double eta, double n) {
  if (xi == 0.0) return 0.0;
  return xi * std::asinh(eta / std::sqrt(xi * xi + n * n));
}

// atan(xi eta / (n R)) at one corner; 0 when n = 0 (the n-terms vanish with n).
double CornerAtan(double xi, double eta, double n) {
  if (n == 0.0) return 0.0;
  const double r = std::sqrt(xi * xi + eta * eta + n * n);
  return std::atan(xi * eta / (n * r));
}

// RectangleIntegralsFarField, inlined into the operators' rows (whose far offsets it vectorizes).
[[gnu::always_inline]] inline void FarFieldRule(double x, double s, double n, double hx, double hs,
                                                double* inv_r, double* n2_r3) {
  // Product midpoint rule with the Taylor expansion about the centre to fourth order:
  //   int f dA ~= A [f + (hx^2 f_xx + hs^2 f_ss) / 24
  //                    + (hx^4 f_xxxx + hs^4 f_ssss) / 1920 + hx^2 hs^2 f_xxss / 576],
  // error O(h^6 / R^6) relative. With X = x^2/R^2, S = s^2/R^2, a = hx^2/R^2, b = hs^2/R^2:
  //   f = 1/R:      f_xx R^3 = 3X - 1,  f_xxxx R^5 = 3 (35X^2 - 30X + 3),
  //                 f_xxss R^5 = 3 (35XS - 5X - 5S + 1)
  //   g = R^-3:     g_xx R^5 = 3 (5X - 1),  g_xxxx R^7 = 45 (21X^2 - 14X + 1),
  //                 g_xxss R^7 = 15 (63XS - 7X - 7S + 1)
  // (and f_ss, f_ssss, g_ss, g_ssss with S for X).
  // (One division and one square root; the constant divisors as products.)
  constexpr double k1_24 = 1.0 / 24.0, k1_1920 = 1.0 / 1920.0;
  const double r2 = x * x + s * s + n * n;
  const double q = 1.0 / r2;
  const double inv_centre = std::sqrt(q);
  const double X = x * x * q, S = s * s * q, a = hx * hx * q, b = hs * hs * q;
  const double aa = a * a, ab = a * b, bb = b * b;
  const double f2 = (a * (3.0 * X - 1.0) + b * (3.0 * S - 1.0)) * k1_24;
  const double f4 = (3.0 * aa * (3.0 - 30.0 * X + 35.0 * X * X) +
                     10.0 * ab * (1.0 - 5.0 * (X + S) + 35.0 * X * S) +
                     3.0 * bb * (3.0 - 30.0 * S + 35.0 * S * S)) *
                    k1_1920;
  const double g2 = (a * (5.0 * X - 1.0) + b * (5.0 * S - 1.0)) * 0.125;
  const double g4 = (45.0 * aa * (1.0 - 14.0 * X + 21.0 * X * X) +
                     50.0 * ab * (1.0 - 7.0 * (X + S) + 63.0 * X * S) +
                     45.0 * bb * (1.0 - 14.0 * S + 21.0 * S * S)) *
                    k1_1920;
  const double area_over_r = hx * hs * inv_centre;
  *inv_r = area_over_r * (1.0 + f2 + f4);
  *n2_r3 = area_over_r * n * n * q * (1.0 + g2 + g4);
}

void CheckMaterial(const Material& m, const char* which) {
  if (!(m.youngs_modulus_Pa > 0.0) || !(m.poisson_ratio >= 0.0 && m.poisson_ratio < 0.5)) {
    std::ostringstream msg;
    msg << "influence: " << which << " material has E = " << m.youngs_modulus_Pa
        << " Pa and nu = " << m.poisson_ratio << "; expected E > 0 and 0 <= nu < 0.5";
    throw InputError(msg.str());
  }
}

}  // namespace

KernelCoefficients MakeKernelCoefficients(const InfluenceSettings& settings) {
  CheckMaterial(settings.wheel, "wheel");
  CheckMaterial(settings.rail, "rail");
  KernelCoefficients c;
  const std::pair<const Material*, int> bodies[2] = {
      {&settings.wheel, settings.wheel_curvature_sign},
      {&settings.rail, settings.rail_curvature_sign}};
  for (const auto& [m, sign] : bodies) {
    const double nu = m->poisson_ratio;
    const double g = m->ShearModulus();
    if (settings.kernel == KernelModel::kBoussinesq) {
      c.inv_r += (1.0 - nu) / (2.0 * std::numbers::pi * g);
    } else {
      const InfluenceConstantSet set = settings.constants.ForBody(sign);
      const double k_d = SeedKernelKd(*m);
      const double k_f = SeedKernelKf(*m, k_d);
      c.inv_r += set.c_f * k_f;
      c.n2_r3 += set.c_z * k_d;
    }
  }
  return c;
}

void RectangleIntegralsClosedForm(double x, double s, double n, double hx, double hs, double* inv_r,
                                  double* n2_r3) {
  // Mixed antiderivatives in the offsets (xi, eta) from the field point to a corner:
  //   F = xi asinh(eta / sqrt(xi^2 + n^2)) + eta asinh(xi / sqrt(eta^2 + n^2)) - n A,
  //   G = n A,  A = atan(xi eta / (n R)),
  // combined over the corners with signs + - - +.
  const double xs[2] = {x - 0.5 * hx, x + 0.5 * hx};
  const double ss[2] = {s - 0.5 * hs, s + 0.5 * hs};
  double f = 0.0;
  double a = 0.0;
  for (int ix = 0; ix < 2; ++ix) {
    for (int is = 0; is < 2; ++is) {
      const double sign = (ix == is) ? 1.0 : -1.0;
      const double xi = xs[ix];
      const double eta = ss[is];
      f += sign * (XiAsinh(xi, eta, n) + XiAsinh(eta, xi, n));
      a += sign * CornerAtan(xi, eta, n);
    }
  }
  *inv_r = f - n * a;
  *n2_r3 = n * a;
}

void RectangleIntegralsFarField(double x, double s, double n, double hx, double hs, double* inv_r,
                                double* n2_r3) {
  FarFieldRule(x, s, n, hx, hs, inv_r, n2_r3);
}

void RectangleIntegrals(double x, double s, double n, double hx, double hs, double* inv_r,
                        double* n2_r3) {
  const double r2 = x * x + s * s + n * n;
  const double far2 = kFarFieldDiagonals * kFarFieldDiagonals * (hx * hx + hs * hs);
  if (r2 > far2) {
    RectangleIntegralsFarField(x, s, n, hx, hs, inv_r, n2_r3);
  } else {
    RectangleIntegralsClosedForm(x, s, n, hx, hs, inv_r, n2_r3);
  }
}

double CellInfluence(const PatchGrid& grid, const KernelCoefficients& coefficients, int field_ix,
                     int field_is, int source_ix, int source_is) {
  const Eigen::Vector2d d_yz = grid.point_yz_m[field_is] - grid.point_yz_m[source_is];
  const double dx = (field_ix - source_ix) * grid.dx_m;
  const double ds = d_yz.dot(grid.tangent_yz[source_is]);
  const double dn = d_yz.dot(grid.normal_yz[source_is]);
  double inv_r = 0.0;
  double n2_r3 = 0.0;
  RectangleIntegrals(dx, ds, dn, grid.dx_m, grid.ds_m, &inv_r, &n2_r3);
  return coefficients.inv_r * inv_r + coefficients.n2_r3 * n2_r3;
}

void CellInfluenceRow(const PatchGrid& grid, const KernelCoefficients& coefficients, int field_is,
                      int source_is, double* out) {
  // The offsets as CellInfluence computes them.
  const Eigen::Vector2d d_yz = grid.point_yz_m[field_is] - grid.point_yz_m[source_is];
  const double ds = d_yz.dot(grid.tangent_yz[source_is]);
  const double dn = d_yz.dot(grid.normal_yz[source_is]);
  const double hx = grid.dx_m, hs = grid.ds_m;
  const double far2 = kFarFieldDiagonals * kFarFieldDiagonals * (hx * hx + hs * hs);
  const double ss[2] = {ds - 0.5 * hs, ds + 0.5 * hs};
  // RectangleIntegralsClosedForm's corner terms at one x corner xi: f's term and the atan, for
  // both s corners.
  struct Corner {
    double xi;
    double f[2], a[2];
  };
  auto corner = [&](double xi) {
    Corner c{xi, {}, {}};
    for (int is = 0; is < 2; ++is) {
      c.f[is] = XiAsinh(xi, ss[is], dn) + XiAsinh(ss[is], xi, dn);
      c.a[is] = CornerAtan(xi, ss[is], dn);
    }
    return c;
  };
  // r2 grows with d, so the near offsets (closed forms) come first and the far ones (the far-field
  // rule, in a loop of its own that the compiler vectorizes) after them.
  const auto near = [&](int d) {
    const double x = d * hx;
    return !(x * x + ds * ds + dn * dn > far2);  // RectangleIntegrals' test, its r2 bit for bit
  };
  int d = 0;
  Corner upper{};  // the last offset's upper x corner
  for (; d < grid.nx && near(d); ++d) {
    // RectangleIntegralsClosedForm(x, ds, dn, hx, hs) with its corners, terms and sums in its
    // order; the lower corner is the last offset's upper one when both round alike.
    const double x = d * hx;
    const double x_lo = x - 0.5 * hx, x_hi = x + 0.5 * hx;
    const Corner lower = d > 0 && upper.xi == x_lo ? upper : corner(x_lo);
    upper = corner(x_hi);
    const Corner* xs[2] = {&lower, &upper};
    double f = 0.0;
    double a = 0.0;
    for (int ix = 0; ix < 2; ++ix) {
      for (int is = 0; is < 2; ++is) {
        const double sign = (ix == is) ? 1.0 : -1.0;
        f += sign * xs[ix]->f[is];
        a += sign * xs[ix]->a[is];
      }
    }
    out[d] = coefficients.inv_r * (f - dn * a) + coefficients.n2_r3 * (dn * a);
  }
  for (; d < grid.nx; ++d) {
    double inv_r = 0.0;
    double n2_r3 = 0.0;
    FarFieldRule(d * hx, ds, dn, hx, hs, &inv_r, &n2_r3);
    out[d] = coefficients.inv_r * inv_r + coefficients.n2_r3 * n2_r3;
  }
}

void CheckGrid(const PatchGrid& grid) {
  RAILWEAR_CHECK(grid.nx >= 1 && grid.ns >= 1);
  RAILWEAR_CHECK(grid.dx_m > 0.0 && grid.ds_m > 0.0);
  RAILWEAR_CHECK(static_cast<int>(grid.point_yz_m.size()) == grid.ns);
  RAILWEAR_CHECK(static_cast<int>(grid.tangent_yz.size()) == grid.ns);
  RAILWEAR_CHECK(static_cast<int>(grid.normal_yz.size()) == grid.ns);
}

}  // namespace internal

double RectangleIntegralInvR(double x, double s, double n, double hx, double hs) {
  double inv_r = 0.0;
  double n2_r3 = 0.0;
  internal::RectangleIntegralsClosedForm(x, s, n, hx, hs, &inv_r, &n2_r3);
  return inv_r;
}

double RectangleIntegralN2R3(double x, double s, double n, double hx, double hs) {
  double inv_r = 0.0;
  double n2_r3 = 0.0;
  internal::RectangleIntegralsClosedForm(x, s, n, hx, hs, &inv_r, &n2_r3);
  return n2_r3;
}

Eigen::MatrixXd AssembleDenseInfluence(const PatchGrid& grid, const InfluenceSettings& settings) {
  internal::CheckGrid(grid);
  const internal::KernelCoefficients coefficients = internal::MakeKernelCoefficients(settings);
  const int n = grid.cells();
  Eigen::MatrixXd c(n, n);
  for (int js = 0; js < grid.ns; ++js) {
    for (int jx = 0; jx < grid.nx; ++jx) {
      const int j = grid.Index(jx, js);
      for (int is = 0; is < grid.ns; ++is) {
        for (int ix = 0; ix < grid.nx; ++ix) {
          c(grid.Index(ix, is), j) = internal::CellInfluence(grid, coefficients, ix, is, jx, js);
        }
      }
    }
  }
  return c;
}

namespace {

class DenseInfluenceOperator final : public InfluenceOperator {
 public:
  explicit DenseInfluenceOperator(Eigen::MatrixXd c) : c_(std::move(c)) {}
  int size() const override { return static_cast<int>(c_.rows()); }
  void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) const override {
    RAILWEAR_CHECK(p.size() == c_.cols());
    u->noalias() = c_ * p;
  }
  double Diagonal(int k) const override { return c_(k, k); }

 private:
  Eigen::MatrixXd c_;
};

}  // namespace

std::unique_ptr<InfluenceOperator> MakeDenseInfluenceOperator(const PatchGrid& grid,
                                                              const InfluenceSettings& settings) {
  return std::make_unique<DenseInfluenceOperator>(AssembleDenseInfluence(grid, settings));
}

}  // namespace railwear
