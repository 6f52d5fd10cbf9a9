// `mpirun -n K railwear sweep PLAN --mpi` (issue 19): the lines of a sweep plan run by K MPI
// ranks, dispatched dynamically, then merged by rank 0. Built into the railwear executable only
// (app/CMakeLists.txt): MPI stays out of railwear_app and out of the libraries, and a study run
// knows nothing of where it runs.
//
// - Rank 0 holds the queue of lines, largest expected cost first (SweepLineCost; ties in
//   manifest order), and hands out one line at a time to the rank that asks: every other rank
//   asks, runs its line (RunSweepLine: a complete run is skipped, a started one continues) and
//   asks again, reporting how the line ended. Rank 0 runs lines too, from the same queue, in a
//   worker thread; its main thread only serves the requests, polling every few milliseconds
//   (Open MPI's blocking receive would spin a core).
// - Each run writes its own database, OUT_DIR/ID.sqlite, as a serial sweep does.
// - When every rank is done, rank 0 merges every line's run in manifest order into the study
//   database (MergeSweepRuns): the same file, bit for bit, as serially or through Slurm.
// - A line that fails (its exception printed by its rank, with the rank) does not stop the
//   others. When every failed line's run recorded its failure (a run that failed: a result,
//   app/sweep_command.h), rank 0 merges the complete and the failed runs, names the failed ones
//   and exits 3; otherwise (bad input, a run that recorded nothing) it merges nothing and ends
//   with exit 1, naming the lines: mpirun again (or `sweep --index N`) runs only those, and the
//   merge.
// - SIGINT / SIGTERM (mpirun forwards them): the rank's run is marked interrupted as by `wear`,
//   and the rank aborts the job (MPI_Abort, exit 130 / 143); runs continue when started again.
// - Each run's worker threads: --threads, default 1 (the ranks are the parallelism).
#pragma once

#include <string>
#include <vector>

#include "app/sweep_command.h"

namespace railwear::app {

// SweepMpiRunner: initialises MPI (MPI_Init_thread, MPI_THREAD_FUNNELED), runs the lines over
// the ranks of MPI_COMM_WORLD, merges on rank 0, finalises MPI. Throws on rank 0 when a line
// failed (std::runtime_error, exit 1) or the merge is refused (InputError, exit 2).
void RunSweepMpi(const SweepPlan& plan, const std::vector<int>& order,
                 const std::vector<double>& costs, const std::string& study_db,
                 const SweepCommandOptions& options);

}  // namespace railwear::app
