// Rigid slip per cell from the motion of the wheel (not one creepage for the whole patch).
//
// Rail frame R (core/notation.md): x forward (rolling direction), y toward the field side,
// z down. The wheel moves forward at speed V and turns about its axle with the pitch velocity
// Omega (pure rolling at the nominal radius r0: Omega = -V / r0, negative about +y in this
// frame). The axle is the wheel frame's y axis at z_W = -r0, turned by the wheel's roll about x
// and by its yaw psi about +z (positive turns the nose toward +y; WheelPose::yaw_rad, the same
// yaw as the contact geometry's, roll after yaw: a = R_x(roll) R_z(psi) e_y). The rail is at rest.
// The rigid slip velocity at a cell centre P is v = V e_x + Omega a x r, with a the axle direction
// and r the perpendicular from the axle to P; the creepage of the cell is v / V resolved on its
// tangents: x and the patch cross-section's s tangent (tangent_yz).
//
// Yaw is part of the geometry (core/geometry/yawed_wheel.h): a yawed wheel touches ahead of or
// behind its axle, and the cells' positions x carry that lead, so the rigid slip is taken at the
// displaced contact point. At an inclined contact (angle gamma) this gives the lateral creepage
// -psi sec(gamma) of the classical theory.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear {

struct WheelMotion {
  double speed_m_s = 1.0;                      // V > 0
  std::optional<double> pitch_velocity_rad_s;  // Omega; pure rolling (-V/r0) when absent
  // Lateral velocity of the wheel toward +y [m/s] (a wheelset's dy/dt while it moves across the
  // track, e.g. in hunting): adds dy/dt / V to the lateral creepage before the contact angle's
  // 1 / cos(gamma), as yaw's -psi does.
  double lateral_velocity_m_s = 0.0;
  // Yaw velocity of the wheel about +z (down) through its profile origin [rad/s] (a wheelset in
  // a curve of radius R turns at -V/R): adds omega_z e_z x (P - O) to the slip at P, O the
  // origin, so a contact point away from the origin slips with its distance from the curve's
  // centre. `speed_m_s` is the origin's speed.
  double yaw_velocity_rad_s = 0.0;
};

// Kalker-style creepages: w_x = xi - phi (s - s_c), w_s = eta + phi (x - x_c), about the
// patch's pressure centre (x_c, s_c).
struct Creepage {
  double xi = 0.0;
  double eta = 0.0;
  double spin_per_m = 0.0;  // phi [1/m]
};

// Per-cell creepage of a patch from the wheel's motion.
RollingInput RigidSlipFromMotion(const WheelRailGeometry& geometry, const PatchGrid& grid,
                                 const WheelMotion& motion, double friction);

// Per-cell creepage from prescribed creepages about the pressure centre of the patch (the same
// point AverageCreepage fits about, so that a fitted average prescribed back gives the same
// constant field): w_x = xi - phi (s - s_c), w_s = eta + phi (x - x_c).
RollingInput RigidSlipFromCreepage(const PatchGrid& grid, const Eigen::VectorXd& pressure,
                                   const Creepage& creepage, double speed_m_s, double friction);

// Pressure-weighted centre (x_c, s_c) of a patch [m]; (0, 0) when nothing is in contact.
Eigen::Vector2d PressureCentre(const PatchGrid& grid, const Eigen::VectorXd& weight);

// Patch-average creepages: the least-squares fit of (xi, eta, phi) to the per-cell creepage
// over the cells with positive weight (pressure), about the weighted centre (x_c, s_c).
Creepage AverageCreepage(const PatchGrid& grid, const Eigen::VectorXd& weight,
                         const RollingInput& input);

}  // namespace railwear
