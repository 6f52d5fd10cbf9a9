// `railwear contact`: scene -> SolveContact -> summary, JSON, CSV, plot.
#include "app/contact_command.h"

#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/contact_output.h"
#include "app/pressure_plot.h"
#include "app/scene.h"
#include "core/contact/contact_case.h"
#include "core/numerics/enum_names.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

// --model replaces kind, geometry and kernel; constants, accuracy and cell size stay. --kernel
// then replaces the kernel (the kind becomes the shorthand that matches, else custom).
void ApplyOverrides(const ContactOptions& o, ModelOptions* model) {
  if (o.model) {
    ModelOptions replaced = MakeModelOptions(*ModelKindFromString(*o.model));
    replaced.constants = model->constants;
    replaced.accuracy = model->accuracy;
    replaced.cell_dx_m = model->cell_dx_m;
    replaced.cell_ds_m = model->cell_ds_m;
    *model = replaced;
  }
  if (o.kernel) {
    if (model->kind == ModelKind::kHertz) {
      throw InputError(fmt::format(
          "--kernel {}: expected a model with an influence kernel (halfspace, conformal, auto); "
          "hertz is analytic",
          *o.kernel));
    }
    model->kernel = *KernelModelFromString(*o.kernel);
    if (model->kind != ModelKind::kAuto) {  // auto keeps picking the geometry per patch
      model->kind = MatchingModelKind(model->geometry, model->kernel);
    }
  }
  if (o.constants) {
    model->constants = NamedInfluenceConstants(*InfluenceConstantsNameFromString(*o.constants));
  }
  if (o.accuracy) {
    model->accuracy = *AccuracyPresetFromString(*o.accuracy);
    model->cell_dx_m.reset();  // the command line wins over the scene's cell_mm
    model->cell_ds_m.reset();
  }
}

// Writes `text` to FILE, or to stdout for "-".
void WriteOutput(const std::string& path, const std::string& text, const std::string& what) {
  if (path == "-") {
    std::cout << text << std::flush;
    return;
  }
  std::ofstream out(path);
  out << text;
  if (!out) throw InputError(fmt::format("{}: cannot write the {}", path, what));
}

void CheckOptions(const ContactOptions& o) {
  if (o.json == "-" && o.csv == "-") {
    throw InputError("--json - and --csv - both want stdout; give one of them a file name");
  }
  if (o.plot) RequireGnuplot();  // before the solve, so nobody waits for nothing
}

// The warnings on stderr (they are also in the summary and the JSON's "warnings").
void Warn(const Scene& scene, const ContactResult& r, const std::string& wheel) {
  for (const std::string& w : ContactWarnings(scene, r, wheel)) {
    std::cerr << "warning: " << w << "\n";
  }
}

// A wheelset on a track: both wheels, each in its rail's own frame.
void RunWheelset(const ContactOptions& o, const Scene& scene) {
  const ContactCase problem = ToContactCase(scene);
  const WheelsetResult result = *SolveContactCase(problem).wheelset;
  if (o.json) WriteOutput(*o.json, MakeWheelsetJson(scene, result).dump(2) + "\n", "JSON");
  if (o.csv) {
    std::ostringstream csv;
    WritePressureCsv(result.right, csv, "right");
    WritePressureCsv(result.left, csv, "left", /*header=*/false);
    WriteOutput(*o.csv, csv.str(), "CSV");
  }
  if (o.json != "-" && o.csv != "-")
    std::cout << FormatWheelsetSummary(scene, result) << std::flush;
  Warn(scene, result.right, "right wheel");
  Warn(scene, result.left, "left wheel");
  if (o.plot) {  // a row per wheel, each in its own rail's frame
    const Profile& wheel = problem.problem.wheel_profile;
    const Profile& rail = problem.problem.rail_profile;
    PlotContact(scene,
                {{"right wheel", &result.right, result.placement.right, &wheel, &rail},
                 {"left wheel", &result.left, result.placement.left, &wheel,
                  problem.wheelset->left_rail_profile ? &*problem.wheelset->left_rail_profile
                                                      : &rail}},
                *o.plot);
  }
  for (const ContactResult* r : {&result.right, &result.left}) {
    if (r->status != SolverStatus::kConverged) {
      throw std::runtime_error(
          fmt::format("contact solve of the {} wheel ended with status '{}': {}",
                      r == &result.right ? "right" : "left", ToString(r->status), r->message));
    }
  }
}

}  // namespace

