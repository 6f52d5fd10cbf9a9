#include "core/numerics/cubic_spline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

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

// The interval lookup (a bucket index) against the naive binary search over the knots: bit for bit
// the same value and derivatives, on unequal knots (clusters, gaps of 100x), at and between the
// knots, outside both ends, at +-inf and NaN.
TEST(CubicSpline, IndexedLookupEqualsBinarySearchBitForBit) {
  std::mt19937 rng(7);  // fixed seed
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n : {2, 3, 7, 150, 1501}) {
    std::vector<double> t{-0.07}, v{0.0};
    for (int i = 1; i < n; ++i) {
      // Mostly even spacing, with clusters (1e-3) and gaps (x10) as on resampled worn profiles.
      const double r = u(rng);
      t.push_back(t.back() + 1e-4 * (r < 0.1 ? 1e-3 : r > 0.95 ? 10.0 : 1.0 + 0.2 * u(rng)));
      v.push_back(std::sin(300.0 * t.back()) + 0.1 * u(rng));
    }
    const CubicSpline s(t, v);
    std::vector<double> m(n);  // the second derivatives at the knots, exactly (a = 1, b = 0)
    for (int i = 0; i < n; ++i) m[i] = s.SecondDerivative(t[i]);
    auto naive = [&](double x, double* value, double* d1, double* d2) {
      const auto it = std::upper_bound(t.begin(), t.end(), x);
      const int i = std::clamp(static_cast<int>(it - t.begin()) - 1, 0, n - 2);
      const double h = t[i + 1] - t[i], a = (t[i + 1] - x) / h, b = (x - t[i]) / h;
      *value = a * v[i] + b * v[i + 1] +
               ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
      *d1 = (v[i + 1] - v[i]) / h - (3.0 * a * a - 1.0) * h * m[i] / 6.0 +
            (3.0 * b * b - 1.0) * h * m[i + 1] / 6.0;
      *d2 = a * m[i] + b * m[i + 1];
    };
    std::vector<double> queries = {-1.0, t.front(), t.back(), t.back() + 1.0,
                                   std::numeric_limits<double>::infinity(),
                                   -std::numeric_limits<double>::infinity()};
    for (int i = 0; i < n; ++i) {
      queries.push_back(t[i]);
      queries.push_back(std::nextafter(t[i], -1e9));
      queries.push_back(std::nextafter(t[i], 1e9));
    }
    for (int k = 0; k < 20 * n; ++k) queries.push_back(t.front() + u(rng) * (t.back() - t.front()));
    for (double x : queries) {
      double a0, a1, a2, b0, b1, b2;
      s.Evaluate(x, &a0, &a1, &a2);
      naive(x, &b0, &b1, &b2);
      if (std::isnan(b0)) {  // at +-inf
        EXPECT_TRUE(std::isnan(a0)) << "n " << n << " t " << x;
        continue;
      }
      ASSERT_EQ(a0, b0) << "n " << n << " t " << x;
      ASSERT_EQ(a1, b1) << "n " << n << " t " << x;
      ASSERT_EQ(a2, b2) << "n " << n << " t " << x;
    }
    double a0, b0, d;
    s.Evaluate(std::nan(""), &a0, &d, &d);
    naive(std::nan(""), &b0, &d, &d);
    EXPECT_TRUE(std::isnan(a0) && std::isnan(b0));
  }
}

// Splines on the same knots share one Locate (a profile's y(s) and z(s), issue 20's grids): each
// one's EvaluateAt at the other's Location is its own Evaluate bit for bit, every output alone or
// together, between, at and beyond the knots.
TEST(CubicSpline, SplinesOnTheSameKnotsShareALocationBitForBit) {
  std::mt19937 rng(20);  // fixed seed
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> t{0.0}, y{0.0}, z{0.0};
  for (int i = 1; i < 400; ++i) {
    t.push_back(t.back() + 2e-4 * (0.5 + u(rng)));
    y.push_back(std::cos(90.0 * t.back()) + 0.01 * u(rng));
    z.push_back(std::sin(40.0 * t.back()) - 0.01 * u(rng));
  }
  const CubicSpline sy(t, y), sz(t, z);
  std::vector<double> queries = {-1e-3, t.front(), t.back(), t.back() + 1e-3};
  for (double knot : t) queries.push_back(knot);
  for (int k = 0; k < 4000; ++k) queries.push_back(t.back() * (1.2 * u(rng) - 0.1));
  int compared = 0;
  for (double x : queries) {
    const CubicSpline::Location at = sy.Locate(x);
    double v, d1, d2, w, e1, e2;
    sz.Evaluate(x, &v, &d1, &d2);
    sz.EvaluateAt(at, &w, &e1, &e2);
    ASSERT_EQ(v, w) << x;
    ASSERT_EQ(d1, e1) << x;
    ASSERT_EQ(d2, e2) << x;
    double only;
    sz.EvaluateAt(at, &only, nullptr, nullptr);
    ASSERT_EQ(only, sz.Value(x)) << x;
    sz.EvaluateAt(at, nullptr, &only, nullptr);
    ASSERT_EQ(only, sz.Derivative(x)) << x;
    sz.EvaluateAt(at, nullptr, nullptr, &only);
    ASSERT_EQ(only, sz.SecondDerivative(x)) << x;
    ++compared;
  }
  EXPECT_EQ(compared, static_cast<int>(queries.size()));
}

}  // namespace
}  // namespace railwear
