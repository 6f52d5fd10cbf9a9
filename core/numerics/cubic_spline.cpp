// Natural cubic splines: second derivatives from the tridiagonal system, then each interval's
// cubic in power form about its start (cubic_spline.h).
#include "core/numerics/cubic_spline.h"

#include <cmath>

#include "core/numerics/check.h"

namespace railwear {

namespace internal {

SplineKnots::SplineKnots(std::vector<double> t) : t_(std::move(t)) {
  const int n = static_cast<int>(t_.size());
  RAILWEAR_CHECK(n >= 2);
  t_first_ = t_.front();
  t_last_ = t_.back();
  bucket_scale_ = (n - 1) / (t_last_ - t_first_);
  RAILWEAR_CHECK(std::isfinite(bucket_scale_) && bucket_scale_ > 0.0);
  // Bucket is monotone in t (a subtraction and a multiplication, each rounded monotonically), so
  // a knot in a lower bucket lies below every t of bucket k: the walk from there only goes on.
  bucket_first_.resize(n);
  int i = 0;
  for (int k = 0; k < n; ++k) {
    while (i + 1 < n - 1 && Bucket(t_[i + 1]) < k) ++i;
    bucket_first_[k] = i;
  }
}

}  // namespace internal

namespace {

// The natural spline through (t_i, v_i), piece i in power form about t_i (cubic_spline.h): the
// knot form's value, slope and half its second derivative at t_i, and the third derivative / 6.
// The last piece is the last interval's cubic about the last knot.
std::vector<internal::CubicCoefficients> PowerForm(const std::vector<double>& t,
                                                   const std::vector<double>& v) {
  const int n = static_cast<int>(t.size());
  RAILWEAR_CHECK(n >= 2 && static_cast<int>(v.size()) == n);
  std::vector<double> m(n, 0.0);  // second derivatives at the knots
  // Thomas algorithm for h_{i-1} m_{i-1} + 2(h_{i-1}+h_i) m_i + h_i m_{i+1} = 6 (d_i - d_{i-1}).
  std::vector<double> c(n, 0.0), d(n, 0.0);
  for (int i = 1; i < n - 1; ++i) {
    const double h0 = t[i] - t[i - 1];
    const double h1 = t[i + 1] - t[i];
    RAILWEAR_CHECK(h0 > 0 && h1 > 0);
    const double rhs = 6.0 * ((v[i + 1] - v[i]) / h1 - (v[i] - v[i - 1]) / h0);
    const double diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
    c[i] = h1 / diag;
    d[i] = (rhs - h0 * d[i - 1]) / diag;
  }
  for (int i = n - 2; i >= 1; --i) m[i] = d[i] - c[i] * m[i + 1];
  // The knot form's slope at a knot of [t_i, t_i+1]: its a = 1 (the start) or a = 0 (the end).
  const auto slope = [&](int i, double a) {
    const double h = t[i + 1] - t[i], b = 1.0 - a;
    return (v[i + 1] - v[i]) / h - (3.0 * a * a - 1.0) * h * m[i] / 6.0 +
           (3.0 * b * b - 1.0) * h * m[i + 1] / 6.0;
  };
  std::vector<internal::CubicCoefficients> pieces(n);
  for (int i = 0; i + 1 < n; ++i) {
    const double h = t[i + 1] - t[i];
    pieces[i] = {v[i], slope(i, 1.0), 0.5 * m[i], (m[i + 1] - m[i]) / (6.0 * h)};
  }
  pieces[n - 1] = {v[n - 1], slope(n - 2, 0.0), 0.5 * m[n - 1], pieces[n - 2][3]};
  return pieces;
}

}  // namespace

CubicSpline::CubicSpline(std::vector<double> t, std::vector<double> v)
    : knots_(std::move(t)), v_(std::move(v)), c_(PowerForm(knots_.t(), v_)) {}

void CubicSpline::Evaluate(double t, double* value, double* d1, double* d2) const {
  const int i = knots_.Piece(t);
  internal::EvaluateCubic(c_[i].data(), t - knots_.t()[i], value, d1, d2);
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

CubicSplineCurve::CubicSplineCurve(std::vector<double> t, const std::vector<double>& y,
                                   const std::vector<double>& z)
    : knots_(std::move(t)) {
  const std::vector<internal::CubicCoefficients> cy = PowerForm(knots_.t(), y);
  const std::vector<internal::CubicCoefficients> cz = PowerForm(knots_.t(), z);
  pieces_.resize(cy.size());
  for (size_t i = 0; i < cy.size(); ++i) pieces_[i] = {cy[i], cz[i]};
}

}  // namespace railwear
