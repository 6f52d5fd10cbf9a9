// Profile fit: (y, z)(s) smoothing spline, normal distances, curvature range, noise estimate.
#include "wear/profile_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/numerics/input_error.h"
#include "core/profile/profile_defects.h"

namespace railwear {

bool ProfileFitOptions::IsValid(std::string* error) const {
  if (!spline.IsValid(error)) return false;
  if (!(std::isfinite(output_spacing_m) && output_spacing_m > 0.0)) {
    if (error != nullptr) {
      *error = fmt::format(
          "profile fit options: output_spacing_m = {}: expected a finite number "
          "> 0",
          output_spacing_m);
    }
    return false;
  }
  if (!(std::isfinite(parameter_smoothing_length_m) && parameter_smoothing_length_m > 0.0)) {
    if (error != nullptr) {
      *error = fmt::format(
          "profile fit options: parameter_smoothing_length_m = {}: expected a "
          "finite number > 0",
          parameter_smoothing_length_m);
    }
    return false;
  }
  return true;
}

namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Foot point of p on the curve near parameter s0: Newton on f(s) = |g(s) - p|^2 / 2, kept in
// the curve's range. Returns its parameter.
double FootPoint(const SmoothingSpline& curve, const Eigen::Vector2d& p, double s0) {
  constexpr int kMaxNewton = 20;
  constexpr double kStepTolerance_m = 1e-13;  // far below any profile gauge
  Eigen::VectorXd g, d1, d2;
  double s = s0;
  for (int it = 0; it < kMaxNewton; ++it) {
    curve.Evaluate(s, &g, &d1, &d2);
    const Eigen::Vector2d diff = g.head<2>() - p;
    const double f1 = d1.head<2>().dot(diff);
    const double f2 = d1.head<2>().squaredNorm() + d2.head<2>().dot(diff);
    if (!(f2 > 0.0)) break;
    const double next = std::clamp(s - f1 / f2, curve.t_begin(), curve.t_end());
    const double step = std::abs(next - s);
    s = next;
    if (step < kStepTolerance_m) break;
  }
  return s;
}

// Signed distance of p from the curve along its left normal at the foot point near s0.
double SignedDistance(const SmoothingSpline& curve, const Eigen::Vector2d& p, double s0) {
  const double s = FootPoint(curve, p, s0);
  Eigen::VectorXd g, d1;
  curve.Evaluate(s, &g, &d1, nullptr);
  const Eigen::Vector2d tangent = d1.head<2>().normalized();
  const Eigen::Vector2d normal(-tangent.y(), tangent.x());
  return (p - g.head<2>()).dot(normal);
}

// Distance from p to the segment [a, b].
double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double x = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + x * ab)).norm();
}

// Leave-one-out deviation of interior point i (2 <= i < n - 2): its distance from the
// parametric cubic through its neighbours i-2, i-1, i+1, i+2 (chord-length parameter), between
// i-1 and i+1.
double LeaveOneOutDeviation(const std::vector<Eigen::Vector2d>& p, int i) {
  const Eigen::Vector2d* q[4] = {&p[i - 2], &p[i - 1], &p[i + 1], &p[i + 2]};
  double u[4] = {0.0, 0.0, 0.0, 0.0};
  for (int j = 1; j < 4; ++j) u[j] = u[j - 1] + std::max((*q[j] - *q[j - 1]).norm(), 1e-15);
  auto cubic = [&](double x) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int j = 0; j < 4; ++j) {
      double l = 1.0;
      for (int m = 0; m < 4; ++m) {
        if (m != j) l *= (x - u[m]) / (u[j] - u[m]);
      }
      c += l * *q[j];
    }
    return c;
  };
  constexpr int kSamples = 32;  // chord error of the sampled cubic: (1/32)^2 / 8 of its sag
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d prev = cubic(u[1]);
  for (int m = 1; m <= kSamples; ++m) {
    const Eigen::Vector2d next = cubic(u[1] + (u[2] - u[1]) * m / kSamples);
    best = std::min(best, SegmentDistance(p[i], prev, next));
    prev = next;
  }
  return best;
}

