// `railwear fem-reference`: the outline. Config (fem_reference_config.h) -> FEM displacement
// and contact experiments (calibration/fem/) -> displacement-curve CSVs and contact result files,
// with the summaries and comparisons of fem_reference_output.h on stdout and progress on stderr.
#include "app/fem_reference_command.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/fem_contact_result.h"
#include "app/fem_reference_output.h"
#include "app/paths.h"
#include "app/toml_fields.h"
#include "calibration/curve_comparison.h"
#include "calibration/fem/ccx_deck.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

namespace fs = std::filesystem;

// Created empty; removed when the experiment succeeds unless kept. On failure it stays, so the
// logs an error message names can be read.
class WorkFolder {
 public:
  WorkFolder(const std::string& out_dir, const std::string& name, bool keep) : keep_(keep) {
    if (keep) {
      path_ = fs::path(out_dir) / (name + ".work");
      fs::remove_all(path_);
      fs::create_directories(path_);
    } else {
      std::string pattern =
          (fs::temp_directory_path() / ("railwear-fem-" + name + "-XXXXXX")).string();
      if (mkdtemp(pattern.data()) == nullptr) {
        throw std::runtime_error("cannot create a temporary directory " + pattern);
      }
      path_ = pattern;
    }
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  ~WorkFolder() {
    if (keep_ || std::uncaught_exceptions() > 0) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  bool keep_;
};

}  // namespace

void SetupFemReference(CLI::App& app) {
  auto options = std::make_shared<FemReferenceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fem-reference",
      "Build FEM reference data with gmsh + CalculiX: the seed paper's displacement experiment "
      "(displacement-curve CSVs) and conformal contact cases (contact result TOML files) that "
      "calibration reads");
  cmd->add_option("config", options->config, "Experiment config (TOML)")->required();
  cmd->add_option("--out-dir", options->out_dir,
                  "Write the CSVs here (created) instead of next to the config");
  cmd->add_flag("--keep-work", options->keep_work,
                "Keep each experiment's .geo, .msh, .inp, .frd and logs in OUT/NAME.work");
  cmd->add_option("--only", options->only, "Run only this experiment (repeatable)");
  cmd->add_option("--jobs", options->jobs, "ccx solves at once (default: [fem] jobs, else 2)")
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--report-only", options->report_only,
                "Run nothing: print the comparisons of the CSVs an earlier run wrote");
  cmd->callback([options]() { RunFemReference(*options); });
}

namespace {

// The curves of an experiment that is not run now: its output file, which must exist.
DisplacementCurves ReadOutput(const FemReferenceConfig& config, const FemExperiment& e,
                              const std::string& why) {
  std::error_code ec;
  if (!fs::exists(e.output, ec)) {
    throw InputError(
        fmt::format("{}:{}: experiment '{}': {} its output {}, which does not exist; "
                    "run that experiment first",
                    config.path, e.line, e.name, why, e.output));
  }
  return ReadDisplacementCurves(e.output);
}

// The comparisons of one experiment's curves: with the half-space (for a flat body the
// validation, for a curved one how far curvature and size take it from flat), and with the
// compare_with experiment (from `done`, or read from its file).
std::string ComparisonsText(const FemReferenceConfig& config, const FemExperiment& e,
                            const DisplacementCurves& curves,
                            std::map<std::string, DisplacementCurves>* done) {
  std::string text =
      FemComparisonText(e, curves, HalfSpaceReference(e.options.material),
                        "half-space (Boussinesq normal, Cerruti tangential)", "halfspace");
  if (e.compare_with.empty()) return text;
  if (done->count(e.compare_with) == 0) {
    const auto other =
        std::find_if(config.experiments.begin(), config.experiments.end(),
                     [&](const FemExperiment& x) { return x.name == e.compare_with; });
    (*done)[e.compare_with] = ReadOutput(config, *other, "compare_with reads");
  }
  return text + FemComparisonText(e, curves, CurvesReference(done->at(e.compare_with)),
                                  fmt::format("against '{}'", e.compare_with), "other");
}

}  // namespace

