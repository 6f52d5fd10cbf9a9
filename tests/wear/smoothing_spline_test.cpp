// Tests of the smoothing spline: the fit against a naive dense solve with an independent
// B-spline evaluation (Cox-de Boor), GCV against a brute-force search, the documented transfer
// function (what lambda means), exactness on the penalty's null space, clamped ends, the robust
// stages, and the messages for bad input.
#include "wear/smoothing_spline.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

// Cox-de Boor value of cubic B-spline j on the uniform knots tau_i = t0 + (i - 3) h.
double CoxDeBoor(int j, int p, double t, double t0, double h) {
  auto tau = [&](int i) { return t0 + (i - 3) * h; };
  if (p == 0) return (tau(j) <= t && t < tau(j + 1)) ? 1.0 : 0.0;
  const double a = (t - tau(j)) / (tau(j + p) - tau(j));
  const double b = (tau(j + p + 1) - t) / (tau(j + p + 1) - tau(j + 1));
  return a * CoxDeBoor(j, p - 1, t, t0, h) + b * CoxDeBoor(j + 1, p - 1, t, t0, h);
}

// The naive problem: dense B, dense penalty by 3-point Gauss and central differences (exact
// inside an interval, where the spline is a cubic), dense solve.
struct Naive {
  Eigen::MatrixXd coefficients;  // [m][dim]
  double trace = 0.0;
  double gcv = 0.0;
};

Naive NaiveFit(const Eigen::VectorXd& t, const Eigen::MatrixXd& v, double knot_spacing,
               double lambda) {
  const int n = static_cast<int>(t.size());
  const double t0 = t[0], range = t[n - 1] - t[0];
  const int k_count = static_cast<int>(std::ceil(range / knot_spacing - 1e-9));
  const double h = range / k_count;
  const int m = k_count + 3;
  const double t_last = std::nextafter(t[n - 1], -1e300);  // half-open last interval
  Eigen::MatrixXd b(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) b(i, j) = CoxDeBoor(j, 3, std::min(t[i], t_last), t0, h);
  }
  Eigen::MatrixXd omega = Eigen::MatrixXd::Zero(m, m);
  const double nodes[3] = {0.5 - std::sqrt(0.15), 0.5, 0.5 + std::sqrt(0.15)};
  const double weights[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const double delta = 1e-3 * h;
  for (int k = 0; k < k_count; ++k) {
    for (int q = 0; q < 3; ++q) {
      const double tq = t0 + (k + nodes[q]) * h;
      Eigen::VectorXd d2(m);
      for (int j = 0; j < m; ++j) {
        d2[j] = (CoxDeBoor(j, 3, tq + delta, t0, h) - 2.0 * CoxDeBoor(j, 3, tq, t0, h) +
                 CoxDeBoor(j, 3, tq - delta, t0, h)) /
                (delta * delta);
      }
      omega += weights[q] * h * d2 * d2.transpose();
    }
  }
  const double w = range / (n - 1);  // the default weight
  const Eigen::MatrixXd mat = w * b.transpose() * b + lambda * omega;
  Naive out;
  out.coefficients = mat.ldlt().solve(w * b.transpose() * v);
  const Eigen::MatrixXd hat = b * mat.ldlt().solve(w * b.transpose());
  out.trace = hat.trace();
  const double rss = (b * out.coefficients - v).squaredNorm() / v.cols();
  out.gcv = (rss / n) / std::pow(1.0 - out.trace / n, 2);
  return out;
}

// Random data on uneven t (fixed seed).
void MakeData(int n, int dim, unsigned seed, Eigen::VectorXd* t, Eigen::MatrixXd* v) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> ts(n);
  for (double& x : ts) x = u(rng);
  std::sort(ts.begin(), ts.end());
  t->resize(n);
  v->resize(n, dim);
  for (int i = 0; i < n; ++i) {
    (*t)[i] = ts[i];
    for (int d = 0; d < dim; ++d) (*v)(i, d) = std::sin(6.0 * ts[i] + d) + 0.1 * (u(rng) - 0.5);
  }
}

// Both solve the same normal equations in double precision; the naive one by dense LDL^T, with
// a finite-difference penalty whose rounding error is ~1e-10 relative.
constexpr double kNaiveTolerance = 1e-7;

