// The operator stage of SolveContact: one influence operator per patch grid (the patch's model
// and the bodies' curvature signs) and the NormalProblem over all patches. Internal to
// SolveContact.
#pragma once

#include <memory>
#include <vector>

#include "core/contact/contact_problem.h"
#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"
#include "core/contact/potential_area.h"

namespace railwear::internal {

// The operators and the problem that points at them (np.blocks[k] == ops[k].get()).
struct NormalAssembly {
  std::vector<std::shared_ptr<const InfluenceOperator>> ops;
  NormalProblem np;
};

// The grids' operators and the normal problem: per cell the gap, the approach weight (the
// normal's vertical component) and the cell area, patch after patch; problem's load.
// kept (optional): a warm start's kept grids; a build that reuses one (builds.kept) takes its
// operator instead of making it again (the same grid and settings: the same operator).
NormalAssembly AssembleNormalProblem(const PatchBuilds& builds, const ContactProblem& problem,
                                     const std::vector<KeptGrid>* kept = nullptr);

}  // namespace railwear::internal
