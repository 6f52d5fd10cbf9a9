// `railwear accuracy SCENE.toml`: what accuracy costs in time (issue 6). A wear scene runs the
// wear-step study of wear_accuracy.h instead of what follows. The scene's contact
// problem is solved with each model at each accuracy level; per run the median time per solve,
// the peak memory the solve adds, and the errors of contact area, peak pressure, total force
// and (when rolling) creep force against a reference (with --tangential, per tangential method,
// against the exact solver's): the finest solution of the reference model
// (conformal geometry + Boussinesq kernel unless --reference-model says otherwise), Richardson-
// extrapolated where the levels allow, or a JSON file given with --reference. Prints a table;
// with --out DIR writes DIR/accuracy.csv and the Pareto plot DIR/accuracy.png (error against
// time, log-log, gnuplot).
//
// The command is split like `contact`: accuracy_config.h (options -> typed plan),
// accuracy_study.h (the measurement), accuracy_output.h (table, CSV, plot); this file is the
// outline (Setup/Run). It includes all three, so callers need only this header.
#pragma once

#include "app/accuracy_config.h"
#include "app/accuracy_output.h"
#include "app/accuracy_study.h"

namespace CLI {
class App;
}

namespace railwear::app {

void SetupAccuracy(CLI::App& app);
// Throws InputError for bad input (exit 2) and std::runtime_error when the reference could not
// be computed (exit 1, after printing what was measured).
void RunAccuracy(const AccuracyOptions& options);

}  // namespace railwear::app