// Noise of a leave-one-out deviation in units of the point noise sigma: the cubic through
// neighbours at -2, -1, +1, +2 spacings predicts the middle with weights (-1/6, 2/3, 2/3, -1/6),
// so the deviation has variance (1 + 2 (1/36 + 4/9)) sigma^2.
const double kLeaveOneOutNoiseFactor = std::sqrt(1.0 + 2.0 * (1.0 / 36.0 + 4.0 / 9.0));

// Arc length along a 2-D spline curve as a function of its parameter: cumulative at the knots
// (5-point Gauss-Legendre per interval, exact to rounding for these smooth speeds) and by the
// same rule inside an interval.
class ArcLength {
 public:
  explicit ArcLength(const SmoothingSpline& curve) : curve_(curve) {
    cumulative_.assign(curve.num_intervals() + 1, 0.0);
    for (int k = 0; k < curve.num_intervals(); ++k) {
      const double a = curve.t_begin() + k * curve.knot_spacing();
      cumulative_[k + 1] = cumulative_[k] + Integral(a, a + curve.knot_spacing());
    }
  }
  double operator()(double t) const {
    const double h = curve_.knot_spacing();
    const int k = std::clamp(static_cast<int>(std::floor((t - curve_.t_begin()) / h)), 0,
                             curve_.num_intervals() - 1);
    const double a = curve_.t_begin() + k * h;
    return cumulative_[k] + Integral(a, t);
  }

 private:
  double Integral(double a, double b) const {
    static constexpr double kX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                     0.5384693101056831, 0.9061798459386640};
    static constexpr double kW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                     0.4786286704993665, 0.2369268850561891};
    double sum = 0.0;
    for (int q = 0; q < 5; ++q) {
      sum += kW[q] * curve_.Derivative(0.5 * (a + b) + 0.5 * (b - a) * kX[q]).head<2>().norm();
    }
    return 0.5 * (b - a) * sum;
  }
  const SmoothingSpline& curve_;
  std::vector<double> cumulative_;
};

// A point's misfit to its neighbours for choosing which point of a defect to drop: the
// leave-one-out deviation inside, the distance from its neighbours' chord next to an end, and
// at an end the distance from the line through the next two points.
double GlitchScore(const std::vector<Eigen::Vector2d>& p, int i) {
  const int n = static_cast<int>(p.size());
  if (i >= 2 && i + 2 < n) return LeaveOneOutDeviation(p, i);
  if (i >= 1 && i + 1 < n) return SegmentDistance(p[i], p[i - 1], p[i + 1]);
  const Eigen::Vector2d& q1 = i == 0 ? p[1] : p[n - 2];
  const Eigen::Vector2d& q2 = i == 0 ? p[2] : p[n - 3];
  const Eigen::Vector2d d = q2 - q1;
  return std::abs(Cross(d, p[i] - q1)) / std::max(d.norm(), 1e-300);
}

// Whether dropping point c leaves no turn-back among the turns it changes and their neighbours.
bool DropClearsTurns(const std::vector<Eigen::Vector2d>& p, int c) {
  const int n = static_cast<int>(p.size());
  std::vector<int> window;
  for (int i = std::max(0, c - 3); i <= std::min(n - 1, c + 3); ++i) {
    if (i != c) window.push_back(i);
  }
  const double cos_max_turn = std::cos(Profile::kMaxTurnAngle_rad);
  for (std::size_t k = 1; k + 1 < window.size(); ++k) {
    const Eigen::Vector2d u = p[window[k]] - p[window[k - 1]];
    const Eigen::Vector2d v = p[window[k + 1]] - p[window[k]];
    if (u.dot(v) < cos_max_turn * u.norm() * v.norm()) return false;
  }
  return true;
}

}  // namespace

int MaxScanGlitches(int n) { return std::max(3, n / 100); }

