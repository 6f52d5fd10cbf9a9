// A random search of C API call sequences (issue 20; docs/library.md "Bad input"): extreme but
// valid handles, profiles (files, circles, grooves, noisy point lists), geometry, models, cells,
// friction, pressure limits and states, each calculate followed by every query. Sequence N draws
// from a generator seeded with N, so a sequence is re-run by its number. Each runs in a forked
// child with an alarm, so an abort (a broken internal check before API 1.5), a crash or a call
// that outlives the alarm shows as the child's signal, with the child's wall time.
//
//   api_call_search FROM TO [ALARM_S]   sequences FROM..TO-1 (ALARM_S default 90, 0 = none)
//   api_call_search --one N             sequence N in this process (for a debugger)
//
// Every call's status is printed (with the message of an error), then one line per sequence
// ("sequence N: exit 0 in 1.23 s" or "sequence N: KILLED by signal 14 after 90.0 s"), and a
// summary line. A study tool, not a test: some sequences take minutes (tests/tools, like
// spread_depth_study); the bad-call table of tests/api/bad_calls_test.cpp is the test.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "railwear/railwear.h"

namespace {

std::mt19937_64 generator;
double Uniform(double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(generator);
}
int Pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(generator); }

void Log(const char* call, int status, rw_problem* p) {
  std::printf("  %s -> %s %s\n", call, rw_status_name(status), status ? rw_last_error(p) : "");
}

// Every query on every patch after a calculate, then (rolling contact) an accumulate and the
// depth fields.
void QueryAll(rw_problem* p, bool tangential) {
  rw_summary summary{};
  summary.struct_size = sizeof summary;
  rw_get_summary(p, &summary);
  int patches = 0;
  rw_get_patch_count(p, &patches);
  for (int i = 0; i < patches; ++i) {
    rw_patch patch{};
    patch.struct_size = sizeof patch;
    int s = rw_get_patch(p, i, &patch);
    if (s) Log("get_patch", s, p);
    patch.struct_size = RW_PATCH_SIZE_1_1;
    s = rw_get_patch(p, i, &patch);
    if (s) Log("get_patch (1.1 size)", s, p);
    const char* model = nullptr;
    const char* reason = nullptr;
    rw_get_patch_model(p, i, &model, &reason);
    size_t c = 0;
    rw_get_cell_count(p, i, &c);
    std::vector<double> b(7 * (c + 1));
    s = rw_get_cells(p, i, c, &b[0], &b[c + 1], &b[2 * (c + 1)], &b[3 * (c + 1)], &b[4 * (c + 1)],
                     &b[5 * (c + 1)], &b[6 * (c + 1)]);
    if (s) Log("get_cells", s, p);
  }
  if (tangential) {
    const int s = rw_accumulate(p, Uniform(0, 3));
    if (s) Log("accumulate", s, p);
  }
  for (int rail = 0; rail < 2; ++rail) {
    size_t c = 0;
    rw_get_depth_count(p, rail, &c);
    std::vector<double> along(c + 1), depth(c + 1);
    rw_get_depth(p, rail, c, along.data(), depth.data());
  }
}

