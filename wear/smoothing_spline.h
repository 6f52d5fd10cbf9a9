// Smoothing cubic spline of a vector-valued function g(t) of one parameter t (arc length), fitted
// with Ceres: used to smooth measured profiles (wear/profile_fit.h, dimension 2: y and z) and the
// wear-depth field after each wear step (wear/depth_smoothing.h, dimension 1).
//
// The spline is a uniform cubic B-spline on K equal intervals of [t_min, t_max] (K + 3
// coefficients, each a vector of the value dimension). It minimises
//
//     J(c) = sum_i w_i rho(|g(t_i) - v_i|^2) + lambda * integral |g''(t)|^2 dt
//
// where rho is the identity (least squares) or a robust loss (Huber, Cauchy) with scale a.
// g'' is linear on each interval, so the two-point Gauss rule per interval integrates the
// penalty exactly; each Gauss point is a residual row. The default weights are the mean data
// spacing, so that the data term approximates integral |g - v|^2 dt and lambda has the units
// [t]^4: for dense, evenly weighted data the fit damps a Fourier component of wavelength L by the
// factor 1 / (1 + lambda (2 pi / L)^4) (the Reinsch smoothing spline's transfer function). The
// smoothing length l = lambda^(1/4) is therefore the cut-off: wavelengths 2 pi l keep half their
// amplitude, shorter ones are damped as (wavelength / (2 pi l))^4.
//
// How lambda is chosen when not given: generalised cross-validation (Craven & Wahba 1979),
//     V(lambda) = n RSS_w(lambda) / (n - tr A(lambda))^2,
// A the influence ("hat") matrix of the least-squares problem, minimised over log lambda on a
// coarse grid then refined by golden section. tr A comes from the band of the inverse of the
// banded normal matrix (Hutchinson & de Hoog 1985), so one evaluation costs O(K). GCV is
// evaluated for the quadratic problem in closed form (banded normal equations); with a robust
// loss it is evaluated a second time with the robust (IRLS) weights of the first robust fit.
//
// How the fit runs: the closed-form least-squares solution at the chosen lambda is the starting
// point; the Ceres problem (LEVENBERG_MARQUARDT, SPARSE_NORMAL_CHOLESKY: the Jacobian is
// banded; one residual block per knot interval, or per point with a loss) then adds what the
// closed form does not have: the robust loss, coefficient bounds (lower_bound, dimension 1;
// B-splines are non-negative and sum to one, so c_j >= b implies g >= b; Ceres' bounds plus an
// active-set loop that holds coefficients at the bound constant and releases them by the sign
// of the gradient, because projected steps alone crawl along active bounds), and a
// weighted-sum constraint (one heavily weighted residual keeping sum_i w_i g(t_i) equal to
// sum_i w_i v_i: the worn area of a depth field).
//
// Robust fitting (loss != kNone), in three stages:
//  1. Scale: sigma = 1.4826 * median of the standardised residual norms |r_i| / sqrt(1 - A_ii)
//     of the least-squares fit (the residual of a curve fit lies essentially along the normal,
//     so its norm is treated as one-dimensional), floored at min_robust_scale (exact data would
//     otherwise treat their own approximation error as noise).
//  2. Rejection: points whose standardised residual exceeds reject_threshold * sigma are left
//     out (weight 0) and the least-squares fit (and GCV) repeated until the set settles; a
//     left-out point within the threshold of the new fit is taken back. The caller may name
//     suspects to leave out of the first fit: when GCV chooses a tiny lambda (very clean data)
//     every point has leverage near 1 and residuals cannot reveal a cluster of glitches, while
//     a bounded-influence loss alone would still let the spline bend toward them.
//  3. M-estimation: the Ceres fit with the loss (scale a = robust_threshold * sigma) on the
//     remaining points, started from the least-squares fit; with GCV, lambda is chosen once more
//     with the loss's IRLS weights rho'(r^2) and Ceres run again.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace railwear {

enum class RobustLoss { kNone, kHuber, kCauchy };
std::string_view ToString(RobustLoss v);  // "none", "huber", "cauchy"
std::optional<RobustLoss> RobustLossFromString(std::string_view s);

