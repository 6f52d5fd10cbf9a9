// Interpolating cubic spline (C2) of one scalar function of a strictly increasing parameter,
// with value, first and second derivative. Used for profile curves y(s), z(s).
#pragma once

#include <vector>

namespace railwear {

class CubicSpline {
 public:
  CubicSpline() = default;
  // t: strictly increasing knots (at least 2); v: values at the knots (same size).
  // Natural end conditions (zero second derivative at both ends).
  CubicSpline(std::vector<double> t, std::vector<double> v);

  double Value(double t) const;
  double Derivative(double t) const;
  double SecondDerivative(double t) const;
  // All three at once (cheaper than three calls).
  void Evaluate(double t, double* value, double* d1, double* d2) const;

  // Where t lies: its interval and the weights of the interval's ends. Splines on the same
  // knots (a profile's y(s) and z(s)) share one Locate: EvaluateAt(Locate(t), ...) on either
  // is its Evaluate(t, ...) bit for bit, with one interval lookup and division for both.
  struct Location {
    int i = 0;
    double h = 0.0, a = 0.0, b = 0.0;  // h = t_i+1 - t_i, a = (t_i+1 - t) / h, b = (t - t_i) / h
  };
  Location Locate(double t) const;
  // Value and derivatives at a Location of a spline with this one's knots (any null is skipped).
  void EvaluateAt(const Location& at, double* value, double* d1, double* d2) const;

  const std::vector<double>& knots() const { return t_; }
  const std::vector<double>& values() const { return v_; }

 private:
  // The interval [t_i, t_i+1] holding t: the last knot i with t_i <= t, clamped to the first
  // and last interval (what a binary search over the knots gives), found in O(1) through
  // bucket_first_.
  int Interval(double t) const;
  std::vector<double> t_;
  std::vector<double> v_;
  std::vector<double> m_;  // second derivatives at the knots
  // Equal buckets of [t_0, t_n-1): bucket k covers from t_0 + k / bucket_scale_, and
  // bucket_first_[k] is Interval() at that start. Profiles' knots are nearly equally spaced, so
  // a lookup walks at most a knot or two from there.
  double bucket_scale_ = 0.0;
  std::vector<int> bucket_first_;
};

}  // namespace railwear
