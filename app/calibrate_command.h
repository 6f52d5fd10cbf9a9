// `railwear calibrate CONFIG.toml [--out FILE.toml] [--db FILE] [--json FILE|-] [--csv FILE]
// [--verbose]`: fits the seed's eq. 4 constants to displacement curves and contact results
// (calibration/influence_fit.h) and writes the influence-constants TOML that scenes load
// with influence_constants = "FILE".
//
// The config, its keys and checks: app/calibrate_config.h. The command is an outline:
// ReadCalibrateConfig -> FitInfluenceConstants -> the outputs of app/calibrate_output.h and the
// constants file of app/influence_constants_file.h.
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
