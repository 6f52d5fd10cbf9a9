// Closest-point and line-crossing queries on a profile spline (coarse scan + safeguarded Newton).
#include "core/geometry/curve_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/numerics/check.h"
#include "core/profile/profile_keyed_cache.h"

namespace railwear {

namespace {

// Rounding margin of the block tests, relative to the size of the coordinates: (p - b) . t and
// |p - q|^2 carry a relative rounding error of a few ulp (~1e-15), so a box must clear the line
// or the best distance by far more than that before its block is skipped. Any value from 1e-13 up
// keeps the answers exact; a larger one only skips fewer blocks.
constexpr double kCullMargin = 1e-12;
// Relative margin of the profile's bounds (ProjectFrom, IntersectLineFrom) and of the tests
// made with them: far above their rounding (1e-15), far below any margin that would matter.
constexpr double kBoundsMargin = 1e-9;
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

struct CurveLocator::Samples {
  double step = 0.0;
  double outward_sign = 1.0;
  std::vector<double> s;
  std::vector<Eigen::Vector2d> p;
  std::vector<Eigen::Vector2d> box_lo, box_hi;
  std::vector<CurveLocator::Bounds> bounds;  // per block
  double max_abs_coordinate = 0.0;
};

namespace {

// The samples of `profile` every sample_step_m (rounded to divide its length), its orientation,
// and the boxes of the blocks of kScanBlock samples.
template <class Samples>
std::shared_ptr<const Samples> SampleProfile(const Profile& profile, bool material_toward_plus_z,
                                             double sample_step_m, int block) {
  auto out = std::make_shared<Samples>();
  const double length = profile.Length();
  const int n = std::max(2, static_cast<int>(std::ceil(length / sample_step_m)) + 1);
  out->step = length / (n - 1);
  std::vector<double>& sample_s = out->s;
  std::vector<Eigen::Vector2d>& sample_p = out->p;
  sample_s.resize(n);
  sample_p.resize(n);
  // The profile's first and second derivatives at the samples, for the blocks' bounds.
  std::vector<Eigen::Vector2d> d1(n), d2(n);
  for (int i = 0; i < n; ++i) {
    sample_s[i] = i * out->step;
    profile.Evaluate(sample_s[i], &sample_p[i], &d1[i], &d2[i]);
  }
  // Orientation: at the surface point facing away from the material (the top of a rail, the
  // bottom of a wheel), the outward normal points to -z for a rail and to +z for a wheel.
  int extreme = 0;
  for (int i = 1; i < n; ++i) {
    const bool better = material_toward_plus_z ? sample_p[i].y() < sample_p[extreme].y()
                                               : sample_p[i].y() > sample_p[extreme].y();
    if (better) extreme = i;
  }
  const double nz = profile.LeftNormal(sample_s[extreme]).y();
  const bool left_points_up = nz < 0.0;
  out->outward_sign = (material_toward_plus_z == left_points_up) ? 1.0 : -1.0;
  const int blocks = (n - 2) / block + 1;  // block k starts at k block <= n - 2
  out->box_lo.resize(blocks);
  out->box_hi.resize(blocks);
  for (int k = 0; k < blocks; ++k) {
    const int first = k * block, last = std::min(first + block, n - 1);
    Eigen::Vector2d lo = sample_p[first], hi = sample_p[first];
    for (int i = first + 1; i <= last; ++i) {
      lo = lo.cwiseMin(sample_p[i]);
      hi = hi.cwiseMax(sample_p[i]);
    }
    out->box_lo[k] = lo;
    out->box_hi[k] = hi;
    out->max_abs_coordinate =
        std::max({out->max_abs_coordinate, lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()});
  }
  // Bounds of the blocks' arcs [s_first, s_last]: C'' is linear in s between the spline's knots,
  // so |C''| (convex there) is largest at a sample or a knot; |C'| changes by at most
  // max |C''| |ds| within half a step of a sample.
  out->bounds.resize(blocks);
  for (int k = 0; k < blocks; ++k) {
    const int first = k * block, last = std::min(first + block, n - 1);
    double d2_max = 0.0, v_min = kInf, v_max = 0.0;
    for (int i = first; i <= last; ++i) {
      d2_max = std::max(d2_max, d2[i].norm());
      v_min = std::min(v_min, d1[i].norm());
      v_max = std::max(v_max, d1[i].norm());
    }
    out->bounds[k] = {d2_max, v_min, v_max};
  }
  const double block_length = block * out->step;
  for (int j = 0; j < static_cast<int>(profile.points().size()); ++j) {
    const double s = profile.KnotS(j);
    Eigen::Vector2d knot_d2;
    profile.Evaluate(s, nullptr, nullptr, &knot_d2);
    // Every block whose arc holds the knot (two where it is a block's end).
    const int k_hi = std::min(blocks - 1, static_cast<int>(s / block_length));
    for (int k = std::max(0, k_hi - 1); k <= k_hi; ++k) {
      if (s >= k * block_length - out->step && s <= (k + 1) * block_length + out->step) {
        out->bounds[k].d2_max = std::max(out->bounds[k].d2_max, knot_d2.norm());
      }
    }
  }
  for (auto& b : out->bounds) {
    // Rounding margins: the norms above carry a relative error of some 1e-16.
    b.d2_max *= 1.0 + kBoundsMargin;
    b.speed_min = b.speed_min * (1.0 - kBoundsMargin) - 0.5 * out->step * b.d2_max;
    b.speed_max = b.speed_max * (1.0 + kBoundsMargin) + 0.5 * out->step * b.d2_max;
  }
  return out;
}

}  // namespace

CurveLocator::CurveLocator(const Profile& profile, bool material_toward_plus_z,
                           double sample_step_m, Scan scan)
    : profile_(&profile), length_(profile.Length()), scan_(scan) {
  RAILWEAR_CHECK(sample_step_m > 0 && length_ > 0);
  static ProfileKeyedCache<Samples> shared(kSharedSampleSets);
  samples_ = shared.Get(profile, {material_toward_plus_z ? 1u : 0u, DoubleBits(sample_step_m)}, {},
                        [&] {
                          return SampleProfile<Samples>(profile, material_toward_plus_z,
                                                        sample_step_m, kScanBlock);
                        });
  step_ = samples_->step;
  outward_sign_ = samples_->outward_sign;
  n_samples_ = static_cast<int>(samples_->s.size());
  sample_s_ = samples_->s.data();
  sample_p_ = samples_->p.data();
  n_boxes_ = static_cast<int>(samples_->box_lo.size());
  box_lo_ = samples_->box_lo.data();
  box_hi_ = samples_->box_hi.data();
  block_bounds_ = samples_->bounds.data();
  max_abs_coordinate_ = samples_->max_abs_coordinate;
}

double CurveLocator::BlockDistance2(int k, const Eigen::Vector2d& q) const {
  const Eigen::Vector2d below = box_lo_[k] - q, above = q - box_hi_[k];
  const Eigen::Vector2d d = below.cwiseMax(above).cwiseMax(0.0);
  return d.squaredNorm();
}

bool CurveLocator::BlockOnOneSide(int k, const Eigen::Vector2d& b, const Eigen::Vector2d& t,
                                  double margin) const {
  const Eigen::Vector2d lo = box_lo_[k] - b, hi = box_hi_[k] - b;
  // (p - b) . t is linear in p: its extremes over the box are at corners.
  const double y_min = t.x() >= 0 ? lo.x() * t.x() : hi.x() * t.x();
  const double y_max = t.x() >= 0 ? hi.x() * t.x() : lo.x() * t.x();
  const double z_min = t.y() >= 0 ? lo.y() * t.y() : hi.y() * t.y();
  const double z_max = t.y() >= 0 ? hi.y() * t.y() : lo.y() * t.y();
  return y_min + z_min > margin || y_max + z_max < -margin;
}

int CurveLocator::ClosestSample(const Eigen::Vector2d& q, int i0, int i1) const {
  int best = i0;
  double best_d2 = std::numeric_limits<double>::infinity();
  if (scan_ == Scan::kEverySample) {
    for (int i = i0; i <= i1; ++i) {
      const double d2 = (sample_p_[i] - q).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best = i;
      }
    }
    return best;
  }
  // The sample scan keeps the first of the smallest distances: the least (d2, i). Taking that
  // least pair is independent of the order of visits, so the block nearest q goes first and the
  // others only where their boxes could hold a pair as small.
  auto visit = [&](int first, int last) {
    for (int i = first; i <= last; ++i) {
      const double d2 = (sample_p_[i] - q).squaredNorm();
      if (d2 < best_d2 || (d2 == best_d2 && i < best)) {
        best_d2 = d2;
        best = i;
      }
    }
  };
  // Block k's own samples here are [k kScanBlock, (k + 1) kScanBlock - 1] within [i0, i1].
  const int k0 = i0 / kScanBlock, k1 = i1 / kScanBlock;
  auto own = [&](int k, int* first, int* last) {
    *first = std::max(i0, k * kScanBlock);
    *last = std::min(i1, (k + 1) * kScanBlock - 1);
  };
  const int last_box = n_boxes_ - 1;
  int nearest = k0;
  double nearest_d2 = std::numeric_limits<double>::infinity();
  for (int k = k0; k <= k1; ++k) {
    const double d2 = BlockDistance2(std::min(k, last_box), q);
    if (d2 < nearest_d2) {
      nearest_d2 = d2;
      nearest = k;
    }
  }
  int first = 0, last = 0;
  own(nearest, &first, &last);
  visit(first, last);
  for (int k = k0; k <= k1; ++k) {
    if (k == nearest) continue;
    // Skip when every sample of the box is farther than the best by more than rounding.
    if (BlockDistance2(std::min(k, last_box), q) * (1.0 - kCullMargin) > best_d2) continue;
    own(k, &first, &last);
    visit(first, last);
  }
  return best;
}

Eigen::Vector2d CurveLocator::OutwardNormal(double s) const {
  return outward_sign_ * profile_->LeftNormal(s);
}

double CurveLocator::RefineClosest(const Eigen::Vector2d& q, double s0, double lo, double hi,
                                   Eigen::Vector2d* c_at, Eigen::Vector2d* d1_at,
                                   bool* evaluated) const {
  // Minimise |C(s) - q|^2: root of g(s) = (C - q) . C', g' = |C'|^2 + (C - q) . C''.
  lo = std::max(lo, 0.0);
  hi = std::min(hi, length_);
  double s = std::clamp(s0, lo, hi);
  *evaluated = false;
  for (int it = 0; it < 50; ++it) {
    Eigen::Vector2d c, d1, d2;
    profile_->Evaluate(s, &c, &d1, &d2);
    const Eigen::Vector2d r = c - q;
    const double g = r.dot(d1);
    // Exactly at the closest point (common on straight pieces), or converged when the Newton
    // step is below tolerance — tested before the bracket, because a step below one ulp leaves
    // s on the bracket end just set and would fall back to bisection. s is the point just
    // evaluated: its position and derivative go back with it.
    const double gp = d1.squaredNorm() + r.dot(d2);
    if (g == 0.0 || (gp > 0 && std::abs(g / gp) < kParameterTolerance_m)) {
      *c_at = c;
      *d1_at = d1;
      *evaluated = true;
      break;
    }
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
  const auto [i0, i1] = SampleRange(s_lo, s_hi);
  const int best = ClosestSample(q, i0, i1);
  Eigen::Vector2d point, d1;
  bool evaluated = false;
  const double s = RefineClosest(q, sample_s_[best], std::max(s_lo, sample_s_[best] - step_),
                                 std::min(s_hi, sample_s_[best] + step_), &point, &d1, &evaluated);
  // The position and derivative at s (the refinement's last evaluation when it ended on one):
  // the values Position(s) and OutwardNormal(s) give, bit for bit.
  if (!evaluated) profile_->Evaluate(s, &point, &d1, nullptr);
  return MakeProjection(q, s, point, d1);
}

CurveLocator::Projection CurveLocator::MakeProjection(const Eigen::Vector2d& q, double s,
                                                      const Eigen::Vector2d& c,
                                                      const Eigen::Vector2d& d1) const {
  const Eigen::Vector2d t = d1.normalized();
  const Eigen::Vector2d outward = outward_sign_ * Eigen::Vector2d(-t.y(), t.x());
  Projection p;
  p.s = s;
  p.point = c;
  const double dist = (q - p.point).norm();
  p.signed_distance = (q - p.point).dot(outward) >= 0 ? dist : -dist;
  return p;
}

std::pair<int, int> CurveLocator::SampleRange(double s_lo, double s_hi) const {
  return {std::clamp(static_cast<int>(std::floor(s_lo / step_)), 0, n_samples_ - 1),
          std::clamp(static_cast<int>(std::ceil(s_hi / step_)), 0, n_samples_ - 1)};
}

CurveLocator::Bounds CurveLocator::BlockBounds(int k0, int k1) const {
  k0 = std::clamp(k0, 0, n_boxes_ - 1);
  k1 = std::clamp(k1, 0, n_boxes_ - 1);
  Bounds b = block_bounds_[k0];
  for (int k = k0 + 1; k <= k1; ++k) {
    b.d2_max = std::max(b.d2_max, block_bounds_[k].d2_max);
    b.speed_min = std::min(b.speed_min, block_bounds_[k].speed_min);
    b.speed_max = std::max(b.speed_max, block_bounds_[k].speed_max);
  }
  return b;
}

CurveLocator::Projection CurveLocator::ProjectFrom(const Eigen::Vector2d& q, double s_start,
                                                   double s_lo, double s_hi) const {
  const double lo = std::max(0.0, s_lo), hi = std::min(length_, s_hi);
  if (lo < hi && s_start > lo && s_start < hi) {
    Eigen::Vector2d point, d1;
    bool evaluated = false;
    const double s = RefineClosest(q, s_start, lo, hi, &point, &d1, &evaluated);
    // A root of g inside the window (by more than the tolerance it is known to), and g' > 0 over
    // the samples Project would scan, [s_i0, s_i1]: |C(s') - q| <= |C(s) - q| + v_max |s' - s|,
    // so g' >= v_min^2 - (|C(s) - q| + v_max reach) max |C''| > 0. Then the distance has this
    // one critical point there, a minimum, which the scan's closest sample brackets.
    if (evaluated && s - lo > 2 * kParameterTolerance_m && hi - s > 2 * kParameterTolerance_m) {
      const auto [i0, i1] = SampleRange(lo, hi);
      const Bounds b = BlockBounds(i0 / kScanBlock, (i1 - 1) / kScanBlock);
      const double reach = std::max(s - sample_s_[i0], sample_s_[i1] - s);
      const double far = (point - q).norm() + b.speed_max * reach;
      if (b.speed_min > 0 && far * b.d2_max < (1.0 - kBoundsMargin) * b.speed_min * b.speed_min) {
        return MakeProjection(q, s, point, d1);
      }
    }
  }
  return Project(q, s_lo, s_hi);
}

CurveLocator::Crossing CurveLocator::RefineCrossing(const Eigen::Vector2d& b,
                                                    const Eigen::Vector2d& n,
                                                    const Eigen::Vector2d& t, int i, double prev,
                                                    double cur) const {
  const double lo = sample_s_[i - 1], hi = sample_s_[i];
  const double s = (prev == cur) ? lo : lo + (hi - lo) * prev / (prev - cur);  // the chord's root
  bool converged = false;
  double slope = 0.0;
  return RefineCrossingFrom(b, n, t, s, lo, hi, prev, &converged, &slope);
}

CurveLocator::Crossing CurveLocator::RefineCrossingFrom(const Eigen::Vector2d& b,
                                                        const Eigen::Vector2d& n,
                                                        const Eigen::Vector2d& t, double s,
                                                        double lo, double hi, double flo,
                                                        bool* converged, double* slope) const {
  // Bisection-safeguarded Newton on phi(s) = (C(s) - b) . t in [lo, hi].
  *converged = false;
  for (int it = 0; it < 60; ++it) {
    Eigen::Vector2d c, d1;
    profile_->Evaluate(s, &c, &d1, nullptr);
    const double f = (c - b).dot(t);
    const double fp = d1.dot(t);
    // Ended on the point just evaluated: its position gives lambda (Position(s) bit for bit).
    if (f == 0.0) {
      *converged = true;
      *slope = fp;
      return Crossing{s, (c - b).dot(n)};
    }
    if ((f <= 0) == (flo <= 0)) {
      lo = s;
      flo = f;
    } else {
      hi = s;
    }
    if (fp != 0 && std::abs(f / fp) < kParameterTolerance_m) {  // as in RefineClosest
      *converged = true;
      *slope = fp;
      return Crossing{s, (c - b).dot(n)};
    }
    double next = (fp != 0) ? s - f / fp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - s);
    s = next;
    if (step < kParameterTolerance_m || hi - lo < kParameterTolerance_m) break;
  }
  return Crossing{s, (profile_->Position(s) - b).dot(n)};
}

std::optional<CurveLocator::Crossing> CurveLocator::IntersectLineFrom(const Eigen::Vector2d& b,
                                                                      const Eigen::Vector2d& n,
                                                                      double s_start, double s_lo,
                                                                      double s_hi) const {
  const Eigen::Vector2d t(n.y(), -n.x());
  const double lo = std::max(0.0, s_lo), hi = std::min(length_, s_hi);
  const auto [i0, i1] = SampleRange(lo, hi);
  // The scan's samples [s_i0, s_i1] bracket a crossing at their ends: then Newton's iteration
  // from s_start inside that bracket.
  const double f0 = (sample_p_[i0] - b).dot(t), f1 = (sample_p_[i1] - b).dot(t);
  const double a = sample_s_[i0], z = sample_s_[i1];
  if (i0 < i1 && ((f0 < 0 && f1 > 0) || (f0 > 0 && f1 < 0)) && s_start > a && s_start < z) {
    bool converged = false;
    double slope = 0.0;
    const Crossing c = RefineCrossingFrom(b, n, t, s_start, a, z, f0, &converged, &slope);
    // phi' = C' . t >= |phi'(s)| - max |C''| |s' - s| keeps phi's sign over [s_i0, s_i1]: phi is
    // monotonic there, and this is the one crossing the scan would find.
    if (converged && c.s - a > 2 * kParameterTolerance_m && z - c.s > 2 * kParameterTolerance_m) {
      const Bounds bd = BlockBounds(i0 / kScanBlock, (i1 - 1) / kScanBlock);
      const double reach = std::max(c.s - a, z - c.s);
      if (std::abs(slope) * (1.0 - kBoundsMargin) > bd.d2_max * reach) return c;
    }
  }
  return IntersectLine(b, n, s_lo, s_hi);
}

std::optional<CurveLocator::Crossing> CurveLocator::IntersectLine(const Eigen::Vector2d& b,
                                                                  const Eigen::Vector2d& n,
                                                                  double s_lo, double s_hi) const {
  // Points of the line satisfy (C - b) . t = 0 with t perpendicular to n.
  const Eigen::Vector2d t(n.y(), -n.x());
  s_lo = std::max(0.0, s_lo);
  s_hi = std::min(length_, s_hi);
  const auto [i0, i1] = SampleRange(s_lo, s_hi);
  std::optional<Crossing> best;
  // Neighbours (i - 1, i) whose values (p - b) . t change sign (or touch zero) bracket a
  // crossing; each is refined and the one with the smallest |lambda| kept.
  auto scan = [&](int first, int last, double prev) {
    for (int i = first; i <= last; ++i) {
      const double cur = (sample_p_[i] - b).dot(t);
      if ((prev <= 0 && cur >= 0) || (prev >= 0 && cur <= 0)) {
        const Crossing c = RefineCrossing(b, n, t, i, prev, cur);
        if (!best || std::abs(c.lambda) < std::abs(best->lambda)) best = c;
      }
      prev = cur;
    }
  };
  if (scan_ == Scan::kEverySample) {
    scan(i0 + 1, i1, (sample_p_[i0] - b).dot(t));
    return best;
  }
  // Pairs (i - 1, i) with i in (k kScanBlock, (k + 1) kScanBlock] lie in block k. A block whose
  // box is strictly on one side of the line (beyond the rounding margin) has all its values of
  // one strict sign: none of its pairs brackets a crossing.
  const double margin = kCullMargin * (1.0 + b.cwiseAbs().maxCoeff() + max_abs_coordinate_);
  for (int i = i0 + 1; i <= i1;) {
    const int k = (i - 1) / kScanBlock;
    const int last = std::min((k + 1) * kScanBlock, i1);
    if (!BlockOnOneSide(k, b, t, margin)) scan(i, last, (sample_p_[i - 1] - b).dot(t));
    i = last + 1;
  }
  return best;
}

}  // namespace railwear
