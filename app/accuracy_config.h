// Options of `railwear accuracy` and their typed form: the model and level names the command
// takes, their validation (InputError naming the option, the value and what was expected), and
// the contact model each name stands for. No TOML: the command reads the scene with LoadScene.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/contact/contact_solver.h"
#include "core/contact/tangential_method.h"
#include "core/numerics/enum_names.h"

namespace railwear::app {

// The model names the command takes (--models, --reference-model).
inline const std::vector<std::string> kAccuracyModels = {
    "hertz", "halfspace", "conformal+boussinesq", "conformal+golubenko", "auto"};
// The accuracy presets, coarse to fine, from their name table (core/contact/contact_types.h).
inline const std::vector<std::string> kAccuracyLevels = EnumChoiceStrings(kAccuracyPresetNames);

struct AccuracyOptions {
  std::string scene_path;
  // Models to compare, names of kAccuracyModels ("conformal" = "conformal+golubenko"); the
  // reference model is run in any case.
  std::vector<std::string> models = kAccuracyModels;
  std::vector<std::string> levels = kAccuracyLevels;  // accuracy presets (Hertz has none)
  int repeats = 3;                       // solves per run; the time is their median (>= 1)
  std::optional<std::string> out_dir;    // --out DIR: accuracy.csv, accuracy.png
  bool plot = true;                      // --no-plot: no accuracy.png (then no gnuplot needed)
  std::optional<std::string> reference;  // --reference FILE: JSON as `contact --json` writes
  std::string reference_model = "conformal+boussinesq";
  // Wear scenes only (wear_accuracy.h): step limits [mm], a shorter total [MGT], threads.
  // levels_given: --levels was on the command line (a wear study's default omits "fine").
  bool levels_given = false;
  bool contact_options_given = false;  // --models, --reference, --reference-model or --tangential
  std::optional<std::vector<double>> step_limits_mm;
  std::optional<double> total_mgt;
  int threads = 0;
  // Vehicle scenes (curving_accuracy.h): the steady-state curving of each vehicle entry at each
  // level instead of the wear study.
  bool curving = false;
  // Rolling contact scenes: the tangential methods to compare (names of kTangentialMethodNames);
  // empty: the scene's own. With more than one, each model and level runs with each method,
  // the creep-force reference is the exact solver's, and every row reports its creep-force
  // error against the exact solver on the same model and level.
  std::vector<std::string> tangential;
};

// The validated contact study: canonical model names without repeats in the order given,
// levels coarse to fine (kAccuracyLevels order, whatever order they were given in), the
// canonical reference model.
struct AccuracyPlan {
  std::vector<std::string> models;
  std::vector<std::string> levels;
  std::string reference_model;
  // The tangential methods in the order given, without repeats; empty: the scene's own.
  std::vector<TangentialMethod> tangential;
};

// Checks repeats, models, levels, the reference model and the tangential methods, in that order.
// Throws InputError for repeats < 1, an unknown model, level or tangential method, or an empty
// list.
AccuracyPlan MakeAccuracyPlan(const AccuracyOptions& options);

// Accuracy presets from their names (any order, repeats dropped), coarse to fine. Throws
// InputError naming --levels for an unknown name or an empty list.
std::vector<AccuracyPreset> ParseAccuracyLevels(const std::vector<std::string>& names);

// The contact model a name of kAccuracyModels stands for; the scene's influence constants
// (`scene_model.constants`) stay.
ModelOptions AccuracyModelOptions(const std::string& model, const ModelOptions& scene_model);

}  // namespace railwear::app
