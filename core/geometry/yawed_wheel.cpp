// The outline of a yawed wheel of revolution seen along the rail (yawed_wheel.h).
#include "core/geometry/yawed_wheel.h"

#include <algorithm>
#include <cmath>

#include "core/numerics/check.h"

namespace railwear {

double YawedWheelSection::SinTheta(const Eigen::Vector2d& n, double yaw_rad) {
  const double t = std::tan(yaw_rad);
  // n_y tan(psi) / n_z, evaluated without dividing by a vanishing n_z.
  const double num = n.x() * t, den = n.y();
  if (num == 0.0) return 0.0;
  if (std::abs(num) >= kMaxSinTheta * std::abs(den)) {
    return std::copysign(kMaxSinTheta, num) * (den < 0 ? -1.0 : 1.0);
  }
  return num / den;
}

YawedWheelSection::YawedWheelSection(const Profile& wheel, double r0, double yaw_rad,
                                     double step_m) {
  RAILWEAR_CHECK(r0 > 0 && step_m > 0 && std::abs(yaw_rad) < 0.5);
  const double c = std::cos(yaw_rad), sn = std::sin(yaw_rad);
  // The wheel's material lies toward -z: at the profile's lowest point (largest z, the flange
  // tip) the outward normal points toward +z. LeftNormal times this sign is outward everywhere.
  const int n = std::max(4, static_cast<int>(std::ceil(wheel.Length() / step_m)) + 1);
  std::vector<Eigen::Vector2d> pts(n);
  wheel_s_.resize(n);
  x_.resize(n);
  std::vector<double> s_of(n);
  for (int i = 0; i < n; ++i) {
    s_of[i] = wheel.Length() * i / (n - 1);
    pts[i] = wheel.Position(s_of[i]);
  }
  const int lowest = static_cast<int>(
      std::max_element(pts.begin(), pts.end(),
                       [](const auto& a, const auto& b) { return a.y() < b.y(); }) -
      pts.begin());
  const double sign = wheel.LeftNormal(s_of[lowest]).y() > 0 ? 1.0 : -1.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = pts[i];
    const double sin_t = SinTheta(sign * wheel.LeftNormal(s_of[i]), yaw_rad);
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double r = r0 + p.y();
    wheel_s_[i] = s_of[i];
    x_[i] = r * sin_t * c - p.x() * sn;
    pts[i] = {r * sin_t * sn + p.x() * c, r * cos_t - r0};
  }
  outline_ = Profile(std::move(pts), wheel.source() + " (yawed outline)");
  // The profile keeps the samples as its knots unless it had to subdivide a long segment.
  knots_are_samples_ = outline_.size() == n;
}

YawedWheelSection::Source YawedWheelSection::SourceAt(double outline_s_m) const {
  if (!knots_are_samples_) return SourceOf(outline_.Position(outline_s_m));
  const int n = outline_.size();
  int lo = 0, hi = n - 1;
  if (outline_s_m <= outline_.KnotS(0)) return {wheel_s_.front(), x_.front()};
  if (outline_s_m >= outline_.KnotS(n - 1)) return {wheel_s_.back(), x_.back()};
  while (hi - lo > 1) {
    const int m = (lo + hi) / 2;
    (outline_.KnotS(m) <= outline_s_m ? lo : hi) = m;
  }
  const double f = (outline_s_m - outline_.KnotS(lo)) / (outline_.KnotS(hi) - outline_.KnotS(lo));
  return {wheel_s_[lo] + f * (wheel_s_[hi] - wheel_s_[lo]), x_[lo] + f * (x_[hi] - x_[lo])};
}

YawedWheelSection::Source YawedWheelSection::SourceOf(const Eigen::Vector2d& yz) const {
  // Nearest sample, then the projection onto the neighbouring chords.
  const auto& pts = outline_.points();
  int best = 0;
  double d_best = (pts[0] - yz).squaredNorm();
  for (int i = 1; i < static_cast<int>(pts.size()); ++i) {
    const double d = (pts[i] - yz).squaredNorm();
    if (d < d_best) {
      d_best = d;
      best = i;
    }
  }
  Source out{wheel_s_[best], x_[best]};
  double d_out = d_best;
  for (int k : {best - 1, best}) {
    if (k < 0 || k + 1 >= static_cast<int>(pts.size())) continue;
    const Eigen::Vector2d e = pts[k + 1] - pts[k];
    const double f = std::clamp((yz - pts[k]).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const double d = (pts[k] + f * e - yz).squaredNorm();
    if (d < d_out) {
      d_out = d;
      out = {wheel_s_[k] + f * (wheel_s_[k + 1] - wheel_s_[k]), x_[k] + f * (x_[k + 1] - x_[k])};
    }
  }
  return out;
}

}  // namespace railwear
