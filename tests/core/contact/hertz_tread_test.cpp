// The fast tread path (core/contact/hertz_tread.h) against the full path on the same pose,
// velocities and load, and its validity checks with their fallback.
#include "core/contact/hertz_tread.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_case.h"
#include "core/contact/contact_forces.h"
#include "core/contact/normal_tangential_stage.h"
#include "core/contact/wheelset_contact.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/contact/same_result.h"

namespace railwear {
namespace {

constexpr double kLoad_N = 100e3;
constexpr double kFriction = 0.3;

// An S1002 wheel rolling on UIC60 at 1:40 at 20 m/s under 100 kN, mu 0.3, FASTSIM (the C API
// benchmark's wheel, tests/benchmarks/api_bench.cpp).
ContactProblem Rolling(ModelKind kind, AccuracyPreset accuracy, double lateral_m, double yaw_rad,
                       double lateral_velocity_m_s = 0.0) {
  ContactProblem p;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.load.vertical_force_N = kLoad_N;
  p.model = MakeModelOptions(kind);
  p.model.accuracy = accuracy;
  p.placement.lateral_shift_m = lateral_m;
  p.placement.yaw_rad = yaw_rad;
  RollingOptions r;
  r.friction = kFriction;
  r.motion.speed_m_s = 20.0;
  r.motion.lateral_velocity_m_s = lateral_velocity_m_s;
  p.rolling = r;
  return p;
}

// Tolerances of the fast path (kind hertz, draft) against the half-space grid at standard
// accuracy (the full path's planar model, whose own discretisation error on area and peak
// pressure is about 1 %, grid_resolution.h). The fast path adds Hertz's constant curvatures over
// the patch, which it admits up to a gap deviation of 0.35 (hertz_tread.cpp), and its FASTSIM grid
// of 4 cells per semi-axis. Measured on these cases (docs/library.md, "The fast tread path"):
// area -4.2 ... +0.4 %, p_max -0.2 ... +0.6 %, contact point 0.08 ... 0.49 mm, the equivalent
// ellipse's semi-axes within 4.3 % (a) and 5.7 % (b), creep forces within 1.1 % of mu Q.
constexpr double kAreaTolerance = 0.06;        // relative
constexpr double kPeakTolerance = 0.02;        // relative
constexpr double kPointTolerance_m = 0.7e-3;   // lateral position of the pressure centre
constexpr double kSemiAxisTolerance = 0.08;    // relative, FASTSIM's equivalent ellipse
constexpr double kCreepTolerance = 0.02;       // of mu Q
// The vertical balance's own tolerance (normal_tangential_stage.h), with round-off.
constexpr double kBalanceToleranceHere = 10 * internal::kBalanceTolerance;

struct TreadCase {
  double lateral_m, yaw_rad, lateral_velocity_m_s;
};

class HertzTreadAgainstFullPath : public ::testing::TestWithParam<TreadCase> {};

TEST_P(HertzTreadAgainstFullPath, MatchesTheHalfspaceGrid) {
  const TreadCase tc = GetParam();
  const ContactProblem fast_problem = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft,
                                              tc.lateral_m, tc.yaw_rad, tc.lateral_velocity_m_s);
  std::string why;
  const std::optional<ContactResult> fast = SolveHertzTread(fast_problem, &why);
  ASSERT_TRUE(fast.has_value()) << why;
  const ContactResult full = SolveContact(Rolling(ModelKind::kHalfspace, AccuracyPreset::kStandard,
                                                  tc.lateral_m, tc.yaw_rad,
                                                  tc.lateral_velocity_m_s));
  ASSERT_EQ(fast->status, SolverStatus::kConverged);
  ASSERT_EQ(full.status, SolverStatus::kConverged);
  ASSERT_EQ(fast->patches.size(), 1u);
  ASSERT_EQ(full.patches.size(), 1u);
  const PatchResult& a = fast->patches[0];
  const PatchResult& f = full.patches[0];
  EXPECT_EQ(a.model, "hertz");
  // Normal force balance: the net vertical force on the rail (pressure and creep forces) is the
  // load, as the full path's.
  EXPECT_NEAR(TotalForcesOnRail(*fast).Net().z(), kLoad_N, kBalanceToleranceHere * kLoad_N);
  EXPECT_NEAR(TotalForcesOnRail(full).Net().z(), kLoad_N, kBalanceToleranceHere * kLoad_N);
  // Location.
  EXPECT_NEAR(a.contact_point_yz_m.x(), f.contact_point_yz_m.x(), kPointTolerance_m);
  EXPECT_NEAR(a.contact_x_m, f.contact_x_m, kPointTolerance_m);
  // Size: area, peak pressure, the semi-axes FASTSIM used.
  EXPECT_NEAR(a.area_m2 / f.area_m2, 1.0, kAreaTolerance);
  EXPECT_NEAR(a.p_max_Pa / f.p_max_Pa, 1.0, kPeakTolerance);
  ASSERT_TRUE(a.rolling && f.rolling);
  EXPECT_NEAR(a.rolling->semi_axis_x_m / f.rolling->semi_axis_x_m, 1.0, kSemiAxisTolerance);
  EXPECT_NEAR(a.rolling->semi_axis_s_m / f.rolling->semi_axis_s_m, 1.0, kSemiAxisTolerance);
  // Creep forces.
  const double muQ = kFriction * kLoad_N;
  EXPECT_NEAR(a.rolling->tangential.force_x_N, f.rolling->tangential.force_x_N,
              kCreepTolerance * muQ);
  EXPECT_NEAR(a.rolling->tangential.force_s_N, f.rolling->tangential.force_s_N,
              kCreepTolerance * muQ);
  EXPECT_NEAR(a.rolling->creepage.eta, f.rolling->creepage.eta,
              1e-3 * std::abs(f.rolling->creepage.eta) + 1e-6);
}

// Tread positions of S1002 on UIC60 1:40 where the patch is Hertzian enough (the crown's 300 mm
// radius: -28 to -14 mm; the 80 mm radius: -7 mm), with yaw and a lateral velocity.
INSTANTIATE_TEST_SUITE_P(
    TreadPositions, HertzTreadAgainstFullPath,
    ::testing::Values(TreadCase{-28e-3, 5e-3, 0.0}, TreadCase{-20e-3, 5e-3, 0.0},
                      TreadCase{-20e-3, -2e-3, 0.05}, TreadCase{-14e-3, 5e-3, 0.0},
                      TreadCase{-7e-3, 0.0, 0.0}));

TEST(HertzTread, NamesWhyItDoesNotApply) {
  std::string why;
  // Where the crown's 300 mm radius meets the 80 mm one inside the patch.
  EXPECT_FALSE(SolveHertzTread(Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -10.4e-3, 5e-3),
                               &why));
  EXPECT_NE(why.find("non-Hertzian patch"), std::string::npos) << why;
  // Tread and gauge corner at once.
  EXPECT_FALSE(
      SolveHertzTread(Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -5.6e-3, 0.0), &why));
  EXPECT_NE(why.find("two-point contact"), std::string::npos) << why;
  // The gauge corner: conformal.
  EXPECT_FALSE(
      SolveHertzTread(Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -4e-3, 0.0), &why));
  EXPECT_NE(why.find("conformal"), std::string::npos) << why;
  // The flange.
  EXPECT_FALSE(
      SolveHertzTread(Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, 0.0, 0.0), &why));
  EXPECT_NE(why.find("steeper than the 45 deg"), std::string::npos) << why;
}

