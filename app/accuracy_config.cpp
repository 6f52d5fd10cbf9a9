// `railwear accuracy`: option validation and the model each name stands for.
#include "app/accuracy_config.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

std::string CanonicalModel(const std::string& name) {
  return name == "conformal" ? "conformal+golubenko" : name;
}

void CheckName(const std::string& name, const std::vector<std::string>& valid,
               const std::string& what) {
  if (std::find(valid.begin(), valid.end(), name) == valid.end()) {
    throw InputError(
        fmt::format("{} '{}': expected one of {}", what, name, fmt::join(valid, ", ")));
  }
}

}  // namespace

std::vector<AccuracyPreset> ParseAccuracyLevels(const std::vector<std::string>& names) {
  std::vector<AccuracyPreset> presets;
  for (const auto& name : names) {
    const auto p = AccuracyPresetFromString(name);
    if (!p) {
      throw InputError(fmt::format("--levels: level '{}': expected one of {}", name,
                                   JoinEnumChoices(kAccuracyPresetNames)));
    }
    if (std::find(presets.begin(), presets.end(), *p) == presets.end()) presets.push_back(*p);
  }
  if (presets.empty()) throw InputError("--levels: expected at least one level");
  std::sort(presets.begin(), presets.end());  // enum order is coarse to fine
  return presets;
}

AccuracyPlan MakeAccuracyPlan(const AccuracyOptions& o) {
  if (o.repeats < 1) {
    throw InputError(fmt::format("--repeats {}: expected at least 1", o.repeats));
  }
  AccuracyPlan plan;
  for (const auto& m : o.models) {
    const std::string c = CanonicalModel(m);
    CheckName(c, kAccuracyModels, "--models: model");
    if (std::find(plan.models.begin(), plan.models.end(), c) == plan.models.end()) {
      plan.models.push_back(c);
    }
  }
  if (plan.models.empty()) throw InputError("--models: expected at least one model");
  for (const auto& l : kAccuracyLevels) {  // coarse to fine, whatever order they were given in
    for (const auto& given : o.levels) CheckName(given, kAccuracyLevels, "--levels: level");
    if (std::find(o.levels.begin(), o.levels.end(), l) != o.levels.end()) plan.levels.push_back(l);
  }
  if (plan.levels.empty()) throw InputError("--levels: expected at least one level");
  plan.reference_model = CanonicalModel(o.reference_model);
  CheckName(plan.reference_model, kAccuracyModels, "--reference-model: model");
  for (const auto& name : o.tangential) {
    const auto m = TangentialMethodFromString(name);
    if (!m) {
      throw InputError(fmt::format("--tangential: method '{}': expected one of {}", name,
                                   JoinEnumChoices(kTangentialMethodNames)));
    }
    if (std::find(plan.tangential.begin(), plan.tangential.end(), *m) == plan.tangential.end()) {
      plan.tangential.push_back(*m);
    }
  }
  return plan;
}

ModelOptions AccuracyModelOptions(const std::string& model, const ModelOptions& scene_model) {
  ModelOptions o;
  if (model == "hertz") {
    o = MakeModelOptions(ModelKind::kHertz);
  } else if (model == "halfspace") {
    o = MakeModelOptions(ModelKind::kHalfspace);
  } else if (model == "conformal+boussinesq") {
    o = MakeModelOptions(ModelKind::kConformal);
    o.kind = ModelKind::kCustom;
    o.kernel = KernelModel::kBoussinesq;
  } else if (model == "conformal+golubenko") {
    o = MakeModelOptions(ModelKind::kConformal);
  } else {
    o = MakeModelOptions(ModelKind::kAuto);
  }
  o.constants = scene_model.constants;
  return o;
}

}  // namespace railwear::app
