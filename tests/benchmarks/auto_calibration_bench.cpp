// The calibration cases of model.kind = "auto" (core/contact/model_selection.cpp), re-run: for
// each contact, what auto picks at a preset, and the errors of halfspace and Hertz against the
// conformal geometry with the Boussinesq kernel (auto's conformal choice) at the same preset.
// Not a test (minutes at standard); it checks the claim of model_selection.cpp that every case
// auto gives to a planar model or to Hertz stays within the preset's tolerance.
//
// Cases: S1002 on UIC60 1:40 at lateral shifts -12 to -3 mm (0.5 mm) and 50/100/150 kN; a
// 10 mm wheel in grooves of 10.5-30 mm (roll 0 and 0.3 rad), 1-50 kN; a laterally flat wheel on
// crowns of 13-80 mm rolled by 0-0.7 rad, 20 and 100 kN.
//
// Run: build/tests/benchmarks/auto_calibration_bench [draft|standard|reference|fine] [> cases.csv]
//   One CSV row per case on stdout, the summary on stderr.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/contact/contact_solver.h"
#include "core/contact/model_selection.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

struct Summary {
  int cases = 0, planar = 0, hertz = 0, conformal = 0;
  double worst_planar = 0.0, worst_hertz = 0.0;  // larger of the area and p_max errors
  std::string worst_planar_case, worst_hertz_case;
};

double Err(const ContactResult& a, const ContactResult& ref) {
  return std::max(std::abs(a.area_m2 / ref.area_m2 - 1.0),
                  std::abs(a.p_max_Pa / ref.p_max_Pa - 1.0));
}

void Case(const std::string& name, ContactProblem p, AccuracyPreset preset, Summary* s) {
  auto run = [&](ModelKind kind, bool boussinesq) {
    ContactProblem q = p;
    q.model = MakeModelOptions(kind);
    if (boussinesq) q.model.kernel = KernelModel::kBoussinesq;
    q.model.accuracy = preset;
    return SolveContact(q);
  };
  const ContactResult cb = run(ModelKind::kConformal, true);
  if (cb.status != SolverStatus::kConverged) {
    std::fprintf(stderr, "skipped %s: conformal+boussinesq %s\n", name.c_str(), cb.message.c_str());
    return;
  }
  const ContactResult automatic = run(ModelKind::kAuto, true);
  const ContactResult hs = run(ModelKind::kHalfspace, false);
  const ContactResult hz = run(ModelKind::kHertz, false);
  std::string models;
  for (const auto& patch : automatic.patches) models += (models.empty() ? "" : ";") + patch.model;
  const bool planar = models.find("conformal") == std::string::npos;
  const bool hertz = models.find("hertz") != std::string::npos;
  const double e_hs = hs.status == SolverStatus::kConverged ? Err(hs, cb) : INFINITY;
  const double e_hz = Err(hz, cb);
  ++s->cases;
  if (hertz) {
    ++s->hertz;
    if (e_hz > s->worst_hertz) s->worst_hertz = e_hz, s->worst_hertz_case = name;
  } else if (planar) {
    ++s->planar;
    if (e_hs > s->worst_planar) s->worst_planar = e_hs, s->worst_planar_case = name;
  } else {
    ++s->conformal;
  }
  std::printf("%s,%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f\n", name.c_str(), models.c_str(),
              cb.area_m2 * 1e6, 100 * (hs.area_m2 / cb.area_m2 - 1),
              100 * (hs.p_max_Pa / cb.p_max_Pa - 1), 100 * (hz.area_m2 / cb.area_m2 - 1),
              100 * (hz.p_max_Pa / cb.p_max_Pa - 1), cb.time_s * 1e3, hs.time_s * 1e3,
              automatic.time_s * 1e3);
  std::fflush(stdout);
}

int Main(int argc, char** argv) {
  const auto preset = AccuracyPresetFromString(argc > 1 ? argv[1] : "standard");
  if (!preset) {
    std::fprintf(stderr, "usage: %s [draft|standard|reference|fine]\n", argv[0]);
    return 2;
  }
  const Material steel{210e9, 0.28};
  Summary s;
  std::printf(
      "case,auto,area_cb_mm2,hs_area_pct,hs_pmax_pct,hertz_area_pct,hertz_pmax_pct,"
      "t_cb_ms,t_hs_ms,t_auto_ms\n");
  {
    ContactProblem p;
    p.wheel_profile = MakeS1002();
    p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
    p.wheel_material = p.rail_material = steel;
    p.placement.rolling_radius_m = 0.46;
    for (double F : {50e3, 100e3, 150e3}) {
      for (int k = 0; k <= 18; ++k) {
        const double shift_mm = -12.0 + 0.5 * k;
        p.placement.lateral_shift_m = shift_mm * 1e-3;
        p.load.vertical_force_N = F;
        char name[64];
        std::snprintf(name, sizeof name, "S1002 %.1f mm %.0f kN", shift_mm, F * 1e-3);
        Case(name, p, *preset, &s);
      }
    }
  }
  for (double R : {0.0105, 0.011, 0.012, 0.015, 0.02, 0.03}) {
    for (double roll : {0.0, 0.3}) {
      if (roll > 0 && R < 0.015) continue;  // the rolled wheel leaves a tight groove's bottom
      for (double F : {1e3, 10e3, 50e3}) {
        ContactProblem p;
        p.rail_profile = MakeGroove(R, BodyRole::kRail);
        p.wheel_profile = MakeCircle(0.010, BodyRole::kWheel);
        p.wheel_material = p.rail_material = steel;
        p.placement.rolling_radius_m = 0.46;
        p.placement.roll_rad = roll;
        p.load.vertical_force_N = F;
        char name[64];
        std::snprintf(name, sizeof name, "groove %.1f mm roll %.1f %.0f kN", R * 1e3, roll,
                      F * 1e-3);
        Case(name, p, *preset, &s);
      }
    }
  }
  for (double R : {0.013, 0.02, 0.04, 0.08}) {
    for (double roll : {0.0, 0.3, 0.5, 0.7}) {
      if (roll > 0.3 && R > 0.05) continue;  // beyond the crown's arc
      for (double F : {20e3, 100e3}) {
        ContactProblem p;
        p.rail_profile = testing::ArcProfile(R, +1.0, std::min(1.4, 0.06 / R), 1201);
        p.wheel_profile = testing::FunctionProfile([](double) { return 0.0; }, -0.04, 0.04, 161);
        p.wheel_material = p.rail_material = steel;
        p.placement.rolling_radius_m = 0.46;
        p.placement.roll_rad = roll;
        p.load.vertical_force_N = F;
        char name[64];
        std::snprintf(name, sizeof name, "crown %.0f mm roll %.1f %.0f kN", R * 1e3, roll,
                      F * 1e-3);
        Case(name, p, *preset, &s);
      }
    }
  }
  std::fprintf(stderr,
               "%s: %d cases; auto chose hertz %d, halfspace %d, conformal %d; worst error "
               "(area or p_max against conformal+boussinesq) of a halfspace choice %.2f %% (%s), "
               "of a Hertz choice %.2f %% (%s); tolerance %.1f %%\n",
               std::string(ToString(*preset)).c_str(), s.cases, s.hertz, s.planar, s.conformal,
               100 * s.worst_planar, s.worst_planar_case.c_str(), 100 * s.worst_hertz,
               s.worst_hertz_case.c_str(), 100 * PresetTolerance(*preset));
  return 0;
}

}  // namespace
}  // namespace railwear

int main(int argc, char** argv) { return railwear::Main(argc, argv); }
