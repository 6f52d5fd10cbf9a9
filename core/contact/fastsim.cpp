// FASTSIM (Kalker's simplified theory) on the patch grid; see fastsim.h for the method.
#include "core/contact/fastsim.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/contact/kalker_coefficients.h"
#include "core/numerics/check.h"

namespace railwear {

std::string_view ToString(TractionBound v) {
  switch (v) {
    case TractionBound::kActualPressure:
      return "actual_pressure";
    case TractionBound::kParabolic:
      return "parabolic";
  }
  return "unknown";
}

std::string_view ToString(FlexibilityModel v) {
  switch (v) {
    case FlexibilityModel::kWeighted:
      return "weighted";
    case FlexibilityModel::kSeparate:
      return "separate";
    case FlexibilityModel::kThree:
      return "three";
  }
  return "unknown";
}

std::string_view ToString(FastsimMarch v) {
  switch (v) {
    case FastsimMarch::kTrapezoidal:
      return "trapezoidal";
    case FastsimMarch::kContactEuler:
      return "contact_euler";
  }
  return "unknown";
}

std::optional<FastsimMarch> FastsimMarchFromString(std::string_view s) {
  for (FastsimMarch v : {FastsimMarch::kTrapezoidal, FastsimMarch::kContactEuler}) {
    if (s == ToString(v)) return v;
  }
  return std::nullopt;
}

bool FastsimOptions::IsValid(std::string* error) const {
  // The checks first, the message only for a failed one: SolveFastsim validates its options on
  // every call, and an ostringstream per call was a few per cent of the fast tread path's time.
  const bool shear_ok = std::isfinite(shear_modulus_Pa) && shear_modulus_Pa > 0.0;
  const bool poisson_ok =
      std::isfinite(poisson_ratio) && poisson_ratio >= 0.0 && poisson_ratio <= 0.5;
  const bool ax_ok = !semi_axis_x_m || (std::isfinite(*semi_axis_x_m) && *semi_axis_x_m > 0.0);
  const bool as_ok = !semi_axis_s_m || (std::isfinite(*semi_axis_s_m) && *semi_axis_s_m > 0.0);
  const bool creep_ok = !((xi && !std::isfinite(*xi)) || (eta && !std::isfinite(*eta)) ||
                          (phi_per_m && !std::isfinite(*phi_per_m)));
  const bool blend_ok = !blend_flexibilities || flexibility == FlexibilityModel::kThree;
  if (shear_ok && poisson_ok && ax_ok && as_ok && creep_ok && blend_ok) {
    if (error != nullptr) error->clear();
    return true;
  }
  std::ostringstream msg;
  if (!shear_ok) {
    msg << "shear_modulus_Pa = " << shear_modulus_Pa << ", expected finite > 0";
  } else if (!poisson_ok) {
    msg << "poisson_ratio = " << poisson_ratio << ", expected in [0, 0.5]";
  } else if (!ax_ok) {
    msg << "semi_axis_x_m = " << *semi_axis_x_m << ", expected finite > 0";
  } else if (!as_ok) {
    msg << "semi_axis_s_m = " << *semi_axis_s_m << ", expected finite > 0";
  } else if (!creep_ok) {
    msg << "patch-average creepages xi, eta, phi_per_m must be finite";
  } else {
    msg << "blend_flexibilities needs flexibility = three, got " << ToString(flexibility);
  }
  if (error != nullptr) *error = msg.str();
  return false;
}

CombinedElastic CombineElastic(const Material& a, const Material& b) {
  const double ga = a.ShearModulus(), gb = b.ShearModulus();
  const double g = 2.0 / (1.0 / ga + 1.0 / gb);
  return {g, 0.5 * g * (a.poisson_ratio / ga + b.poisson_ratio / gb)};
}

namespace {

// what() makes the message, only when the check fails (SolveFastsim checks its input on every
// call; formatting the numbers each time was a few per cent of the fast tread path's time).
template <class Message>
void Require(bool ok, const Message& what) {
  if (!ok) throw std::invalid_argument("SolveFastsim: " + what());
}

}  // namespace

ContactEllipse EstimateContactEllipse(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa) {
  ContactEllipse e;
  double xmin = 1e300, xmax = -1e300, smin = 1e300, smax = -1e300, xsum = 0.0, ssum = 0.0;
  const double dA = grid.CellArea();
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const double p = pressure_Pa[grid.Index(i, j)];
      if (p <= 0.0) continue;
      ++e.cells;
      const double x = grid.X(i), s = grid.S(j);
      xmin = std::min(xmin, x);
      xmax = std::max(xmax, x);
      smin = std::min(smin, s);
      smax = std::max(smax, s);
      xsum += x;
      ssum += s;
      e.normal_force_N += p * dA;
    }
  }
  if (e.cells == 0) return e;
  e.centroid_x_m = xsum / e.cells;
  e.centroid_s_m = ssum / e.cells;
  const double ratio = (xmax - xmin + grid.dx_m) / (smax - smin + grid.ds_m);  // a/b
  const double ab = e.cells * dA / std::numbers::pi;
  e.semi_axis_x_m = std::sqrt(ab * ratio);
  e.semi_axis_s_m = std::sqrt(ab / ratio);
  return e;
}

