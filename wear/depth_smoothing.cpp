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
    case SmoothingSplineStatus::kConverged:
      return 0;
    case SmoothingSplineStatus::kNoConvergence:
      return 1;
    case SmoothingSplineStatus::kFailure:
      return 2;
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
    return Fail(error,
                fmt::format("margin_lengths = {}: expected a finite number > 0", margin_lengths));
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
    throw InputError(
        fmt::format("depth smoothing: bin width h_m = {}: expected a finite number "
                    "> 0",
                    h_m));
  }
  const int n = static_cast<int>(depth_m.size());
  double max_depth = 0.0;
  double area_before = 0.0;
  for (int i = 0; i < n; ++i) {
    if (!(std::isfinite(depth_m[i]) && depth_m[i] >= 0.0)) {
      throw InputError(
          fmt::format("depth smoothing: depth_m[{}] = {}: expected a finite depth "
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

  // 1. Bands: runs of bins above the threshold. Each band is smoothed on its own window (the
  //    band widened by the margin; windows of neighbouring bands may overlap, their results
  //    add). Smoothing bands one by one keeps each band's own area: with two bands in one window
  //    the area residual let the fit trade a low band's area against a high band's (a band of
  //    1 % of the peak 20 mm away kept 2 % of its area).
  const double threshold = o.support_threshold * max_depth;
  const int margin = std::max(1, static_cast<int>(std::ceil(o.margin_lengths * l / h_m)));
  struct Band {
    int first, last;  // bins of the band
    int window_first, window_last;
  };
  std::vector<Band> bands;
  for (int i = 0; i < n; ++i) {
    if (!(depth_m[i] > threshold)) continue;
    if (!bands.empty() && bands.back().last == i - 1) {
      bands.back().last = i;
    } else {
      bands.push_back({i, i, 0, 0});
    }
  }
  for (Band& b : bands) {
    b.window_first = std::max(0, b.first - margin);
    b.window_last = std::min(n - 1, b.last + margin);
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
  for (const Band& band : bands) {
    const int first = band.window_first, last = band.window_last;
    const int m = last - first + 1;
    // The band's own depth: zero outside it (another band's bins belong to that band).
    const auto band_depth = [&](int i) {
      return i >= band.first && i <= band.last ? depth_m[i] : 0.0;
    };
    if (m < 4) {  // a window of 1-3 bins (tiny array end): nothing to smooth
      for (int i = first; i <= last; ++i) out.depth_m[i] += band_depth(i);
      continue;
    }
    Eigen::VectorXd t(m), w = Eigen::VectorXd::Constant(m, h_m);
    Eigen::MatrixXd v(m, 1);
    for (int i = 0; i < m; ++i) {
      t[i] = (first + i) * h_m;
      v(i, 0) = band_depth(first + i);
    }
    const double range = (m - 1) * h_m;
    // Knots every l / knots_per_length, not finer than a bin, and at least 8 intervals so that
    // clamping both ends leaves coefficients free.
    so.knot_spacing = std::min(std::max(h_m, l / o.knots_per_smoothing_length), range / 8.0);
    so.clamp_start = first > 0;
    so.clamp_end = last < n - 1;
    const SmoothingSplineFit fit = FitSmoothingSpline(t, v, w, so);
    for (int i = 0; i < m; ++i) {
      out.depth_m[first + i] += std::max(0.0, fit.spline.Value(t[i])[0]);
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
