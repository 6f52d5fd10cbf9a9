// The wheel-frame contact location of rw_patch (API 1.2): the pressure centre turned into the
// wheel's frame lies on the wheel profile (to the initial gap there, at most the approach), at
// the lateral position the placement puts it and ahead of the axle by a cone's lead; a caller
// of API 1.1 still gets its smaller rw_patch, filled up to its size.
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "core/geometry/curve_locator.h"
#include "core/profile/builtin_profiles.h"
#include "railwear/railwear.h"
#include "tests/api/rolling_wheel.h"

namespace railwear::test {
namespace {

// The wheel frame is the wheel's placed at first contact (the solve's geometry, before the
// approach): the pressure centre on the rail surface is then off the wheel profile by the
// initial gap there. Inside the contact area a cell's initial gap is at most the approach's
// share along its normal (gap = w delta - deformation, deformation >= 0, w <= 1), so the bound
// is the approach itself (measured: 0.001 to 0.1 of it, a gauge-corner patch to the wide
// tread-and-flange-root patch of the wheelset's right wheel).
constexpr double kOnProfileShareOfApproach = 1.0;
// The lead of a point on a cone of angle gamma over the axle, r tan(gamma) tan(psi), with the
// patch's resultant angle for gamma: the resultant of a curved patch tilts from the geometric
// angle at its pressure centre by a few per cent (measured 5 % on the tread, 7 % at the gauge
// corner); 15 % is the bound. The wrong sign of the yaw's mixing of y into x is 29 % off at
// the gauge corner.
constexpr double kLeadRelTol = 0.15;
// x_R = cos(psi) x_W - sin(psi) y_W, the yaw turned back: rounding of millimetre values.
constexpr double kTurnBackTol_m = 1e-15;

// An S1002 wheel (the built-in, MakeS1002()) rolling on UIC60 1:40, conformal at draft
// accuracy (tests/api/rolling_wheel.h), or a wheelset of them.
struct Fixture {
  Profile wheel = MakeS1002();
  rw_problem* p = nullptr;

  explicit Fixture(int kind)
      : p(MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT, kind)) {
    EXPECT_NE(p, nullptr);
  }
  ~Fixture() { rw_destroy(p); }

