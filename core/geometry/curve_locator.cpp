// Closest-point and line-crossing queries on a profile spline (coarse scan + safeguarded Newton).
#include "core/geometry/curve_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/numerics/check.h"

namespace railwear {

CurveLocator::CurveLocator(const Profile& profile, bool material_toward_plus_z,
                           double sample_step_m)
    : profile_(&profile), length_(profile.Length()) {
  RAILWEAR_CHECK(sample_step_m > 0 && length_ > 0);
  const int n = std::max(2, static_cast<int>(std::ceil(length_ / sample_step_m)) + 1);
  step_ = length_ / (n - 1);
  sample_s_.resize(n);
  sample_p_.resize(n);
  for (int i = 0; i < n; ++i) {
    sample_s_[i] = i * step_;
    sample_p_[i] = profile.Position(sample_s_[i]);
  }
  // Orientation: at the surface point facing away from the material (the top of a rail, the
  // bottom of a wheel), the outward normal points to -z for a rail and to +z for a wheel.
  int extreme = 0;
  for (int i = 1; i < n; ++i) {
    const bool better = material_toward_plus_z ? sample_p_[i].y() < sample_p_[extreme].y()
                                               : sample_p_[i].y() > sample_p_[extreme].y();
    if (better) extreme = i;
  }
  const double nz = profile.LeftNormal(sample_s_[extreme]).y();
  const bool left_points_up = nz < 0.0;
  outward_sign_ = (material_toward_plus_z == left_points_up) ? 1.0 : -1.0;
}

Eigen::Vector2d CurveLocator::OutwardNormal(double s) const {
  return outward_sign_ * profile_->LeftNormal(s);
}

double CurveLocator::RefineClosest(const Eigen::Vector2d& q, double s0, double lo,
                                   double hi) const {
  // Minimise |C(s) - q|^2: root of g(s) = (C - q) . C', g' = |C'|^2 + (C - q) . C''.
  lo = std::max(lo, 0.0);
  hi = std::min(hi, length_);
  double s = std::clamp(s0, lo, hi);
  for (int it = 0; it < 50; ++it) {
    Eigen::Vector2d c, d1, d2;
    profile_->Evaluate(s, &c, &d1, &d2);
    const Eigen::Vector2d r = c - q;
    const double g = r.dot(d1);
    if (g == 0.0) break;  // exactly at the closest point (common on straight pieces)
    const double gp = d1.squaredNorm() + r.dot(d2);
    // Converged when the Newton step is below tolerance — tested before the bracket, because a
    // step below one ulp leaves s on the bracket end just set and would fall back to bisection.
    if (gp > 0 && std::abs(g / gp) < kParameterTolerance_m) break;
    if (g > 0)
      hi = s;
    else
      lo = s;
    double next = (gp > 0) ? s - g / gp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - s);
    s = next;
    if (step < kParameterTolerance_m || hi - lo < kParameterTolerance_m) break;
  }
  return s;
}

CurveLocator::Projection CurveLocator::Project(const Eigen::Vector2d& q, double s_lo,
                                               double s_hi) const {
  s_lo = std::max(0.0, s_lo);
  s_hi = std::min(length_, s_hi);
  const int n = static_cast<int>(sample_s_.size());
  int i0 = std::clamp(static_cast<int>(std::floor(s_lo / step_)), 0, n - 1);
  int i1 = std::clamp(static_cast<int>(std::ceil(s_hi / step_)), 0, n - 1);
  int best = i0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int i = i0; i <= i1; ++i) {
    const double d2 = (sample_p_[i] - q).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  const double s = RefineClosest(q, sample_s_[best], std::max(s_lo, sample_s_[best] - step_),
                                 std::min(s_hi, sample_s_[best] + step_));
  Projection p;
  p.s = s;
  p.point = profile_->Position(s);
  const double dist = (q - p.point).norm();
  p.signed_distance = (q - p.point).dot(OutwardNormal(s)) >= 0 ? dist : -dist;
  return p;
}

std::optional<CurveLocator::Crossing> CurveLocator::IntersectLine(const Eigen::Vector2d& b,
                                                                  const Eigen::Vector2d& n,
                                                                  double s_lo, double s_hi) const {
  // Points of the line satisfy (C - b) . t = 0 with t perpendicular to n.
  const Eigen::Vector2d t(n.y(), -n.x());
  s_lo = std::max(0.0, s_lo);
  s_hi = std::min(length_, s_hi);
  const int n_samples = static_cast<int>(sample_s_.size());
  const int i0 = std::clamp(static_cast<int>(std::floor(s_lo / step_)), 0, n_samples - 1);
  const int i1 = std::clamp(static_cast<int>(std::ceil(s_hi / step_)), 0, n_samples - 1);
  std::optional<Crossing> best;
  double prev = (sample_p_[i0] - b).dot(t);
  for (int i = i0 + 1; i <= i1; ++i) {
    const double cur = (sample_p_[i] - b).dot(t);
    if ((prev <= 0 && cur >= 0) || (prev >= 0 && cur <= 0)) {
      // Bisection-safeguarded Newton on phi(s) = (C(s) - b) . t in [s_{i-1}, s_i].
      double lo = sample_s_[i - 1], hi = sample_s_[i];
      double flo = prev;
      double s = (prev == cur) ? lo : lo + (hi - lo) * prev / (prev - cur);
      for (int it = 0; it < 60; ++it) {
        Eigen::Vector2d c, d1;
        profile_->Evaluate(s, &c, &d1, nullptr);
        const double f = (c - b).dot(t);
        if (f == 0.0) break;
        if ((f <= 0) == (flo <= 0)) {
          lo = s;
          flo = f;
        } else {
          hi = s;
        }
        const double fp = d1.dot(t);
        if (fp != 0 && std::abs(f / fp) < kParameterTolerance_m) break;  // as in RefineClosest
        double next = (fp != 0) ? s - f / fp : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const double step = std::abs(next - s);
        s = next;
        if (step < kParameterTolerance_m || hi - lo < kParameterTolerance_m) break;
      }
      const double lambda = (profile_->Position(s) - b).dot(n);
      if (!best || std::abs(lambda) < std::abs(best->lambda)) best = Crossing{s, lambda};
    }
    prev = cur;
  }
  return best;
}

}  // namespace railwear
