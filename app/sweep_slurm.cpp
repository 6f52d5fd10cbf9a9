// The Slurm job array, merge job and submit script of a sweep plan (app/sweep_slurm.h).
#include "app/sweep_slurm.h"

#include <algorithm>
#include <filesystem>
#include <regex>

#include <fmt/format.h>

#include "app/toml_fields.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

namespace fs = std::filesystem;

// `text` as one shell word: single-quoted, a quote inside as '\''.
std::string Quote(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

// The #SBATCH lines every job of the sweep shares: time, memory, partition.
std::string SharedDirectives(const SlurmResources& r) {
  std::string out = fmt::format("#SBATCH --time={}\n#SBATCH --mem={}\n", r.time, r.mem);
  if (r.partition) out += fmt::format("#SBATCH --partition={}\n", *r.partition);
  return out;
}

}  // namespace

void ValidateSlurmResources(const SlurmResources& r) {
  if (r.cpus_per_task < 1) {
    throw InputError(
        fmt::format("--cpus-per-task {}: expected 1 or more CPUs per array task", r.cpus_per_task));
  }
  // sbatch --time: minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS.
  if (r.max_array_size < 1) {
    throw InputError(fmt::format(
        "--max-array-size {}: expected the cluster's MaxArraySize, 1 or more (Slurm's default "
        "1001; `scontrol show config | grep MaxArraySize`)",
        r.max_array_size));
  }
  static const std::regex kTime(R"(\d+(:\d+){0,2}|\d+-\d+(:\d+){0,2})");
  if (!std::regex_match(r.time, kTime)) {
    throw InputError(fmt::format(
        "--time '{}': expected a Slurm time limit: minutes, MM:SS, HH:MM:SS or D-HH:MM:SS",
        r.time));
  }
  static const std::regex kMem(R"([0-9]+[KMGT]?)");
  if (!std::regex_match(r.mem, kMem) || r.mem.front() == '0') {
    throw InputError(fmt::format(
        "--mem '{}': expected the memory of a task as a positive number with an optional unit "
        "K, M, G or T (e.g. 2G)",
        r.mem));
  }
  static const std::regex kPartition(R"([A-Za-z0-9_.,-]+)");
  if (r.partition && !std::regex_match(*r.partition, kPartition)) {
    throw InputError(
        fmt::format("--partition '{}': expected partition names of letters, digits, '_', '-', '.' "
                    "(several separated by commas)",
                    *r.partition));
  }
}

