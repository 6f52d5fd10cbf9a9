// `railwear wear SCENE.toml [--db FILE] [--run NAME] [--resume] [--steps N] [--plot PREFIX]`:
// runs a worn-profile evolution study (wear/wear_simulation.h) and stores every step in the
// profile history database (profiles_db/), one transaction per step.
//
// A new run is stored with its step 0 (the unworn rail) in one transaction. --resume continues
// the named run from its last complete step (a run killed with kill -9 loses at most the step in
// flight; a run without steps gets its step 0 from the scene) and ends with the same profile as
// an uninterrupted run; it refuses a scene that differs from the stored one. SIGINT and SIGTERM
// finish the step being committed or drop the one being solved, mark the run "interrupted" and
// end with Interrupted (exit 130 / 143; app/interrupt_signals.h). A database file deleted or
// replaced under the run stops it with std::runtime_error (exit 1) at the next commit.
// Progress goes to stderr: a progress bar when stderr is a terminal, one log line per step
// otherwise. The summary table goes to stdout.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace railwear::app {

struct Scene;

struct WearCommandOptions {
  std::string scene_path;
  std::optional<std::string> db;   // default: [wear] db, else "wear.sqlite"
  std::optional<std::string> run;  // default: the scene's name
  bool resume = false;
  int steps = 0;                    // > 0: stop after this many new steps (resume later)
  std::optional<int> threads;       // overrides [wear] threads
  std::optional<std::string> plot;  // PNG file prefix: history plots after the run
  // The command that continues an interrupted run, as its message says (default: `railwear wear
  // SCENE --db DB --run NAME --resume`; a sweep gives its own).
  std::string resume_command;
};

void SetupWear(CLI::App& app);

// Throws InputError for a bad scene, database or option (exit 2); std::runtime_error for a
// numerical failure (exit 1; the steps before it stay stored and the run can be resumed) or a
// database file that vanished; Interrupted after SIGINT / SIGTERM.
void RunWearCommand(const WearCommandOptions& options);
// The same for a scene already read (options.scene_path then only names it in messages): the
// sweep's scenes are a base scene with a plan line's overrides (app/sweep_command.h).
void RunWearScene(const Scene& scene, const WearCommandOptions& options);

// The database a wear or history command uses when --db is not given.
constexpr const char* kDefaultDatabase = "wear.sqlite";

}  // namespace railwear::app
