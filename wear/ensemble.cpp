// Ensemble sampling (GSL's MT19937, shuffles, Sobol sequence and normal quantiles), percentile
// bands (GSL's sorted-data quantile) and first crossings of a limit.
#include "wear/ensemble.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_qrng.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cfloat>
#include <memory>
#include <numeric>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

struct RngFree {
  void operator()(gsl_rng* r) const { gsl_rng_free(r); }
};
struct QrngFree {
  void operator()(gsl_qrng* q) const { gsl_qrng_free(q); }
};

std::unique_ptr<gsl_rng, RngFree> SeededRng(uint64_t seed) {
  std::unique_ptr<gsl_rng, RngFree> rng(gsl_rng_alloc(gsl_rng_mt19937));
  // MT19937 takes 32 bits of seed; fold the upper half in so distinct 64-bit seeds stay distinct
  // in practice. (gsl_rng_set maps seed 0 to its default 4357.)
  gsl_rng_set(rng.get(), static_cast<unsigned long>((seed ^ (seed >> 32)) & 0xffffffffull));
  return rng;
}

// The standard normal's probability of `z` (+-inf allowed).
double Phi(double z) {
  if (z == -INFINITY) return 0.0;
  if (z == INFINITY) return 1.0;
  return gsl_cdf_ugaussian_P(z);
}

// The standardised bounds of a normal or log-normal distribution.
double StandardLower(const SampleDistribution& d) {
  if (d.kind == SampleDistributionKind::kNormal) return (d.lower - d.a) / d.b;
  return d.lower <= 0.0 ? -INFINITY : std::log(d.lower / d.a) / d.b;
}
double StandardUpper(const SampleDistribution& d) {
  if (d.kind == SampleDistributionKind::kNormal) return (d.upper - d.a) / d.b;
  return d.upper <= 0.0 ? -INFINITY : std::log(d.upper / d.a) / d.b;
}

}  // namespace

void ValidateSampleDistribution(const SampleDistribution& d, const std::string& what) {
  if (!std::isfinite(d.a) || !std::isfinite(d.b)) {
    throw InputError(fmt::format("{}: parameters {} and {}: expected finite numbers", what, d.a, d.b));
  }
  switch (d.kind) {
    case SampleDistributionKind::kUniform:
      if (!(d.a < d.b)) {
        throw InputError(fmt::format("{}: min {} and max {}: expected min < max", what, d.a, d.b));
      }
      return;
    case SampleDistributionKind::kNormal:
      if (!(d.b > 0.0)) {
        throw InputError(fmt::format("{}: std {}: expected a number > 0", what, d.b));
      }
      break;
    case SampleDistributionKind::kLognormal:
      if (!(d.a > 0.0)) {
        throw InputError(fmt::format("{}: median {}: expected a number > 0", what, d.a));
      }
      if (!(d.b > 0.0)) {
        throw InputError(fmt::format("{}: sigma_ln {}: expected a number > 0", what, d.b));
      }
      break;
  }
  if (!(d.lower < d.upper)) {
    throw InputError(
        fmt::format("{}: min {} and max {}: expected min < max", what, d.lower, d.upper));
  }
  if (!(Phi(StandardUpper(d)) - Phi(StandardLower(d)) > 1e-12)) {
    throw InputError(fmt::format(
        "{}: min {} and max {} leave no probability (beyond 7 standard deviations); expected "
        "bounds around the distribution's centre",
        what, d.lower, d.upper));
  }
}

double SampleDistribution::Quantile(double u) const {
  // u strictly inside (0, 1): the quantile of 0 or 1 is infinite.
  u = std::clamp(u, DBL_MIN, 1.0 - DBL_EPSILON / 2);
  if (kind == SampleDistributionKind::kUniform) return a + u * (b - a);
  const double p_lo = Phi(StandardLower(*this)), p_hi = Phi(StandardUpper(*this));
  const double p = std::clamp(p_lo + u * (p_hi - p_lo), DBL_MIN, 1.0 - DBL_EPSILON / 2);
  const double z = gsl_cdf_ugaussian_Pinv(p);
  const double x = kind == SampleDistributionKind::kNormal ? a + b * z : a * std::exp(b * z);
  return std::clamp(x, lower, upper);  // rounding at a bound stays inside it
}