SlurmScripts MakeSlurmScripts(const SlurmSweepJob& job) {
  ValidateSlurmResources(job.resources);
  const SlurmResources& r = job.resources;
  const std::string logs = (fs::path(job.out_dir) / "logs").string();
  const std::string sweep = fmt::format("{} sweep {} --out-dir {}", Quote(job.railwear),
                                        Quote(job.plan), Quote(job.out_dir));
  // More lines than one array takes: slices of `slice` tasks, each with its first line's offset.
  const int slice = r.max_array_size;
  const bool sliced = job.lines > slice;
  SlurmScripts s;
  s.array = fmt::format(
      "#!/bin/bash\n"
      "# The sweep {plan} as a Slurm job array: task N runs line N of its manifest\n"
      "# (`railwear sweep PLAN --list`) into {out}/ID.sqlite. Written by\n"
      "# `railwear sweep --slurm`; submit it with submit.sh beside it (then the merge job\n"
      "# follows), or alone. A killed or failed line is resubmitted by its index:\n"
      "#   sbatch --array=3,7 {array_file}\n"
      "# (a complete line is skipped, a started one continues where its database ends).\n"
      "#SBATCH --job-name=railwear-sweep-{name}\n"
      "#SBATCH --array=0-{last}\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task={cpus}\n"
      "{shared}"
      "#SBATCH --output={logs}/sweep_%A_%a.log\n"
      "set -euo pipefail\n"
      "{slices}"
      "exec {sweep} --threads \"${{SLURM_CPUS_PER_TASK:-{cpus}}}\" --index {index}\n",
      fmt::arg("plan", job.plan), fmt::arg("out", job.out_dir),
      fmt::arg("array_file", (fs::path(job.out_dir) / "sweep.sbatch").string()),
      fmt::arg("name", job.name), fmt::arg("last", std::min(job.lines, slice) - 1),
      fmt::arg("slices", sliced ? fmt::format("# {} lines in slices of {} (MaxArraySize): this task runs line "
                                              "RAILWEAR_SWEEP_OFFSET + SLURM_ARRAY_TASK_ID\n",
                                              job.lines, slice)
                                : std::string()),
      fmt::arg("index", sliced ? "\"$((${RAILWEAR_SWEEP_OFFSET:-0} + SLURM_ARRAY_TASK_ID))\""
                               : "\"$SLURM_ARRAY_TASK_ID\""),
      fmt::arg("cpus", r.cpus_per_task), fmt::arg("shared", SharedDirectives(r)),
      fmt::arg("logs", logs), fmt::arg("sweep", sweep));
  s.merge = fmt::format(
      "#!/bin/bash\n"
      "# Merges the runs of the sweep {plan} ({out}/*.sqlite) into {db},\n"
      "# once every line is complete (otherwise exit 2, naming the lines to resubmit).\n"
      "# submit.sh submits it with --dependency=afterok on the job array.\n"
      "#SBATCH --job-name=railwear-merge-{name}\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task=1\n"
      "{shared}"
      "#SBATCH --output={logs}/merge_%j.log\n"
      "set -euo pipefail\n"
      "exec {sweep} --merge --db {qdb}{max_array}\n",
      fmt::arg("plan", job.plan), fmt::arg("out", job.out_dir), fmt::arg("db", job.study_db),
      fmt::arg("name", job.name), fmt::arg("shared", SharedDirectives(r)), fmt::arg("logs", logs),
      fmt::arg("sweep", sweep), fmt::arg("qdb", Quote(job.study_db)),
      fmt::arg("max_array", sliced ? fmt::format(" --max-array-size {}", slice) : std::string()));
  if (sliced) {
    std::string slices;
    for (int first = 0; first < job.lines; first += slice) {
      slices += fmt::format(" \"{} 0-{}\"", first, std::min(slice, job.lines - first) - 1);
    }
    s.submit = fmt::format(
        "#!/bin/bash\n"
        "# Submits the sweep {plan} ({lines} lines) as job arrays of at most {slice} tasks\n"
        "# (Slurm's MaxArraySize), task I of the slice from line K running line K + I\n"
        "# (RAILWEAR_SWEEP_OFFSET=K), then merge.sbatch with --dependency=afterok on all of them.\n"
        "# With arguments one slice is submitted: `RAILWEAR_SWEEP_OFFSET=K submit.sh --array=I,J`\n"
        "# resubmits lines K+I and K+J and a new merge job (scancel a pending one first).\n"
        "set -euo pipefail\n"
        "ids=\"\"\n"
        "if [ $# -gt 0 ]; then\n"
        "  array=$(sbatch --parsable --export=ALL,RAILWEAR_SWEEP_OFFSET=\"${{RAILWEAR_SWEEP_OFFSET:-0}}\" "
        "\"$@\" {array})\n"
        "  ids=\":${{array%%;*}}\"\n"
        "else\n"
        "  for slice in{slices}; do\n"
        "    set -- $slice\n"
        "    array=$(sbatch --parsable --export=ALL,RAILWEAR_SWEEP_OFFSET=\"$1\" --array=\"$2\" {array})\n"
        "    ids=\"$ids:${{array%%;*}}\"\n"
        "  done\n"
        "fi\n"
        "merge=$(sbatch --parsable --dependency=afterok\"$ids\" {merge})\n"
        "merge=${{merge%%;*}}\n"
        "echo \"railwear sweep: job array(s) ${{ids#:}} ({lines} line(s) of {plan}), merge job $merge "
        "into {db}\"\n",
        fmt::arg("plan", job.plan), fmt::arg("lines", job.lines), fmt::arg("slice", slice),
        fmt::arg("slices", slices),
        fmt::arg("array", Quote((fs::path(job.out_dir) / "sweep.sbatch").string())),
        fmt::arg("merge", Quote((fs::path(job.out_dir) / "merge.sbatch").string())),
        fmt::arg("db", job.study_db));
    return s;
  }
  s.submit = fmt::format(
      "#!/bin/bash\n"
      "# Submits the sweep {plan}: the job array sweep.sbatch, then merge.sbatch with\n"
      "# --dependency=afterok on it (it runs once every task ended well). Arguments go to the\n"
      "# array's sbatch: `submit.sh --array=3,7` resubmits lines 3 and 7 and a new merge job\n"
      "# (cancel a merge job left pending by a failed task with scancel first).\n"
      "set -euo pipefail\n"
      "array=$(sbatch --parsable \"$@\" {array})\n"
      "array=${{array%%;*}}\n"
      "merge=$(sbatch --parsable --dependency=afterok:\"$array\" {merge})\n"
      "merge=${{merge%%;*}}\n"
      "echo \"railwear sweep: job array $array ({lines} line(s) of {plan}), merge job $merge "
      "into {db}\"\n",
      fmt::arg("plan", job.plan), fmt::arg("lines", job.lines),
      fmt::arg("array", Quote((fs::path(job.out_dir) / "sweep.sbatch").string())),
      fmt::arg("merge", Quote((fs::path(job.out_dir) / "merge.sbatch").string())),
      fmt::arg("db", job.study_db));
  return s;
}

std::string WriteSlurmScripts(const SlurmSweepJob& job) {
  const SlurmScripts s = MakeSlurmScripts(job);
  const fs::path dir(job.out_dir);
  fs::create_directories(dir / "logs");
  WriteOutputFile((dir / "sweep.sbatch").string(), s.array, "the sweep's Slurm job array");
  WriteOutputFile((dir / "merge.sbatch").string(), s.merge, "the sweep's Slurm merge job");
  const std::string submit = (dir / "submit.sh").string();
  WriteOutputFile(submit, s.submit, "the sweep's Slurm submit script");
  fs::permissions(submit, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  return submit;
}

}  // namespace railwear::app
