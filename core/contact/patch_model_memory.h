// The model of each patch during SolveContact's re-grid loop. With a fixed model (not auto)
// every patch gets the scene's model. With kind = auto (model_selection.h) the choice per patch
// is made from the estimated patch when it first appears, found again by position (the
// candidate's interval) on later grids, checked again on each solution while it is planar (the
// estimate can miss a patch that spreads), and then only ever switched to the conformal
// geometry. Before any grid, CheckHertz decides whether every patch qualifies for Hertz (Hertz
// and grid patches are not mixed in one solve: they would need one common approach).
// Internal to SolveContact.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/hertz_estimate.h"
#include "core/contact/model_selection.h"
#include "core/contact/patch_results.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

class PatchModelMemory {
 public:
  // estar: contact modulus [Pa]; stiffness_ratio_K = k_rail / (k_wheel + k_rail) (seed eq. 1).
  // geom and problem must outlive the memory.
  PatchModelMemory(const WheelRailGeometry& geom, const ContactProblem& problem, double estar,
                   double stiffness_ratio_K, const FirstContactEstimate& first);

  bool is_auto() const { return auto_model_; }

  // kind = auto without rolling contact: the Hertz check, on the patches at the first contact
  // point first (the usual verdict, at no extra search), then on all Hertz's patches. When every
  // patch qualifies, the Hertz model's result (from *result, with each patch's reason);
  // otherwise std::nullopt and *result keeps its stage time. Adds the "model selection" stage.
  // With a pressure limit, a Hertz peak above it sends the case to the grid (plastic cells).
  std::optional<ContactResult> CheckHertz(ContactResult* result);

  // The model of candidate c's grid; approach_now [m] the best estimate of the approach so far.
  PatchModelChoice ChooseFor(const ContactCandidate& c, double approach_now);

  // kind = auto, a patch not yet conformal, on a converged solution whose contact has the
  // extent e: the choice checked again on the measured stretch (remembered and put in *choice).
  // Returns true when the patch switched to the conformal geometry.
  bool Recheck(const ContactCandidate& c, const Extent& e, PatchModelChoice* choice);

 private:
  // The auto model's choice per patch, found again by position (the candidate's interval).
  struct ChoiceMemory {
    double y_lo_m, y_hi_m;
    PatchModelChoice choice;
  };
  std::vector<ChoiceMemory> Verdicts(const std::vector<ContactCandidate>& cands,
                                     const std::vector<HertzSolution>& hertz, double delta,
                                     const std::vector<ContactCandidate>& at_delta) const;
  // Why a grid patch is not Hertz (Hertz and grid patches are not mixed in one solve).
  std::string NoHertzReason(const ContactCandidate& c) const;

  const WheelRailGeometry& geom_;
  const ContactProblem& problem_;
  double estar_;
  double stiffness_ratio_K_;
  bool auto_model_;
  const FirstContactEstimate& first_;
  PatchModelChoice fixed_choice_;             // the scene's model when it is not auto
  std::vector<ChoiceMemory> hertz_verdicts_;  // of the Hertz check, per Hertz patch
  // The Hertz check qualified every patch, but a Hertz peak passes the pressure limit.
  bool hertz_above_limit_ = false;
  std::vector<ChoiceMemory> choice_memory_;
  std::vector<ContactCandidate> at_approach_;  // FindCandidates(at_approach_delta_)
  double at_approach_delta_;
};

}  // namespace railwear::internal
