// `railwear accuracy WEAR_SCENE.toml`: what accuracy costs in time for the wear step (issue 6).
// The scene's wear study is run to its end (or to --mgt) at each accuracy level and each step
// limit (max_depth_per_step); per run the wall time, the number of profile updates, and the
// error of the final worn profile against the reference run, the finest level with the smallest
// step limit:
//   profile error   max over the unworn profile's arc length of |d(s) - d_ref(s)|, d the
//                   normal wear depth of wear_measures.h (the distance between the two final
//                   profiles measured along the unworn rail's normals) [mm];
//   max-depth error |max d - max d_ref| / max d_ref;
//   area error      |A - A_ref| / A_ref, A the worn area.
// The reference is itself approximate: the table also gives the difference between it and the
// next coarser run in each direction (level, step limit), an estimate of its own error.
// Nothing is stored in a database. Prints a table; with --out DIR writes DIR/wear_accuracy.csv
// and DIR/wear_accuracy.png (profile error against run time, log-log, one line per level).
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/scene.h"

namespace railwear::app {

struct WearAccuracyOptions {
  // Accuracy presets, names of kAccuracyLevels (accuracy_command.h); run coarse to fine.
  std::vector<std::string> levels = {"draft", "standard", "reference"};
  // Step limits [mm], > 0; run large to small.
  std::vector<double> step_limits_mm = {0.2, 0.1, 0.05};
  // Length of every run [MGT] instead of the scene's total (> 0).
  std::optional<double> total_mgt;
  int threads = 0;  // load-case workers; 0 = the scene's [wear] threads
};

struct WearAccuracyRow {
  std::string level;
  double step_limit_mm = 0.0;
  double time_s = 0.0;  // wall time of the whole run (one run: wear runs are long)
  int steps = 0;
  double passes = 0.0, mgt = 0.0;
  double max_depth_mm = 0.0, worn_area_mm2 = 0.0, wear_45_mm = 0.0;
  std::vector<double> depth_m;  // d(s) on the unworn profile's samples [m] (NaN: unmatched)
  double err_profile_mm = 0.0, err_max_depth = 0.0, err_area = 0.0;  // against the reference
};

struct WearAccuracyStudy {
  std::string scene_name, scene_path;
  double total_mgt = 0.0;
  std::vector<WearAccuracyRow> rows;  // levels coarse to fine, step limits large to small
  int reference_row = -1;             // index in rows
  std::vector<std::string> notes;     // the reference's own error estimate
};

// Runs the study. `progress` (may be empty) receives one line per finished run. Throws
// InputError for a scene without a wear study, an unknown level, a non-positive step limit or
// total.
WearAccuracyStudy RunWearAccuracyStudy(
    const Scene& scene, const WearAccuracyOptions& options,
    const std::function<void(const std::string&)>& progress = {});

std::string FormatWearAccuracyTable(const WearAccuracyStudy& study);
void WriteWearAccuracyCsv(const WearAccuracyStudy& study, std::ostream& out);
// Profile error [mm] against run time [s], log-log, one line per accuracy level. Throws
// std::runtime_error when gnuplot is missing or fails.
void PlotWearAccuracy(const WearAccuracyStudy& study, const std::string& png_path);

}  // namespace railwear::app
