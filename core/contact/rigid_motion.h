// The wheel's rigid motion in the rail frame R: the slip velocity of any point of the wheel
// relative to the rail at rest, from its speed, pitch velocity about the axle, lateral velocity
// and yaw velocity (the model of kinematics.h, whose RigidSlipFromMotion samples it cell by cell
// on a placed WheelRailGeometry). Shared with the fast tread path (hertz_tread.h), which places
// the wheel without a WheelRailGeometry. Defined in kinematics.cpp.
#pragma once

#include <Eigen/Core>

#include "core/contact/kinematics.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear {

struct WheelRigidMotion {
  double speed_m_s = 1.0;             // V > 0 of the wheel profile origin, along x
  double pitch_velocity_rad_s = 0.0;  // Omega about the axle direction
  double lateral_velocity_m_s = 0.0;  // along +y
  double yaw_velocity_rad_s = 0.0;    // about +z through the wheel profile origin
  Eigen::Vector3d axle_point_m = Eigen::Vector3d::Zero();  // a point of the axle (x = 0), R
  Eigen::Vector3d axle_direction = Eigen::Vector3d::UnitY();  // unit, R
  Eigen::Vector2d origin_yz_m = Eigen::Vector2d::Zero();      // the wheel profile origin (y, z), R

  // Slip velocity [m/s] of the wheel's material point at p_R (x, y, z in R) relative to the rail:
  // V e_x + dy/dt e_y + Omega a x r + omega_z e_z x (p - origin), r the perpendicular from the
  // axle to p.
  Eigen::Vector3d SlipVelocity(const Eigen::Vector3d& p_R) const;
};

// The motion of a wheel whose axle passes through axle_yz_m and whose profile origin is at
// origin_yz_m (both (y, z) in R of the placed wheel: its W points (0, -r0) and (0, 0)), with
// roll and yaw [rad] (roll after yaw, as the geometry's), rolling radius r0 [m] (the pitch
// velocity's default -V / r0 when motion gives none).
WheelRigidMotion MakeWheelRigidMotion(const Eigen::Vector2d& axle_yz_m,
                                      const Eigen::Vector2d& origin_yz_m, double roll_rad,
                                      double yaw_rad, double rolling_radius_m,
                                      const WheelMotion& motion);

// Per-cell creepage of `grid` under `motion` (RigidSlipFromMotion's loop): the slip velocity at
// each cell centre divided by V, resolved on x and the cell row's s tangent.
RollingInput RigidSlipOfMotion(const WheelRigidMotion& motion, const PatchGrid& grid,
                               double friction);

}  // namespace railwear