ContactCase ToContactCase(const Scene& scene) {
  ContactCase c;
  c.problem = scene.problem;
  if (scene.wheelset) {
    c.wheelset.emplace();
    c.wheelset->track = *scene.track;
    c.wheelset->wheelset = *scene.wheelset;
  }
  c.friction = scene.friction;
  return c;
}

void SetupContact(CLI::App& app) {
  auto options = std::make_shared<ContactOptions>();
  CLI::App* sub = app.add_subcommand(
      "contact",
      "Contact of a wheel on its rail (or a wheelset on a track): normal, rolling, damage");
  sub->add_option("scene", options->scene_path, "Scene file (TOML); see `railwear init`")
      ->required();
  sub->add_option("--model", options->model, "Replace the scene's model kind")
      ->check(CLI::IsMember(EnumChoiceStrings(kModelKindNames)));
  sub->add_option("--accuracy", options->accuracy, "Replace the scene's accuracy (and its cell_mm)")
      ->check(CLI::IsMember(EnumChoiceStrings(kAccuracyPresetNames)));
  sub->add_option("--kernel", options->kernel,
                  "Replace the influence kernel (after --model), keeping the geometry")
      ->check(CLI::IsMember(EnumChoiceStrings(kKernelModelNames)));
  sub->add_option("--constants", options->constants,
                  "Replace the scene's influence constants by a named set (fem: FEM-calibrated, "
                  "the default; paper: the seed's)")
      ->check(CLI::IsMember(EnumChoiceStrings(kInfluenceConstantsNames)));
  sub->add_option("--json", options->json, "Write the result as JSON to FILE ('-' = stdout)");
  sub->add_option("--csv", options->csv, "Write the pressure field as CSV to FILE ('-' = stdout)");
  sub->add_option("--plot", options->plot, "Draw the pressure map to PNG (needs gnuplot)");
  sub->callback([options]() { RunContact(*options); });
}

void RunContact(const ContactOptions& o) {
  CheckOptions(o);
  Scene scene = LoadScene(o.scene_path);
  if (scene.wear) {
    throw InputError(fmt::format(
        "{}: a wear scene (effect \"wear\", [[traffic]]): expected a single contact ([load] or "
        "[wheelset]); run it with `railwear wear {}`",
        o.scene_path, o.scene_path));
  }
  ApplyOverrides(o, &scene.problem.model);
  if (scene.wheelset) {
    RunWheelset(o, scene);
    return;
  }
  const ContactResult result = SolveContactCase(ToContactCase(scene)).wheel;

  if (o.json) WriteOutput(*o.json, MakeContactJson(scene, result).dump(2) + "\n", "JSON");
  if (o.csv) {
    std::ostringstream csv;
    WritePressureCsv(result, csv);
    WriteOutput(*o.csv, csv.str(), "CSV");
  }
  if (o.json != "-" && o.csv != "-") std::cout << FormatSummary(scene, result) << std::flush;
  Warn(scene, result, "");
  if (o.plot) {
    const WheelPlacement& pl = scene.problem.placement;
    PlotContact(scene,
                {{"wheel", &result,
                  WheelPose{pl.lateral_shift_m, pl.roll_rad, pl.rolling_radius_m, pl.yaw_rad},
                  &scene.problem.wheel_profile, &scene.problem.rail_profile}},
                *o.plot);
  }

  if (result.status != SolverStatus::kConverged) {
    throw std::runtime_error(fmt::format("contact solve ended with status '{}': {}",
                                         ToString(result.status), result.message));
  }
}

}  // namespace railwear::app