enum class SmoothingSplineStatus {
  kConverged,      // Ceres reported convergence
  kNoConvergence,  // iteration limit reached; the coefficients are the last (usable) iterate
  kFailure,        // Ceres failed (numerical failure); the coefficients are the starting point
};
std::string_view ToString(SmoothingSplineStatus v);  // "converged", "no-convergence", "failure"
std::optional<SmoothingSplineStatus> SmoothingSplineStatusFromString(std::string_view s);

struct SmoothingSplineOptions {
  // Target knot spacing [units of t], > 0. The range [t_min, t_max] is cut into
  // K = max(1, ceil(range / knot_spacing)) equal intervals. 0.5 mm suits profiles.
  double knot_spacing = 0.5e-3;

  // Penalty weight lambda [t^4] (>= 0). Empty: chosen by GCV.
  std::optional<double> lambda;
  // GCV searches the smoothing length l = lambda^(1/4) between these multiples of the knot
  // spacing, log-evenly on gcv_grid_points points, then refines by golden section. The lower
  // end 0.1: below it the penalty no longer controls a coefficient that only a point or two at
  // the edge of a data gap (rejected glitches) touch, and bridges go wild; l = 0.05 mm still
  // reproduces S1002 to 0.5 um.
  double gcv_min_length_ratio = 0.1;
  double gcv_max_length_ratio = 100.0;
  int gcv_grid_points = 25;  // >= 3
  // V uses n - gcv_dof_factor * tr A (>= 1). 1 is GCV proper; 1.4 is the "modified GCV" of
  // Cummins, Filloon & Nychka (2001), which counters GCV's undersmoothing of correlated noise
  // (e.g. coordinates rounded to 0.01 mm along a shallow slope).
  double gcv_dof_factor = 1.0;

  RobustLoss loss = RobustLoss::kHuber;
  // Loss scale a = robust_threshold * sigma (> 0): residuals beyond a are down-weighted.
  double robust_threshold = 3.0;
  // sigma given by the caller [value units] (> 0); empty: from the MAD of the first fit.
  std::optional<double> robust_scale;
  // Floor for the estimated sigma [value units] (>= 0). 1e-6: 1 um, below any profile gauge.
  double min_robust_scale = 1e-6;
  // With a loss: points whose standardised least-squares residual exceeds reject_threshold *
  // sigma are left out as gross outliers (>= 0; 0 disables). 10: never reached by Gaussian
  // noise, while a scan glitch of 0.1 mm on 1-10 um noise is 10-100 times beyond it.
  double reject_threshold = 10.0;

  // g, g' and g'' vanish at t_min (clamp_start) / t_max (clamp_end): the first / last three
  // coefficients are held at 0, so the spline joins a zero field outside with C2 continuity.
  bool clamp_start = false;
  bool clamp_end = false;
  // Lower bound on every coefficient (hence on g) [value units]; empty: unbounded. Needs value
  // dimension 1 (FitSmoothingSpline throws otherwise).
  std::optional<double> lower_bound;
  // Keep sum_i w_i g(t_i) = sum_i w_i v_i (per component) through one residual whose weight is
  // sum_constraint_weight (> 0) times that of the data term; the remaining relative error is
  // reported in the summary (about 1/sum_constraint_weight of what the bounds would move).
  bool preserve_weighted_sum = false;
  double sum_constraint_weight = 1e6;

  // Ceres: iteration limit (>= 1) and relative tolerances (> 0) on cost change and step.
  int max_num_iterations = 200;
  double function_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;

  // False with a message naming the first bad option, its value and what was expected.
  bool IsValid(std::string* error) const;
};

// A uniform cubic B-spline g: [t_begin, t_end] -> R^dim. Outside the range the end cubics are
// extended.
class SmoothingSpline {
 public:
  SmoothingSpline() = default;
  // coefficients: shape [num_intervals + 3][dim]; knot spacing h > 0, num_intervals >= 1.
  SmoothingSpline(double t_begin, double knot_spacing, int num_intervals,
                  Eigen::MatrixXd coefficients);

