// `railwear fem-reference CONFIG.toml [--out-dir DIR] [--keep-work] [--only NAME] [--jobs N]
// [--report-only]`:
// builds the seed paper's displacement experiment as a 3-D FEM model per [[experiment]] of the
// config (gmsh mesh, CalculiX solves; calibration/fem/fem_displacement.h), writes the
// displacement-curve CSVs that `calibrate` reads, and prints a summary per experiment, with the
// comparison with the half-space (the validation for a flat body, the effect of curvature and
// size for a curved one) and with another experiment when asked (compare_with).
//
// The config and its keys: app/fem_reference_config.h; what is printed:
// app/fem_reference_output.h.
#pragma once

#include <string>
#include <vector>

#include "app/fem_reference_config.h"

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

void SetupFemReference(CLI::App& app);

// Runs the experiments. InputError for a bad config or a missing gmsh/ccx (exit code 2);
// std::runtime_error when gmsh or ccx fail (exit code 1; the message names the log).
void RunFemReference(const FemReferenceOptions& options);

}  // namespace railwear::app
