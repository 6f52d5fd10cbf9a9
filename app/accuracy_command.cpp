// `railwear accuracy`: the command line and the outline of a run (the study of
// accuracy_study.h or, for a wear scene, of wear_accuracy.h; then the table, CSV and plot).
#include "app/accuracy_command.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/cli_checks.h"
#include "app/curving_accuracy.h"
#include "app/gnuplot.h"
#include "app/wear_accuracy.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace fs = std::filesystem;

void SetupAccuracy(CLI::App& app) {
  auto options = std::make_shared<AccuracyOptions>();
  auto no_plot = std::make_shared<bool>(false);
  CLI::App* sub =
      app.add_subcommand("accuracy",
                         "What accuracy costs in time: each model at each accuracy level, time, "
                         "memory and errors against a reference (table, CSV, Pareto plot)");
  sub->add_option("scene", options->scene_path, "Scene file (TOML), one wheel on one rail")
      ->required();
  CLI::Option* models =
      sub->add_option("--models", options->models,
                      "Models, comma-separated: hertz, halfspace, conformal+boussinesq, "
                      "conformal+golubenko (or conformal), auto (default: all)")
          ->delimiter(',');
  CLI::Option* levels =
      sub->add_option("--levels", options->levels,
                      "Accuracy levels, comma-separated: draft, standard, reference, fine "
                      "(default: all; a wear scene: draft, standard, reference)")
          ->delimiter(',');
  sub->add_option("--repeats", options->repeats, "Solves per run; the time is their median")
      ->check(IntegerIn(1, 1000));
  sub->add_option("--out", options->out_dir,
                  "Write DIR/accuracy.csv and the Pareto plot DIR/accuracy.png");
  sub->add_flag("--no-plot", *no_plot, "With --out: no plot (gnuplot not needed)");
  CLI::Option* reference =
      sub->add_option("--reference", options->reference,
                      "Compare against this JSON (as `railwear contact --json` writes it; any of "
                      "total.area_mm2, p_max_MPa, vertical_force_N + lateral_force_N)");
  CLI::Option* reference_model =
      sub->add_option("--reference-model", options->reference_model,
                      "Model whose finest (extrapolated) solution is the reference "
                      "(default conformal+boussinesq)");
  sub->add_option("--step-limits", options->step_limits_mm,
                  "Wear scenes: step limits (max_depth_per_step) in mm, comma-separated "
                  "(default 0.2,0.1,0.05)")
      ->delimiter(',')
      ->check(NumberIn(0.001, 1.0));  // as [wear] max_depth_per_step_mm
  sub->add_option("--mgt", options->total_mgt,
                  "Wear scenes: run every study to this many MGT instead of the scene's total")
      ->check(NumberIn(1e-6, 1e4));  // as [wear] total_MGT
  sub->add_option("--threads", options->threads, "Wear scenes: load-case workers (0: the scene's)")
      ->check(IntegerIn(0, 256));  // as [wear] threads
  CLI::Option* tangential =
      sub->add_option("--tangential", options->tangential,
                      "Rolling scenes: tangential methods to compare, comma-separated: fastsim, "
                      "exact, auto (default: the scene's); adds each method's creep-force error "
                      "against the exact solver on the same model and level")
          ->delimiter(',');
  sub->add_flag("--curving", options->curving,
                "Vehicle scenes: the steady-state curving of each vehicle entry at each level "
                "(time, solves, positions and flange force against the finest) instead of the "
                "wear study");
  sub->callback([options, no_plot, levels, models, reference, reference_model, tangential]() {
    options->plot = !*no_plot;
    options->levels_given = levels->count() > 0;
    options->contact_options_given =
        models->count() + reference->count() + reference_model->count() + tangential->count() > 0;
    RunAccuracy(*options);
  });
}

namespace {

fs::path CreateOutDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError(fmt::format("--out {}: cannot create the directory ({})", dir,
                                 ec ? ec.message() : "a file of that name exists"));
  }
  return fs::path(dir);
}

