// The fast tread path (issue 20): kind = "hertz" with rolling contact, solved as multibody codes
// solve a tread contact, for a single wheel.
//
//  1. A cheap placement instead of WheelRailGeometry's (which samples the whole yawed wheel
//     outline and both profiles every 20 um and builds their locators): the wheel's silhouette
//     seen along the rail (the closed form of core/geometry/yawed_wheel.h, per profile point)
//     against the rail's upper envelope on the profiles' own points (0.1 mm apart for the
//     built-in ones), its smallest vertical gap refined on the splines by golden section. That
//     point lowered to first contact is the contact point.
//  2. Hertz's ellipse from the principal relative curvatures there (hertz_estimate.h's
//     CandidateCurvatures: the wheel's parallel circle by Meusnier, the lateral curvatures of the
//     two profiles), for the load or the approach.
//  3. The tangential solution on a planar grid over that ellipse carrying Hertz's pressure
//     (scaled so that the cells carry the normal force exactly), by the problem's tangential
//     method through the rolling stage's per-patch seam (rolling_patch.h; FASTSIM by default),
//     with the rigid slip of the wheel's motion per cell (rigid_motion.h). With a vertical load,
//     the normal force is balanced against the creep forces' vertical part as the grid models do
//     (balance_target.h).
//
// When it applies, and what it reports otherwise: the contact must be ONE Hertzian patch. The
// patch is measured as kind = "auto" measures it before it picks Hertz (model_selection.h:
// ChoosePatchModel on the normal's angle and turn, the approach weight and the gap's departure
// from Hertz's quadratic over the Hertz patch, at the preset's limits), and a second basin of
// the gap within 1.5 times the approach (two-point contact: tread and flange root, say) also
// disqualifies it. Not applying, SolveHertzRolling falls back to the full path, kind = "auto"
// at the same accuracy (Hertz, halfspace or conformal per patch on its grids), and each patch's
// model_reason starts with "fast tread path not valid: " and why; the patches' `model` is then
// the grid model auto chose, "hertz" only on the fast path.
//
// Approximations (docs/library.md, "The fast tread path", measures them against the full path):
// Hertz's constant curvatures over the patch; the wheel's lateral curvature is its profile's, not
// its yawed silhouette's (they differ at O(yaw)); the coarse gap is linear between the profiles'
// points before the refinement on the splines.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"

namespace railwear {

// Where the fast path's contact point lies on the wheel: the wheel frame of rw_patch (API 1.2).
struct HertzTreadPoint {
  // Along the wheel's own rolling direction (its yaw undone) from the wheel profile origin's
  // cross-section, > 0 ahead of the axle [m].
  double wheel_x_m = 0.0;
  // The wheel profile point (y, z) of the contact, frame W [m]: wheel radius r0 + z there.
  double wheel_y_m = 0.0, wheel_z_m = 0.0;
};

// True for the problems the fast path serves: kind = hertz with rolling contact.
bool IsHertzRolling(const ContactProblem& problem);

// The fast path on `problem` (IsHertzRolling; a single wheel). std::nullopt when the contact is
// not one Hertzian patch, with the reason in *why_not. point (optional out): the contact point in
// the wheel frame. Throws InputError for the coupling effect (it needs a grid model) and as
// SolveContact does for bad input.
std::optional<ContactResult> SolveHertzTread(const ContactProblem& problem, std::string* why_not,
                                             HertzTreadPoint* point = nullptr);

// The model the full path falls back to: kind = auto at the problem's accuracy, cell sizes and
// influence constants.
ModelOptions HertzTreadFallbackModel(const ModelOptions& hertz);

// A full solve of a problem (SolveContact, or SolveContactCase's with its placement cache).
using FullContactSolve = std::function<ContactResult(const ContactProblem&)>;

// A fallback's result marked as such: each patch's model_reason becomes "fast tread path not
// valid: " + why, then "; full path: " and the full path's own reason when it gave one.
void MarkTreadFallback(const std::string& why, ContactResult* result);

// kind = hertz with rolling contact: the fast path, or when it does not apply `full` on the
// problem with HertzTreadFallbackModel, its patches' model_reason saying why (file comment).
// point (optional out): set to the fast path's wheel-frame point, reset on the fallback.
ContactResult SolveHertzRolling(const ContactProblem& problem, const FullContactSolve& full,
                                std::optional<HertzTreadPoint>* point = nullptr);

struct ContactCase;
struct ContactCaseResult;
class PlacementCache;
class ContactWarmStart;
// SolveContactCase (contact_case.h) that also gives the fast tread path's wheel-frame point: set
// when the single wheel took the fast path, reset otherwise (the C API reports it as rw_patch's
// wheel-frame location, which it finds on the placed geometry for every other solve).
// warm (optional, in/out): a single wheel's grid solve starts from the last call's measured
// patch and balance and keeps its own (contact_warm_start.h); a wheelset's right wheel uses it,
// and its left wheel left_warm, as SolveWheelset's right_warm and left_warm (without an axle
// force target).
ContactCaseResult SolveContactCase(const ContactCase& c, PlacementCache* cache,
                                   std::optional<HertzTreadPoint>* tread_point,
                                   ContactWarmStart* warm = nullptr,
                                   ContactWarmStart* left_warm = nullptr);

}  // namespace railwear
