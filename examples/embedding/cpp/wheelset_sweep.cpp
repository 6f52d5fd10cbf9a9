// A wheelset stepped across the track through the railwear C API from C++, as a vehicle-dynamics
// code calls it per time step: one handle set up once, then per step the state and a calculate.
// S1002 wheels on UIC60 rails canted 1:40, 1435 mm gauge, 50 kN per wheel, 10 m/s, draft
// accuracy; the lateral displacement runs from 0 to 8 mm and the right wheel's contact moves from
// the tread to the gauge corner. Prints per step each patch's wheel, position and forces.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include <railwear/railwear.h>

namespace {

// The handle owned by a unique_ptr, and every status turned into an exception on the C++ side.
using Problem = std::unique_ptr<rw_problem, decltype(&rw_destroy)>;

void Check(rw_problem* p, rw_status s, const char* what) {
  if (s != RW_OK) {
    throw std::runtime_error(std::string(what) + ": " + rw_status_name(s) + ": " +
                             rw_last_error(p));
  }
}

template <class T>
T Init(rw_status (*init)(T*)) {
  T t{};
  t.struct_size = sizeof t;
  init(&t);
  return t;
}

}  // namespace

int main() try {
  rw_problem* raw = nullptr;
  Check(nullptr, rw_create(RW_PROBLEM_WHEELSET, &raw), "rw_create");
  Problem problem(raw, &rw_destroy);
  rw_problem* p = problem.get();

  Check(p, rw_set_profile_file(p, RW_BODY_WHEEL, "builtin:S1002"), "wheel");
  Check(p, rw_set_profile_file(p, RW_BODY_RAIL, "builtin:UIC60"), "rail");
  rw_geometry geometry = Init(&rw_init_geometry);  // 1435 mm gauge, flange backs 1360 mm
  geometry.rail_cant = 1.0 / 40.0;
  Check(p, rw_set_geometry(p, &geometry), "geometry");
  rw_model model = Init(&rw_init_model);
  model.accuracy = RW_ACCURACY_DRAFT;
  model.effects = RW_EFFECT_TANGENTIAL;
  Check(p, rw_set_model(p, &model), "model");
  Check(p, rw_set_friction(p, 0.3), "friction");

  for (int step = 0; step <= 4; ++step) {
    rw_state state = Init(&rw_init_state);
    state.lateral_m = 2e-3 * step;
    state.yaw_rad = 2e-3;
    state.vertical_force_N = 50e3;
    state.speed_m_s = 10.0;
    Check(p, rw_set_state(p, &state), "state");
    Check(p, rw_calculate(p), "calculate");
    rw_summary summary{};
    summary.struct_size = sizeof summary;
    Check(p, rw_get_summary(p, &summary), "summary");
    std::printf("y_ws %.1f mm: %d patches, L/V right %.3f left %.3f\n", state.lateral_m * 1e3,
                summary.patches, summary.l_over_v[0], summary.l_over_v[1]);
    for (int i = 0; i < summary.patches; ++i) {
      rw_patch patch{};
      patch.struct_size = sizeof patch;
      Check(p, rw_get_patch(p, i, &patch), "patch");
      std::printf(
          "  %s wheel: Y %.1f mm, angle %.1f deg, p_max %.0f MPa, force on rail (%.2f, "
          "%.2f, %.2f) kN\n",
          patch.wheel == 0 ? "right" : "left", patch.contact_track_Y_m * 1e3,
          patch.contact_angle_rad * 57.29577951308232, patch.p_max_Pa * 1e-6,
          patch.force_on_rail_N[0] * 1e-3, patch.force_on_rail_N[1] * 1e-3,
          patch.force_on_rail_N[2] * 1e-3);
    }
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 1;
}
