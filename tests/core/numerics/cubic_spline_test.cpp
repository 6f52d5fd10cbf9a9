#include "core/numerics/cubic_spline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/numerics/knot_form_spline.h"

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

// Knots as a resampled worn profile has them: mostly even spacing, with clusters (1e-3 of the
// step) and gaps (10 steps), and values of order 1 varying on the scale of a few steps.
void UnevenKnots(int n, std::mt19937* rng, std::vector<double>* t, std::vector<double>* v) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  *t = {-0.07};
  *v = {0.0};
  for (int i = 1; i < n; ++i) {
    const double r = u(*rng);
    t->push_back(t->back() + 1e-4 * (r < 0.1 ? 1e-3 : r > 0.95 ? 10.0 : 1.0 + 0.2 * u(*rng)));
    v->push_back(std::sin(300.0 * t->back()) + 0.1 * u(*rng));
  }
}

// Where the lookups are tested: at, just below and just above every knot, outside both ends,
// and random points between the ends.
std::vector<double> Queries(const std::vector<double>& t, int random, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> queries = {-1.0, t.back() + 1.0};
  for (double knot : t) {
    queries.push_back(knot);
    queries.push_back(std::nextafter(knot, -1e9));
    queries.push_back(std::nextafter(knot, 1e9));
  }
  for (int k = 0; k < random; ++k) queries.push_back(t.front() + u(*rng) * (t.back() - t.front()));
  return queries;
}

// The bucket index against a binary search over the knots: the same knot, on unequal knots, on
// equal knots whose bucket starts fall on knots (where rounding decides), at and between the
// knots, outside both ends, at +-inf and NaN. The walk from a bucket's first knot only goes on,
// so a bucket whose first knot lay above one of its points would fail here.
TEST(CubicSpline, KnotLookupEqualsBinarySearch) {
  std::mt19937 rng(7);  // fixed seed
  std::vector<std::vector<double>> knot_sets;
  for (int n : {2, 3, 7, 150, 1501}) {
    std::vector<double> t, v;
    UnevenKnots(n, &rng, &t, &v);
    knot_sets.push_back(t);
  }
  for (double step : {0.1, 1e-4, 3.3e-4}) {
    std::vector<double> t;
    for (int i = 0; i < 1000; ++i) t.push_back(0.3 + step * i);
    knot_sets.push_back(t);
  }
  for (const std::vector<double>& t : knot_sets) {
    const int n = static_cast<int>(t.size());
    const internal::SplineKnots knots(t);
    std::vector<double> queries = Queries(t, 20 * n, &rng);
    queries.push_back(std::numeric_limits<double>::infinity());
    queries.push_back(-std::numeric_limits<double>::infinity());
    for (double x : queries) {
      const int expected =
          std::max(0, static_cast<int>(std::upper_bound(t.begin(), t.end(), x) - t.begin()) - 1);
      ASSERT_EQ(knots.Piece(x), expected) << "n " << n << " t " << x;
    }
    EXPECT_EQ(knots.Piece(std::nan("")), 0);
  }
}

// The power form against the knot form it replaced (tests/core/numerics/knot_form_spline.h).
// At the knots, the last included, value and both derivatives are the knot form's bit for bit
// (the coefficients are its values there). Between the knots and a step beyond the ends they
// differ by rounding: a few ulps of the largest value, slope and second derivative (Horner's
// sums of terms up to those sizes, against the knot form's weighted sums). Measured here at most
// 1.4e-15, 7.6e-16 and 2.4e-16 of them; 1e-14 (some 45 ulps) leaves a margin of 7.
constexpr double kPowerFormRelTol = 1e-14;

struct FormDifference {
  double value = 0.0, d1 = 0.0, d2 = 0.0;  // largest |difference| / largest |knot form|
};

