// The normal-tangential stage of SolveContact (normal_tangential_stage.h).
#include "core/contact/normal_tangential_stage.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/contact/contact_forces.h"
#include "core/contact/coupling.h"
#include "core/contact/patch_results.h"
#include "core/contact/rolling_stage.h"

namespace railwear::internal {
namespace {

// The smallest slope d(V_p + V_c)/dT a secant step divides by: creep forces that cancel the
// pressure's vertical part (dV_c/dV_p near -1) leave no load to balance.
constexpr double kMinBalanceSlope = 0.05;
// A bracket on the target narrower than this (relative to the load) that has not met the
// tolerance holds a jump of f, not a root.
constexpr double kStalledBracket = 1e-10;

std::pair<double, double> AreaAndPeak(const ContactResult& r) {
  double area = 0.0, p_max = 0.0;
  for (const auto& p : r.patches) {
    area += p.area_m2;
    p_max = std::max(p_max, p.p_max_Pa);
  }
  return {area, p_max};
}

// The iteration on the pressure's target T for f(T) = V_p + V_c - Q = 0: secant steps, and once
// f has changed sign, regula falsi (Illinois) inside the bracket. V_c(T) can jump where a cell
// enters or leaves the contact (the tangential solution changes with the contact set); the
// bracket then closes on the jump without a root, and Stalled() says so.
class BalanceTarget {
 public:
  BalanceTarget(double load_N, double target_N) : load_(load_N), target_(target_N) {}

  // f [N] of the result solved with the current target.
  double Error(const ContactResult& r) const {
    const ForceParts f = TotalForcesOnRail(r);
    return f.normal_N.z() + f.creep_N.z() - load_;
  }
  bool Settled(const ContactResult& r) const {
    return std::abs(Error(r)) <= kBalanceTolerance * load_;
  }
  // The bracket has closed to round-off without meeting the tolerance: f jumps there.
  bool Stalled() const { return lo_ && hi_ && hi_->first - lo_->first <= kStalledBracket * load_; }
  // The jump of f across the closed bracket [N].
  double Jump() const { return lo_ && hi_ ? hi_->second - lo_->second : 0.0; }

  // The next target from the result of the current one; nullopt when none is positive.
  std::optional<double> Next(const ContactResult& r) {
    const double f = Error(r);
    // f grows with T (the pressure's part does, and dV_c/dT > -1): f < 0 below the root.
    if (f < 0) {
      if (lo_ && side_ == -1 && hi_) hi_->second *= 0.5;  // Illinois
      lo_ = std::pair{target_, f};
      side_ = -1;
    } else {
      if (hi_ && side_ == +1 && lo_) lo_->second *= 0.5;
      hi_ = std::pair{target_, f};
      side_ = +1;
    }
    if (lo_ && hi_) {
      double t =
          (lo_->first * hi_->second - hi_->first * lo_->second) / (hi_->second - lo_->second);
      if (!(t > lo_->first && t < hi_->first)) t = 0.5 * (lo_->first + hi_->first);
      target_ = t;
    } else {
      double slope = 1.0;
      if (last_) {
        slope = (f - last_->second) / (target_ - last_->first);
      } else {
        const ForceParts parts = TotalForcesOnRail(r);
        if (parts.normal_N.z() > 0.0) slope = 1.0 + parts.creep_N.z() / parts.normal_N.z();
      }
      if (!std::isfinite(slope) || slope < kMinBalanceSlope) slope = kMinBalanceSlope;
      last_ = std::pair{target_, f};
      target_ -= f / slope;
    }
    if (!(target_ > 0.0)) return std::nullopt;
    return target_;
  }

 private:
  double load_, target_;
  std::optional<std::pair<double, double>> last_;     // (T, f) of the previous secant step
  std::optional<std::pair<double, double>> lo_, hi_;  // (T, f) with f < 0 and f >= 0
  int side_ = 0;