TEST(HertzTread, FallsBackToTheAutoModelAndSaysWhy) {
  const ContactProblem hertz = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -10.4e-3, 5e-3);
  ContactProblem auto_model = hertz;
  auto_model.model = HertzTreadFallbackModel(hertz.model);
  EXPECT_EQ(auto_model.model.kind, ModelKind::kAuto);
  EXPECT_EQ(auto_model.model.accuracy, AccuracyPreset::kDraft);
  const ContactResult r = SolveContact(hertz);
  testing::ExpectSameResult(r, SolveContact(auto_model));
  ASSERT_FALSE(r.patches.empty());
  for (const PatchResult& p : r.patches) {
    EXPECT_NE(p.model, "hertz");
    EXPECT_EQ(p.model_reason.rfind("fast tread path not valid: non-Hertzian patch", 0), 0u)
        << p.model_reason;
  }
  // The C API's entry point: the same, and no wheel-frame point of the fast path.
  ContactCase c;
  c.problem = hertz;
  PlacementCache cache;
  std::optional<HertzTreadPoint> point = HertzTreadPoint{};
  testing::ExpectSameResult(SolveContactCase(c, &cache, &point).wheel, r);
  EXPECT_FALSE(point.has_value());
}

TEST(HertzTread, CaseEntryPointsTakeTheFastPath) {
  ContactCase c;
  c.problem = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -20e-3, 5e-3);
  std::string why;
  HertzTreadPoint direct_point;
  const std::optional<ContactResult> direct = SolveHertzTread(c.problem, &why, &direct_point);
  ASSERT_TRUE(direct.has_value()) << why;
  PlacementCache cache;
  std::optional<HertzTreadPoint> point;
  testing::ExpectSameResult(SolveContactCase(c, &cache, &point).wheel, *direct);
  testing::ExpectSameResult(SolveContact(c.problem), *direct);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->wheel_y_m, direct_point.wheel_y_m);
  // The wheel point lies below the contact on the rail: its lateral position is the rail point's
  // less the lateral shift (no roll), to the placement's refinement.
  EXPECT_NEAR(point->wheel_y_m, direct->patches[0].contact_point_yz_m.x() + 20e-3, 1e-6);
  // x_W is the rail-frame x turned by the yaw about the vertical through the wheel profile
  // origin, x_W = cos(psi) x + sin(psi) y_W (as the C API finds it on a placed geometry).
  const double yaw = 5e-3;
  EXPECT_NEAR(point->wheel_x_m,
              std::cos(yaw) * direct->patches[0].contact_x_m + std::sin(yaw) * point->wheel_y_m,
              1e-9);
}