void Sequence(int n) {
  generator.seed(n);
  const int kind = Pick(2);
  rw_problem* p = nullptr;
  rw_create(kind, &p);
  const char* wheels[] = {"builtin:S1002", "builtin:S1002", "circle:300", "circle:460"};
  const char* rails[] = {"builtin:UIC60", "builtin:UIC60", "circle:300",
                         "circle:13",     "groove:20",     "circle:80"};
  const char* wheel = wheels[Pick(4)];
  const char* rail = rails[Pick(6)];
  std::printf("sequence %d: kind %d wheel %s rail %s\n", n, kind, wheel, rail);
  Log("wheel", rw_set_profile_file(p, RW_BODY_WHEEL, wheel), p);
  Log("rail", rw_set_profile_file(p, RW_BODY_RAIL, rail), p);
  if (Pick(4) == 0) {  // a parabola with a sine ripple as points, on the rail or the wheel
    std::vector<double> yz;
    const int points = 4 + Pick(60);
    const double amplitude = Uniform(1e-4, 5e-3), wavenumber = Uniform(50, 2000);
    const double radius = Uniform(0.005, 1.0);
    for (int i = 0; i < points; ++i) {
      const double y = -0.03 + 0.06 * i / (points - 1);
      yz.push_back(y);
      yz.push_back(y * y / (2 * radius) + amplitude * std::sin(wavenumber * y));
    }
    const int body = Pick(2) ? RW_BODY_RAIL : RW_BODY_WHEEL;
    std::printf(
        "  profile points on body %d: %d points, ripple %.17g m at %.17g rad/m, radius %.17g m\n",
        body, points, amplitude, wavenumber, radius);
    Log("profile points", rw_set_profile_points(p, body, yz.data(), points), p);
  }
  if (kind && Pick(4) == 0)
    Log("left rail", rw_set_profile_file(p, RW_BODY_LEFT_RAIL, rails[Pick(6)]), p);
  rw_geometry g{};
  g.struct_size = sizeof g;
  rw_init_geometry(&g);
  const double cants[] = {0, 1.0 / 40, 1.0 / 20, 0.2, -0.2, 0.1};
  g.rail_cant = cants[Pick(6)];
  if (Pick(3) == 0) g.rolling_radius_m = std::pow(10.0, Uniform(-1.5, 0.3));
  if (Pick(3) == 0) g.gauge_m = Uniform(0.9, 1.8);
  if (Pick(4) == 0) g.gauge_height_m = Uniform(0, 0.05);
  if (Pick(3) == 0) g.flange_back_distance_m = Uniform(0.9, 1.8);
  if (Pick(4) == 0) g.flange_back_position_m = Uniform(-0.2, 0.2);
  std::printf(
      "  geometry cant %.17g rolling radius %.17g gauge %.17g gauge height %.17g flange back "
      "distance %.17g position %.17g\n",
      g.rail_cant, g.rolling_radius_m, g.gauge_m, g.gauge_height_m, g.flange_back_distance_m,
      g.flange_back_position_m);
  Log("geometry", rw_set_geometry(p, &g), p);
  rw_material wheel_steel{}, rail_steel{};
  wheel_steel.struct_size = rail_steel.struct_size = sizeof wheel_steel;
  rw_init_material(&wheel_steel);
  rw_init_material(&rail_steel);
  rail_steel.hardness_Pa = wheel_steel.hardness_Pa = 3e9;
  rail_steel.shear_yield_Pa = wheel_steel.shear_yield_Pa = 300e6;
  rw_set_materials(p, &wheel_steel, &rail_steel);
  rw_model m{};
  m.struct_size = sizeof m;
  rw_init_model(&m);
  const int kinds[] = {RW_MODEL_HERTZ, RW_MODEL_HALFSPACE, RW_MODEL_CONFORMAL, RW_MODEL_AUTO,
                       RW_MODEL_HERTZ};
  m.kind = kinds[Pick(5)];
  m.accuracy = Pick(5) == 0 ? RW_ACCURACY_STANDARD : RW_ACCURACY_DRAFT;
  const unsigned effects[] = {0, RW_EFFECT_TANGENTIAL, RW_EFFECT_TANGENTIAL,
                              RW_EFFECT_TANGENTIAL | RW_EFFECT_DAMAGE, RW_EFFECT_COUPLING};
  m.effects = effects[Pick(5)];
  if (m.kind == RW_MODEL_HERTZ && (m.effects & RW_EFFECT_COUPLING))
    m.effects = RW_EFFECT_TANGENTIAL;
  m.tangential = Pick(3);
  if (Pick(4) == 0 && m.kind != RW_MODEL_HERTZ) {
    m.cell_dx_m = std::pow(10.0, Uniform(-4.3, -1.7));
    m.cell_ds_m = std::pow(10.0, Uniform(-4.3, -1.7));
  }
  std::printf("  model %d accuracy %d effects %u tangential %d cells %.17g %.17g\n", m.kind,
              m.accuracy, m.effects, m.tangential, m.cell_dx_m, m.cell_ds_m);
  Log("model", rw_set_model(p, &m), p);
  const double friction = Pick(3) == 0 ? std::pow(10.0, Uniform(-6, 0.3)) : Uniform(0.05, 0.6);
  std::printf("  friction %.17g\n", friction);
  Log("friction", rw_set_friction(p, friction), p);
  if (Pick(6) == 0) {
    const double limit_Pa = std::pow(10.0, Uniform(6, 10));
    std::printf("  pressure limit %.17g Pa\n", limit_Pa);
    Log("pressure limit", rw_set_pressure_limit(p, RW_PRESSURE_LIMIT_VALUE, limit_Pa), p);
  }
  if (Pick(4) == 0) {
    rw_wear law{};
    law.struct_size = sizeof law;
    rw_init_wear(&law);
    law.law = Pick(4);
    std::printf("  wear law %d\n", law.law);
    Log("wear", rw_set_wear(p, &law), p);
  }
  const int steps = 1 + Pick(3);
  for (int k = 0; k < steps; ++k) {
    rw_state s{};
    s.struct_size = sizeof s;
    rw_init_state(&s);
    s.lateral_m = Pick(4) == 0 ? Uniform(-0.1, 0.1) : Uniform(-0.012, 0.012);
    s.yaw_rad = Pick(5) == 0 ? Uniform(-0.1, 0.1) : Uniform(-0.01, 0.01);
    s.roll_rad = Pick(4) == 0 ? Uniform(-0.5, 0.5) : 0.0;
    if (kind == 0 && Pick(4) == 0) {
      s.approach_m = std::pow(10.0, Uniform(-9, -1.5));
    } else {
      s.vertical_force_N = std::pow(10.0, Uniform(-1, 7));
    }
    if (kind && Pick(3) == 0) s.left_vertical_force_N = std::pow(10.0, Uniform(3, 5.3));
    s.speed_m_s = Pick(4) == 0 ? std::pow(10.0, Uniform(-6, 3)) : Uniform(0.5, 60);
    s.lateral_velocity_m_s = Pick(3) == 0 ? Uniform(-1, 1) : 0.0;
    s.yaw_velocity_rad_s = Pick(4) == 0 ? Uniform(-0.5, 0.5) : 0.0;
    const int mode = Pick(5);  // creepages, axle force, pitch velocity, or free rolling (3, 4)
    if (mode == 0) {
      s.flags = RW_STATE_CREEPAGE;
      s.creepage_xi = Uniform(-1, 1);
      s.creepage_eta = Uniform(-1, 1);
      s.creepage_spin_per_m = Uniform(-500, 500);
    } else if (mode == 1) {
      s.longitudinal_force_N = Uniform(-1, 1) * std::pow(10.0, Uniform(2, 5.5));
    } else if (mode == 2) {
      s.pitch_velocity_rad_s = s.speed_m_s / 0.46 * (1 + Uniform(-0.01, 0.01));
    }
    if (kind && Pick(3) == 0) s.curvature_per_m = Uniform(0, 0.1);
    std::printf(
        "  state lateral %.17g yaw %.17g roll %.17g load %.17g approach %.17g left load %.17g "
        "speed %.17g lateral velocity %.17g yaw velocity %.17g mode %d axle force %.17g "
        "curvature %.17g creepages %.17g %.17g %.17g pitch velocity %.17g\n",
        s.lateral_m, s.yaw_rad, s.roll_rad, s.vertical_force_N, s.approach_m,
        s.left_vertical_force_N, s.speed_m_s, s.lateral_velocity_m_s, s.yaw_velocity_rad_s, mode,
        s.longitudinal_force_N, s.curvature_per_m, s.creepage_xi, s.creepage_eta,
        s.creepage_spin_per_m, s.pitch_velocity_rad_s);
    std::fflush(stdout);
    int status = rw_set_state(p, &s);
    if (status) {
      Log("state", status, p);
      continue;
    }
    status = rw_calculate(p);
    Log("calculate", status, p);
    std::fflush(stdout);
    QueryAll(p, m.effects != 0);
    if (Pick(4) == 0) {
      g.rail_cant = cants[Pick(6)];
      std::printf("  geometry again: cant %.17g\n", g.rail_cant);
      Log("geometry again", rw_set_geometry(p, &g), p);
    }
  }
  rw_destroy(p);
}

