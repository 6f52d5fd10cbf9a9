// `railwear curving SCENE.toml [--json FILE]`: the steady-state curving of every vehicle entry
// of a wear scene on its unworn rails (core/vehicle/curving.h, docs/curving.md): per wheelset
// the lateral displacement, angle of attack, wheel loads, flange force and L/V against Nadal's
// limit, with the status, the equilibrium's residuals and the time. What the wear study will
// start from, and the way to ask "how does this vehicle run in this curve".
//
// With --db FILE [--run NAME] [--step N]: on the worn rails of a stored wear step instead (both
// rails of the run's step N, default its last, placed as the wear loop places them), each
// vehicle starting as the run's next step would: from the step's stored curving solution, then
// (when that fails, or the step stored none: step 0) from the vehicle's equilibrium on the run's
// unworn rails (solved first, as the run does), then centred: how the vehicle runs after that
// much traffic, and the way to see why a run stopped on a curving that did not converge. The
// database is only read. --start unworn leaves out the stored solution, --start centred both
// (a cold solve). The output names the start of a solution from a fallback and each start's
// solves (JSON: "starts").
//
// --predictor table: a cold solve (on the unworn rails, or a stored step without a curving
// solution) iterates on the contact-table predictor (core/contact/contact_table.h; docs/curving.md
// "The table predictor") before the full model finishes it; default: the scene's [curving]
// predictor (itself `model`, the draft grid, by default). A continued solve (a stored step's
// solution) goes to the full model directly either way.
//
// SIGINT / SIGTERM (issue 17) stop the solve in flight within one contact evaluation and end the
// command with exit 130 / 143 and a message naming the entry; nothing is written (--json
// neither). Before each solve stderr says which entry it solves.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace railwear::app {

struct CurvingOptions {
  std::string scene;
  std::optional<std::string> json;  // "-" for stdout
  std::optional<std::string> db;    // a wear run's database: its step's worn rails
  std::optional<std::string> run;   // default: the scene's name
  std::optional<int> step;          // default: the run's last stored step
  // The cold solve's: "model" or "table"; absent: the scene's [curving] predictor.
  std::optional<std::string> predictor;
  // With db: the first start, "stored" (the run's next step's sequence), "unworn" or "centred".
  std::string start = "stored";
};

void SetupCurving(CLI::App& app);

// Throws InputError for a bad scene or one without vehicle traffic (exit 2), std::runtime_error
// when a vehicle has no equilibrium or does not converge (after printing every entry; exit 1),
// Interrupted for SIGINT / SIGTERM (exit 130 / 143).
void RunCurving(const CurvingOptions& options);

}  // namespace railwear::app
