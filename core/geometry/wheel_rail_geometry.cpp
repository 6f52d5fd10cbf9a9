// Placement of the wheel on the rail, first contact by lowering, and the vertical-gap search for
// contact candidates (one or several separate patches, e.g. tread and flange at once).
#include "core/geometry/wheel_rail_geometry.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <limits>
#include <mutex>
#include <string>

#include "core/geometry/polyline_envelope.h"
#include "core/numerics/check.h"
#include "core/numerics/golden_section.h"
#include "core/profile/profile_keyed_cache.h"

namespace railwear {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The arc-length half-width of a windowed crossing scan (ExactVerticalGap): the golden search
// moves y by 4 sampling steps at most, which moves a crossing by that over the profile's lateral
// slope: 2 mm holds it up to 87 degrees at the default 20 um sampling (the full scan follows).
constexpr double kGapWindow_m = 2e-3;

// The yawed wheel's outline shared by every geometry of the same wheel, rolling radius and yaw
// (issue 18 point 3): a curving solve's Jacobian moves a wheelset laterally at its yaw, and a
// wear step's load cases spread the wheelsets laterally at their equilibrium yaw, so the same
// outline (a 15 000-point spline, 12 % of a curving run) was built again and again. The key is
// the exact input: the wheel profile's points and source byte for byte (they alone define the
// Profile) and the bits of r0 and yaw, so a shared outline is the one the geometry would build.
// The kMaxSharedOutlines most recently used ones are kept (about 1.5 MB each); the cache is
// process-wide under a mutex (curving solves wheelsets in parallel: ProfileKeyedCache) and
// invisible in results.
constexpr size_t kMaxSharedOutlines = 12;

std::shared_ptr<const YawedWheelSection> SharedYawedSection(const Profile& wheel, double r0,
                                                            double yaw_rad) {
  static ProfileKeyedCache<YawedWheelSection> shared(kMaxSharedOutlines);
  return shared.Get(wheel, {DoubleBits(r0), DoubleBits(yaw_rad)}, wheel.source(), [&] {
    return std::make_shared<const YawedWheelSection>(wheel, r0, yaw_rad);
  });
}

// The points of a profile at equal arc steps of at most step_m (both ends included), which the
// placement rasterises into the vertical-gap envelopes. They depend only on the profile and the
// step, not on the pose, so every placement of the same wheel (or yawed outline) and rail shares
// them: a time loop's placements at a new position each call sampled both profiles again
// (some 12 000 spline evaluations, 9 % of a warm gauge-corner call, docs/library.md). The key is
// the profile's points byte for byte and the step's bits (ProfileKeyedCache: a hit is the value
// a new sampling would make, bit for bit); the kMaxSharedSampledProfiles most recently used
// (about 0.1 MB each at the default 20 um) are kept.
constexpr size_t kMaxSharedSampledProfiles = 16;

std::shared_ptr<const std::vector<Eigen::Vector2d>> SharedSamples(const Profile& p, double step_m) {
  static ProfileKeyedCache<std::vector<Eigen::Vector2d>> shared(kMaxSharedSampledProfiles);
  return shared.Get(p, {DoubleBits(step_m)}, "", [&] {
    const int n = std::max(2, static_cast<int>(std::ceil(p.Length() / step_m)) + 1);
    auto pts = std::make_shared<std::vector<Eigen::Vector2d>>(n);
    for (int i = 0; i < n; ++i) (*pts)[i] = p.Position(p.Length() * i / (n - 1));
    return std::shared_ptr<const std::vector<Eigen::Vector2d>>(std::move(pts));
  });
}

// Lateral curvature of a profile at s, positive where the body is convex.
double ConvexCurvature(const CurveLocator& loc, double s) {
  const Eigen::Vector2d outward = loc.OutwardNormal(s);
  const Eigen::Vector2d left = loc.profile().LeftNormal(s);
  // The curve turns toward the material on a convex body: toward -outward.
  return loc.profile().Curvature(s) * (left.dot(-outward) > 0 ? 1.0 : -1.0);
}

}  // namespace

