// The flange onset of a vehicle entry's wheelsets on a stored step, scanned (issue 16, docs/wear.md
// "The spike below the flange onset"): for one wheelset and rail, the wheelset is moved from its
// curving equilibrium toward that rail in steps of the spread's standard deviation, without the
// spread rule's hold at the onset, and every position's contact is solved as a wear step solves a
// load case (the study's contact set-up, the step's rail in the track frame), printing per patch
// its contact angle, position, normal force, area, peak pressure and worn area per pass, with the
// onsets FlangeOnsetOffset and RigidFlangeOnsetOffset find.
//
//   flange_onset_scan DB RUN STEP TRAFFIC WHEELSET high|low X0 X1 DX > scan.txt
//     X0, X1, DX: the scanned offsets [spread standard deviations], toward the rail.
// A study tool, not a test: it prints (tests/tools, like spread_depth_study).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>

#include "app/scene.h"
#include "app/stored_study.h"
#include "core/contact/contact_solver.h"
#include "core/geometry/curve_locator.h"
#include "wear/pass_depth.h"
#include "wear/vehicle_traffic.h"
#include "wear/wear_simulation.h"

namespace {

using namespace railwear;

constexpr double kDeg = 180.0 / M_PI;

}  // namespace

int main(int argc, char** argv) {
  if (argc != 10) {
    std::cerr << "usage: flange_onset_scan DB RUN STEP TRAFFIC WHEELSET high|low X0 X1 DX\n";
    return 2;
  }
  try {
    const ProfileStore store = app::OpenExistingStudy(argv[1]);
    const RunInfo run = app::FindRunOrThrow(store, argv[2]);
    const app::Scene scene = app::ParseScene(run.scene_text, "stored.toml");
    const WearStudy& study = *scene.wear;
    const WearState unworn = app::StateFromStore(store, run.id, 0);
    const WearState state = app::StateFromStore(store, run.id, std::stoi(argv[3]));
    const int t = std::stoi(argv[4]), w = std::stoi(argv[5]);
    const bool high = std::string(argv[6]) == "high";
    const double x0 = std::stod(argv[7]), x1 = std::stod(argv[8]), dx = std::stod(argv[9]);
    const Profile high_track = RailInTrack(study, unworn.rail, state.rail);
    const Profile low_track = RailInTrack(study, *unworn.low_rail, *state.low_rail);
    const CurvingStart* start =
        t < static_cast<int>(state.curving.size()) ? &state.curving[t] : nullptr;
    VehicleEquilibrium eq = SolveVehicleEquilibrium(study, t, high_track, low_track, start);
    const double std_m = study.traffic[t].lateral_shift_std_m;
    std::printf(
        "traffic %d wheelset %d %s rail: equilibrium lateral %.4f mm, spread std %.3f mm;"
        " flange onsets [std] high %.4f, low %.4f (rigid: %.4f, %.4f)\n",
        t, w, high ? "high" : "low", eq.result.wheelsets[w].lateral_m * 1e3, std_m * 1e3,
        // The onsets themselves: eq holds them only up to the rule's outermost nodes.
        FlangeOnsetOffset(study, t, eq, w, RailSide::kHigh) / std_m,
        FlangeOnsetOffset(study, t, eq, w, RailSide::kLow) / std_m,
        RigidFlangeOnsetOffset(eq, w, RailSide::kHigh, std_m) / std_m,
        RigidFlangeOnsetOffset(eq, w, RailSide::kLow, std_m) / std_m);
    // Without the hold: every offset is its own position.
    VehicleEquilibrium free = eq;
    for (auto& o : free.flange_onset_m) {
      o = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    }
    const Profile& rail = high ? high_track : low_track;
    const CurveLocator locator(rail, /*material_toward_plus_z=*/true);
    const WearGrid grid =
        WearGrid::ForProfile(high ? state.rail : *state.low_rail, study.options.bin_m);
    for (double x = x0; x <= x1 + 1e-12; x += dx) {
      const double signed_x = high ? x : -x;
      const LoadCase lc = VehicleNodeCases(study, t, free, w, signed_x, 0, 1.0)[high ? 0 : 1];
      const ContactResult r = SolveContact(LoadCaseProblem(study, rail, lc));
      double worn = 0.0;
      std::string patches;
      for (const PatchResult& p : r.patches) {
        const std::vector<double> d =
            CalcPatchPassDepth(p, locator, study.options.law, study.rail_material.hardness_Pa,
                               lc.motion.speed_m_s, grid);
        const double a = WornArea(d, grid);
        worn += a;
        char buf[200];
        std::snprintf(buf, sizeof buf, " | %.1f deg y %.2f N %.1f kN A %.1f mm2 p %.2f GPa w %.2e",
                      p.contact_angle_rad * kDeg, p.contact_point_yz_m.x() * 1e3,
                      p.normal_force_N * 1e-3, p.area_m2 * 1e6, p.p_max_Pa * 1e-9, a * 1e6);
        patches += buf;
      }
      std::printf("x %.4f shift %.4f mm approach %.1f um %s worn %.3e mm2 patches %zu%s\n", x,
                  lc.placement.lateral_shift_m * 1e3, r.approach_m * 1e6,
                  std::string(ToString(r.status)).c_str(), worn * 1e6, r.patches.size(),
                  patches.c_str());
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::cerr << "flange_onset_scan: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