std::vector<std::vector<double>> UnitSamples(int dims, int n, SamplingMethod method,
                                             uint64_t seed) {
  std::vector<std::vector<double>> points(static_cast<size_t>(std::max(n, 0)),
                                          std::vector<double>(static_cast<size_t>(dims)));
  if (n < 1 || dims < 1) return points;
  const auto rng = SeededRng(seed);
  if (method == SamplingMethod::kLatinHypercube) {
    std::vector<int> strata(static_cast<size_t>(n));
    for (int d = 0; d < dims; ++d) {
      std::iota(strata.begin(), strata.end(), 0);
      gsl_ran_shuffle(rng.get(), strata.data(), strata.size(), sizeof(int));
      for (int i = 0; i < n; ++i) {
        // gsl_rng_uniform_pos is in (0, 1): the point strictly inside its stratum.
        points[i][d] = (strata[i] + gsl_rng_uniform_pos(rng.get())) / n;
      }
    }
    return points;
  }
  if (dims > kMaxSobolDimensions) {
    throw InputError(fmt::format("sampling \"sobol\" with {} distribution axes: expected at most {}",
                                 dims, kMaxSobolDimensions));
  }
  std::vector<double> shift(static_cast<size_t>(dims));
  for (double& s : shift) s = gsl_rng_uniform_pos(rng.get());
  std::unique_ptr<gsl_qrng, QrngFree> sobol(
      gsl_qrng_alloc(gsl_qrng_sobol, static_cast<unsigned>(dims)));
  for (int i = 0; i < n; ++i) {
    gsl_qrng_get(sobol.get(), points[i].data());
    for (int d = 0; d < dims; ++d) {
      const double v = points[i][d] + shift[d];
      points[i][d] = v >= 1.0 ? v - 1.0 : v;
    }
  }
  return points;
}

std::vector<std::vector<double>> DrawSamples(const std::vector<SampleDistribution>& dims, int n,
                                             SamplingMethod method, uint64_t seed) {
  std::vector<std::vector<double>> points =
      UnitSamples(static_cast<int>(dims.size()), n, method, seed);
  for (auto& point : points) {
    for (size_t d = 0; d < dims.size(); ++d) point[d] = dims[d].Quantile(point[d]);
  }
  return points;
}

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double f = std::clamp(p / 100.0, 0.0, 1.0);
  // The two order statistics the quantile interpolates between: +inf when one of them is.
  const double h = (values.size() - 1) * f;
  if (!std::isfinite(values[static_cast<size_t>(std::ceil(h))])) return INFINITY;
  // On an order statistic: itself (GSL would weigh the next one by 0, and 0 x inf is NaN).
  if (h == std::floor(h)) return values[static_cast<size_t>(h)];
  return gsl_stats_quantile_from_sorted_data(values.data(), 1, values.size(), f);
}

double InterpolateAt(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (xs.empty() || x < xs.front() || x > xs.back()) return std::nan("");
  // The last point at or before x; where xs repeats, the later point wins.
  const size_t hi = static_cast<size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  const size_t i = hi - 1;
  if (xs[i] == x || i + 1 == xs.size()) return ys[i];
  const double t = (x - xs[i]) / (xs[i + 1] - xs[i]);
  return ys[i] + t * (ys[i + 1] - ys[i]);
}

PercentileBands ComputePercentileBands(const std::vector<MeasureSeries>& runs,
                                       const std::vector<double>& mgt,
                                       const std::vector<double>& percentiles) {
  PercentileBands bands;
  bands.mgt = mgt;
  bands.percentiles = percentiles;
  bands.value.assign(percentiles.size(), std::vector<double>(mgt.size(), std::nan("")));
  bands.runs.assign(mgt.size(), 0);
  for (size_t j = 0; j < mgt.size(); ++j) {
    std::vector<double> at;
    for (const MeasureSeries& r : runs) {
      const double v = InterpolateAt(r.mgt, r.value, mgt[j]);
      if (std::isfinite(v)) at.push_back(v);
    }
    bands.runs[j] = static_cast<int>(at.size());
    for (size_t p = 0; p < percentiles.size(); ++p) bands.value[p][j] = Percentile(at, percentiles[p]);
  }
  return bands;
}

std::optional<double> FirstCrossing(const MeasureSeries& s, double limit) {
  for (size_t k = 0; k < s.value.size(); ++k) {
    if (!(s.value[k] >= limit)) continue;
    if (k == 0) return s.mgt[0];
    const double v0 = s.value[k - 1], v1 = s.value[k];
    if (!std::isfinite(v0)) return s.mgt[k];
    const double t = (limit - v0) / (v1 - v0);
    return s.mgt[k - 1] + t * (s.mgt[k] - s.mgt[k - 1]);
  }
  return std::nullopt;
}

double WeightedQuantile(const std::vector<double>& values, const std::vector<double>& weights,
                        double p) {
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return values[a] < values[b]; });
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  if (values.empty() || !(total > 0.0)) return std::nan("");
  const double target = std::clamp(p / 100.0, 0.0, 1.0) * total;
  double sum = 0.0;
  for (const size_t i : order) {
    sum += weights[i];
    // A relative tolerance: the weights' sum may round just below the target it equals.
    if (sum >= target * (1.0 - 1e-12) && weights[i] > 0.0) return values[i];
  }
  return values[order.back()];
}

}  // namespace railwear
