// `railwear curving SCENE.toml [--json FILE]`: the steady-state curving of every vehicle entry
// of a wear scene on its unworn rails (core/vehicle/curving.h, docs/curving.md): per wheelset
// the lateral displacement, angle of attack, wheel loads, flange force and L/V against Nadal's
// limit, with the status, the equilibrium's residuals and the time. What the wear study will
// start from, and the way to ask "how does this vehicle run in this curve".
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
};

void SetupCurving(CLI::App& app);

// Throws InputError for a bad scene or one without vehicle traffic (exit 2), std::runtime_error
// when a vehicle has no equilibrium or does not converge (after printing every entry; exit 1).
void RunCurving(const CurvingOptions& options);

}  // namespace railwear::app
