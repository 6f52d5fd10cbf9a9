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

}  // namespace railwear