  int dim() const { return static_cast<int>(coefficients_.cols()); }
  int num_intervals() const { return num_intervals_; }
  double t_begin() const { return t_begin_; }
  double t_end() const { return t_begin_ + knot_spacing_ * num_intervals_; }
  double knot_spacing() const { return knot_spacing_; }
  const Eigen::MatrixXd& coefficients() const { return coefficients_; }

  // Value, first and second derivative with respect to t at t; shape [dim].
  Eigen::VectorXd Value(double t) const;
  Eigen::VectorXd Derivative(double t) const;
  Eigen::VectorXd SecondDerivative(double t) const;
  // All three at once; any pointer may be null.
  void Evaluate(double t, Eigen::VectorXd* value, Eigen::VectorXd* d1, Eigen::VectorXd* d2) const;

 private:
  double t_begin_ = 0.0;
  double knot_spacing_ = 1.0;
  int num_intervals_ = 0;
  Eigen::MatrixXd coefficients_;
};

struct SmoothingSplineSummary {
  SmoothingSplineStatus status = SmoothingSplineStatus::kFailure;
  std::string message;  // Ceres' termination message, or why the fit failed

  int num_points = 0;
  int dim = 0;
  int num_coefficients = 0;  // K + 3 (per component)
  double knot_spacing = 0.0;

  double lambda = 0.0;           // penalty weight used [t^4]
  bool lambda_from_gcv = false;  // true when chosen by GCV
  double gcv_score = 0.0;        // V(lambda) at the choice (0 when lambda was given)
  double effective_dof = 0.0;    // tr A at lambda with the final weights (per component)

  // Residuals r_i = |g(t_i) - v_i| of the final fit (unweighted) [value units].
  double rms_residual = 0.0;
  double max_residual = 0.0;
  int max_residual_index = -1;

  RobustLoss loss = RobustLoss::kNone;
  double robust_sigma = 0.0;         // sigma [value units] (0 without a loss)
  double loss_scale = 0.0;           // a = robust_threshold * sigma
  int num_rejected = 0;              // gross outliers left out of the fit
  int num_downweighted = 0;          // other points with r_i > a (the loss reduced their weight)
  double rms_inlier_residual = 0.0;  // RMS residual of the points not rejected

  // (sum w g - sum w v) / |sum w v| of the component with the largest magnitude, before any
  // correction by the caller; 0 unless preserve_weighted_sum.
  double relative_sum_error = 0.0;

  // Levenberg-Marquardt iterations of the final Ceres solve (summed over its active-set rounds)
  int num_ceres_iterations = 0;
  int num_ceres_solves = 0;  // Ceres solves (1, or 2 with a robust loss and GCV)
  double time_s = 0.0;       // wall time of the whole fit

  // One line: status, points, knots, lambda and how chosen, RMS and max residual, outliers.
  std::string BriefReport() const;
};

struct SmoothingSplineFit {
  SmoothingSpline spline;
  SmoothingSplineSummary summary;
  std::vector<bool> rejected;  // [n]: true for the points left out as gross outliers
};

// Fits the smoothing spline to the data.
//   t:       shape [n], parameter values, finite, in any order, t_max > t_min, n >= 2.
//   values:  shape [n][dim], dim in 1..3, finite.
//   weights: shape [n], finite and > 0; or empty for the default (mean spacing
//            (t_max - t_min) / (n - 1) for every point).
//   suspects: shape [n] or empty: points to leave out of the first least-squares fit of the
//            rejection stage (found by some other test); the rejection rounds take back those
//            that lie within the threshold of the fit. Ignored without a loss or rejection.
// Throws InputError for invalid options (IsValid's message) or data (naming the index and value).
// An expected numerical outcome (no convergence) is reported in the summary's status instead.
SmoothingSplineFit FitSmoothingSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& values,
                                      const Eigen::VectorXd& weights,
                                      const SmoothingSplineOptions& options,
                                      const std::vector<bool>& suspects = {});

}  // namespace railwear
