// Normal contact solver: pressures p >= 0 with complementarity against the deformed gap, for a
// prescribed load or a prescribed approach. Several patches share one rigid approach.
//
// Unknowns p_k >= 0 (cell pressures, Pa) and delta (rigid approach along the load direction e_F,
// m). Deformed gap g = d - delta * w + C p, with w_k = e_F . (-n_k) the share of the approach
// that closes cell k's normal gap. Conditions: g >= 0, p >= 0, p_k g_k = 0, and either
//   sum_k p_k A_k w_k = F   (prescribed load; A_k cell area)   or   delta = delta0 (prescribed).
// With a pressure limit p_lim (elastic-perfectly-plastic surface layer) the pressures are bounded,
// 0 <= p_k <= p_lim, and the conditions become
//   p_k = 0          where g_k >= 0   (the gap is open),
//   0 < p_k < p_lim  where g_k = 0    (elastic contact),
//   p_k = p_lim      where g_k <= 0   (plastic cells: -g_k is the interpenetration that the
//                                      elastic half-spaces cannot take up, the plastic set),
// with the same load or approach condition, so that under a prescribed load the patch grows until
// it carries the load. Without a limit the solve is the elastic one, operation for operation.
// Method: projected conjugate gradients of Polonsky & Keer (1999) type, with the approach as the
// multiplier of the load condition. Numerical outcomes (no contact, no convergence) are reported
// in the status, never thrown.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/contact/influence_operator.h"

