// Test and benchmark support: a C API handle of an S1002 wheel rolling on UIC60 canted 1:40
// (the wheel and rail of examples/rolling_gauge_corner.toml), FASTSIM, mu 0.3, steel; the
// caller gives the model kind and accuracy and then the state per step.
#pragma once

#include "railwear/railwear.h"

namespace railwear::test {

// NULL when the handle could not be made (every call's status is checked). problem_kind
// RW_PROBLEM_WHEELSET: a wheelset of these wheels on two such rails.
inline rw_problem* MakeRollingS1002Wheel(int model_kind, int accuracy,
                                         int problem_kind = RW_PROBLEM_WHEEL) {
  rw_problem* p = nullptr;
  if (rw_create(problem_kind, &p) != RW_OK) return nullptr;
  rw_geometry g{};
  g.struct_size = sizeof g;
  rw_init_geometry(&g);
  g.rail_cant = 1.0 / 40.0;
  rw_model m{};
  m.struct_size = sizeof m;
  rw_init_model(&m);
  m.kind = model_kind;
  m.accuracy = accuracy;
  m.effects = RW_EFFECT_TANGENTIAL;
  if (rw_set_profile_file(p, RW_BODY_WHEEL, "builtin:S1002") != RW_OK ||
      rw_set_profile_file(p, RW_BODY_RAIL, "builtin:UIC60") != RW_OK ||
      rw_set_geometry(p, &g) != RW_OK || rw_set_model(p, &m) != RW_OK ||
      rw_set_friction(p, 0.3) != RW_OK) {
    rw_destroy(p);
    return nullptr;
  }
  return p;
}

// A state of that wheel at a lateral position [m] and yaw [rad]: 100 kN, rolling at 20 m/s.
inline rw_state RollingState(double lateral_m, double yaw_rad) {
  rw_state s{};
  s.struct_size = sizeof s;
  rw_init_state(&s);
  s.lateral_m = lateral_m;
  s.yaw_rad = yaw_rad;
  s.vertical_force_N = 100e3;
  s.speed_m_s = 20.0;
  return s;
}

}  // namespace railwear::test
