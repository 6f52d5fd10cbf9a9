// The rolling stage of SolveContact (the "tangential" effect) on the normal patches of a
// result: rigid slip per cell (from the wheel's motion or prescribed creepages), its patch
// average, the tangential solution by the problem's method (tangential_method.h) and, with the
// damage effect, damage per patch; with a prescribed longitudinal force the pitch velocity that
// carries it.
#pragma once

#include <functional>
#include <optional>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear {

// The rolling stage alone on a result of SolveContact (its normal patches): rigid slip, the
// tangential solution and, when asked, damage per patch. The pitch velocity used is stored in
// result->pitch_velocity_rad_s. problem.rolling must be set (and not hold a force target: that
// is SolveContact's and SolveWheelset's business).
// `geometry` is the problem's placed wheel and rail (to reuse it across repeated calls).
// The normal patches are left as they are: no vertical balance with the new creep forces (that
// is SolveContact's normal-tangential stage; SolveWheelset re-solves after its search).
void ApplyRolling(const ContactProblem& problem, const WheelRailGeometry& geometry,
                  ContactResult* result);

// The pitch velocity Omega = -V (1 + c) / r0 for which fx(Omega) = target_N, with fx increasing
// in the spin-up creepage c (a driving wheel turns faster than it rolls). Brackets c outward up
// to |c| = 1, then bisection with secant steps to |fx - target| <= tolerance_N. nullopt when the
// target lies beyond the largest force the bracket reaches (beyond adhesion).
std::optional<double> SolvePitchVelocityForForce(const std::function<double(double)>& fx,
                                                 double target_N, double speed_m_s,
                                                 double rolling_radius_m, double tolerance_N);

// Sums over a result's patches [N]: the creep forces F_x on the wheel (0 for a patch without a
// rolling solution), and the pressures' normal forces.
double TotalForceX(const ContactResult& r);
double TotalNormalForce(const ContactResult& r);

namespace internal {

// The rolling stage of SolveContact: ApplyRolling, or with problem.rolling->longitudinal_force_N
// the pitch velocity solved for that force (status kNotConverged in *result when friction
// cannot carry it).
void RunRollingStage(const ContactProblem& problem, const WheelRailGeometry& geom,
                     ContactResult* result);

}  // namespace internal

}  // namespace railwear
