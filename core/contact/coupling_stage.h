// The coupling stage of SolveContact (the "coupling" effect): the tangential tractions add
// CouplingDisplacement (coupling.h, seed eq. 4 cross terms) to each patch's gap; the normal and
// rolling stages are repeated until the pressure settles. Internal to SolveContact.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/normal_solver.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// cands[kept_build[k]] is the candidate of result->patches[k], whose cells start at
// kept_offset[k] in np's vectors; np is the uncoupled normal problem (its gap is changed) and
// pressure its solution [Pa], shape [np->gap_m.size()]. Iterations, the relative area and peak
// changes, or kNotConverged go into *result.
void SolveCoupled(const ContactProblem& problem, const WheelRailGeometry& geom,
                  const std::vector<ContactCandidate>& cands, const std::vector<int>& kept_build,
                  const std::vector<int>& kept_offset, NormalProblem* np, Eigen::VectorXd pressure,
                  ContactResult* result);

}  // namespace railwear::internal
