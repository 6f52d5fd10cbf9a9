// Threads: the C API keeps no global state, so independent handles used from two threads at
// once give the same results, bit for bit, as the same handles run one after the other. And a
// handle's own state between calls (the placed geometry it reuses at a repeated pose,
// core/contact/placement_cache.h) does not change results: a step equals the same step on a
// fresh handle, bit for bit.
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "railwear/railwear.h"
#include "tests/api/rolling_wheel.h"

namespace {

// What a step gives, compared bit for bit.
struct Outcome {
  rw_status status = RW_ERROR_INTERNAL;
  std::string error;
  std::vector<double> values;  // per patch: p_max, area, force on rail, creep forces
  bool operator==(const Outcome&) const = default;
};

// A wheel on the gauge corner (S1002 on UIC60 1:40, the rolling_gauge_corner example at draft
// accuracy) or on its tread, rolling with FASTSIM, at a few lateral positions.
struct Case {
  double lateral_m;
  double yaw_rad;
  double lateral_velocity_m_s = 0.0;
};

Outcome Step(rw_problem* p, const Case& c) {
  rw_state s{};
  s.struct_size = sizeof s;
  rw_init_state(&s);
  s.lateral_m = c.lateral_m;
  s.yaw_rad = c.yaw_rad;
  s.vertical_force_N = 100e3;
  s.speed_m_s = 20.0;
  s.lateral_velocity_m_s = c.lateral_velocity_m_s;
  Outcome o;
  o.status = rw_set_state(p, &s);
  if (o.status == RW_OK) o.status = rw_calculate(p);
  o.error = rw_last_error(p);
  int n = 0;
  if (rw_get_patch_count(p, &n) != RW_OK) return o;
  for (int i = 0; i < n; ++i) {
    rw_patch patch{};
    patch.struct_size = sizeof patch;
    rw_get_patch(p, i, &patch);
    o.values.insert(o.values.end(), {patch.p_max_Pa, patch.area_m2, patch.force_on_rail_N[0],
                                     patch.force_on_rail_N[1], patch.force_on_rail_N[2],
                                     patch.creep_force_x_N, patch.creep_force_s_N});
  }
  return o;
}

TEST(ApiThreads, TwoHandlesInTwoThreadsEqualSerialRuns) {
  // Gauge corner (-4 mm) and tread (-10.4 mm) positions, two yaw angles each.
  const std::vector<Case> a = {{-4e-3, 5e-3}, {-4.5e-3, 0.0}, {-3.5e-3, -2e-3}};
  const std::vector<Case> b = {{-10.4e-3, 0.0}, {-9e-3, 3e-3}, {-8e-3, -3e-3}};
  auto run = [](const std::vector<Case>& cases, std::vector<Outcome>* out) {
    rw_problem* p = railwear::test::MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT);
    for (const Case& c : cases) out->push_back(Step(p, c));
    rw_destroy(p);
  };
  std::vector<Outcome> serial_a, serial_b;
  run(a, &serial_a);
  run(b, &serial_b);
  for (const Outcome& o : serial_a) ASSERT_EQ(o.status, RW_OK) << o.error;
  for (const Outcome& o : serial_b) ASSERT_EQ(o.status, RW_OK) << o.error;

  std::vector<Outcome> threaded_a, threaded_b;
  std::thread ta(run, std::cref(a), &threaded_a);
  std::thread tb(run, std::cref(b), &threaded_b);
  ta.join();
  tb.join();
  EXPECT_TRUE(threaded_a == serial_a);
  EXPECT_TRUE(threaded_b == serial_b);
}

TEST(ApiReuse, RepeatedPosesEqualFreshHandlesBitForBit) {
  // One handle through a sequence that repeats poses (the geometry reused), changes only the
  // velocity (reused) and moves (placed again); each step against a fresh handle.
  const std::vector<Case> steps = {{-10.4e-3, 5e-3},       {-10.4e-3, 5e-3},
                                   {-10.4e-3, 5e-3, 0.05}, {-4e-3, 0.0},
                                   {-4e-3, 0.0, -0.05},    {-10.4e-3, 5e-3}};
  rw_problem* kept = railwear::test::MakeRollingS1002Wheel(RW_MODEL_AUTO, RW_ACCURACY_DRAFT);
  for (const Case& c : steps) {
    rw_problem* fresh = railwear::test::MakeRollingS1002Wheel(RW_MODEL_AUTO, RW_ACCURACY_DRAFT);
    const Outcome want = Step(fresh, c);
    rw_destroy(fresh);
    ASSERT_EQ(want.status, RW_OK) << want.error;
    EXPECT_TRUE(Step(kept, c) == want) << "at lateral " << c.lateral_m;
  }
  rw_destroy(kept);
}

}  // namespace
