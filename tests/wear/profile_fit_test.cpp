// Tests of the profile fit: exact built-in profiles are reproduced, measured profiles are fitted
// at the level of their measurement noise without overshoot at the gauge corner (flange root for
// wheels), a single gross outlier barely moves the fit, and the noise estimator recovers known
// noise. Measured figures are printed (ctest -R ProfileFit --verbose) for the README.
#include "wear/profile_fit.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "core/profile/profile_io.h"

namespace railwear {
namespace {

constexpr double kMm = 1e3;

// Distance from q to the profile's own spline, searching near arc length s (Newton on the
// squared distance; the profile curves here have radii >= 5 mm, far above the offsets).
double DistanceToProfile(const Profile& p, const Eigen::Vector2d& q, double s) {
  for (int it = 0; it < 30; ++it) {
    Eigen::Vector2d pos, d1, d2;
    p.Evaluate(s, &pos, &d1, &d2);
    const Eigen::Vector2d diff = pos - q;
    const double next =
        std::clamp(s - d1.dot(diff) / (d1.squaredNorm() + d2.dot(diff)), 0.0, p.Length());
    if (std::abs(next - s) < 1e-14) break;
    s = next;
  }
  return (p.Position(s) - q).norm();
}

// Largest normal distance of the fitted curve (sampled every 0.02 mm) from the reference.
double MaxDeviation(const ProfileFit& fit, const Profile& reference) {
  double worst = 0.0;
  for (double s = fit.spline.t_begin(); s <= fit.spline.t_end(); s += 0.02e-3) {
    const Eigen::VectorXd v = fit.spline.Value(s);
    worst = std::max(worst, DistanceToProfile(reference, v.head<2>(), s));
  }
  return worst;
}

// The requirement for exact profiles: within 0.005 mm of the built-in's own spline.
constexpr double kExactTolerance_m = 0.005e-3;

TEST(ProfileFitTest, BuiltinS1002AndUic60AreReproduced) {
  for (const Profile& builtin : {MakeS1002(), MakeUic60()}) {
    const auto start = std::chrono::steady_clock::now();
    const ProfileFit fit = FitProfile(builtin, ProfileFitOptions());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double deviation = MaxDeviation(fit, builtin);
    std::cout << fmt::format(
        "[figure] {}: {} points, max normal deviation {:.5f} mm (tolerance {:.3f} mm), RMS "
        "distance {:.6f} mm, lambda {:.3g} m^4, {} rejected, {:.1f} ms\n",
        builtin.source(), builtin.size(), deviation * kMm, kExactTolerance_m * kMm,
        fit.rms_distance_m * kMm, fit.lambda_m4, fit.num_rejected, seconds * 1e3);
    EXPECT_LT(deviation, kExactTolerance_m) << builtin.source();
    EXPECT_EQ(fit.num_rejected, 0) << builtin.source();
    EXPECT_EQ(fit.summary.status, SmoothingSplineStatus::kConverged) << fit.summary.message;
    // Resampled every ~0.1 mm along the same arc, same ends.
    EXPECT_NEAR(fit.profile.Length(), builtin.Length(), 1e-3 * builtin.Length());
    EXPECT_LT((fit.profile.points().front() - builtin.points().front()).norm(), kExactTolerance_m);
    EXPECT_LT((fit.profile.points().back() - builtin.points().back()).norm(), kExactTolerance_m);
    EXPECT_NEAR(fit.profile.Length() / (fit.profile.size() - 1), 0.1e-3, 0.01e-3);
    EXPECT_EQ(fit.profile.source(), builtin.source() + " (fitted)");
    // UIC60's sharpest arc is R13 and S1002's is ~R12: curvature magnitudes stay below 1/11 mm.
    EXPECT_LT(std::max(-fit.curvature_min_per_m, fit.curvature_max_per_m), 1.0 / 11e-3);
  }
}

std::string SharedProfile(const std::string& name) {
  return std::string(RAILWEAR_SHARED_DIR) + "/data/profiles/" + name;
}

struct MeasuredCase {
  const char* file;
  bool rail;  // rail: gauge corner on the gauge side (y < 0); wheel: flange root
};
const MeasuredCase kMeasured[] = {{"avg_HR.BAN", true},
                                  {"avg_low2.ban", true},
                                  {"Car7216_0001r.whl", false},
                                  {"avg_wheel.whl", false}};

// Fitted noise and the independent estimate agree within this factor: the two estimators differ
// by ~10 % on synthetic noise (NoiseEstimateRecoversKnownNoise) and MiniProf data are rounded to
// 0.01 mm (rounding error is not white), so 1.5 leaves room without hiding a misfit (an
// under- or over-fit changes the ratio by integer factors).
constexpr double kNoiseRatioTolerance = 1.5;
// Scan glitches the fit may leave out: at most 2 % of the points.
constexpr double kMaxRejectedShare = 0.02;

TEST(ProfileFitTest, MeasuredProfilesFitAtTheirNoiseLevel) {
  if (!std::filesystem::exists(SharedProfile("avg_HR.BAN"))) {
    GTEST_SKIP() << "measured profiles not found under " << RAILWEAR_SHARED_DIR;
  }
  for (const MeasuredCase& c : kMeasured) {
    const ProfileFile file = ReadProfileFile(SharedProfile(c.file));
    const ProfileFit fit = FitProfile(file.profile, ProfileFitOptions());
    const int n = file.profile.size();
    std::cout << fmt::format(
        "[figure] {}: {} points, RMS distance {:.4f} mm ({:.4f} mm without the {} rejected), "
        "max {:.4f} mm at point {}; noise from the points {:.4f} mm, implied by the fit {:.4f} mm "
        "(ratio {:.2f}); {} down-weighted; smoothing length {:.3f} mm (GCV); curvature "
        "{:.3f} .. {:.3f} 1/mm; {:.1f} ms\n",
        c.file, n, fit.rms_distance_m * kMm, fit.rms_inlier_distance_m * kMm, fit.num_rejected,
        fit.max_distance_m * kMm, fit.max_distance_index, fit.noise_estimate_m * kMm,
        fit.fit_noise_m * kMm, fit.fit_noise_m / fit.noise_estimate_m, fit.num_downweighted,
        fit.smoothing_length_m * kMm, fit.curvature_min_per_m / kMm, fit.curvature_max_per_m / kMm,
        fit.summary.time_s * 1e3);
    EXPECT_GT(fit.noise_estimate_m, 0.0) << c.file;
    EXPECT_LT(fit.fit_noise_m, kNoiseRatioTolerance * fit.noise_estimate_m) << c.file;
    EXPECT_GT(fit.fit_noise_m, fit.noise_estimate_m / kNoiseRatioTolerance) << c.file;
    // The residuals themselves are at (not above) the noise level.
    EXPECT_LT(fit.rms_inlier_distance_m, kNoiseRatioTolerance * fit.noise_estimate_m) << c.file;
    EXPECT_LE(fit.num_rejected, kMaxRejectedShare * n) << c.file;
    EXPECT_EQ(fit.summary.status, SmoothingSplineStatus::kConverged) << fit.summary.message;
  }
}

// Arc length of the fit's sharpest corner where overshoot would show: for a rail the largest
// curvature on the gauge side (y < 0); for a wheel the flange root, the largest curvature
// between 3 mm past the flange tip (largest z) and the taping line (y = 0).
double CornerArc(const ProfileFit& fit, bool rail) {
  const double step = 0.02e-3;
  double y_min = -std::numeric_limits<double>::infinity();
  if (!rail) {
    double z_max = -std::numeric_limits<double>::infinity();
    for (double s = fit.spline.t_begin(); s <= fit.spline.t_end(); s += step) {
      const Eigen::VectorXd v = fit.spline.Value(s);
      if (v[1] > z_max) {
        z_max = v[1];
        y_min = v[0] + 3e-3;
      }
    }
  }
  double best = -std::numeric_limits<double>::infinity(), best_s = 0.0;
  for (double s = fit.spline.t_begin(); s <= fit.spline.t_end(); s += step) {
    const Eigen::VectorXd v = fit.spline.Value(s);
    if (v[0] > 0.0 || v[0] < y_min) continue;
    const Eigen::VectorXd d1 = fit.spline.Derivative(s), d2 = fit.spline.SecondDerivative(s);
    const double kappa = (d1[0] * d2[1] - d1[1] * d2[0]) / std::pow(d1.norm(), 3);
    if (kappa > best) {
      best = kappa;
      best_s = s;
    }
  }
  return best_s;
}

// Within 5 mm of arc on either side of the corner, no kept point lies farther than kBand noise
// standard deviations from the fit, and no run of 5 consecutive points lies on one side by more
// than one standard deviation on average: an overshooting (or corner-cutting) spline would put
// a run of points on one side by more than the noise.
constexpr double kCornerHalfWidth_m = 5e-3;
constexpr double kBand = 4.0;     // 4 sigma: ~1 in 16000 for Gaussian noise
constexpr double kRunBias = 1.0;  // mean of 5 points: its own spread is 0.45 sigma
constexpr int kRun = 5;

TEST(ProfileFitTest, NoOvershootAtTheGaugeCornerOrFlangeRoot) {
  if (!std::filesystem::exists(SharedProfile("avg_HR.BAN"))) {
    GTEST_SKIP() << "measured profiles not found under " << RAILWEAR_SHARED_DIR;
  }
  for (const MeasuredCase& c : kMeasured) {
    const ProfileFile file = ReadProfileFile(SharedProfile(c.file));
    const Profile& p = file.profile;
    const ProfileFit fit = FitProfile(p, ProfileFitOptions());
    const double corner = CornerArc(fit, c.rail);
    const double sigma = fit.noise_estimate_m;
    double max_distance = 0.0, max_run = 0.0;
    int count = 0;
    for (int i = 0; i < p.size(); ++i) {
      if (std::abs(p.KnotS(i) - corner) > kCornerHalfWidth_m) continue;
      ++count;
      max_distance = std::max(max_distance, std::abs(fit.distance_m[i]));
      if (i + kRun > p.size()) continue;
      double mean = 0.0;
      for (int j = i; j < i + kRun; ++j) mean += fit.distance_m[j] / kRun;
      max_run = std::max(max_run, std::abs(mean));
    }
    const Eigen::VectorXd at = fit.spline.Value(corner);
    std::cout << fmt::format(
        "[figure] {} corner at y = {:.2f} mm, z = {:.2f} mm: {} points within 5 mm, max distance "
        "{:.4f} mm ({:.2f} sigma), largest 5-point mean {:.4f} mm ({:.2f} sigma)\n",
        c.file, at[0] * kMm, at[1] * kMm, count, max_distance * kMm, max_distance / sigma,
        max_run * kMm, max_run / sigma);
    EXPECT_GE(count, 15) << c.file;  // the window holds data (spacing 0.25-0.5 mm)
    EXPECT_LT(max_distance, kBand * sigma) << c.file;
    EXPECT_LT(max_run, kRunBias * sigma) << c.file;
  }
}

// The S1002 wheel sampled at 500 points (0.31 mm apart) with normal noise of sigma_m (2 um: a
// good MiniProf scan). (At UIC60's 0.26 mm spacing a 1 mm spike would turn the polyline back by
// more than Profile accepts.)
Profile NoisyProfile(unsigned seed, double sigma_m, std::vector<double>* s_points) {
  const Profile rail = MakeS1002();
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_m);
  std::vector<Eigen::Vector2d> points;
  const int n = 500;
  for (int i = 0; i < n; ++i) {
    const double s = rail.Length() * i / (n - 1);
    points.push_back(rail.Position(s) + noise(rng) * rail.LeftNormal(s));
    if (s_points != nullptr) s_points->push_back(s);
  }
  return Profile(points, "noisy S1002");
}

// The issue: a single 1 mm outlier among 500 points moves the fit by less than 0.01 mm.
constexpr double kOutlierShiftTolerance_m = 0.01e-3;

TEST(ProfileFitTest, SingleOutlierBarelyMovesTheFit) {
  const Profile clean = NoisyProfile(17, 2e-6, nullptr);
  const ProfileFit clean_fit = FitProfile(clean, ProfileFitOptions());
  for (int index : {120, 200, 380}) {  // flange, flange root, tread
    std::vector<Eigen::Vector2d> points = clean.points();
    points[index] += 1e-3 * clean.LeftNormal(clean.KnotS(index));
    const Profile bad(points, "noisy S1002 with an outlier");
    const ProfileFit fit = FitProfile(bad, ProfileFitOptions());
    const double shift = MaxDeviation(fit, clean_fit.profile);
    // For contrast: least squares, and the Huber loss without the rejection stage.
    ProfileFitOptions plain;
    plain.spline.loss = RobustLoss::kNone;
    const double plain_shift = MaxDeviation(FitProfile(bad, plain), clean_fit.profile);
    ProfileFitOptions huber_only;
    huber_only.spline.reject_threshold = 0.0;
    const double huber_shift = MaxDeviation(FitProfile(bad, huber_only), clean_fit.profile);
    std::cout << fmt::format(
        "[figure] 1 mm outlier at point {} of 500: the fit moves by at most {:.5f} mm ({} "
        "rejected); least squares {:.3f} mm, Huber loss without rejection {:.4f} mm\n",
        index, shift * kMm, fit.num_rejected, plain_shift * kMm, huber_shift * kMm);
    EXPECT_LT(shift, kOutlierShiftTolerance_m) << index;
    EXPECT_EQ(fit.num_rejected, 1);
    EXPECT_EQ(fit.rejected_points, std::vector<int>{index});
    EXPECT_EQ(fit.max_distance_index, index);
    EXPECT_NEAR(fit.max_distance_m, 1e-3, 0.01e-3);
    EXPECT_GT(plain_shift, 5.0 * kOutlierShiftTolerance_m);  // it matters without a robust fit
  }
}

TEST(ProfileFitTest, GlitchClusterIsRejectedAndBridged) {
  // A scan glitch as MiniProf files show it (Car7216_0001r.whl near the flange tip): ten
  // consecutive points zigzag +0.3 / -0.25 mm about the profile. S1002 at 640 points (0.24 mm
  // apart), exact elsewhere, so GCV all but interpolates and only the suspects from the
  // leave-one-out test let the rejection see the cluster.
  const Profile truth = MakeS1002();
  const int n = 640, length = 10;
  for (int start : {106, 256, 384}) {  // flange, flange root, tread
    std::vector<Eigen::Vector2d> points;
    std::vector<int> glitch;
    for (int i = 0; i < n; ++i) {
      const double s = truth.Length() * i / (n - 1);
      Eigen::Vector2d p = truth.Position(s);
      if (i >= start && i < start + length) {
        p += ((i - start) % 2 ? 0.3e-3 : -0.25e-3) * truth.LeftNormal(s);
        glitch.push_back(i);
      }
      points.push_back(p);
    }
    const ProfileFit fit = FitProfile(Profile(points, "S1002 with a glitch"), ProfileFitOptions());
    EXPECT_EQ(fit.rejected_points, glitch) << start;
    // The 2.4 mm gap is bridged by the spline with the least curvature energy; on S1002 that
    // stays well within the exact-profile tolerance (measured: under 0.001 mm).
    EXPECT_LT(MaxDeviation(fit, truth), kExactTolerance_m) << start;
  }
}

TEST(ProfileFitTest, NoiseEstimateRecoversKnownNoise) {
  for (double sigma : {0.5e-6, 2e-6, 5e-6}) {
    const Profile noisy = NoisyProfile(23, sigma, nullptr);
    // The median of 500 differences has a spread of ~6 %; the chord-offset formula assumes
    // even spacing and straight chords, worth a few per cent more.
    constexpr double kEstimateTolerance = 0.2;
    EXPECT_NEAR(EstimateProfileNoise(noisy) / sigma, 1.0, kEstimateTolerance) << sigma;
  }
  // An exact profile: only the curvature's higher derivatives remain, far below 0.1 um.
  EXPECT_LT(EstimateProfileNoise(MakeUic60()), 0.1e-6);
}

TEST(ProfileFitTest, GivenSmoothingLengthIsUsed) {
  const Profile noisy = NoisyProfile(29, 2e-6, nullptr);
  ProfileFitOptions o;
  o.spline.lambda = std::pow(1e-3, 4);  // 1 mm
  const ProfileFit fit = FitProfile(noisy, o);
  EXPECT_FALSE(fit.summary.lambda_from_gcv);
  EXPECT_NEAR(fit.smoothing_length_m, 1e-3, 1e-12);
  // Heavier smoothing than GCV's choice: larger residuals, smaller curvature extremes.
  const ProfileFit gcv = FitProfile(noisy, ProfileFitOptions());
  EXPECT_LT(gcv.smoothing_length_m, fit.smoothing_length_m);
  EXPECT_GT(fit.rms_distance_m, gcv.rms_distance_m);
}

TEST(ProfileFitTest, BadOptionsThrowWithTheValue) {
  ProfileFitOptions o;
  o.output_spacing_m = -1.0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("output_spacing_m = -1"), std::string::npos);
  try {
    FitProfile(MakeUic60(), o);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), error);
  }
  o = ProfileFitOptions();
  o.spline.robust_threshold = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("robust_threshold = 0"), std::string::npos);
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

