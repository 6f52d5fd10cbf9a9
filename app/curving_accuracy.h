// `railwear accuracy VEHICLE_SCENE.toml --curving`: what accuracy costs in steady-state curving
// (issue 15). Every vehicle traffic entry of the scene is solved on its unworn rails (as
// `railwear curving` does) at each accuracy level, from the centred start: the finer levels
// with the draft predictor first (CurvingOptions::predictor, the library's default), the draft
// level in one phase. Per run the wall time, the wheelset contact solves, the status, the
// leading wheelset's state (y, angle of attack, the high rail's lateral force from its high
// wheel, L/V) and the largest difference over all wheelsets from the finest level's run of the
// same entry (the reference): |dy| [mm], |dpsi| [mrad], |dY_high| [kN]. Each entry's levels use
// the scene's cold predictor ([curving] predictor, CurvingOptions::cold_predictor); one more row
// per entry solves the finest level with the other predictor (model or table): what the
// predictor choice costs and gains in time and solves, and how far its equilibrium lies from
// the reference's (the same full model, reached through the other predictor). Nothing is stored.
// Prints a table; with --out DIR writes DIR/curving_accuracy.csv.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "app/scene.h"

namespace railwear::app {

struct CurvingAccuracyRow {
  std::string traffic;  // the traffic entry's name
  std::string level;    // accuracy preset name
  // The cold predictor ("model" or "table"; "table (fell_back)" when the table's start failed).
  std::string predictor;
  std::string status;   // CurvingStatus name
  double time_s = 0.0;  // wall time of the solve
  int solves = 0;       // wheelset contact solves
  // The leading wheelset: y [mm], angle of attack [mrad], high-wheel lateral force [kN], L/V.
  double lead_y_mm = 0.0, lead_psi_mrad = 0.0, lead_y_high_kN = 0.0, lead_l_over_v = 0.0;
  // Largest over the wheelsets, against the reference row of the same entry (0 for it).
  double err_y_mm = 0.0, err_psi_mrad = 0.0, err_y_high_kN = 0.0;
};

struct CurvingAccuracyStudy {
  std::string scene_path;
  std::vector<std::string> levels;       // coarse to fine; the last is the reference
  // Per vehicle entry: its levels coarse to fine with the scene's predictor, then the finest
  // level with the other predictor.
  std::vector<CurvingAccuracyRow> rows;
};

// Runs the study on the levels given (names of kAccuracyLevels, any order, run coarse to fine).
// `progress` (may be empty) receives one line per solve. Throws InputError for a scene without
// vehicle traffic, an unknown level or an empty list.
CurvingAccuracyStudy RunCurvingAccuracyStudy(
    const Scene& scene, const std::vector<std::string>& levels,
    const std::function<void(const std::string&)>& progress);

std::string FormatCurvingAccuracyTable(const CurvingAccuracyStudy& study);
void WriteCurvingAccuracyCsv(const CurvingAccuracyStudy& study, std::ostream& out);

}  // namespace railwear::app
