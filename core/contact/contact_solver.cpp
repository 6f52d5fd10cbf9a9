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
#include <memory>
#include <optional>

#include "core/contact/contact_forces.h"
#include "core/contact/hertz_estimate.h"
#include "core/contact/hertz_tread.h"
#include "core/contact/normal_part_memo.h"
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
  // kind = hertz with rolling contact: the fast tread path, or its fallback (hertz_tread.h).
  if (IsHertzRolling(problem)) {
    return SolveHertzRolling(problem, [](const ContactProblem& p) { return SolveContact(p); });
  }
  CheckContactProblem(problem);
  // 1. Placement.
  const auto t0 = Clock::now();
  const WheelRailGeometry geom = PlaceWheel(problem);
  return SolveContact(problem, geom, SecondsSince(t0));
}

ContactResult SolveContact(const ContactProblem& problem, const WheelRailGeometry& geom,
                           double placement_s) {
  return internal::SolveContact(problem, geom, placement_s, nullptr);
}

namespace {

// Whether a solve's vertical balance can start from a warm memo's last balanced state
// (normal_part_memo.h): a prescribed load without coupling.
bool WarmBalanceApplies(const ContactProblem& problem, const NormalPartMemo* memo) {
  return memo && memo->warm_balance() && problem.rolling && !problem.rolling->coupling &&
         problem.load.vertical_force_N;
}

// 5. Rolling, then coupling and the vertical balance, from the normal part's result, candidates,
// kept patches, normal problem *np (changed by the balance) and solution. A warm memo
// (WarmBalanceApplies) keeps the balanced state for the next solve.
void RunRollingPart(const ContactProblem& problem, const WheelRailGeometry& geom,
                    const std::vector<ContactCandidate>& cands, const KeptPatches& kept,
                    NormalProblem* np, const Eigen::VectorXd& pressure, ContactResult* result,
                    NormalPartMemo* memo) {
  if (!problem.rolling || result->status != SolverStatus::kConverged) return;
  auto t0 = Clock::now();
  // The exact solver's set-up and warm start per patch and the pitch search's last solution,
  // kept across the pitch search's and the normal-tangential loop's repeated solves on the same
  // grids (rolling_stage.h).
  RollingStageMemory memory;
  RunRollingStage(problem, geom, result, &memory);
  AddStage(&result->stages, "tangential", SecondsSince(t0));
  if (result->status == SolverStatus::kConverged &&
      (problem.rolling->coupling || problem.load.vertical_force_N)) {
    t0 = Clock::now();
    Eigen::VectorXd balanced = IterateNormalTangential(problem, geom, cands, kept.build,
                                                       kept.offset, np, pressure, result, &memory);
    AddStage(&result->stages, problem.rolling->coupling ? "coupling" : "balance",
             SecondsSince(t0));
    if (WarmBalanceApplies(problem, memo) && result->status == SolverStatus::kConverged &&
        np->force_N) {
      memo->KeepBalanced({result->patches, result->approach_m, *np->force_N, std::move(balanced)});
    }
  }
}

}  // namespace