// A raw scan of the UIC60 rail every 0.1 mm of arc (some 1500 points, a MiniProf-like density)
// with 2 um of normal noise.
std::vector<Eigen::Vector2d> DenseScan(const Profile& rail, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 2e-6);
  std::vector<Eigen::Vector2d> points;
  const int n = static_cast<int>(rail.Length() / 0.1e-3);
  for (int i = 0; i <= n; ++i) {
    const double s = rail.Length() * i / n;
    points.push_back(rail.Position(s) + noise(rng) * rail.LeftNormal(s));
  }
  return points;
}

TEST(CleanScanTest, OnePointSpikeIsDroppedAndBarelyMovesTheFit) {
  const Profile rail = MakeUic60();
  const std::vector<Eigen::Vector2d> clean = DenseScan(rail, 5);
  const ProfileFit clean_fit = FitProfile(Profile(clean, "clean"), ProfileFitOptions());
  for (const int index : {300, 700, 1100}) {
    std::vector<Eigen::Vector2d> spiked = clean;
    const Profile clean_profile(clean, "clean");
    spiked[index] += 1e-3 * clean_profile.LeftNormal(clean_profile.KnotS(index));
    // The case: the Profile itself refuses such a scan (a 168-degree turn).
    EXPECT_THROW(Profile(spiked, "spiked"), InputError);
    const CleanedScan cleaned = CleanScan(spiked, {}, "spiked");
    ASSERT_EQ(cleaned.dropped.size(), 1u) << index;
    EXPECT_EQ(cleaned.dropped[0].index, index);
    EXPECT_NE(cleaned.dropped[0].reason.find("turned the scan back by 16"), std::string::npos)
        << cleaned.dropped[0].reason;
    EXPECT_EQ(cleaned.profile.size(), static_cast<int>(clean.size()) - 1);
    const ProfileFit fit = FitProfile(cleaned.profile, ProfileFitOptions());
    const double shift = MaxDeviation(fit, clean_fit.profile);
    std::cout << fmt::format(
        "[figure] 1 mm one-point spike at point {} of {} (0.1 mm spacing): dropped, the fit "
        "moves by at most {:.5f} mm\n",
        index + 1, clean.size(), shift * kMm);
    EXPECT_LT(shift, kOutlierShiftTolerance_m) << index;
  }
}

