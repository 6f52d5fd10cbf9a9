// Normal-tangential coupling through the cross terms of the seed's eq. 4 (the "coupling" effect).
//
// Seed eq. 4 gives the normal displacement of body b at cell i due to a unit tangential load at
// cell j as  w_x = c_t(b) k_d Δx/ρ²,  w_y = c_t(b) k_d Δs/ρ², with c_t(b) = 1 + c_s sign(b),
// sign +1 for a concave body (a flange root), -1 for a convex one (a gauge corner). The wheel
// carries the traction q and the rail -q, so the two bodies' contributions to the gap differ by
//   κ = c_t(wheel) k_d(wheel) − c_t(rail) k_d(rail),
// which vanishes for identical bodies of equal curvature sign (and for c_s = 0 with identical
// materials) but not at a gauge corner: 2 c_s k_d for identical steel. The gap of cell i grows by
//   u_i = κ Σ_j A_j (q_x,j Δx_ij + q_s,j Δs_ij) / ρ_ij²,
// Δx, Δs the offsets of i from j along j's tangents and ρ the distance (3-D on curved grids).
// The seed states the kernel but no coupled results, so the sign convention here is this file's
// (the gap grows ahead of a traction pointing away from i); tests check consistency only.
// Near cells (within 2 cells) are integrated with 4 x 4 Gauss points over the source cell;
// the cell's own contribution vanishes by symmetry.
#pragma once

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/patch_grid.h"
#include "core/contact/tangential_types.h"

namespace railwear {

// κ [m^2/N] (as k_d): see the file comment.
// wheel_sign, rail_sign: +1 concave, -1 convex (from the patch's lateral curvatures).
double CouplingCoefficient(const InfluenceConstants& c, const Material& wheel, int wheel_sign,
                           const Material& rail, int rail_sign);

// u [m] per grid cell (size grid.cells()) from the tractions of `t` on the same grid.
Eigen::VectorXd CouplingDisplacement(const PatchGrid& grid, const TangentialSolution& t,
                                     double kappa);

}  // namespace railwear