namespace internal {

ContactResult SolveContact(const ContactProblem& problem, const WheelRailGeometry& geom,
                           double placement_s, NormalPartMemo* memo, ContactWarmStart* warm_start) {
  const auto t_start = Clock::now();
  auto finish = [&](ContactResult r) {
    FillDeferredAreas(&r.patches);  // (the patches' areas the stages left to the end)
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

  // Steps 2-4 kept by an earlier solve of this problem on this geometry (normal_part_memo.h):
  // continue from a copy of its state.
  if (const NormalPart* part = memo ? memo->Find(geom) : nullptr) {
    const auto t0 = Clock::now();
    ContactResult continued = part->result;
    continued.stages = std::move(result.stages);
    NormalProblem np = part->assembly.np;  // its blocks are the kept operators
    AddStage(&continued.stages, "normal reused", SecondsSince(t0));
    memo->CountReuse();
    // A warm memo: the balance starts from the last balanced state instead of the load (and
    // from the load after all when that fails).
    const BalancedPart* warm = WarmBalanceApplies(problem, memo) ? memo->Balanced(geom) : nullptr;
    if (warm) {
      ContactResult from_warm = continued;
      from_warm.patches = warm->patches;
      from_warm.approach_m = warm->approach_m;
      NormalProblem warm_np = np;
      warm_np.force_N = warm->target_N;
      memo->CountWarmBalance();
      const Eigen::VectorXd pressure = warm->pressure;  // (KeepBalanced replaces *warm)
      RunRollingPart(problem, geom, part->cands, part->kept, &warm_np, pressure, &from_warm, memo);
      if (from_warm.status == SolverStatus::kConverged) return finish(std::move(from_warm));
    }
    RunRollingPart(problem, geom, part->cands, part->kept, &np, part->pressure, &continued, memo);
    return finish(std::move(continued));
  }

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
  // From a warm start's state (contact_warm_start.h) one attempt only, on the last call's
  // measured patch: nullopt when it does not fit (the call is then solved cold).
  auto solve_grids = [&](const WarmStartState* from) -> std::optional<ContactResult> {
    ContactResult out = result;
    // (a warm attempt on its own models: a fallback starts from the untouched ones)
    std::optional<PatchModelMemory> warm_models;
    if (from) warm_models.emplace(geom, problem, estar, stiffness_ratio_K, first);
    PatchModelMemory& m = from ? *warm_models : models;
    PotentialArea area(problem, first, stiffness_ratio_K);
    double approach_now = first.delta;  // the best estimate of the approach so far
    // A warm attempt under a prescribed load with a balance: the pressure's target is the last
    // call's balanced one, scaled to this call's load.
    std::optional<double> warm_target_N;
    if (from) {
      area.TakeOver(from->area);
      approach_now = from->approach_m;
      if (from->target_N && from->load_N && problem.load.vertical_force_N) {
        warm_target_N = *from->target_N * (*problem.load.vertical_force_N / *from->load_N);
      }
    }
    int total_iterations = 0;
    for (int attempt = 0; attempt < (from ? 1 : 12); ++attempt) {
      PatchBuilds builds;
      auto t0 = Clock::now();
      // A warm attempt keeps the last call's grids (and operators) where the wheel has hardly
      // moved (KeptGrid).
      const std::vector<KeptGrid>* kept_grids = from ? &from->kept_grids : nullptr;
      if (!area.Build(geom, &m, approach_now, &builds, &out, kept_grids)) {
        if (from) return std::nullopt;
        return out;
      }
      if (from &&
          (builds.unremembered > 0 || static_cast<int>(builds.builds.size()) != from->candidates)) {
        return std::nullopt;
      }

      t0 = Clock::now();
      NormalAssembly assembly = AssembleNormalProblem(builds, problem, kept_grids);
      if (warm_target_N) assembly.np.force_N = *warm_target_N;
      AddStage(&out.stages, "influence", SecondsSince(t0));

      // A warm attempt under a prescribed load starts from the last call's pressures on the new
      // grids (under a prescribed approach an unscaled start can take more iterations,
      // normal_solver.h).
      std::optional<Eigen::VectorXd> start;
      if (from && assembly.np.force_N && !from->grids.empty()) {
        start = WarmPressureStart(*from, builds);
      }
      const NormalSolution sol =
          SolveNormalStage(assembly.np, problem.solver, &out.stages, start ? &*start : nullptr);
      total_iterations += sol.iterations;
      const bool converged = sol.status == SolverStatus::kConverged;
      // A solve on the measuring cells that fails is solved again on the preset's
      // (potential_area.h).
      if (!converged && !sol.load_above_limit && area.measuring() && attempt < 11) {
        area.StopMeasuring();
        continue;
      }
      if (converged) approach_now = sol.approach_m;
      const AreaReview review = area.Review(&builds, sol, assembly.np.cell_area_m2, &m);
      if (from && (!converged || review.Again())) return std::nullopt;
      // A plastic patch larger than the whole grid (every cell at the pressure limit, the load
      // not carried) grows the grid like a converged one whose pressure reaches its edge.
      if ((converged || sol.load_above_limit) && review.Again() && attempt < 11) {
        area.Widen(review, sol);
        continue;
      }

      // The grids and operators for the next call's warm start (before CollectPatches takes
      // the grids); a grid kept again keeps the pose it was built at, so that the wheel's moves
      // add up against kMaxKeptGridMove.
      std::vector<KeptGrid> next_kept;
      if (warm_start) {
        for (size_t k = 0; k < builds.builds.size(); ++k) {
          const PatchBuild& b = builds.builds[k];
          if (kept_grids && builds.kept[k] >= 0) {
            next_kept.push_back((*kept_grids)[builds.kept[k]]);
          } else if (!b.grid.planar && !b.rail_s_m.empty()) {
            next_kept.push_back(KeepGrid(geom, builds, k, assembly.ops[k]));
          }
        }
      }

      // 4. Patch results; without a memo their areas deferred to the end (finish), since the
      // balance's solves replace the patches.
      out.status = sol.status;
      out.message = sol.message;
      out.approach_m = sol.approach_m;
      out.iterations = total_iterations;
      const KeptPatches kept =
          CollectPatches(geom, &builds, sol, m.is_auto(), assembly.np.pressure_limit_Pa, &out,
                         memo ? PatchArea::kNow : PatchArea::kDeferred);
      if (review.grow) {
        out.message += (out.message.empty() ? "" : "; ");
        out.message += "pressure reaches the edge of the potential contact area";
      }

      // A warm start's state for the next call: what this call measured and its balanced
      // target and pressures (`np` after the balance).
      auto keep_warm = [&](const NormalProblem& np, const ContactResult& solved) {
        if (!warm_start || solved.status != SolverStatus::kConverged) return;
        auto state = std::make_unique<WarmStartState>();
        state->area = area.measured();
        state->candidates = static_cast<int>(builds.builds.size());
        state->approach_m = solved.approach_m;
        // The balance's target (without coupling: the coupling's balance is on another gap).
        if (problem.rolling && !problem.rolling->coupling && problem.load.vertical_force_N &&
            np.force_N) {
          state->load_N = *problem.load.vertical_force_N;
          state->target_N = *np.force_N;
        }
        for (const PatchResult& patch : solved.patches) {
          state->grids.push_back(patch.grid);
          state->grids.back().gap_m.resize(0);  // (not needed)
          state->pressures_Pa.push_back(patch.pressure_Pa);
        }
        state->kept_grids = std::move(next_kept);
        warm_start->Keep(std::move(state));
      };
      // 5. Rolling, then coupling and the vertical balance; with a memo, the normal part is
      // kept for the next solve first (the balance changes the normal problem: it runs on a
      // copy).
      if (memo && problem.rolling && out.status == SolverStatus::kConverged) {
        auto part = std::make_unique<NormalPart>(
            NormalPart{out, builds.cands, kept, std::move(assembly), sol.pressure_Pa});
        NormalProblem np = part->assembly.np;
        const NormalPart& kept_part = *part;
        memo->Keep(geom, std::move(part));  // (before the balance: a warm memo keeps its state)
        RunRollingPart(problem, geom, kept_part.cands, kept_part.kept, &np, kept_part.pressure,
                       &out, memo);
        // A warm attempt that does not fit: the cold solve's Keep replaces this part.
        if (from && out.status != SolverStatus::kConverged) return std::nullopt;
        keep_warm(np, out);
        return out;
      }
      RunRollingPart(problem, geom, builds.cands, kept, &assembly.np, sol.pressure_Pa, &out,
                     nullptr);
      if (from && out.status != SolverStatus::kConverged) return std::nullopt;
      keep_warm(assembly.np, out);
      return out;
    }
    out.status = SolverStatus::kNotConverged;
    out.message = "the potential contact area did not settle";
    return out;
  };
  // (With a memo, an axle force target's rounds, only the first solve on a geometry gets here
  // and may start warm: the rounds continue from the memo's normal part above.)
  if (warm_start && warm_start->state()) {
    if (std::optional<ContactResult> warm_result = solve_grids(warm_start->state())) {
      warm_start->CountWarm();
      return finish(std::move(*warm_result));
    }
    warm_start->CountFallback();
  }
  if (warm_start) warm_start->CountCold();
  std::optional<ContactResult> cold = solve_grids(nullptr);
  if (warm_start && cold->status != SolverStatus::kConverged) warm_start->Clear();
  return finish(std::move(*cold));
}

}  // namespace internal

}  // namespace railwear
