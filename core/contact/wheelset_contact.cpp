// Both wheels of a wheelset on their rails.
#include "core/contact/wheelset_contact.h"

namespace railwear {

WheelsetResult SolveWheelset(const WheelsetProblem& problem) {
  WheelsetResult out;
  out.placement = PlaceWheelset(problem.wheel_rail.rail_profile, problem.track, problem.wheelset);
  const WheelPose& r = out.placement.right;
  const WheelPose& l = out.placement.left;

  ContactProblem right = problem.wheel_rail;
  right.placement = {r.lateral_shift_m, r.roll_rad, r.rolling_radius_m};
  if (right.rolling) right.rolling->motion.yaw_rad = problem.wheelset.yaw_rad;

  // The left wheel and rail are the mirror images of the right ones in the track; in the left
  // rail's own frame (y toward its field side) they are the same profiles, so only the pose
  // (PlaceWheelset) and the yaw are mirrored.
  ContactProblem left = problem.wheel_rail;
  left.placement = {l.lateral_shift_m, l.roll_rad, l.rolling_radius_m};
  if (left.rolling) left.rolling->motion.yaw_rad = -problem.wheelset.yaw_rad;

  out.right = SolveContact(right);
  out.left = SolveContact(left);
  return out;
}

}  // namespace railwear
