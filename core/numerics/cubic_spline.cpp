// Natural cubic spline: second derivatives from the tridiagonal system, evaluated per interval.
#include "core/numerics/cubic_spline.h"

#include <algorithm>

#include "core/numerics/check.h"

namespace railwear {

CubicSpline::CubicSpline(std::vector<double> t, std::vector<double> v)
    : t_(std::move(t)), v_(std::move(v)) {
  const int n = static_cast<int>(t_.size());
  RAILWEAR_CHECK(n >= 2 && static_cast<int>(v_.size()) == n);
  m_.assign(n, 0.0);
  if (n == 2) return;
  // Thomas algorithm for h_{i-1} m_{i-1} + 2(h_{i-1}+h_i) m_i + h_i m_{i+1} = 6 (d_i - d_{i-1}).
  std::vector<double> c(n, 0.0), d(n, 0.0);
  for (int i = 1; i < n - 1; ++i) {
    const double h0 = t_[i] - t_[i - 1];
    const double h1 = t_[i + 1] - t_[i];
    RAILWEAR_CHECK(h0 > 0 && h1 > 0);
    const double rhs = 6.0 * ((v_[i + 1] - v_[i]) / h1 - (v_[i] - v_[i - 1]) / h0);
    const double diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
    c[i] = h1 / diag;
    d[i] = (rhs - h0 * d[i - 1]) / diag;
  }
  for (int i = n - 2; i >= 1; --i) m_[i] = d[i] - c[i] * m_[i + 1];
}

int CubicSpline::Interval(double t) const {
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  int i = static_cast<int>(it - t_.begin()) - 1;
  return std::clamp(i, 0, static_cast<int>(t_.size()) - 2);
}

void CubicSpline::Evaluate(double t, double* value, double* d1, double* d2) const {
  const int i = Interval(t);
  const double h = t_[i + 1] - t_[i];
  const double a = (t_[i + 1] - t) / h;
  const double b = (t - t_[i]) / h;
  const double m0 = m_[i], m1 = m_[i + 1];
  if (value) {
    *value =
        a * v_[i] + b * v_[i + 1] + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
  }
  if (d1) {
    *d1 = (v_[i + 1] - v_[i]) / h - (3.0 * a * a - 1.0) * h * m0 / 6.0 +
          (3.0 * b * b - 1.0) * h * m1 / 6.0;
  }
  if (d2) *d2 = a * m0 + b * m1;
}

double CubicSpline::Value(double t) const {
  double v;
  Evaluate(t, &v, nullptr, nullptr);
  return v;
}
double CubicSpline::Derivative(double t) const {
  double d;
  Evaluate(t, nullptr, &d, nullptr);
  return d;
}
double CubicSpline::SecondDerivative(double t) const {
  double d;
  Evaluate(t, nullptr, nullptr, &d);
  return d;
}

}  // namespace railwear
