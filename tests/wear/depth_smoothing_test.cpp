// Tests of the wear-depth smoothing: worn area kept, wear peak not moved, bin-scale noise
// removed, depth >= 0 where the plain smoothing spline would undershoot, zeros outside the
// support, symmetry, 200 repeated applications without growing oscillation, and the time per
// call on a 1500-bin field (printed: ctest -R DepthSmoothing --verbose).
#include "wear/depth_smoothing.h"

#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

constexpr double kBin_m = 0.1e-3;  // 0.1 mm bins
constexpr int kBins = 1500;        // 150 mm of rail profile
// The issue: the worn area is kept within 0.5 % by the fit itself (before the rescale).
constexpr double kAreaTolerance = 5e-3;

double Area(const std::vector<double>& d) {
  double a = 0.0;
  for (double x : d) a += x * kBin_m;
  return a;
}

int ArgMax(const std::vector<double>& d) {
  return static_cast<int>(std::max_element(d.begin(), d.end()) - d.begin());
}

// Largest bin-scale wiggle: |d_i - (d_{i-1} + d_{i+1}) / 2|.
double BinScaleWiggle(const std::vector<double>& d) {
  double w = 0.0;
  for (std::size_t i = 1; i + 1 < d.size(); ++i) {
    w = std::max(w, std::abs(d[i] - 0.5 * (d[i - 1] + d[i + 1])));
  }
  return w;
}

// A Gaussian wear band of peak `peak_m` and standard deviation `width_m` centred at `centre_m`
// (not on a bin), times (1 + saw) with a bin-scale sawtooth of relative amplitude `saw`
// (period 3 bins: 1, -0.5, -0.5), so depth stays >= 0.
std::vector<double> PeakWithSawtooth(double centre_m, double width_m, double peak_m, double saw) {
  std::vector<double> d(kBins, 0.0);
  for (int i = 0; i < kBins; ++i) {
    const double x = (i * kBin_m - centre_m) / width_m;
    if (std::abs(x) > 6.0) continue;  // compact support, as a wear increment has
    const double sawtooth = (i % 3 == 0) ? 1.0 : -0.5;
    d[i] = peak_m * std::exp(-0.5 * x * x) * (1.0 + saw * sawtooth);
  }
  return d;
}

TEST(DepthSmoothingTest, KeepsAreaAndPeakAndLosesTheSawtooth) {
  const double centre_m = 70.04e-3, width_m = 2e-3, peak_m = 10e-6;
  const std::vector<double> raw = PeakWithSawtooth(centre_m, width_m, peak_m, 0.3);
  const DepthSmoothingOptions options;
  const DepthSmoothing out = SmoothDepthField(raw, kBin_m, options);
  ASSERT_EQ(out.depth_m.size(), raw.size());
  EXPECT_EQ(out.status, SmoothingSplineStatus::kConverged) << out.message;
  EXPECT_LT(std::abs(out.area_error), kAreaTolerance);
  // After the documented rescale the area is exact to rounding.
  EXPECT_NEAR(Area(out.depth_m) / Area(raw), 1.0, 1e-12);
  // The peak stays within one bin of the band's centre (bin 700.4).
  EXPECT_LE(std::abs(ArgMax(out.depth_m) - centre_m / kBin_m), 1.0);
  // The sawtooth (period 0.3 mm, damped ~(0.3 / 6.3)^4 ~ 5e-6 by the filter) is gone: the
  // bin-scale wiggle drops from ~40 % of the peak to that of the smooth band itself
  // (h^2 / (2 width^2) = 0.1 %).
  const double smooth_wiggle = 0.5 * peak_m * (kBin_m / width_m) * (kBin_m / width_m);
  EXPECT_GT(BinScaleWiggle(raw), 0.3 * peak_m);
  EXPECT_LT(BinScaleWiggle(out.depth_m), 1.5 * smooth_wiggle);
  // The band's height drops as the transfer function 1 / (1 + (omega l)^4) predicts for a
  // Gaussian: the integral of exp(-(omega width)^2 / 2) / (1 + (omega l)^4) over that of the
  // Gaussian spectrum (0.909 for width = 2 l).
  const double l = options.smoothing_length_m;
  double num = 0.0, den = 0.0;
  for (double x = -10.0; x < 10.0; x += 1e-4) {  // x = omega l, midpoint rule
    const double g = std::exp(-0.5 * std::pow(x * width_m / l, 2));
    num += g / (1.0 + std::pow(x, 4));
    den += g;
  }
  // Bins (0.1 mm) and knots (0.5 mm) change the continuous transfer by well under 1 %.
  constexpr double kHeightTolerance = 0.01;
  EXPECT_NEAR(out.depth_m[ArgMax(out.depth_m)] / peak_m, num / den, kHeightTolerance);
  EXPECT_DOUBLE_EQ(out.lambda, std::pow(options.smoothing_length_m, 4));
  for (double d : out.depth_m) ASSERT_GE(d, 0.0);
}

