// Smoothing the wear-depth field after each wear step, before the profile is updated: removes
// bin-scale noise (from the contact grid and the traffic sampling) that would otherwise grow
// into waviness of the worn profile, while keeping the worn area, the position of the wear
// peak, and depth >= 0.
//
// What is solved: on each band of the field (a run of non-zero bins) widened by a margin of
// margin_lengths smoothing lengths (bands one by one; zeros elsewhere stay zeros), the spline of
// wear/smoothing_spline.h with
//     minimise  sum_i h (g(s_i) - d_i)^2 + l^4 integral g''(s)^2 ds
//     subject to  B-spline coefficients >= 0        (so g >= 0)
//                 sum_i h g(s_i) = sum_i h d_i      (worn area; heavily weighted residual)
//                 g = g' = g'' = 0 at a window end inside the field (C2 join with the zeros).
// l = smoothing_length_m, so lambda = l^4 [m^4]. Away from active bounds this is Reinsch's
// smoothing spline: a symmetric linear filter with transfer function 1 / (1 + (2 pi l / L)^4)
// for wavelength L along the profile. Wavelength 2 pi l (6.3 mm for the default 1 mm) keeps
// half its amplitude; the bin-scale sawtooth (L = 2 h = 0.2 mm) is damped by ~1e-6; wear
// features wider than ~4 pi l are kept within a few per cent. Its equivalent kernel is
// symmetric, so a symmetric peak does not move; constants and linear trends pass unchanged, so
// even without the constraint the area (and the first moment) is kept wherever the bounds are
// inactive. Repeated application damps as 1 / (1 + (2 pi l / L)^4)^k: it never amplifies any
// wavelength (no growing oscillation), and k applications act like one with length l k^(1/4).
//
// Speed: only windows are fitted (knots every l / knots_per_smoothing_length, not finer than a
// bin); a ~32 mm support (42 mm window) of a 1500-bin field costs about 2.5 ms per call
// (depth_smoothing_test prints the figure: ctest -R DepthSmoothing --verbose).
#pragma once

#include <string>
#include <vector>

#include "wear/smoothing_spline.h"

namespace railwear {

struct DepthSmoothingOptions {
  // Smoothing length l [m] (> 0): lambda = l^4; wavelengths below 2 pi l are damped by more
  // than half (see above). 1 mm: well below a contact patch (10+ mm), ten bins of 0.1 mm.
  double smoothing_length_m = 1e-3;
  // Knot spacing = l / knots_per_smoothing_length, not below the bin width (> 0). 2: the
  // smoothed field has no content above 1 / l, so 4 pi knots per cut-off wavelength suffice.
  double knots_per_smoothing_length = 2.0;
  // Margin around the support [smoothing lengths] (> 0). The filter's kernel changes sign at
  // 3.3 l; 5 l leaves room for the smoothed field to come down to zero inside the window.
  double margin_lengths = 5.0;
  // Bins with depth > support_threshold * max depth form the support (in [0, 1)). Depth below it
  // and farther than the margin from the support is set to zero (its area, at most
  // support_threshold * max depth * width, shows in area_error).
  double support_threshold = 1e-6;
  // Weight of the area residual relative to the data term (> 0); the remaining area error is
  // about 1 / area_constraint_weight of what the bounds alone would change.
  double area_constraint_weight = 1e6;
  // After the fit, scale the field by (area before) / (area after) so the area is exact to
  // rounding; area_error reports the error before this correction.
  bool rescale_to_area = true;
  // Ceres iteration limit per window (>= 1).
  int max_num_iterations = 100;

  // False with a message naming the first bad option, its value and what was expected.
  bool IsValid(std::string* error) const;
};

struct DepthSmoothing {
  std::vector<double> depth_m;  // smoothed depth [m], shape [n], >= 0
  // (area after - area before) / area before, before the final rescale (0 for an all-zero field).
  double area_error = 0.0;
  double lambda = 0.0;           // l^4 [m^4]
  int num_windows = 0;           // windows fitted
  int num_fitted_bins = 0;       // bins inside windows
  int num_ceres_iterations = 0;  // summed over windows
  // The worst status over the windows (kConverged when nothing was fitted) and its message.
  SmoothingSplineStatus status = SmoothingSplineStatus::kConverged;
  std::string message;
};

// depth_m: wear depth on uniform bins of width h_m along the rail arc length, shape [n], metres,
// finite and >= 0. h_m > 0 [m]. Throws InputError for invalid options, h_m or depth values
// (naming the index and value). Fields with fewer than 4 bins are returned unchanged.
DepthSmoothing SmoothDepthField(const std::vector<double>& depth_m, double h_m,
                                const DepthSmoothingOptions& options);

}  // namespace railwear
