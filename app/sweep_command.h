// `railwear sweep PLAN.toml [--list] [--index N] [--out-dir DIR] [--threads N] [--merge]
//                  [--db FILE] [--mpi] [--slurm [--cpus-per-task N] [--time T] [--mem M]
//                  [--partition P] [--max-array-size N]]`:
// the runs of a sweep plan (app/sweep_plan.h), each a wear study in its own database (issue 19).
//
// --list prints the manifest (stdout): one line per run, its id and the values it sets
// ("0001-3fa2c1d0  wear.k=0.0002 track.radius_m=600"); every line's scene is read first, so a
// value the scene rejects is reported (exit 2) before anything runs. --index N runs line N
// (0-based); without it SLURM_ARRAY_TASK_ID is used when set (a Slurm job array), and without
// both every line runs, one after the other: a line whose run fails is recorded and the sweep
// goes on (below); bad input (exit 2) or a signal (130/143) stops it; run again, the complete
// lines are skipped.
//
// A line runs as `railwear wear` would: into OUT_DIR/ID.sqlite, as run ID, its scene written
// beside it as OUT_DIR/ID.toml. A finished run (state complete) is skipped; a started one
// (killed, interrupted, stopped by a failure) is continued (`wear --resume`); a database that
// holds run ID of another scene (the plan or the base scene changed) is refused (exit 2). SQLite
// is never shared: each line writes its own file, so lines may run at once on any machines that
// see OUT_DIR. `railwear merge` then combines the files.
//
// Past one machine (every way gives the same study database, bit for bit):
// - --merge: runs nothing; merges every line's run, in manifest order, into the study database
//   --db (default OUT_DIR.sqlite, beside the folder), as `railwear merge` does. Refused (exit 2,
//   naming the lines and how to run them) unless every line's run is complete. With
//   --max-array-size (a sliced Slurm sweep's merge job passes it) the resubmit hint is per slice.
// - --mpi, under `mpirun -n K` (app/sweep_mpi.h): rank 0 hands the lines to the ranks (itself
//   included) one at a time, largest expected cost first (SweepLineCost); each run writes its
//   own database; rank 0 merges them into --db at the end when every line is complete.
// - --slurm (app/sweep_slurm.h): writes OUT_DIR/sweep.sbatch (a job array, one task per line;
//   slices of --max-array-size tasks, Slurm's MaxArraySize, for a plan of more lines),
//   OUT_DIR/merge.sbatch (the --merge above) and OUT_DIR/submit.sh (the array, then the merge
//   job with --dependency=afterok), and runs nothing.
//
// Failed runs (issue 19). A line whose run fails (a solve that does not converge, a grid too
// large, ...) is a result of the ensemble, not a reason to lose the others: the wear command
// marks its run aborted and records the error message in the line's database (schema 9,
// ProfileStore::SetRunFailed). Then
// - the serial sweep (every line) goes on with the next line, and at the end names the failed
//   lines (index, run id, values, message) and exits 3 (SomeRunsFailed); `--index N` of a failing
//   line exits 1, as `wear` does;
// - --merge (and --mpi's merge) merges the complete runs AND the failed ones (with their
//   failure, so the merged study says which runs failed and why), names the failed ones on
//   stdout and exits 3; lines not run, or started and not complete without a recorded failure
//   (killed, interrupted), still refuse the merge (they are work left, not results);
// - `history bands` / `life` band the complete runs and name the failed ones
//   (app/history_ensemble.h).
// Exit 3 ("done, but some runs failed") is distinct from 1 (a failure stopped the command) and
// 2 (bad input): a script sees that the answer covers fewer runs than the plan, and the study
// is complete as far as it can be (running it again fails the same lines again).
// Slurm: the failing line's task ends FAILED (exit 1), so the merge job (afterok) never starts;
// `scancel` it and run `railwear sweep PLAN --merge` (or `sbatch merge.sbatch`).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/sweep_slurm.h"

namespace CLI {
class App;
}

namespace railwear::app {

// Exit code of a sweep or merge whose every line ended, some with a failed run (SomeRunsFailed).
constexpr int kExitSomeRunsFailed = 3;

// Thrown when every line of a sweep ended and some runs failed (recorded in their databases):
// main() prints the message as a warning and exits with kExitSomeRunsFailed.
class SomeRunsFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SweepCommandOptions {
  std::string plan_path;
  bool list = false;
  std::optional<int> index;            // default: SLURM_ARRAY_TASK_ID, else every line
  std::optional<std::string> out_dir;  // overrides the plan's out_dir
  std::optional<int> threads;          // each run's worker threads (wear --threads)
  bool merge = false;                  // merge the complete runs into `db`, run nothing
  std::optional<std::string> db;       // the merged study database (default: OUT_DIR.sqlite)
  bool mpi = false;                    // under mpirun: dynamic dispatch, rank 0 merges
  bool slurm = false;                  // write the Slurm scripts, run nothing
  SlurmResources slurm_resources;      // of each array task (--slurm)
};

struct SweepPlan;
struct SweepLine;

// Runs the lines of `plan` over MPI (app/sweep_mpi.h), in `order` (line indices, largest expected
// cost first), then merges them into `study_db`. Linked into the railwear executable only.
using SweepMpiRunner = void (*)(const SweepPlan& plan, const std::vector<int>& order,
                                const std::vector<double>& costs, const std::string& study_db,
                                const SweepCommandOptions& options);

// `mpi`: what --mpi calls (null: --mpi is refused, this railwear has no MPI).
void SetupSweep(CLI::App& app, SweepMpiRunner mpi = nullptr);

// Throws InputError for a malformed plan, a rejected value, an index out of range or a bad
// SLURM_ARRAY_TASK_ID (exit 2); what `wear` throws for a run (exit 1, Interrupted).
void RunSweepCommand(const SweepCommandOptions& options, SweepMpiRunner mpi = nullptr);

// One line: skipped when its run is complete, continued when started, else started (the
// progress lines on stderr). What `wear` throws.
void RunSweepLine(const SweepPlan& plan, const SweepLine& line, const SweepCommandOptions& options);

// The merged study database of a sweep: options.db, else OUT_DIR.sqlite (beside the folder).
std::string SweepStudyPath(const SweepPlan& plan, const SweepCommandOptions& options);

// The run of `line` in its own database (OUT_DIR/ID.sqlite) when it failed with a recorded
// failure (state aborted, ProfileStore::FindRunFailure); nullopt otherwise.
std::optional<std::string> SweepLineFailure(const SweepPlan& plan, const SweepLine& line);

// "line 3 (0003-1a2b3c4d; wear.k=0.0002 traffic[0].friction=0.3): MESSAGE": a failed line as the
// sweep, the merge and `history` name it.
std::string FailedLineText(const SweepLine& line, const std::string& message);

// Merges every line's run into `study_db` in manifest order (RunMergeCommand): the complete ones
// and the failed ones (with their recorded failure). Throws InputError naming the lines whose run
// is missing or started and not complete (no recorded failure), and how to resubmit them (for a
// plan of more lines than `max_array_size`, submitted in slices: per slice,
// `RAILWEAR_SWEEP_OFFSET=K submit.sh --array=I,J`), and nothing is merged. After merging, names
// the failed lines on stdout and throws SomeRunsFailed when there are any.
void MergeSweepRuns(const SweepPlan& plan, const std::string& study_db, int max_array_size = 1001);

}  // namespace railwear::app
