// Uncertainty ensembles and rail-life answers (issue 19 points 4 and 5): samples of uncertain wear
// inputs (a wear coefficient, friction, lateral spread, axle loads), drawn reproducibly from a
// seed; percentile bands of a wear measure against MGT over an ensemble of runs; the traffic
// [MGT] at which a measure first reaches a limit.
//
// Sampling. A plan's distribution axes are the dimensions of one design of `n` points in the unit
// cube, mapped through each dimension's inverse CDF (GSL's gsl_cdf_*_Pinv):
// - Latin hypercube (McKay, Beckman & Conover 1979): each dimension's [0, 1) cut into n equal
//   strata, one point in each, at a uniform position inside it; the strata paired across the
//   dimensions by independent random permutations (gsl_ran_shuffle).
// - Sobol (Bratley & Fox 1988, GSL's gsl_qrng_sobol, at most 40 dimensions), shifted by one
//   uniform random vector modulo 1 (Cranley-Patterson rotation), so the seed matters, the design
//   keeps its low discrepancy and no point sits at 0.
// The random numbers are GSL's MT19937 (gsl_rng_mt19937) seeded with `seed`: the same seed gives
// the same samples bit for bit on any machine (MT19937's sequence is specified; the inverse CDFs
// are GSL's, the same library everywhere this builds).
//
// Percentiles are GSL's gsl_stats_quantile_from_sorted_data: linear interpolation between order
// statistics, the p-quantile of sorted x[0..n-1] at rank (n - 1) p (R's and NumPy's default
// "type 7").
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace railwear {

enum class SampleDistributionKind {
  kUniform,    // a = min, b = max
  kNormal,     // a = mean, b = standard deviation (> 0)
  kLognormal,  // a = median (> 0), b = sigma of ln(x) (> 0)
};

// One uncertain input. `lower` and `upper` truncate the distribution (normal and log-normal):
// a sample's probability u is mapped into [F(lower), F(upper)] before the inverse CDF, so every
// stratum of a Latin hypercube stays inside the bounds.
struct SampleDistribution {
  SampleDistributionKind kind = SampleDistributionKind::kUniform;
  double a = 0.0;
  double b = 1.0;
  double lower = -INFINITY;
  double upper = INFINITY;
  // The value of probability u in (0, 1). InputError for parameters out of range
  // (ValidateSampleDistribution's messages).
  double Quantile(double u) const;
};

// Throws InputError naming `what` (e.g. "plan.toml:12: axis 'wear.k' distribution") when the
// parameters do not define a distribution: min >= max, std or sigma_ln <= 0, median <= 0,
// non-finite values, lower >= upper, or bounds that leave no probability.
void ValidateSampleDistribution(const SampleDistribution& d, const std::string& what);

enum class SamplingMethod { kLatinHypercube, kSobol };

// The most dimensions gsl_qrng_sobol draws.
constexpr int kMaxSobolDimensions = 40;

// `n` points of the unit cube [0, 1)^dims (points[i][d]), reproducible from `seed`. Latin
// hypercube: for every d, the values floor(n u) over the points are 0..n-1, each once. n >= 1,
// dims >= 1 (Sobol: dims <= kMaxSobolDimensions).
std::vector<std::vector<double>> UnitSamples(int dims, int n, SamplingMethod method,
                                             uint64_t seed);

// UnitSamples mapped through each distribution's Quantile: samples[i][d].
std::vector<std::vector<double>> DrawSamples(const std::vector<SampleDistribution>& dims, int n,
                                             SamplingMethod method, uint64_t seed);

// The wear coefficient's scatter, the log-normal default: published Archard / T-gamma
// coefficients scatter by +-40 to 60 % (issue 19); +-50 % as the 5 / 95 % range gives
// sigma of ln k = ln(1.5) / z(0.95) = 0.2465 (z(0.95) = 1.6449, the standard normal's 95 %
// quantile). The median is the scene's own value.
inline const double kWearCoefficientSigmaLn = std::log(1.5) / 1.6448536269514722;

// The p-th percentile (p in [0, 100]) of `values` (type 7, above); NaN for no values. Infinite
// values (a run that never reached a limit) sort last: a percentile that needs one is +inf.
double Percentile(std::vector<double> values, double p);

// y(x) on the polyline (xs, ys), xs non-decreasing; NaN outside [xs.front(), xs.back()] or for
// no points. Where xs repeats, the later point wins.
double InterpolateAt(const std::vector<double>& xs, const std::vector<double>& ys, double x);

// One run's measure against MGT (its stored steps, in order).
struct MeasureSeries {
  std::vector<double> mgt;
  std::vector<double> value;
};

// Percentile bands over an ensemble: value[p][j] = Percentile over the runs of each run's
// measure interpolated at mgt[j] (InterpolateAt), for percentiles[p]. A run that does not reach
// mgt[j] is left out of that point (runs[j] counts the runs in it).
struct PercentileBands {
  std::vector<double> mgt;
  std::vector<double> percentiles;
  std::vector<std::vector<double>> value;  // [percentile][mgt]
  std::vector<int> runs;                   // [mgt]
};
PercentileBands ComputePercentileBands(const std::vector<MeasureSeries>& runs,
                                       const std::vector<double>& mgt,
                                       const std::vector<double>& percentiles);

// The first MGT at which the series reaches `limit` (value >= limit), interpolated linearly
// between the stored steps around it (the first step's MGT when it is already there); nullopt
// when no stored step reaches it. With a constant wear rate r from 0, limit / r exactly (up to
// rounding); otherwise within one step of the crossing.
std::optional<double> FirstCrossing(const MeasureSeries& series, double limit);

// The weighted empirical p-quantile (p in [0, 100]): the smallest value whose cumulative weight
// (values sorted) reaches p / 100 of the total; +inf values sort last. NaN for no values or no
// weight. Used for the line summary: each run weighted by its curve class's length on the line
// divided by the class's runs, so the p-quantile of life is the traffic by which p % of the
// line's curve length has reached the limit.
double WeightedQuantile(const std::vector<double>& values, const std::vector<double>& weights,
                        double p);

}  // namespace railwear