TEST(DepthSmoothingTest, StaysNonNegativeWhereThePlainSplineUndershoots) {
  // A peak narrower than the smoothing length: the plain smoothing spline's kernel has negative
  // side lobes, so unconstrained it goes below zero beside the peak.
  std::vector<double> raw(kBins, 0.0);
  for (int i = 745; i <= 755; ++i) raw[i] = 20e-6 * (1.0 - std::abs(i - 750) / 6.0);
  SmoothingSplineOptions plain;
  plain.lambda = 1e-12;  // l = 1 mm, as the default
  plain.loss = RobustLoss::kNone;
  plain.knot_spacing = 0.5e-3;
  Eigen::VectorXd t(kBins), w = Eigen::VectorXd::Constant(kBins, kBin_m);
  Eigen::MatrixXd v(kBins, 1);
  for (int i = 0; i < kBins; ++i) {
    t[i] = i * kBin_m;
    v(i, 0) = raw[i];
  }
  const SmoothingSplineFit unconstrained = FitSmoothingSpline(t, v, w, plain);
  double lowest = 0.0;
  for (int i = 0; i < kBins; ++i) lowest = std::min(lowest, unconstrained.spline.Value(t[i])[0]);
  EXPECT_LT(lowest, -1e-3 * 20e-6) << "the constraint would not be tested";

  const DepthSmoothing out = SmoothDepthField(raw, kBin_m, DepthSmoothingOptions());
  for (double d : out.depth_m) ASSERT_GE(d, 0.0);
  EXPECT_LT(std::abs(out.area_error), kAreaTolerance);
  EXPECT_EQ(ArgMax(out.depth_m), 750);
  std::cout << fmt::format(
      "[figure] narrow peak: plain spline undershoots to {:.2f} % of the peak; constrained "
      "minimum {:.3g}, area error before the rescale {:.2e}\n",
      100.0 * lowest / 20e-6, *std::min_element(out.depth_m.begin(), out.depth_m.end()),
      out.area_error);
}

TEST(DepthSmoothingTest, ZerosFarFromTheSupportStayZeroAndPatchesStaySeparate) {
  std::vector<double> raw(kBins, 0.0);
  for (int i = 300; i < 400; ++i) raw[i] = 5e-6;    // tread band
  for (int i = 1000; i < 1100; ++i) raw[i] = 8e-6;  // gauge-corner band
  const DepthSmoothingOptions options;
  const DepthSmoothing out = SmoothDepthField(raw, kBin_m, options);
  EXPECT_EQ(out.num_windows, 2);
  const int margin =
      static_cast<int>(std::ceil(options.margin_lengths * options.smoothing_length_m / kBin_m));
  for (int i = 0; i < kBins; ++i) {
    const bool near =
        (i >= 300 - margin && i < 400 + margin) || (i >= 1000 - margin && i < 1100 + margin);
    if (!near) {
      ASSERT_EQ(out.depth_m[i], 0.0) << i;
    }
  }
  // Each band keeps its own area: no wear moves from one patch to the other.
  double a1 = 0.0, a2 = 0.0;
  for (int i = 0; i < kBins; ++i) {
    if (i < 700) {
      a1 += out.depth_m[i] * kBin_m;
    } else {
      a2 += out.depth_m[i] * kBin_m;
    }
  }
  EXPECT_NEAR(a1 / (100 * 5e-6 * kBin_m), 1.0, kAreaTolerance);
  EXPECT_NEAR(a2 / (100 * 8e-6 * kBin_m), 1.0, kAreaTolerance);
}

