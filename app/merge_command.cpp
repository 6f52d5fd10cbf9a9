// `railwear merge`: study databases -> one study database, one transaction per input.
#include "app/merge_command.h"

#include <chrono>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"

namespace railwear::app {
namespace {

// InputError when `input` names the same file as `out` (merging a file into itself).
void RequireDistinct(const std::string& out, const std::string& input) {
  std::error_code ec;
  if (std::filesystem::equivalent(out, input, ec)) {
    throw InputError(fmt::format(
        "merge: input '{}' is the output '{}'; expected study databases other than the output",
        input, out));
  }
}

}  // namespace

void SetupMerge(CLI::App& app) {
  auto options = std::make_shared<MergeCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Copy the runs of study databases (e.g. a sweep's per-run files) into one study database, "
      "one transaction per input; runs already there with the same content are left alone");
  cmd->add_option("out", options->out, "The study database to merge into (created if missing)")
      ->required();
  cmd->add_option("inputs", options->inputs, "Study databases to merge from (only read)")
      ->required();
  cmd->callback([options]() { RunMergeCommand(*options); });
}

void RunMergeCommand(const MergeCommandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Every input is checked before the output is touched: a refused one stops the merge whole.
  for (const std::string& input : options.inputs) {
    RequireDistinct(options.out, input);
    ProfileStore::OpenReadOnly(input).MergeTableRoles();
  }
  ProfileStore out = ProfileStore::Open(options.out);
  MergeSummary total;
  for (const std::string& input : options.inputs) {
    const ProfileStore in = ProfileStore::OpenReadOnly(input);
    const MergeSummary s = out.MergeRunsFrom(in);
    std::cout << fmt::format("{}: {} run(s) copied, {} already in {} (same content), {} rows\n",
                             input, s.runs_copied, s.runs_identical, options.out, s.rows_copied);
    if (s.calibrations_left > 0) {
      std::cerr << fmt::format(
          "railwear: note: {} holds {} calibration(s); merge copies runs only (calibrations are "
          "read with `railwear history --db {} calibrations`)\n",
          input, s.calibrations_left, input);
    }
    total.runs_copied += s.runs_copied;
    total.runs_identical += s.runs_identical;
    total.rows_copied += s.rows_copied;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << fmt::format(
      "railwear: merged {} input(s) into {}: {} run(s) copied, {} already there, {} rows, "
      "{:.2f} s\n",
      options.inputs.size(), options.out, total.runs_copied, total.runs_identical,
      total.rows_copied, seconds);
}

}  // namespace railwear::app