WheelRailGeometry::WheelRailGeometry(const Profile& wheel, const Profile& rail,
                                     const WheelPose& pose, double vertical_step_m)
    : pose_(pose),
      yawed_(pose.yaw_rad != 0.0 ? SharedYawedSection(wheel, pose.rolling_radius_m, pose.yaw_rad)
                                 : nullptr),
      rail_locator_(rail, /*material_toward_plus_z=*/true),
      wheel_locator_(yawed_ ? yawed_->outline() : wheel, /*material_toward_plus_z=*/false),
      cos_roll_(std::cos(pose.roll_rad)),
      sin_roll_(std::sin(pose.roll_rad)),
      cos_yaw_(std::cos(pose.yaw_rad)),
      sin_yaw_(std::sin(pose.yaw_rad)) {
  RAILWEAR_CHECK(pose.rolling_radius_m > 0 && vertical_step_m > 0);
  if (yawed_) surface_locator_.emplace(wheel, /*material_toward_plus_z=*/false);
  const Profile& section = yawed_ ? yawed_->outline() : wheel;
  // Sample both cross-sections (wheel at dz = 0) and intersect their lateral ranges.
  const std::shared_ptr<const std::vector<Eigen::Vector2d>> rail_pts =
      SharedSamples(rail, vertical_step_m);
  std::vector<Eigen::Vector2d> wheel_pts = *SharedSamples(section, vertical_step_m);
  for (auto& p : wheel_pts) p = WheelToRail(p);  // dz_ is still 0
  double ry0 = kInf, ry1 = -kInf, wy0 = kInf, wy1 = -kInf;
  for (const auto& p : *rail_pts) {
    ry0 = std::min(ry0, p.x());
    ry1 = std::max(ry1, p.x());
  }
  for (const auto& p : wheel_pts) {
    wy0 = std::min(wy0, p.x());
    wy1 = std::max(wy1, p.x());
  }
  const double y0 = std::max(ry0, wy0), y1 = std::min(ry1, wy1);
  if (!(y1 > y0)) return;
  const int n = static_cast<int>(std::floor((y1 - y0) / vertical_step_m)) + 1;
  std::vector<double> ztop(n, kInf), zbot(n, -kInf);
  internal::RasteriseEnvelope(*rail_pts, y0, vertical_step_m, n, /*take_min=*/true, &ztop);
  internal::RasteriseEnvelope(wheel_pts, y0, vertical_step_m, n, /*take_min=*/false, &zbot);
  gap_y_.resize(n);
  gap_.assign(n, std::numeric_limits<double>::quiet_NaN());
  int best = -1;
  for (int i = 0; i < n; ++i) {
    gap_y_[i] = y0 + i * vertical_step_m;
    if (std::isfinite(ztop[i]) && std::isfinite(zbot[i])) {
      gap_[i] = ztop[i] - zbot[i];
      if (best < 0 || gap_[i] < gap_[best]) best = i;
    }
  }
  if (best < 0) return;
  has_overlap_ = true;
  // Refine the first contact on the splines: the exact vertical gap near the sampled minimum.
  rail_top_ = ztop;
  wheel_bottom_ = zbot;
  const double y_star = RefineMinimum(best);
  double g_min = ExactVerticalGap(y_star, best);
  if (!std::isfinite(g_min)) g_min = gap_[best];
  dz_ = g_min;
  for (double& g : gap_) g -= dz_;
}

double WheelRailGeometry::ExactVerticalGap(double y, int sample,
                                           std::optional<GapWindow>* near) const {
  // Crossings of the vertical line at y with both splines, near the sampled envelopes: each
  // locator's scan runs over its whole profile, or over a window about a nearby y's crossing
  // (the same sample interval, so the same crossing bit for bit, at a fraction of the cost).
  auto cross = [&](const CurveLocator& loc, const Eigen::Vector2d& b, const Eigen::Vector2d& n,
                   std::optional<double> s_near) {
    std::optional<CurveLocator::Crossing> c;
    if (s_near) c = loc.IntersectLine(b, n, *s_near - kGapWindow_m, *s_near + kGapWindow_m);
    if (!c) c = loc.IntersectLine(b, n, 0.0, kInf);
    return c;
  };
  const bool windowed = near && near->has_value();
  const auto r = cross(rail_locator_, {y, rail_top_[sample]}, {0.0, 1.0},
                       windowed ? std::optional<double>((*near)->rail_s) : std::nullopt);
  const Eigen::Vector2d b_w = RailToWheel({y, wheel_bottom_[sample]});
  const Eigen::Vector2d n_w = RailDirectionToWheel({0.0, 1.0});
  const auto w = cross(wheel_locator_, b_w, n_w,
                       windowed ? std::optional<double>((*near)->wheel_s) : std::nullopt);
  if (!r || !w) return kInf;
  if (near) *near = GapWindow{r->s, w->s};
  return (rail_top_[sample] + r->lambda) - (wheel_bottom_[sample] + w->lambda);
}

