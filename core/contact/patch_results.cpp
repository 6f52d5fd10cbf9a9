// The patch-results stage of SolveContact (patch_results.h).
#include "core/contact/patch_results.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/contact/contact_forces.h"

namespace railwear::internal {

Extent MeasureExtent(const PatchGrid& g, const Eigen::Ref<const Eigen::VectorXd>& p) {
  Extent e;
  double s_lo = 1e300, s_hi = -1e300;
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (p[g.Index(i, j)] <= 0) continue;
      ++e.cells;
      e.half_x = std::max(e.half_x, std::abs(g.X(i)) + 0.5 * g.dx_m);
      s_lo = std::min(s_lo, g.S(j) - 0.5 * g.ds_m);
      s_hi = std::max(s_hi, g.S(j) + 0.5 * g.ds_m);
      if (i == 0 || i == g.nx - 1) e.touches_x_edge = true;
      if (j == 0 || j == g.ns - 1) e.touches_s_edge = true;
    }
  }
  if (e.cells > 0) {
    e.half_s = 0.5 * (s_hi - s_lo);
    e.s_lo = s_lo;
    e.s_hi = s_hi;
  }
  return e;
}

namespace {

// The bilinear interpolant of a, b (t = 0, r = 0 and 1) and c, d (t = 1) at sample (u, v) of
// the square's kSubSamples x kSubSamples points.
double SampleOf(double a, double b, double c, double d, int u, int v) {
  const double t = (v + 0.5) / kSubSamples;
  const double r = (u + 0.5) / kSubSamples;
  return (1 - r) * (1 - t) * a + r * (1 - t) * b + (1 - r) * t * c + r * t * d;
}

}  // namespace

// Along a row of samples (t fixed) the interpolant is linear in r, A + B r, so its positive
// samples are the row's first or last ones: a row whose ends agree is all in or all out, and
// another row's change of sign is found by bisection. The samples evaluated are those the full
// count evaluates, in the same expression, so the count is the full count's; a row whose B is
// within the rounding of its terms (where the computed signs might change more than once) is
// counted sample by sample.
int SubSampledHits(double a, double b, double c, double d) {
  // Each sample's rounding is below 1e-15 (|a| + |b| + |c| + |d|); a row whose samples step by
  // more than twice a generous bound of it changes computed sign at most once.
  const double rounding = 1e-14 * (std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d));
  int hit = 0;
  for (int v = 0; v < kSubSamples; ++v) {
    const double t = (v + 0.5) / kSubSamples;
    const double slope = (1 - t) * (b - a) + t * (d - c);
    if (!(std::abs(slope) > 4.0 * kSubSamples * rounding)) {
      for (int u = 0; u < kSubSamples; ++u) hit += SampleOf(a, b, c, d, u, v) > 0;
      continue;
    }
    const bool first = SampleOf(a, b, c, d, 0, v) > 0;
    const bool last = SampleOf(a, b, c, d, kSubSamples - 1, v) > 0;
    if (first == last) {
      hit += first ? kSubSamples : 0;
      continue;
    }
    // The first sample whose sign is last's: in (lo, hi].
    int lo = 0, hi = kSubSamples - 1;
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      ((SampleOf(a, b, c, d, mid, v) > 0) == last ? hi : lo) = mid;
    }
    hit += first ? hi : kSubSamples - hi;
  }
  return hit;
}