TEST(HertzTread, CarriesALongitudinalForceTarget) {
  ContactProblem p = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -20e-3, 0.0);
  p.rolling->longitudinal_force_N = 10e3;
  std::string why;
  const std::optional<ContactResult> r = SolveHertzTread(p, &why);
  ASSERT_TRUE(r.has_value()) << why;
  ASSERT_EQ(r->status, SolverStatus::kConverged) << r->message;
  // SolvePitchVelocityForForce's tolerance, 1e-6 mu F_n (rolling_stage.h).
  EXPECT_NEAR(r->patches[0].rolling->tangential.force_x_N, 10e3, 1e-6 * kFriction * kLoad_N * 2);
  p.rolling->longitudinal_force_N = 0.5 * kFriction * kLoad_N * 3;  // beyond adhesion
  const std::optional<ContactResult> beyond = SolveHertzTread(p, &why);
  ASSERT_TRUE(beyond.has_value());
  EXPECT_EQ(beyond->status, SolverStatus::kNotConverged);
  EXPECT_NE(beyond->message.find("cannot be carried"), std::string::npos) << beyond->message;
}

TEST(HertzTread, RefusesCoupling) {
  ContactProblem p = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -20e-3, 0.0);
  p.rolling->coupling = true;
  try {
    SolveContact(p);
    ADD_FAILURE() << "coupling with the hertz model was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("coupling effect needs a patch grid"), std::string::npos)
        << e.what();
  }
}

// A wheelset of the wheels above (100 kN per wheel, 20 m/s, mu 0.3) on tangent track, displaced
// and yawed; kind = hertz (draft) or the model given.
WheelsetProblem TreadWheelset(double displacement_m, double yaw_rad,
                              ModelKind kind = ModelKind::kHertz,
                              AccuracyPreset accuracy = AccuracyPreset::kDraft) {
  WheelsetProblem w;
  w.wheel_rail = Rolling(kind, accuracy, 0.0, 0.0);
  w.wheel_rail.placement = {};
  w.wheelset.lateral_displacement_m = displacement_m;
  w.wheelset.yaw_rad = yaw_rad;
  return w;
}

// One wheel of a wheelset as a single wheel's problem: its pose and motion as SolveWheelset
// places and moves it (the left one in its rail's own frame).
ContactProblem WheelOf(const WheelsetProblem& w, const WheelsetResult& r, bool right) {
  ContactProblem p = w.wheel_rail;
  const WheelPose& pose = right ? r.placement.right : r.placement.left;
  p.placement = {pose.lateral_shift_m, pose.roll_rad, pose.rolling_radius_m, pose.yaw_rad};
  const WheelMotions m = CurveWheelMotions(w.wheel_rail.rolling->motion, r.placement,
                                           w.curvature_per_m, w.wheelset.rolling_radius_m);
  p.rolling->motion = right ? m.right : m.left;
  return p;
}

