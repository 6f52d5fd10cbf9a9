// The fast tread path (hertz_tread.h).
#include "core/contact/hertz_tread.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "core/contact/balance_target.h"
#include "core/contact/contact_forces.h"
#include "core/contact/grid_resolution.h"
#include "core/contact/hertz_estimate.h"
#include "core/contact/model_selection.h"
#include "core/contact/normal_tangential_stage.h"
#include "core/contact/patch_results.h"
#include "core/contact/placement_stage.h"
#include "core/contact/rigid_motion.h"
#include "core/contact/rolling_patch.h"
#include "core/contact/rolling_stage.h"
#include "core/contact/stage_timer.h"
#include "core/geometry/polyline_envelope.h"
#include "core/geometry/yawed_wheel.h"
#include "core/numerics/check.h"
#include "core/numerics/golden_section.h"
#include "core/numerics/input_error.h"
#include "core/profile/profile_keyed_cache.h"

namespace railwear {

namespace {

using internal::AddStage;
using internal::Clock;
using internal::SecondsSince;

constexpr double kInf = std::numeric_limits<double>::infinity();
// The coarse gap's spacing [m]: every k-th point of each profile, k making about this arc
// length (the built-in profiles have a point every 0.1 mm), and the lateral step of the rail's
// upper envelope. The envelope's chords depart from the rail by h^2 / (8 R): 0.1 um on the
// 300 mm crown, 2.4 um on the 13 mm gauge corner, well inside the two-point margin below; the
// first contact is refined on the splines over +-2 coarse steps about the coarse minimum.
constexpr double kEnvelopeStep_m = 5e-4;
// A second basin of the coarse gap whose bottom lies within kTwoPointMargin times the approach
// of the contact's gap would be in contact too (two-point contact). The margin covers the coarse
// gap's chords (above: a few um; the approach is tens of um at 100 kN, 10 um at 10 kN).
constexpr double kTwoPointMargin = 1.5;
// Two basins of the coarse gap are separate when the gap rises between them by more than this
// fraction of the margin kTwoPointMargin * approach (WheelRailGeometry::FindCandidates' rule).
constexpr double kBasinProminence = 0.1;
// The largest departure of the gap from Hertz's quadratic over the patch (PatchConformity::
// gap_deviation, measured over the larger patch estimate) the fast path accepts. kind = "auto"
// takes Hertz only within the preset's tolerance (5 % at draft), which no S1002/UIC60 1:40 tread
// position meets (the crown's 300 mm radius meets the 80 mm one within the patch). Measured
// against the half-space grid at standard accuracy (tests/benchmarks/tread_hertz_accuracy.py,
// docs/library.md): up to 0.31 the fast path's area is within 4.2 %, p_max within 0.6 %, the
// contact point within 0.5 mm and the creep forces within 1.1 % of mu Q; with this check removed,
// at 0.41-0.55 the area was 6.5 % off and the point 1 mm, beyond 0.6 the patch is another (area
// -20 to -50 %).
constexpr double kMaxTreadGapDeviation = 0.35;
// The golden-section refinement of the first contact stops at this width of wheel arc [m]
// (WheelRailGeometry refines y to 1e-10 m).
constexpr double kRefineTolerance_m = 1e-10;
// Newton's steps on a profile parameter stop below this [m] (round-off of the splines' arc
// length is about 1e-16 x 0.15 m; a step of 1e-12 m moves a point by less than that).
constexpr double kNewtonTolerance_m = 1e-12;

// Every how many points of `profile` the coarse gap takes one (about kEnvelopeStep_m apart).
int Stride(const Profile& profile) {
  const double spacing = profile.Length() / std::max(1, profile.size() - 1);
  return std::max(1, static_cast<int>(std::lround(kEnvelopeStep_m / spacing)));
}

// A profile's point, unit tangent, left normal and curvature at s from one evaluation of its
// splines: bit for bit Profile::Position, Tangent, LeftNormal and Curvature (profile.cpp), which
// evaluate them once each (the conformity check below takes all four at ten points).
struct ProfileFrame {
  Eigen::Vector2d position, tangent, left_normal;
  double curvature = 0.0;
};
ProfileFrame FrameAt(const Profile& profile, double s) {
  ProfileFrame f;
  Eigen::Vector2d d1, d2;
  profile.Evaluate(s, &f.position, &d1, &d2);
  f.tangent = d1.normalized();
  f.left_normal = {-f.tangent.y(), f.tangent.x()};
  const double speed = d1.norm();
  f.curvature = (d1.x() * d2.y() - d1.y() * d2.x()) / (speed * speed * speed);
  return f;
}

// The rail's upper envelope on every Stride(rail)-th point (and the last), on a lateral grid of
// kEnvelopeStep_m: its z and the rail parameter under it (the exact top's search starts there),
// and the rail's orientation. A pure function of the rail profile, so one is kept per rail and
// shared (RailEnvelopeOf): an MBS time loop runs on one rail.
struct RailEnvelope {
  double rail_sign = 1.0;  // outward normal = rail_sign * LeftNormal (CurveLocator's rule)
  double y0_m = 0.0;       // lateral position of the first sample [m]
  std::vector<double> top_z_m, top_s_m;  // per sample; +inf and -1 where no rail is