FormDifference CompareWithKnotForm(const std::vector<double>& t, const std::vector<double>& v,
                                   std::mt19937* rng) {
  const int n = static_cast<int>(t.size());
  const CubicSpline spline(t, v);
  testing::KnotFormSpline knot_form{t, v, std::vector<double>(n)};
  for (int i = 0; i < n; ++i) knot_form.m[i] = spline.SecondDerivative(t[i]);
  for (int i = 0; i < n; ++i) {
    double a0, a1, a2, b0, b1, b2;
    spline.Evaluate(t[i], &a0, &a1, &a2);
    knot_form.Evaluate(t[i], &b0, &b1, &b2);
    EXPECT_EQ(a0, b0) << "knot " << i << " of " << n;
    EXPECT_EQ(a1, b1) << "knot " << i << " of " << n;
    EXPECT_EQ(a2, b2) << "knot " << i << " of " << n;
  }
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double lo = t[0] - (t[1] - t[0]), hi = t[n - 1] + (t[n - 1] - t[n - 2]);
  std::vector<double> queries = Queries(t, 50 * n, rng);
  queries.erase(queries.begin(), queries.begin() + 2);  // a step beyond the ends at most:
  for (int k = 0; k < 100; ++k) queries.push_back(lo + u(*rng) * (t[0] - lo));
  for (int k = 0; k < 100; ++k) queries.push_back(t[n - 1] + u(*rng) * (hi - t[n - 1]));
  double max_value = 0.0, max_d1 = 0.0, max_d2 = 0.0;
  FormDifference diff;
  for (double x : queries) {
    double a0, a1, a2, b0, b1, b2;
    spline.Evaluate(x, &a0, &a1, &a2);
    knot_form.Evaluate(x, &b0, &b1, &b2);
    max_value = std::max(max_value, std::abs(b0));
    max_d1 = std::max(max_d1, std::abs(b1));
    max_d2 = std::max(max_d2, std::abs(b2));
    diff.value = std::max(diff.value, std::abs(a0 - b0));
    diff.d1 = std::max(diff.d1, std::abs(a1 - b1));
    diff.d2 = std::max(diff.d2, std::abs(a2 - b2));
  }
  // (A straight line's second derivative is zero everywhere: its difference stays absolute.)
  if (max_value > 0.0) diff.value /= max_value;
  if (max_d1 > 0.0) diff.d1 /= max_d1;
  if (max_d2 > 0.0) diff.d2 /= max_d2;
  return diff;
}

TEST(CubicSpline, PowerFormIsTheKnotFormWithinRounding) {
  std::mt19937 rng(20);  // fixed seed
  for (int n : {2, 3, 7, 150, 1501}) {
    std::vector<double> t, v;
    UnevenKnots(n, &rng, &t, &v);
    const FormDifference diff = CompareWithKnotForm(t, v, &rng);
    EXPECT_LE(diff.value, kPowerFormRelTol) << n;
    EXPECT_LE(diff.d1, kPowerFormRelTol) << n;
    EXPECT_LE(diff.d2, kPowerFormRelTol) << n;
  }
}

// A curve's y and z are the splines of each coordinate alone, bit for bit, every output alone
// or together, at, between and beyond the knots.
TEST(CubicSplineCurve, IsTheSplinesOfItsCoordinatesBitForBit) {
  std::mt19937 rng(21);  // fixed seed
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> t{0.0}, y{0.0}, z{0.0};
  for (int i = 1; i < 400; ++i) {
    t.push_back(t.back() + 2e-4 * (0.5 + u(rng)));
    y.push_back(std::cos(90.0 * t.back()) + 0.01 * u(rng));
    z.push_back(std::sin(40.0 * t.back()) - 0.01 * u(rng));
  }
  const CubicSpline sy(t, y), sz(t, z);
  const CubicSplineCurve curve(t, y, z);
  std::vector<double> queries = Queries(t, 4000, &rng);
  for (int k = 0; k < 400; ++k) queries.push_back(t.back() * (1.2 * u(rng) - 0.1));
  int compared = 0;
  for (double x : queries) {
    double y0, y1, y2, z0, z1, z2;
    sy.Evaluate(x, &y0, &y1, &y2);
    sz.Evaluate(x, &z0, &z1, &z2);
    Eigen::Vector2d p, d1, d2;
    curve.Evaluate(x, &p, &d1, &d2);
    ASSERT_EQ(p.x(), y0) << x;
    ASSERT_EQ(p.y(), z0) << x;
    ASSERT_EQ(d1.x(), y1) << x;
    ASSERT_EQ(d1.y(), z1) << x;
    ASSERT_EQ(d2.x(), y2) << x;
    ASSERT_EQ(d2.y(), z2) << x;
    Eigen::Vector2d only;
    curve.Evaluate(x, &only, nullptr, nullptr);
    ASSERT_EQ(only, p) << x;
    curve.Evaluate(x, nullptr, &only, nullptr);
    ASSERT_EQ(only, d1) << x;
    curve.Evaluate(x, nullptr, nullptr, &only);
    ASSERT_EQ(only, d2) << x;
    ++compared;
  }
  EXPECT_EQ(compared, static_cast<int>(queries.size()));
  EXPECT_EQ(curve.knots(), t);
}

}  // namespace
}  // namespace railwear
