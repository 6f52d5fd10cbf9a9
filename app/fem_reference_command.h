// `railwear fem-reference CONFIG.toml [--out-dir DIR] [--keep-work] [--only NAME] [--jobs N]
// [--report-only]`:
// builds the seed paper's displacement experiment as a 3-D FEM model per [[experiment]] of the
// config (gmsh mesh, CalculiX solves; wear/calibration/fem_displacement.h), writes the
// displacement-curve CSVs that `calibrate` reads, and prints a summary per experiment, with the
// comparison with the half-space (the validation for a flat body, the effect of curvature and
// size for a curved one) and with another experiment when asked (compare_with).
//
// The config (keys of [fem] are defaults that an [[experiment]] may override):
//   [fem]
//   mesh_size_at_load_mm = 0.1      h0, element size at the load point, > 0
//   mesh_growth = 0.12              h = h0 + mesh_growth * r (mm per mm), in (0, 2]
//   max_element_mm = 20             largest element, >= h0
//   min_distance_mm = 0.5           distances written, from the load point
//   max_distance_mm = 25
//   supports = "bottom"             "bottom" (bottom face clamped) | "far_faces"
//   material = { E_MPa = 210000, nu = 0.28 }
//   loads = ["normal", "axial", "circumferential"]
//   compare_range_mm = [1, 10]      where comparisons fit the offset and report errors
//   jobs = 2                        ccx solves at once ([fem] only; --jobs overrides)
//   threads_per_job = 1             ([fem] only)
//   timeout_s = 3600                per gmsh or ccx run ([fem] only)
//   [[experiment]]
//   name = "r15_convex"             letters, digits, '_', '-', '.'; unique
//   kind = "displacement"           the default (other kinds may come later)
//   body = "convex"                 "flat" | "convex" | "concave"
//   radius_mm = 15                  convex and concave only
//   length_mm, width_mm, depth_mm   body size; defaults per body (DefaultFemBodySize)
//   output = "r15_convex.csv"       default NAME.csv; relative to the config file or --out-dir
//   compare_with = "other"          an earlier experiment of this config (run before this one,
//                                   or its output file when --only skipped it)
#pragma once

#include <string>
#include <vector>

#include "wear/calibration/fem_displacement.h"

namespace CLI {
class App;
}

namespace railwear::app {

struct FemReferenceOptions {
  std::string config;
  std::string out_dir;            // empty: outputs relative to the config file
  bool keep_work = false;         // keep each experiment's work folder as OUT/NAME.work
  std::vector<std::string> only;  // run only these experiments (empty: all)
  int jobs = 0;                   // ccx solves at once; 0: from the config
  // Run nothing: read the CSVs an earlier run wrote and print their comparisons again.
  bool report_only = false;
};

struct FemExperiment {
  std::string name;
  int line = 0;                    // of its [[experiment]] table
  FemDisplacementOptions options;  // work_dir and progress are set when it runs
  std::string output;              // the CSV path, resolved
  std::string compare_with;        // empty: none
  double compare_from_m = 1e-3;
  double compare_to_m = 10e-3;
};

struct FemReferenceConfig {
  std::string path;
  std::vector<FemExperiment> experiments;
};

// Reads and validates a config. Throws InputError "FILE:LINE: key 'KEY' = VALUE: expected ..."
// for unknown keys, wrong types, out-of-range values, unknown names and inconsistent options.
FemReferenceConfig ReadFemReferenceConfig(const std::string& path, const std::string& out_dir);

void SetupFemReference(CLI::App& app);

// Runs the experiments. InputError for a bad config or a missing gmsh/ccx (exit code 2);
// std::runtime_error when gmsh or ccx fail (exit code 1; the message names the log).
void RunFemReference(const FemReferenceOptions& options);

}  // namespace railwear::app