namespace {

void CheckFastsimInput(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                       const RollingInput& in, const FastsimOptions& opt) {
  const int n = grid.cells();
  Require(grid.nx > 0 && grid.ns > 0 && grid.dx_m > 0.0 && grid.ds_m > 0.0,
          [] { return std::string("grid must have nx, ns >= 1 and dx, ds > 0"); });
  Require(static_cast<int>(grid.tangent_yz.size()) == grid.ns, [&] {
    return "grid.tangent_yz has " + std::to_string(grid.tangent_yz.size()) +
           " entries, expected ns = " + std::to_string(grid.ns);
  });
  Require(pressure_Pa.size() == n, [&] {
    return "pressure has " + std::to_string(pressure_Pa.size()) + " cells, expected " +
           std::to_string(n);
  });
  Require(in.creep_x.size() == n && in.creep_s.size() == n, [&] {
    return "creep_x/creep_s have " + std::to_string(in.creep_x.size()) + "/" +
           std::to_string(in.creep_s.size()) + " cells, expected " + std::to_string(n);
  });
  Require(pressure_Pa.allFinite() && in.creep_x.allFinite() && in.creep_s.allFinite(),
          [] { return std::string("pressure and creepages must be finite"); });
  Require(std::isfinite(in.speed_m_s) && in.speed_m_s > 0.0, [&] {
    return "speed_m_s = " + std::to_string(in.speed_m_s) + ", expected > 0";
  });
  Require(std::isfinite(in.friction) && in.friction > 0.0, [&] {
    return "friction = " + std::to_string(in.friction) + ", expected > 0";
  });
  std::string error;
  Require(opt.IsValid(&error), [&] { return "options: " + error; });
}

// Steps 1 and 2 of SolveFastsim on the contact region: the patch's normal force, centroid and
// semi-axes (the options' or the region's), and its average creepages.
void FitPatch(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa, const RollingInput& in,
              const FastsimOptions& opt, const ContactEllipse& region, FastsimPatch* out) {
  const int count = region.cells;
  const double fn = region.normal_force_N;
  FastsimPatch& patch = *out;
  patch.normal_force_N = fn;
  patch.centroid_x_m = region.centroid_x_m;
  patch.centroid_s_m = region.centroid_s_m;
  {
    const double ratio = region.semi_axis_x_m / region.semi_axis_s_m;  // a/b
    if (opt.semi_axis_x_m && opt.semi_axis_s_m) {
      patch.semi_axis_x_m = *opt.semi_axis_x_m;
      patch.semi_axis_s_m = *opt.semi_axis_s_m;
    } else if (opt.semi_axis_x_m) {
      patch.semi_axis_x_m = *opt.semi_axis_x_m;
      patch.semi_axis_s_m = *opt.semi_axis_x_m / ratio;
    } else if (opt.semi_axis_s_m) {
      patch.semi_axis_s_m = *opt.semi_axis_s_m;
      patch.semi_axis_x_m = *opt.semi_axis_s_m * ratio;
    } else {
      patch.semi_axis_x_m = region.semi_axis_x_m;
      patch.semi_axis_s_m = region.semi_axis_s_m;
    }
  }

  // 2. Patch-average creepages: least squares of w_x = xi - phi s', w_s = eta + phi x' about
  // the centroid; the normal equations decouple because sum x' = sum s' = 0.
  {
    double wx = 0.0, ws = 0.0, num = 0.0, den = 0.0;
    for (int j = 0; j < grid.ns; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const int k = grid.Index(i, j);
        if (pressure_Pa[k] <= 0.0) continue;
        const double xp = grid.X(i) - patch.centroid_x_m, sp = grid.S(j) - patch.centroid_s_m;
        wx += in.creep_x[k];
        ws += in.creep_s[k];
        num += xp * in.creep_s[k] - sp * in.creep_x[k];
        den += xp * xp + sp * sp;
      }
    }
    patch.xi = opt.xi.value_or(wx / count);
    patch.eta = opt.eta.value_or(ws / count);
    patch.phi_per_m = opt.phi_per_m.value_or(den > 0.0 ? num / den : 0.0);
  }
}

