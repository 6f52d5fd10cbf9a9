/* The C API's header compiled as C99 (-std=c99 -pedantic-errors, tests/CMakeLists.txt) and used
 * from C: the sizes a C compiler gives the structs, for abi_test.cpp to compare with C++'s and
 * with the pinned ones, and a small solve written in plain C. */
#include <math.h>
#include <stddef.h>

#include "railwear/railwear.h"

size_t rw_test_c_sizeof(int which) {
  switch (which) {
    case 0: return sizeof(rw_material);
    case 1: return sizeof(rw_model);
    case 2: return sizeof(rw_influence_constants);
    case 3: return sizeof(rw_geometry);
    case 4: return sizeof(rw_state);
    case 5: return sizeof(rw_summary);
    case 6: return sizeof(rw_patch);
    case 7: return sizeof(rw_wear);
    case 8: return RW_PATCH_SIZE_1_1;
    case 9: return RW_MODEL_SIZE_1_4;
    default: return 0;
  }
}

/* A Hertz contact of two circles from C; returns the peak pressure [Pa], or -status. */
double rw_test_c_solve(void) {
  rw_problem* p = NULL;
  rw_model model;
  rw_state state;
  rw_patch patch;
  int count = 0;
  double p_max = -1.0;
  rw_status s = rw_create(RW_PROBLEM_WHEEL, &p);
  if (s != RW_OK) return -(double)s;
  model.struct_size = sizeof model;
  rw_init_model(&model);
  model.kind = RW_MODEL_HERTZ;
  state.struct_size = sizeof state;
  rw_init_state(&state);
  state.vertical_force_N = 50e3;
  patch.struct_size = sizeof patch;
  if ((s = rw_set_profile_file(p, RW_BODY_WHEEL, "circle:300")) == RW_OK &&
      (s = rw_set_profile_file(p, RW_BODY_RAIL, "circle:300")) == RW_OK &&
      (s = rw_set_model(p, &model)) == RW_OK && (s = rw_set_state(p, &state)) == RW_OK &&
      (s = rw_calculate(p)) == RW_OK && (s = rw_get_patch_count(p, &count)) == RW_OK &&
      count == 1 && (s = rw_get_patch(p, 0, &patch)) == RW_OK) {
    p_max = patch.p_max_Pa;
  } else {
    p_max = -(double)(s == RW_OK ? RW_ERROR_INTERNAL : s);
  }
  rw_destroy(p);
  return isfinite(p_max) ? p_max : -1.0;
}
