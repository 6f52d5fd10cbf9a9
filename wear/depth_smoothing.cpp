// Wear-depth smoothing: support windows, one constrained smoothing spline per window.
#include "wear/depth_smoothing.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {

namespace {

bool Fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = "depth smoothing options: " + message;
  return false;
}

bool PositiveFinite(double x) { return std::isfinite(x) && x > 0.0; }

int Severity(SmoothingSplineStatus s) {
  switch (s) {
    case SmoothingSplineStatus::kConverged: return 0;
    case SmoothingSplineStatus::kNoConvergence: return 1;
    case SmoothingSplineStatus::kFailure: return 2;
  }
  return 2;
}

}  // namespace

bool DepthSmoothingOptions::IsValid(std::string* error) const {
  if (!PositiveFinite(smoothing_length_m)) {
    return Fail(error, fmt::format("smoothing_length_m = {}: expected a finite number > 0",
                                   smoothing_length_m));
  }
  if (!PositiveFinite(knots_per_smoothing_length)) {
    return Fail(error, fmt::format("knots_per_smoothing_length = {}: expected a finite number > 0",
                                   knots_per_smoothing_length));
  }
  if (!PositiveFinite(margin_lengths)) {
    return Fail(error, fmt::format("margin_lengths = {}: expected a finite number > 0",
                                   margin_lengths));
  }
  if (!(support_threshold >= 0.0 && support_threshold < 1.0)) {
    return Fail(error, fmt::format("support_threshold = {}: expected a number in [0, 1)",
                                   support_threshold));
  }
  if (!PositiveFinite(area_constraint_weight)) {
    return Fail(error, fmt::format("area_constraint_weight = {}: expected a finite number > 0",
                                   area_constraint_weight));
  }
  if (max_num_iterations < 1) {
    return Fail(error, fmt::format("max_num_iterations = {}: expected >= 1", max_num_iterations));
  }
  return true;
}

DepthSmoothing SmoothDepthField(const std::vector<double>& depth_m, double h_m,
                                const DepthSmoothingOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
  if (!PositiveFinite(h_m)) {
    throw InputError(fmt::format("depth smoothing: bin width h_m = {}: expected a finite number "
                                 "> 0",
                                 h_m));
  }
  const int n = static_cast<int>(depth_m.size());
  double max_depth = 0.0;
  double area_before = 0.0;
  for (int i = 0; i < n; ++i) {
    if (!(std::isfinite(depth_m[i]) && depth_m[i] >= 0.0)) {
      throw InputError(fmt::format("depth smoothing: depth_m[{}] = {}: expected a finite depth "
                                   ">= 0",
                                   i, depth_m[i]));
    }
    max_depth = std::max(max_depth, depth_m[i]);
    area_before += depth_m[i] * h_m;
  }
  const double l = o.smoothing_length_m;
  DepthSmoothing out;
  out.lambda = l * l * l * l;
  if (n < 4 || max_depth == 0.0) {
    out.depth_m = depth_m;
    return out;
  }

  // 1. Windows: support runs widened by the margin, merged where they touch.
  const double threshold = o.support_threshold * max_depth;
  const int margin = std::max(1, static_cast<int>(std::ceil(o.margin_lengths * l / h_m)));
  std::vector<std::pair<int, int>> windows;  // [first, last] bins
  for (int i = 0; i < n; ++i) {
    if (!(depth_m[i] > threshold)) continue;
    const int first = std::max(0, i - margin);
    const int last = std::min(n - 1, i + margin);
    if (!windows.empty() && first <= windows.back().second + 1) {
      windows.back().second = std::max(windows.back().second, last);
    } else {
      windows.emplace_back(first, last);
    }
  }

  // 2. One constrained smoothing spline per window.
  out.depth_m.assign(n, 0.0);
  SmoothingSplineOptions so;
  so.lambda = out.lambda;
  so.loss = RobustLoss::kNone;
  so.lower_bound = 0.0;
  so.preserve_weighted_sum = true;
  so.sum_constraint_weight = o.area_constraint_weight;
  so.max_num_iterations = o.max_num_iterations;
  for (const auto& [first, last] : windows) {
    const int m = last - first + 1;
    if (m < 4) {  // a window of 1-3 bins (tiny array end): nothing to smooth
      for (int i = first; i <= last; ++i) out.depth_m[i] = depth_m[i];
      continue;
    }
    Eigen::VectorXd t(m), w = Eigen::VectorXd::Constant(m, h_m);
    Eigen::MatrixXd v(m, 1);
    for (int i = 0; i < m; ++i) {
      t[i] = (first + i) * h_m;
      v(i, 0) = depth_m[first + i];
    }
    const double range = (m - 1) * h_m;
    // Knots every l / knots_per_length, not finer than a bin, and at least 8 intervals so that
    // clamping both ends leaves coefficients free.
    so.knot_spacing = std::min(std::max(h_m, l / o.knots_per_smoothing_length), range / 8.0);
    so.clamp_start = first > 0;
    so.clamp_end = last < n - 1;
    const SmoothingSplineFit fit = FitSmoothingSpline(t, v, w, so);
    for (int i = 0; i < m; ++i) {
      out.depth_m[first + i] = std::max(0.0, fit.spline.Value(t[i])[0]);
    }
    ++out.num_windows;
    out.num_fitted_bins += m;
    out.num_ceres_iterations += fit.summary.num_ceres_iterations;
    if (Severity(fit.summary.status) > Severity(out.status) || out.message.empty()) {
      out.status = fit.summary.status;
      out.message = fit.summary.message;
    }
  }

  // 3. Area error before the optional exact rescale.
  double area_after = 0.0;
  for (double d : out.depth_m) area_after += d * h_m;
  out.area_error = (area_after - area_before) / area_before;
  if (o.rescale_to_area && area_after > 0.0) {
    const double factor = area_before / area_after;
    for (double& d : out.depth_m) d *= factor;
  }
  return out;
}

}  // namespace railwear
