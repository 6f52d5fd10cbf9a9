// `railwear sweep`: a plan's manifest, and its lines run as wear studies, one database each.
#include "app/cli_checks.h"
#include "app/sweep_command.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <numeric>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include "app/interrupt_signals.h"
#include "app/merge_command.h"
#include "app/scene.h"
#include "app/sweep_plan.h"
#include "app/sweep_slurm.h"
#include "app/toml_fields.h"
#include "app/wear_command.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"

namespace railwear::app {
namespace {

namespace fs = std::filesystem;

// The line to run: --index, else SLURM_ARRAY_TASK_ID, else none (every line).
std::optional<int> LineToRun(const SweepCommandOptions& options, int lines) {
  std::optional<int> index = options.index;
  std::string from = "--index";
  if (!index) {
    const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
    if (task == nullptr || *task == '\0') return std::nullopt;
    from = "SLURM_ARRAY_TASK_ID";
    char* end = nullptr;
    const long v = std::strtol(task, &end, 10);
    if (*end != '\0' || v < 0 || v > kMaxSweepLines) {
      throw InputError(fmt::format(
          "environment variable SLURM_ARRAY_TASK_ID = '{}': expected a line number of the plan "
          "(0 to {}; the job array's --array=0-{})",
          task, lines - 1, lines - 1));
    }
    index = static_cast<int>(v);
  }
  if (*index < 0 || *index >= lines) {
    throw InputError(fmt::format("{} {}: the plan {} has {} line(s); expected 0 to {}", from,
                                 *index, options.plan_path, lines, lines - 1));
  }
  return index;
}

// Absolute, without . and .. (the Slurm scripts run from any folder).
std::string Absolute(const std::string& path) {
  return fs::weakly_canonical(fs::absolute(path)).string();
}

// "0,3-5,9" for sorted indices (the form of sbatch --array).
std::string Ranges(const std::vector<int>& v) {
  std::string out;
  for (size_t i = 0; i < v.size();) {
    size_t j = i;
    while (j + 1 < v.size() && v[j + 1] == v[j] + 1) ++j;
    out += fmt::format("{}{}", out.empty() ? "" : ",",
                       j == i ? fmt::format("{}", v[i]) : fmt::format("{}-{}", v[i], v[j]));
    i = j + 1;
  }
  return out;
}

// Writes the Slurm scripts of the plan (--slurm) and says how to submit them.
void WriteSlurm(const SweepPlan& plan, const SweepCommandOptions& options) {
  SlurmSweepJob job;
  job.railwear = fs::read_symlink("/proc/self/exe").string();
  job.plan = Absolute(plan.path);
  job.out_dir = Absolute(plan.out_dir);
  job.study_db = Absolute(SweepStudyPath(plan, options));
  job.lines = static_cast<int>(plan.lines.size());
  job.name = fs::path(plan.path).stem().string();
  job.resources = options.slurm_resources;
  const std::string submit = WriteSlurmScripts(job);
  const int slice = std::min(job.lines, job.resources.max_array_size);
  if (slice < job.lines) {
    std::cout << fmt::format(
        "{}/sweep.sbatch: {} lines in {} slices of at most {} task(s) (Slurm's MaxArraySize); "
        "task I of the slice from line K runs line K + I (RAILWEAR_SWEEP_OFFSET=K)\n",
        plan.out_dir, job.lines, (job.lines + slice - 1) / slice, slice);
  }
  std::cout << fmt::format(
      "{}/sweep.sbatch: job array of {} task(s) (--array=0-{}, {} CPU(s), {}, {} each)\n"
      "{}/merge.sbatch: merges the runs into {}\n"
      "{}: submits the array, then the merge job after it (afterok)\n",
      plan.out_dir, slice, slice - 1, job.resources.cpus_per_task, job.resources.time,
      job.resources.mem, plan.out_dir, job.study_db, submit);
  std::cerr << fmt::format(
      "railwear: submit with `{}`; resubmit killed or failed lines by index with `{} "
      "--array=3,7` (complete lines are skipped)\n",
      submit, submit);
}

}  // namespace

void RunSweepLine(const SweepPlan& plan, const SweepLine& line,
                  const SweepCommandOptions& options) {
  const Scene scene = SweepLineScene(plan, line);
  fs::create_directories(plan.out_dir);
  const std::string base = (fs::path(plan.out_dir) / line.id).string();
  WearCommandOptions wear;
  wear.scene_path = base + ".toml";
  wear.db = base + ".sqlite";
  wear.run = line.id;
  wear.threads = options.threads;
  wear.resume_command = fmt::format("railwear sweep {} --index {}", plan.path, line.index);
  {
    ProfileStore store = ProfileStore::Open(*wear.db);
    if (const std::optional<RunInfo> run = store.FindRun(line.id)) {
      if (run->scene_text != scene.text) {
        throw InputError(fmt::format(
            "{}: run {} there was started from another scene than line {} of {} now (the plan "
            "or its base scene changed); expected the same scene: remove the file, or give the "
            "sweep another out_dir",
            *wear.db, line.id, line.index, plan.path));
      }
      if (run->state == RunState::kComplete) {
        std::cerr << fmt::format("railwear: sweep line {} ({}): complete in {}; skipped\n",
                                 line.index, line.id, *wear.db);
        return;
      }
      wear.resume = true;
    }
  }
  WriteOutputFile(wear.scene_path, scene.text, "the scene of a sweep line");
  std::cerr << fmt::format("railwear: sweep line {} ({}): {}{}\n", line.index, line.id,
                           line.overrides.empty() ? "the base scene" : line.Differences(),
                           wear.resume ? " (continued)" : "");
  RunWearScene(scene, wear);
}

std::string SweepStudyPath(const SweepPlan& plan, const SweepCommandOptions& options) {
  if (options.db) return *options.db;
  std::string dir = plan.out_dir;
  while (dir.size() > 1 && (dir.back() == '/' || dir.back() == '\\')) dir.pop_back();
  return dir + ".sqlite";
}

std::optional<std::string> SweepLineFailure(const SweepPlan& plan, const SweepLine& line) {
  const std::string db = (fs::path(plan.out_dir) / (line.id + ".sqlite")).string();
  if (!fs::exists(db)) return std::nullopt;
  const ProfileStore store = ProfileStore::OpenReadOnly(db);
  const std::optional<RunInfo> run = store.FindRun(line.id);
  if (!run || run->state != RunState::kAborted) return std::nullopt;
  if (const std::optional<RunFailure> f = store.FindRunFailure(run->id)) return f->message;
  return std::nullopt;
}

std::string FailedLineText(const SweepLine& line, const std::string& message) {
  return fmt::format("line {} ({}; {}): {}", line.index, line.id,
                     line.overrides.empty() ? "the base scene" : line.Differences(), message);
}

void MergeSweepRuns(const SweepPlan& plan, const std::string& study_db, int max_array_size) {
  std::vector<int> missing, unfinished;
  std::vector<std::string> failed;
  MergeCommandOptions merge;
  merge.out = study_db;
  for (const SweepLine& line : plan.lines) {
    const std::string db = (fs::path(plan.out_dir) / (line.id + ".sqlite")).string();
    std::optional<RunInfo> run;
    if (fs::exists(db)) run = ProfileStore::OpenReadOnly(db).FindRun(line.id);
    if (!run) {
      missing.push_back(line.index);
    } else if (run->state != RunState::kComplete) {
      if (const std::optional<std::string> why = SweepLineFailure(plan, line)) {
        failed.push_back(FailedLineText(line, *why));
      } else {
        unfinished.push_back(line.index);
      }
    }
    merge.inputs.push_back(db);
  }
  if (!missing.empty() || !unfinished.empty()) {
    std::vector<int> all = missing;
    all.insert(all.end(), unfinished.begin(), unfinished.end());
    std::sort(all.begin(), all.end());
    // Slurm: one array, or (past MaxArraySize) the slices' task ids with their offsets.
    std::string resubmit;
    const int lines = static_cast<int>(plan.lines.size());
    if (lines <= max_array_size) {
      resubmit = fmt::format("`sbatch --array={} {}/sweep.sbatch`", Ranges(all), plan.out_dir);
    } else {
      for (size_t i = 0; i < all.size();) {
        const int first = all[i] / max_array_size * max_array_size;
        std::vector<int> tasks;
        for (; i < all.size() && all[i] < first + max_array_size; ++i) tasks.push_back(all[i] - first);
        resubmit += fmt::format("{}`RAILWEAR_SWEEP_OFFSET={} {}/submit.sh --array={}`",
                                resubmit.empty() ? "" : ", ", first, plan.out_dir, Ranges(tasks));
      }
    }
    throw InputError(fmt::format(
        "sweep {}: {} of {} line(s) not complete in {} (not run: {}; started, not complete: "
        "{}{}); expected every line complete (or failed, with its failure recorded) before the "
        "merge: run them with `railwear sweep {} --index N`, or resubmit them with {}; complete "
        "lines are skipped",
        plan.path, all.size(), plan.lines.size(), plan.out_dir,
        missing.empty() ? "none" : Ranges(missing),
        unfinished.empty() ? "none" : Ranges(unfinished),
        failed.empty() ? "" : fmt::format("; failed: {}", failed.size()), plan.path, resubmit));
  }
  RunMergeCommand(merge);
  if (!failed.empty()) {
    for (const std::string& f : failed) std::cout << "failed run: " << f << "\n";
    throw SomeRunsFailed(fmt::format(
        "sweep {}: {} of {} run(s) failed and are merged into {} with their error (state "
        "aborted; `history bands` and `history life` leave them out and name them), the other "
        "{} complete: {}",
        plan.path, failed.size(), plan.lines.size(), study_db, plan.lines.size() - failed.size(),
        fmt::join(failed, "; ")));
  }
}

void SetupSweep(CLI::App& app, SweepMpiRunner mpi) {
  auto options = std::make_shared<SweepCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Run the wear studies of a sweep plan (a base scene and axes of values), one database per "
      "run; --list prints the manifest, --index N (or SLURM_ARRAY_TASK_ID) runs one line, --mpi "
      "runs them under mpirun, --slurm writes a Slurm job array and merge job");
  cmd->add_option("plan", options->plan_path, "Sweep plan (TOML)")->required();
  CLI::Option* list =
      cmd->add_flag("--list", options->list, "Print the manifest: run id and values per line");
  CLI::Option* index = cmd->add_option("--index", options->index, "Run line N only (0-based)")
                           ->check(IntegerIn(0, kMaxSweepLines - 1));
  cmd->add_option("--out-dir", options->out_dir,
                  "Folder of the runs' databases (default: the plan's out_dir)");
  CLI::Option* threads =
      cmd->add_option("--threads", options->threads,
                      "Each run's worker threads (0: all cores; default: all, 1 with --mpi)")
          ->check(IntegerIn(0, 256));
  CLI::Option* merge = cmd->add_flag(
      "--merge", options->merge,
      "Run nothing: merge every line's run (all complete) into the study database --db");
  cmd->add_option("--db", options->db,
                  "The merged study database of --merge, --mpi and --slurm (default: the runs' "
                  "folder with .sqlite)");
  CLI::Option* with_mpi = cmd->add_flag(
      "--mpi", options->mpi,
      "Under mpirun: rank 0 hands out the lines, largest expected cost first, and merges");
  CLI::Option* slurm =
      cmd->add_flag("--slurm", options->slurm,
                    "Write a Slurm job array (sweep.sbatch), its merge job (merge.sbatch) and "
                    "submit.sh into the runs' folder; run nothing");
  SlurmResources& r = options->slurm_resources;
  cmd->add_option("--cpus-per-task", r.cpus_per_task,
                  "--slurm: CPUs of each array task, and its run's threads (default 1)")
      ->check(IntegerIn(1, 256))
      ->needs(slurm);
  cmd->add_option("--time", r.time, "--slurm: time limit of each task (default 01:00:00)")
      ->needs(slurm);
  cmd->add_option("--mem", r.mem, "--slurm: memory of each task (default 2G)")->needs(slurm);
  cmd->add_option("--partition", r.partition, "--slurm: the partition (default: Slurm's)")
      ->needs(slurm);
  CLI::Option* max_array = cmd->add_option(
      "--max-array-size", r.max_array_size,
      "--slurm: the cluster's MaxArraySize (default 1001); a plan of more lines is submitted in "
      "slices of this many tasks (--merge: how to resubmit a line of a slice)");
  list->excludes(index, merge, with_mpi, slurm);
  index->excludes(merge, with_mpi, slurm);
  merge->excludes(with_mpi, slurm);
  with_mpi->excludes(slurm);
  threads->excludes(merge, slurm);
  cmd->callback([options, mpi, max_array]() {
    if (max_array->count() > 0 && !options->slurm && !options->merge) {
      throw InputError(fmt::format(
          "--max-array-size {}: the Slurm array size of --slurm (or of --merge's resubmit hint); "
          "expected --slurm or --merge",
          options->slurm_resources.max_array_size));
    }
    RunSweepCommand(*options, mpi);
  });
}

