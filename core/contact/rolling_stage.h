// The rolling stage of SolveContact (the "tangential" effect) on the normal patches of a
// result: rigid slip per cell (from the wheel's motion or prescribed creepages), its patch
// average, the tangential solution by the problem's method (tangential_method.h) and, with the
// damage effect, damage per patch; with a prescribed longitudinal force the pitch velocity that
// carries it.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/tangential_method.h"
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
// in the spin-up creepage c (a driving wheel turns faster than it rolls). Brackets c outward from
// start_c (first step first_step_c, doubling) up to |c - start_c| = 1, then bisection with secant
// steps to |fx - target| <= tolerance_N. nullopt when the target lies beyond the largest force
// the bracket reaches (beyond adhesion). The defaults start at rolling without spin-up; a caller
// that knows a nearby solution (the previous search of a loop) starts there with a small step.
std::optional<double> SolvePitchVelocityForForce(const std::function<double(double)>& fx,
                                                 double target_N, double speed_m_s,
                                                 double rolling_radius_m, double tolerance_N,
                                                 double start_c = 0.0, double first_step_c = 1e-4);

// What the rolling stage keeps from one run to the next on the same patches (SolveContact's
// vertical balance and coupling loop repeat it on the same grids with slightly changed pressure):
// per patch the exact solver's set-up and warm start, and the spin-up creepage c of the last
// pitch search under a prescribed longitudinal force, where the next search starts
// (kPitchRestartStep). For one contact solve (one problem's materials and patch grids).
struct RollingStageMemory {
  std::vector<ExactTangentialReuse> patches;  // one per patch of the result
  std::optional<double> spin_up_creepage;     // c of the last pitch search's solution
};

// The first bracketing step of a pitch search restarted at the last search's solution: 1e-6,
// well below the creepages of a patch in partial slip (1e-5 to 1e-3) and far above the shift of
// the solution between two of the loop's repeats (the pressure moves by the balance's or the
// coupling's last correction); a wrong guess costs only a few doublings.
inline constexpr double kPitchRestartStep = 1e-6;

// Sums over a result's patches [N]: the creep forces F_x on the wheel (0 for a patch without a
// rolling solution), and the pressures' normal forces.
double TotalForceX(const ContactResult& r);
double TotalNormalForce(const ContactResult& r);

namespace internal {

// The rolling stage of SolveContact: ApplyRolling, or with problem.rolling->longitudinal_force_N
// the pitch velocity solved for that force (status kNotConverged in *result when friction
// cannot carry it). memory (optional, in/out): what is kept from one solve of a patch to the
// next, across the pitch search's evaluations and across calls (the loop's repeats); its
// patches are resized to those of *result. Results agree with a run without it to the exact
// solver's tolerance and the pitch search's (1e-6 mu F_n).
void RunRollingStage(const ContactProblem& problem, const WheelRailGeometry& geom,
                     ContactResult* result, RollingStageMemory* memory = nullptr);

}  // namespace internal

}  // namespace railwear
