// Smoothing cubic spline: uniform cubic B-spline basis, closed-form banded solve and GCV, and the
// Ceres problem (robust loss, bounds, weighted-sum constraint). See smoothing_spline.h.
#include "wear/smoothing_spline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "core/numerics/check.h"
#include "core/numerics/input_error.h"

namespace railwear {

std::string_view ToString(RobustLoss v) {
  switch (v) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "?";
}

std::optional<RobustLoss> RobustLossFromString(std::string_view s) {
  for (RobustLoss v : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    if (ToString(v) == s) return v;
  }
  return std::nullopt;
}

std::string_view ToString(SmoothingSplineStatus v) {
  switch (v) {
    case SmoothingSplineStatus::kConverged:
      return "converged";
    case SmoothingSplineStatus::kNoConvergence:
      return "no-convergence";
    case SmoothingSplineStatus::kFailure:
      return "failure";
  }
  return "?";
}

std::optional<SmoothingSplineStatus> SmoothingSplineStatusFromString(std::string_view s) {
  for (SmoothingSplineStatus v :
       {SmoothingSplineStatus::kConverged, SmoothingSplineStatus::kNoConvergence,
        SmoothingSplineStatus::kFailure}) {
    if (ToString(v) == s) return v;
  }
  return std::nullopt;
}

namespace {

bool Fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = "smoothing spline options: " + message;
  return false;
}

bool PositiveFinite(double x) { return std::isfinite(x) && x > 0.0; }

}  // namespace