TEST(SmoothingSplineTest, FitMatchesNaiveDenseSolve) {
  Eigen::VectorXd t;
  Eigen::MatrixXd v;
  MakeData(60, 2, 7, &t, &v);
  SmoothingSplineOptions o;
  o.knot_spacing = 0.1;
  o.lambda = 1e-4;
  o.loss = RobustLoss::kNone;
  const SmoothingSplineFit fit = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
  const Naive naive = NaiveFit(t, v, o.knot_spacing, *o.lambda);
  ASSERT_EQ(fit.spline.coefficients().rows(), naive.coefficients.rows());
  const double scale = naive.coefficients.cwiseAbs().maxCoeff();
  EXPECT_LT((fit.spline.coefficients() - naive.coefficients).cwiseAbs().maxCoeff(),
            kNaiveTolerance * scale);
  EXPECT_NEAR(fit.summary.effective_dof, naive.trace, kNaiveTolerance * naive.trace);
  EXPECT_EQ(fit.summary.status, SmoothingSplineStatus::kConverged) << fit.summary.message;
  EXPECT_FALSE(fit.summary.lambda_from_gcv);
  EXPECT_DOUBLE_EQ(fit.summary.lambda, 1e-4);
  // Values through the class agree with the Cox-de Boor sum.
  for (double x : {0.05, 0.333, 0.71}) {
    double cdb = 0.0;
    for (int j = 0; j < naive.coefficients.rows(); ++j) {
      cdb += naive.coefficients(j, 1) * CoxDeBoor(j, 3, x, t[0], fit.spline.knot_spacing());
    }
    EXPECT_NEAR(fit.spline.Value(x)[1], cdb, kNaiveTolerance * scale);
  }
}

TEST(SmoothingSplineTest, GcvFindsTheMinimumOfABruteForceSearch) {
  Eigen::VectorXd t;
  Eigen::MatrixXd v;
  MakeData(80, 1, 11, &t, &v);
  SmoothingSplineOptions o;
  o.knot_spacing = 0.05;
  o.loss = RobustLoss::kNone;
  const SmoothingSplineFit fit = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
  ASSERT_TRUE(fit.summary.lambda_from_gcv);
  // Brute force over the smoothing length on a fine log grid of the same search range.
  double best = std::numeric_limits<double>::infinity();
  double best_lambda = 0.0;
  for (int g = 0; g <= 400; ++g) {
    const double l = o.gcv_min_length_ratio * o.knot_spacing *
                     std::pow(o.gcv_max_length_ratio / o.gcv_min_length_ratio, g / 400.0);
    const Naive naive = NaiveFit(t, v, o.knot_spacing, std::pow(l, 4));
    if (naive.gcv < best) {
      best = naive.gcv;
      best_lambda = std::pow(l, 4);
    }
  }
  const Naive at_choice = NaiveFit(t, v, o.knot_spacing, fit.summary.lambda);
  // The golden-section optimum is at least as good as the grid (to rounding) and close to it.
  EXPECT_LE(at_choice.gcv, best * (1.0 + 1e-6));
  EXPECT_NEAR(std::log(fit.summary.lambda), std::log(best_lambda), 4.0 * 0.05);
}

TEST(SmoothingSplineTest, LambdaIsTheDocumentedTransferFunction) {
  // Dense evenly spaced samples of a sine of wavelength L; the fit keeps 1 / (1 + lambda
  // (2 pi / L)^4) of the amplitude away from the ends.
  const double length = 0.2, wavelength = 0.01, amplitude = 1e-3;
  const int n = 2001;
  Eigen::VectorXd t(n);
  Eigen::MatrixXd v(n, 1);
  for (int i = 0; i < n; ++i) {
    t[i] = length * i / (n - 1);
    v(i, 0) = amplitude * std::sin(2.0 * M_PI * t[i] / wavelength);
  }
  for (double l_ratio : {1.0, 0.5}) {
    const double l = l_ratio * wavelength / (2.0 * M_PI);
    SmoothingSplineOptions o;
    o.lambda = std::pow(l, 4);
    o.loss = RobustLoss::kNone;
    const SmoothingSplineFit fit = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
    double peak = 0.0;
    for (double x = 0.05; x < 0.15; x += 1e-5) peak = std::max(peak, fit.spline.Value(x)[0]);
    const double expected = 1.0 / (1.0 + std::pow(l_ratio, 4));
    // Discrete sampling (20 points per wavelength) and knots every 0.5 mm change the continuous
    // transfer function by well under 1 %.
    constexpr double kTransferTolerance = 0.01;
    EXPECT_NEAR(peak / amplitude, expected, kTransferTolerance) << "l / (L / 2 pi) = " << l_ratio;
  }
}

