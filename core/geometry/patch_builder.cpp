// Potential contact area, reference cross-section and initial separation of one patch.
#include "core/geometry/patch_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/numerics/check.h"

namespace railwear {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The lateral walk never leaves this distance from the contact point (beyond any patch).
constexpr double kMaxLateralReach_m = 0.08;

// Cells beyond the largest accepted ns that the size-capped walk goes on for (see 0. in
// BuildPatchGrid): the grid's cells are centred on the contact point and bounded by half cells.
constexpr int kReachMarginCells = 3;

// Cells on either side of the central column for a half-length x_half.
int HalfCells(double x_half_m, double cell_dx_m) {
  const double n = std::ceil(x_half_m / cell_dx_m - 0.5);
  return std::max(1, static_cast<int>(std::min(n, 1e9)));
}

using Section = LateralWalkCache::Section;

// Rail and wheel crossings of the line P_c + tau t0 + lambda n0, near the previous crossing
// (`near`'s, searched within `window` of them, Newton's iteration started at `start`'s:
// CurveLocator::IntersectLineFrom).
bool CrossSection(const WheelRailGeometry& g, const Eigen::Vector2d& pc, const Eigen::Vector2d& t0,
                  const Eigen::Vector2d& n0, double tau, const Section& near, const Section& start,
                  double window, Section* out) {
  const Eigen::Vector2d b = pc + tau * t0;
  auto r =
      g.rail().IntersectLineFrom(b, n0, start.rail_s, near.rail_s - window, near.rail_s + window);
  if (!r) r = g.rail().IntersectLine(b, n0, 0.0, kInf);
  const Eigen::Vector2d b_w = g.RailToWheel(b);
  const Eigen::Vector2d n_w = g.RailDirectionToWheel(n0);
  auto w = g.wheel().IntersectLineFrom(b_w, n_w, start.wheel_s, near.wheel_s - window,
                                       near.wheel_s + window);
  if (!w) w = g.wheel().IntersectLine(b_w, n_w, 0.0, kInf);
  if (!r || !w) return false;
  *out = Section{tau, r->lambda, w->lambda, r->s, w->s};
  return true;
}

// Walks tau outward (sign = +1 or -1) while the normal gap stays below the threshold.
// The walk's sections are those of *side (the ones already walked on that side, from `start`),
// extended as needed; returns how many of them it takes, in order of increasing |tau|
// (excluding tau = 0), and whether it stopped for a geometric limit rather than the threshold.
// After the threshold is passed it goes on for `extra` steps, so that cell centres near the
// edge interpolate the reference curve instead of extrapolating it; *within is the number of
// sections up to the first one past the threshold.
// `reach` (below kMaxLateralReach_m: the memory estimate's bound) ends the walk without either:
// *capped is set, *limited is not.
int Walk(const WheelRailGeometry& g, const Eigen::Vector2d& pc, const Eigen::Vector2d& t0,
         const Eigen::Vector2d& n0, const Section& start, double step, double threshold_n,
         double sign, double y_stop, int extra, double reach, LateralWalkCache::Side* side,
         bool* limited, bool* capped, int* within) {
  std::vector<Section>& walked = side->sections;
  int taken = 0;
  *limited = false;
  *capped = false;
  *within = -1;
  for (int k = 1;; ++k) {
    const double tau = sign * k * step;
    if (std::abs(tau) > kMaxLateralReach_m) {
      *limited = true;
      break;
    }
    if (std::abs(tau) > reach) {
      *capped = true;
      break;
    }
    if (k > static_cast<int>(walked.size())) {  // beyond the sections walked so far
      if (side->ended) {
        *limited = true;
        break;
      }
      const Section prev = k == 1 ? start : walked[k - 2];
      // Newton's start: the crossings extrapolated linearly from the two previous sections.
      const Section before = k <= 2 ? start : walked[k - 3];
      Section guess = prev;
      if (k > 1) {
        guess.rail_s = 2.0 * prev.rail_s - before.rail_s;
        guess.wheel_s = 2.0 * prev.wheel_s - before.wheel_s;
      }
      Section s;
      if (!CrossSection(g, pc, t0, n0, tau, prev, guess, LateralWalkWindow(step), &s)) {
        side->ended = true;
        *limited = true;
        break;
      }
      walked.push_back(s);
    }
    const Section& s = walked[k - 1];
    taken = k;
    // Past the threshold, or past the saddle that separates this patch from its neighbour.
    const double y_rail = (pc + tau * t0 + s.lambda_r * n0).x();
    const bool past_saddle = sign * (y_rail - y_stop) > 0;
    if (*within < 0 && (s.lambda_w - s.lambda_r > threshold_n || past_saddle)) {
      *within = taken;
    }
    if (*within >= 0 && taken >= *within + extra) break;
  }
  if (*within < 0) *within = taken;
  return taken;
}

// The kept walk of candidate c at this step in *cache (emptied first when it was made on
// another geometry), or a new one with its centre section.
LateralWalkCache::Walked* FindWalk(const WheelRailGeometry& g, const ContactCandidate& c,
                                   const Eigen::Vector2d& t0, const Eigen::Vector2d& n0,
                                   double step, LateralWalkCache* cache) {
  if (cache->geometry != &g) {
    cache->walks.clear();
    cache->geometry = &g;
  }
  for (LateralWalkCache::Walked& w : cache->walks) {
    if (w.rail_point_m == c.rail_point_m && w.normal == c.normal && w.rail_s_m == c.rail_s_m &&
        w.wheel_s_m == c.wheel_s_m && w.step_m == step) {
      ++cache->reused;
      return &w;
    }
  }
  LateralWalkCache::Walked w{c.rail_point_m, c.normal,  c.rail_s_m, c.wheel_s_m, step,
                             false,          Section{}, {},         {}};
  Section near;
  near.rail_s = c.rail_s_m;
  near.wheel_s = c.wheel_s_m;
  w.centre_found = CrossSection(g, c.rail_point_m, t0, n0, 0.0, near, near, 1e-3, &w.centre);
  cache->walks.push_back(std::move(w));
  return &cache->walks.back();
}

// Crops `grid` to the bounding box of the cells with gap <= approach * w (w the vertical
// component of the cell normal), widened by kTrimMarginCells and kept symmetric in x about 0.
// False when no cell qualifies.
bool TrimToClosableCells(double approach_m, PatchGrid* grid) {
  PatchGrid& g = *grid;
  int i_lo = g.nx, i_hi = -1, j_lo = g.ns, j_hi = -1;
  for (int j = 0; j < g.ns; ++j) {
    const double w = -g.normal_yz[j].y();
    for (int i = 0; i < g.nx; ++i) {
      if (g.gap_m[g.Index(i, j)] > approach_m * w) continue;
      i_lo = std::min(i_lo, i);
      i_hi = std::max(i_hi, i);
      j_lo = std::min(j_lo, j);
      j_hi = std::max(j_hi, j);
    }
  }
  if (i_hi < 0) return false;
  const int ic = (g.nx - 1) / 2;  // the x = 0 column (grids are symmetric in x)
  const int half = std::min(ic, std::max(ic - i_lo, i_hi - ic) + kTrimMarginCells);
  i_lo = ic - half;
  i_hi = ic + half;
  j_lo = std::max(0, j_lo - kTrimMarginCells);
  j_hi = std::min(g.ns - 1, j_hi + kTrimMarginCells);
  if (i_lo == 0 && i_hi == g.nx - 1 && j_lo == 0 && j_hi == g.ns - 1) return true;
  PatchGrid t;
  t.nx = i_hi - i_lo + 1;
  t.ns = j_hi - j_lo + 1;
  t.dx_m = g.dx_m;
  t.ds_m = g.ds_m;
  t.x0_m = g.X(i_lo);
  t.s0_m = g.S(j_lo);
  t.planar = g.planar;
  t.point_yz_m.assign(g.point_yz_m.begin() + j_lo, g.point_yz_m.begin() + j_hi + 1);
  t.tangent_yz.assign(g.tangent_yz.begin() + j_lo, g.tangent_yz.begin() + j_hi + 1);
  t.normal_yz.assign(g.normal_yz.begin() + j_lo, g.normal_yz.begin() + j_hi + 1);
  t.gap_m.resize(t.cells());
  for (int j = 0; j < t.ns; ++j) {
    for (int i = 0; i < t.nx; ++i) t.gap_m[t.Index(i, j)] = g.gap_m[g.Index(i_lo + i, j_lo + j)];
  }
  *grid = std::move(t);
  return true;
}

// Search windows of the gap projections in profile arc length: wide for the first cell of a
// column, narrow for warm starts from the neighbouring cell (the closest point moves by much
// less than a cell).
double ProjectionWindow(const PatchGrid& grid) { return 3 * grid.ds_m + 1e-3; }
double WarmProjectionWindow(const PatchGrid& grid) {
  return 1e-4 + 0.5 * std::max(grid.dx_m, grid.ds_m);
}

// Step 4 of BuildPatchGrid for the conformal model: seed eq. 2, every cell's signed distance to
// the rail (prismatic) plus to the wheel (revolution), row j's projections searched about
// rail_s[j] and wheel_s[j], marching outward along x from the column ic (at x_contact_m).
void FillConformalGaps(const WheelRailGeometry& g, double x_contact_m, int ic,
                       const std::vector<double>& rail_s, const std::vector<double>& wheel_s,
                       PatchGrid* out) {
  PatchGrid& grid = *out;
  const double window = ProjectionWindow(grid);
  const double warm_window = WarmProjectionWindow(grid);
  grid.gap_m.resize(grid.cells());
  // Without yaw the wheel is a surface of revolution about an axle in the y-z plane, and a
  // point's distance to it depends on x only through |x| (WheelRailGeometry::Meridian: hypot of
  // x and the radial offset). On a grid centred on x = 0 the columns ic - k then take the
  // projections of the columns ic + k (GapsMirroredWithoutYaw). The columns' x are x0 + i dx,
  // mirror images to rounding: a mirrored cell's x may differ from its own by an ulp of x.
  const bool mirrored = g.pose().yaw_rad == 0.0 && x_contact_m == 0.0 && 2 * ic + 1 == grid.nx;
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d p = grid.point_yz_m[j];
    const auto pr = g.ProjectOnRail(p, rail_s[j] - window, rail_s[j] + window);
    const double s_centre =
        g.ProjectOnWheel({x_contact_m, p.x(), p.y()}, wheel_s[j] - window, wheel_s[j] + window).s;
    // Each cell's wheel projection searched about its neighbour's toward the contact column,
    // Newton's iteration started there (extrapolated from the two before; ProjectFrom).
    const CurveLocator& wheel = g.wheel_surface();
    const auto march = [&](int from, int dir) {
      double sg = s_centre, sg_before = s_centre;
      for (int i = from; i >= 0 && i < grid.nx; i += dir) {
        const Eigen::Vector3d q(grid.X(i), p.x(), p.y());
        const auto pw = wheel.ProjectFrom(g.Meridian(q), 2.0 * sg - sg_before, sg - warm_window,
                                          sg + warm_window);
        sg_before = sg;
        sg = pw.s;
        grid.gap_m[grid.Index(i, j)] = pr.signed_distance + pw.signed_distance;
      }
    };
    march(ic, +1);
    if (!mirrored) {
      march(ic - 1, -1);
      continue;
    }
    for (int i = ic - 1; i >= 0; --i) {
      grid.gap_m[grid.Index(i, j)] = grid.gap_m[grid.Index(2 * ic - i, j)];
    }
  }
}

}  // namespace

