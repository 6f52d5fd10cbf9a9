// The load cases of a wear step under the adaptive spread rule (wear/spread_integration.h): the
// first nodes of every spread, solved, then rounds of bisections where the step's worn area per
// pass is not yet converged, each round's new cases solved together.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "core/profile/profile.h"
#include "wear/spread_integration.h"
#include "wear/traffic.h"
#include "wear/wear_simulation.h"

namespace railwear {

// A solved case: its worn area per pass [m^2] and its depth per pass on its rail's bins [m].
struct SolvedCase {
  double worn_area_per_pass_m2 = 0.0;
  std::vector<double> depth_per_pass_m;
};

// Solves a batch of load cases (the caller keeps their outcomes, in the order given, after those
// of the batches before) and returns each one's worn area per pass and depth field. In a
// refinement batch (`refinement`) a case whose contact does not converge has a NaN area instead
// of an exception: its node is left out (the interval it would have split is not bisected) and
// the case never reaches the step.
using SolveCaseBatch =
    std::function<std::vector<SolvedCase>(const std::vector<LoadCase>& batch, bool refinement)>;

// The rails' bins the depth fields are on, per rail ([0] high, [1] low): their count (0 for a
// rail the study does not have) and width [m].
struct SpreadRailBins {
  std::array<int, 2> count = {0, 0};
  std::array<double, 2> width_m = {0.0, 0.0};
};

// The adaptive rule's cases of a step.
struct SpreadStep {
  // Every case solved, in the order they were handed to `solve`, with their final weights
  // (each rail's sum to 1) and node numbers (failed refinement nodes' cases too: not in `order`).
  std::vector<LoadCase> cases;
  // The cases in StepLoadCases order (prescribed entries first, then the others in entry order;
  // within an entry by wheelset, node, rail): indices into `cases`.
  std::vector<int> order;
  SpreadIntegrationSummary summary;
};

// The step's cases on these rails (as internal::StepLoadCases: the track-frame rails, each
// vehicle entry's curving from `curving_starts`, its solution left in `curving_solved`),
// integrated over every spread by the adaptive rule to `tolerance` (relative, > 0), on the depth
// field of `bins` (SpreadUnit's depth-field criterion) unless `bins` is absent (the worn area
// alone, the rule before the criterion).
SpreadStep IntegrateSpreads(const WearStudy& study, const Profile& high_rail_track,
                            const std::optional<Profile>& low_rail_track,
                            const std::vector<CurvingStart>& curving_starts,
                            std::vector<CurvingStart>* curving_solved, double tolerance,
                            const SolveCaseBatch& solve,
                            const std::optional<SpreadRailBins>& bins = std::nullopt);

}  // namespace railwear
