// Hertz's elliptical point contact and the 2-D line contact (formulas: reference README §1).
// GSL supplies the complete elliptic integrals and Brent's bracketed root finder for the axis
// ratio; GSL errors are returned as codes (handler off) and translated to exceptions here.
#include "core/contact/hertz.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_ellint.h>

namespace railwear {
namespace {

// GSL must report errors as return codes, never abort (STYLE.md "Errors").
const bool kGslHandlerOff = [] {
  gsl_set_error_handler_off();
  return true;
}();

// Below this r - 1 the series r = 1 + 3m/4 + O(m^2) gives m to ~1e-6 relative, i.e. g to
// ~1e-12; above it the closed form K - E loses at most ~1e-10 relative to cancellation.
constexpr double kNearCircleRatio = 1e-6;
// Relative accuracy of the axis ratio from the bracketed root finder.
constexpr double kAxisRatioRelTol = 1e-14;
constexpr int kMaxRootIterations = 200;

// K(m) and E(m) together, bit for bit internal::CompleteEllipticK and CompleteEllipticE: below
// k^2 = 1 - sqrt(eps) GSL's Kcomp(k) is Carlson's R_F(0, 1 - k^2, 1) and its Ecomp(k) is
// R_F - k^2/3 R_D of the same arguments, so one R_F serves both (above it, their series, from
// the two functions as before). The axis ratio's root finder calls this a dozen times per Hertz
// shape; sharing R_F saves a third of its elliptic-integral time. (Checked against Kcomp and
// Ecomp on 2e6 values of m in [0, 1), down to 1 - 1e-16: all equal.)
void CompleteEllipticKE(double m, double* K, double* E) {
  (void)kGslHandlerOff;
  const double k = std::sqrt(m);
  if (!(k * k < 1.0 - GSL_SQRT_DBL_EPSILON)) {
    *K = internal::CompleteEllipticK(m);
    *E = internal::CompleteEllipticE(m);
    return;
  }
  const double y = 1.0 - k * k;
  gsl_sf_result rf, rd;
  const int rf_status = gsl_sf_ellint_RF_e(0.0, y, 1.0, GSL_PREC_DOUBLE, &rf);
  const int rd_status = gsl_sf_ellint_RD_e(0.0, y, 1.0, GSL_PREC_DOUBLE, &rd);
  if (rf_status != GSL_SUCCESS || rd_status != GSL_SUCCESS) {
    throw std::runtime_error("elliptic integrals K, E(m = " + std::to_string(m) + ") failed: " +
                             gsl_strerror(rf_status != GSL_SUCCESS ? rf_status : rd_status));
  }
  *K = rf.val;
  *E = rf.val - k * k / 3.0 * rd.val;
}

// (larger curvature)/(smaller curvature) as a function of g = b/a (reference README §1).
double CurvatureRatio(double g) {
  const double m = (1.0 - g) * (1.0 + g);  // e^2, without cancellation near g = 1
  double k = 0.0, e = 0.0;
  CompleteEllipticKE(m, &k, &e);
  return (e / (g * g) - k) / (k - e);
}

struct RootParams {
  double target;
};

double RatioResidual(double g, void* params) {
  return CurvatureRatio(g) - static_cast<const RootParams*>(params)->target;
}

void CheckPositiveFinite(double v, const char* name) {
  if (!(std::isfinite(v) && v > 0.0)) {
    throw std::invalid_argument(std::string("Hertz: ") + name + " must be > 0 and finite, got " +
                                std::to_string(v));
  }
}

void CheckNonNegativeFinite(double v, const char* name) {
  if (!(std::isfinite(v) && v >= 0.0)) {
    throw std::invalid_argument(std::string("Hertz: ") + name + " must be >= 0 and finite, got " +
                                std::to_string(v));
  }
}

}  // namespace

namespace internal {

double CompleteEllipticK(double m) {
  (void)kGslHandlerOff;
  gsl_sf_result r;
  const int status = gsl_sf_ellint_Kcomp_e(std::sqrt(m), GSL_PREC_DOUBLE, &r);
  if (status != GSL_SUCCESS) {
    throw std::runtime_error("elliptic integral K(m = " + std::to_string(m) +
                             ") failed: " + gsl_strerror(status));
  }
  return r.val;
}

double CompleteEllipticE(double m) {
  (void)kGslHandlerOff;
  gsl_sf_result r;
  const int status = gsl_sf_ellint_Ecomp_e(std::sqrt(m), GSL_PREC_DOUBLE, &r);
  if (status != GSL_SUCCESS) {
    throw std::runtime_error("elliptic integral E(m = " + std::to_string(m) +
                             ") failed: " + gsl_strerror(status));
  }
  return r.val;
}

double HertzAxisRatio(double curvature_ratio) {
  if (!(curvature_ratio >= 1.0) || !std::isfinite(curvature_ratio)) {
    throw std::invalid_argument("Hertz: curvature ratio must be >= 1 and finite, got " +
                                std::to_string(curvature_ratio));
  }
  const double excess = curvature_ratio - 1.0;
  if (excess < kNearCircleRatio) return std::sqrt(1.0 - 4.0 * excess / 3.0);

  // Bracket: CurvatureRatio grows monotonically as g falls from 1 to 0.
  RootParams params{curvature_ratio};
  // Upper end: r(m) ~ 1 + 3m/4, so m = excess/2 lies below the root; shrink if needed.
  double m_hi = std::min(0.5 * excess, 0.5);
  double g_hi = std::sqrt(1.0 - m_hi);
  while (RatioResidual(g_hi, &params) >= 0.0) {
    m_hi *= 0.25;
    if (m_hi < 1e-12) throw std::runtime_error("Hertz: cannot bracket the axis ratio (upper)");
    g_hi = std::sqrt(1.0 - m_hi);
  }
  // Lower end: r ~ 1/(g^2 (ln(4/g) - 1)) for small g; halve until past the root.
  double g_lo = std::min(0.5, g_hi * 0.5);
  while (RatioResidual(g_lo, &params) <= 0.0) {
    g_lo *= 0.5;
    if (g_lo < 1e-7) {
      throw std::runtime_error("Hertz: curvature ratio " + std::to_string(curvature_ratio) +
                               " too extreme to bracket the axis ratio");
    }
  }

  gsl_function f{&RatioResidual, &params};
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (solver == nullptr) throw std::runtime_error("Hertz: cannot allocate GSL root solver");
  int status = gsl_root_fsolver_set(solver, &f, g_lo, g_hi);
  double g = 0.5 * (g_lo + g_hi);
  for (int it = 0; status == GSL_SUCCESS && it < kMaxRootIterations; ++it) {
    status = gsl_root_fsolver_iterate(solver);
    if (status != GSL_SUCCESS) break;
    g = gsl_root_fsolver_root(solver);
    const double lo = gsl_root_fsolver_x_lower(solver);
    const double hi = gsl_root_fsolver_x_upper(solver);
    status = gsl_root_test_interval(lo, hi, 0.0, kAxisRatioRelTol);
    if (status == GSL_SUCCESS) break;
    if (status == GSL_CONTINUE) status = GSL_SUCCESS;
  }
  gsl_root_fsolver_free(solver);
  if (status != GSL_SUCCESS) {
    throw std::runtime_error(std::string("Hertz: axis-ratio root finder failed: ") +
                             gsl_strerror(status));
  }
  return g;
}

}  // namespace internal

HertzShape::HertzShape(double A_per_m, double B_per_m) : A_per_m_(A_per_m), B_per_m_(B_per_m) {
  CheckPositiveFinite(A_per_m, "curvature A");
  CheckPositiveFinite(B_per_m, "curvature B");
  const double small = std::min(A_per_m, B_per_m);
  const double large = std::max(A_per_m, B_per_m);
  g_ = internal::HertzAxisRatio(large / small);
  const double m = (1.0 - g_) * (1.0 + g_);
  CompleteEllipticKE(m, &k_, &e_);
}

HertzSolution HertzShape::Solve(double contact_modulus_Pa, double force_N) const {
  CheckPositiveFinite(contact_modulus_Pa, "contact modulus E*");
  CheckNonNegativeFinite(force_N, "force P");
  HertzSolution s;
  s.force_N = force_N;
  if (force_N == 0.0) return s;
  const double g = g_, k = k_, e = e_;
  const double pi = std::numbers::pi;
  const double c3 =
      3.0 * force_N * e / (2.0 * pi * contact_modulus_Pa * (A_per_m_ + B_per_m_) * std::sqrt(g));
  const double c = std::cbrt(c3);
  const double a = c / std::sqrt(g);  // major semi-axis, along the smaller curvature
  const double b = c * std::sqrt(g);
  s.p0_Pa = 3.0 * force_N / (2.0 * pi * a * b);
  s.approach_m = s.p0_Pa * b * k / contact_modulus_Pa;
  s.area_m2 = pi * a * b;
  // The major axis lies along the direction of the smaller curvature.
  if (A_per_m_ <= B_per_m_) {
    s.semi_axis_x_m = a;
    s.semi_axis_y_m = b;
  } else {
    s.semi_axis_x_m = b;
    s.semi_axis_y_m = a;
  }
  return s;
}

HertzSolution HertzShape::SolveForApproach(double contact_modulus_Pa, double approach_m) const {
  CheckNonNegativeFinite(approach_m, "approach delta");
  // delta is proportional to P^(2/3): scale from the solution for a unit force.
  const HertzSolution unit = Solve(contact_modulus_Pa, 1.0);
  const double force_N = std::pow(approach_m / unit.approach_m, 1.5);
  HertzSolution s = Solve(contact_modulus_Pa, force_N);
  s.approach_m = approach_m;  // exact by construction; avoid the round-trip rounding
  return s;
}

HertzSolution SolveHertz(double A_per_m, double B_per_m, double contact_modulus_Pa,
                         double force_N) {
  CheckPositiveFinite(A_per_m, "curvature A");
  CheckPositiveFinite(B_per_m, "curvature B");
  CheckPositiveFinite(contact_modulus_Pa, "contact modulus E*");
  CheckNonNegativeFinite(force_N, "force P");
  if (force_N == 0.0) {  // no axis ratio needed (nor a failure to find one)
    HertzSolution s;
    s.force_N = force_N;
    return s;
  }
  return HertzShape(A_per_m, B_per_m).Solve(contact_modulus_Pa, force_N);
}

HertzSolution SolveHertzForApproach(double A_per_m, double B_per_m, double contact_modulus_Pa,
                                    double approach_m) {
  CheckNonNegativeFinite(approach_m, "approach delta");
  // The unit-force solve checked A, B and E* first (SolveHertz's order).
  CheckPositiveFinite(A_per_m, "curvature A");
  CheckPositiveFinite(B_per_m, "curvature B");
  CheckPositiveFinite(contact_modulus_Pa, "contact modulus E*");
  return HertzShape(A_per_m, B_per_m).SolveForApproach(contact_modulus_Pa, approach_m);
}

LineContactSolution SolveLineContact(double force_per_length_N_m, double relative_radius_m,
                                     double contact_modulus_Pa) {
  CheckNonNegativeFinite(force_per_length_N_m, "force per length P'");
  CheckPositiveFinite(relative_radius_m, "relative radius R");
  CheckPositiveFinite(contact_modulus_Pa, "contact modulus E*");
  LineContactSolution s;
  if (force_per_length_N_m == 0.0) return s;
  const double pi = std::numbers::pi;
  s.half_width_m =
      std::sqrt(4.0 * force_per_length_N_m * relative_radius_m / (pi * contact_modulus_Pa));
  s.p0_Pa = 2.0 * force_per_length_N_m / (pi * s.half_width_m);
  return s;
}

}  // namespace railwear