CleanedScan CleanScan(const std::vector<Eigen::Vector2d>& points_m, const std::vector<int>& lines,
                      const std::string& source) {
  const int n = static_cast<int>(points_m.size());
  const auto name = [&](int raw) {
    return lines.empty() ? fmt::format("point {}", raw + 1) : fmt::format("line {}", lines[raw]);
  };
  const auto at = [&](int raw) {
    return fmt::format("(y = {:.4f}, z = {:.4f} mm)", points_m[raw].x() * 1e3,
                       points_m[raw].y() * 1e3);
  };
  CleanedScan out;
  std::vector<Eigen::Vector2d> p = points_m;
  out.kept.resize(n);
  for (int i = 0; i < n; ++i) out.kept[i] = i;
  while (const auto defect = FindProfileDefect(p)) {
    const int a = defect->a, b = defect->b;
    std::string what;
    std::vector<int> candidates;
    switch (defect->kind) {
      case ProfileDefect::Kind::kDuplicate:
        what = fmt::format("repeats {}", name(out.kept[a]));
        candidates = {b};
        break;
      case ProfileDefect::Kind::kTurnBack:
        what = fmt::format("turned the scan back by {:.1f} degrees at {}",
                           defect->turn_rad * 180.0 / 3.14159265358979323846, name(out.kept[a]));
        candidates = {a - 1, a, a + 1};
        break;
      case ProfileDefect::Kind::kCrossing:
        what = fmt::format("made the scan cross itself (segments from {} and {})",
                           name(out.kept[a]), name(out.kept[b]));
        candidates = {a, a + 1, b, b + 1};
        break;
    }
    if (static_cast<int>(out.dropped.size()) >= MaxScanGlitches(n) ||
        static_cast<int>(p.size()) <= 4) {
      throw InputError(fmt::format(
          "{}: {} {} {}, after {} point(s) dropped as scan glitches (at most {} of {} points); "
          "expected a scan ordered along the profile (a point out of order or a spike one point "
          "wide is dropped, but not this many)",
          source, name(out.kept[b]), at(out.kept[b]), what, out.dropped.size(), MaxScanGlitches(n),
          n));
    }
    int best = -1;
    bool best_clears = false;
    double best_score = -1.0;
    for (const int c : candidates) {
      if (c < 0 || c >= static_cast<int>(p.size())) continue;
      const bool clears =
          defect->kind == ProfileDefect::Kind::kTurnBack ? DropClearsTurns(p, c) : true;
      const double score = GlitchScore(p, c);
      if (best < 0 || (clears && !best_clears) || (clears == best_clears && score > best_score)) {
        best = c;
        best_clears = clears;
        best_score = score;
      }
    }
    out.dropped.push_back({out.kept[best], what});
    p.erase(p.begin() + best);
    out.kept.erase(out.kept.begin() + best);
  }
  out.profile = Profile(std::move(p), source);
  return out;
}