TEST(SmoothingSplineTest, StraightLinesPassUnchangedAtAnyLambda) {
  const int n = 50;
  Eigen::VectorXd t(n);
  Eigen::MatrixXd v(n, 2);
  for (int i = 0; i < n; ++i) {
    t[i] = 0.001 * i * i / n;  // uneven
    v(i, 0) = 0.3 - 2.0 * t[i];
    v(i, 1) = 5.0 * t[i];
  }
  // Smoothing lengths across the whole GCV search range (0.01 to 100 knot spacings).
  for (double l_ratio : {0.01, 1.0, 100.0}) {
    SmoothingSplineOptions o;
    o.knot_spacing = 1e-4;
    o.lambda = std::pow(l_ratio * o.knot_spacing, 4);
    const SmoothingSplineFit fit = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
    // The normal equations' condition number grows as lambda / h^4; at l = 100 h about 1e9
    // relative is left of double precision (values here are of order 0.3).
    constexpr double kRounding = 1e-8;
    EXPECT_LT(fit.summary.max_residual, kRounding) << "l / h = " << l_ratio;
    EXPECT_EQ(fit.summary.num_rejected, 0);
  }
}

TEST(SmoothingSplineTest, GcvOnNoisySineRecoversTheNoise) {
  std::mt19937 rng(3);
  const double sigma = 0.01;
  std::normal_distribution<double> noise(0.0, sigma);
  const int n = 400;
  Eigen::VectorXd t(n);
  Eigen::MatrixXd v(n, 1), truth(n, 1);
  for (int i = 0; i < n; ++i) {
    t[i] = i / (n - 1.0);
    truth(i, 0) = std::sin(5.0 * t[i]) + 0.5 * std::cos(13.0 * t[i]);
    v(i, 0) = truth(i, 0) + noise(rng);
  }
  SmoothingSplineOptions o;
  o.knot_spacing = 0.01;
  const SmoothingSplineFit fit = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
  // Wahba's estimate RSS / (n - tr A) of the noise variance, and the error against the truth.
  const double fit_sigma =
      fit.summary.rms_residual * std::sqrt(n / (n - fit.summary.effective_dof));
  constexpr double kSigmaTolerance = 0.1;  // 400 samples: the estimate's own spread is ~4 %
  EXPECT_NEAR(fit_sigma / sigma, 1.0, kSigmaTolerance);
  double max_error = 0.0;
  for (int i = 0; i < n; ++i) {
    max_error = std::max(max_error, std::abs(fit.spline.Value(t[i])[0] - truth(i, 0)));
  }
  EXPECT_LT(max_error, sigma);  // the fit is closer to the truth than a typical sample
  EXPECT_EQ(fit.summary.num_rejected, 0);
  EXPECT_TRUE(fit.summary.lambda_from_gcv);
}

TEST(SmoothingSplineTest, GrossOutlierIsRejectedAndModerateOnesDownWeighted) {
  std::mt19937 rng(5);
  const double sigma = 0.01;
  std::normal_distribution<double> noise(0.0, sigma);
  const int n = 300;
  Eigen::VectorXd t(n);
  Eigen::MatrixXd v(n, 1);
  for (int i = 0; i < n; ++i) {
    t[i] = i / (n - 1.0);
    v(i, 0) = std::sin(4.0 * t[i]) + noise(rng);
  }
  Eigen::MatrixXd bad = v;
  bad(150, 0) += 100.0 * sigma;
  SmoothingSplineOptions o;
  o.knot_spacing = 0.02;
  const SmoothingSplineFit clean = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
  const SmoothingSplineFit fit = FitSmoothingSpline(t, bad, Eigen::VectorXd(), o);
  EXPECT_EQ(fit.summary.num_rejected, 1);
  EXPECT_TRUE(fit.rejected[150]);
  EXPECT_EQ(fit.summary.max_residual_index, 150);
  EXPECT_NEAR(fit.summary.robust_sigma / sigma, 1.0, 0.15);  // MAD of 300 residuals: ~6 % spread
  // Without the outlier the fits differ only as much as one point's share of the data moves
  // them: far below the noise.
  EXPECT_LT(std::abs(fit.spline.Value(t[150])[0] - clean.spline.Value(t[150])[0]), 0.2 * sigma);
  // Gaussian noise has ~0.3 % of points beyond the Huber scale of 3 sigma.
  EXPECT_LE(clean.summary.num_downweighted, 5);
  EXPECT_NE(fit.summary.BriefReport().find("huber"), std::string::npos);
}

