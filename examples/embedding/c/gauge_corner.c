/* A wheel on the gauge corner through the railwear C API: S1002 on UIC60 canted 1:40, the wheel
 * 4 mm toward the gauge side, 100 kN, rolling at 20 m/s with 5 mrad of yaw (the scene of
 * examples/rolling_gauge_corner.toml, without damage), conformal model at standard accuracy.
 * Prints each patch and its peak cell; exits 1 on any error. */
#include <stdio.h>
#include <stdlib.h>

#include <railwear/railwear.h>

static int check(rw_problem* p, rw_status s, const char* what) {
  if (s == RW_OK) return 0;
  fprintf(stderr, "%s: %s: %s\n", what, rw_status_name(s), rw_last_error(p));
  return 1;
}

int main(void) {
  rw_problem* p = NULL;
  rw_geometry geometry;
  rw_model model;
  rw_state state;
  int count = 0, i, failed = 0;
  if (rw_api_version() / 10000 != RW_API_VERSION_MAJOR) {
    fprintf(stderr, "librailwear %d does not match the header's %d\n", rw_api_version(),
            RW_API_VERSION);
    return 1;
  }
  if (check(NULL, rw_create(RW_PROBLEM_WHEEL, &p), "rw_create")) return 1;

  geometry.struct_size = sizeof geometry;
  rw_init_geometry(&geometry);
  geometry.rolling_radius_m = 0.46;
  geometry.rail_cant = 1.0 / 40.0;
  model.struct_size = sizeof model;
  rw_init_model(&model); /* conformal, standard accuracy, FASTSIM */
  model.effects = RW_EFFECT_TANGENTIAL;
  state.struct_size = sizeof state;
  rw_init_state(&state);
  state.lateral_m = -4e-3;
  state.yaw_rad = 5e-3;
  state.vertical_force_N = 100e3;
  state.speed_m_s = 20.0;

  failed = check(p, rw_set_profile_file(p, RW_BODY_WHEEL, "builtin:S1002"), "wheel") ||
           check(p, rw_set_profile_file(p, RW_BODY_RAIL, "builtin:UIC60"), "rail") ||
           check(p, rw_set_geometry(p, &geometry), "geometry") ||
           check(p, rw_set_model(p, &model), "model") ||
           check(p, rw_set_friction(p, 0.3), "friction") ||
           check(p, rw_set_state(p, &state), "state") ||
           check(p, rw_calculate(p), "calculate") ||
           check(p, rw_get_patch_count(p, &count), "patch count");
  for (i = 0; !failed && i < count; ++i) {
    rw_patch patch;
    size_t n = 0, k;
    double* pressure;
    double peak = 0.0;
    patch.struct_size = sizeof patch;
    failed = check(p, rw_get_patch(p, i, &patch), "patch") ||
             check(p, rw_get_cell_count(p, i, &n), "cell count");
    if (failed) break;
    pressure = (double*)malloc(n * sizeof *pressure);
    if (pressure == NULL ||
        check(p, rw_get_cells(p, i, n, NULL, NULL, pressure, NULL, NULL, NULL, NULL), "cells")) {
      free(pressure);
      failed = 1;
      break;
    }
    for (k = 0; k < n; ++k) {
      if (pressure[k] > peak) peak = pressure[k];
    }
    free(pressure);
    printf("patch %d: y %.2f mm, angle %.1f deg, area %.1f mm2, p_max %.0f MPa (peak cell %.0f), "
           "F_n %.1f kN, creepages %.5f %.5f, creep forces %.2f %.2f kN, %zu cells\n",
           i, patch.contact_y_m * 1e3, patch.contact_angle_rad * 180.0 / 3.14159265358979,
           patch.area_m2 * 1e6, patch.p_max_Pa * 1e-6, peak * 1e-6, patch.normal_force_N * 1e-3,
           patch.creepage_xi, patch.creepage_eta, patch.creep_force_x_N * 1e-3,
           patch.creep_force_s_N * 1e-3, n);
  }
  rw_destroy(p);
  return failed ? 1 : 0;
}