PatchBuild BuildPatchGrid(const WheelRailGeometry& g, const ContactCandidate& c,
                          const PatchGridOptions& o) {
  RAILWEAR_CHECK(o.cell_dx_m > 0 && o.cell_ds_m > 0 && o.threshold_m > 0);
  PatchBuild build;
  const Eigen::Vector2d n0 = c.normal.normalized();
  const Eigen::Vector2d t0(-n0.y(), n0.x());  // points toward +y when n0 points up
  const double w0 = -n0.y();
  if (w0 < o.min_approach_weight) return build;
  const Eigen::Vector2d pc = c.rail_point_m;
  const double threshold_n = o.threshold_m * w0;
  const bool planar = o.geometry == GeometryModel::kPlanar;

  // 0. The size estimate before the walk (issue 17): the walk steps an eighth of a cell, so a
  // tiny cell made it take minutes and gigabytes before the grid's size was asked. The grid's
  // nx follows from the wheel radius at the contact point (the walk can only raise it, see 3),
  // and the largest ns that size_accepted takes with it bounds how far the walk needs to go: a
  // patch that still lies within the threshold beyond (ns_max + kReachMarginCells) cells of
  // the contact point on one side alone has more than ns_max cells (the reference curve's arc
  // is at least the walk's |tau|). Exact: no grid the caller would accept is refused.
  double reach = kMaxLateralReach_m;
  PatchGrid sized;
  sized.planar = planar;
  sized.dx_m = o.cell_dx_m;
  sized.ds_m = o.cell_ds_m;
  sized.nx = 2 * HalfCells(std::sqrt(2.0 * c.wheel_radius_m * o.threshold_m), o.cell_dx_m) + 1;
  if (o.size_accepted) {
    const double widest = std::ceil(2.0 * kMaxLateralReach_m / o.cell_ds_m) + 1.0;
    const int ns_reach = static_cast<int>(std::min(widest, 1e9));
    sized.ns = 1;
    if (!o.size_accepted(sized)) {  // not even one row of cells
      build.grid = sized;
      build.too_large = true;
      return build;
    }
    sized.ns = ns_reach;
    if (!o.size_accepted(sized)) {
      int lo = 1, hi = ns_reach;  // lo accepted, hi refused
      while (hi - lo > 1) {
        sized.ns = lo + (hi - lo) / 2;
        (o.size_accepted(sized) ? lo : hi) = sized.ns;
      }
      reach = std::min(reach, (lo + kReachMarginCells) * o.cell_ds_m);
      sized.ns = lo + kReachMarginCells;  // what a walk cut at `reach` shows at least
    }
  }

  // 1. Lateral walk along t0 at x = 0 (or the part of a kept one it needs, LateralWalkCache).
  const double step = std::min(o.cell_ds_m / 8.0, 2e-5);
  LateralWalkCache own;  // (without a cache: kept for this grid only)
  LateralWalkCache::Walked* walk = FindWalk(g, c, t0, n0, step, o.walks ? o.walks : &own);
  if (!walk->centre_found) return build;
  const Section centre = walk->centre;
  bool lim_lo = false, lim_hi = false, cap_lo = false, cap_hi = false;
  int within_lo = 0, within_hi = 0;
  const int extra = static_cast<int>(std::ceil(o.cell_ds_m / step)) + 2;
  const double y_stop_lo = c.split_lo ? c.y_lo_m : -kInf;
  const double y_stop_hi = c.split_hi ? c.y_hi_m : kInf;
  const int n_lo = Walk(g, pc, t0, n0, centre, step, threshold_n, -1.0, y_stop_lo, extra, reach,
                        &walk->lo, &lim_lo, &cap_lo, &within_lo);
  const int n_hi = Walk(g, pc, t0, n0, centre, step, threshold_n, +1.0, y_stop_hi, extra, reach,
                        &walk->hi, &lim_hi, &cap_hi, &within_hi);
  std::vector<Section> sections(walk->lo.sections.rend() - n_lo, walk->lo.sections.rend());
  sections.push_back(centre);
  sections.insert(sections.end(), walk->hi.sections.begin(), walk->hi.sections.begin() + n_hi);
  const int centre_index = n_lo;

  // 2. Reference curve samples (rail frame) and their arc length, 0 at the contact point.
  const double K = o.stiffness_ratio_K;
  const int m = static_cast<int>(sections.size());
  std::vector<Eigen::Vector2d> curve(m);
  std::vector<double> arc(m, 0.0);
  for (int k = 0; k < m; ++k) {
    const Section& s = sections[k];
    const double lambda = planar ? 0.0 : K * s.lambda_w + (1.0 - K) * s.lambda_r;
    curve[k] = pc + s.tau * t0 + lambda * n0;
    if (k > 0) arc[k] = arc[k - 1] + (curve[k] - curve[k - 1]).norm();
  }
  const double arc0 = arc[centre_index];
  for (double& a : arc) a -= arc0;

  // Keep only the part where the reference normal lets a vertical approach close the gap.
  auto tangent_at = [&](int k) {
    const int a = std::max(0, k - 1), b = std::min(m - 1, k + 1);
    return (curve[b] - curve[a]).normalized().eval();
  };
  // Sections inside the threshold (plus the first one past it) bound the cells.
  int k_lo = centre_index - within_lo, k_hi = centre_index + within_hi;
  for (int k = centre_index; k >= k_lo; --k) {
    if (tangent_at(k).x() < o.min_approach_weight) {
      k_lo = k + 1;
      lim_lo = true;
      break;
    }
  }
  for (int k = centre_index; k <= k_hi; ++k) {
    if (tangent_at(k).x() < o.min_approach_weight) {
      k_hi = k - 1;
      lim_hi = true;
      break;
    }
  }
  if (k_hi <= k_lo) return build;
  // A walk cut at `reach` whose steep-normal limit does not end the range before its last
  // section: the patch goes on beyond, wider than the grid the caller accepts.
  if ((cap_lo && k_lo == 0) || (cap_hi && k_hi == m - 1)) {
    build.grid = sized;
    build.too_large = true;
    return build;
  }
  build.lateral_limited = lim_lo || lim_hi;

  // 3. Cells: one centred on the contact point in s and on x = 0.
  PatchGrid& grid = build.grid;
  grid.planar = planar;
  grid.dx_m = o.cell_dx_m;
  grid.ds_m = o.cell_ds_m;
  const int j_lo = static_cast<int>(std::floor(arc[k_lo] / o.cell_ds_m + 0.5));
  const int j_hi = static_cast<int>(std::ceil(arc[k_hi] / o.cell_ds_m - 0.5));
  grid.ns = std::max(1, j_hi - j_lo + 1);
  grid.s0_m = j_lo * o.cell_ds_m;
  // A row of cells at s lies on the reference curve's segment k (linear between samples; rows up
  // to half a cell beyond the sampled range extrapolate the end segment), with that segment's
  // normal on n0's side.
  auto segment_at = [&](double s) {
    return std::clamp(
        static_cast<int>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin()) - 1, 0, m - 2);
  };
  auto segment_normal = [&](int k) {
    const Eigen::Vector2d t = (curve[k + 1] - curve[k]).normalized();
    Eigen::Vector2d n(-t.y(), t.x());
    if (n.dot(n0) < 0) n = -n;
    return n;
  };
  // The range above is judged on the samples' central differences; a row at its end takes the
  // segment beyond, whose normal can turn past horizontal on a rippled profile (a cell a
  // vertical approach cannot close, which the normal solver refuses: tests/tools/
  // api_call_search's sequence 2104). The grid ends before such a row.
  if (!planar) {
    auto closable = [&](int j) { return -segment_normal(segment_at(grid.S(j))).y() > 0.0; };
    const int j_contact = std::clamp(-j_lo, 0, grid.ns - 1);  // the row at s = 0
    if (!closable(j_contact)) return build;
    int first = j_contact, last = j_contact;
    while (first > 0 && closable(first - 1)) --first;
    while (last < grid.ns - 1 && closable(last + 1)) ++last;
    if (first > 0 || last < grid.ns - 1) {
      grid.s0_m = grid.S(first);
      grid.ns = last - first + 1;
      build.lateral_limited = true;
    }
  }
  double r_max = c.wheel_radius_m;
  for (int k = k_lo; k <= k_hi; ++k) {
    const double r =
        g.pose().rolling_radius_m + g.wheel().profile().Position(sections[k].wheel_s).y();
    r_max = std::max(r_max, r);
  }
  const double x_half = std::sqrt(2.0 * r_max * o.threshold_m);
  const int half_cells = HalfCells(x_half, o.cell_dx_m);
  grid.nx = 2 * half_cells + 1;
  // Centred on the contact point's x: ahead of or behind the axle for a yawed wheel (0 without).
  grid.x0_m = c.x_m - half_cells * o.cell_dx_m;

  if (o.size_accepted && !o.size_accepted(grid)) {
    build.too_large = true;
    return build;
  }

  grid.point_yz_m.resize(grid.ns);
  grid.tangent_yz.resize(grid.ns);
  grid.normal_yz.resize(grid.ns);
  std::vector<double> rail_s(grid.ns), wheel_s(grid.ns), lambda_r(grid.ns), lambda_w(grid.ns);
  for (int j = 0; j < grid.ns; ++j) {
    const double s = grid.S(j);
    // Locate s on the sampled reference curve (linear between samples).
    const int k = segment_at(s);
    const double f = (s - arc[k]) / (arc[k + 1] - arc[k]);
    grid.point_yz_m[j] = planar ? Eigen::Vector2d(pc + s * t0)
                                : Eigen::Vector2d(curve[k] + f * (curve[k + 1] - curve[k]));
    grid.tangent_yz[j] = planar ? t0 : Eigen::Vector2d((curve[k + 1] - curve[k]).normalized());
    grid.normal_yz[j] = planar ? n0 : segment_normal(k);
    rail_s[j] = sections[k].rail_s;
    // The wheel search windows are on the wheel profile (the body of revolution), whose
    // parameter differs from the yawed outline's that the sections walked along.
    wheel_s[j] = g.SurfaceSource(sections[k].wheel_s).wheel_s_m;
    lambda_r[j] = sections[k].lambda_r + f * (sections[k + 1].lambda_r - sections[k].lambda_r);
    lambda_w[j] = sections[k].lambda_w + f * (sections[k + 1].lambda_w - sections[k].lambda_w);
  }

  // 4. Initial separation per cell.
  grid.gap_m.resize(grid.cells());
  const double window = ProjectionWindow(grid);
  const double warm_window = WarmProjectionWindow(grid);
  const int ic = half_cells;  // the column through the contact point (x = c.x_m)
  // x of the lowest point of the wheel's parallel circle through the contact point: the axle
  // line there (the contact point leads it by c.lead_m; both 0 without yaw).
  const double x_axle = c.x_m - c.lead_m;
  if (!planar) {
    FillConformalGaps(g, c.x_m, ic, rail_s, wheel_s, &grid);
  } else {
    for (int j = 0; j < grid.ns; ++j) {
      // Model A: gap along n0 between the rail line crossing and the wheel surface at x.
      const Eigen::Vector2d b = pc + (grid.S(j)) * t0;
      const auto rail_cross = g.rail().IntersectLine(b, n0, rail_s[j] - window, rail_s[j] + window);
      const double lr = rail_cross ? rail_cross->lambda : lambda_r[j];
      const double s_centre =
          g.ProjectOnWheel({c.x_m, (b + lambda_w[j] * n0).x(), (b + lambda_w[j] * n0).y()},
                           wheel_s[j] - window, wheel_s[j] + window)
              .s;
      // March outward from the x = 0 column, each column starting from its neighbour's root and
      // closest wheel point: the closest point moves along the flange as the wheel lifts with
      // |x|, by far more than one search window over the whole grid on a steep flange (a window
      // fixed at the centre column's point made the far columns' gaps negative there).
      for (int dir : {+1, -1}) {
        double sg = s_centre;
        double root = lambda_w[j];
        for (int i = (dir > 0 ? ic : ic - 1); i >= 0 && i < grid.nx; i += dir) {
          const double x = grid.X(i);
          const double x_prev = i == ic ? c.x_m : grid.X(i - dir);
          // Root of the wheel's signed distance along the line (x, b + lambda n0); secant steps
          // from the neighbour's root plus the change of a body of revolution's lift.
          double s_found = sg;
          auto dist = [&](double lambda) {
            const Eigen::Vector2d yz = b + lambda * n0;
            const auto pw =
                g.ProjectOnWheel({x, yz.x(), yz.y()}, sg - warm_window, sg + warm_window);
            s_found = pw.s;
            return pw.signed_distance;
          };
          const double u = x - x_axle, u_prev = x_prev - x_axle;
          double l0 = root + (u * u - u_prev * u_prev) * w0 / (2.0 * r_max);
          double f0 = dist(l0);
          double l1 = l0 + f0, f1 = dist(l1);
          for (int it = 0; it < 30 && std::abs(f1) > 1e-13; ++it) {
            const double slope = (f1 - f0) / (l1 - l0);
            const double l2 = (slope != 0) ? l1 - f1 / slope : l1 + f1;
            l0 = l1;
            f0 = f1;
            l1 = l2;
            f1 = dist(l1);
            if (std::abs(l1 - l0) < 1e-13) break;
          }
          root = l1;
          sg = s_found;
          grid.gap_m[grid.Index(i, j)] = l1 - lr;
        }
      }
    }
  }

  const double s0_untrimmed = grid.s0_m;
  if (std::isfinite(o.trim_approach_m)) {
    if (!TrimToClosableCells(o.trim_approach_m, &grid)) return build;  // nothing can touch
    build.trimmed = true;
  }
  if (!planar) {
    const int j0 = static_cast<int>(std::lround((grid.s0_m - s0_untrimmed) / grid.ds_m));
    build.rail_s_m.assign(rail_s.begin() + j0, rail_s.begin() + j0 + grid.ns);
    build.wheel_s_m.assign(wheel_s.begin() + j0, wheel_s.begin() + j0 + grid.ns);
    build.x_contact_m = c.x_m;
  }
  build.valid = true;
  return build;
}

bool UpdateConformalGaps(const WheelRailGeometry& g, PatchBuild* build) {
  PatchGrid& grid = build->grid;
  if (!build->valid || grid.planar || static_cast<int>(build->rail_s_m.size()) != grid.ns) {
    return false;
  }
  FillConformalGaps(g, build->x_contact_m, (grid.nx - 1) / 2, build->rail_s_m, build->wheel_s_m,
                    &grid);
  return true;
}

}  // namespace railwear
