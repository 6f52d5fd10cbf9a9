// The load cases of a wear step under the adaptive spread rule (wear/spread_integration.h): the
// first nodes of every spread, solved, then rounds of bisections where the step's worn area per
// pass is not yet converged, each round's new cases solved together.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/profile/profile.h"
#include "wear/spread_integration.h"
#include "wear/traffic.h"
#include "wear/wear_simulation.h"

namespace railwear {

// Solves a batch of load cases (the caller keeps their outcomes, in the order given, after those
// of the batches before) and returns each one's worn area per pass [m^2]. In a refinement batch
// (`refinement`) a case whose contact does not converge is NaN instead of an exception: its node
// is left out (the interval it would have split is not bisected) and the case never reaches the
// step.
using SolveCaseBatch =
    std::function<std::vector<double>(const std::vector<LoadCase>& batch, bool refinement)>;

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
// integrated over every spread by the adaptive rule to `tolerance` (relative, > 0).
SpreadStep IntegrateSpreads(const WearStudy& study, const Profile& high_rail_track,
                            const std::optional<Profile>& low_rail_track,
                            const std::vector<CurvingStart>& curving_starts,
                            std::vector<CurvingStart>* curving_solved, double tolerance,
                            const SolveCaseBatch& solve);

}  // namespace railwear
