// The normal-solve stage of SolveContact: the normal problem over all patch grids solved, and
// the solution's patches (those with cells in contact) turned into PatchResults. Internal to
// SolveContact.
#pragma once

#include <optional>
#include <vector>

#include "core/contact/contact_result.h"
#include "core/contact/normal_solver.h"
#include "core/contact/patch_results.h"
#include "core/contact/potential_area.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// SolveNormal (from `start` when given, SolveNormal's), timed as the stage "solve".
NormalSolution SolveNormalStage(const NormalProblem& np, const NormalSolverOptions& options,
                                std::vector<StageTime>* stages,
                                const Eigen::VectorXd* start = nullptr);

// Which grid of the attempt each patch of the result came from, and where its cells start in
// the NormalProblem's vectors.
struct KeptPatches {
  std::vector<int> build;
  std::vector<int> offset;
};

// Appends to result->patches one PatchResult per grid with cells in contact (its grid moved out
// of *builds), labelled with its model (and, with auto_model, the reason).
// pressure_limit_Pa: the NormalProblem's (plastic cells are counted against it); area: when
// the patches' sub-cell areas are computed (NumericalPatch).
KeptPatches CollectPatches(const WheelRailGeometry& geom, PatchBuilds* builds,
                           const NormalSolution& sol, bool auto_model,
                           std::optional<double> pressure_limit_Pa, ContactResult* result,
                           PatchArea area = PatchArea::kNow);

}  // namespace railwear::internal
