// Per-pass wear depth, damage and frictional energy of one patch on rail-profile bins: the
// column sums along x and the area-conserving mapping onto the rail (see pass_depth.h).
#include "wear/pass_depth.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/numerics/check.h"
#include "core/numerics/input_error.h"

namespace railwear {

namespace {

// The patch must carry a grid and the rolling stage's slip field. `what` names the quantity,
// `subject` what needs them ("wear").
void RequireGridAndRolling(const PatchResult& patch, const char* what, const char* subject) {
  if (patch.grid.cells() == 0) {
    throw InputError(fmt::format(
        "{}: the patch was solved with the Hertz model, which has no grid: {} needs a grid "
        "model (kind \"halfspace\" or \"conformal\") and the tangential effect",
        what, subject));
  }
  if (!patch.rolling.has_value()) {
    throw InputError(fmt::format(
        "{}: the patch has no rolling solution: {} needs a grid model and the tangential effect "
        "(scene effects = [\"normal\", \"tangential\", ...]) for the slip field",
        what, subject));
  }
  const int cells = patch.grid.cells();
  const TangentialSolution& t = patch.rolling->tangential;
  RAILWEAR_CHECK(patch.pressure_Pa.size() == cells);
  RAILWEAR_CHECK(t.traction_x_Pa.size() == cells && t.traction_s_Pa.size() == cells);
  RAILWEAR_CHECK(t.slip_x_m_s.size() == cells && t.slip_s_m_s.size() == cells);
  RAILWEAR_CHECK(static_cast<int>(patch.grid.point_yz_m.size()) == patch.grid.ns);
}

void RequirePositive(const char* what, const char* name, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("{}: {} = {}: expected a finite number > 0", what, name, value));
  }
}

// The wear law's input at cell k.
WearCellState CellState(const PatchResult& patch, int k) {
  const TangentialSolution& t = patch.rolling->tangential;
  WearCellState c;
  c.pressure_Pa = patch.pressure_Pa[k];
  c.slip_speed_m_s = std::hypot(t.slip_x_m_s[k], t.slip_s_m_s[k]);
  c.frictional_power_Pa_m_s =
      std::abs(t.traction_x_Pa[k] * t.slip_x_m_s[k] + t.traction_s_Pa[k] * t.slip_s_m_s[k]);
  return c;
}

int BinOf(double s, const WearGrid& g) {
  return std::clamp(static_cast<int>(std::floor(s / g.h_m)), 0, g.n - 1);
}

// Adds `area` [m^2] spread uniformly over the rail arc [lo, hi] to the bins, as depth (area / h).
void SpreadArea(double lo, double hi, double area, const WearGrid& g, std::vector<double>* bins) {
  if (area == 0.0) return;
  const double width = hi - lo;
  if (!(width > 0.0)) {
    (*bins)[BinOf(lo, g)] += area / g.h_m;
    return;
  }
  const int b0 = BinOf(lo, g), b1 = BinOf(hi, g);
  for (int b = b0; b <= b1; ++b) {
    const double overlap = std::min(hi, (b + 1) * g.h_m) - std::max(lo, b * g.h_m);
    if (overlap > 0.0) (*bins)[b] += area * (overlap / width) / g.h_m;
  }
}

void RequireWearGrid(const WearGrid& g) { RAILWEAR_CHECK(g.n > 0 && g.h_m > 0.0); }

}  // namespace

std::vector<double> MapColumnAmounts(const PatchGrid& grid, const std::vector<double>& per_column,
                                     const CurveLocator& body, const WearGrid& g) {
  RAILWEAR_CHECK(static_cast<int>(per_column.size()) == grid.ns);
  std::vector<double> bins(g.n, 0.0);
  bool any = false;
  for (double v : per_column) any = any || v != 0.0;
  if (!any) return bins;
  const std::vector<double> edges = CalcColumnEdgesOnRail(grid, body);
  for (int j = 0; j < grid.ns; ++j) {
    const double a = edges[j], b = edges[j + 1];
    SpreadArea(std::min(a, b), std::max(a, b), per_column[j] * grid.ds_m, g, &bins);
  }
  return bins;
}