void RunSweepCommand(const SweepCommandOptions& options, SweepMpiRunner mpi) {
  SweepPlan plan = LoadSweepPlan(options.plan_path);
  if (options.out_dir) plan.out_dir = *options.out_dir;
  const int lines = static_cast<int>(plan.lines.size());
  if (options.db && !options.merge && !options.mpi && !options.slurm) {
    throw InputError(fmt::format(
        "--db {}: the merged study database of --merge, --mpi or --slurm; expected one of them "
        "(a line's own database is OUT_DIR/ID.sqlite)",
        *options.db));
  }
  if (options.merge) {
    MergeSweepRuns(plan, SweepStudyPath(plan, options), options.slurm_resources.max_array_size);
    return;
  }
  if (options.slurm) {
    ValidateSlurmResources(options.slurm_resources);
    for (const SweepLine& line : plan.lines) SweepLineScene(plan, line);  // every value checked
    WriteSlurm(plan, options);
    return;
  }
  if (options.mpi) {
    if (mpi == nullptr) {
      throw InputError(
          "--mpi: this railwear was built without MPI; expected a build with Open "
          "MPI (libopenmpi-dev)");
    }
    // Every line's scene is read (and checked) by every rank before MPI starts: a bad value
    // stops all of them with exit 2, before anything runs.
    std::vector<double> costs;
    for (const SweepLine& line : plan.lines)
      costs.push_back(SweepLineCost(SweepLineScene(plan, line)));
    std::vector<int> order(plan.lines.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&costs](int a, int b) { return costs[a] > costs[b]; });
    mpi(plan, order, costs, SweepStudyPath(plan, options), options);
    return;
  }
  if (options.list) {
    for (const SweepLine& line : plan.lines) SweepLineScene(plan, line);  // every value checked
    for (const SweepLine& line : plan.lines) {
      std::cout << fmt::format("{}  {}\n", line.id,
                               line.overrides.empty() ? "(base scene)" : line.Differences());
    }
    std::cerr << fmt::format("railwear: {} run(s) in {}; databases in {}\n", lines,
                             options.plan_path, plan.out_dir);
    if (plan.ensemble) {
      std::cerr << fmt::format(
          "railwear: an ensemble of {} sample(s) per curve class ({}, seed {}) of {}\n",
          plan.ensemble->samples, ToString(plan.ensemble->method), plan.ensemble->seed,
          fmt::join(plan.ensemble->keys, ", "));
    }
    return;
  }
  if (const std::optional<int> index = LineToRun(options, lines)) {
    RunSweepLine(plan, plan.lines[*index], options);
    return;
  }
  for (const SweepLine& line : plan.lines) SweepLineScene(plan, line);  // all before the first
  std::vector<std::string> failed;
  for (const SweepLine& line : plan.lines) {
    try {
      RunSweepLine(plan, line, options);
    } catch (const Interrupted&) {
      throw;
    } catch (const InputError&) {
      throw;
    } catch (const InternalError&) {  // a bug ends the sweep (app/main.cpp), as the check did
      throw;
    } catch (const std::exception& e) {
      // A run that failed and says so in its database is a result: the sweep goes on.
      const std::optional<std::string> why = SweepLineFailure(plan, line);
      if (!why) throw;
      failed.push_back(FailedLineText(line, *why));
      std::cerr << fmt::format(
          "railwear: error: sweep {}; its run is recorded as failed, the "
          "sweep goes on\n",
          failed.back());
    }
  }
  if (!failed.empty()) {
    throw SomeRunsFailed(fmt::format(
        "sweep {}: {} of {} run(s) failed (recorded in their databases in {}), the other {} "
        "complete: {}; merge them all with `railwear sweep {} --merge` (the failed runs are "
        "named, not banded)",
        options.plan_path, failed.size(), lines, plan.out_dir, lines - failed.size(),
        fmt::join(failed, "; "), options.plan_path));
  }
  std::cerr << fmt::format(
      "railwear: sweep {}: {} run(s) done in {}; merge them into {} with `railwear sweep {} "
      "--merge`\n",
      options.plan_path, lines, plan.out_dir, SweepStudyPath(plan, options), options.plan_path);
}

}  // namespace railwear::app
