// The coupling stage of SolveContact (coupling_stage.h).
#include "core/contact/coupling_stage.h"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "core/contact/coupling.h"
#include "core/contact/patch_results.h"
#include "core/contact/rolling_stage.h"

namespace railwear::internal {

void SolveCoupled(const ContactProblem& problem, const WheelRailGeometry& geom,
                  const std::vector<ContactCandidate>& cands, const std::vector<int>& kept_build,
                  const std::vector<int>& kept_offset, NormalProblem* np, Eigen::VectorXd pressure,
                  ContactResult* result) {
  const RollingOptions& o = *problem.rolling;
  auto totals = [](const ContactResult& r) {
    double area = 0.0, p_max = 0.0;
    for (const auto& p : r.patches) {
      area += p.area_m2;
      p_max = std::max(p_max, p.p_max_Pa);
    }
    return std::pair{area, p_max};
  };
  const auto [area0, p_max0] = totals(*result);
  const Eigen::VectorXd base_gap = np->gap_m;
  std::vector<double> kappa;
  for (int b : kept_build) {
    const int wheel_sign = BodyCurvatureSign(cands[b].wheel_lateral_curvature);
    const int rail_sign = BodyCurvatureSign(cands[b].rail_lateral_curvature);
    kappa.push_back(CouplingCoefficient(problem.model.constants, problem.wheel_material, wheel_sign,
                                        problem.rail_material, rail_sign));
  }
  for (int it = 1; it <= o.coupling_max_iterations; ++it) {
    result->coupling_iterations = it;
    np->gap_m = base_gap;
    for (size_t k = 0; k < result->patches.size(); ++k) {
      const PatchResult& patch = result->patches[k];
      np->gap_m.segment(kept_offset[k], patch.grid.cells()) +=
          CouplingDisplacement(patch.grid, patch.rolling->tangential, kappa[k]);
    }
    const NormalSolution sol = SolveNormal(*np, problem.solver);
    result->iterations += sol.iterations;
    if (sol.status != SolverStatus::kConverged) {
      result->status = sol.status;
      result->message = "coupled normal solve: " + sol.message;
      return;
    }
    for (size_t k = 0; k < result->patches.size(); ++k) {
      PatchGrid grid = result->patches[k].grid;
      const int n = grid.cells();
      PatchResult updated =
          NumericalPatch(geom, std::move(grid), sol.pressure_Pa.segment(kept_offset[k], n));
      updated.model = std::move(result->patches[k].model);
      updated.model_reason = std::move(result->patches[k].model_reason);
      result->patches[k] = std::move(updated);
    }
    result->approach_m = sol.approach_m;
    RunRollingStage(problem, geom, result);
    const double change =
        (sol.pressure_Pa - pressure).cwiseAbs().maxCoeff() / std::max(pressure.maxCoeff(), 1.0);
    pressure = sol.pressure_Pa;
    if (change < o.coupling_tolerance) {
      const auto [area1, p_max1] = totals(*result);
      result->coupling_area_change = area1 / area0 - 1.0;
      result->coupling_p_max_change = p_max1 / p_max0 - 1.0;
      return;
    }
  }
  result->status = SolverStatus::kNotConverged;
  result->message = fmt::format("normal-tangential coupling did not settle in {} iterations",
                                o.coupling_max_iterations);
}

}  // namespace railwear::internal
