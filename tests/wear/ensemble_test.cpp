// wear/ensemble.h: seeded samples (bit for bit the same from the same seed; one point per stratum
// of a Latin hypercube; inside truncation bounds), percentiles against hand-computed order
// statistics, bands of a one-parameter model whose quantiles are known, monotone in MGT, and the
// first crossing of a limit on a constant wear rate.
#include "wear/ensemble.h"

#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

SampleDistribution Lognormal(double median, double sigma_ln) {
  SampleDistribution d;
  d.kind = SampleDistributionKind::kLognormal;
  d.a = median;
  d.b = sigma_ln;
  return d;
}

TEST(EnsembleSampling, TheSameSeedGivesTheSameSamplesBitForBit) {
  SampleDistribution friction;  // uniform
  friction.a = 0.3;
  friction.b = 0.5;
  const std::vector<SampleDistribution> dims = {Lognormal(2e-4, kWearCoefficientSigmaLn),
                                                friction};
  for (const SamplingMethod m : {SamplingMethod::kLatinHypercube, SamplingMethod::kSobol}) {
    const auto a = DrawSamples(dims, 16, m, 7);
    const auto b = DrawSamples(dims, 16, m, 7);
    ASSERT_EQ(a.size(), 16u);
    for (size_t i = 0; i < a.size(); ++i) {
      for (size_t d = 0; d < dims.size(); ++d) {
        // Bit for bit: the same double, not merely close.
        EXPECT_EQ(std::memcmp(&a[i][d], &b[i][d], sizeof(double)), 0) << i << " " << d;
      }
    }
    // Another seed, other samples.
    const auto c = DrawSamples(dims, 16, m, 8);
    EXPECT_NE(a[0][0], c[0][0]);
  }
}

TEST(EnsembleSampling, LatinHypercubeHasOnePointInEachStratumOfEachDimension) {
  const int n = 37;
  const auto points = UnitSamples(3, n, SamplingMethod::kLatinHypercube, 11);
  for (int d = 0; d < 3; ++d) {
    std::vector<int> strata;
    for (const auto& p : points) {
      ASSERT_GT(p[d], 0.0);
      ASSERT_LT(p[d], 1.0);
      strata.push_back(static_cast<int>(std::floor(p[d] * n)));
    }
    std::sort(strata.begin(), strata.end());
    for (int i = 0; i < n; ++i) EXPECT_EQ(strata[i], i);
  }
}

TEST(EnsembleSampling, SobolPointsAreInsideTheUnitCube) {
  const auto points = UnitSamples(4, 64, SamplingMethod::kSobol, 3);
  for (const auto& p : points) {
    for (double v : p) {
      EXPECT_GE(v, 0.0);
      EXPECT_LT(v, 1.0);
    }
  }
}

TEST(EnsembleSampling, QuantilesAreTheDistributionsAndStayInsideTheBounds) {
  const SampleDistribution k = Lognormal(2e-4, 0.3);
  EXPECT_DOUBLE_EQ(k.Quantile(0.5), 2e-4);
  EXPECT_NEAR(k.Quantile(0.95), 2e-4 * std::exp(0.3 * 1.6448536269514722), 1e-15);
  // The literature default: the 95 % quantile is 1.5x the median.
  EXPECT_NEAR(Lognormal(1.0, kWearCoefficientSigmaLn).Quantile(0.95), 1.5, 1e-12);
  SampleDistribution spread;
  spread.kind = SampleDistributionKind::kNormal;
  spread.a = 1.0;
  spread.b = 1.0;
  spread.lower = 0.0;
  for (const auto& p : UnitSamples(1, 200, SamplingMethod::kLatinHypercube, 5)) {
    EXPECT_GE(spread.Quantile(p[0]), 0.0);
  }
  // Truncated at 0: the median of the remaining mass, mean + z(0.5 + 0.5 Phi(-1)) std.
  const double p0 = gsl_cdf_ugaussian_P(-1.0);
  EXPECT_NEAR(spread.Quantile(0.5), 1.0 + gsl_cdf_ugaussian_Pinv(p0 + 0.5 * (1 - p0)), 1e-12);
}

