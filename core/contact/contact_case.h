// One contact case as the front ends pose it (the CLI's `railwear contact`, the C API of
// include/railwear/railwear.h): a single wheel on its rail, or a wheelset on a track. The one
// entry point of both front ends, so that they give the same results bit for bit (issue 20:
// one engine, two front ends).
#pragma once

#include <optional>

#include "core/contact/wheelset_contact.h"

namespace railwear {

struct ContactCase {
  // The single wheel; for a wheelset the right-hand profiles, set-up, load per wheel and
  // rolling options (WheelsetProblem::wheel_rail).
  ContactProblem problem;
  // A wheelset on a track: the rest of its problem (track, wheelset, curvature, left load);
  // its wheel_rail is ignored, `problem` is used. Absent: the single wheel.
  std::optional<WheelsetProblem> wheelset;
  // A friction coefficient for normal contact: it has none of its own, but sets Nadal's limit
  // of the single wheel's flange-climb check (rolling contact uses problem.rolling->friction).
  std::optional<double> friction;
};

struct ContactCaseResult {
  ContactResult wheel;                     // the single wheel (empty for a wheelset)
  std::optional<WheelsetResult> wheelset;  // both wheels of a wheelset
};

// The model kind shorthand an explicit geometry and kernel match (halfspace = planar +
// boussinesq, conformal = conformal + golubenko), else kCustom: what a scene's `geometry` and
// `kernel` keys, the CLI's --kernel and the C API's RW_MODEL_CUSTOM make of them.
ModelKind MatchingModelKind(GeometryModel geometry, KernelModel kernel);

// Throws InputError as SolveContact and SolveWheelset do. `cache` (optional, the C API's handle
// keeps one) reuses the placed geometries of an earlier call at the same pose on the same
// profiles (placement_cache.h): the same results, bit for bit.
ContactCaseResult SolveContactCase(const ContactCase& c, PlacementCache* cache = nullptr);

}  // namespace railwear