// Contact area with the edge located inside the boundary cells (a level-set estimate).
// p^2 is a smooth function that crosses zero at the contact edge (for Hertz it is the quadratic
// p0^2 (1 - x^2/a^2 - y^2/b^2)). Take phi = p^2 at cells in contact; at cells out of contact next
// to the contact (8-neighbourhood), extrapolate p^2 quadratically along each line through
// contact cells (phi = 3 f0 - 3 f1 + f2 from the three cells on the line, linear 2 f0 - f1 when
// only two are in contact) and average; the area is that of {phi > 0} under the bilinear
// interpolation of phi between cell centres. Second order in the cell size, where counting whole
// cells overestimates the area by about 0.3 / (cells per semi-axis) on Hertz cases.
double SubCellArea(const PatchGrid& g, const Eigen::Ref<const Eigen::VectorXd>& p) {
  const int nx = g.nx, ns = g.ns;
  auto inside = [&](int i, int j) { return i >= 0 && j >= 0 && i < nx && j < ns; };
  auto p2 = [&](int i, int j) {
    if (!inside(i, j)) return 0.0;
    const double v = p[g.Index(i, j)];
    return v > 0 ? v * v : 0.0;
  };
  double p2max = 0.0;
  for (int k = 0; k < p.size(); ++k) p2max = std::max(p2max, p[k] > 0 ? p[k] * p[k] : 0.0);
  if (p2max <= 0) return 0.0;
  const double far = -p2max;  // level of cells away from the contact
  std::vector<double> phi(static_cast<size_t>(nx) * ns, far);
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) {
      double& f = phi[g.Index(i, j)];
      const double own = p2(i, j);
      if (own > 0) {
        f = own;
        continue;
      }
      double sum = 0.0;
      int count = 0;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0) continue;
          const double f0 = p2(i - di, j - dj);
          if (f0 <= 0) continue;
          const double f1 = p2(i - 2 * di, j - 2 * dj);
          const double f2 = p2(i - 3 * di, j - 3 * dj);
          double e = (f1 > 0 && f2 > 0) ? 3 * f0 - 3 * f1 + f2 : (f1 > 0 ? 2 * f0 - f1 : -f0);
          sum += std::min(e, -1e-12 * p2max);  // out of contact: strictly negative
          ++count;
        }
      }
      if (count > 0) f = sum / count;
    }
  }
  // Area of {phi > 0} over the squares between cell centres; mixed squares by sub-sampling the
  // bilinear interpolant on kSubSamples x kSubSamples points (SubSampledHits; its error is far
  // below the level-set error).
  double cells = 0.0;
  for (int j = 0; j + 1 < ns; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const double a = phi[g.Index(i, j)], b = phi[g.Index(i + 1, j)];
      const double c = phi[g.Index(i, j + 1)], d = phi[g.Index(i + 1, j + 1)];
      const int positive = (a > 0) + (b > 0) + (c > 0) + (d > 0);
      if (positive == 0) continue;
      if (positive == 4) {
        cells += 1.0;
        continue;
      }
      cells += static_cast<double>(SubSampledHits(a, b, c, d)) / (kSubSamples * kSubSamples);
    }
  }
  return cells * g.CellArea();
}

PatchResult NumericalPatch(const WheelRailGeometry& geom, PatchGrid grid,
                           const Eigen::Ref<const Eigen::VectorXd>& p,
                           std::optional<double> pressure_limit_Pa, PatchArea area_when) {
  PatchResult r;
  const double area = grid.CellArea();
  double fy = 0.0, fz = 0.0, fn = 0.0, ps = 0.0, px = 0.0, psum = 0.0;
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d n = grid.normal_yz[j];
    for (int i = 0; i < grid.nx; ++i) {
      const double pk = p[grid.Index(i, j)];
      if (pk <= 0) continue;
      ++r.cells_in_contact;
      fn += pk * area;
      fy += pk * area * (-n.x());
      fz += pk * area * (-n.y());
      ps += pk * grid.S(j);
      px += pk * grid.X(i);
      psum += pk;
      r.p_max_Pa = std::max(r.p_max_Pa, pk);
      if (pressure_limit_Pa && pk >= *pressure_limit_Pa) {
        ++r.plastic_cells;
        r.plastic_area_m2 += area;
        r.plastic_force_N += pk * area;
      }
    }
  }
  r.cells = grid.cells();
  r.area_m2 = area_when == PatchArea::kNow ? SubCellArea(grid, p)
                                           : std::numeric_limits<double>::quiet_NaN();
  r.normal_force_N = fn;
  r.vertical_force_N = fz;
  r.lateral_force_N = fy;
  r.contact_angle_rad = std::atan2(fy, fz);
  if (psum > 0) {
    // Pressure centre on the reference cross-section, projected onto the rail profile.
    const double sbar = ps / psum;
    r.contact_x_m = px / psum;
    const double jf = std::clamp((sbar - grid.s0_m) / grid.ds_m, 0.0, grid.ns - 1.0);
    const int j0 = std::min(static_cast<int>(jf), std::max(grid.ns - 2, 0));
    const int j1 = std::min(j0 + 1, grid.ns - 1);
    const double f = jf - j0;
    const Eigen::Vector2d q = (1 - f) * grid.point_yz_m[j0] + f * grid.point_yz_m[j1];
    r.contact_point_yz_m = geom.rail().Project(q).point;
  }
  r.grid = std::move(grid);
  r.pressure_Pa = p;
  return r;
}

void FillDeferredAreas(std::vector<PatchResult>* patches) {
  for (PatchResult& patch : *patches) {
    if (std::isnan(patch.area_m2)) patch.area_m2 = SubCellArea(patch.grid, patch.pressure_Pa);
  }
}

PatchResult HertzPatch(const ContactCandidate& c, const HertzSolution& h) {
  PatchResult p;
  p.hertz = h;
  p.area_m2 = h.area_m2;
  p.p_max_Pa = h.p0_Pa;
  p.normal_force_N = h.force_N;
  p.vertical_force_N = h.force_N * (-c.normal.y());
  p.lateral_force_N = h.force_N * (-c.normal.x());
  p.contact_point_yz_m = c.rail_point_m;
  p.contact_x_m = c.x_m;
  p.contact_angle_rad = std::atan2(p.lateral_force_N, p.vertical_force_N);
  return p;
}

ContactResult FinishResult(ContactResult r, double time_s) {
  r.time_s = time_s;
  SumPatchTotals(&r);
  return r;
}

}  // namespace railwear::internal
