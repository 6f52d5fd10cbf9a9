// Interpolating cubic splines (C2) of a strictly increasing parameter, with value, first and
// second derivative: CubicSpline for one scalar function, CubicSplineCurve for a plane curve
// (y(t), z(t)) on shared knots, as a profile's y(s) and z(s) are.
//
// Both store each interval's cubic in power form about the interval's start, so that an
// evaluation is one interval lookup and Horner's rule, without a division: on [t_i, t_i+1],
// with u = t - t_i,
//   value = c0 + u (c1 + u (c2 + u c3)),  c0 = v_i,  c1 = the slope at t_i,  c2 = m_i / 2,
//   c3 = (m_i+1 - m_i) / (6 h),  h = t_i+1 - t_i,  m the second derivatives at the knots.
// The coefficients are the knot form's values at t_i (its a = 1, b = 0), so value, first and
// second derivative at every knot are those of the knot form
//   a v_i + b v_i+1 + ((a^3 - a) m_i + (b^3 - b) m_i+1) h^2 / 6,  a = (t_i+1 - t) / h, b = 1 - a,
// bit for bit; between the knots the two forms differ by rounding (tests/core/numerics/
// cubic_spline_test.cpp bounds it). The last knot has a piece of its own, the last interval's
// cubic expanded about it, so that it too is exact and t beyond it extrapolates that cubic.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace railwear {

namespace internal {

// Strictly increasing knots t_0 < ... < t_n-1 (n >= 2) and an O(1) lookup of the knot at or
// below a parameter.
class SplineKnots {
 public:
  SplineKnots() = default;
  explicit SplineKnots(std::vector<double> t);

  // The last knot i with t_i <= t; 0 for t below t_0 (and NaN), n - 1 at or beyond t_n-1.
  int Piece(double t) const {
    if (!(t >= t_first_)) return 0;
    if (t >= t_last_) return static_cast<int>(t_.size()) - 1;
    // The bucket's first knot is at or below t (Bucket is monotone in t), and t < t_last_ stops
    // the walk on the last interval at the latest.
    int i = bucket_first_[Bucket(t)];
    while (t_[i + 1] <= t) ++i;
    return i;
  }
  const std::vector<double>& t() const { return t_; }

 private:
  // Equal buckets of [t_0, t_n-1), one per interval: t < t_n-1 lies in bucket Bucket(t) <= n - 1
  // (the product may round up to n - 1), and bucket_first_[k] is the last knot i (< n - 1) whose
  // own bucket is below k, or 0. Profiles' knots are nearly equally spaced, so a lookup walks
  // on a knot or two from there.
  int Bucket(double t) const { return static_cast<int>((t - t_first_) * bucket_scale_); }
  std::vector<double> t_;
  double t_first_ = 0.0, t_last_ = 0.0, bucket_scale_ = 0.0;
  std::vector<int> bucket_first_;
};

// A cubic's power-form coefficients c0..c3 about its piece's knot.
using CubicCoefficients = std::array<double, 4>;

// Value, first and second derivative of c0 + u (c1 + u (c2 + u c3)) (any null is skipped).
inline void EvaluateCubic(const double* c, double u, double* value, double* d1, double* d2) {
  if (value) *value = c[0] + u * (c[1] + u * (c[2] + u * c[3]));
  if (d1) *d1 = c[1] + u * (2.0 * c[2] + u * (3.0 * c[3]));
  if (d2) *d2 = 2.0 * c[2] + u * (6.0 * c[3]);
}

}  // namespace internal

class CubicSpline {
 public:
  CubicSpline() = default;
  // t: strictly increasing knots (at least 2); v: values at the knots (same size).
  // Natural end conditions (zero second derivative at both ends).
  CubicSpline(std::vector<double> t, std::vector<double> v);

  double Value(double t) const;
  double Derivative(double t) const;
  double SecondDerivative(double t) const;
  // All three at once (cheaper than three calls; any null is skipped).
  void Evaluate(double t, double* value, double* d1, double* d2) const;

  const std::vector<double>& knots() const { return knots_.t(); }
  const std::vector<double>& values() const { return v_; }

 private:
  internal::SplineKnots knots_;
  std::vector<double> v_;
  std::vector<internal::CubicCoefficients> c_;  // per knot, the cubic from it on
};

// A plane curve (y(t), z(t)): two natural cubic splines on the same knots, as CubicSpline
// builds them, each piece's eight coefficients side by side in one cache line, evaluated after
// one interval lookup for both. Its y and z are those of CubicSpline(t, y) and
// CubicSpline(t, z) bit for bit.
class CubicSplineCurve {
 public:
  CubicSplineCurve() = default;
  // t: strictly increasing knots (at least 2); y, z: the coordinates at the knots (same size).
  CubicSplineCurve(std::vector<double> t, const std::vector<double>& y,
                   const std::vector<double>& z);

  // (y, z), its first and second derivative with respect to t, at t (any null is skipped).
  void Evaluate(double t, Eigen::Vector2d* value, Eigen::Vector2d* d1, Eigen::Vector2d* d2) const {
    const int i = knots_.Piece(t);
    const double u = t - knots_.t()[i];
    const Piece& p = pieces_[i];
    internal::EvaluateCubic(p.y.data(), u, value ? &value->x() : nullptr, d1 ? &d1->x() : nullptr,
                            d2 ? &d2->x() : nullptr);
    internal::EvaluateCubic(p.z.data(), u, value ? &value->y() : nullptr, d1 ? &d1->y() : nullptr,
                            d2 ? &d2->y() : nullptr);
  }

  const std::vector<double>& knots() const { return knots_.t(); }

 private:
  struct alignas(64) Piece {
    internal::CubicCoefficients y, z;
  };
  internal::SplineKnots knots_;
  std::vector<Piece> pieces_;  // per knot, the cubics from it on
};

}  // namespace railwear