 public:
  // Forget the history (f has changed: the coupling moved the gap).
  void Reset() {
    last_.reset();
    lo_.reset();
    hi_.reset();
    side_ = 0;
  }
};

}  // namespace

double BalanceResidual(const ContactResult& result, double load_N) {
  const ForceParts f = TotalForcesOnRail(result);
  return std::abs(f.normal_N.z() + f.creep_N.z() - load_N) / load_N;
}

namespace {

// The loop itself: with `coupling` the gap gets the coupling displacement, with `balance` the
// load target moves; until what is on settles. Returns false (and says why in *result) when
// it does not.
bool Iterate(const ContactProblem& problem, const WheelRailGeometry& geom,
             const std::vector<double>& kappa, const std::vector<int>& kept_offset,
             const Eigen::VectorXd& base_gap, bool coupling, BalanceTarget* balance,
             NormalProblem* np, Eigen::VectorXd* pressure, ContactResult* result) {
  const RollingOptions& o = *problem.rolling;
  const int max_iterations = coupling ? o.coupling_max_iterations : kBalanceMaxIterations;
  // Once the coupling has settled its gap stays as it is, so that the balance's f(T) no longer
  // changes between steps and its bracket holds.
  bool gap_settled = !coupling;
  for (int it = 1; it <= max_iterations; ++it) {
    if (coupling) result->coupling_iterations = it;
    if (balance && !balance->Settled(*result) && balance->Stalled()) {
      // As near as the pressure's target can come: say so, and stop moving it.
      result->message += fmt::format(
          "{}vertical balance: the creep forces' vertical part jumps by {:.3g} N where a cell "
          "enters the contact; residual {:.2e} of the load",
          result->message.empty() ? "" : "; ", balance->Jump(), result->balance_residual);
      if (!coupling) return true;
      balance = nullptr;
    }
    if (balance) {
      ++result->balance_iterations;
      if (!balance->Settled(*result)) {
        const auto target = balance->Next(*result);
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
    const NormalSolution sol = SolveNormal(*np, problem.solver);
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
      PatchResult updated = NumericalPatch(
          geom, std::move(grid), sol.pressure_Pa.segment(kept_offset[k], n), np->pressure_limit_Pa);
      updated.model = std::move(result->patches[k].model);
      updated.model_reason = std::move(result->patches[k].model_reason);
      result->patches[k] = std::move(updated);
    }
    result->approach_m = sol.approach_m;
    RunRollingStage(problem, geom, result);
    if (result->status != SolverStatus::kConverged) return false;  // force target not carried
    const double change =
        (sol.pressure_Pa - *pressure).cwiseAbs().maxCoeff() / std::max(pressure->maxCoeff(), 1.0);
    *pressure = sol.pressure_Pa;
    if (balance) {
      result->balance_residual = BalanceResidual(*result, *problem.load.vertical_force_N);
    }
    if (change < o.coupling_tolerance) gap_settled = true;
    if (gap_settled && (!balance || balance->Settled(*result))) return true;
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

void IterateNormalTangential(const ContactProblem& problem, const WheelRailGeometry& geom,
                             const std::vector<ContactCandidate>& cands,
                             const std::vector<int>& kept_build,
                             const std::vector<int>& kept_offset, NormalProblem* np,
                             Eigen::VectorXd pressure, ContactResult* result) {
  const bool coupling = problem.rolling->coupling;
  std::optional<BalanceTarget> balance;
  if (problem.load.vertical_force_N) {
    balance.emplace(*problem.load.vertical_force_N, *np->force_N);
    result->balance_residual = BalanceResidual(*result, *problem.load.vertical_force_N);
  }
  BalanceTarget* balance_ptr = balance ? &*balance : nullptr;
  const Eigen::VectorXd base_gap = np->gap_m;
  // The balance first, alone: the coupling's changes are measured against the balanced
  // uncoupled solution, so that they are the coupling's own.
  if (balance && !balance->Settled(*result) &&
      !Iterate(problem, geom, {}, kept_offset, base_gap, false, balance_ptr, np, &pressure,
               result)) {
    return;
  }
  if (!coupling) return;
  const auto [area0, p_max0] = AreaAndPeak(*result);
  std::vector<double> kappa;
  for (int b : kept_build) {
    const int wheel_sign = BodyCurvatureSign(cands[b].wheel_lateral_curvature);
    const int rail_sign = BodyCurvatureSign(cands[b].rail_lateral_curvature);
    kappa.push_back(CouplingCoefficient(problem.model.constants, problem.wheel_material, wheel_sign,
                                        problem.rail_material, rail_sign));
  }
  if (!Iterate(problem, geom, kappa, kept_offset, base_gap, true, balance_ptr, np, &pressure,
               result)) {
    return;
  }
  const auto [area1, p_max1] = AreaAndPeak(*result);
  result->coupling_area_change = area1 / area0 - 1.0;
  result->coupling_p_max_change = p_max1 / p_max0 - 1.0;
}

}  // namespace railwear::internal