double WheelRailGeometry::RefineMinimum(int sample) const {
  const double h = gap_y_.size() > 1 ? gap_y_[1] - gap_y_[0] : 1e-5;
  std::optional<GapWindow> near;
  return GoldenMinimise([&](double y) { return ExactVerticalGap(y, sample, &near); },
                        gap_y_[sample] - 2 * h, gap_y_[sample] + 2 * h, 1e-10);
}

Eigen::Vector2d WheelRailGeometry::WheelToRail(const Eigen::Vector2d& p) const {
  return {cos_roll_ * p.x() - sin_roll_ * p.y() + pose_.lateral_shift_m,
          sin_roll_ * p.x() + cos_roll_ * p.y() + dz_};
}

Eigen::Vector2d WheelRailGeometry::RailToWheel(const Eigen::Vector2d& p) const {
  const double dy = p.x() - pose_.lateral_shift_m, dzz = p.y() - dz_;
  return {cos_roll_ * dy + sin_roll_ * dzz, -sin_roll_ * dy + cos_roll_ * dzz};
}

Eigen::Vector2d WheelRailGeometry::RailDirectionToWheel(const Eigen::Vector2d& d) const {
  return {cos_roll_ * d.x() + sin_roll_ * d.y(), -sin_roll_ * d.x() + cos_roll_ * d.y()};
}

Eigen::Vector2d WheelRailGeometry::Meridian(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d w = RailToWheel({p.y(), p.z()});
  const double r0 = pose_.rolling_radius_m;
  if (!yawed_) {
    const double r = std::hypot(p.x(), w.y() + r0);
    return {w.x(), r - r0};
  }
  // Undo the yaw about the vertical through the wheel profile origin: wheel axes (x_w along the
  // wheel's own rolling direction, y_w along the axle).
  const double x_w = cos_yaw_ * p.x() + sin_yaw_ * w.x();
  const double y_w = -sin_yaw_ * p.x() + cos_yaw_ * w.x();
  const double r = std::hypot(x_w, w.y() + r0);
  return {y_w, r - r0};
}

CurveLocator::Projection WheelRailGeometry::ProjectOnWheel(const Eigen::Vector3d& p, double s_lo,
                                                           double s_hi) const {
  return wheel_surface().Project(Meridian(p), s_lo, s_hi);
}

YawedWheelSection::Source WheelRailGeometry::SurfaceSource(double outline_s_m) const {
  if (!yawed_) return {outline_s_m, 0.0};
  return yawed_->SourceAt(outline_s_m);
}

CurveLocator::Projection WheelRailGeometry::ProjectOnRail(const Eigen::Vector2d& yz, double s_lo,
                                                          double s_hi) const {
  return rail_locator_.Project(yz, s_lo, s_hi);
}

Eigen::Vector2d WheelRailGeometry::WheelOutwardNormalInRail(double s) const {
  const Eigen::Vector2d n = wheel_locator_.OutwardNormal(s);
  return {cos_roll_ * n.x() - sin_roll_ * n.y(), sin_roll_ * n.x() + cos_roll_ * n.y()};
}