// Traction rates -dq/dx of sticking material per cell [Pa/m], shape [grid.cells()], and the
// flexibilities the slip magnitudes use [m/Pa].
struct TractionRates {
  Eigen::VectorXd rate_x, rate_s;
  double lx_slip = 0.0, ls_slip = 0.0;
};

// Step 3 of SolveFastsim: the flexibilities (into *patch_io) and the traction rates.
TractionRates CalcTractionRates(const PatchGrid& grid, const RollingInput& in,
                                const FastsimOptions& opt, FastsimPatch* patch_io) {
  FastsimPatch& patch = *patch_io;
  const int n = grid.cells();
  const double fn = patch.normal_force_N;
  const double a = patch.semi_axis_x_m, b = patch.semi_axis_s_m, c = std::sqrt(a * b);
  // 3. Flexibilities.
  const double g_mod = opt.shear_modulus_Pa;
  const CreepCoefficients cc = KalkerCoefficients(a / b, opt.poisson_ratio);
  double l1 = 8.0 * a / (3.0 * cc.c11 * g_mod);
  double l2 = 8.0 * a / (3.0 * cc.c22 * g_mod);
  double l3 = std::numbers::pi * a * std::sqrt(a / b) / (4.0 * cc.c23 * g_mod);
  if (opt.blend_flexibilities) {
    // CONTACT's simpflex (fastsim.h): blend toward the combined flexibility as creepage grows.
    const double xi = patch.xi, eta = patch.eta, phi = patch.phi_per_m;
    const double f_phi = phi * 3.0 * std::numbers::pi * a / 32.0;  // phi (pi a^2/4)/(8a/3)
    const double num = xi * xi + eta * eta + f_phi * f_phi;
    if (num > 0.0) {
      const double l_comb = num / (xi * xi / l1 + eta * eta / l2 + f_phi * f_phi / l3);
      const double mu_fn = in.friction * fn;
      const double ch_xi = mu_fn / (c * c * g_mod * cc.c11);
      const double ch_eta = mu_fn / (c * c * g_mod * cc.c22);
      const double ch_phi = mu_fn / (c * c * c * g_mod * cc.c23) * kContactLengthUnit_m;
      const double phi_unit = phi * kContactLengthUnit_m;
      const double creep = std::sqrt((xi * xi + eta * eta + phi_unit * phi_unit) /
                                     (ch_xi * ch_xi + ch_eta * ch_eta + ch_phi * ch_phi));
      const double w = std::min(1.0, creep / 3.0);
      l1 = (1.0 - w) * l1 + w * l_comb;
      l2 = (1.0 - w) * l2 + w * l_comb;
      l3 = (1.0 - w) * l3 + w * l_comb;
      patch.blend_weight = w;
    }
  }
  if (opt.flexibility == FlexibilityModel::kSeparate) {
    patch.flexibility_x_m_Pa = l1;
    patch.flexibility_s_m_Pa = l2;
  } else {
    const double wxi = std::abs(patch.xi), weta = std::abs(patch.eta),
                 wphi = std::abs(patch.phi_per_m) * c;
    const double sum = wxi + weta + wphi;
    const double l = sum > 0.0 ? (wxi * l1 + weta * l2 + wphi * l3) / sum : l1;
    patch.flexibility_x_m_Pa = patch.flexibility_s_m_Pa = l;
  }
  const double lx = patch.flexibility_x_m_Pa, ls = patch.flexibility_s_m_Pa;
  // Slip magnitudes use one flexibility per component (for kThree: the weighted L).
  double lx_slip = lx, ls_slip = ls;
  if (opt.flexibility == FlexibilityModel::kThree) {
    const double wxi = std::abs(patch.xi), weta = std::abs(patch.eta),
                 wphi = std::abs(patch.phi_per_m) * c;
    const double sum = wxi + weta + wphi;
    lx_slip = ls_slip = sum > 0.0 ? (wxi * l1 + weta * l2 + wphi * l3) / sum : l1;
    patch.flexibility_x_m_Pa = l1;
    patch.flexibility_s_m_Pa = l2;
    patch.flexibility_spin_m_Pa = l3;
  }
  // Traction rate -dq/dx of sticking material per cell [Pa/m]: w/L, or for kThree the spin part
  // of Kalker's field over L3 and the rest over L1, L2.
  Eigen::VectorXd rate_x(n), rate_s(n);
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const int k = grid.Index(i, j);
      const double wx = in.creep_x[k], ws = in.creep_s[k];
      if (opt.flexibility == FlexibilityModel::kThree) {
        const double xp = grid.X(i) - patch.centroid_x_m, sp = grid.S(j) - patch.centroid_s_m;
        const double spin_x = -patch.phi_per_m * sp, spin_s = patch.phi_per_m * xp;
        rate_x[k] = (wx - spin_x) / l1 + spin_x / l3;
        rate_s[k] = (ws - spin_s) / l2 + spin_s / l3;
      } else {
        rate_x[k] = wx / lx;
        rate_s[k] = ws / ls;
      }
    }
  }
  return {std::move(rate_x), std::move(rate_s), lx_slip, ls_slip};
}

