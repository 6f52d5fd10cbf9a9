#include "core/numerics/cubic_spline.h"

#include <cmath>

#include <gtest/gtest.h>

namespace railwear {
namespace {

TEST(CubicSpline, ReproducesCubicInTheInterior) {
  // A natural spline reproduces a straight line exactly and interpolates the knots.
  std::vector<double> t, v;
  for (int i = 0; i <= 10; ++i) {
    t.push_back(0.3 * i);
    v.push_back(2.0 - 1.5 * t.back());
  }
  CubicSpline s(t, v);
  for (double x = 0.0; x <= 3.0; x += 0.07) {
    EXPECT_NEAR(s.Value(x), 2.0 - 1.5 * x, 1e-12);
    EXPECT_NEAR(s.Derivative(x), -1.5, 1e-12);
    EXPECT_NEAR(s.SecondDerivative(x), 0.0, 1e-12);
  }
}

TEST(CubicSpline, ConvergesOnSmoothFunction) {
  // sin on a fine grid: interior error O(h^4) for the value, O(h^2) for the second derivative.
  std::vector<double> t, v;
  const int n = 200;
  for (int i = 0; i <= n; ++i) {
    t.push_back(M_PI * i / n);
    v.push_back(std::sin(t.back()));
  }
  CubicSpline s(t, v);
  for (double x = 0.5; x <= 2.5; x += 0.013) {
    EXPECT_NEAR(s.Value(x), std::sin(x), 1e-9);
    EXPECT_NEAR(s.Derivative(x), std::cos(x), 1e-6);
    EXPECT_NEAR(s.SecondDerivative(x), -std::sin(x), 1e-4);
  }
}

}  // namespace
}  // namespace railwear