std::vector<ContactCandidate> WheelRailGeometry::FindCandidates(double threshold_m) const {
  std::vector<ContactCandidate> out;
  if (!has_overlap_) return out;
  const int n = static_cast<int>(gap_.size());
  // Runs of samples below the threshold, each split at its prominent saddles: two basins of
  // the gap (tread and flange root, say) are separate candidates when the gap between them
  // rises by more than kProminence * threshold above both.
  constexpr double kProminence = 0.1;
  const double prom = kProminence * threshold_m;
  struct Segment {
    int a, b;  // [a, b) samples
    bool split_lo, split_hi;
  };
  std::vector<Segment> segments;
  for (int i = 0; i < n;) {
    if (!(gap_[i] < threshold_m)) {
      ++i;
      continue;
    }
    int j = i;
    while (j < n && gap_[j] < threshold_m) ++j;
    int start = i, lo = i, hi = i;
    bool split_before = false;
    for (int k = i + 1; k < j; ++k) {
      if (gap_[hi] - gap_[lo] <= prom && gap_[k] < gap_[lo]) {
        lo = hi = k;  // still descending into the same basin
      } else if (gap_[k] > gap_[hi]) {
        hi = k;
      } else if (gap_[hi] - gap_[k] > prom && gap_[hi] - gap_[lo] > prom) {
        segments.push_back({start, hi, split_before, true});  // saddle at hi: a new basin
        start = hi;
        split_before = true;
        lo = hi = k;
      }
    }
    segments.push_back({start, j, split_before, false});
    i = j;
  }
  for (const Segment& seg : segments) {
    int best = seg.a;
    for (int k = seg.a; k < seg.b; ++k) {
      if (gap_[k] < gap_[best]) best = k;
    }
    const int i = seg.a, j = seg.b;
    ContactCandidate c;
    c.y_lo_m = gap_y_[i];
    c.y_hi_m = gap_y_[j - 1];
    c.split_lo = seg.split_lo;
    c.split_hi = seg.split_hi;
    c.y_m = RefineMinimum(best);
    c.gap_m = ExactVerticalGap(c.y_m, best);
    if (!std::isfinite(c.gap_m)) {
      c.y_m = gap_y_[best];
      c.gap_m = gap_[best];
    }
    SetContactPoint(best, c.y_m, c.gap_m, &c);
    out.push_back(c);
  }
  return out;
}

void WheelRailGeometry::SetContactPoint(int sample, double y, double gap,
                                        ContactCandidate* c) const {
  // Contact point: the rail top under the lateral position (projected onto the spline), and the
  // wheel point straight above it.
  const auto rp = rail_locator_.Project({y, rail_top_[sample]}, 0.0, kInf);
  c->rail_s_m = rp.s;
  c->rail_point_m = rp.point;
  const Eigen::Vector2d above = c->rail_point_m - Eigen::Vector2d(0.0, gap);
  const auto wp = wheel_locator_.Project(RailToWheel(above));
  c->wheel_s_m = wp.s;
  c->normal = rail_locator_.OutwardNormal(c->rail_s_m);
  c->rail_lateral_curvature = ConvexCurvature(rail_locator_, c->rail_s_m);
  c->wheel_lateral_curvature = ConvexCurvature(wheel_locator_, c->wheel_s_m);
  c->x_m = 0.0;
  c->lead_m = 0.0;
  if (!yawed_) {
    c->wheel_radius_m =
        pose_.rolling_radius_m + wheel_locator_.profile().Position(c->wheel_s_m).y();
  } else {
    // The surface point behind the outline point: its radius, position along x, and lead over
    // the axle line through it (the axle runs along (-sin psi, cos psi) in the wheel's unrolled
    // frame, so at lateral position Y_w it lies at x = -Y_w tan psi).
    const YawedWheelSection::Source src = yawed_->SourceAt(c->wheel_s_m);
    c->wheel_radius_m =
        pose_.rolling_radius_m + surface_locator_->profile().Position(src.wheel_s_m).y();
    c->x_m = src.x_m;
    const double y_w = wheel_locator_.profile().Position(c->wheel_s_m).x();
    c->lead_m = c->x_m + y_w * sin_yaw_ / cos_yaw_;
  }
}

ContactCandidate WheelRailGeometry::CandidateAt(const ContactCandidate& interval,
                                                double y_m) const {
  ContactCandidate c = interval;
  if (gap_y_.empty()) return c;
  double y = std::clamp(y_m, interval.y_lo_m, interval.y_hi_m);
  const auto it = std::lower_bound(gap_y_.begin(), gap_y_.end(), y);
  int sample = static_cast<int>(std::min<std::ptrdiff_t>(
      it - gap_y_.begin(), static_cast<std::ptrdiff_t>(gap_y_.size()) - 1));
  if (sample > 0 && std::abs(gap_y_[sample - 1] - y) < std::abs(gap_y_[sample] - y)) --sample;
  double gap = ExactVerticalGap(y, sample);
  if (!std::isfinite(gap)) {
    y = gap_y_[sample];
    gap = gap_[sample];
  }
  SetContactPoint(sample, y, gap, &c);
  return c;
}

}  // namespace railwear