TEST(DepthSmoothingTest, MirroredFieldGivesMirroredResult) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> raw = PeakWithSawtooth(60e-3, 3e-3, 4e-6, 0.0);
  for (double& d : raw) d *= 1.0 + 0.5 * u(rng);
  std::vector<double> mirrored(raw.rbegin(), raw.rend());
  const DepthSmoothing a = SmoothDepthField(raw, kBin_m, DepthSmoothingOptions());
  const DepthSmoothing b = SmoothDepthField(mirrored, kBin_m, DepthSmoothingOptions());
  // Both solve the same (mirrored) problem; Ceres' stopping point may differ by its relative
  // tolerances only.
  constexpr double kSymmetryTolerance = 1e-6;
  double worst = 0.0;
  for (int i = 0; i < kBins; ++i) {
    worst = std::max(worst, std::abs(a.depth_m[i] - b.depth_m[kBins - 1 - i]));
  }
  EXPECT_LT(worst, kSymmetryTolerance * 4e-6);
}

// A long wear run: each step adds a new increment (a wear band whose position wanders with the
// traffic, plus bin-scale noise), then smooths the accumulated field.
TEST(DepthSmoothingTest, TwoHundredApplicationsGrowNoOscillation) {
  std::mt19937 rng(7);
  std::normal_distribution<double> shift(0.0, 1.5e-3);
  std::uniform_real_distribution<double> noise(0.0, 1.0);
  std::vector<double> field(kBins, 0.0);
  double added_area = 0.0, seconds = 0.0, worst_area_error = 0.0, worst_wiggle_ratio = 0.0;
  int max_fitted = 0, iterations = 0;
  const DepthSmoothingOptions options;
  constexpr int kSteps = 200;
  for (int step = 0; step < kSteps; ++step) {
    const std::vector<double> band = PeakWithSawtooth(75e-3 + shift(rng), 2.5e-3, 1e-6, 0.0);
    for (int i = 0; i < kBins; ++i) {
      const double inc = band[i] * (0.7 + 0.6 * noise(rng));
      field[i] += inc;
      added_area += inc * kBin_m;
    }
    const auto start = std::chrono::steady_clock::now();
    const DepthSmoothing out = SmoothDepthField(field, kBin_m, options);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(out.status, SmoothingSplineStatus::kConverged) << step << ": " << out.message;
    worst_area_error = std::max(worst_area_error, std::abs(out.area_error));
    max_fitted = std::max(max_fitted, out.num_fitted_bins);
    iterations += out.num_ceres_iterations;
    field = out.depth_m;
    worst_wiggle_ratio = std::max(
        worst_wiggle_ratio, BinScaleWiggle(field) / *std::max_element(field.begin(), field.end()));
  }
  const double max_depth = *std::max_element(field.begin(), field.end());
  // Total variation of a single hump is twice its height; oscillations would add to it.
  double total_variation = 0.0;
  int local_maxima = 0;
  for (int i = 1; i < kBins; ++i) total_variation += std::abs(field[i] - field[i - 1]);
  for (int i = 1; i + 1 < kBins; ++i) {
    if (field[i] > field[i - 1] && field[i] >= field[i + 1] && field[i] > 1e-3 * max_depth) {
      ++local_maxima;
    }
  }
  std::cout << fmt::format(
      "[figure] 200 smoothing steps on {} bins of {:.1f} mm: {:.2f} ms per call ({:.1f} Ceres "
      "iterations per call, at most {} bins fitted); worst area error before rescale {:.1e}; "
      "final field: {} local maxima, total variation {:.3f} x twice the peak, largest bin-scale "
      "wiggle {:.2e} of the peak\n",
      kBins, kBin_m * 1e3, 1e3 * seconds / kSteps, static_cast<double>(iterations) / kSteps,
      max_fitted, worst_area_error, local_maxima, total_variation / (2.0 * max_depth),
      worst_wiggle_ratio);
  EXPECT_NEAR(Area(field) / added_area, 1.0, 1e-9);  // rescaled every step
  EXPECT_LT(worst_area_error, kAreaTolerance);
  for (double d : field) ASSERT_GE(d, 0.0);
  EXPECT_EQ(local_maxima, 1);
  // 1 % above a single hump's total variation: room for rounding, none for an oscillation.
  EXPECT_LT(total_variation, 1.01 * 2.0 * max_depth);
  // The bin-scale noise of the increments never survives a step: the wiggle stays at the level
  // of a smooth band (h^2 / (2 width^2) ~ 1e-3 of the peak).
  EXPECT_LT(worst_wiggle_ratio, 2e-3);
  // Only the support plus margins is fitted (~30 mm here), not the 150 mm field.
  EXPECT_LT(max_fitted, kBins / 2);
}