WearGrid WearGrid::ForProfile(const Profile& rail, double h_m) {
  if (!(h_m > 0.0) || !std::isfinite(h_m)) {
    throw InputError(fmt::format(
        "wear grid: bin width h = {} m on rail profile '{}': expected a finite width > 0", h_m,
        rail.source()));
  }
  WearGrid g;
  g.h_m = h_m;
  g.n = std::max(1, static_cast<int>(std::ceil(rail.Length() / h_m)));
  return g;
}

std::vector<double> CalcColumnPassDepth(const PatchResult& patch, const WearLaw& law,
                                        double hardness_Pa, double speed_m_s) {
  constexpr const char* kWhat = "per-pass wear depth";
  RequireGridAndRolling(patch, kWhat, "wear");
  RequirePositive(kWhat, "rolling speed V [m/s]", speed_m_s);
  if (law.kind != WearLawKind::kUsfd) {
    RequirePositive(kWhat, "rail hardness H [Pa]", hardness_Pa);
  }
  const PatchGrid& grid = patch.grid;
  std::vector<double> dz(grid.ns, 0.0);
  for (int j = 0; j < grid.ns; ++j) {
    double sum = 0.0;
    for (int i = 0; i < grid.nx; ++i) {
      const int k = grid.Index(i, j);
      if (!(patch.pressure_Pa[k] > 0.0)) continue;
      sum += WearDepthPerRolledMetre(law, CellState(patch, k), hardness_Pa, speed_m_s);
    }
    dz[j] = sum * grid.dx_m;
  }
  return dz;
}

std::vector<double> CalcColumnEdgesOnRail(const PatchGrid& grid, const CurveLocator& rail) {
  RAILWEAR_CHECK(grid.ns >= 1 && static_cast<int>(grid.point_yz_m.size()) == grid.ns);
  const auto& p = grid.point_yz_m;
  std::vector<double> edges(grid.ns + 1);
  auto project = [&](const Eigen::Vector2d& q) { return rail.Project(q).s; };
  if (grid.ns == 1) {
    RAILWEAR_CHECK(grid.tangent_yz.size() == 1u);
    edges[0] = project(p[0] - 0.5 * grid.ds_m * grid.tangent_yz[0]);
    edges[1] = project(p[0] + 0.5 * grid.ds_m * grid.tangent_yz[0]);
    return edges;
  }
  edges[0] = project(p[0] - 0.5 * (p[1] - p[0]));
  for (int e = 1; e < grid.ns; ++e) edges[e] = project(0.5 * (p[e - 1] + p[e]));
  edges[grid.ns] = project(p[grid.ns - 1] + 0.5 * (p[grid.ns - 1] - p[grid.ns - 2]));
  return edges;
}

std::vector<double> CalcPatchPassDepth(const PatchResult& patch, const CurveLocator& rail,
                                       const WearLaw& law, double hardness_Pa, double speed_m_s,
                                       const WearGrid& wear_grid) {
  RequireWearGrid(wear_grid);
  const std::vector<double> dz = CalcColumnPassDepth(patch, law, hardness_Pa, speed_m_s);
  return MapColumnAmounts(patch.grid, dz, rail, wear_grid);
}

std::vector<double> CalcPatchPassDepth(const PatchResult& patch, const Profile& rail,
                                       const WearLaw& law, double hardness_Pa, double speed_m_s,
                                       const WearGrid& wear_grid) {
  const CurveLocator locator(rail, /*material_toward_plus_z=*/true);
  return CalcPatchPassDepth(patch, locator, law, hardness_Pa, speed_m_s, wear_grid);
}

