// WheelRailGeometry: a wheel placed on a rail (lateral shift, roll, rolling radius), lowered
// until first contact, with the geometric queries the contact patches need.
//
// Frames (core/notation.md): rail frame R (y toward the field side, z down); wheel profile frame
// W (origin on the taping line, z toward the rail, axle at z = -r0). The wheel profile's origin
// sits at (lateral_shift, dz) in R, rotated by roll about x; dz is chosen so that the smallest
// vertical gap between the bodies is zero (first contact).
//
// Yaw: a wheel yawed by psi touches the rail ahead of or behind its axle. The 2-D search runs on
// the wheel's outline seen along the rail (core/geometry/yawed_wheel.h), which is exact for the
// prismatic rail; wheel() is that outline's locator and wheel_surface() the wheel profile's, on
// which ProjectOnWheel measures 3-D distances to the yawed body of revolution. Without yaw both
// are the wheel profile and every result is that of the unyawed geometry, bit for bit. Roll turns
// the yawed outline about x (roll after yaw; the kinematics use the same order).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/curve_locator.h"
#include "core/geometry/yawed_wheel.h"
#include "core/profile/profile.h"

namespace railwear {

struct WheelPose {
  double lateral_shift_m = 0.0;
  double roll_rad = 0.0;
  double rolling_radius_m = 0.46;
  // About +z (down), through the wheel profile origin: positive turns the nose (+x) toward +y.
  // |yaw| < 0.5 rad.
  double yaw_rad = 0.0;
};

// A potential contact region found on the vertical-gap function g(y) at x = 0.
struct ContactCandidate {
  double y_lo_m = 0.0, y_hi_m = 0.0;  // lateral interval (R) where g < threshold
  // True where the interval ends at a saddle shared with a neighbouring candidate (two-point
  // contact) rather than where the gap reaches the threshold.
  bool split_lo = false, split_hi = false;
  double y_m = 0.0;        // lateral position of the smallest gap in the interval
  double gap_m = 0.0;      // that smallest vertical gap (0 at first contact)
  double rail_s_m = 0.0;   // rail profile parameter of the contact point
  double wheel_s_m = 0.0;  // wheel profile parameter of the contact point
  Eigen::Vector2d rail_point_m = Eigen::Vector2d::Zero();  // on the rail, R
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();        // rail outward normal there, R
  double rail_lateral_curvature = 0.0;                     // 1/m, convex positive
  double wheel_lateral_curvature = 0.0;                    // 1/m, convex positive
  double wheel_radius_m = 0.0;                             // rolling radius at the contact point
  // Longitudinal position of the contact point [m], R, from the wheel profile origin's
  // cross-section (0 without yaw), and its lead over the axle line at the point's lateral
  // position (> 0 ahead of the axle): r tan(gamma) tan(psi) / cos(psi) on a cone.
  double x_m = 0.0;
  double lead_m = 0.0;
};

class WheelRailGeometry {
 public:
  // Profiles must outlive this object. vertical_step_m is the lateral sampling of g(y).
  WheelRailGeometry(const Profile& wheel, const Profile& rail, const WheelPose& pose,
                    double vertical_step_m = 2e-5);

  // False when the profiles do not overlap laterally (no contact is possible).
  bool has_overlap() const { return has_overlap_; }
  const WheelPose& pose() const { return pose_; }
  double dz_m() const { return dz_; }

  // Connected lateral intervals where g(y) < threshold, split at saddles that rise by more than
  // a tenth of the threshold above the minima on both sides; each with its contact point.
  std::vector<ContactCandidate> FindCandidates(double threshold_m) const;
  // The candidate `interval` (one of FindCandidates') with its contact point moved to the lateral
  // position y_m [m] (clamped to the interval): the rail point under it, the wheel point above,
  // their normal, curvatures and radius, as FindCandidates fills them at the smallest gap. y_m and
  // gap_m stay the interval's smallest gap, by which the candidate is found again. The planar
  // grid's tangent plane is re-centred on a solved patch's pressure centre this way
  // (core/contact/potential_area.h).
  ContactCandidate CandidateAt(const ContactCandidate& interval, double y_m) const;

