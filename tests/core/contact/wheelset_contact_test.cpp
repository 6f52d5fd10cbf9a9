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
