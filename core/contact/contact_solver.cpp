// SolveContact as an outline of named stages, each in its own file:
//   placement       placement_stage.h   input checks, the placed wheel and rail, no-contact exits
//   Hertz estimates hertz_estimate.h    the Hertz model, the first estimate of approach and size
//   auto model      patch_model_memory.h the model of each patch (kind = auto: Hertz check, memory)
//   potential area  potential_area.h    grids per candidate; re-grid / grow / crop until they fit
//   operator        operator_stage.h    influence operators and the NormalProblem
//   normal solve    normal_stage.h      SolveNormal and the solution's patches
//   patch results   patch_results.h     areas, forces, pressure centres
//   rolling         rolling_stage.h     tangential solution (one seam: tangential_method.h)
//   normal-tangential normal_tangential_stage.h  coupling and the vertical balance with the
//                   creep forces, in one loop
//   (every exit)    contact_forces.h    L/V and Nadal's limit (FlangeClimbCheck)
#include "core/contact/contact_solver.h"

#include <algorithm>
#include <optional>

#include "core/contact/contact_forces.h"
#include "core/contact/hertz_estimate.h"
#include "core/contact/normal_stage.h"
#include "core/contact/normal_tangential_stage.h"
#include "core/contact/operator_stage.h"
#include "core/contact/patch_model_memory.h"
#include "core/contact/patch_results.h"
#include "core/contact/placement_stage.h"
#include "core/contact/potential_area.h"
#include "core/contact/stage_timer.h"

namespace railwear {

using namespace internal;  // the stages

ContactResult SolveContact(const ContactProblem& problem) {
  CheckContactProblem(problem);
  // 1. Placement.
  const auto t0 = Clock::now();
  const WheelRailGeometry geom = PlaceWheel(problem);
  return SolveContact(problem, geom, SecondsSince(t0));
}

ContactResult SolveContact(const ContactProblem& problem, const WheelRailGeometry& geom,
                           double placement_s) {
  const auto t_start = Clock::now();
  auto finish = [&](ContactResult r) {
    r = FinishResult(std::move(r), placement_s + SecondsSince(t_start));
    r.climb = CheckFlangeClimb(
        r, problem.rolling ? std::optional<double>(problem.rolling->friction) : std::nullopt);
    return r;
  };
  CheckContactProblem(problem);
  ContactResult result;
  result.model = problem.model;
  result.pressure_limit_Pa =
      PressureLimitOf(problem.pressure_limit, problem.wheel_material, problem.rail_material);
  AddStage(&result.stages, "placement", placement_s);

  // The cases that end before any grid.
  if (const auto no_contact = NoContactBeforeGrid(problem, geom)) {
    result.status = SolverStatus::kNoContact;
    result.message = *no_contact;
    return finish(result);
  }
  CheckRollingProblem(problem);

  // 2. The Hertz model, or the Hertz estimates that seed the grid models.
  const double estar = ContactModulus(problem.wheel_material, problem.rail_material);
  if (problem.model.kind == ModelKind::kHertz) {
    const auto t_hertz = Clock::now();
    return finish(SolveHertzModel(SearchHertz(geom, problem, estar), std::move(result), t_hertz));
  }
  const double k_w = problem.wheel_material.Compliance();
  const double k_r = problem.rail_material.Compliance();
  const double stiffness_ratio_K = k_r / (k_w + k_r);
  const FirstContactEstimate first = EstimateFirstContact(geom, problem, estar);
  PatchModelMemory models(geom, problem, estar, stiffness_ratio_K, first);
  if (models.is_auto() && !problem.rolling) {
    if (auto hertz = models.CheckHertz(&result)) return finish(std::move(*hertz));
  }

  // 3. Grids, operators and the normal solve, until the potential area fits the solution.
  PotentialArea area(problem, first, stiffness_ratio_K);
  double approach_now = first.delta;  // the best estimate of the approach so far
  int total_iterations = 0;
  for (int attempt = 0; attempt < 12; ++attempt) {
    PatchBuilds builds;
    auto t0 = Clock::now();
    if (!area.Build(geom, &models, approach_now, &builds, &result)) return finish(result);

    t0 = Clock::now();
    NormalAssembly assembly = AssembleNormalProblem(builds, problem);
    AddStage(&result.stages, "influence", SecondsSince(t0));

    const NormalSolution sol = SolveNormalStage(assembly.np, problem.solver, &result.stages);
    total_iterations += sol.iterations;
    const bool converged = sol.status == SolverStatus::kConverged;
    if (converged) approach_now = sol.approach_m;
    const AreaReview review = area.Review(&builds, sol, assembly.np.cell_area_m2, &models);
    // A plastic patch larger than the whole grid (every cell at the pressure limit, the load not
    // carried) grows the grid like a converged one whose pressure reaches its edge.
    if ((converged || sol.load_above_limit) && review.Again() && attempt < 11) {
      area.Widen(review, sol);
      continue;
    }

    // 4. Patch results.
    result.status = sol.status;
    result.message = sol.message;
    result.approach_m = sol.approach_m;
    result.iterations = total_iterations;
    const KeptPatches kept = CollectPatches(geom, &builds, sol, models.is_auto(),
                                            assembly.np.pressure_limit_Pa, &result);
    if (review.grow) {
      result.message += (result.message.empty() ? "" : "; ");
      result.message += "pressure reaches the edge of the potential contact area";
    }

    // 5. Rolling, then coupling and the vertical balance.
    if (problem.rolling && result.status == SolverStatus::kConverged) {
      t0 = Clock::now();
      RunRollingStage(problem, geom, &result);
      AddStage(&result.stages, "tangential", SecondsSince(t0));
      if (result.status == SolverStatus::kConverged &&
          (problem.rolling->coupling || problem.load.vertical_force_N)) {
        t0 = Clock::now();
        IterateNormalTangential(problem, geom, builds.cands, kept.build, kept.offset, &assembly.np,
                                sol.pressure_Pa, &result);
        AddStage(&result.stages, problem.rolling->coupling ? "coupling" : "balance",
                 SecondsSince(t0));
      }
    }
    return finish(result);
  }
  result.status = SolverStatus::kNotConverged;
  result.message = "the potential contact area did not settle";
  return finish(result);
}

}  // namespace railwear
