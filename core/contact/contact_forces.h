// The one labelled force convention of railwear's outputs (issue 14), and the flange-climb
// check (L/V against Nadal's limit).
//
// Forces are those the wheel exerts ON THE RAIL unless a name says "on the wheel". Frames
// (core/notation.md):
//   rail   R: the rail profile's frame, x forward, y toward the rail's field side, z down;
//   track  T: x forward, Y to the right, z down; the right rail's frame is parallel to it, the
//             left rail's frame is its mirror (y = -Y);
//   patch  (normal, longitudinal, lateral): the normal along the pressure resultant of the patch
//             (into the rail), longitudinal = x, lateral in the tangent plane toward the field
//             side: (0, cos g, -sin g) in R at the contact angle g.
// Each force has a normal part (the pressure's resultant) and a creep part (the reaction of the
// tangential tractions of the rail on the wheel, TangentialSolution), and their sum.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/contact/contact_result.h"

namespace railwear {

// A force on the rail in the rail frame R, (x, y, z) [N].
struct ForceParts {
  Eigen::Vector3d normal_N = Eigen::Vector3d::Zero();  // the pressure's resultant
  Eigen::Vector3d creep_N = Eigen::Vector3d::Zero();   // the creep forces' reaction on the rail
  Eigen::Vector3d Net() const { return normal_N + creep_N; }
};

// The patch's force on the rail in R; creep part zero without rolling contact.
ForceParts PatchForcesOnRail(const PatchResult& patch);
// The sum over the result's patches.
ForceParts TotalForcesOnRail(const ContactResult& result);

// A rail-frame vector f [N] in the patch frame at contact angle g [rad]: (normal, longitudinal,
// lateral) = (f . (0, sin g, cos g), f_x, f . (0, cos g, -sin g)).
Eigen::Vector3d RailToPatchFrame(const Eigen::Vector3d& f, double contact_angle_rad);

// A rail-frame vector in the track frame: unchanged for a right wheel, y mirrored for a left one.
Eigen::Vector3d RailToTrackFrame(const Eigen::Vector3d& f, bool left_wheel);

// Nadal's flange-climb limit (Nadal 1908) (tan g - mu) / (1 + mu tan g) at contact angle g
// [rad] and friction mu; nullopt where g <= atan(mu): the limit is <= 0 there, the wheel cannot
// climb a slope that friction alone holds (railwear reports no limit and warns of nothing).
std::optional<double> NadalLimit(double contact_angle_rad, double friction);

// Sets a result's totals from its patches: area, largest p_max, vertical and lateral force, and
// the plastic cells, area and force (after a caller replaced patches, as the wear's friction
// zones do).
void SumPatchTotals(ContactResult* r);

// The check for a result; friction absent for normal contact (L/V only, no limit).
FlangeClimbCheck CheckFlangeClimb(const ContactResult& result, std::optional<double> friction);

// The same check at the wheel's steepest loaded contact angle instead of each patch's resultant
// angle (steady-state curving, core/vehicle/curving.h). A conformal patch that wraps from the
// flange root (about 30 degrees) onto the flange (70) as the flange comes into contact has a
// resultant angle between both, and Nadal's limit there is far below the one that governs
// climbing, that of the flange. The angle here is the steepest of the grid columns that carry at
// least 5 % of the patch's most loaded column (the patch's own angle for a planar grid or a
// Hertz patch, where every normal is the same).
FlangeClimbCheck CheckFlangeClimbAtSteepest(const ContactResult& result, double friction);

// The one-line warning for an exceeded check ("L/V 2.31 exceeds Nadal's limit 1.18 at 69.5 deg,
// mu 0.35: flange climb possible"); `wheel` ("right wheel", ...) may be empty.
std::string FlangeClimbWarning(const FlangeClimbCheck& check, const std::string& wheel);

}  // namespace railwear