ProfileFit FitProfile(const Profile& raw, const ProfileFitOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  const int n = raw.size();
  const std::vector<Eigen::Vector2d>& points_m = raw.points();
  ProfileFit out;
  out.noise_estimate_m = EstimateProfileNoise(raw);

  // 1. The parameter: arc length along a pilot curve, the spline of the raw points in their
  // own arc length with the long smoothing length parameter_smoothing_length_m and no loss,
  // at each point's foot point on it. For clean points this is their arc length to within the
  // pilot's smoothing; a spike, which lengthens the raw arc length by twice its height and so
  // would be a smooth bump of the parametric curve that no loss could tell from the profile,
  // gets the parameter of where it sits along the profile and becomes a plain outlier.
  Eigen::VectorXd raw_s(n);
  Eigen::MatrixXd yz(n, 2);
  for (int i = 0; i < n; ++i) {
    raw_s[i] = raw.KnotS(i);
    yz.row(i) = points_m[i].transpose();
  }
  SmoothingSplineOptions pilot_options = options.spline;
  pilot_options.lambda = std::pow(options.parameter_smoothing_length_m, 4);
  pilot_options.loss = RobustLoss::kNone;
  const SmoothingSplineFit pilot = FitSmoothingSpline(raw_s, yz, Eigen::VectorXd(), pilot_options);
  const ArcLength pilot_arc(pilot.spline);
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = pilot_arc(FootPoint(pilot.spline, points_m[i], raw_s[i]));

  // 2. Suspects for the spline's rejection stage: points farther from the cubic through their
  // two neighbours on each side than reject_threshold times that distance's noise. The
  // rejection takes back those the fit passes close to (a glitch's clean neighbours).
  std::vector<bool> suspects(n, false);
  if (options.spline.loss != RobustLoss::kNone && options.spline.reject_threshold > 0.0) {
    const double threshold = options.spline.reject_threshold * kLeaveOneOutNoiseFactor *
                             std::max(out.noise_estimate_m, options.spline.min_robust_scale);
    for (int i = 2; i + 2 < n; ++i) suspects[i] = LeaveOneOutDeviation(points_m, i) > threshold;
  }

  // 3. The spline.
  SmoothingSplineFit spline_fit =
      FitSmoothingSpline(s, yz, Eigen::VectorXd(), options.spline, suspects);
  const std::vector<bool>& rejected = spline_fit.rejected;

  out.spline = std::move(spline_fit.spline);
  out.summary = std::move(spline_fit.summary);
  out.num_downweighted = out.summary.num_downweighted;
  out.lambda_m4 = out.summary.lambda;
  out.smoothing_length_m = std::pow(out.lambda_m4, 0.25);

  // Resampled profile and curvature range.
  const double length = out.spline.t_end() - out.spline.t_begin();
  const int intervals = std::max(3, static_cast<int>(std::ceil(length / options.output_spacing_m)));
  std::vector<Eigen::Vector2d> points(intervals + 1);
  out.curvature_min_per_m = std::numeric_limits<double>::infinity();
  out.curvature_max_per_m = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd g, d1, d2;
  for (int k = 0; k <= intervals; ++k) {
    const double sk = out.spline.t_begin() + length * k / intervals;
    out.spline.Evaluate(sk, &g, &d1, &d2);
    points[k] = g.head<2>();
    const double speed = d1.head<2>().norm();
    const double kappa = Cross(d1.head<2>(), d2.head<2>()) / (speed * speed * speed);
    if (kappa < out.curvature_min_per_m) {
      out.curvature_min_per_m = kappa;
      out.curvature_min_at_m = points[k];
    }
    if (kappa > out.curvature_max_per_m) {
      out.curvature_max_per_m = kappa;
      out.curvature_max_at_m = points[k];
    }
  }
  out.profile = Profile(std::move(points), raw.source() + " (fitted)");

  // 4. Normal distances of all raw points.
  out.distance_m.resize(n);
  double ss = 0.0, inlier_ss = 0.0;
  int num_inliers = 0;
  for (int i = 0; i < n; ++i) {
    const double d = SignedDistance(out.spline, points_m[i], s[i]);
    out.distance_m[i] = d;
    ss += d * d;
    if (rejected[i]) {
      out.rejected_points.push_back(i);
    } else {
      inlier_ss += d * d;
      ++num_inliers;
    }
    if (std::abs(d) > out.max_distance_m || out.max_distance_index < 0) {
      out.max_distance_m = std::abs(d);
      out.max_distance_index = i;
    }
  }
  out.num_rejected = static_cast<int>(out.rejected_points.size());
  out.rms_distance_m = std::sqrt(ss / n);
  out.rms_inlier_distance_m = std::sqrt(inlier_ss / std::max(1, num_inliers));
  out.fit_noise_m = std::sqrt(inlier_ss / std::max(1.0, num_inliers - out.summary.effective_dof));
  return out;
}

double EstimateProfileNoise(const Profile& profile) {
  const std::vector<Eigen::Vector2d>& p = profile.points();
  const int n = static_cast<int>(p.size());
  if (n < 5) return 0.0;
  std::vector<double> e(n, 0.0);  // chord offsets, e[0] and e[n-1] unused
  for (int i = 1; i + 1 < n; ++i) {
    const Eigen::Vector2d chord = p[i + 1] - p[i - 1];
    e[i] = Cross(chord, p[i] - p[i - 1]) / chord.norm();
  }
  std::vector<double> d;
  d.reserve(n);
  for (int i = 2; i + 2 < n; ++i) d.push_back(std::abs(e[i + 1] - 2.0 * e[i] + e[i - 1]));
  const std::size_t mid = d.size() / 2;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(mid), d.end());
  // e[i+1] - 2 e[i] + e[i-1] = -eps[i-2]/2 + 2 eps[i-1] - 3 eps[i] + 2 eps[i+1] - eps[i+2]/2
  // for white normal noise eps on evenly spaced points: variance 17.5 sigma^2.
  constexpr double kVarianceFactor = 17.5;
  constexpr double kMadToSigma = 1.482602218505602;  // Gaussian consistency of the MAD
  return kMadToSigma * d[mid] / std::sqrt(kVarianceFactor);
}

}  // namespace railwear
