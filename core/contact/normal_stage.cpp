// The normal-solve stage of SolveContact (normal_stage.h).
#include "core/contact/normal_stage.h"

#include <utility>

#include "core/contact/patch_results.h"
#include "core/contact/stage_timer.h"

namespace railwear::internal {

NormalSolution SolveNormalStage(const NormalProblem& np, const NormalSolverOptions& options,
                                std::vector<StageTime>* stages, const Eigen::VectorXd* start) {
  const auto t0 = Clock::now();
  NormalSolution sol = SolveNormal(np, options, start);
  AddStage(stages, "solve", SecondsSince(t0));
  return sol;
}

KeptPatches CollectPatches(const WheelRailGeometry& geom, PatchBuilds* builds,
                           const NormalSolution& sol, bool auto_model,
                           std::optional<double> pressure_limit_Pa, ContactResult* result,
                           PatchArea area) {
  KeptPatches kept;
  int offset = 0;
  for (size_t k = 0; k < builds->builds.size(); ++k) {
    const int n = builds->builds[k].grid.cells();
    PatchResult pr = NumericalPatch(geom, std::move(builds->builds[k].grid),
                                    sol.pressure_Pa.segment(offset, n), pressure_limit_Pa, area);
    if (pr.cells_in_contact > 0) {
      pr.model = builds->choices[k].label;
      if (auto_model) pr.model_reason = builds->choices[k].reason;
      result->patches.push_back(std::move(pr));
      kept.build.push_back(static_cast<int>(k));
      kept.offset.push_back(offset);
    }
    offset += n;
  }
  return kept;
}

}  // namespace railwear::internal