namespace railwear {

enum class SolverStatus { kConverged, kNotConverged, kNoContact };
std::string_view ToString(SolverStatus s);

// Preconditioner of the conjugate-gradient directions.
//   kNone:            plain projected CG (Polonsky & Keer): the direction is the gap residual.
//   kInverseOperator: the residual on the contact set, mapped by each block's approximate
//                     inverse (InfluenceOperator::ApplyPreconditioner), restricted to the contact
//                     set again (Vollebregt 2014). One more FFT-sized product per iteration, far
//                     fewer iterations on large grids. Needs every block to have an inverse;
//                     without one the solve runs unpreconditioned (NormalSolution::preconditioned
//                     says which).
//   kAuto:            kInverseOperator when every block has an inverse, else kNone.
enum class CgPreconditioner { kAuto, kNone, kInverseOperator };
std::string_view ToString(CgPreconditioner p);

// When the projected CG stops (NormalSolverOptions::criterion; `tolerance` is relative to the
// scale each names).
//   kGapResidual:    the deformed gap's complementarity residual (NormalSolution::
//                    complementarity_residual_m) <= tolerance * h, with h = max over the contact
//                    set (p_k > 0) of |delta * w_k - d_k|: the largest elastic displacement in
//                    the patch (at the solution, C p = delta w - d there), independent of a
//                    constant offset in d (several patches, first contact not at d = 0). Checked
//                    with a freshly applied C p, never with an updated one. The strict
//                    setting (StrictNormalSolverOptions(): 1e-10): for references to more than
//                    4 digits and for callers that difference solutions at small steps.
//   kPressureUpdate: the default (1e-4, issue 18 point 4: 4 significant digits of p_max and
//                    F_n with margin, docs/speed.md). CONTACT's NormCG criterion (E.A.H.
//                    Vollebregt, CONTACT's src/m_solvpn.f90, its EPS): the last step neither moved
//                    a cell into or out of the contact set and changed the pressures by at most
//                    tolerance times their size, both as RMS values over the contact set (cells
//                    with 0 < p < p_lim) before the step:
//                      rms_k(tau t_k) <= tolerance * rms_k(p_k),
//                    with rms(p) taken after the step and, as in CONTACT, refreshed only in
//                    iterations 1, 2, 3 and every 10th. The tolerance is thereby stated in the
//                    pressures users read (about the relative error of p_max and F_n it leaves;
//                    docs/speed.md measures it). CONTACT checks its contact set every iteration
//                    only above 400 potential-contact cells (below, every 2nd or 3rd); this mode
//                    checks every iteration. The returned pressures are those of the last step;
//                    C p is applied afresh for the reported gap and residual.
// Either way, under a prescribed load also load_error_relative <= tolerance.
enum class NormalStopCriterion { kGapResidual, kPressureUpdate };
std::string_view ToString(NormalStopCriterion c);

inline constexpr double kDefaultNormalTolerance = 1e-4;  // kPressureUpdate's, the default
inline constexpr double kStrictNormalTolerance = 1e-10;  // kGapResidual's, the strict setting
// The tolerances a scene ([model] normal_tolerance) or the C API (rw_model.normal_tolerance) may
// ask for: from 1e-13 (a few hundred times double rounding of the pressures' RMS: a step below
// that is rounding and may never come) to 1e-2 (2 digits; looser stops before the contact set
// settles).
inline constexpr double kMinNormalTolerance = 1e-13, kMaxNormalTolerance = 1e-2;

struct NormalSolverOptions {
  // Stopping criterion, see NormalStopCriterion; the tolerance is dimensionless, > 0. The
  // default keeps 4 significant digits of p_max and F_n with margin (measured within 2.3e-6 and
  // 1e-6 of the strict solution on CONTACT's perfc cases, docs/speed.md).
  NormalStopCriterion criterion = NormalStopCriterion::kPressureUpdate;
  double tolerance = kDefaultNormalTolerance;
  // Projected-CG iterations (one operator application each, plus one more when the contact set
  // grows or shrinks, plus one preconditioner application when preconditioned, plus O(n) work)
  // before giving up with kNotConverged. >= 1. The conjugate
  // directions restart when the residual has not halved in 30 iterations (operators that are
  // only nearly symmetric), so a stalled solve ends here with a message instead of looping.
  int max_iterations = 2000;
  // See CgPreconditioner. The solution is the same either way (to the tolerance).
  CgPreconditioner preconditioner = CgPreconditioner::kAuto;
  // Returns "" when valid, otherwise what is wrong.
  std::string Validate() const;
};

// The strict setting: the gap residual at kStrictNormalTolerance (the default before issue 18
// point 4), the other options at their defaults.
NormalSolverOptions StrictNormalSolverOptions();

struct NormalProblem {
  // One operator per patch; cells of patch b occupy the consecutive range [offset_b,
  // offset_b + blocks[b]->size()) of the vectors below. Patches do not interact elastically.
  std::vector<const InfluenceOperator*> blocks;
  Eigen::VectorXd gap_m;             // d, initial separation per cell [m]
  Eigen::VectorXd approach_weight;   // w, per cell, in (0, 1]
  Eigen::VectorXd cell_area_m2;      // A, per cell [m^2]
  std::optional<double> force_N;     // prescribed load F [N] (F <= 0 gives kNoContact) ...
  std::optional<double> approach_m;  // ... or prescribed approach delta [m]; exactly one is set
  // Pressure limit p_lim [Pa] (> 0, finite) of every cell: elastic-perfectly-plastic contact.
  // Absent: elastic, p unbounded above.
  std::optional<double> pressure_limit_Pa;
};
// Preconditions (checked, abort on violation: the caller builds the problem): at least one
// block, none null, block sizes summing to n = gap_m.size(); approach_weight and cell_area_m2
// of size n; 0 < w_k <= 1; A_k > 0; all entries finite; pressure_limit_Pa > 0 when given;
// options.Validate() == "".
// The operators should be positive definite on any contact set (Boussinesq), or nearly so
// (seed kernel on a curved grid); if the iteration stagnates the result is kNotConverged.

struct NormalSolution {
  SolverStatus status = SolverStatus::kNotConverged;
  std::string message;
  Eigen::VectorXd pressure_Pa;     // per cell
  Eigen::VectorXd deformed_gap_m;  // g per cell
  // delta [m]: the prescribed one, or the load multiplier (weighted least-squares fit of d + Cp
  // against w over the contact set; with a limit over its free cells 0 < p < p_lim). With no
  // contact under a prescribed load: min_k d_k / w_k, the largest approach that carries nothing.
  double approach_m = 0.0;
  double force_N = 0.0;  // sum_k p_k A_k w_k [N] (the load that follows a prescribed approach)
  int iterations = 0;    // projected-CG iterations
  // max( max_{0 < p_k < p_lim} |g_k|, max_{p_k = 0} max(0, -g_k), max_{p_k = p_lim} max(0, g_k) )
  // [m] (without a limit the last set is empty)
  double complementarity_residual_m = 0.0;
  // |sum_k p_k A_k w_k - F| / F under a prescribed load; 0 under a prescribed approach.
  double load_error_relative = 0.0;
  int operator_applications = 0;  // calls of InfluenceOperator::Apply (per block set), for cost
  // Calls of InfluenceOperator::ApplyPreconditioner (per block set); about as costly as Apply.
  int preconditioner_applications = 0;
  bool preconditioned = false;  // the directions were preconditioned (see CgPreconditioner)
  // With a pressure limit: cells at p_lim (plastic) and the load they carry, sum p_k A_k w_k
  // over them [N]. 0 without a limit.
  int plastic_cells = 0;
  double plastic_force_N = 0.0;
  // Every cell of the grids is at p_lim and the prescribed load is still not carried (status
  // kNotConverged): the grid is too small for a plastic patch; a larger grid may carry it.
  bool load_above_limit = false;
};

// `start`, when given (size n, finite, >= 0): the pressures [Pa] to begin from instead of the
// initial guess, e.g. the solution of a nearby problem on the same grids (a new load target,
// a slightly changed gap); they are clipped to the limit and, under a prescribed load, scaled to
// it. The solution is the same to the tolerance. Under a prescribed load a nearby start needs
// fewer iterations; under a prescribed approach the unscaled start can need more (measured on
// the Hertz case at +2 % approach: 75 against 53), so the contact code uses it under loads only.
NormalSolution SolveNormal(const NormalProblem& problem, const NormalSolverOptions& options = {},
                           const Eigen::VectorXd* start = nullptr);

}  // namespace railwear