  explicit RailEnvelope(const Profile& rail) {
    const auto& rp = rail.points();
    const int np = static_cast<int>(rp.size());
    const int stride = Stride(rail);
    std::vector<Eigen::Vector2d> pts;
    std::vector<int> knot;
    pts.reserve(np / stride + 2);
    knot.reserve(np / stride + 2);
    for (int k = 0; k < np; k += stride) {
      pts.push_back(rp[k]);
      knot.push_back(k);
    }
    if (knot.back() != np - 1) {
      pts.push_back(rp[np - 1]);
      knot.push_back(np - 1);
    }
    // Orientation as CurveLocator's: outward at the rail's highest point is -z.
    int highest = 0;
    y0_m = kInf;
    double y1 = -kInf;
    for (size_t k = 0; k < pts.size(); ++k) {
      if (pts[k].y() < pts[highest].y()) highest = static_cast<int>(k);
      y0_m = std::min(y0_m, pts[k].x());
      y1 = std::max(y1, pts[k].x());
    }
    rail_sign = rail.LeftNormal(rail.KnotS(knot[highest])).y() < 0 ? 1.0 : -1.0;
    const int n = static_cast<int>(std::floor((y1 - y0_m) / kEnvelopeStep_m)) + 1;
    top_z_m.assign(n, kInf);
    internal::RasteriseEnvelope(pts, y0_m, kEnvelopeStep_m, n, /*take_min=*/true, &top_z_m);
    top_s_m.assign(n, -1.0);
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      const Eigen::Vector2d& a = pts[k];
      const Eigen::Vector2d& b = pts[k + 1];
      const double ya = std::min(a.x(), b.x()), yb = std::max(a.x(), b.x());
      const int i0 = std::max(0, static_cast<int>(std::ceil((ya - y0_m) / kEnvelopeStep_m)));
      const int i1 = std::min(n - 1, static_cast<int>(std::floor((yb - y0_m) / kEnvelopeStep_m)));
      for (int i = i0; i <= i1; ++i) {
        const double y = y0_m + i * kEnvelopeStep_m;
        const double t = yb == ya ? 0.0 : (y - a.x()) / (b.x() - a.x());
        const double z = a.y() + t * (b.y() - a.y());
        if (z <= top_z_m[i]) {
          top_s_m[i] = rail.KnotS(knot[k]) + t * (rail.KnotS(knot[k + 1]) - rail.KnotS(knot[k]));
        }
      }
    }
  }
};

// The envelope of `rail`, shared process-wide by the rail's points (ProfileKeyedCache: a hit is
// the envelope a new build would make, bit for bit). A few rails are enough: a handle has one or
// two.
constexpr size_t kMaxSharedEnvelopes = 8;
std::shared_ptr<const RailEnvelope> RailEnvelopeOf(const Profile& rail) {
  static ProfileKeyedCache<RailEnvelope> shared(kMaxSharedEnvelopes);
  return shared.Get(rail, {}, {}, [&] { return std::make_shared<const RailEnvelope>(rail); });
}

// The wheel and the rail as the fast path sees them: the wheel's silhouette seen along the rail
// (YawedWheelSection's closed form per profile point) placed by the pose, and the rail's top.
class TreadGeometry {
 public:
  TreadGeometry(const Profile& wheel, const Profile& rail, const WheelPose& pose)
      : wheel_(wheel),
        rail_(rail),
        pose_(pose),
        cr_(std::cos(pose.roll_rad)),
        sr_(std::sin(pose.roll_rad)),
        cy_(std::cos(pose.yaw_rad)),
        sy_(std::sin(pose.yaw_rad)),
        tan_yaw_(std::tan(pose.yaw_rad)),
        envelope_(RailEnvelopeOf(rail)) {
    // The wheel's orientation as CurveLocator's: outward at its lowest point is +z.
    const auto& wp = wheel.points();
    const int nw = static_cast<int>(wp.size());
    int lowest = 0;
    const int wheel_stride = Stride(wheel);
    for (int i = 0; i < nw; i += wheel_stride) {
      if (wp[i].y() > wp[lowest].y()) lowest = i;
    }
    wheel_sign_ = wheel.LeftNormal(wheel.KnotS(lowest)).y() >= 0 ? 1.0 : -1.0;
  }