  // Solves at the state; the patches.
  std::vector<rw_patch> Solve(double lateral_m, double yaw_rad, double roll_rad = 0.0) {
    rw_state s{};
    s.struct_size = sizeof s;
    rw_init_state(&s);
    s.lateral_m = lateral_m;
    s.yaw_rad = yaw_rad;
    s.roll_rad = roll_rad;
    s.vertical_force_N = 100e3;
    s.speed_m_s = 20.0;
    EXPECT_EQ(rw_set_state(p, &s), RW_OK) << rw_last_error(p);
    EXPECT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
    int n = 0;
    EXPECT_EQ(rw_get_patch_count(p, &n), RW_OK);
    std::vector<rw_patch> out(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      out[i].struct_size = sizeof(rw_patch);
      EXPECT_EQ(rw_get_patch(p, i, &out[i]), RW_OK) << rw_last_error(p);
    }
    return out;
  }
  rw_summary Summary() {
    rw_summary s{};
    s.struct_size = sizeof s;
    EXPECT_EQ(rw_get_summary(p, &s), RW_OK);
    return s;
  }
  // Distance of the patch's wheel-frame point (y, z) to the wheel profile [m].
  double DistanceToWheel(const rw_patch& q) const {
    const CurveLocator locator(wheel, /*material_toward_plus_z=*/false);
    return std::abs(locator.Project({q.contact_wheel_y_m, q.contact_wheel_z_m}).signed_distance);
  }
};

TEST(ApiWheelFrame, WithoutYawTheWheelPointIsTheRailPointLessTheLateralShift) {
  Fixture f(RW_PROBLEM_WHEEL);
  for (const double lateral : {-10.4e-3, -4e-3}) {  // tread, gauge corner
    const std::vector<rw_patch> patches = f.Solve(lateral, 0.0);
    ASSERT_FALSE(patches.empty());
    const double approach = f.Summary().approach_m[0];
    for (const rw_patch& q : patches) {
      // No roll: the wheel profile frame is the rail frame shifted by (lateral, dz).
      EXPECT_EQ(q.contact_wheel_y_m, q.contact_y_m - lateral);
      EXPECT_EQ(q.contact_wheel_x_m, q.contact_x_m);
      EXPECT_LE(f.DistanceToWheel(q), kOnProfileShareOfApproach * approach) << "at " << lateral;
    }
  }
}

TEST(ApiWheelFrame, AYawedAndRolledWheelsPointLiesOnItsProfile) {
  // With yaw the patch leads or trails the axle (x != 0 in the rail frame); turned into the
  // wheel's frame the point lands on the wheel profile again, as without yaw. Roll moves the
  // profile frame against the rail frame. A wrong sign of either puts the point millimetres off.
  Fixture f(RW_PROBLEM_WHEEL);
  for (const double yaw : {8e-3, -8e-3}) {
    for (const double roll : {0.0, 3e-3}) {
      for (const double lateral : {-10.4e-3, -4e-3}) {
        const std::vector<rw_patch> patches = f.Solve(lateral, yaw, roll);
        ASSERT_FALSE(patches.empty());
        const double approach = f.Summary().approach_m[0];
        for (const rw_patch& q : patches) {
          EXPECT_LE(f.DistanceToWheel(q), kOnProfileShareOfApproach * approach)
              << "yaw " << yaw << " roll " << roll << " lateral " << lateral;
          // (x_W, y_W) are the rail frame's (x, y) about the wheel profile origin turned by the
          // yaw (y_W from the engine's own projection, x_W from the API's).
          EXPECT_NEAR(std::cos(yaw) * q.contact_wheel_x_m - std::sin(yaw) * q.contact_wheel_y_m,
                      q.contact_x_m, kTurnBackTol_m);
          // x_W is the point's lead over the axle: r tan(gamma) tan(psi) on a cone, gamma the
          // angle against the axle (the rail frame's contact angle plus the roll).
          const double lead = (0.46 + q.contact_wheel_z_m) *
                              std::tan(q.contact_angle_rad + roll) * std::tan(yaw);
          EXPECT_NEAR(q.contact_wheel_x_m, lead, kLeadRelTol * std::abs(lead))
              << "yaw " << yaw << " roll " << roll << " lateral " << lateral;
        }
      }
    }
  }
}

TEST(ApiWheelFrame, BothWheelsOfAWheelsetLieOnTheirProfiles) {
  Fixture f(RW_PROBLEM_WHEELSET);
  const std::vector<rw_patch> patches = f.Solve(5e-3, 4e-3);
  const rw_summary s = f.Summary();
  bool seen[2] = {false, false};
  for (const rw_patch& q : patches) {
    seen[q.wheel] = true;
    EXPECT_LE(f.DistanceToWheel(q), kOnProfileShareOfApproach * s.approach_m[q.wheel])
        << "wheel " << q.wheel;
  }
  EXPECT_TRUE(seen[0] && seen[1]);
}

TEST(ApiWheelFrame, AnApi11CallerGetsItsSmallerPatch) {
  Fixture f(RW_PROBLEM_WHEEL);
  const std::vector<rw_patch> patches = f.Solve(-4e-3, 5e-3);
  ASSERT_FALSE(patches.empty());
  // A 1.1 struct followed by bytes the library must not touch.
  unsigned char buffer[sizeof(rw_patch) + 16];
  std::memset(buffer, 0xAB, sizeof buffer);
  const size_t old_size = RW_PATCH_SIZE_1_1;
  std::memcpy(buffer, &old_size, sizeof old_size);
  ASSERT_EQ(rw_get_patch(f.p, 0, reinterpret_cast<rw_patch*>(buffer)), RW_OK);
  rw_patch old{};
  std::memcpy(&old, buffer, old_size);
  EXPECT_EQ(old.struct_size, old_size);
  EXPECT_EQ(old.p_max_Pa, patches[0].p_max_Pa);
  EXPECT_EQ(old.contact_track_Y_m, patches[0].contact_track_Y_m);
  EXPECT_EQ(old.cells_in_contact, patches[0].cells_in_contact);
  for (size_t i = old_size; i < sizeof buffer; ++i) ASSERT_EQ(buffer[i], 0xAB) << "byte " << i;
  // Any other size is still refused.
  rw_patch wrong{};
  wrong.struct_size = RW_PATCH_SIZE_1_1 - 8;
  EXPECT_EQ(rw_get_patch(f.p, 0, &wrong), RW_ERROR_STRUCT_SIZE);
  EXPECT_NE(std::string(rw_last_error(f.p)).find("208"), std::string::npos) << rw_last_error(f.p);
}

}  // namespace
}  // namespace railwear::test
