// RW_MODEL_HERTZ with rolling contact (API 1.3): the fast tread path through the C API equals
// the core's (core/contact/hertz_tread.h), rw_get_patch_model says which path solved a patch and
// why, and a wheelset handle takes it on both wheels (API 1.4).
#include <cmath>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_case.h"
#include "core/contact/hertz_tread.h"
#include "core/profile/builtin_profiles.h"
#include "railwear/railwear.h"
#include "tests/api/rolling_wheel.h"

namespace railwear::test {
namespace {

// The handle's problem (tests/api/rolling_wheel.h) as the core's ContactCase.
ContactCase CoreCase(double lateral_m, double yaw_rad) {
  ContactCase c;
  ContactProblem& p = c.problem;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.model = MakeModelOptions(ModelKind::kHertz);
  p.model.accuracy = AccuracyPreset::kDraft;
  p.placement.lateral_shift_m = lateral_m;
  p.placement.yaw_rad = yaw_rad;
  p.load.vertical_force_N = 100e3;
  RollingOptions r;
  r.friction = 0.3;
  r.motion.speed_m_s = 20.0;
  p.rolling = r;
  return c;
}

TEST(ApiHertzTread, EqualsTheCoreFastPath) {
  rw_problem* p = MakeRollingS1002Wheel(RW_MODEL_HERTZ, RW_ACCURACY_DRAFT);
  ASSERT_NE(p, nullptr);
  const rw_state s = RollingState(-20e-3, 5e-3);
  ASSERT_EQ(rw_set_state(p, &s), RW_OK) << rw_last_error(p);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  int n = 0;
  ASSERT_EQ(rw_get_patch_count(p, &n), RW_OK);
  ASSERT_EQ(n, 1);
  rw_patch q{};
  q.struct_size = sizeof q;
  ASSERT_EQ(rw_get_patch(p, 0, &q), RW_OK);
  const char* model = nullptr;
  const char* reason = nullptr;
  ASSERT_EQ(rw_get_patch_model(p, 0, &model, &reason), RW_OK);
  EXPECT_STREQ(model, "hertz");
  EXPECT_EQ(std::string(reason).rfind("fast tread path: one Hertzian patch", 0), 0u) << reason;

  PlacementCache cache;
  std::optional<HertzTreadPoint> point;
  const ContactResult core = SolveContactCase(CoreCase(-20e-3, 5e-3), &cache, &point).wheel;
  ASSERT_EQ(core.patches.size(), 1u);
  ASSERT_TRUE(point.has_value());
  const PatchResult& c = core.patches[0];
  EXPECT_EQ(q.area_m2, c.area_m2);
  EXPECT_EQ(q.p_max_Pa, c.p_max_Pa);
  EXPECT_EQ(q.contact_y_m, c.contact_point_yz_m.x());
  EXPECT_EQ(q.creep_force_x_N, c.rolling->tangential.force_x_N);
  EXPECT_EQ(q.creep_force_s_N, c.rolling->tangential.force_s_N);
  EXPECT_EQ(q.contact_wheel_x_m, point->wheel_x_m);
  EXPECT_EQ(q.contact_wheel_y_m, point->wheel_y_m);
  EXPECT_EQ(q.contact_wheel_z_m, point->wheel_z_m);
  // The wheel point is the wheel profile's: y_W is the rail point's y less the lateral shift
  // (no roll), to the placement's refinement.
  EXPECT_NEAR(q.contact_wheel_y_m, q.contact_y_m + 20e-3, 1e-6);
  // Its cells are the ellipse grid FASTSIM ran on.
  size_t cells = 0;
  ASSERT_EQ(rw_get_cell_count(p, 0, &cells), RW_OK);
  EXPECT_EQ(cells, static_cast<size_t>(c.grid.cells()));
  EXPECT_GT(cells, 0u);
  rw_destroy(p);
}

TEST(ApiHertzTread, FallsBackAndSaysWhy) {
  rw_problem* p = MakeRollingS1002Wheel(RW_MODEL_HERTZ, RW_ACCURACY_DRAFT);
  ASSERT_NE(p, nullptr);
  // The benchmark's tread position: the crown's 300 mm radius meets the 80 mm one in the patch.
  const rw_state s = RollingState(-10.4e-3, 5e-3);
  ASSERT_EQ(rw_set_state(p, &s), RW_OK);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  int n = 0;
  ASSERT_EQ(rw_get_patch_count(p, &n), RW_OK);
  ASSERT_GE(n, 1);
  const char* model = nullptr;
  const char* reason = nullptr;
  ASSERT_EQ(rw_get_patch_model(p, 0, &model, &reason), RW_OK);
  EXPECT_STRNE(model, "hertz");
  EXPECT_EQ(std::string(reason).rfind("fast tread path not valid: non-Hertzian patch", 0), 0u)
      << reason;
  // The wheel-frame location comes from the full path's placed geometry.
  rw_patch q{};
  q.struct_size = sizeof q;
  ASSERT_EQ(rw_get_patch(p, 0, &q), RW_OK);
  EXPECT_NEAR(q.contact_wheel_y_m, q.contact_y_m + 10.4e-3, 1e-6);
  rw_destroy(p);
}

// Since 1.4 a wheelset handle takes the fast path on both wheels (core/contact/wheelset_contact.h):
// each patch says so, and each wheel's wheel-frame location is its fast path's point.
TEST(ApiHertzTread, WheelsetTakesItOnBothWheels) {
  rw_problem* p = MakeRollingS1002Wheel(RW_MODEL_HERTZ, RW_ACCURACY_DRAFT, RW_PROBLEM_WHEELSET);
  ASSERT_NE(p, nullptr);
  // Displaced 4 mm to the left: the right wheel on the crown, the left one on the 80 mm radius
  // (core_tests' HertzTread.WheelsetTakesTheFastPathOnBothWheels).
  const rw_state s = RollingState(-4e-3, 1e-3);
  ASSERT_EQ(rw_set_state(p, &s), RW_OK) << rw_last_error(p);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  int n = 0;
  ASSERT_EQ(rw_get_patch_count(p, &n), RW_OK);
  ASSERT_EQ(n, 2);
  rw_summary summary{};
  summary.struct_size = sizeof summary;
  ASSERT_EQ(rw_get_summary(p, &summary), RW_OK);
  for (int i = 0; i < n; ++i) {
    rw_patch q{};
    q.struct_size = sizeof q;
    ASSERT_EQ(rw_get_patch(p, i, &q), RW_OK);
    EXPECT_EQ(q.wheel, i);
    const char* model = nullptr;
    const char* reason = nullptr;
    ASSERT_EQ(rw_get_patch_model(p, i, &model, &reason), RW_OK);
    EXPECT_STREQ(model, "hertz");
    EXPECT_EQ(std::string(reason).rfind("fast tread path: one Hertzian patch", 0), 0u) << reason;
    EXPECT_NEAR(q.normal_force_N, 100e3, 0.05 * 100e3);  // the creep forces' vertical part aside
    if (i == 0) {
      // The right wheel's point lies below its contact on the rail, shifted by the wheel's
      // lateral shift (rw_summary's wheelset_lateral_m); the wheelset's roll moves it by
      // roll x z, under a micrometre here.
      EXPECT_NEAR(q.contact_wheel_y_m, q.contact_y_m - summary.wheelset_lateral_m, 1e-5);
    }
  }
  // An axle force beyond adhesion: not converged, and the patches still carry the fast path's
  // wheel-frame points (there is no placed geometry to find them on).
  rw_state beyond = s;
  beyond.longitudinal_force_N = 1.5 * 0.3 * 2 * 100e3;
  ASSERT_EQ(rw_set_state(p, &beyond), RW_OK) << rw_last_error(p);
  EXPECT_EQ(rw_calculate(p), RW_ERROR_NOT_CONVERGED);
  rw_patch q{};
  q.struct_size = sizeof q;
  ASSERT_EQ(rw_get_patch(p, 0, &q), RW_OK) << rw_last_error(p);
  EXPECT_NEAR(q.contact_wheel_y_m, q.contact_y_m - summary.wheelset_lateral_m, 1e-5);
  rw_destroy(p);
}

}  // namespace
}  // namespace railwear::test