  const Profile& wheel() const { return wheel_; }
  const Profile& rail() const { return rail_; }
  const WheelPose& pose() const { return pose_; }
  double wheel_sign() const { return wheel_sign_; }
  double rail_sign() const { return envelope_->rail_sign; }

  // W -> R with the wheel lowered by dz [m] (WheelRailGeometry::WheelToRail's transform).
  Eigen::Vector2d WheelToRail(const Eigen::Vector2d& p, double dz) const {
    return {cr_ * p.x() - sr_ * p.y() + pose_.lateral_shift_m, sr_ * p.x() + cr_ * p.y() + dz};
  }
  Eigen::Vector2d WheelDirectionToRail(const Eigen::Vector2d& d) const {
    return {cr_ * d.x() - sr_ * d.y(), sr_ * d.x() + cr_ * d.y()};
  }

  // The silhouette point of the wheel-profile point p_W with outward normal n_W: its (y, z) in R
  // before lowering, its x [m] (forward of the wheel profile origin) and its outline Y (the
  // unrolled yawed wheel frame's lateral coordinate).
  struct Silhouette {
    Eigen::Vector2d yz_R;
    double x_m = 0.0, outline_y_m = 0.0, sin_theta = 0.0;
  };
  Silhouette SilhouetteOf(const Eigen::Vector2d& p_W, const Eigen::Vector2d& n_W) const {
    Silhouette out;
    const double r0 = pose_.rolling_radius_m;
    const double sin_t = YawedWheelSection::SinThetaFromTan(n_W, tan_yaw_);
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double r = r0 + p_W.y();
    const Eigen::Vector2d q(r * sin_t * sy_ + p_W.x() * cy_, r * cos_t - r0);
    out.yz_R = WheelToRail(q, 0.0);
    out.x_m = r * sin_t * cy_ - p_W.x() * sy_;
    out.outline_y_m = q.x();
    out.sin_theta = sin_t;
    return out;
  }
  // d1 (optional out): the wheel profile's derivative there, Profile::Derivative's value.
  Silhouette WheelAt(double s, Eigen::Vector2d* d1_out = nullptr) const {
    Eigen::Vector2d p, d1;
    wheel_.Evaluate(s, &p, &d1, nullptr);
    if (d1_out) *d1_out = d1;
    return SilhouetteOf(p, wheel_sign_ * Eigen::Vector2d(-d1.y(), d1.x()).normalized());
  }

  // True when the silhouette point of the wheel-profile point p_W lies off the rail envelope's
  // lateral extent whatever its normal (CoarseTop would give +inf there), decided without the
  // normal: with sin(theta) = 0 the point's y in R is cr (y_W cy) - sr z_W + shift, and the
  // silhouette moves it by cr r sin(theta) sy - sr r (cos(theta) - 1), at most
  // r (|cr sy| kMaxSinTheta + |sr| (1 - cos(asin(kMaxSinTheta)))); kOffRailSlack_m covers the
  // rounding. *y_R: that estimate of its y [m].
  bool OffRail(const Eigen::Vector2d& p_W, double* y_R) const {
    constexpr double kOffRailSlack_m = 1e-9;
    const double r = std::abs(pose_.rolling_radius_m + p_W.y());
    const double s = YawedWheelSection::kMaxSinTheta;
    const double margin =
        r * (std::abs(cr_ * sy_) * s + std::abs(sr_) * (1.0 - std::sqrt(1.0 - s * s))) +
        kOffRailSlack_m;
    const double y = cr_ * (p_W.x() * cy_) - sr_ * p_W.y() + pose_.lateral_shift_m;
    *y_R = y;
    const double y_lo = envelope_->y0_m;
    const double y_hi = y_lo + kEnvelopeStep_m * static_cast<double>(envelope_->top_z_m.size() - 1);
    return y + margin < y_lo || y - margin > y_hi;
  }