int Usage() {
  std::fprintf(stderr,
               "usage: api_call_search FROM TO [ALARM_S]  (sequences FROM..TO-1, alarm default "
               "90 s, 0 = none)\n       api_call_search --one N\n");
  return 2;
}

bool ReadInt(const char* text, long* value) {
  char* end = nullptr;
  *value = std::strtol(text, &end, 10);
  return end != text && *end == '\0' && *value >= 0;
}

}  // namespace

int main(int argc, char** argv) {
  long from = 0, to = 0, alarm_s = 90;
  if (argc == 3 && std::string(argv[1]) == "--one") {
    if (!ReadInt(argv[2], &from)) return Usage();
    Sequence(static_cast<int>(from));
    return 0;
  }
  if (argc < 3 || argc > 4 || !ReadInt(argv[1], &from) || !ReadInt(argv[2], &to) || from >= to ||
      (argc == 4 && !ReadInt(argv[3], &alarm_s))) {
    return Usage();
  }
  int killed = 0;
  double slowest_s = 0;
  for (long n = from; n < to; ++n) {
    std::fflush(stdout);
    const auto start = std::chrono::steady_clock::now();
    const pid_t child = fork();
    if (child < 0) {
      std::perror("fork");
      return 1;
    }
    if (child == 0) {
      if (alarm_s > 0) alarm(static_cast<unsigned>(alarm_s));
      Sequence(static_cast<int>(n));
      std::fflush(stdout);
      _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    slowest_s = std::max(slowest_s, wall_s);
    if (WIFSIGNALED(status)) {
      ++killed;
      std::printf("sequence %ld: KILLED by signal %d after %.2f s\n", n, WTERMSIG(status), wall_s);
    } else {
      std::printf("sequence %ld: exit %d in %.2f s\n", n, WEXITSTATUS(status), wall_s);
    }
  }
  std::printf("%ld sequences, %d killed by a signal, slowest %.2f s\n", to - from, killed,
              slowest_s);
  return killed ? 1 : 0;
}