// Displaced 4 mm to the left, the right wheel runs on the crown (-14.5 mm) and the left one on
// the 80 mm radius (-6.5 mm), both single Hertzian patches at 100 kN (at 3 mm the left wheel's gap
// departs from Hertz's quadratic by 43 %, at 5 mm it touches at two points): each wheel is the
// single wheel's fast path on its own pose and motion, bit for bit, with its wheel-frame point;
// against the full path (the half-space grid at standard, as above) within the same tolerances.
TEST(HertzTread, WheelsetTakesTheFastPathOnBothWheels) {
  const WheelsetProblem w = TreadWheelset(-4e-3, 1e-3);
  const WheelsetResult r = SolveWheelset(w);
  ASSERT_TRUE(r.right_tread_point.has_value());
  ASSERT_TRUE(r.left_tread_point.has_value());
  const WheelsetResult full =
      SolveWheelset(TreadWheelset(-4e-3, 1e-3, ModelKind::kHalfspace, AccuracyPreset::kStandard));
  for (const bool right : {true, false}) {
    SCOPED_TRACE(right ? "right wheel" : "left wheel");
    const ContactResult& wheel = right ? r.right : r.left;
    ASSERT_EQ(wheel.status, SolverStatus::kConverged) << wheel.message;
    ASSERT_EQ(wheel.patches.size(), 1u);
    EXPECT_EQ(wheel.patches[0].model, "hertz");
    std::string why;
    HertzTreadPoint point;
    const std::optional<ContactResult> single = SolveHertzTread(WheelOf(w, r, right), &why, &point);
    ASSERT_TRUE(single.has_value()) << why;
    testing::ExpectSameResult(wheel, *single);
    const HertzTreadPoint& got = right ? *r.right_tread_point : *r.left_tread_point;
    EXPECT_EQ(got.wheel_x_m, point.wheel_x_m);
    EXPECT_EQ(got.wheel_y_m, point.wheel_y_m);
    EXPECT_EQ(got.wheel_z_m, point.wheel_z_m);

    const ContactResult& f = right ? full.right : full.left;
    ASSERT_EQ(f.patches.size(), 1u);
    const PatchResult& a = wheel.patches[0];
    const PatchResult& b = f.patches[0];
    EXPECT_NEAR(a.area_m2, b.area_m2, kAreaTolerance * b.area_m2);
    EXPECT_NEAR(a.p_max_Pa, b.p_max_Pa, kPeakTolerance * b.p_max_Pa);
    EXPECT_NEAR(a.contact_point_yz_m.x(), b.contact_point_yz_m.x(), kPointTolerance_m);
    const double muQ = kFriction * kLoad_N;
    EXPECT_NEAR(a.rolling->tangential.force_x_N, b.rolling->tangential.force_x_N,
                kCreepTolerance * muQ);
    EXPECT_NEAR(a.rolling->tangential.force_s_N, b.rolling->tangential.force_s_N,
                kCreepTolerance * muQ);
  }
}

// An axle force target on the fast path: the pitch search runs over the wheels' whole fast solves
// (each balanced), so the wheels at the root carry the target; beyond adhesion the status says so.
TEST(HertzTread, WheelsetCarriesAnAxleForceTarget) {
  WheelsetProblem w = TreadWheelset(-4e-3, 0.0);
  w.wheel_rail.rolling->longitudinal_force_N = 20e3;
  const WheelsetResult r = SolveWheelset(w);
  ASSERT_EQ(r.right.status, SolverStatus::kConverged) << r.right.message;
  ASSERT_EQ(r.left.status, SolverStatus::kConverged) << r.left.message;
  ASSERT_TRUE(r.right_tread_point.has_value());
  EXPECT_EQ(r.right.patches.at(0).model, "hertz");
  EXPECT_EQ(r.left.patches.at(0).model, "hertz");
  // SolvePitchVelocityForForce's tolerance, 1e-6 mu F_n of both wheels (wheelset_contact.h).
  const double fn = TotalNormalForce(r.right) + TotalNormalForce(r.left);
  EXPECT_NEAR(TotalForceX(r.right) + TotalForceX(r.left), 20e3, 1e-6 * kFriction * fn);
  EXPECT_EQ(r.right.pitch_velocity_rad_s, r.left.pitch_velocity_rad_s);  // one axle

  w.wheel_rail.rolling->longitudinal_force_N = 1.5 * kFriction * 2 * kLoad_N;
  const WheelsetResult beyond = SolveWheelset(w);
  EXPECT_EQ(beyond.right.status, SolverStatus::kNotConverged);
  EXPECT_TRUE(beyond.right_tread_point.has_value());  // still the fast path's wheels
  EXPECT_TRUE(beyond.left_tread_point.has_value());
  EXPECT_NE(beyond.right.message.find("cannot be carried"), std::string::npos)
      << beyond.right.message;
}

// Centred, both wheels run where the crown's 300 mm radius meets the 80 mm one (-10.5 mm, not a
// Hertzian patch): the whole wheelset is the fallback's (kind auto at the same accuracy), bit for
// bit, every patch naming the wheel and the reason.
TEST(HertzTread, WheelsetFallsBackAsAWhole) {
  const WheelsetProblem w = TreadWheelset(0.0, 1e-3);
  const WheelsetResult r = SolveWheelset(w);
  WheelsetProblem fallback = w;
  fallback.wheel_rail.model = HertzTreadFallbackModel(w.wheel_rail.model);
  const WheelsetResult full = SolveWheelset(fallback);
  testing::ExpectSameResult(r.right, full.right);
  testing::ExpectSameResult(r.left, full.left);
  EXPECT_FALSE(r.right_tread_point.has_value());
  EXPECT_FALSE(r.left_tread_point.has_value());
  for (const ContactResult* wheel : {&r.right, &r.left}) {
    ASSERT_FALSE(wheel->patches.empty());
    for (const PatchResult& p : wheel->patches) {
      EXPECT_NE(p.model, "hertz");
      EXPECT_EQ(
          p.model_reason.rfind("fast tread path not valid: right wheel: non-Hertzian patch", 0), 0u)
          << p.model_reason;
    }
  }
}

}  // namespace
}  // namespace railwear
