#include "core/contact/wheelset_contact.h"

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"

namespace railwear {
namespace {

WheelsetProblem Problem(double displacement_m, double yaw_rad) {
  WheelsetProblem p;
  p.wheel_rail.wheel_profile = MakeS1002();
  p.wheel_rail.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_rail.wheel_material = p.wheel_rail.rail_material = {210e9, 0.28};
  p.wheel_rail.load.vertical_force_N = 50e3;
  p.wheel_rail.model = MakeModelOptions(ModelKind::kConformal);
  p.wheel_rail.model.accuracy = AccuracyPreset::kDraft;
  RollingOptions r;
  r.friction = 0.3;
  r.motion.speed_m_s = 2.0;
  p.wheel_rail.rolling = r;
  p.wheelset.lateral_displacement_m = displacement_m;
  p.wheelset.yaw_rad = yaw_rad;
  p.wheelset.rolling_radius_m = 0.46;
  p.wheel_rail.placement.rolling_radius_m = 0.46;
  return p;
}

// Mirror images are solved on mirrored profiles whose point order and spline sampling are
// exactly mirrored: results agree to round-off, far below this.
constexpr double kMirrorTolerance = 1e-9;

void ExpectMirrored(const ContactResult& a, const ContactResult& b) {
  ASSERT_EQ(a.status, SolverStatus::kConverged);
  ASSERT_EQ(b.status, SolverStatus::kConverged);
  ASSERT_EQ(a.patches.size(), b.patches.size());
  EXPECT_NEAR(a.area_m2, b.area_m2, kMirrorTolerance * a.area_m2);
  EXPECT_NEAR(a.p_max_Pa, b.p_max_Pa, kMirrorTolerance * a.p_max_Pa);
  EXPECT_NEAR(a.lateral_force_N, b.lateral_force_N, 1e-6 * std::abs(a.vertical_force_N));
  for (size_t k = 0; k < a.patches.size(); ++k) {
    const auto& ra = *a.patches[k].rolling;
    const auto& rb = *b.patches[k].rolling;
    EXPECT_NEAR(ra.tangential.force_x_N, rb.tangential.force_x_N, 1e-6 * 50e3);
    EXPECT_NEAR(ra.tangential.force_s_N, rb.tangential.force_s_N, 1e-6 * 50e3);
    EXPECT_NEAR(ra.creepage.spin_per_m, rb.creepage.spin_per_m, 1e-9);
    // Yaw in the geometry: the contact leads or trails the axle alike on both sides.
    EXPECT_NEAR(a.patches[k].contact_x_m, b.patches[k].contact_x_m, 1e-9);
  }
}

// A left wheel of its own (worn wheels of one wheelset differ, wear co-evolution): the right-hand
// wheel's profile given again changes nothing, bit for bit; another profile (here the S1002
// moved 0.5 mm toward its flange back) moves the left wheel's contact and leaves the right
// wheel's solution as it was, bit for bit (no axle force target couples them here).
TEST(WheelsetContact, LeftWheelProfileReplacesOnlyTheLeftWheel) {
  const WheelsetProblem p = Problem(0.002, 0.0);
  const WheelsetResult base = SolveWheelset(p);
  WheelsetProblem same = p;
  same.left_wheel_profile = MakeS1002();
  const WheelsetResult again = SolveWheelset(same);
  EXPECT_EQ(again.left.p_max_Pa, base.left.p_max_Pa);
  EXPECT_EQ(again.left.patches.at(0).contact_point_yz_m, base.left.patches.at(0).contact_point_yz_m);
  EXPECT_EQ(again.right.p_max_Pa, base.right.p_max_Pa);
  WheelsetProblem other = p;
  other.left_wheel_profile = MakeS1002().Transformed(0.0, Eigen::Vector2d(-5e-4, 0.0));
  const WheelsetResult moved = SolveWheelset(other);
  ASSERT_EQ(moved.left.status, SolverStatus::kConverged);
  EXPECT_EQ(moved.right.p_max_Pa, base.right.p_max_Pa);
  EXPECT_EQ(moved.right.patches.at(0).contact_point_yz_m,
            base.right.patches.at(0).contact_point_yz_m);
  EXPECT_GT((moved.left.patches.at(0).contact_point_yz_m -
             base.left.patches.at(0).contact_point_yz_m).norm(),
            1e-5);
}

TEST(WheelsetContact, CentredWheelsetIsSymmetric) {
  const WheelsetResult r = SolveWheelset(Problem(0.0, 0.0));
  ExpectMirrored(r.right, r.left);
}

TEST(WheelsetContact, MirroredInputsGiveMirroredOutputs) {
  // Issue 3: displacement and yaw of opposite sign swap the roles of the wheels.
  const WheelsetResult plus = SolveWheelset(Problem(0.004, 0.003));
  const WheelsetResult minus = SolveWheelset(Problem(-0.004, -0.003));
  ExpectMirrored(plus.right, minus.left);
  ExpectMirrored(plus.left, minus.right);
  // The displaced wheelset brings the right wheel toward flange contact: a steeper contact.
  EXPECT_GT(plus.right.patches[0].contact_angle_rad, plus.left.patches[0].contact_angle_rad);
}

TEST(WheelsetContact, MirroredFlangeContactUnderYawIsMirrored) {
  // Issue 14: at 7 mm and 15 mrad the right wheel runs on its flange, its contact about 20 mm
  // ahead of the axle; the mirrored inputs put the left wheel there, at the same lead.
  const WheelsetResult plus = SolveWheelset(Problem(0.007, 0.015));
  const WheelsetResult minus = SolveWheelset(Problem(-0.007, -0.015));
  ExpectMirrored(plus.right, minus.left);
  ExpectMirrored(plus.left, minus.right);
  double lead = 0.0;
  for (const auto& patch : plus.right.patches) lead = std::max(lead, patch.contact_x_m);
  EXPECT_GT(lead, 0.01);  // a flange contact well ahead of the axle
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

TEST(WheelsetContact, LateralVelocityMovesBothWheelsAcrossTheTrack) {
  // A centred wheelset moving toward +Y at 0.02 m/s (1 % of V): in the track both wheels slip
  // the same way, so in their own rail frames (the left one mirrored) the lateral creepages have
  // opposite signs, about ydot / V each, and the creep forces on both wheels point to -Y
  // (Kalker's forces oppose the creepage: the wheelset's lateral creep damping). The two are not
  // mirror images (the right wheel slips toward its field side, the left one toward its gauge
  // side, against the same geometric spin), so only their magnitudes are compared: 5 %.
  WheelsetProblem p = Problem(0.0, 0.0);
  const double V = p.wheel_rail.rolling->motion.speed_m_s, ydot = 0.02;
  p.wheel_rail.rolling->motion.lateral_velocity_m_s = ydot;
  const WheelsetResult r = SolveWheelset(p);
  ASSERT_EQ(r.right.status, SolverStatus::kConverged);
  ASSERT_EQ(r.left.status, SolverStatus::kConverged);
  const auto& right = *r.right.patches.at(0).rolling;
  const auto& left = *r.left.patches.at(0).rolling;
  // ydot / V over the cosine of a contact angle of a few degrees: within 1 %.
  EXPECT_NEAR(right.creepage.eta, ydot / V, 0.01 * ydot / V);
  EXPECT_NEAR(left.creepage.eta, -ydot / V, 0.01 * ydot / V);
  EXPECT_LT(right.tangential.force_s_N, 0.0);  // on the right wheel, toward -y = -Y
  EXPECT_GT(left.tangential.force_s_N, 0.0);   // on the left wheel, toward +y = -Y
  EXPECT_NEAR(left.tangential.force_s_N, -right.tangential.force_s_N,
              0.05 * std::abs(right.tangential.force_s_N));
}

TEST(WheelsetContact, YawVelocityTurnsTheWheelsetAboutItsCentre) {
  // A centred wheelset yawing at 0.1 rad/s: the right wheel (Y_w about +0.75 m) goes back at
  // psidot Y_w, the left one forward, so with the axle rolling at the centre's V / r0 the
  // longitudinal creepages are -psidot Y_w / V_w, V_w = V - psidot Y_w each wheel's own speed.
  // 1 %: the contact points lie a few millimetres from the wheel origins and their rolling radii
  // differ from r0 by the nominal rolling circle's tolerance.
  WheelsetProblem p = Problem(0.0, 0.0);
  const double V = p.wheel_rail.rolling->motion.speed_m_s, psidot = 0.1;
  p.wheel_rail.rolling->motion.yaw_velocity_rad_s = psidot;
  const WheelsetResult r = SolveWheelset(p);
  ASSERT_EQ(r.right.status, SolverStatus::kConverged);
  ASSERT_EQ(r.left.status, SolverStatus::kConverged);
  const double y_right = r.placement.right_rail_origin_Y_m + r.placement.right.lateral_shift_m;
  const double y_left = r.placement.left_rail_origin_Y_m - r.placement.left.lateral_shift_m;
  const double want_right = -psidot * y_right / (V - psidot * y_right);  // about -0.039
  const double want_left = -psidot * y_left / (V - psidot * y_left);     // about +0.036
  EXPECT_NEAR(r.right.patches.at(0).rolling->creepage.xi, want_right, 0.01 * std::abs(want_right));
  EXPECT_NEAR(r.left.patches.at(0).rolling->creepage.xi, want_left, 0.01 * std::abs(want_left));
}

TEST(WheelsetContact, AxleLongitudinalForceIsSharedByBothWheels) {
  WheelsetProblem p = Problem(0.002, 0.0);
  p.wheel_rail.rolling->longitudinal_force_N = 8000.0;  // traction on the axle
  const WheelsetResult r = SolveWheelset(p);
  ASSERT_EQ(r.right.status, SolverStatus::kConverged) << r.right.message;
  ASSERT_EQ(r.left.status, SolverStatus::kConverged);
  EXPECT_DOUBLE_EQ(r.right.pitch_velocity_rad_s, r.left.pitch_velocity_rad_s);  // one axle
  const double fx = r.right.patches[0].rolling->tangential.force_x_N +
                    r.left.patches[0].rolling->tangential.force_x_N;
  EXPECT_NEAR(fx, 8000.0, 1e-5 * 0.3 * 100e3);
}

}  // namespace
}  // namespace railwear
