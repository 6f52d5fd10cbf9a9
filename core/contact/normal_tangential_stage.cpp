// The normal-tangential stage of SolveContact (normal_tangential_stage.h).
#include "core/contact/normal_tangential_stage.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/contact/balance_target.h"
#include "core/contact/contact_forces.h"
#include "core/contact/coupling.h"
#include "core/contact/patch_results.h"
#include "core/contact/rolling_stage.h"

namespace railwear::internal {
namespace {

std::pair<double, double> AreaAndPeak(const ContactResult& r) {
  double area = 0.0, p_max = 0.0;
  for (const auto& p : r.patches) {
    area += p.area_m2;
    p_max = std::max(p_max, p.p_max_Pa);
  }
  return {area, p_max};
}

// f = V_p + V_c - Q [N] of a rolling result under the load Q.
double BalanceError(const ContactResult& r, double load_N) {
  const ForceParts f = TotalForcesOnRail(r);
  return f.normal_N.z() + f.creep_N.z() - load_N;
}

// df/dT's estimate for the first secant step: 1 + V_c / V_p.
double InitialBalanceSlope(const ContactResult& r) {
  const ForceParts parts = TotalForcesOnRail(r);
  return parts.normal_N.z() > 0.0 ? 1.0 + parts.creep_N.z() / parts.normal_N.z() : 1.0;
}

// The loop's normal solves run in the strict setting (the gap residual at 1e-10, or the
// caller's gap residual when tighter) whatever problem.solver's criterion: the balance settles
// |V_p + V_c - Q| to kBalanceTolerance (1e-9) of the load and the coupling the pressure's change
// to coupling_tolerance (1e-6), both below what the default criterion (the pressure update at
// 1e-4, 4 significant digits) resolves. With the default's solves V_c moved by some 1e-8 to 1e-7
// of the load from one target to the next, which the balance took for a step of V_c
// (examples/rolling_flange.toml: "jumps", stopped at a residual of 5e-8 after 8 iterations
// against 5). Each of these solves starts from the last pressures, so only the first solve of a
// contact (SolveContact's normal stage) runs at the default criterion. The balance alone loosens
// its solves while it is far from the load (BalanceSolveTolerance), never below this setting's
// criterion, and settles only on a strict solve.
NormalSolverOptions LoopSolverOptions(const NormalSolverOptions& o) {
  NormalSolverOptions strict = o;
  const bool tighter =
      o.criterion == NormalStopCriterion::kGapResidual && o.tolerance < kStrictNormalTolerance;
  strict.criterion = NormalStopCriterion::kGapResidual;
  if (!tighter) strict.tolerance = kStrictNormalTolerance;
  return strict;
}

}  // namespace

double BalanceResidual(const ContactResult& result, double load_N) {
  return std::abs(BalanceError(result, load_N)) / load_N;
}

double BalanceSolveTolerance(double f_N, double load_N, double strict_tolerance) {
  return std::clamp(kBalanceSolveFraction * std::abs(f_N) / load_N, strict_tolerance,
                    std::max(strict_tolerance, kLoosestBalanceSolveTolerance));
}

namespace {

// The loop itself: with `coupling` the gap gets the coupling displacement, with `balance` the
// load target moves; until what is on settles. Returns false (and says why in *result) when
// it does not.
bool Iterate(const ContactProblem& problem, const WheelRailGeometry& geom,
             const std::vector<double>& kappa, const std::vector<int>& kept_offset,
             const Eigen::VectorXd& base_gap, bool coupling, BalanceTarget* balance,
             NormalProblem* np, Eigen::VectorXd* pressure, ContactResult* result,
             RollingStageMemory* memory) {
  const RollingOptions& o = *problem.rolling;
  const int max_iterations = coupling ? o.coupling_max_iterations : kBalanceMaxIterations;
  // Once the coupling has settled its gap stays as it is, so that the balance's f(T) no longer
  // changes between steps and its bracket holds.
  bool gap_settled = !coupling;
  const double load_N = balance ? *problem.load.vertical_force_N : 0.0;
  // After a step of f: one more solve on the bracket's better side, then the balance stops.
  bool last_balance_solve = false;
  for (int it = 1; it <= max_iterations; ++it) {
    if (coupling) result->coupling_iterations = it;
    const double f = balance ? BalanceError(*result, load_N) : 0.0;
    if (balance && !balance->Settled(f) && balance->Stalled()) {
      // As near as the pressure's target can come: say so, take the side of the step nearer to
      // the load, and stop moving the target.
      const auto [best_target, best_f] = balance->Best();
      result->message += fmt::format(
          "{}vertical balance: the creep forces' vertical part jumps by {:.3g} N where a cell "
          "enters the contact; residual {:.2e} of the load",
          result->message.empty() ? "" : "; ", balance->Jump(), std::abs(best_f) / load_N);
      balance = nullptr;
      if (std::abs(f) > std::abs(best_f)) {
        np->force_N = best_target;
        last_balance_solve = true;
      } else if (!coupling) {
        return true;
      }
    }
    if (balance) {
      ++result->balance_iterations;
      if (!balance->Settled(f)) {
        const auto target = balance->Next(f, InitialBalanceSlope(*result));
        if (!target) {
          result->status = SolverStatus::kNotConverged;
          result->message =
              "vertical balance: the creep forces' vertical part leaves no load for the pressure";
          return false;
        }
        np->force_N = *target;
      }
    }
    if (!gap_settled) {
      if (balance) balance->Reset();
      np->gap_m = base_gap;
      for (size_t k = 0; k < result->patches.size(); ++k) {
        const PatchResult& patch = result->patches[k];
        np->gap_m.segment(kept_offset[k], patch.grid.cells()) +=
            CouplingDisplacement(patch.grid, patch.rolling->tangential, kappa[k]);
      }
    }
    // Under a prescribed load from the last solution, scaled to the new target: the target or
    // the coupling's gap moves the pressures little (the same solution to the solver's
    // tolerance, in fewer iterations). Under a prescribed approach the unscaled last pressures
    // start farther off than the initial guess (measured: more iterations), so not there.
    NormalSolverOptions solve_options = LoopSolverOptions(problem.solver);
    const double strict_tolerance = solve_options.tolerance;
    if (balance && !coupling) {
      solve_options.tolerance = BalanceSolveTolerance(f, load_N, strict_tolerance);
    }
    const bool strict_solve = solve_options.tolerance == strict_tolerance;
    const NormalSolution sol = SolveNormal(*np, solve_options, np->force_N ? pressure : nullptr);
    result->iterations += sol.iterations;
    if (sol.status != SolverStatus::kConverged) {
      result->status = sol.status;
      result->message =
          (coupling ? "coupled normal solve: " : "balanced normal solve: ") + sol.message;
      return false;
    }
    for (size_t k = 0; k < result->patches.size(); ++k) {
      PatchGrid grid = result->patches[k].grid;
      const int n = grid.cells();
      // (the area of the patches reported only: IterateNormalTangential fills it)
      PatchResult updated =
          NumericalPatch(geom, std::move(grid), sol.pressure_Pa.segment(kept_offset[k], n),
                         np->pressure_limit_Pa, PatchArea::kDeferred);
      updated.model = std::move(result->patches[k].model);
      updated.model_reason = std::move(result->patches[k].model_reason);
      result->patches[k] = std::move(updated);
    }
    result->approach_m = sol.approach_m;
    RunRollingStage(problem, geom, result, memory);
    if (result->status != SolverStatus::kConverged) return false;  // force target not carried
    const double change =
        (sol.pressure_Pa - *pressure).cwiseAbs().maxCoeff() / std::max(pressure->maxCoeff(), 1.0);
    *pressure = sol.pressure_Pa;
    if (balance || last_balance_solve) {
      result->balance_residual = BalanceResidual(*result, load_N);
    }
    if (last_balance_solve && !coupling) return true;
    last_balance_solve = false;
    if (change < o.coupling_tolerance) gap_settled = true;
    // (a looser solve that lands within the tolerance is repeated strictly at its target: the
    // next round's f is settled, so the target stays)
    if (gap_settled &&
        (!balance || (strict_solve && balance->Settled(BalanceError(*result, load_N))))) {
      return true;
    }
  }
  result->status = SolverStatus::kNotConverged;
  result->message = coupling
                        ? fmt::format("normal-tangential coupling did not settle in {} iterations",
                                      o.coupling_max_iterations)
                        : fmt::format(
                              "the vertical balance with the creep forces did not settle in {} "
                              "iterations (residual {:.2e} of the load)",
                              kBalanceMaxIterations, result->balance_residual);
  return false;
}

}  // namespace

Eigen::VectorXd IterateNormalTangential(const ContactProblem& problem,
                                        const WheelRailGeometry& geom,
                                        const std::vector<ContactCandidate>& cands,
                                        const std::vector<int>& kept_build,
                                        const std::vector<int>& kept_offset, NormalProblem* np,
                                        Eigen::VectorXd pressure, ContactResult* result,
                                        RollingStageMemory* memory) {
  const bool coupling = problem.rolling->coupling;
  std::optional<BalanceTarget> balance;
  if (problem.load.vertical_force_N) {
    balance.emplace(*problem.load.vertical_force_N, *np->force_N, kBalanceTolerance);
    result->balance_residual = BalanceResidual(*result, *problem.load.vertical_force_N);
  }
  BalanceTarget* balance_ptr = balance ? &*balance : nullptr;
  const Eigen::VectorXd base_gap = np->gap_m;
  // The balance first, alone: the coupling's changes are measured against the balanced
  // uncoupled solution, so that they are the coupling's own.
  const bool balanced = !balance ||
                        balance->Settled(BalanceError(*result, *problem.load.vertical_force_N)) ||
                        Iterate(problem, geom, {}, kept_offset, base_gap, false, balance_ptr, np,
                                &pressure, result, memory);
  FillDeferredAreas(&result->patches);
  if (!balanced || !coupling) return pressure;
  const auto [area0, p_max0] = AreaAndPeak(*result);
  std::vector<double> kappa;
  for (int b : kept_build) {
    const int wheel_sign = BodyCurvatureSign(cands[b].wheel_lateral_curvature);
    const int rail_sign = BodyCurvatureSign(cands[b].rail_lateral_curvature);
    kappa.push_back(CouplingCoefficient(problem.model.constants, problem.wheel_material, wheel_sign,
                                        problem.rail_material, rail_sign));
  }
  const bool coupled = Iterate(problem, geom, kappa, kept_offset, base_gap, true, balance_ptr, np,
                               &pressure, result, memory);
  FillDeferredAreas(&result->patches);
  if (!coupled) return pressure;
  const auto [area1, p_max1] = AreaAndPeak(*result);
  result->coupling_area_change = area1 / area0 - 1.0;
  result->coupling_p_max_change = p_max1 / p_max0 - 1.0;
  return pressure;
}

}  // namespace railwear::internal
