// Normal-tangential coupling through the cross terms of the seed's eq. 4 (the "coupling" effect).
//
// Seed eq. 4 gives the normal displacement of body b at cell i due to a unit tangential load at
// cell j as  w_x = c_t(b) k_d Δx/ρ²,  w_y = c_t(b) k_d Δs/ρ², with c_t(b) = 1 + c_s(b) sign(b),
// sign +1 for a concave body (a flange root), -1 for a convex one (a gauge corner), and c_s(b)
// the constant of b's set (InfluenceConstants::ForBody; one set for both bodies by default).
// The sign is the physical one (Cerruti; Landau & Lifshitz §8: on a half-space a tangential
// point load Q moves the surface into the body ahead of it, u_z = (1-2ν)/(4πG) Q x/ρ²; the same
// convention as calibration/displacement_curves.h, whose SeedKernelDisplacement a CalculiX
// run confirmed). The wheel carries the traction q (the rail's on the wheel, tangential_types.h)
// and the rail -q. At a cell i ahead of q (q . (P_i - P_j) > 0) the wheel's surface therefore
// moves into the wheel, opening the gap by c_t(wheel) k_d(wheel), while i lies behind the rail's
// load -q, where the rail's surface rises toward the wheel and closes the gap by
// c_t(rail) k_d(rail). The net coefficient
//   κ = c_t(wheel) k_d(wheel) − c_t(rail) k_d(rail)
// vanishes for identical bodies of equal curvature sign (and for c_s = 0 with identical
// materials) but not at a gauge corner: 2 c_s k_d for identical steel, a concave wheel on a
// convex rail. The gap of cell i grows by
//   u_i = κ Σ_j A_j (q_x,j Δx_ij + q_s,j Δs_ij) / ρ_ij²,
// Δx, Δs the offsets of i from j along j's tangents and ρ the distance (3-D on curved grids):
// with κ > 0 the gap opens ahead of the wheel's traction and closes behind it
// (coupling_test.cpp pins this down against the point-load formula for each body alone).
// Near cells (within 2 cells) are integrated with 4 x 4 Gauss points over the source cell;
// the cell's own contribution vanishes by symmetry.
#pragma once

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear {

// κ [m^2/N] (as k_d): see the file comment.
// wheel_sign, rail_sign: +1 concave, -1 convex (BodyCurvatureSign of the patch's lateral
// curvatures).
double CouplingCoefficient(const InfluenceConstants& c, const Material& wheel, int wheel_sign,
                           const Material& rail, int rail_sign);

// u [m] per grid cell (size grid.cells()) from the tractions of `t` on the same grid.
Eigen::VectorXd CouplingDisplacement(const PatchGrid& grid, const TangentialSolution& t,
                                     double kappa);

}  // namespace railwear