  // Transforms between the wheel profile frame W (x = 0 cross-section) and R.
  Eigen::Vector2d WheelToRail(const Eigen::Vector2d& p_W) const;
  Eigen::Vector2d RailToWheel(const Eigen::Vector2d& p_R) const;
  // A direction of R in the wheel profile frame (the roll undone).
  Eigen::Vector2d RailDirectionToWheel(const Eigen::Vector2d& d_R) const;
  // A 3-D point (x, y, z) in R in the wheel's meridian coordinates (y_W, r - r0): the point's
  // position in the wheel profile frame after rotating it about the axle into the x = 0 plane.
  Eigen::Vector2d Meridian(const Eigen::Vector3d& p_R) const;

  const CurveLocator& rail() const { return rail_locator_; }
  // The wheel's cross-section seen along the rail (the yawed outline; the profile without yaw).
  const CurveLocator& wheel() const { return wheel_locator_; }
  // The wheel profile itself (the body of revolution's meridian), for 3-D projections.
  const CurveLocator& wheel_surface() const {
    return surface_locator_ ? *surface_locator_ : wheel_locator_;
  }
  // The wheel-profile parameter of wheel()'s parameter s, and the longitudinal position x [m]
  // (R, from the wheel profile origin's cross-section) of the surface point there.
  YawedWheelSection::Source SurfaceSource(double outline_s_m) const;

  // Signed distance of a 3-D point (R) to the wheel surface (> 0 outside), with the wheel
  // profile parameter of the closest point; the search covers [s_lo, s_hi] of the wheel profile
  // (wheel_surface()'s parameter).
  CurveLocator::Projection ProjectOnWheel(const Eigen::Vector3d& p_R, double s_lo,
                                          double s_hi) const;
  // The same for the (prismatic) rail: only (y, z) matters.
  CurveLocator::Projection ProjectOnRail(const Eigen::Vector2d& yz_R, double s_lo,
                                         double s_hi) const;

  // The sampled vertical gap g(y) that FindCandidates searches (0 at first contact, NaN where
  // the profiles do not overlap), at the lateral positions gap_samples_y() [m], R, one
  // vertical_step_m apart (empty without overlap).
  const std::vector<double>& gap_samples_y() const { return gap_y_; }
  const std::vector<double>& gap_samples() const { return gap_; }

  // Outward normal of the wheel's cross-section (wheel()) at its parameter s, in R.
  Eigen::Vector2d WheelOutwardNormalInRail(double s) const;

 private:
  WheelPose pose_;
  // The yawed outline (null without yaw); shared so that copies keep the locator's profile.
  std::shared_ptr<const YawedWheelSection> yawed_;
  CurveLocator rail_locator_;
  CurveLocator wheel_locator_;
  std::optional<CurveLocator> surface_locator_;  // with yaw: on the wheel profile
  double dz_ = 0.0;
  bool has_overlap_ = false;
  // The splines' parameters of a crossing found at a nearby y [m].
  struct GapWindow {
    double rail_s, wheel_s;
  };
  // Vertical gap at y on the splines (after lowering), near gap sample `sample`. With `near`
  // set, the scan for each crossing is limited to kGapWindow_m of arc about it (the whole profile
  // when nothing crosses there); `near` is then set to this y's crossings.
  double ExactVerticalGap(double y, int sample, std::optional<GapWindow>* near = nullptr) const;
  // Fills c's contact point (rail and wheel points, normal, curvatures, radius, x and lead) at the
  // lateral position y with vertical gap `gap` there, near gap sample `sample`.
  void SetContactPoint(int sample, double y, double gap, ContactCandidate* c) const;
  // Lateral position of the smallest exact gap near gap sample `sample`.
  double RefineMinimum(int sample) const;
  std::vector<double> gap_y_, gap_, rail_top_, wheel_bottom_;
  double cos_roll_ = 1.0, sin_roll_ = 0.0;
  double cos_yaw_ = 1.0, sin_yaw_ = 0.0;
};

}  // namespace railwear