bool SmoothingSplineOptions::IsValid(std::string* error) const {
  if (!PositiveFinite(knot_spacing)) {
    return Fail(error,
                fmt::format("knot_spacing = {}: expected a finite number > 0", knot_spacing));
  }
  if (lambda && !(std::isfinite(*lambda) && *lambda >= 0.0)) {
    return Fail(error, fmt::format("lambda = {}: expected a finite number >= 0", *lambda));
  }
  if (!PositiveFinite(gcv_min_length_ratio) || !PositiveFinite(gcv_max_length_ratio) ||
      !(gcv_min_length_ratio < gcv_max_length_ratio)) {
    return Fail(error, fmt::format("gcv_min_length_ratio = {}, gcv_max_length_ratio = {}: "
                                   "expected 0 < min < max",
                                   gcv_min_length_ratio, gcv_max_length_ratio));
  }
  if (gcv_grid_points < 3) {
    return Fail(error, fmt::format("gcv_grid_points = {}: expected >= 3", gcv_grid_points));
  }
  if (!(std::isfinite(gcv_dof_factor) && gcv_dof_factor >= 1.0)) {
    return Fail(error,
                fmt::format("gcv_dof_factor = {}: expected a finite number >= 1", gcv_dof_factor));
  }
  if (!(std::isfinite(reject_threshold) && reject_threshold >= 0.0)) {
    return Fail(error, fmt::format("reject_threshold = {}: expected a finite number >= 0",
                                   reject_threshold));
  }
  if (!PositiveFinite(robust_threshold)) {
    return Fail(error, fmt::format("robust_threshold = {}: expected a finite number > 0",
                                   robust_threshold));
  }
  if (robust_scale && !PositiveFinite(*robust_scale)) {
    return Fail(error,
                fmt::format("robust_scale = {}: expected a finite number > 0", *robust_scale));
  }
  if (!(std::isfinite(min_robust_scale) && min_robust_scale >= 0.0)) {
    return Fail(error, fmt::format("min_robust_scale = {}: expected a finite number >= 0",
                                   min_robust_scale));
  }
  if (lower_bound && !std::isfinite(*lower_bound)) {
    return Fail(error, fmt::format("lower_bound = {}: expected a finite number", *lower_bound));
  }
  if (lower_bound && *lower_bound > 0.0 && (clamp_start || clamp_end)) {
    return Fail(error, fmt::format("lower_bound = {} with a clamped end (g = 0 there): expected "
                                   "lower_bound <= 0",
                                   *lower_bound));
  }
  if (!PositiveFinite(sum_constraint_weight)) {
    return Fail(error, fmt::format("sum_constraint_weight = {}: expected a finite number > 0",
                                   sum_constraint_weight));
  }
  if (max_num_iterations < 1) {
    return Fail(error, fmt::format("max_num_iterations = {}: expected >= 1", max_num_iterations));
  }
  if (!PositiveFinite(function_tolerance) || !PositiveFinite(parameter_tolerance)) {
    return Fail(error, fmt::format("function_tolerance = {}, parameter_tolerance = {}: expected "
                                   "finite numbers > 0",
                                   function_tolerance, parameter_tolerance));
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Uniform cubic B-spline basis. On interval k (t_k <= t < t_k+1, u = (t - t_k)/h in [0, 1]) the
// spline is g = sum_r c_{k+r} b_r(u), r = 0..3.
namespace {

constexpr int kOrder = 4;  // cubic: four basis functions are non-zero on each interval
using Weights4 = std::array<double, kOrder>;

void BasisValues(double u, Weights4* b) {
  const double v = 1.0 - u;
  (*b)[0] = v * v * v / 6.0;
  (*b)[1] = (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0;
  (*b)[2] = (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0;
  (*b)[3] = u * u * u / 6.0;
}
void BasisFirst(double u, Weights4* b) {  // d/du
  const double v = 1.0 - u;
  (*b)[0] = -v * v / 2.0;
  (*b)[1] = (3.0 * u * u - 4.0 * u) / 2.0;
  (*b)[2] = (-3.0 * u * u + 2.0 * u + 1.0) / 2.0;
  (*b)[3] = u * u / 2.0;
}
void BasisSecond(double u, Weights4* b) {  // d2/du2
  (*b)[0] = 1.0 - u;
  (*b)[1] = 3.0 * u - 2.0;
  (*b)[2] = -3.0 * u + 1.0;
  (*b)[3] = u;
}

// Interval index (clamped to the range, so the end cubics extend) and local coordinate u.
int Locate(double t, double t_begin, double h, int num_intervals, double* u) {
  const double x = (t - t_begin) / h;
  int k = static_cast<int>(std::floor(x));
  k = std::clamp(k, 0, num_intervals - 1);
  *u = x - k;
  return k;
}

// Two-point Gauss-Legendre nodes on [0, 1]; weights 1/2 each. Exact for the quadratic |g''|^2.
constexpr std::array<double, 2> kGaussNodes = {0.5 - 0.28867513459481287,
                                               0.5 + 0.28867513459481287};

}  // namespace

SmoothingSpline::SmoothingSpline(double t_begin, double knot_spacing, int num_intervals,
                                 Eigen::MatrixXd coefficients)
    : t_begin_(t_begin),
      knot_spacing_(knot_spacing),
      num_intervals_(num_intervals),
      coefficients_(std::move(coefficients)) {
  RAILWEAR_CHECK(knot_spacing > 0.0 && num_intervals >= 1);
  RAILWEAR_CHECK(coefficients_.rows() == num_intervals + 3 && coefficients_.cols() >= 1);
}

void SmoothingSpline::Evaluate(double t, Eigen::VectorXd* value, Eigen::VectorXd* d1,
                               Eigen::VectorXd* d2) const {
  RAILWEAR_CHECK(num_intervals_ >= 1);
  double u = 0.0;
  const int k = Locate(t, t_begin_, knot_spacing_, num_intervals_, &u);
  Weights4 b;
  auto combine = [&](Eigen::VectorXd* out, double scale) {
    out->setZero(dim());
    for (int r = 0; r < kOrder; ++r) *out += (b[r] * scale) * coefficients_.row(k + r).transpose();
  };
  if (value != nullptr) {
    BasisValues(u, &b);
    combine(value, 1.0);
  }
  if (d1 != nullptr) {
    BasisFirst(u, &b);
    combine(d1, 1.0 / knot_spacing_);
  }
  if (d2 != nullptr) {
    BasisSecond(u, &b);
    combine(d2, 1.0 / (knot_spacing_ * knot_spacing_));
  }
}

Eigen::VectorXd SmoothingSpline::Value(double t) const {
  Eigen::VectorXd v;
  Evaluate(t, &v, nullptr, nullptr);
  return v;
}
Eigen::VectorXd SmoothingSpline::Derivative(double t) const {
  Eigen::VectorXd v;
  Evaluate(t, nullptr, &v, nullptr);
  return v;
}
Eigen::VectorXd SmoothingSpline::SecondDerivative(double t) const {
  Eigen::VectorXd v;
  Evaluate(t, nullptr, nullptr, &v);
  return v;
}

std::string SmoothingSplineSummary::BriefReport() const {
  std::string out = fmt::format(
      "smoothing spline: {}, {} points x {}, {} coefficients (knot spacing {:.4g}), lambda "
      "{:.4g} ({}), dof {:.1f}, RMS residual {:.4g}, max {:.4g} at point {}",
      ToString(status), num_points, dim, num_coefficients, knot_spacing, lambda,
      lambda_from_gcv ? "GCV" : "given", effective_dof, rms_residual, max_residual,
      max_residual_index);
  if (loss != RobustLoss::kNone) {
    out += fmt::format(", {} loss a = {:.4g}: {} down-weighted", ToString(loss), loss_scale,
                       num_downweighted);
  }
  out += fmt::format(", {} Ceres iterations", num_ceres_iterations);
  return out;
}

namespace {

// ---------------------------------------------------------------------------------------------
// Symmetric positive definite band matrix of half-bandwidth 3 (the normal matrix of a cubic
// B-spline fit): LDL^T factorisation, solves, and the band of the inverse.
class BandSpd {
 public:
  static constexpr int kBand = kOrder - 1;
  explicit BandSpd(int size) : a_(size, Weights4{0, 0, 0, 0}) {}
  int size() const { return static_cast<int>(a_.size()); }
  // Adds x to M(i, j) (and M(j, i)); |i - j| <= 3.
  void Add(int i, int j, double x) {
    if (i < j) std::swap(i, j);
    a_[i][i - j] += x;
  }
  double Get(int i, int j) const {
    if (i < j) std::swap(i, j);
    return (i - j <= kBand) ? a_[i][i - j] : 0.0;
  }
  void AddScaled(const BandSpd& other, double s) {
    for (int i = 0; i < size(); ++i) {
      for (int d = 0; d <= kBand; ++d) a_[i][d] += s * other.a_[i][d];
    }
  }
  // In place: a_[i][0] = D_i, a_[i][d] = L(i, i - d). False if a pivot is not positive.
  bool Factor() {
    const int n = size();
    for (int i = 0; i < n; ++i) {
      for (int j = std::max(0, i - kBand); j <= i; ++j) {
        double s = a_[i][i - j];
        for (int k = std::max(0, i - kBand); k < j; ++k) {
          s -= a_[i][i - k] * a_[j][j - k] * a_[k][0];
        }
        if (j == i) {
          if (!(s > 0.0) || !std::isfinite(s)) return false;
          a_[i][0] = s;
        } else {
          a_[i][i - j] = s / a_[j][0];
        }
      }
    }
    return true;
  }
  // Solves M x = b in place (after Factor).
  void Solve(double* x) const {
    const int n = size();
    for (int i = 0; i < n; ++i) {
      for (int k = std::max(0, i - kBand); k < i; ++k) x[i] -= a_[i][i - k] * x[k];
    }
    for (int i = 0; i < n; ++i) x[i] /= a_[i][0];
    for (int i = n - 1; i >= 0; --i) {
      for (int k = i + 1; k <= std::min(n - 1, i + kBand); ++k) x[i] -= a_[k][k - i] * x[k];
    }
  }
  // Band of M^-1 (after Factor): s[i][d] = (M^-1)(i, i + d), d = 0..3 (Hutchinson & de Hoog).
  std::vector<Weights4> InverseBand() const {
    const int n = size();
    std::vector<Weights4> s(n, Weights4{0, 0, 0, 0});
    auto sigma = [&](int i, int j) {  // symmetric access to computed entries
      if (i > j) std::swap(i, j);
      return s[i][j - i];
    };
    for (int i = n - 1; i >= 0; --i) {
      const int last = std::min(n - 1, i + kBand);
      for (int j = last; j >= i; --j) {
        double x = (j == i) ? 1.0 / a_[i][0] : 0.0;
        for (int k = i + 1; k <= last; ++k) x -= a_[k][k - i] * sigma(k, j);
        s[i][j - i] = x;
      }
    }
    return s;
  }

 private:
  std::vector<Weights4> a_;
};

// ---------------------------------------------------------------------------------------------
// The fitting problem in normalised units: values divided by value_scale, weights by their mean
// (so Ceres' absolute gradient tolerance means the same for every data set), lambda likewise.
struct Setup {
  int n = 0, dim = 0, num_intervals = 0, num_coefficients = 0;
  int free_begin = 0, free_end = 0;  // coefficients [free_begin, free_end) are unknowns
  double t_begin = 0.0, h = 0.0;
  double value_scale = 1.0, weight_scale = 1.0;
  std::vector<int> interval;    // [n]
  std::vector<Weights4> basis;  // [n]
  Eigen::MatrixXd v;            // [n][dim], normalised
  Eigen::VectorXd w;            // [n], normalised (mean 1)
  BandSpd penalty{0};           // integral of g''^2 as a quadratic form on the free unknowns
  std::vector<double> sum_row;  // [num_coefficients]: d(sum_i w_i g(t_i)) / d c_j
  Eigen::VectorXd sum_target;   // [dim]: sum_i w_i v_i

  int num_free() const { return free_end - free_begin; }
  bool IsFree(int j) const { return j >= free_begin && j < free_end; }
};

// Gauss point q of interval k: weights of c_k..c_k+3 in sqrt(h/2) g''.
Weights4 PenaltyRow(double h, int q) {
  Weights4 b;
  BasisSecond(kGaussNodes[q], &b);
  const double s = std::sqrt(h / 2.0) / (h * h);
  for (double& x : b) x *= s;
  return b;
}

BandSpd DataMatrix(const Setup& s, const Eigen::VectorXd& w) {
  BandSpd g(s.num_free());
  for (int i = 0; i < s.n; ++i) {
    const int k = s.interval[i];
    for (int r = 0; r < kOrder; ++r) {
      if (!s.IsFree(k + r)) continue;
      for (int c = 0; c <= r; ++c) {
        if (!s.IsFree(k + c)) continue;
        g.Add(k + r - s.free_begin, k + c - s.free_begin, w[i] * s.basis[i][r] * s.basis[i][c]);
      }
    }
  }
  return g;
}

BandSpd PenaltyMatrix(const Setup& s) {
  BandSpd p(s.num_free());
  for (int k = 0; k < s.num_intervals; ++k) {
    for (int q = 0; q < 2; ++q) {
      const Weights4 b = PenaltyRow(s.h, q);
      for (int r = 0; r < kOrder; ++r) {
        if (!s.IsFree(k + r)) continue;
        for (int c = 0; c <= r; ++c) {
          if (s.IsFree(k + c)) p.Add(k + r - s.free_begin, k + c - s.free_begin, b[r] * b[c]);
        }
      }
    }
  }
  return p;
}

// Right-hand sides B^T W v, shape [num_free][dim].
Eigen::MatrixXd DataRhs(const Setup& s, const Eigen::VectorXd& w) {
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(s.num_free(), s.dim);
  for (int i = 0; i < s.n; ++i) {
    const int k = s.interval[i];
    for (int r = 0; r < kOrder; ++r) {
      if (s.IsFree(k + r)) rhs.row(k + r - s.free_begin) += w[i] * s.basis[i][r] * s.v.row(i);
    }
  }
  return rhs;
}

// Full coefficient matrix [num_coefficients][dim] from the free unknowns (fixed ones are 0).
Eigen::MatrixXd Expand(const Setup& s, const Eigen::MatrixXd& free) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(s.num_coefficients, s.dim);
  c.middleRows(s.free_begin, s.num_free()) = free;
  return c;
}

// Residuals g(t_i) - v_i, shape [n][dim] (normalised units).
Eigen::MatrixXd Residuals(const Setup& s, const Eigen::MatrixXd& c) {
  Eigen::MatrixXd r(s.n, s.dim);
  for (int i = 0; i < s.n; ++i) {
    const int k = s.interval[i];
    Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(s.dim);
    for (int q = 0; q < kOrder; ++q) g += s.basis[i][q] * c.row(k + q);
    r.row(i) = g - s.v.row(i);
  }
  return r;
}

struct ClosedForm {
  bool ok = false;
  Eigen::MatrixXd coefficients;  // [num_coefficients][dim]
  double trace = 0.0;            // tr A (per component), when asked for
  Eigen::VectorXd hat;           // [n] diagonal A_ii, when asked for
};

enum class Extras { kNone, kTrace, kTraceAndHat };

// Least-squares solution at lambda for the data matrix and right-hand sides of weights w;
// optionally with the weighted-sum constraint as a penalty (Sherman-Morrison on the banded
// factor, sum_weight > 0), the trace of A and its diagonal A_ii = w_i b_i^T M^-1 b_i.
ClosedForm SolveClosedForm(const Setup& s, const BandSpd& data, const Eigen::MatrixXd& rhs,
                           double lambda, double sum_weight, Extras extras,
                           const Eigen::VectorXd& w) {
  ClosedForm out;
  BandSpd m = data;
  m.AddScaled(s.penalty, lambda);
  if (!m.Factor()) return out;
  Eigen::MatrixXd x = rhs;
  for (int d = 0; d < s.dim; ++d) m.Solve(x.col(d).data());
  if (sum_weight > 0.0) {
    // (M + mu beta beta^T) c = rhs + mu beta S0, mu = sum_weight.
    Eigen::VectorXd beta(s.num_free());
    for (int j = 0; j < s.num_free(); ++j) beta[j] = s.sum_row[j + s.free_begin];
    Eigen::VectorXd z = beta;
    m.Solve(z.data());
    const double beta_z = beta.dot(z);
    for (int d = 0; d < s.dim; ++d) {
      Eigen::VectorXd xd = x.col(d) + sum_weight * s.sum_target[d] * z;
      xd -= z * (sum_weight * beta.dot(xd) / (1.0 + sum_weight * beta_z));
      x.col(d) = xd;
    }
  }
  out.coefficients = Expand(s, x);
  if (extras != Extras::kNone) {
    const std::vector<Weights4> inv = m.InverseBand();
    auto sigma = [&](int i, int j) {  // (M^-1)(i, j) for free indices within the band
      if (i > j) std::swap(i, j);
      return inv[i - s.free_begin][j - i];
    };
    double tr = 0.0;
    for (int i = 0; i < s.num_free(); ++i) {
      tr += inv[i][0] * data.Get(i, i);
      for (int d = 1; d <= BandSpd::kBand && i + d < s.num_free(); ++d) {
        tr += 2.0 * inv[i][d] * data.Get(i + d, i);
      }
    }
    out.trace = tr;
    if (extras == Extras::kTraceAndHat) {
      out.hat.resize(s.n);
      for (int i = 0; i < s.n; ++i) {
        const int k = s.interval[i];
        double a = 0.0;
        for (int r = 0; r < kOrder; ++r) {
          if (!s.IsFree(k + r)) continue;
          for (int c = 0; c < kOrder; ++c) {
            if (s.IsFree(k + c)) a += s.basis[i][r] * s.basis[i][c] * sigma(k + r, k + c);
          }
        }
        out.hat[i] = w[i] * a;
      }
    }
  }
  out.ok = true;
  return out;
}

struct GcvChoice {
  double lambda = 0.0;  // normalised
  double score = 0.0;
};

// GCV over the smoothing length l (lambda = l^4 / weight_scale in normalised units).
GcvChoice ChooseLambdaByGcv(const Setup& s, const Eigen::VectorXd& w,
                            const SmoothingSplineOptions& o) {
  const BandSpd data = DataMatrix(s, w);
  const Eigen::MatrixXd rhs = DataRhs(s, w);
  const double n = s.n;
  auto lambda_of = [&](double log_l) { return std::exp(4.0 * log_l) / s.weight_scale; };
  auto score = [&](double log_l) {
    const ClosedForm f = SolveClosedForm(s, data, rhs, lambda_of(log_l), 0.0, Extras::kTrace, w);
    if (!f.ok) return std::numeric_limits<double>::infinity();
    const Eigen::MatrixXd r = Residuals(s, f.coefficients);
    double rss = 0.0;
    for (int i = 0; i < s.n; ++i) rss += w[i] * r.row(i).squaredNorm();
    const double denom = 1.0 - o.gcv_dof_factor * f.trace / n;
    if (!(denom > 0.0)) return std::numeric_limits<double>::infinity();
    return (rss / n) / (denom * denom);
  };
  const double lo = std::log(o.gcv_min_length_ratio * s.h);
  const double hi = std::log(o.gcv_max_length_ratio * s.h);
  const int n_grid = o.gcv_grid_points;
  const double step = (hi - lo) / (n_grid - 1);
  int best = 0;
  double best_score = std::numeric_limits<double>::infinity();
  for (int g = 0; g < n_grid; ++g) {
    const double v = score(lo + g * step);
    if (v < best_score) {
      best_score = v;
      best = g;
    }
  }
  // Golden section on the bracket around the best grid point.
  double a = lo + std::max(0, best - 1) * step;
  double b = lo + std::min(n_grid - 1, best + 1) * step;
  constexpr double kInvPhi = 0.6180339887498949;
  constexpr double kLogTolerance = 1e-3;  // 0.1 % in l: far below what changes the fit
  double x1 = b - kInvPhi * (b - a), x2 = a + kInvPhi * (b - a);
  double f1 = score(x1), f2 = score(x2);
  while (b - a > kLogTolerance) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - kInvPhi * (b - a);
      f1 = score(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + kInvPhi * (b - a);
      f2 = score(x2);
    }
  }
  GcvChoice out;
  const double x = (f1 <= f2) ? x1 : x2;
  const double fx = std::min(f1, f2);
  if (fx <= best_score) {
    out.lambda = lambda_of(x);
    out.score = fx;
  } else {
    out.lambda = lambda_of(lo + best * step);
    out.score = best_score;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Ceres cost functions.

// Rows on one knot interval k, each r = scale * (sum_r a_r c_{k+r} - target) (dim residuals);
// the four parameter blocks c_k..c_k+3 of size dim. Data points and the two Gauss points of
// the penalty on the same interval share one residual block unless a loss needs them apart.
struct BandRow {
  Weights4 a;
  double scale;
  Eigen::VectorXd target;  // [dim]
};

class BandResidual final : public ceres::CostFunction {
 public:
  BandResidual(int dim, std::vector<BandRow> rows) : dim_(dim), rows_(std::move(rows)) {
    set_num_residuals(dim * static_cast<int>(rows_.size()));
    for (int r = 0; r < kOrder; ++r) mutable_parameter_block_sizes()->push_back(dim);
  }
  bool Evaluate(double const* const* c, double* residuals, double** jacobians) const override {
    const int n = num_residuals();
    for (std::size_t q = 0; q < rows_.size(); ++q) {
      const BandRow& row = rows_[q];
      for (int d = 0; d < dim_; ++d) {
        double g = 0.0;
        for (int r = 0; r < kOrder; ++r) g += row.a[r] * c[r][d];
        residuals[q * dim_ + d] = row.scale * (g - row.target[d]);
      }
    }
    if (jacobians != nullptr) {
      for (int r = 0; r < kOrder; ++r) {
        if (jacobians[r] == nullptr) continue;
        std::fill(jacobians[r], jacobians[r] + n * dim_, 0.0);
        for (std::size_t q = 0; q < rows_.size(); ++q) {
          for (int d = 0; d < dim_; ++d) {
            jacobians[r][(q * dim_ + d) * dim_ + d] = rows_[q].scale * rows_[q].a[r];
          }
        }
      }
    }
    return true;
  }

 private:
  int dim_;
  std::vector<BandRow> rows_;
};

// r = scale * (sum_j beta_j c_j - target), dim residuals; one parameter block per coefficient.
class SumResidual final : public ceres::CostFunction {
 public:
  SumResidual(int dim, std::vector<double> beta, double scale, Eigen::VectorXd target)
      : dim_(dim), beta_(std::move(beta)), scale_(scale), target_(std::move(target)) {
    set_num_residuals(dim);
    for (std::size_t j = 0; j < beta_.size(); ++j) mutable_parameter_block_sizes()->push_back(dim);
  }
  bool Evaluate(double const* const* c, double* residuals, double** jacobians) const override {
    for (int d = 0; d < dim_; ++d) {
      double sum = 0.0;
      for (std::size_t j = 0; j < beta_.size(); ++j) sum += beta_[j] * c[j][d];
      residuals[d] = scale_ * (sum - target_[d]);
    }
    if (jacobians != nullptr) {
      for (std::size_t j = 0; j < beta_.size(); ++j) {
        if (jacobians[j] == nullptr) continue;
        std::fill(jacobians[j], jacobians[j] + dim_ * dim_, 0.0);
        for (int d = 0; d < dim_; ++d) jacobians[j][d * dim_ + d] = scale_ * beta_[j];
      }
    }
    return true;
  }

 private:
  int dim_;
  std::vector<double> beta_;
  double scale_;
  Eigen::VectorXd target_;
};

struct CeresOutcome {
  SmoothingSplineStatus status = SmoothingSplineStatus::kFailure;
  std::string message;
  int iterations = 0;
};

// Active-set rounds (each one Ceres solve) before giving up; a round moves one coefficient
// into or out of the set, and only coefficients near the support's edges ever are.
constexpr int kMaxActiveSetRounds = 100;
// An active coefficient leaves the set when the normalised cost's gradient is below minus this.
constexpr double kReleaseGradient = 1e-12;

// Solves the full problem with Ceres from *c (updated in place; kept on failure).
// loss_scale: a in normalised units (ignored for kNone); points with inlier[i] == 0 are left out.
CeresOutcome SolveWithCeres(const Setup& s, const SmoothingSplineOptions& o, double lambda,
                            double loss_scale, const std::vector<char>& inlier,
                            Eigen::MatrixXd* c) {
  const int m = s.num_coefficients;
  std::vector<double> x(static_cast<std::size_t>(m) * s.dim);
  for (int j = 0; j < m; ++j) {
    for (int d = 0; d < s.dim; ++d) {
      double value = s.IsFree(j) ? (*c)(j, d) : 0.0;
      if (o.lower_bound && s.IsFree(j)) value = std::max(value, *o.lower_bound / s.value_scale);
      x[j * s.dim + d] = value;
    }
  }
  auto block = [&](int j) { return x.data() + static_cast<std::ptrdiff_t>(j) * s.dim; };

  ceres::Problem problem;
  for (int j = 0; j < m; ++j) problem.AddParameterBlock(block(j), s.dim);
  // One residual block per knot interval: its data rows (unless a loss needs each point in a
  // block of its own) and its two penalty rows.
  const bool robust = o.loss != RobustLoss::kNone;
  std::vector<std::vector<BandRow>> rows(s.num_intervals);
  for (int i = 0; i < s.n; ++i) {
    if (!inlier[i]) continue;  // rejected as a gross outlier
    const int k = s.interval[i];
    const double sw = std::sqrt(s.w[i]);
    BandRow row{s.basis[i], sw, s.v.row(i).transpose()};
    if (!robust) {
      rows[k].push_back(std::move(row));
      continue;
    }
    ceres::LossFunction* loss = nullptr;
    if (o.loss == RobustLoss::kHuber) loss = new ceres::HuberLoss(loss_scale * sw);
    if (o.loss == RobustLoss::kCauchy) loss = new ceres::CauchyLoss(loss_scale * sw);
    problem.AddResidualBlock(new BandResidual(s.dim, {std::move(row)}), loss, block(k),
                             block(k + 1), block(k + 2), block(k + 3));
  }
  const double sl = std::sqrt(lambda);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s.dim);
  for (int k = 0; k < s.num_intervals; ++k) {
    for (int q = 0; q < 2; ++q) rows[k].push_back(BandRow{PenaltyRow(s.h, q), sl, zero});
    problem.AddResidualBlock(new BandResidual(s.dim, std::move(rows[k])), nullptr, block(k),
                             block(k + 1), block(k + 2), block(k + 3));
  }
  if (o.preserve_weighted_sum) {
    std::vector<double> beta;
    std::vector<double*> blocks;
    for (int j = s.free_begin; j < s.free_end; ++j) {
      if (s.sum_row[j] == 0.0) continue;
      beta.push_back(s.sum_row[j]);
      blocks.push_back(block(j));
    }
    const double scale = std::sqrt(o.sum_constraint_weight / s.w.sum());
    problem.AddResidualBlock(new SumResidual(s.dim, std::move(beta), scale, s.sum_target), nullptr,
                             blocks);
  }
  const double lb = o.lower_bound ? *o.lower_bound / s.value_scale : 0.0;
  for (int j = 0; j < m; ++j) {
    if (!s.IsFree(j)) {
      problem.SetParameterBlockConstant(block(j));
    } else if (o.lower_bound) {
      problem.SetParameterLowerBound(block(j), 0, lb);  // dimension 1 (checked by the caller)
    }
  }

  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(options.sparse_linear_algebra_library_type)
          ? ceres::SPARSE_NORMAL_CHOLESKY
          : ceres::DENSE_QR;
  // Without a loss the problem is linear least squares: a huge initial trust region makes the
  // first Levenberg-Marquardt step the Gauss-Newton step, i.e. the solution.
  if (o.loss == RobustLoss::kNone) options.initial_trust_region_radius = 1e16;
  options.max_num_iterations = o.max_num_iterations;
  options.function_tolerance = o.function_tolerance;
  options.parameter_tolerance = o.parameter_tolerance;
  // The problem is normalised (values by their scale, weights to mean 1), so an absolute
  // tolerance on the projected gradient can be tight; the relative tolerances stop the solve.
  options.gradient_tolerance = 1e-14;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;

  // With a lower bound, an active-set loop around Ceres: coefficients at the bound are held
  // constant, so every solve is an unconstrained one that converges in a step or two (Ceres'
  // projected steps alone crawl along active bounds). A free coefficient that a solve pushes
  // onto its bound joins the set; the active coefficient whose gradient most wants it to
  // increase leaves it; the loop ends when neither happens (the KKT conditions hold).
  std::vector<int> active;
  if (o.lower_bound) {
    for (int j = s.free_begin; j < s.free_end; ++j) {
      if (x[j] <= lb) {
        x[j] = lb;
        problem.SetParameterBlockConstant(block(j));
        active.push_back(j);
      }
    }
  }
  CeresOutcome out;
  for (int round = 0; round < kMaxActiveSetRounds; ++round) {
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    out.message = summary.message;
    out.iterations += static_cast<int>(summary.iterations.size()) - 1;
    if (!summary.IsSolutionUsable()) {
      out.status = SmoothingSplineStatus::kFailure;
      return out;
    }
    out.status = (summary.termination_type == ceres::CONVERGENCE)
                     ? SmoothingSplineStatus::kConverged
                     : SmoothingSplineStatus::kNoConvergence;
    if (!o.lower_bound) break;
    bool changed = false;
    for (int j = s.free_begin; j < s.free_end; ++j) {
      if (x[j] <= lb && !problem.IsParameterBlockConstant(block(j))) {
        x[j] = lb;
        problem.SetParameterBlockConstant(block(j));
        active.push_back(j);
        changed = true;
      }
    }
    if (changed) continue;
    if (active.empty()) break;
    // Gradient of the cost with respect to the active coefficients.
    ceres::Problem::EvaluateOptions eval;
    for (int j : active) {
      problem.SetParameterBlockVariable(block(j));
      eval.parameter_blocks.push_back(block(j));
    }
    std::vector<double> gradient;
    problem.Evaluate(eval, nullptr, nullptr, &gradient, nullptr);
    for (int j : active) problem.SetParameterBlockConstant(block(j));
    int release = -1;
    double most = -kReleaseGradient;
    for (std::size_t a = 0; a < active.size(); ++a) {
      if (gradient[a] < most) {
        most = gradient[a];
        release = static_cast<int>(a);
      }
    }
    if (release < 0) break;
    problem.SetParameterBlockVariable(block(active[release]));
    active.erase(active.begin() + release);
    if (round + 1 == kMaxActiveSetRounds) {
      out.status = SmoothingSplineStatus::kNoConvergence;
      out.message = "active-set limit reached";
    }
  }
  for (int j = 0; j < m; ++j) {
    for (int d = 0; d < s.dim; ++d) (*c)(j, d) = x[j * s.dim + d];
  }
  return out;
}

// IRLS weight rho'(r^2) of the loss at residual norm r (normalised units).
double RobustWeight(RobustLoss loss, double r, double a) {
  switch (loss) {
    case RobustLoss::kNone:
      return 1.0;
    case RobustLoss::kHuber:
      return r <= a ? 1.0 : a / r;
    case RobustLoss::kCauchy:
      return 1.0 / (1.0 + (r / a) * (r / a));
  }
  return 1.0;
}

double Median(std::vector<double> x) {
  RAILWEAR_CHECK(!x.empty());
  const std::size_t mid = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(mid), x.end());
  double m = x[mid];
  if (x.size() % 2 == 0) {
    m = 0.5 * (m + *std::max_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(mid)));
  }
  return m;
}

constexpr double kMadToSigma = 1.482602218505602;  // 1 / Phi^-1(3/4), Gaussian consistency
// Rejection stops after this many refits (each round can only move points across the
// threshold; two or three rounds settle it in practice).
constexpr int kMaxRejectionRounds = 4;
// 1 - A_ii is floored here when standardising residuals: A_ii -> 1 only for a point alone in
// its knot interval at vanishing lambda, whose residual is then ~0 anyway.
constexpr double kMinLeverageGap = 1e-6;

void ValidateData(const Eigen::VectorXd& t, const Eigen::MatrixXd& values,
                  const Eigen::VectorXd& weights) {
  const Eigen::Index n = t.size();
  if (n < 2) throw InputError(fmt::format("smoothing spline: {} points: expected >= 2", n));
  if (values.rows() != n) {
    throw InputError(
        fmt::format("smoothing spline: {} values for {} parameters: expected equal "
                    "counts",
                    values.rows(), n));
  }
  if (values.cols() < 1 || values.cols() > 3) {
    throw InputError(
        fmt::format("smoothing spline: value dimension {}: expected 1, 2 or 3", values.cols()));
  }
  if (weights.size() != 0 && weights.size() != n) {
    throw InputError(
        fmt::format("smoothing spline: {} weights for {} points: expected {} or "
                    "none",
                    weights.size(), n, n));
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(t[i])) {
      throw InputError(
          fmt::format("smoothing spline: t[{}] = {}: expected a finite number", i, t[i]));
    }
    for (Eigen::Index d = 0; d < values.cols(); ++d) {
      if (!std::isfinite(values(i, d))) {
        throw InputError(
            fmt::format("smoothing spline: value[{}][{}] = {}: expected a finite "
                        "number",
                        i, d, values(i, d)));
      }
    }
    if (weights.size() != 0 && !PositiveFinite(weights[i])) {
      throw InputError(
          fmt::format("smoothing spline: weight[{}] = {}: expected a finite number "
                      "> 0",
                      i, weights[i]));
    }
  }
  if (!(t.maxCoeff() > t.minCoeff())) {
    throw InputError(
        fmt::format("smoothing spline: parameter range [{}, {}]: expected t_max > "
                    "t_min",
                    t.minCoeff(), t.maxCoeff()));
  }
}

}  // namespace

