// SolveContact: one wheel on one rail, end to end. Placement -> contact search -> patch grids
// and gaps -> influence operators -> normal solve -> patch results -> (rolling -> coupling).
// The entry point of the contact module: includes the problem and result types and the rolling
// stage's public functions that callers need.
#pragma once

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/rolling_stage.h"

namespace railwear {

// Throws InputError for inconsistent input (both or neither load given, non-positive radius,
// rolling contact asked of the Hertz model, which has no grid; damage without the rail's shear
// yield stress).
ContactResult SolveContact(const ContactProblem& problem);

// The same with the wheel already placed on the rail: `placed` must be the WheelRailGeometry of
// problem.wheel_profile, problem.rail_profile and problem.placement (callers that solve one
// placement several times, e.g. a wheelset's axle-force search, build it once).
// `placement_s` is the time its construction took (reported as the "placement" stage).
ContactResult SolveContact(const ContactProblem& problem, const WheelRailGeometry& placed,
                           double placement_s = 0.0);

}  // namespace railwear
