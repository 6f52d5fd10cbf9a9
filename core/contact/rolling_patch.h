// The rolling stage's work on one patch (rolling_stage.h), shared with the fast tread path
// (hertz_tread.h): from the patch's grid and pressure and its per-cell rigid slip, the
// patch-average creepage, the tangential solution by the problem's method (the one seam,
// SolveTangential), the equivalent ellipse's semi-axes and, with the damage effect, the damage.
// Defined in rolling_stage.cpp. Internal to SolveContact.
#pragma once

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/tangential_method.h"

namespace railwear::internal {

// patch: a solved patch (grid, pressure_Pa of shape [grid.cells()], normal_force_N, p_max_Pa);
// in: its per-cell rigid slip (kinematics.h). problem.rolling must be set. reuse (optional):
// the exact solver's set-up and warm start kept for this patch (tangential_method.h).
RollingPatch SolveRollingPatch(const ContactProblem& problem, const PatchResult& patch,
                               const RollingInput& in, ExactTangentialReuse* reuse = nullptr);

}  // namespace railwear::internal
