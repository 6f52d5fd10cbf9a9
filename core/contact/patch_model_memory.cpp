// The model of each patch during SolveContact's re-grid loop (patch_model_memory.h).
#include "core/contact/patch_model_memory.h"

#include <algorithm>

#include "core/numerics/check.h"

namespace railwear::internal {

PatchModelMemory::PatchModelMemory(const WheelRailGeometry& geom, const ContactProblem& problem,
                                   double estar, double stiffness_ratio_K,
                                   const FirstContactEstimate& first)
    : geom_(geom),
      problem_(problem),
      estar_(estar),
      stiffness_ratio_K_(stiffness_ratio_K),
      auto_model_(problem.model.kind == ModelKind::kAuto),
      first_(first),
      at_approach_(first.at_delta),
      at_approach_delta_(first.delta) {
  fixed_choice_.geometry = problem.model.geometry;
  fixed_choice_.kernel = problem.model.kernel;
  fixed_choice_.label = PatchModelLabel(problem.model);
}

std::vector<PatchModelMemory::ChoiceMemory> PatchModelMemory::Verdicts(
    const std::vector<ContactCandidate>& cands, const std::vector<HertzSolution>& hertz,
    double delta, const std::vector<ContactCandidate>& at_delta) const {
  std::vector<ChoiceMemory> out;
  for (size_t k = 0; k < cands.size(); ++k) {
    if (hertz[k].force_N <= 0) continue;
    const ContactCandidate& c = cands[k];
    // The larger estimate of the patch: Hertz gets no check on a solved patch.
    const double b = EstimateSemiAxisS(geom_, c, estar_, delta, at_delta).hi;
    out.push_back({c.y_lo_m, c.y_hi_m,
                   ChoosePatchModel(MeasureConformity(geom_, c, -b, b, stiffness_ratio_K_),
                                    problem_.model, "")});
  }
  return out;
}

std::optional<ContactResult> PatchModelMemory::CheckHertz(ContactResult* result) {
  const auto t0 = Clock::now();
  auto all_hertz = [](const std::vector<ChoiceMemory>& v) {
    return !v.empty() && std::all_of(v.begin(), v.end(), [](const ChoiceMemory& m) {
      return m.choice.model == PatchModel::kHertz;
    });
  };
  hertz_verdicts_ = Verdicts(first_.first, first_.hs, first_.delta, first_.at_delta);
  if (!all_hertz(hertz_verdicts_)) {
    AddStage(&result->stages, "model selection", SecondsSince(t0));
    return std::nullopt;
  }
  const HertzSearch search = SearchHertz(geom_, problem_, estar_);
  hertz_verdicts_ =
      Verdicts(search.cands, search.hs, search.delta, geom_.FindCandidates(search.delta));
  AddStage(&result->stages, "model selection", SecondsSince(t0));
  if (!all_hertz(hertz_verdicts_)) return std::nullopt;
  if (const auto lim = PressureLimitOf(problem_.pressure_limit, problem_.wheel_material,
                                       problem_.rail_material)) {
    for (const HertzSolution& h : search.hs) {
      if (h.force_N > 0 && h.p0_Pa > *lim) hertz_above_limit_ = true;
    }
    if (hertz_above_limit_) return std::nullopt;
  }
  ContactResult r = SolveHertzModel(search, std::move(*result), Clock::now());
  RAILWEAR_CHECK(r.patches.size() == hertz_verdicts_.size());
  for (size_t k = 0; k < r.patches.size(); ++k) {
    r.patches[k].model_reason = hertz_verdicts_[k].choice.reason;
  }
  return r;
}

std::string PatchModelMemory::NoHertzReason(const ContactCandidate& c) const {
  if (problem_.rolling) return "rolling contact needs a grid";
  for (const auto& v : hertz_verdicts_) {
    if (c.y_m < v.y_lo_m || c.y_m > v.y_hi_m) continue;
    if (v.choice.model == PatchModel::kHertz) {
      if (hertz_above_limit_) {
        return "Hertz would do here, but its peak pressure passes the pressure limit (plastic "
               "cells need a grid)";
      }
      return "Hertz would do here, but another patch needs a grid";
    }
    if (v.choice.model == PatchModel::kConformal) {
      return "on the larger estimate of the patch the Hertz check found it conformal";
    }
    const std::string& r = v.choice.reason;
    const size_t at = r.find("not Hertz: ");
    return r.substr(at == std::string::npos ? 0 : at + 11) +
           " (on the larger estimate of the patch)";
  }
  return "the patch appeared after the Hertz check";
}

PatchModelChoice PatchModelMemory::ChooseFor(const ContactCandidate& c, double approach_now) {
  if (!auto_model_) return fixed_choice_;
  const ChoiceMemory* known = nullptr;
  for (const auto& m : choice_memory_) {
    if (c.y_m >= m.y_lo_m && c.y_m <= m.y_hi_m) known = &m;
  }
  if (known != nullptr) return known->choice;
  if (approach_now != at_approach_delta_) {
    at_approach_ = geom_.FindCandidates(approach_now);
    at_approach_delta_ = approach_now;
  }
  const double b = EstimateSemiAxisS(geom_, c, estar_, approach_now, at_approach_).lo;
  PatchModelChoice choice = ChoosePatchModel(MeasureConformity(geom_, c, -b, b, stiffness_ratio_K_),
                                             problem_.model, NoHertzReason(c));
  choice_memory_.push_back({c.y_lo_m, c.y_hi_m, choice});
  return choice;
}

bool PatchModelMemory::Recheck(const ContactCandidate& c, const Extent& e,
                               PatchModelChoice* choice) {
  constexpr double kTiny_m = 1e-9;  // keeps the measured stretch around the contact point
  PatchConformity post = MeasureConformity(geom_, c, std::min(e.s_lo, -kTiny_m),
                                           std::max(e.s_hi, kTiny_m), stiffness_ratio_K_);
  post.measured = true;
  const PatchModelChoice again = ChoosePatchModel(post, problem_.model, NoHertzReason(c));
  for (auto& m : choice_memory_) {
    if (c.y_m >= m.y_lo_m && c.y_m <= m.y_hi_m) m.choice = again;
  }
  *choice = again;
  return again.model == PatchModel::kConformal;
}

}  // namespace railwear::internal