  // The rail envelope's z at y (linear between its samples), +inf off the rail.
  double CoarseTop(double y) const {
    const std::vector<double>& top = envelope_->top_z_m;
    const double u = (y - envelope_->y0_m) / kEnvelopeStep_m;
    const int i = static_cast<int>(std::floor(u));
    if (i < 0 || i + 1 >= static_cast<int>(top.size())) return kInf;
    const double f = u - i;
    return top[i] + f * (top[i + 1] - top[i]);
  }
  // The rail's top on the spline at lateral y: its parameter (Newton on y(s) = y from the
  // envelope's point, kept inside that point's neighbours), or -1 off the rail.
  double RailTopS(double y, double s_start = -1.0) const {
    double s = s_start;
    if (s < 0) {
      const std::vector<double>& top_s = envelope_->top_s_m;
      const int i = static_cast<int>(std::lround((y - envelope_->y0_m) / kEnvelopeStep_m));
      if (i < 0 || i >= static_cast<int>(top_s.size()) || top_s[i] < 0) return -1.0;
      s = top_s[i];
    }
    for (int it = 0; it < 8; ++it) {
      Eigen::Vector2d p, d1;
      rail_.Evaluate(s, &p, &d1, nullptr);
      if (std::abs(d1.x()) < 1e-3) break;  // a vertical face: no top here
      const double step = (p.x() - y) / d1.x();
      s = std::clamp(s - step, 0.0, rail_.Length());
      if (std::abs(step) < kNewtonTolerance_m) break;
    }
    return s;
  }

  // The vertical gap between the rail's top and the silhouette point of wheel parameter s
  // before lowering [m] (+inf off the rail); *rail_s the rail's parameter there.
  double Gap(double s, double* rail_s) const {
    const Silhouette w = WheelAt(s);
    const double s_r = RailTopS(w.yz_R.x(), *rail_s);
    if (s_r < 0) return kInf;
    *rail_s = s_r;
    return rail_.Position(s_r).y() - w.yz_R.y();
  }