// Step 4 of SolveFastsim: the bound pressure [Pa] per cell, shape [grid.cells()].
Eigen::VectorXd CalcBoundPressure(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                  const FastsimOptions& opt, const FastsimPatch& patch) {
  const double dA = grid.CellArea();
  const double fn = patch.normal_force_N;
  const double a = patch.semi_axis_x_m, b = patch.semi_axis_s_m;
  // 4. The bound pressure.
  Eigen::VectorXd bound_Pa = pressure_Pa.cwiseMax(0.0);
  if (opt.bound == TractionBound::kParabolic) {
    const double peak = 2.0 * fn / (std::numbers::pi * a * b);
    double sum = 0.0;
    for (int j = 0; j < grid.ns; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const int k = grid.Index(i, j);
        if (pressure_Pa[k] <= 0.0) continue;
        const double xr = (grid.X(i) - patch.centroid_x_m) / a;
        const double sr = (grid.S(j) - patch.centroid_s_m) / b;
        bound_Pa[k] = peak * std::max(0.0, 1.0 - xr * xr - sr * sr);
        sum += bound_Pa[k] * dA;
      }
    }
    if (sum > 0.0) bound_Pa *= fn / sum;
  }
  return bound_Pa;
}

// Step 5 of SolveFastsim: every strip marched from its leading edge; tractions, slip and the
// stick flag into *sol_io; the numbers of sticking and slipping cells into the last two.
void MarchStrips(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                 const Eigen::VectorXd& bound_Pa, const TractionRates& rates,
                 const RollingInput& in, const FastsimOptions& opt, TangentialSolution* sol_io,
                 double* stick_cells_out, double* slip_cells_out) {
  TangentialSolution& sol = *sol_io;
  const Eigen::VectorXd& rate_x = rates.rate_x;
  const Eigen::VectorXd& rate_s = rates.rate_s;
  const double lx_slip = rates.lx_slip, ls_slip = rates.ls_slip;
  // 5. March every strip from its leading edge (largest x) to its trailing edge.
  const double mu = in.friction, v = in.speed_m_s;
  const bool euler = opt.march == FastsimMarch::kContactEuler;
  // kContactEuler: the cell's rate taken kContactSpinShift of a cell upstream (toward +x), by
  // linear interpolation to the upstream neighbour (extrapolation in the last column).
  auto shifted = [&](const Eigen::VectorXd& rate, int i, int k) {
    if (grid.nx == 1) return rate[k];
    const double up = i + 1 < grid.nx ? rate[k + 1] - rate[k] : rate[k] - rate[k - 1];
    return rate[k] + kContactSpinShift * up;
  };
  double stick_cells = 0, slip_cells = 0;
  for (int j = 0; j < grid.ns; ++j) {
    double qx = 0.0, qs = 0.0;
    bool inside = false;
    for (int i = grid.nx - 1; i >= 0; --i) {
      const int k = grid.Index(i, j);
      if (pressure_Pa[k] <= 0.0) {
        qx = qs = 0.0;
        inside = false;
        continue;
      }
      double h = grid.dx_m, rx = 0.0, rs = 0.0;
      if (euler) {
        // A full step from the previous cell (from q = 0 at the strip's first cell).
        rx = shifted(rate_x, i, k);
        rs = shifted(rate_s, i, k);
      } else if (inside) {
        // Trapezoidal rule between cell centres (second order for creepage varying along x).
        rx = 0.5 * (rate_x[k] + rate_x[k + 1]);
        rs = 0.5 * (rate_s[k] + rate_s[k + 1]);
      } else {
        // From the leading face of the first cell, the cell's own rate.
        h = 0.5 * grid.dx_m;
        rx = rate_x[k];
        rs = rate_s[k];
      }
      inside = true;
      const double tx = qx - rx * h, ts = qs - rs * h;
      const double g = mu * bound_Pa[k];
      const double t_norm = std::sqrt(tx * tx + ts * ts);
      if (t_norm <= g) {
        qx = tx;
        qs = ts;
        sol.stick[k] = 1;
        ++stick_cells;
      } else {
        qx = g * tx / t_norm;
        qs = g * ts / t_norm;
        sol.stick[k] = 0;
        ++slip_cells;
        // Slip s = V (w - du/dx) with du/dx = L (q_prev - q)/h: s = V (L/h)(q - q_trial).
        const double sx = lx_slip / h * (qx - tx), ss = ls_slip / h * (qs - ts);
        const double speed = v * std::sqrt(sx * sx + ss * ss);
        if (t_norm > 0.0) {
          // Opposite the traction (exact for the weighted L; see fastsim.h for kSeparate).
          sol.slip_x_m_s[k] = -speed * tx / t_norm;
          sol.slip_s_m_s[k] = -speed * ts / t_norm;
        }
      }
      sol.traction_x_Pa[k] = qx;
      sol.traction_s_Pa[k] = qs;
    }
  }
  *stick_cells_out = stick_cells;
  *slip_cells_out = slip_cells;
}