TEST(CleanScanTest, PointOutOfScanOrderIsTheOneDropped) {
  const std::vector<Eigen::Vector2d> clean = DenseScan(MakeUic60(), 6);
  std::vector<Eigen::Vector2d> p = clean;
  const int k = 500;
  // Three points back, between points k-4 and k-3: dropping its predecessor would not help.
  p[k] = p[k - 3] - 0.5 * (p[k - 3] - p[k - 4]);
  const CleanedScan cleaned = CleanScan(p, {}, "scan");
  ASSERT_EQ(cleaned.dropped.size(), 1u);
  EXPECT_EQ(cleaned.dropped[0].index, k);
  EXPECT_EQ(cleaned.kept[k], k + 1);
}

TEST(CleanScanTest, RepeatedPointIsDropped) {
  std::vector<Eigen::Vector2d> p = DenseScan(MakeUic60(), 7);
  p[40] = p[39];
  const CleanedScan cleaned = CleanScan(p, {}, "scan");
  ASSERT_EQ(cleaned.dropped.size(), 1u);
  EXPECT_EQ(cleaned.dropped[0].index, 40);
  EXPECT_NE(cleaned.dropped[0].reason.find("repeats point 40"), std::string::npos);
}

TEST(CleanScanTest, DisorderedScanStaysAnErrorNamingALine) {
  std::vector<Eigen::Vector2d> p = DenseScan(MakeUic60(), 8);
  std::vector<int> lines(p.size());
  for (size_t i = 0; i < p.size(); ++i) lines[i] = static_cast<int>(i) + 2;  // after a header
  // Every 20th pair swapped: some 60 pairs out of order, far beyond max(3, 1 %) of 1324.
  for (size_t i = 100; i + 1 < p.size(); i += 20) std::swap(p[i], p[i + 1]);
  try {
    CleanScan(p, lines, "scan.csv");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("scan.csv: line "), std::string::npos) << m;
    EXPECT_NE(m.find(fmt::format("point(s) dropped as scan glitches (at most {} of {} points)",
                                 MaxScanGlitches(static_cast<int>(p.size())), p.size())),
              std::string::npos)
        << m;
  }
}

}  // namespace
}  // namespace railwear
