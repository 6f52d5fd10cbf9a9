// The placement stage of SolveContact: the input checks, the placed wheel and rail, and the
// cases that end before any grid is built (no lateral overlap, no load). Internal to
// SolveContact.
#pragma once

#include <optional>
#include <string>

#include "core/contact/contact_problem.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// Throws InputError unless exactly one of the load and the approach is given, the rolling radius
// is positive and the normal solver's options are valid.
void CheckContactProblem(const ContactProblem& problem);

// Throws InputError for a rolling stage the problem cannot run: rolling contact asked of the
// Hertz model on a grid path (the Hertz model rolls only on the fast tread path, hertz_tread.h,
// which passes hertz_tread = true), damage without the rail's shear yield stress,
// speed or friction <= 0. Nothing to check without problem.rolling.
void CheckRollingProblem(const ContactProblem& problem, bool hertz_tread = false);

// The wheel's pose on the rail (problem.placement: lateral shift, roll, rolling radius, yaw).
WheelPose PoseOf(const ContactProblem& problem);

// The wheel placed on the rail at PoseOf(problem).
WheelRailGeometry PlaceWheel(const ContactProblem& problem);

// Why there is no contact to solve before any grid is built (the profiles do not overlap
// laterally, a zero load or approach); std::nullopt when there is one.
std::optional<std::string> NoContactBeforeGrid(const ContactProblem& problem,
                                               const WheelRailGeometry& geom);

}  // namespace railwear::internal
