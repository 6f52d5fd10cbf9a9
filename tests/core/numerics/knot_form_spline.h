// The knot form of a natural cubic spline, the naive reference for CubicSpline's power form
// (core/numerics/cubic_spline.h): on [t_i, t_i+1], h = t_i+1 - t_i, a = (t_i+1 - t) / h,
// b = (t - t_i) / h,
//   value = a v_i + b v_i+1 + ((a^3 - a) m_i + (b^3 - b) m_i+1) h^2 / 6,
// with t's interval found by a binary search over the knots and clamped to the first and last
// interval: what CubicSpline evaluated before issue 20 stored power forms.
#pragma once

#include <algorithm>
#include <vector>

namespace railwear::testing {

struct KnotFormSpline {
  std::vector<double> t, v, m;  // knots, values and second derivatives at the knots (same size)

  void Evaluate(double x, double* value, double* d1, double* d2) const {
    const int n = static_cast<int>(t.size());
    const auto it = std::upper_bound(t.begin(), t.end(), x);
    const int i = std::clamp(static_cast<int>(it - t.begin()) - 1, 0, n - 2);
    const double h = t[i + 1] - t[i], a = (t[i + 1] - x) / h, b = (x - t[i]) / h;
    *value = a * v[i] + b * v[i + 1] +
             ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
    *d1 = (v[i + 1] - v[i]) / h - (3.0 * a * a - 1.0) * h * m[i] / 6.0 +
          (3.0 * b * b - 1.0) * h * m[i + 1] / 6.0;
    *d2 = a * m[i] + b * m[i + 1];
  }
};

}  // namespace railwear::testing
