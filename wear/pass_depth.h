// Per-pass wear depth of one contact patch on the rail profile, and damage and frictional energy
// per rail position (DESIGN.md §1 "Wear" and "Damage").
//
// 1. Depth per column. A rail point under the patch spends dx/V in each cell it passes, so the
//    depth one wheel pass removes at patch column j (fixed s on the reference surface) is the
//    closed-form sum along the rolling direction
//        dz_j = sum_i (dz/dL)(cell i, j) * dx            [m per pass]
//    with dz/dL the wear law's depth per metre rolled (wear/wear_law.h) from the cell's pressure
//    p, slip speed |v| = hypot(v_x, v_s) and frictional power density |q_x v_x + q_s v_s|.
//    The worn area per metre of track of the patch is  A = sum_j dz_j ds  [m^2].
//
// 2. Mapping onto the rail. The rail is prismatic, so the orthogonal projection of a grid point
//    onto the rail (seed eq. 2) is a 1-D search along the rail profile (CurveLocator::Project),
//    giving a rail arc length (the closest point over the whole profile). Column j covers the
//    reference-surface arc between its edge points: the midpoints between neighbouring column
//    centres, and at the two end columns the centre minus/plus half the step to its neighbour (a
//    one-column grid uses its tangent and ds / 2). The projections of those ns + 1 edge points
//    bound the rail arc interval [s_a, s_b] of column j. Column j's worn area dz_j ds is spread
//    uniformly over that interval and accumulated onto fixed bins of rail arc length (WearGrid).
//    Every column deposits exactly its own area, so the worn area is conserved to rounding:  sum_b
//    depth_b h = sum_j dz_j ds. Where the reference surface is longer or shorter than the rail arc
//    it projects onto (the intermediate surface of a conformal patch lies inside the overlap; a
//    planar patch leaves the curved rail), the depth on the rail is the column depth times ds /
//    (s_b - s_a): area, not the column depth, is what carries over. A column whose interval has
//    zero width (its edges project onto one point) puts its area into the bin of that point.
//
// 3. Damage per position. The Whole Life Rail Model damage per axle of the patch
//    (PatchDamage::wlrm_damage) is intensive: every rail position the loaded columns (any cell
//    with p > 0) cover receives the patch's damage for that pass, weighted by the fraction of
//    the bin covered (at most 1 per bin). A loaded column whose edges project onto one point
//    covers nothing.
//
// 4. Frictional energy per position: e_j = sum_i |q . v| / V dx [J/m^2 per pass], mapped like
//    the depth (area-conserving): sum_b e_b h = frictional power / V [J/m], the patch's energy
//    dissipated per metre rolled (all slip, spin included; T-gamma of damage.h keeps only the
//    two creepage terms).
//
// Frames and units: rail profile frame R (core/notation.md), SI throughout; the patch grid's
// points are in the frame of the rail profile that was passed to SolveContact (canted), and the
// same profile must be passed here. Bins are of rail-profile arc length s measured from the
// profile's first point.
#pragma once

#include <vector>

#include "core/contact/contact_solver.h"
#include "core/geometry/curve_locator.h"
#include "core/profile/profile.h"
#include "wear/wear_law.h"

namespace railwear {

// Fixed bins of rail-profile arc length: bin b covers [b h, (b + 1) h), b = 0 .. n - 1,
// n = ceil(L / h) with L the profile's arc length (the last bin may reach past L).
struct WearGrid {
  double h_m = 1e-4;  // bin width [m] > 0
  int n = 0;          // number of bins

  // Bins of width h_m covering the whole profile. Throws InputError unless h_m is finite and > 0.
  static WearGrid ForProfile(const Profile& rail, double h_m);
  // Arc length of bin b's centre [m].
  double Centre(int b) const { return (b + 0.5) * h_m; }
};

// Per-column wear depth of one pass dz_j [m], size patch.grid.ns (column j = grid s index j).
// hardness_Pa > 0 (Archard, KTH; ignored by USFD), speed_m_s = V > 0 the rolling speed the
// tangential solution was computed at. Throws InputError when the patch has no grid (Hertz
// model) or no rolling stage, or for a non-positive hardness or speed.
std::vector<double> CalcColumnPassDepth(const PatchResult& patch, const WearLaw& law,
                                        double hardness_Pa, double speed_m_s);

// Rail arc lengths [m] of the projections of the grid's column edge points (section 2 above),
// size grid.ns + 1: column j covers the rail interval between entries j and j + 1 (in either
// order). `rail` locates the rail profile (material toward +z).
std::vector<double> CalcColumnEdgesOnRail(const PatchGrid& grid, const CurveLocator& rail);

// Per-column amounts (per_column[j] per unit reference arc, so per_column[j] * grid.ds_m is column
// j's amount, e.g. a worn area) spread over the bins of the profile `body` locates (rail or
// wheel, placed in the frame the patch was solved in), as amount per unit arc length: each column
// over the interval its edges project onto (section 2 above), conserving every column's amount.
std::vector<double> MapColumnAmounts(const PatchGrid& grid, const std::vector<double>& per_column,
                                     const CurveLocator& body, const WearGrid& wear_grid);

// Per-pass wear depth [m] of one patch on the bins, size wear_grid.n, area-conserving:
// sum_b depth_b h == sum_j dz_j ds (to rounding). Arguments as CalcColumnPassDepth; `rail` is
// the rail profile the patch was solved on. Throws as CalcColumnPassDepth.
std::vector<double> CalcPatchPassDepth(const PatchResult& patch, const Profile& rail,
                                       const WearLaw& law, double hardness_Pa, double speed_m_s,
                                       const WearGrid& wear_grid);
// The same with a locator built once on the rail profile (for many patches on one rail).
std::vector<double> CalcPatchPassDepth(const PatchResult& patch, const CurveLocator& rail,
                                       const WearLaw& law, double hardness_Pa, double speed_m_s,
                                       const WearGrid& wear_grid);

// Worn area per pass [m^2] (per metre of track) of a bin vector: sum_b depth_b h.
// depth_m: size wear_grid.n, [m].
double WornArea(const std::vector<double>& depth_m, const WearGrid& wear_grid);

// WLRM damage per axle pass [-] at every bin: patch.rolling->damage->wlrm_damage times the
// fraction of the bin the loaded columns cover (capped at 1). Size wear_grid.n. Throws
// InputError when the patch has no grid or no rolling stage, or was solved without the damage
// effect.
std::vector<double> CalcPatchDamageSpread(const PatchResult& patch, const Profile& rail,
                                          const WearGrid& wear_grid);
std::vector<double> CalcPatchDamageSpread(const PatchResult& patch, const CurveLocator& rail,
                                          const WearGrid& wear_grid);

// Frictional energy dissipated per unit rail surface area in one pass [J/m^2] at every bin,
// area-conserving: sum_b e_b h = rolling->tangential.frictional_power_W / V [J/m]. Size
// wear_grid.n. speed_m_s = V > 0. Throws InputError as CalcColumnPassDepth.
std::vector<double> CalcPatchPassEnergy(const PatchResult& patch, const Profile& rail,
                                        double speed_m_s, const WearGrid& wear_grid);
std::vector<double> CalcPatchPassEnergy(const PatchResult& patch, const CurveLocator& rail,
                                        double speed_m_s, const WearGrid& wear_grid);

}  // namespace railwear
