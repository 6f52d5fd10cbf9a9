// `railwear sweep PLAN --slurm` (issue 19): the scripts that run a sweep plan as a Slurm job
// array and merge its runs in a dependent job, written into the runs' folder (OUT_DIR):
//
//   OUT_DIR/sweep.sbatch  the job array: --array=0-(lines-1), one task per manifest line, each
//                         `railwear sweep PLAN --out-dir OUT_DIR --threads "$SLURM_CPUS_PER_TASK"
//                         --index "$SLURM_ARRAY_TASK_ID"`; resources per task: --cpus-per-task,
//                         --time, --mem (and --partition when given); logs in OUT_DIR/logs/.
//   OUT_DIR/merge.sbatch  one task: `railwear sweep PLAN --out-dir OUT_DIR --merge --db STUDY`,
//                         which refuses (exit 2, naming the lines) unless every line is complete.
//   OUT_DIR/submit.sh     submits the array, then the merge job with
//                         --dependency=afterok:ARRAY (it starts once every task ended well).
//                         Its arguments go to the array's sbatch: `submit.sh --array=3,7`
//                         resubmits lines 3 and 7 (killed or failed) and a new merge job; a
//                         complete line is skipped, a started one continues (`wear --resume`).
//
// A plan of more lines than Slurm's MaxArraySize (task ids 0..MaxArraySize-1; 1001 by default,
// `--max-array-size` when the cluster's differs) is submitted in slices: sweep.sbatch's task runs
// line RAILWEAR_SWEEP_OFFSET + SLURM_ARRAY_TASK_ID, and submit.sh submits the array once per
// slice (--array=0-(size-1) with --export=ALL,RAILWEAR_SWEEP_OFFSET=first line of the slice),
// the merge job after all of them (afterok:A1:A2:...). `RAILWEAR_SWEEP_OFFSET=K submit.sh
// --array=I,J` resubmits lines K+I and K+J. A plan that fits one array gets the scripts without
// the offset.
//
// Every path in the scripts is absolute (the railwear executable as running now, the plan, the
// runs' folder, the study database): the jobs run from any folder of any node that sees them.
#pragma once

#include <optional>
#include <string>

namespace railwear::app {

// Resources of each array task (the merge job takes one CPU and the same time and memory).
struct SlurmResources {
  int cpus_per_task = 1;          // also each run's worker threads (SLURM_CPUS_PER_TASK)
  std::string time = "01:00:00";  // sbatch --time: [D-]HH:MM:SS, MM:SS or minutes
  std::string mem = "2G";         // sbatch --mem: a number with an optional K, M, G or T
  std::optional<std::string> partition;
  int max_array_size = 1001;  // the cluster's MaxArraySize: an array's task ids stay below it
};

// What the scripts run, every path absolute.
struct SlurmSweepJob {
  std::string railwear;  // the executable
  std::string plan;      // the plan file
  std::string out_dir;   // the runs' folder; the scripts and logs/ go there too
  std::string study_db;  // the merged study database
  int lines = 0;         // manifest lines: the array is 0..lines-1
  std::string name;      // the job name's suffix (the plan's stem)
  SlurmResources resources;
};

struct SlurmScripts {
  std::string array;   // sweep.sbatch
  std::string merge;   // merge.sbatch
  std::string submit;  // submit.sh
};

// Throws InputError naming the option and the value for a resource Slurm would not take
// (cpus_per_task < 1, max_array_size < 1, a malformed time or memory, a partition name with spaces or quotes).
void ValidateSlurmResources(const SlurmResources& resources);

// The three scripts' text (validates the resources).
SlurmScripts MakeSlurmScripts(const SlurmSweepJob& job);

// Writes the scripts into job.out_dir (created with its logs/ folder; submit.sh executable) and
// returns the path of submit.sh.
std::string WriteSlurmScripts(const SlurmSweepJob& job);

}  // namespace railwear::app
