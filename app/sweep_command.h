// `railwear sweep PLAN.toml [--list] [--index N] [--out-dir DIR] [--threads N]`: the runs of a
// sweep plan (app/sweep_plan.h), each a wear study in its own database (issue 19).
//
// --list prints the manifest (stdout): one line per run, its id and the values it sets
// ("0001-3fa2c1d0  wear.k=0.0002 track.radius_m=600"); every line's scene is read first, so a
// value the scene rejects is reported (exit 2) before anything runs. --index N runs line N
// (0-based); without it SLURM_ARRAY_TASK_ID is used when set (a Slurm job array), and without
// both every line runs, one after the other, stopping at the first that fails (its exception
// propagates: exit 1, or 130/143 for a signal); run again, the complete lines are skipped.
//
// A line runs as `railwear wear` would: into OUT_DIR/ID.sqlite, as run ID, its scene written
// beside it as OUT_DIR/ID.toml. A finished run (state complete) is skipped; a started one
// (killed, interrupted, stopped by a failure) is continued (`wear --resume`); a database that
// holds run ID of another scene (the plan or the base scene changed) is refused (exit 2). SQLite
// is never shared: each line writes its own file, so lines may run at once on any machines that
// see OUT_DIR. `railwear merge` then combines the files.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace railwear::app {

struct SweepCommandOptions {
  std::string plan_path;
  bool list = false;
  std::optional<int> index;            // default: SLURM_ARRAY_TASK_ID, else every line
  std::optional<std::string> out_dir;  // overrides the plan's out_dir
  std::optional<int> threads;          // each run's worker threads (wear --threads)
};

void SetupSweep(CLI::App& app);

// Throws InputError for a malformed plan, a rejected value, an index out of range or a bad
// SLURM_ARRAY_TASK_ID (exit 2); what `wear` throws for a run (exit 1, Interrupted).
void RunSweepCommand(const SweepCommandOptions& options);

}  // namespace railwear::app
