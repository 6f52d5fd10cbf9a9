// `railwear calibrate CONFIG.toml [--out FILE.toml] [--db FILE] [--json FILE|-] [--csv FILE]
// [--verbose]`: fits the seed's eq. 4 constants to displacement curves and contact results
// (calibration/influence_fit.h) and writes the influence-constants TOML that scenes load
// with influence_constants = "FILE".
//
// Config (strict: unknown keys, wrong types and out-of-range values are errors naming
// FILE:LINE and the key; paths are relative to the config file):
//
//   [calibration]
//   name = "paper experiment, R15/R80"   # default: the config file's name
//   fit = ["c_f", "c_z", "c_s"]          # any non-empty subset; default all three
//   separate_bodies = false              # true: a convex and a concave set
//   start = { c_f = 0.75, c_z = 1.0, c_s = 0.25 }   # or { convex = {...}, concave = {...} }
//   fit_offsets = true                   # one offset per curve (FE supports)
//   out = "calibrated_constants.toml"    # default: CONFIG-STEM_constants.toml beside the config
//   db = "calibration.sqlite"            # optional: store the calibration there
//   contact_relative_step = 0.01         # central-difference step on contact results
//   max_iterations = 100
//
//   [[displacement_curves]]              # any number, >= 1 in all with contact_results
//   file = "r15_convex.csv"              # required (displacement_curves.h format)
//   weight = 1.0                         # > 0
//   min_distance_mm = 0.5                # leave out points nearer the load (FE near field)
//   max_distance_mm = 20                 # ... and farther
//
//   [[contact_results]]
//   scene = "groove_conformal.toml"      # required: a single-wheel scene, golubenko kernel
//   area_mm2 = 60.2                      # required target contact area, > 0
//   p_max_MPa = 1234                     # required target peak pressure, > 0
//   weight = 1.0
//
// Output: stdout the report (data, constants with standard errors, correlations, conditioning,
// residuals per curve and per contact result before and after, Ceres's brief report; the full
// one with --verbose); stderr warnings and progress. --json writes every number, every point's
// residual and both Ceres reports (with --json - the JSON goes to stdout and the report to
// stderr); --csv every point's residual. The constants TOML records the provenance in comments.
// With a db (config or --db, which wins) the calibration and the text of every input (config,
// CSVs, scenes and the profile files they name) go to the study database (profiles_db/SCHEMA.md).
//
// Exit codes (app/main.cpp): 0 fitted (also when badly conditioned: warnings on stderr); 1 when
// Ceres fails (nothing written) or stops without converging (outputs written, marked so); 2 for
// bad input: the config, a CSV (the reader's FILE:LINE message), a missing file, a scene that
// does not load.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace railwear::app {

struct CalibrateOptions {
  std::string config;
  std::optional<std::string> out;   // overrides [calibration] out
  std::optional<std::string> db;    // overrides [calibration] db
  std::optional<std::string> json;  // FILE or "-"
  std::optional<std::string> csv;   // FILE: one row per point
  bool verbose = false;             // Ceres's full report in the text output
};

void SetupCalibrate(CLI::App& app);

// Throws InputError for bad input (exit 2), std::runtime_error when the fit fails or does not
// converge (exit 1; in the latter case after writing the outputs).
void RunCalibrate(const CalibrateOptions& options);

}  // namespace railwear::app
