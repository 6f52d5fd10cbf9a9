// The fast tread path (core/contact/hertz_tread.h) against the full path on the same pose,
// velocities and load, and its validity checks with their fallback.
#include "core/contact/hertz_tread.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_case.h"
#include "core/contact/contact_forces.h"
#include "core/contact/normal_tangential_stage.h"
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

TEST(HertzTread, RefusesCouplingAndWheelsets) {
  ContactProblem p = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, -20e-3, 0.0);
  p.rolling->coupling = true;
  try {
    SolveContact(p);
    ADD_FAILURE() << "coupling with the hertz model was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("coupling effect needs a patch grid"), std::string::npos)
        << e.what();
  }
  ContactCase c;
  c.problem = Rolling(ModelKind::kHertz, AccuracyPreset::kDraft, 0.0, 0.0);
  c.problem.placement = {};
  c.wheelset.emplace();
  try {
    SolveContactCase(c);
    ADD_FAILURE() << "a wheelset with hertz rolling contact was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("single wheel's fast tread path"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace railwear
