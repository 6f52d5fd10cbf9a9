// Warm start of a wheel's contact across calls (contact_warm_start.h).
#include "core/contact/contact_warm_start.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/contact/potential_area.h"

namespace railwear {

ContactWarmStart::ContactWarmStart() = default;
ContactWarmStart::~ContactWarmStart() = default;
ContactWarmStart::ContactWarmStart(ContactWarmStart&&) noexcept = default;
ContactWarmStart& ContactWarmStart::operator=(ContactWarmStart&&) noexcept = default;

void ContactWarmStart::Clear() { state_.reset(); }

void ContactWarmStart::Keep(std::unique_ptr<internal::WarmStartState> state) {
  state_ = std::move(state);
}

}  // namespace railwear

namespace railwear::internal {

namespace {

// Where the rail-frame point q lies on the cross-section of `grid` (its rows' points): the
// fractional row index t (rows j and j + 1 bracket it, linear between their points), or nullopt
// when q lies more than half a cell beyond the first or last row or farther than one cell from
// the cross-section.
std::optional<double> RowOf(const PatchGrid& grid, const Eigen::Vector2d& q) {
  const auto& p = grid.point_yz_m;
  if (grid.ns == 1) {
    const double along = (q - p[0]).dot(grid.tangent_yz[0]);
    const double off = (q - p[0] - along * grid.tangent_yz[0]).norm();
    if (std::abs(along) > 0.5 * grid.ds_m || off > grid.ds_m) return std::nullopt;
    return 0.0;
  }
  double best_distance = std::numeric_limits<double>::infinity();
  double best_t = 0.0;
  for (int j = 0; j + 1 < grid.ns; ++j) {
    const Eigen::Vector2d d = p[j + 1] - p[j];
    const double u = (q - p[j]).dot(d) / d.squaredNorm();
    // The end segments extend half a cell beyond their rows; inner ones end at their rows.
    const double u_lo = j == 0 ? -0.5 : 0.0;
    const double u_hi = j + 2 == grid.ns ? 1.5 : 1.0;
    const double uc = std::clamp(u, u_lo, u_hi);
    const double distance = (q - p[j] - uc * d).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best_t = j + uc;
      // beyond the first or last row by more than half a cell
      if ((j == 0 && u < u_lo) || (j + 2 == grid.ns && u > u_hi)) {
        best_t = std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  if (!(best_distance <= grid.ds_m) || std::isnan(best_t)) return std::nullopt;
  return best_t;
}

// Linear interpolation weights of the fractional index t on [0, n - 1] (clamped at the ends).
struct Bracket {
  int lo, hi;
  double w_hi;
};
Bracket BracketOf(double t, int n) {
  const double tc = std::clamp(t, 0.0, static_cast<double>(n - 1));
  const int lo = std::min(static_cast<int>(std::floor(tc)), n - 1);
  const int hi = std::min(lo + 1, n - 1);
  return {lo, hi, tc - lo};
}

}  // namespace

Eigen::VectorXd WarmPressureStart(const WarmStartState& state, const PatchBuilds& builds) {
  int total = 0;
  for (const PatchBuild& b : builds.builds) total += b.grid.cells();
  Eigen::VectorXd start = Eigen::VectorXd::Zero(total);
  int offset = 0;
  for (const PatchBuild& b : builds.builds) {
    const PatchGrid& g = b.grid;
    for (int j = 0; j < g.ns; ++j) {
      for (size_t k = 0; k < state.grids.size(); ++k) {
        const PatchGrid& old = state.grids[k];
        const std::optional<double> t = RowOf(old, g.point_yz_m[j]);
        if (!t) continue;
        const Bracket row = BracketOf(*t, old.ns);
        const Eigen::VectorXd& p = state.pressures_Pa[k];
        for (int i = 0; i < g.nx; ++i) {
          const double r = (g.X(i) - old.x0_m) / old.dx_m;
          if (r < -0.5 || r > old.nx - 0.5) continue;
          const Bracket col = BracketOf(r, old.nx);
          auto at = [&](int jj) {
            return (1.0 - col.w_hi) * p[old.Index(col.lo, jj)] +
                   col.w_hi * p[old.Index(col.hi, jj)];
          };
          start[offset + g.Index(i, j)] = (1.0 - row.w_hi) * at(row.lo) + row.w_hi * at(row.hi);
        }
        break;  // (patches do not overlap: the first grid that holds the row)
      }
    }
    offset += g.cells();
  }
  return start;
}

}  // namespace railwear::internal