double WornArea(const std::vector<double>& depth_m, const WearGrid& wear_grid) {
  RAILWEAR_CHECK(static_cast<int>(depth_m.size()) == wear_grid.n);
  double sum = 0.0;
  for (double d : depth_m) sum += d;
  return sum * wear_grid.h_m;
}

std::vector<double> CalcPatchDamageSpread(const PatchResult& patch, const CurveLocator& rail,
                                          const WearGrid& wear_grid) {
  constexpr const char* kWhat = "damage per position";
  RequireGridAndRolling(patch, kWhat, "damage per position");
  RequireWearGrid(wear_grid);
  if (!patch.rolling->damage.has_value()) {
    // A patch left without pressure (the vertical balance or the coupling unloaded a small
    // second patch) has no tractions and damages nothing.
    if (patch.rolling->tangential.status == SolverStatus::kNoContact) {
      return std::vector<double>(wear_grid.n, 0.0);
    }
    throw InputError(
        "damage per position: the patch has no damage indices: it needs the damage effect "
        "(scene effects = [..., \"damage\"]) and the rail's shear_yield_MPa");
  }
  const double damage = patch.rolling->damage->wlrm_damage;
  const PatchGrid& grid = patch.grid;
  std::vector<double> coverage(wear_grid.n, 0.0);
  std::vector<double> edges;
  for (int j = 0; j < grid.ns; ++j) {
    bool loaded = false;
    for (int i = 0; i < grid.nx && !loaded; ++i) loaded = patch.pressure_Pa[grid.Index(i, j)] > 0;
    if (!loaded) continue;
    if (edges.empty()) edges = CalcColumnEdgesOnRail(grid, rail);
    const double lo = std::min(edges[j], edges[j + 1]), hi = std::max(edges[j], edges[j + 1]);
    const int b0 = BinOf(lo, wear_grid), b1 = BinOf(hi, wear_grid);
    for (int b = b0; b <= b1; ++b) {
      const double overlap =
          std::min(hi, (b + 1) * wear_grid.h_m) - std::max(lo, b * wear_grid.h_m);
      if (overlap > 0.0) coverage[b] += overlap / wear_grid.h_m;
    }
  }
  std::vector<double> out(wear_grid.n, 0.0);
  for (int b = 0; b < wear_grid.n; ++b) out[b] = damage * std::min(coverage[b], 1.0);
  return out;
}

std::vector<double> CalcPatchDamageSpread(const PatchResult& patch, const Profile& rail,
                                          const WearGrid& wear_grid) {
  const CurveLocator locator(rail, /*material_toward_plus_z=*/true);
  return CalcPatchDamageSpread(patch, locator, wear_grid);
}

std::vector<double> CalcPatchPassEnergy(const PatchResult& patch, const CurveLocator& rail,
                                        double speed_m_s, const WearGrid& wear_grid) {
  constexpr const char* kWhat = "frictional energy per position";
  RequireGridAndRolling(patch, kWhat, "frictional energy per position");
  RequirePositive(kWhat, "rolling speed V [m/s]", speed_m_s);
  RequireWearGrid(wear_grid);
  const PatchGrid& grid = patch.grid;
  std::vector<double> e(grid.ns, 0.0);
  for (int j = 0; j < grid.ns; ++j) {
    double sum = 0.0;
    for (int i = 0; i < grid.nx; ++i) {
      sum += CellState(patch, grid.Index(i, j)).frictional_power_Pa_m_s;
    }
    e[j] = sum * grid.dx_m / speed_m_s;
  }
  return MapColumnAmounts(grid, e, rail, wear_grid);
}

std::vector<double> CalcPatchPassEnergy(const PatchResult& patch, const Profile& rail,
                                        double speed_m_s, const WearGrid& wear_grid) {
  const CurveLocator locator(rail, /*material_toward_plus_z=*/true);
  return CalcPatchPassEnergy(patch, locator, speed_m_s, wear_grid);
}

}  // namespace railwear
