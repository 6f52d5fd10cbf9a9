// Internal to core/vehicle and its tests, not the library's interface (no scene key, option or
// binding reaches it): the curving solve with each wheelset's contact forces taken from a given
// function instead of the contact solve, so that the Newton rules of SolveCurving (docs/curving.md,
// "The Newton rules") can be tested on analytic forces, e.g. a stiff flange whose lateral force
// steps at a lateral position. SolveCurving is SolveCurvingWith and an empty function.
#pragma once

#include <functional>
#include <vector>

#include "core/vehicle/curving.h"

namespace railwear {
namespace internal {

// The rails' forces on one wheelset, in CurvedWheelset's conventions: the lateral force [N]
// (track frame, +Y toward the high rail) and the yaw moment about its centre [N m].
struct WheelsetForces {
  double lateral_N = 0.0;
  double yaw_moment_Nm = 0.0;
};

// Wheelset `index` (from the front) at lateral displacement y [m] and angle of attack psi [rad].
// Called from the solve's worker threads (CurvingOptions::threads): it must be thread-safe.
using WheelsetForceModel = std::function<WheelsetForces(int index, double y_m, double psi_rad)>;

// What the Newton iteration of a solve did, in order (a test's record of which rule acted).
enum class NewtonEvent {
  kSolve,                     // a start's (or phase's) Newton solve began
  kFreshJacobian,             // the Jacobian evaluated by finite differences
  kLineSearch,                // the line search accepted a step
  kLineSearchFailed,          // ... and refused every trial
  kLevenbergMarquardt,        // a Levenberg-Marquardt trial accepted
  kLevenbergMarquardtFailed,  // every Levenberg-Marquardt trial refused
  kNaturalLevel,              // the natural-level step accepted a trial
  kNaturalLevelFailed,        // ... and refused every trial
  kProbeMoved,                // ProbeForceStep did not bracket but reduced the residual
  kProbeFailed,               // ProbeForceStep neither bracketed nor reduced it
  kStalled,                   // a start that was not the last gave up, stalled far off
  kEnded,                     // a rule ended the solve (CurvingResult::ending names it)
};

// The lateral position [m, the wheel profile's frame] of the tip-side end of `wheel`'s steepest
// flank: from the flange's tip (the profile's deepest point) toward the tread, the first point
// whose slope comes within half a degree of the front face's steepest (S1002: near y = -39.6 mm,
// 70 deg). A contact beyond it (toward the tip) climbs (CurvedWheelset::climbing).
double SteepestFlankTipSideY(const Profile& wheel);

// SolveCurving with `forces` in place of every wheelset's contact solve (empty: the contact, as
// SolveCurving). The returned wheelsets carry the model's forces; their contact results are
// empty, marked converged, and they are never in flange climb. The problem is validated as
// SolveCurving's (its profiles place the rails; the contact model decides whether a predictor
// phase comes first: give options.predictor = contact.model for one phase).
// `events`, when given, receives what the Newton iterations did.
CurvingResult SolveCurvingWith(const CurvingProblem& problem, const WheelsetForceModel& forces,
                               std::vector<NewtonEvent>* events = nullptr);

}  // namespace internal
}  // namespace railwear
