// `railwear sweep`: a plan's manifest, and its lines run as wear studies, one database each.
#include "app/sweep_command.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/scene.h"
#include "app/sweep_plan.h"
#include "app/toml_fields.h"
#include "app/wear_command.h"
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

// Runs one line: skipped when its run is complete, continued when started, else started.
void RunLine(const SweepPlan& plan, const SweepLine& line, const SweepCommandOptions& options) {
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

}  // namespace

void SetupSweep(CLI::App& app) {
  auto options = std::make_shared<SweepCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Run the wear studies of a sweep plan (a base scene and axes of values), one database per "
      "run; --list prints the manifest, --index N (or SLURM_ARRAY_TASK_ID) runs one line");
  cmd->add_option("plan", options->plan_path, "Sweep plan (TOML)")->required();
  cmd->add_flag("--list", options->list, "Print the manifest: run id and values per line");
  cmd->add_option("--index", options->index, "Run line N only (0-based)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out-dir", options->out_dir,
                  "Folder of the runs' databases (default: the plan's out_dir)");
  cmd->add_option("--threads", options->threads, "Each run's worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([options]() { RunSweepCommand(*options); });
}

void RunSweepCommand(const SweepCommandOptions& options) {
  SweepPlan plan = LoadSweepPlan(options.plan_path);
  if (options.out_dir) plan.out_dir = *options.out_dir;
  const int lines = static_cast<int>(plan.lines.size());
  if (options.list) {
    for (const SweepLine& line : plan.lines) SweepLineScene(plan, line);  // every value checked
    for (const SweepLine& line : plan.lines) {
      std::cout << fmt::format("{}  {}\n", line.id,
                               line.overrides.empty() ? "(base scene)" : line.Differences());
    }
    std::cerr << fmt::format("railwear: {} run(s) in {}; databases in {}\n", lines,
                             options.plan_path, plan.out_dir);
    return;
  }
  if (const std::optional<int> index = LineToRun(options, lines)) {
    RunLine(plan, plan.lines[*index], options);
    return;
  }
  for (const SweepLine& line : plan.lines) SweepLineScene(plan, line);  // all before the first
  for (const SweepLine& line : plan.lines) RunLine(plan, line, options);
  std::cerr << fmt::format(
      "railwear: sweep {}: {} run(s) done in {}; merge them with `railwear "
      "merge STUDY.sqlite {}/*.sqlite`\n",
      options.plan_path, lines, plan.out_dir, plan.out_dir);
}

}  // namespace railwear::app
