// A wheelset on a track: both wheels' contact, each on its rail (core/geometry/wheelset.h).
//
// The right-hand wheel and rail profiles of `wheel_rail` serve both sides: in the track the left
// wheel and rail are their mirror images, which in the left rail's own frame (y toward its field
// side, core/notation.md) are the same profiles; so results of the left wheel (positions,
// lateral forces, lateral creepage, spin) are in the left rail profile's own coordinates. Both
// wheels carry the same vertical load and share the axle's pitch velocity; the left wheel sees the
// mirrored yaw and roll. Prescribed creepages (RollingOptions::creepage) apply to each wheel in its
// own frame. Under a prescribed load each wheel is balanced vertically with its creep forces
// (SolveContact); with an axle force target the balanced solves and the pitch-velocity search
// alternate until both hold. Each wheel's FlangeClimbCheck (L/V, Nadal) is in its own rail frame.
#pragma once

#include "core/contact/contact_solver.h"
#include "core/geometry/wheelset.h"

namespace railwear {

struct WheelsetProblem {
  ContactProblem wheel_rail;  // right-hand profiles, materials, model, load per wheel, rolling
  TrackSpec track;
  WheelsetSpec wheelset;
};

struct WheelsetResult {
  WheelsetPlacement placement;
  ContactResult right;
  ContactResult left;
};

// Throws InputError as SolveContact does, and when the rail is too shallow for the gauge height.
WheelsetResult SolveWheelset(const WheelsetProblem& problem);

}  // namespace railwear