void RunFemReference(const FemReferenceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!options.out_dir.empty()) fs::create_directories(options.out_dir);
  FemReferenceConfig config = ReadFemReferenceConfig(options.config, options.out_dir);
  for (const std::string& name : options.only) {
    const bool known = std::any_of(config.experiments.begin(), config.experiments.end(),
                                   [&](const FemExperiment& e) { return e.name == name; });
    if (!known) {
      std::vector<std::string_view> names;
      for (const FemExperiment& e : config.experiments) names.push_back(e.name);
      throw InputError(fmt::format("--only {}: no such experiment in {}; expected one of {}", name,
                                   options.config, JoinQuoted(names)));
    }
  }
  auto selected = [&](const FemExperiment& e) {
    return options.only.empty() ||
           std::find(options.only.begin(), options.only.end(), e.name) != options.only.end();
  };
  std::map<std::string, DisplacementCurves> done;
  if (options.report_only) {  // the tables of an earlier run, from its files
    for (const FemExperiment& e : config.experiments) {
      if (!selected(e)) continue;
      if (e.kind == FemExperimentKind::kContact) {
        const FemContactTarget t = ReadFemContactTarget(e.output);
        std::cout << FemContactTargetText(e, t);
        continue;
      }
      const DisplacementCurves curves = ReadOutput(config, e, "--report-only reads");
      std::cout << fmt::format("{}: {} points read from {}\n", e.name, curves.points.size(),
                               e.output)
                << ComparisonsText(config, e, curves, &done) << std::flush;
      done[e.name] = curves;
    }
    return;
  }
  FemPrograms programs;
  {
    ScopedTempDir probe("railwear-fem-probe");
    programs = FindFemPrograms(probe.path().string());
  }
  std::cerr << fmt::format("fem-reference: gmsh {} ({}), CalculiX {} ({})\n", programs.gmsh_version,
                           programs.gmsh, programs.ccx_version, programs.ccx);
  const std::string out_dir =
      options.out_dir.empty() ? DirectoryOf(options.config) : options.out_dir;
  int run = 0;
  for (FemExperiment& e : config.experiments) {
    if (!selected(e)) continue;
    if (options.jobs > 0) e.options.jobs = options.jobs;
    WorkFolder work(out_dir, e.name, options.keep_work);
    e.options.work_dir = work.path().string();
    const std::string name = e.name;
    e.options.progress = [name](std::string_view message) {
      std::cerr << fmt::format("fem-reference: {}: {}\n", name, message);
    };
    if (e.kind == FemExperimentKind::kContact) {
      e.contact.work_dir = work.path().string();
      e.contact.progress = e.options.progress;
      const FemContactOptions resolved = ResolvedFemContactOptions(e.contact);
      for (const double h : resolved.mesh_sizes_m) {
        e.options.progress(fmt::format("mesh level {:g} mm: about {:.3g} nodes (estimate)", h * 1e3,
                                       EstimateFemContactNodes(resolved, h)));
      }
      const FemContactResult r = RunFemContact(e.contact, programs);
      const fs::path folder = fs::absolute(e.output).parent_path();
      const std::string scene =
          e.scene.empty()
              ? ""
              : fs::absolute(e.scene).lexically_normal().lexically_relative(folder).string();
      fs::create_directories(folder);
      WriteWorkFile(e.output,
                    FemContactResultText(
                        e.name, r, scene,
                        {{"generated_by", fmt::format("railwear {} fem-reference {}, experiment {}",
                                                      RAILWEAR_VERSION, options.config, e.name)},
                         {"gmsh_version", programs.gmsh_version},
                         {"ccx_version", programs.ccx_version}}));
      std::cout << FemContactSummaryText(e, r) << std::flush;
      ++run;
      continue;
    }
    e.options.progress(fmt::format("mesh: about {:.3g} nodes (estimate)",
                                   EstimateFemDisplacementNodes(e.options)));
    FemDisplacementResult r = RunFemDisplacement(e.options, programs);
    r.curves.metadata.insert(
        r.curves.metadata.begin(),
        {"generated_by", fmt::format("railwear {} fem-reference {}, experiment {}",
                                     RAILWEAR_VERSION, options.config, e.name)});
    const fs::path parent = fs::path(e.output).parent_path();
    if (!parent.empty()) fs::create_directories(parent);
    WriteDisplacementCurves(r.curves, e.output);
    const int jobs = std::min(e.options.jobs, static_cast<int>(e.options.loads.size()));
    std::cout << FemDisplacementSummaryText(e, r, jobs)
              << ComparisonsText(config, e, r.curves, &done) << std::flush;
    done[e.name] = r.curves;
    ++run;
  }
  std::cout << fmt::format(
      "fem-reference: {} experiment(s) in {:.1f} s\n", run,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace railwear::app
