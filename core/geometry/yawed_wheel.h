// YawedWheelSection: a wheel of revolution turned by a yaw angle, seen along the rail.
//
// The rail is prismatic along x, so two bodies touch where the wheel's outline seen along x (its
// silhouette, the "contact locus" of MBS codes) touches the rail's cross-section. For an unyawed
// wheel that outline is the wheel profile itself, at x = 0 below the axle. A yawed wheel touches
// ahead of or behind its axle: a point of the profile with outward normal (n_y, n_z) in the
// meridian plane (y along the axle, z toward the rail) lies on the outline at the angle theta
// about the axle (from straight below the axle, positive forward) where the surface normal has no
// x component:
//
//   sin(theta) = (n_y / n_z) tan(psi),
//
// and there, with r = r0 + z the wheel's radius at the profile point (exact, no small-angle
// approximation):
//
//   x = r sin(theta) cos(psi) - y sin(psi)     (forward, from the wheel profile origin)
//   Y = r sin(theta) sin(psi) + y cos(psi)     (lateral, in the unrolled wheel frame)
//   Z = r cos(theta) - r0                      (toward the rail)
//
// On a profile of slope angle gamma (n_y / n_z = tan(gamma) on the flange side) the point leads
// the axle line through it by r tan(gamma) tan(psi) / cos(psi) (the well-known r tan(gamma)
// tan(psi) for small psi).
//
// Frames (core/notation.md): the wheel profile frame W; yaw psi about +z (down), positive turns
// the nose (+x) toward +y. Roll is applied after yaw, as a rotation of the outline about x (the
// outline seen along x turns with it exactly); the kinematics (core/contact/kinematics.h) use the
// same order, so geometry and rigid slip describe one body.
//
// Where the outline is not defined (|n_y / n_z tan(psi)| >= 1: faces steeper than
// 90 deg - |psi|, the vertical flange back) theta is held at the bound kMaxSinTheta; such faces
// never touch a rail from above.
//
// The outline follows the surface normal, so a measured profile's noise in its slope moves its
// points round the wheel and can fold it (swallowtails of micrometres on a flange face, loops on
// a noisy near-vertical face). The hidden parts are removed: samples that step back against the
// profile's direction, then the loops between crossing segments. A smooth profile keeps every
// sample (tests/core/geometry/yawed_wheel_test.cpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/profile/profile.h"

namespace railwear {

class YawedWheelSection {
 public:
  // Bound on |sin(theta)| where the outline is undefined (steep faces).
  static constexpr double kMaxSinTheta = 0.5;

  // wheel: the wheel profile (frame W); r0 > 0 its radius at z = 0 [m]; yaw_rad with
  // |yaw_rad| < 0.5 (a wheel on a rail is never yawed by more than a few degrees; the bound keeps
  // the outline single-valued); step_m the arc-length sampling of the outline (> 0).
  YawedWheelSection(const Profile& wheel, double r0, double yaw_rad, double step_m = 2e-5);

  // The outline as a profile in the unrolled, yawed wheel frame (Y, Z), ready for the 2-D
  // contact search; its points are the samples below, in the wheel profile's order.
  const Profile& outline() const { return outline_; }

  // For the outline point nearest (Y, Z) [m] (interpolated between samples): the wheel profile
  // parameter s of the surface point it comes from, and that point's x [m] (forward of the wheel
  // profile origin, in the yawed frame).
  struct Source {
    double wheel_s_m = 0.0;
    double x_m = 0.0;
  };
  Source SourceOf(const Eigen::Vector2d& yz) const;

  // The same for the outline's own arc-length parameter (outline().Length() range).
  Source SourceAt(double outline_s_m) const;

  // Closed form for one profile point: sin(theta) from its outward normal (n_y, n_z) in W,
  // clamped to +-kMaxSinTheta.
  static double SinTheta(const Eigen::Vector2d& outward_normal_W, double yaw_rad);
  // The same with tan(yaw_rad) given (bit for bit SinTheta's value), for callers that evaluate
  // many points at one yaw (the fast tread path, core/contact/hertz_tread.cpp).
  static double SinThetaFromTan(const Eigen::Vector2d& outward_normal_W, double tan_yaw);

 private:
  Profile outline_;
  std::vector<double> wheel_s_;    // per sample: wheel profile parameter [m]
  std::vector<double> x_;          // per sample: x of the surface point [m]
  bool knots_are_samples_ = true;  // outline_'s knots are the samples (no subdivision)
};

}  // namespace railwear
