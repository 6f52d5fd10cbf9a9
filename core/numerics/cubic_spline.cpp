// Natural cubic spline: second derivatives from the tridiagonal system, evaluated per interval.
#include "core/numerics/cubic_spline.h"

#include <algorithm>
#include <cmath>

#include "core/numerics/check.h"

namespace railwear {

CubicSpline::CubicSpline(std::vector<double> t, std::vector<double> v)
    : t_(std::move(t)), v_(std::move(v)) {
  const int n = static_cast<int>(t_.size());
  RAILWEAR_CHECK(n >= 2 && static_cast<int>(v_.size()) == n);
  m_.assign(n, 0.0);
  // The interval index: one bucket per interval on average, each starting where a sweep over
  // the knots says (the same interval a binary search gives at the bucket's start).
  const int buckets = n - 1;
  bucket_scale_ = buckets / (t_[n - 1] - t_[0]);
  RAILWEAR_CHECK(std::isfinite(bucket_scale_) && bucket_scale_ > 0.0);
  bucket_first_.resize(buckets);
  int i = 0;
  for (int k = 0; k < buckets; ++k) {
    const double start = t_[0] + k / bucket_scale_;
    while (i + 1 < n - 1 && t_[i + 1] <= start) ++i;
    bucket_first_[k] = i;
  }
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
  const int last = static_cast<int>(t_.size()) - 2;  // the last interval
  if (!(t >= t_[0])) return std::isnan(t) ? last : 0;
  if (t >= t_[last + 1]) return last;
  const int k = std::min(static_cast<int>((t - t_[0]) * bucket_scale_),
                         static_cast<int>(bucket_first_.size()) - 1);
  int i = bucket_first_[k];
  // The bucket's start is rounded: step back or on to the last knot at or below t.
  while (i > 0 && t_[i] > t) --i;
  while (i < last && t_[i + 1] <= t) ++i;
  return i;
}

CubicSpline::Location CubicSpline::Locate(double t) const {
  Location at;
  at.i = Interval(t);
  at.h = t_[at.i + 1] - t_[at.i];
  at.a = (t_[at.i + 1] - t) / at.h;
  at.b = (t - t_[at.i]) / at.h;
  return at;
}

void CubicSpline::EvaluateAt(const Location& at, double* value, double* d1, double* d2) const {
  const int i = at.i;
  const double h = at.h, a = at.a, b = at.b;
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

void CubicSpline::Evaluate(double t, double* value, double* d1, double* d2) const {
  EvaluateAt(Locate(t), value, d1, d2);
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