TEST(SmoothingSplineTest, ClampedEndsJoinZeroWithC2) {
  const int n = 100;
  Eigen::VectorXd t(n);
  Eigen::MatrixXd v(n, 1);
  for (int i = 0; i < n; ++i) {
    t[i] = 1e-4 * i;
    v(i, 0) = 1e-6 * std::exp(-std::pow((i - 50) / 10.0, 2));
  }
  SmoothingSplineOptions o;
  o.knot_spacing = 5e-4;
  o.lambda = 1e-15;
  o.loss = RobustLoss::kNone;
  o.clamp_start = o.clamp_end = true;
  const SmoothingSplineFit fit = FitSmoothingSpline(t, v, Eigen::VectorXd(), o);
  for (double x : {t[0], t[n - 1]}) {
    EXPECT_EQ(fit.spline.Value(x)[0], 0.0);
    EXPECT_EQ(fit.spline.Derivative(x)[0], 0.0);
    EXPECT_EQ(fit.spline.SecondDerivative(x)[0], 0.0);
  }
  EXPECT_GT(fit.spline.Value(t[50])[0], 0.5e-6);
}

TEST(SmoothingSplineTest, NamesRoundTrip) {
  for (RobustLoss v : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    EXPECT_EQ(RobustLossFromString(ToString(v)), v);
  }
  for (SmoothingSplineStatus v :
       {SmoothingSplineStatus::kConverged, SmoothingSplineStatus::kNoConvergence,
        SmoothingSplineStatus::kFailure}) {
    EXPECT_EQ(SmoothingSplineStatusFromString(ToString(v)), v);
  }
  EXPECT_FALSE(RobustLossFromString("tukey").has_value());
}

std::string ThrownMessage(const Eigen::VectorXd& t, const Eigen::MatrixXd& v,
                          const Eigen::VectorXd& w, const SmoothingSplineOptions& o) {
  try {
    FitSmoothingSpline(t, v, w, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(SmoothingSplineTest, BadInputNamesTheValue) {
  Eigen::VectorXd t(5);
  t << 0.0, 1.0, 2.0, std::nan(""), 4.0;
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(5, 1);
  SmoothingSplineOptions o;
  EXPECT_NE(ThrownMessage(t, v, {}, o).find("t[3] = nan: expected a finite number"),
            std::string::npos)
      << ThrownMessage(t, v, {}, o);
  EXPECT_NE(ThrownMessage(Eigen::VectorXd::Constant(5, 2.0), v, {}, o)
                .find("parameter range [2, 2]: expected t_max > t_min"),
            std::string::npos);
  t[3] = 3.0;
  v(2, 0) = std::nan("");
  EXPECT_NE(ThrownMessage(t, v, {}, o).find("value[2][0] = nan"), std::string::npos);
  v(2, 0) = 0.0;
  Eigen::VectorXd w = Eigen::VectorXd::Ones(5);
  w[4] = -1.0;
  EXPECT_NE(ThrownMessage(t, v, w, o).find("weight[4] = -1"), std::string::npos);
  EXPECT_NE(ThrownMessage(t, Eigen::MatrixXd::Zero(5, 4), {}, o).find("dimension 4"),
            std::string::npos);
  o.lower_bound = 0.0;
  EXPECT_NE(ThrownMessage(t, Eigen::MatrixXd::Zero(5, 2), {}, o)
                .find("lower_bound = 0 with value dimension 2: expected dimension 1"),
            std::string::npos);
  o.lower_bound.reset();

  std::string error;
  o.knot_spacing = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("knot_spacing = 0: expected a finite number > 0"), std::string::npos);
  EXPECT_EQ(ThrownMessage(t, v, {}, o), error);
  o = SmoothingSplineOptions();
  o.lambda = -1.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("lambda = -1"), std::string::npos);
  o = SmoothingSplineOptions();
  o.lower_bound = 1.0;
  o.clamp_start = true;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("lower_bound = 1"), std::string::npos);
  o = SmoothingSplineOptions();
  o.gcv_grid_points = 2;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("gcv_grid_points = 2"), std::string::npos);
  EXPECT_TRUE(SmoothingSplineOptions().IsValid(&error));
}

}  // namespace
}  // namespace railwear
