// The operator stage of SolveContact (operator_stage.h).
#include "core/contact/operator_stage.h"

namespace railwear::internal {

NormalAssembly AssembleNormalProblem(const PatchBuilds& builds, const ContactProblem& problem,
                                     const std::vector<KeptGrid>* kept) {
  const InfluenceSettings settings{problem.model.kernel, problem.model.constants,
                                   problem.wheel_material, problem.rail_material};
  NormalAssembly out;
  NormalProblem& np = out.np;
  int total = 0;
  for (const auto& b : builds.builds) total += b.grid.cells();
  np.gap_m.resize(total);
  np.approach_weight.resize(total);
  np.cell_area_m2.resize(total);
  int offset = 0;
  for (size_t k = 0; k < builds.builds.size(); ++k) {
    const PatchBuild& b = builds.builds[k];
    InfluenceSettings patch_settings = settings;
    patch_settings.kernel = builds.choices[k].kernel;
    patch_settings.wheel_curvature_sign =
        BodyCurvatureSign(builds.cands[k].wheel_lateral_curvature);
    patch_settings.rail_curvature_sign = BodyCurvatureSign(builds.cands[k].rail_lateral_curvature);
    const int kept_index = k < builds.kept.size() ? builds.kept[k] : -1;
    if (kept && kept_index >= 0) {
      out.ops.push_back((*kept)[kept_index].op);
    } else {
      out.ops.push_back(MakeInfluenceOperator(b.grid, patch_settings));
    }
    np.blocks.push_back(out.ops.back().get());
    np.gap_m.segment(offset, b.grid.cells()) = b.grid.gap_m;
    for (int j = 0; j < b.grid.ns; ++j) {
      const double w = -b.grid.normal_yz[j].y();
      np.approach_weight.segment(offset + j * b.grid.nx, b.grid.nx).setConstant(w);
    }
    np.cell_area_m2.segment(offset, b.grid.cells()).setConstant(b.grid.CellArea());
    offset += b.grid.cells();
  }
  np.force_N = problem.load.vertical_force_N;
  np.approach_m = problem.load.approach_m;
  np.pressure_limit_Pa =
      PressureLimitOf(problem.pressure_limit, problem.wheel_material, problem.rail_material);
  return out;
}

}  // namespace railwear::internal