TEST(DepthSmoothingTest, SupportsFrom10MmToTheWholeField) {
  // Cosine bands of 10 to 150 mm with 30 % bin-scale noise (fixed seed); the time per call grows
  // with the fitted window (the area residual couples all its coefficients).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double width_mm : {10.0, 30.0, 80.0, 150.0}) {
    std::vector<double> raw(kBins, 0.0);
    for (int i = 0; i < kBins; ++i) {
      const double x_mm = i * 0.1 - 75.0;
      if (std::abs(x_mm) < width_mm / 2) {
        raw[i] = 1e-6 * (1.0 + 0.3 * u(rng)) * std::cos(M_PI * x_mm / width_mm);
      }
    }
    constexpr int kRepeats = 5;
    DepthSmoothing out;
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < kRepeats; ++r) out = SmoothDepthField(raw, kBin_m, DepthSmoothingOptions());
    const double ms =
        1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
        kRepeats;
    std::cout << fmt::format(
        "[figure] support {:.0f} mm: {:.2f} ms per call, {} bins fitted, area error before the "
        "rescale {:.1e}\n",
        width_mm, ms, out.num_fitted_bins, out.area_error);
    EXPECT_EQ(out.status, SmoothingSplineStatus::kConverged) << out.message;
    EXPECT_LT(std::abs(out.area_error), kAreaTolerance) << width_mm;
    for (double d : out.depth_m) ASSERT_GE(d, 0.0);
    EXPECT_LT(BinScaleWiggle(out.depth_m), 1e-3 * 1e-6) << width_mm;
  }
}

TEST(DepthSmoothingTest, TrivialFieldsPassThrough) {
  const DepthSmoothing zero = SmoothDepthField(std::vector<double>(100, 0.0), kBin_m, {});
  EXPECT_EQ(zero.depth_m, std::vector<double>(100, 0.0));
  EXPECT_EQ(zero.area_error, 0.0);
  EXPECT_EQ(zero.num_windows, 0);
  const std::vector<double> tiny = {1e-6, 2e-6, 1e-6};
  EXPECT_EQ(SmoothDepthField(tiny, kBin_m, {}).depth_m, tiny);
  EXPECT_TRUE(SmoothDepthField({}, kBin_m, {}).depth_m.empty());
}

std::string ThrownMessage(const std::vector<double>& d, double h, const DepthSmoothingOptions& o) {
  try {
    SmoothDepthField(d, h, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(DepthSmoothingTest, BadInputNamesTheValue) {
  std::vector<double> d(20, 1e-6);
  d[5] = -1e-6;
  EXPECT_NE(ThrownMessage(d, kBin_m, {}).find("depth_m[5] = -1e-06: expected a finite depth >= 0"),
            std::string::npos)
      << ThrownMessage(d, kBin_m, {});
  d[5] = 1e-6;
  EXPECT_NE(ThrownMessage(d, 0.0, {}).find("h_m = 0: expected a finite number > 0"),
            std::string::npos);
  DepthSmoothingOptions o;
  o.smoothing_length_m = -1.0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("smoothing_length_m = -1"), std::string::npos);
  EXPECT_EQ(ThrownMessage(d, kBin_m, o), error);
  o = DepthSmoothingOptions();
  o.support_threshold = 1.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("support_threshold = 1: expected a number in [0, 1)"), std::string::npos);
  EXPECT_TRUE(DepthSmoothingOptions().IsValid(&error));
}

}  // namespace
}  // namespace railwear