TEST(EnsembleSampling, BadParametersAreInputErrors) {
  const auto message = [](const SampleDistribution& d) {
    try {
      ValidateSampleDistribution(d, "plan.toml:3: axis 'wear.k' distribution");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(Lognormal(-1.0, 0.2)).find("median -1"), std::string::npos);
  EXPECT_NE(message(Lognormal(1.0, 0.0)).find("sigma_ln 0"), std::string::npos);
  SampleDistribution u;
  u.a = 1.0;
  u.b = 1.0;
  EXPECT_NE(message(u).find("expected min < max"), std::string::npos);
  SampleDistribution far;
  far.kind = SampleDistributionKind::kNormal;
  far.a = 0.0;
  far.b = 1.0;
  far.lower = 50.0;
  EXPECT_NE(message(far).find("leave no probability"), std::string::npos);
  EXPECT_EQ(message(Lognormal(1.0, 0.2)), "");
}

TEST(EnsemblePercentiles, EqualHandComputedOrderStatistics) {
  // Type 7: rank (n - 1) p between order statistics. Sorted {1, 2, 4, 8}: rank 0.15 for 5 %,
  // 1.5 for 50 %, 2.85 for 95 %.
  const std::vector<double> v = {8.0, 1.0, 4.0, 2.0};
  EXPECT_DOUBLE_EQ(Percentile(v, 5.0), 1.0 + 0.15 * (2.0 - 1.0));
  EXPECT_DOUBLE_EQ(Percentile(v, 50.0), 2.0 + 0.5 * (4.0 - 2.0));
  EXPECT_DOUBLE_EQ(Percentile(v, 95.0), 4.0 + 0.85 * (8.0 - 4.0));
  EXPECT_DOUBLE_EQ(Percentile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(Percentile(v, 100.0), 8.0);
  // A run that never reached a limit (+inf) sorts last: the percentiles that need it are +inf.
  const std::vector<double> censored = {3.0, 1.0, INFINITY};
  EXPECT_DOUBLE_EQ(Percentile(censored, 50.0), 3.0);
  EXPECT_EQ(Percentile(censored, 95.0), INFINITY);
  EXPECT_TRUE(std::isnan(Percentile({}, 50.0)));
}

// A one-parameter model whose quantiles are known: W(m) = k m with k log-normal, so the
// p-quantile of W at m is m Q_k(p). The ensemble's k are a Latin hypercube of n samples: its
// sorted values lie one in each stratum of probability 1/n, so the empirical p-quantile lies
// between Q_k(p - 1/n) and Q_k(p + 1/n).
TEST(EnsembleBands, OfALinearModelAreTheKnownQuantilesWithinOneStratum) {
  const SampleDistribution k = Lognormal(0.4, 0.25);  // mm/MGT
  for (const int n : {32, 64}) {
    const auto samples = DrawSamples({k}, n, SamplingMethod::kLatinHypercube, 19);
    std::vector<MeasureSeries> runs;
    for (const auto& s : samples) {
      MeasureSeries r;
      // Steps at uneven MGT (as the step control chooses them), all ending at 3 MGT.
      for (double m : {0.0, 0.37, 0.9, 1.6, 2.2, 3.0}) {
        r.mgt.push_back(m);
        r.value.push_back(s[0] * m);
      }
      runs.push_back(r);
    }
    const std::vector<double> grid = {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
    const std::vector<double> ps = {5.0, 50.0, 95.0};
    const PercentileBands b = ComputePercentileBands(runs, grid, ps);
    for (size_t p = 0; p < ps.size(); ++p) {
      for (size_t j = 1; j < grid.size(); ++j) {
        const double f = ps[p] / 100.0;
        EXPECT_GE(b.value[p][j], grid[j] * k.Quantile(std::max(f - 1.0 / n, 1e-9)) * (1 - 1e-12));
        EXPECT_LE(b.value[p][j], grid[j] * k.Quantile(std::min(f + 1.0 / n, 1 - 1e-9)) * (1 + 1e-12));
        // Monotone in MGT (wear only grows).
        EXPECT_GE(b.value[p][j], b.value[p][j - 1]);
      }
      EXPECT_EQ(b.value[p][0], 0.0);
    }
    for (int r : b.runs) EXPECT_EQ(r, n);
  }
}

TEST(EnsembleBands, AreHandComputedPercentilesOfTheRunsAtTheirStoredSteps) {
  // Three runs stored at the grid's MGT: the bands are the percentiles of the stored values.
  std::vector<MeasureSeries> runs = {{{0.0, 1.0, 2.0}, {0.0, 0.3, 0.5}},
                                     {{0.0, 1.0, 2.0}, {0.0, 0.1, 0.9}},
                                     {{0.0, 1.0, 2.0, 2.5}, {0.0, 0.2, 0.4, 0.6}}};
  const PercentileBands b = ComputePercentileBands(runs, {0.0, 1.0, 2.0, 1.5}, {50.0, 75.0});
  EXPECT_DOUBLE_EQ(b.value[0][1], 0.2);                     // median of {0.1, 0.2, 0.3}
  EXPECT_DOUBLE_EQ(b.value[1][1], 0.2 + 0.5 * (0.3 - 0.2));  // rank 1.5
  EXPECT_DOUBLE_EQ(b.value[0][2], 0.5);                     // {0.4, 0.5, 0.9}
  // Between stored steps: linear. At 1.5 MGT: 0.4, 0.5, 0.3.
  EXPECT_DOUBLE_EQ(b.value[0][3], 0.4);
  // A run that does not reach an MGT is left out of it.
  const PercentileBands beyond = ComputePercentileBands(runs, {2.5}, {50.0});
  EXPECT_EQ(beyond.runs[0], 1);
  EXPECT_DOUBLE_EQ(beyond.value[0][0], 0.6);
}

TEST(EnsembleLife, OnAConstantWearRateIsLimitOverRate) {
  // W = r m, stored at uneven steps: the crossing, linear between the steps around it, is
  // exactly limit / r (up to rounding).
  const double rate = 0.37;  // mm/MGT
  MeasureSeries s;
  for (double m = 0.0; m < 40.0; m += 0.7 + 0.1 * std::sin(m)) {
    s.mgt.push_back(m);
    s.value.push_back(rate * m);
  }
  for (const double limit : {0.5, 2.0, 8.0}) {
    const std::optional<double> at = FirstCrossing(s, limit);
    ASSERT_TRUE(at.has_value());
    EXPECT_NEAR(*at, limit / rate, 1e-12 * limit / rate);
  }
  EXPECT_FALSE(FirstCrossing(s, 100.0).has_value());  // beyond the last step
  EXPECT_EQ(FirstCrossing({{0.0, 1.0}, {0.5, 1.0}}, 0.2), 0.0);  // already there at step 0
}

TEST(EnsembleLife, WeightedQuantileIsTheShareOfTheLength) {
  // Class A (3 km) lives 10 and 20 MGT, class B (1 km) 5 MGT: by 5 MGT 25 % of the length,
  // by 10 MGT 62.5 %, by 20 MGT all of it.
  const std::vector<double> values = {10.0, 20.0, 5.0}, weights = {1.5, 1.5, 1.0};
  EXPECT_EQ(WeightedQuantile(values, weights, 25.0), 5.0);
  EXPECT_EQ(WeightedQuantile(values, weights, 50.0), 10.0);
  EXPECT_EQ(WeightedQuantile(values, weights, 62.5), 10.0);
  EXPECT_EQ(WeightedQuantile(values, weights, 70.0), 20.0);
  EXPECT_EQ(WeightedQuantile({10.0, INFINITY}, {1.0, 1.0}, 90.0), INFINITY);
}

}  // namespace
}  // namespace railwear