 private:
  const Profile& wheel_;
  const Profile& rail_;
  WheelPose pose_;
  double cr_, sr_, cy_, sy_, tan_yaw_;
  std::shared_ptr<const RailEnvelope> envelope_;
  double wheel_sign_ = 1.0;
};

// The first contact of the placed wheel: the coarse gap per wheel-profile point, refined.
struct TreadPlacement {
  bool overlap = false;
  double dz_m = 0.0;        // the wheel lowered to first contact
  double wheel_s_m = 0.0;   // wheel profile parameter of the contact point
  double rail_s_m = 0.0;
  // The coarse samples: every Stride(wheel)-th wheel point (its index), its gap before lowering
  // (+inf off the rail) and its silhouette's y in R [m].
  std::vector<int> knot;
  std::vector<double> coarse_gap, coarse_y;
  int best = -1;  // the coarse sample of the smallest gap
};

TreadPlacement Place(const TreadGeometry& g) {
  TreadPlacement out;
  const Profile& wheel = g.wheel();
  const auto& wp = wheel.points();
  const int n = static_cast<int>(wp.size());
  const int stride = Stride(wheel);
  int& best = out.best;
  const size_t samples = static_cast<size_t>(n / stride + 2);
  out.knot.reserve(samples);
  out.coarse_gap.reserve(samples);
  out.coarse_y.reserve(samples);
  for (int i = 0; i < n; i += std::min(stride, std::max(1, n - 1 - i))) {
    // Wheel points off the rail's lateral extent have no gap (+inf, as CoarseTop gives them);
    // their y (never read where the gap is infinite) is the estimate OffRail makes.
    double y_off = 0.0;
    if (g.OffRail(wp[i], &y_off)) {
      out.knot.push_back(i);
      out.coarse_gap.push_back(kInf);
      out.coarse_y.push_back(y_off);
      if (i == n - 1) break;
      continue;
    }
    const Eigen::Vector2d t = wp[std::min(i + 1, n - 1)] - wp[std::max(i - 1, 0)];
    const Eigen::Vector2d normal = g.wheel_sign() * Eigen::Vector2d(-t.y(), t.x()).normalized();
    const auto w = g.SilhouetteOf(wp[i], normal);
    const double top = g.CoarseTop(w.yz_R.x());
    out.knot.push_back(i);
    out.coarse_gap.push_back(std::isfinite(top) ? top - w.yz_R.y() : kInf);
    out.coarse_y.push_back(w.yz_R.x());
    const int k = static_cast<int>(out.knot.size()) - 1;
    if (std::isfinite(top) && (best < 0 || out.coarse_gap[k] < out.coarse_gap[best])) best = k;
    if (i == n - 1) break;
  }
  if (best < 0) return out;
  out.overlap = true;
  const int m = static_cast<int>(out.knot.size());
  const double lo = wheel.KnotS(out.knot[std::max(best - 2, 0)]);
  const double hi = wheel.KnotS(out.knot[std::min(best + 2, m - 1)]);
  double rail_s = -1.0;
  const double s = GoldenMinimise([&](double si) { return g.Gap(si, &rail_s); }, lo, hi,
                                  kRefineTolerance_m);
  rail_s = -1.0;
  double gap = g.Gap(s, &rail_s);
  if (!std::isfinite(gap)) {
    out.overlap = false;
    return out;
  }
  out.dz_m = gap;
  out.wheel_s_m = s;
  out.rail_s_m = rail_s;
  return out;
}

// The contact candidate at the placement's point, filled as WheelRailGeometry::SetContactPoint
// fills it (the wheel's lateral curvature is its profile's: hertz_tread.h).
ContactCandidate CandidateOf(const TreadGeometry& g, const TreadPlacement& pl) {
  ContactCandidate c;
  const Profile& rail = g.rail();
  const Profile& wheel = g.wheel();
  const ProfileFrame fr = FrameAt(rail, pl.rail_s_m);
  const ProfileFrame fw = FrameAt(wheel, pl.wheel_s_m);
  c.rail_s_m = pl.rail_s_m;
  c.rail_point_m = fr.position;
  c.y_m = c.y_lo_m = c.y_hi_m = c.rail_point_m.x();
  c.gap_m = 0.0;
  c.wheel_s_m = pl.wheel_s_m;
  c.normal = g.rail_sign() * fr.left_normal;
  c.rail_lateral_curvature = -g.rail_sign() * fr.curvature;
  c.wheel_lateral_curvature = -g.wheel_sign() * fw.curvature;
  c.wheel_radius_m = g.pose().rolling_radius_m + fw.position.y();
  const auto w = g.WheelAt(pl.wheel_s_m);
  c.x_m = w.x_m;
  c.lead_m = c.x_m + w.outline_y_m * std::tan(g.pose().yaw_rad);
  return c;
}

// How many separate basins the coarse gap has below threshold_m (after lowering by dz).
int CountBasins(const std::vector<double>& gap, double dz, double threshold_m) {
  const double prom = kBasinProminence * threshold_m;
  int basins = 0;
  bool down = true, in_run = false;
  double lo = kInf, hi = -kInf;
  for (double g0 : gap) {
    const double g = g0 - dz;
    if (!(g < threshold_m)) {
      if (in_run && down) ++basins;
      in_run = false;
      down = true;
      lo = kInf;
      continue;
    }
    in_run = true;
    if (down) {
      if (g < lo) {
        lo = g;
      } else if (g > lo + prom) {
        ++basins;
        down = false;
        hi = g;
      }
    } else if (g > hi) {
      hi = g;
    } else if (g < hi - prom) {
      down = true;
      lo = g;
    }
  }
  if (in_run && down) ++basins;
  return basins;
}

// Half the lateral reach [m] of the interpenetration at the vertical approach delta: the run of
// wheel points about the contact's whose lowered coarse gap is below delta.
double InterpenetrationHalfWidth(const TreadPlacement& pl, double delta) {
  const int n = static_cast<int>(pl.coarse_gap.size());
  int lo = pl.best, hi = pl.best;
  while (lo > 0 && pl.coarse_gap[lo - 1] - pl.dz_m < delta) --lo;
  while (hi + 1 < n && pl.coarse_gap[hi + 1] - pl.dz_m < delta) ++hi;
  return 0.5 * std::abs(pl.coarse_y[hi] - pl.coarse_y[lo]);
}

// The patch's conformity as MeasureConformity (model_selection.h) measures it on a placed
// WheelRailGeometry: rail points at arc offsets t in [-b, b] from the contact point, each
// projected onto the wheel's silhouette (Newton on the wheel-profile parameter).
PatchConformity MeasureTreadConformity(const TreadGeometry& g, const TreadPlacement& pl,
                                       const ContactCandidate& c, double b, double K) {
  const Profile& rail = g.rail();
  const Profile& wheel = g.wheel();
  const double dir = rail.Tangent(c.rail_s_m).x() >= 0 ? 1.0 : -1.0;
  const double wdir = g.WheelDirectionToRail(wheel.Tangent(pl.wheel_s_m)).x() >= 0 ? 1.0 : -1.0;
  auto sample = [&](double t) {
    const double s_r = std::clamp(c.rail_s_m + dir * t, 0.0, rail.Length());
    const ProfileFrame fr = FrameAt(rail, s_r);
    const Eigen::Vector2d& p = fr.position;
    // The silhouette point nearest p: (q(s) - p) . T(s) = 0, |dq/ds| about 1.
    double s_w = std::clamp(pl.wheel_s_m + wdir * t, 0.0, wheel.Length());
    Eigen::Vector2d q;
    for (int it = 0; it < 6; ++it) {
      Eigen::Vector2d d1;
      const auto w = g.WheelAt(s_w, &d1);
      q = w.yz_R + Eigen::Vector2d(0.0, pl.dz_m);
      const Eigen::Vector2d T = g.WheelDirectionToRail(d1.normalized());  // Tangent(s_w)
      const double step = (q - p).dot(T);
      s_w = std::clamp(s_w - step, 0.0, wheel.Length());
      if (std::abs(step) < kNewtonTolerance_m) break;
    }
    const ProfileFrame fw = FrameAt(wheel, s_w);
    const Eigen::Vector2d n_w = g.WheelDirectionToRail(g.wheel_sign() * fw.left_normal);
    ConformitySample out;
    const Eigen::Vector2d n_rail = g.rail_sign() * fr.left_normal;
    out.normal = ((1.0 - K) * n_rail - K * n_w).normalized();
    out.gap_m = (p - q).dot(n_w);
    out.k_rail = -g.rail_sign() * fr.curvature;
    out.k_wheel = -g.wheel_sign() * fw.curvature;
    return out;
  };
  return ConformityFromSamples(sample, -b, b);
}

// A planar grid over Hertz's ellipse h at candidate c, carrying Hertz's pressure scaled so that
// the cells carry h.force_N exactly; into patch->grid and patch->pressure_Pa.
void EllipseGrid(const ContactCandidate& c, const internal::Curvatures& k,
                 const HertzSolution& h, const ModelOptions& model, PatchResult* patch) {
  const double a = h.semi_axis_x_m, b = h.semi_axis_y_m;
  const CellSize cell = ChooseCellSize(model, a, b);
  PatchGrid g;
  g.nx = std::max(1, static_cast<int>(std::ceil(2.0 * a / cell.dx_m - 1e-9)));
  g.ns = std::max(1, static_cast<int>(std::ceil(2.0 * b / cell.ds_m - 1e-9)));
  g.dx_m = 2.0 * a / g.nx;
  g.ds_m = 2.0 * b / g.ns;
  g.x0_m = c.x_m - a + 0.5 * g.dx_m;
  g.s0_m = -b + 0.5 * g.ds_m;
  g.planar = true;
  // The tangent toward +y (s grows toward the field side), the normal out of the rail.
  Eigen::Vector2d t(-c.normal.y(), c.normal.x());
  if (t.x() < 0) t = -t;
  g.point_yz_m.resize(g.ns);
  g.tangent_yz.assign(g.ns, t);
  g.normal_yz.assign(g.ns, c.normal);
  for (int j = 0; j < g.ns; ++j) g.point_yz_m[j] = c.rail_point_m + g.S(j) * t;
  g.gap_m.resize(g.cells());
  Eigen::VectorXd p(g.cells());
  double sum = 0.0;
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.X(i) - c.x_m, s = g.S(j);
      const double u = 1.0 - (x * x) / (a * a) - (s * s) / (b * b);
      const int idx = g.Index(i, j);
      p[idx] = u > 0 ? h.p0_Pa * std::sqrt(u) : 0.0;
      g.gap_m[idx] = k.A * x * x + k.B * s * s;  // Hertz's initial gap
      sum += p[idx];
    }
  }
  if (sum > 0) p *= h.force_N / (sum * g.CellArea());
  patch->cells = g.cells();
  patch->cells_in_contact = static_cast<int>((p.array() > 0).count());
  patch->grid = std::move(g);
  patch->pressure_Pa = std::move(p);
}

}  // namespace