SmoothingSplineFit FitSmoothingSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& values,
                                      const Eigen::VectorXd& weights,
                                      const SmoothingSplineOptions& o,
                                      const std::vector<bool>& suspects) {
  const auto clock_start = std::chrono::steady_clock::now();
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
  ValidateData(t, values, weights);

  // 1. Knots, basis rows and normalisation.
  Setup s;
  s.n = static_cast<int>(t.size());
  s.dim = static_cast<int>(values.cols());
  s.t_begin = t.minCoeff();
  const double range = t.maxCoeff() - s.t_begin;
  s.num_intervals = std::max(1, static_cast<int>(std::ceil(range / o.knot_spacing - 1e-9)));
  s.h = range / s.num_intervals;
  s.num_coefficients = s.num_intervals + 3;
  s.free_begin = o.clamp_start ? 3 : 0;
  s.free_end = o.clamp_end ? s.num_coefficients - 3 : s.num_coefficients;
  if (o.lower_bound && s.dim != 1) {
    throw InputError(
        fmt::format("smoothing spline: lower_bound = {} with value dimension {}: "
                    "expected dimension 1 (a bound on each coefficient of a scalar "
                    "field)",
                    *o.lower_bound, s.dim));
  }
  if (s.num_free() < 1) {
    throw InputError(
        fmt::format("smoothing spline: {} knot intervals cannot be clamped at both "
                    "ends: expected a knot_spacing below {} (a quarter of the range)",
                    s.num_intervals, range / 4.0));
  }
  s.value_scale = std::max(values.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  s.v = values / s.value_scale;
  Eigen::VectorXd w =
      weights.size() == 0 ? Eigen::VectorXd::Constant(s.n, range / (s.n - 1)) : weights;
  s.weight_scale = w.mean();
  s.w = w / s.weight_scale;
  s.interval.resize(s.n);
  s.basis.resize(s.n);
  for (int i = 0; i < s.n; ++i) {
    double u = 0.0;
    s.interval[i] = Locate(t[i], s.t_begin, s.h, s.num_intervals, &u);
    BasisValues(u, &s.basis[i]);
  }
  s.penalty = PenaltyMatrix(s);
  s.sum_row.assign(s.num_coefficients, 0.0);
  s.sum_target = Eigen::VectorXd::Zero(s.dim);
  for (int i = 0; i < s.n; ++i) {
    for (int r = 0; r < kOrder; ++r) s.sum_row[s.interval[i] + r] += s.w[i] * s.basis[i][r];
    s.sum_target += s.w[i] * s.v.row(i).transpose();
  }
  const double sum_weight = o.preserve_weighted_sum ? o.sum_constraint_weight / s.w.sum() : 0.0;

  SmoothingSplineFit fit;
  SmoothingSplineSummary& sum = fit.summary;
  sum.num_points = s.n;
  sum.dim = s.dim;
  sum.num_coefficients = s.num_coefficients;
  sum.knot_spacing = s.h;
  sum.loss = o.loss;

  // 2. Weights of the least-squares stages: data weights, 0 for rejected points.
  const bool robust = o.loss != RobustLoss::kNone;
  std::vector<char> inlier(s.n, 1);
  if (robust && o.reject_threshold > 0.0) {
    for (int i = 0; i < s.n && i < static_cast<int>(suspects.size()); ++i) {
      if (suspects[i]) inlier[i] = 0;
    }
  }
  auto masked = [&](const std::vector<char>& mask) {
    Eigen::VectorXd m = s.w;
    for (int i = 0; i < s.n; ++i) {
      if (!mask[i]) m[i] = 0.0;
    }
    return m;
  };
  auto choose_lambda = [&](const Eigen::VectorXd& w) {
    if (o.lambda) return *o.lambda / s.weight_scale;
    const GcvChoice g = ChooseLambdaByGcv(s, w, o);
    sum.gcv_score = g.score;
    sum.lambda_from_gcv = true;
    return g.lambda;
  };
  auto solve = [&](const Eigen::VectorXd& w, double lambda, double sum_w, Extras extras) {
    ClosedForm f = SolveClosedForm(s, DataMatrix(s, w), DataRhs(s, w), lambda, sum_w, extras, w);
    if (!f.ok) {
      // Only lambda = 0 with knot intervals the data leave undetermined gets here.
      throw InputError(
          fmt::format("smoothing spline: lambda = {} leaves the spline undetermined "
                      "by {} points on {} knot intervals: expected lambda > 0 or a "
                      "larger knot_spacing",
                      lambda * s.weight_scale, s.n, s.num_intervals));
    }
    return f;
  };

  // 3. Robust scale and rejection of gross outliers: standardised residuals
  // r_i / sqrt(1 - A_ii) of the least-squares fit (their variance is sigma^2 for a linear
  // smoother); sigma from their MAD; points beyond reject_threshold sigma are left out (weight 0)
  // and the fit repeated, until the set of rejected points no longer changes. A left-out point
  // is taken back when it lies within the threshold of the new fit.
  double lambda = choose_lambda(masked(inlier));
  double sigma = 0.0;
  if (robust) {
    for (int round = 0; round < kMaxRejectionRounds; ++round) {
      const ClosedForm f = solve(masked(inlier), lambda, 0.0, Extras::kTraceAndHat);
      const Eigen::MatrixXd r = Residuals(s, f.coefficients);
      std::vector<double> standardised(s.n);
      for (int i = 0; i < s.n; ++i) {
        standardised[i] = r.row(i).norm() / std::sqrt(std::max(1.0 - f.hat[i], kMinLeverageGap));
      }
      // sigma from this round's kept points
      if (o.robust_scale) {
        sigma = *o.robust_scale / s.value_scale;
      } else {
        std::vector<double> kept_values;
        for (int i = 0; i < s.n; ++i) {
          if (inlier[i]) kept_values.push_back(standardised[i]);
        }
        sigma = std::max(kMadToSigma * Median(kept_values.empty() ? standardised : kept_values),
                         o.min_robust_scale / s.value_scale);
      }
      sigma = std::max(sigma, std::numeric_limits<double>::min());
      if (o.reject_threshold <= 0.0) break;
      std::vector<char> next(s.n);
      int kept = 0;
      for (int i = 0; i < s.n; ++i) {
        next[i] = standardised[i] <= o.reject_threshold * sigma;
        kept += next[i];
      }
      // Never leave out half the data or more: that is no longer an outlier.
      if (kept <= s.n / 2 || next == inlier) break;
      inlier = next;
      lambda = choose_lambda(masked(inlier));
    }
  }
  const double loss_scale = o.robust_threshold * sigma;
  sum.robust_sigma = robust ? sigma * s.value_scale : 0.0;
  sum.loss_scale = robust ? loss_scale * s.value_scale : 0.0;

  // 4. Ceres from the least-squares solution; with a robust loss and GCV, lambda is chosen
  // again with the robust (IRLS) weights of that fit and the fit repeated.
  Eigen::MatrixXd c = solve(masked(inlier), lambda, sum_weight, Extras::kNone).coefficients;
  CeresOutcome outcome = SolveWithCeres(s, o, lambda, loss_scale, inlier, &c);
  sum.num_ceres_solves = 1;
  auto robust_weights = [&](const Eigen::MatrixXd& coefficients) {
    const Eigen::MatrixXd r = Residuals(s, coefficients);
    Eigen::VectorXd rw = masked(inlier);
    for (int i = 0; i < s.n; ++i) rw[i] *= RobustWeight(o.loss, r.row(i).norm(), loss_scale);
    return rw;
  };
  Eigen::VectorXd fit_weights = masked(inlier);  // for tr A of the final fit
  if (robust) {
    fit_weights = robust_weights(c);
    if (!o.lambda && outcome.status != SmoothingSplineStatus::kFailure) {
      lambda = choose_lambda(fit_weights);
      c = solve(fit_weights, lambda, sum_weight, Extras::kNone).coefficients;
      outcome = SolveWithCeres(s, o, lambda, loss_scale, inlier, &c);
      sum.num_ceres_solves = 2;
      fit_weights = robust_weights(c);
    }
  }
  sum.status = outcome.status;
  sum.message = outcome.message;
  sum.num_ceres_iterations = outcome.iterations;
  sum.lambda = lambda * s.weight_scale;
  sum.effective_dof = solve(fit_weights, lambda, 0.0, Extras::kTrace).trace;

  // 5. Residual statistics in the caller's units.
  const Eigen::MatrixXd r = Residuals(s, c) * s.value_scale;
  double ss = 0.0, inlier_ss = 0.0;
  int num_inliers = 0;
  for (int i = 0; i < s.n; ++i) {
    const double ri = r.row(i).norm();
    ss += ri * ri;
    if (ri > sum.max_residual || sum.max_residual_index < 0) {
      sum.max_residual = ri;
      sum.max_residual_index = i;
    }
    if (!inlier[i]) {
      ++sum.num_rejected;
    } else {
      inlier_ss += ri * ri;
      ++num_inliers;
      if (robust && ri > sum.loss_scale) ++sum.num_downweighted;
    }
  }
  sum.rms_inlier_residual = std::sqrt(inlier_ss / std::max(1, num_inliers));
  sum.rms_residual = std::sqrt(ss / s.n);
  if (o.preserve_weighted_sum) {
    double worst = 0.0;
    for (int d = 0; d < s.dim; ++d) {
      double fitted = 0.0;
      for (int j = 0; j < s.num_coefficients; ++j) fitted += s.sum_row[j] * c(j, d);
      const double target = s.sum_target[d];
      const double rel = (target != 0.0) ? (fitted - target) / std::abs(target) : fitted - target;
      if (std::abs(rel) >= std::abs(worst)) worst = rel;
    }
    sum.relative_sum_error = worst;
  }
  fit.spline = SmoothingSpline(s.t_begin, s.h, s.num_intervals, c * s.value_scale);
  fit.rejected.resize(s.n);
  for (int i = 0; i < s.n; ++i) fit.rejected[i] = !inlier[i];
  const auto elapsed = std::chrono::steady_clock::now() - clock_start;
  sum.time_s = std::chrono::duration<double>(elapsed).count();
  return fit;
}

}  // namespace railwear
