// The outline of a yawed wheel of revolution seen along the rail (yawed_wheel.h).
#include "core/geometry/yawed_wheel.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/numerics/check.h"
#include "core/profile/profile_defects.h"

namespace railwear {
namespace {

// At most this many folds are cut out of one outline (Car7216_0001r.whl at 20 mrad needs a few
// dozen); beyond it the outline is refused with the Profile's message.
constexpr int kMaxFoldCuts = 2000;

}  // namespace

double YawedWheelSection::SinTheta(const Eigen::Vector2d& n, double yaw_rad) {
  return SinThetaFromTan(n, std::tan(yaw_rad));
}

double YawedWheelSection::SinThetaFromTan(const Eigen::Vector2d& n, double t) {
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
  // A sample whose outline point steps back against the profile's direction is dropped: the
  // outline follows the surface normal, so a measured profile's noise in its slope folds the
  // outline into swallowtails of a few micrometres (avg_wheel.whl's flange face at 5 mrad), whose
  // backward part is hidden behind the rest of the silhouette. A smooth profile keeps every sample.
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = pts[i];
    const double sin_t = SinTheta(sign * wheel.LeftNormal(s_of[i]), yaw_rad);
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double r = r0 + p.y();
    const Eigen::Vector2d q(r * sin_t * sn + p.x() * c, r * cos_t - r0);
    if (kept > 0 && (q - pts[kept - 1]).dot(wheel.Tangent(s_of[i])) <= 0.0) continue;
    wheel_s_[kept] = s_of[i];
    x_[kept] = r * sin_t * c - p.x() * sn;
    pts[kept++] = q;
  }
  auto erase = [&](int from, int to) {  // samples [from, to)
    pts.erase(pts.begin() + from, pts.begin() + to);
    wheel_s_.erase(wheel_s_.begin() + from, wheel_s_.begin() + to);
    x_.erase(x_.begin() + from, x_.begin() + to);
  };
  erase(kept, n);
  // Folds that step forward and still cross an earlier stretch: a measured profile's noisy,
  // nearly vertical faces (Car7216_0001r.whl's hooked flange tip and its flange back at 4-20
  // mrad), where the outline point moves round the wheel by up to r |sin(theta)| and back. The
  // loop between two crossing segments is the hidden part of the silhouette and is cut out (a
  // turn back or a duplicate: its one point), one at a time (each check well under a
  // millisecond; a smooth outline pays for one, which the Profile makes again).
  for (int cut = 0; cut < kMaxFoldCuts; ++cut) {
    const std::optional<ProfileDefect> d = FindProfileDefect(pts);
    if (!d) break;
    int from = d->b, to = d->b + 1;  // a duplicate: point b
    if (d->kind == ProfileDefect::Kind::kTurnBack) from = d->a + 1, to = d->a + 2;
    if (d->kind == ProfileDefect::Kind::kCrossing) from = d->a + 1, to = d->b + 1;
    to = std::min(to, static_cast<int>(pts.size()) - 1);  // keep the last point
    if (from >= to) break;  // nothing to cut: the Profile below says what is wrong
    erase(from, to);
  }
  kept = static_cast<int>(pts.size());
  outline_ = Profile(std::move(pts), wheel.source() + " (yawed outline)");
  // The profile keeps the samples as its knots unless it had to subdivide a long segment.
  knots_are_samples_ = outline_.size() == kept;
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