// The studies' progress lines, on stderr.
void Progress(const std::string& line) { std::cerr << "railwear accuracy: " << line << "\n"; }

// Writes DIR/NAME (DIR created) with `write` and says so on stderr.
void WriteCsv(const std::string& dir, const std::string& name,
              const std::function<void(std::ostream&)>& write) {
  const fs::path csv = CreateOutDir(dir) / name;
  {
    std::ofstream out(csv);
    write(out);
    if (!out) throw InputError(fmt::format("{}: cannot write the CSV", csv.string()));
  }
  std::cerr << "railwear accuracy: wrote " << csv.string() << "\n";
}

void RunCurvingAccuracy(const Scene& scene, const AccuracyOptions& o) {
  if (o.contact_options_given || o.step_limits_mm || o.total_mgt) {
    throw InputError(fmt::format(
        "{}: --curving takes --levels and --out; --models, --reference, --reference-model, "
        "--tangential, --step-limits and --mgt are for the other studies",
        scene.path));
  }
  const std::vector<std::string> levels =
      o.levels_given ? o.levels : std::vector<std::string>{"draft", "standard", "reference"};
  const CurvingAccuracyStudy study = RunCurvingAccuracyStudy(scene, levels, Progress);
  std::cout << FormatCurvingAccuracyTable(study) << std::flush;
  if (!o.out_dir) return;
  WriteCsv(*o.out_dir, "curving_accuracy.csv",
           [&](std::ostream& out) { WriteCurvingAccuracyCsv(study, out); });
}

void RunWearAccuracy(const Scene& scene, const AccuracyOptions& o) {
  if (o.contact_options_given) {
    throw InputError(
        fmt::format("{}: a wear scene runs with its own [model]; --models, --reference, "
                    "--reference-model and --tangential are for contact scenes",
                    o.scene_path));
  }
  WearAccuracyOptions w;
  if (o.levels_given) w.levels = o.levels;
  if (o.step_limits_mm) w.step_limits_mm = *o.step_limits_mm;
  w.total_mgt = o.total_mgt;
  w.threads = o.threads;
  const WearAccuracyStudy study = RunWearAccuracyStudy(scene, w, Progress);
  std::cout << FormatWearAccuracyTable(study) << std::flush;
  if (!o.out_dir) return;
  WriteCsv(*o.out_dir, "wear_accuracy.csv",
           [&](std::ostream& out) { WriteWearAccuracyCsv(study, out); });
  if (o.plot) {
    const fs::path png = fs::path(*o.out_dir) / "wear_accuracy.png";
    PlotWearAccuracy(study, png.string());
    std::cerr << "railwear accuracy: wrote " << png.string() << "\n";
  }
}

}  // namespace

void RunAccuracy(const AccuracyOptions& o) {
  // Before the runs, so nobody waits for nothing.
  if (o.out_dir && o.plot && !o.curving)
    RequireGnuplotFor("railwear accuracy's Pareto plot", "pass --no-plot");
  const Scene scene = LoadScene(o.scene_path);
  if (o.curving) {
    RunCurvingAccuracy(scene, o);
    return;
  }
  if (scene.wear) {
    RunWearAccuracy(scene, o);
    return;
  }
  if (o.step_limits_mm || o.total_mgt || o.threads > 0) {
    throw InputError(
        fmt::format("{}: --step-limits, --mgt and --threads are for wear scenes; "
                    "this scene has no wear study",
                    o.scene_path));
  }
  const AccuracyStudy study = RunAccuracyStudy(scene, o, Progress);
  std::cout << FormatAccuracyTable(study) << std::flush;
  if (!o.out_dir) return;
  WriteCsv(*o.out_dir, "accuracy.csv", [&](std::ostream& out) { WriteAccuracyCsv(study, out); });
  if (o.plot) {
    const fs::path png = fs::path(*o.out_dir) / "accuracy.png";
    PlotAccuracy(study, png.string());
    std::cerr << "railwear accuracy: wrote " << png.string() << "\n";
  }
}

}  // namespace railwear::app
