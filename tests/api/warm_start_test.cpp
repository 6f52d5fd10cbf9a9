// rw_set_warm_start (API 1.5, core/contact/contact_warm_start.h): off by default; the first
// calculate of a warm handle, and the first after a set-up call, is the cold one bit for bit;
// a warm step stays near the cold one (its accuracy: tests/core/contact/
// contact_warm_start_test.cpp and docs/library.md "Warm start"); bad values are refused.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "railwear/railwear.h"
#include "tests/api/rolling_wheel.h"

namespace railwear::test {
namespace {

// Every patch of the handle's last calculate, as the C API reports it.
std::vector<rw_patch> Patches(rw_problem* p) {
  int n = 0;
  EXPECT_EQ(rw_get_patch_count(p, &n), RW_OK);
  std::vector<rw_patch> out(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    out[i].struct_size = sizeof(rw_patch);
    EXPECT_EQ(rw_get_patch(p, i, &out[i]), RW_OK);
  }
  return out;
}

// The same numbers bit for bit (the struct has no padding between its doubles and ints that
// the library leaves unset: it fills the whole struct).
void ExpectSamePatches(const std::vector<rw_patch>& a, const std::vector<rw_patch>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].area_m2, b[i].area_m2) << i;
    EXPECT_EQ(a[i].p_max_Pa, b[i].p_max_Pa) << i;
    EXPECT_EQ(a[i].normal_force_N, b[i].normal_force_N) << i;
    EXPECT_EQ(a[i].creep_force_x_N, b[i].creep_force_x_N) << i;
    EXPECT_EQ(a[i].creep_force_s_N, b[i].creep_force_s_N) << i;
    EXPECT_EQ(a[i].contact_y_m, b[i].contact_y_m) << i;
    EXPECT_EQ(a[i].cells, b[i].cells) << i;
    EXPECT_EQ(a[i].cells_in_contact, b[i].cells_in_contact) << i;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a[i].force_on_rail_N[k], b[i].force_on_rail_N[k]) << i;
  }
}

struct Handles {
  rw_problem* warm = MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT);
  rw_problem* cold = MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT);
  Handles() { EXPECT_EQ(rw_set_warm_start(warm, 1), RW_OK); }
  ~Handles() {
    rw_destroy(warm);
    rw_destroy(cold);
  }
  // Both handles at lateral_m; true when both solved.
  bool Step(double lateral_m) {
    const rw_state s = RollingState(lateral_m, 0.0);
    return rw_set_state(warm, &s) == RW_OK && rw_calculate(warm) == RW_OK &&
           rw_set_state(cold, &s) == RW_OK && rw_calculate(cold) == RW_OK;
  }
};

TEST(ApiWarmStart, FirstCalculateIsTheColdOneBitForBit) {
  Handles h;
  ASSERT_TRUE(h.Step(-5.6e-3));
  ExpectSamePatches(Patches(h.warm), Patches(h.cold));
}

TEST(ApiWarmStart, ASetUpCallMakesTheNextCalculateCold) {
  Handles h;
  ASSERT_TRUE(h.Step(-5.6e-3));
  ASSERT_TRUE(h.Step(-5.65e-3));                   // warm: near the cold one (not compared here)
  ASSERT_EQ(rw_set_friction(h.warm, 0.3), RW_OK);  // the same friction: still a set-up call
  ASSERT_TRUE(h.Step(-5.7e-3));
  ExpectSamePatches(Patches(h.warm), Patches(h.cold));
  ASSERT_TRUE(h.Step(-5.75e-3));
  ASSERT_EQ(rw_set_warm_start(h.warm, 1), RW_OK);  // turned on again: cleared
  ASSERT_TRUE(h.Step(-5.8e-3));
  ExpectSamePatches(Patches(h.warm), Patches(h.cold));
}

TEST(ApiWarmStart, AWheelsetsFirstCalculateIsColdAndItsNextOnesWarm) {
  // A wheelset toward its right rail's gauge corner (each wheel keeps its own warm start:
  // core/contact/contact_warm_start.h; their accuracy: ContactWarmStart.AWheelsets*): the first
  // calculate and the first after a set-up call equal a cold handle's bit for bit, a step of
  // 0.05 mm starts warm (it differs from the cold handle's) with every patch of both wheels.
  rw_problem* warm =
      MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT, RW_PROBLEM_WHEELSET);
  rw_problem* cold =
      MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT, RW_PROBLEM_WHEELSET);
  ASSERT_NE(warm, nullptr);
  ASSERT_NE(cold, nullptr);
  ASSERT_EQ(rw_set_warm_start(warm, 1), RW_OK);
  auto step = [&](double lateral_m) {
    const rw_state s = RollingState(lateral_m, 0.0);
    return rw_set_state(warm, &s) == RW_OK && rw_calculate(warm) == RW_OK &&
           rw_set_state(cold, &s) == RW_OK && rw_calculate(cold) == RW_OK;
  };
  ASSERT_TRUE(step(4.9e-3));
  ExpectSamePatches(Patches(warm), Patches(cold));
  ASSERT_TRUE(step(4.95e-3));
  const std::vector<rw_patch> w = Patches(warm), c = Patches(cold);
  ASSERT_EQ(w.size(), c.size());
  bool differs = false;
  for (size_t i = 0; i < w.size(); ++i) {
    differs = differs || w[i].p_max_Pa != c[i].p_max_Pa || w[i].area_m2 != c[i].area_m2 ||
              w[i].creep_force_x_N != c[i].creep_force_x_N;
  }
  EXPECT_TRUE(differs);
  ASSERT_EQ(rw_set_friction(warm, 0.3), RW_OK);  // a set-up call: the next calculate cold
  ASSERT_TRUE(step(5.0e-3));
  ExpectSamePatches(Patches(warm), Patches(cold));
  rw_destroy(warm);
  rw_destroy(cold);
}

TEST(ApiWarmStart, RefusesBadCalls) {
  EXPECT_EQ(rw_set_warm_start(nullptr, 1), RW_ERROR_NULL_ARGUMENT);
  Handles h;
  for (const int bad : {-1, 2, 100}) {
    EXPECT_EQ(rw_set_warm_start(h.warm, bad), RW_ERROR_INVALID_VALUE) << bad;
    EXPECT_NE(std::strstr(rw_last_error(h.warm), "enable ="), nullptr) << rw_last_error(h.warm);
  }
  EXPECT_EQ(rw_set_warm_start(h.warm, 0), RW_OK);
  ASSERT_TRUE(h.Step(-5.6e-3));
  ASSERT_TRUE(h.Step(-5.65e-3));  // off: every calculate cold
  ExpectSamePatches(Patches(h.warm), Patches(h.cold));
}

}  // namespace
}  // namespace railwear::test