// Step 6 of SolveFastsim: forces, spin moment and frictional power from the tractions.
void AddTotals(const PatchGrid& grid, TangentialSolution* sol_io) {
  const double x_ref = grid.XCentre();
  TangentialSolution& sol = *sol_io;
  const double dA = grid.CellArea();
  // 6. Totals.
  for (int j = 0; j < grid.ns; ++j) {
    double fs_strip = 0.0;
    for (int i = 0; i < grid.nx; ++i) {
      const int k = grid.Index(i, j);
      const double qx = sol.traction_x_Pa[k], qs = sol.traction_s_Pa[k];
      sol.force_x_N += qx * dA;
      fs_strip += qs * dA;
      sol.spin_moment_Nm += ((grid.X(i) - x_ref) * qs - grid.S(j) * qx) * dA;
      sol.frictional_power_W += std::abs(qx * sol.slip_x_m_s[k] + qs * sol.slip_s_m_s[k]) * dA;
    }
    sol.force_s_N += fs_strip;
    sol.force_s_yz_N += fs_strip * grid.tangent_yz[j];
  }
}

}  // namespace

TangentialSolution SolveFastsim(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                const RollingInput& in, const FastsimOptions& opt,
                                FastsimPatch* patch_out) {
  const int n = grid.cells();
  CheckFastsimInput(grid, pressure_Pa, in, opt);

  TangentialSolution sol = EmptyTangentialSolution(n);
  const double dA = grid.CellArea();

  // 1. The contact region: cell count, extents (to the cell faces), centroid, normal force.
  const ContactEllipse region = EstimateContactEllipse(grid, pressure_Pa);
  if (region.cells == 0) {
    sol.status = SolverStatus::kNoContact;
    sol.message = "no cell carries pressure";
    return sol;
  }
  const int count = region.cells;
  // 2. Its semi-axes and patch-average creepages.
  FastsimPatch patch;
  FitPatch(grid, pressure_Pa, in, opt, region, &patch);
  // 3. Flexibilities and traction rates.
  const TractionRates rates = CalcTractionRates(grid, in, opt, &patch);
  // 4. The bound pressure.
  const Eigen::VectorXd bound_Pa = CalcBoundPressure(grid, pressure_Pa, opt, patch);
  // 5. March every strip from its leading edge (largest x) to its trailing edge.
  double stick_cells = 0, slip_cells = 0;
  MarchStrips(grid, pressure_Pa, bound_Pa, rates, in, opt, &sol, &stick_cells, &slip_cells);
  // 6. Totals.
  AddTotals(grid, &sol);
  sol.stick_area_m2 = stick_cells * dA;
  sol.slip_area_m2 = slip_cells * dA;
  RAILWEAR_CHECK(stick_cells + slip_cells == count);
  sol.status = SolverStatus::kConverged;
  sol.iterations = 1;
  sol.message = "FASTSIM: one sweep";
  if (patch_out != nullptr) *patch_out = patch;
  return sol;
}

}  // namespace railwear