bool IsHertzRolling(const ContactProblem& problem) {
  return problem.model.kind == ModelKind::kHertz && problem.rolling.has_value();
}

ModelOptions HertzTreadFallbackModel(const ModelOptions& hertz) {
  ModelOptions m = MakeModelOptions(ModelKind::kAuto);
  m.accuracy = hertz.accuracy;
  m.constants = hertz.constants;
  m.cell_dx_m = hertz.cell_dx_m;
  m.cell_ds_m = hertz.cell_ds_m;
  return m;
}

std::optional<ContactResult> SolveHertzTread(const ContactProblem& problem, std::string* why_not,
                                             HertzTreadPoint* point) {
  const auto t_start = Clock::now();
  internal::CheckContactProblem(problem);
  RAILWEAR_CHECK(IsHertzRolling(problem));
  const RollingOptions& ro = *problem.rolling;
  if (ro.coupling) {
    throw InputError(
        "the coupling effect needs a patch grid: use the halfspace, conformal or auto model, not "
        "hertz");
  }
  internal::CheckRollingProblem(problem, /*hertz_tread=*/true);
  ContactResult result;
  result.model = problem.model;
  auto not_valid = [&](std::string why) {
    if (why_not) *why_not = std::move(why);
    return std::nullopt;
  };

  // 1. Placement.
  const TreadGeometry g(problem.wheel_profile, problem.rail_profile, internal::PoseOf(problem));
  const TreadPlacement pl = Place(g);
  if (!pl.overlap) return not_valid("the wheel and rail profiles do not overlap laterally");
  const ContactCandidate c = CandidateOf(g, pl);
  const double placement_s = SecondsSince(t_start);
  AddStage(&result.stages, "placement", placement_s);
  const auto t_hertz = Clock::now();

  // 2. Hertz at the load (the pressure's vertical part T; the balance below moves it) or the
  // approach.
  const double estar = ContactModulus(problem.wheel_material, problem.rail_material);
  const internal::Curvatures k = internal::CandidateCurvatures(c, problem.placement.roll_rad);
  const HertzShape shape(k.A, k.B);
  const bool load_given = problem.load.vertical_force_N.has_value();
  if ((load_given && !(*problem.load.vertical_force_N > 0)) ||
      (!load_given && !(*problem.load.approach_m > 0))) {
    return not_valid("no load");
  }
  auto hertz_for = [&](double target_N) {
    return load_given ? shape.Solve(estar, target_N / k.w0)
                      : shape.SolveForApproach(estar, *problem.load.approach_m * k.w0);
  };
  const double load_N = load_given ? *problem.load.vertical_force_N : 0.0;
  HertzSolution h = hertz_for(load_N);
  const double vertical_approach = h.approach_m / k.w0;

  // 3. Is it one Hertzian patch?
  const double threshold = kTwoPointMargin * vertical_approach;
  if (CountBasins(pl.coarse_gap, pl.dz_m, threshold) > 1) {
    return not_valid(fmt::format(
        "two-point contact: the gap has a second basin within {:.1f} um (1.5 times the approach) "
        "of first contact",
        threshold * 1e6));
  }
  const double k_w = problem.wheel_material.Compliance();
  const double k_r = problem.rail_material.Compliance();
  // Over the larger of Hertz's lateral semi-axis and the interpenetration's reach / sqrt(2), as
  // kind = auto measures its patch estimate (hertz_estimate.h EstimateSemiAxisS: where the gap
  // flattens beyond Hertz's patch, the patch spreads there).
  const double reach_b = InterpenetrationHalfWidth(pl, vertical_approach) /
                         std::max(k.w0, 0.1) / std::sqrt(2.0);
  const PatchConformity conformity = MeasureTreadConformity(
      g, pl, c, std::max(h.semi_axis_y_m, reach_b), k_r / (k_w + k_r));
  const PatchModelChoice choice =
      ChoosePatchModel(conformity, problem.model, "the fast tread path's gap limit is its own");
  // (A contact steeper than 45 degrees, flange contact, is "conformal" here.)
  if (choice.model == PatchModel::kConformal) return not_valid(choice.reason);
  if (!(conformity.gap_deviation <= kMaxTreadGapDeviation)) {
    return not_valid(fmt::format(
        "non-Hertzian patch: the gap departs from Hertz's quadratic by {:.0f} % over s {:.2f} to "
        "{:.2f} mm (the fast tread path's limit {:.0f} %)",
        100.0 * conformity.gap_deviation, conformity.t_lo_m * 1e3, conformity.t_hi_m * 1e3,
        100.0 * kMaxTreadGapDeviation));
  }

  const std::string valid_reason = fmt::format(
      "fast tread path: one Hertzian patch: over s {:.2f} to {:.2f} mm the gap departs from "
      "Hertz's quadratic by {:.0f} % (limit {:.0f} %), the normal turns by {:.2f} deg and stands "
      "at {:.1f} deg to the vertical",
      conformity.t_lo_m * 1e3, conformity.t_hi_m * 1e3, 100.0 * conformity.gap_deviation,
      100.0 * kMaxTreadGapDeviation, conformity.normal_turn_rad * 180.0 / 3.14159265358979323846,
      conformity.normal_angle_rad * 180.0 / 3.14159265358979323846);

  // 4. The patch and its rolling solution at the pressure's vertical target T.
  const double r0 = problem.placement.rolling_radius_m;
  const Eigen::Vector2d axle_yz = g.WheelToRail({0.0, -r0}, pl.dz_m);
  const Eigen::Vector2d origin_yz = g.WheelToRail({0.0, 0.0}, pl.dz_m);
  auto solve_at = [&](double target_N, std::optional<double> pitch, ContactResult* r) {
    h = hertz_for(target_N);
    PatchResult patch = internal::HertzPatch(c, h);
    patch.model = "hertz";
    patch.model_reason = valid_reason;
    EllipseGrid(c, k, h, problem.model, &patch);
    WheelMotion motion = ro.motion;
    if (pitch) motion.pitch_velocity_rad_s = pitch;
    const RollingInput in =
        ro.creepage ? RigidSlipFromCreepage(patch.grid, patch.pressure_Pa, *ro.creepage,
                                            ro.motion.speed_m_s, ro.friction)
                    : RigidSlipOfMotion(MakeWheelRigidMotion(axle_yz, origin_yz,
                                                             problem.placement.roll_rad,
                                                             problem.placement.yaw_rad, r0, motion),
                                        patch.grid, ro.friction);
    patch.rolling = internal::SolveRollingPatch(problem, patch, in);
    r->patches.assign(1, std::move(patch));
    r->approach_m = h.approach_m / k.w0;
    r->pitch_velocity_rad_s = motion.pitch_velocity_rad_s.value_or(-ro.motion.speed_m_s / r0);
  };
  // With a longitudinal force target, the pitch velocity that carries it (rolling_stage.h).
  bool force_carried = true;
  auto solve_rolling = [&](double target_N, ContactResult* r) {
    if (!ro.longitudinal_force_N) {
      solve_at(target_N, std::nullopt, r);
      return;
    }
    solve_at(target_N, std::nullopt, r);
    const double tolerance = 1e-6 * ro.friction * TotalNormalForce(*r);
    const auto omega = SolvePitchVelocityForForce(
        [&](double w) {
          solve_at(target_N, w, r);
          return TotalForceX(*r);
        },
        *ro.longitudinal_force_N, ro.motion.speed_m_s, r0, tolerance);
    force_carried = omega.has_value();
    if (omega) solve_at(target_N, omega, r);
  };
  result.status = SolverStatus::kConverged;
  solve_rolling(load_N, &result);
  if (load_given && force_carried) {
    // The vertical balance: V_p(T) + V_c(T) = Q (normal_tangential_stage.h).
    internal::BalanceTarget balance(load_N, load_N, internal::kBalanceTolerance);
    for (int it = 0; it < internal::kBalanceMaxIterations; ++it) {
      const ForceParts f = TotalForcesOnRail(result);
      const double residual = f.Net().z() - load_N;
      result.balance_iterations = it;
      result.balance_residual = std::abs(residual) / load_N;
      if (balance.Settled(residual)) break;
      const auto next = balance.Next(residual, 1.0 + f.creep_N.z() / f.normal_N.z());
      if (!next) break;
      if (balance.Stalled()) {
        solve_rolling(balance.Best().first, &result);
        break;
      }
      solve_rolling(*next, &result);
    }
  }
  if (!force_carried) {
    result.status = SolverStatus::kNotConverged;
    result.message = fmt::format(
        "the longitudinal force {:.1f} N cannot be carried: friction limits it to about "
        "{:.1f} N here (mu F_n = {:.1f} N)",
        *ro.longitudinal_force_N, std::abs(TotalForceX(result)),
        ro.friction * TotalNormalForce(result));
  }
  AddStage(&result.stages, "hertz tread", SecondsSince(t_hertz));
  if (point) {
    const auto w = g.WheelAt(pl.wheel_s_m);
    const Eigen::Vector2d p_W = problem.wheel_profile.Position(pl.wheel_s_m);
    point->wheel_x_m = (r0 + p_W.y()) * w.sin_theta;
    point->wheel_y_m = p_W.x();
    point->wheel_z_m = p_W.y();
  }
  result = internal::FinishResult(std::move(result), SecondsSince(t_start));
  result.climb = CheckFlangeClimb(result, ro.friction);
  return result;
}

void MarkTreadFallback(const std::string& why, ContactResult* result) {
  for (PatchResult& patch : result->patches) {
    patch.model_reason = "fast tread path not valid: " + why +
                         (patch.model_reason.empty() ? "" : "; full path: " + patch.model_reason);
  }
}

ContactResult SolveHertzRolling(const ContactProblem& problem, const FullContactSolve& full,
                                std::optional<HertzTreadPoint>* point) {
  const auto t0 = Clock::now();
  std::string why;
  HertzTreadPoint p;
  if (auto fast = SolveHertzTread(problem, &why, &p)) {
    if (point) *point = p;
    return std::move(*fast);
  }
  if (point) point->reset();
  const double check_s = SecondsSince(t0);
  ContactProblem fallback = problem;
  fallback.model = HertzTreadFallbackModel(problem.model);
  ContactResult r = full(fallback);
  MarkTreadFallback(why, &r);
  AddStage(&r.stages, "hertz tread check", check_s);
  r.time_s += check_s;
  return r;
}

}  // namespace railwear
