// The tangential methods' table: each TangentialMethod's name and solver, in enum order, and the
// rule of `auto` (tangential_method.h).
#include "core/contact/tangential_method.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/contact/fastsim.h"
#include "core/contact/grid_resolution.h"
#include "core/contact/kalker_coefficients.h"
#include "core/contact/tangential_exact.h"
#include "core/numerics/check.h"

namespace railwear {

namespace {

using TangentialSolver = TangentialSolution (*)(AccuracyPreset, const PatchGrid&,
                                                const Eigen::VectorXd&, const RollingInput&,
                                                const Material&, const Material&, TangentialChoice*,
                                                ExactTangentialReuse*, double);

FastsimOptions FastsimFor(const Material& wheel, const Material& rail) {
  const CombinedElastic elastic = CombineElastic(wheel, rail);
  FastsimOptions fo;
  fo.shear_modulus_Pa = elastic.shear_modulus_Pa;
  fo.poisson_ratio = elastic.poisson_ratio;
  return fo;
}

TangentialSolution SolveByFastsim(AccuracyPreset, const PatchGrid& grid,
                                  const Eigen::VectorXd& pressure_Pa, const RollingInput& input,
                                  const Material& wheel, const Material& rail,
                                  TangentialChoice* choice, ExactTangentialReuse*, double) {
  choice->method = TangentialMethod::kFastsim;
  return SolveFastsim(grid, pressure_Pa, input, FastsimFor(wheel, rail));
}

// The exact solver at `tolerance` (ExactTangentialOptions::tolerance), with the set-up and the
// warm start kept in `reuse` when there is one.
TangentialSolution SolveExact(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                              const RollingInput& input, const Material& wheel,
                              const Material& rail, ExactTangentialReuse* reuse, double tolerance) {
  ExactTangentialOptions options;
  options.tolerance = tolerance;
  if (reuse == nullptr) return SolveTangentialExact(grid, pressure_Pa, input, wheel, rail, options);
  if (!reuse->setup || !reuse->setup->Fits(grid)) {
    reuse->setup.emplace(grid, wheel, rail, options.method);
    reuse->last.reset();
  }
  const TangentialSolution* start =
      reuse->last && reuse->last->traction_x_Pa.size() == grid.cells() ? &*reuse->last : nullptr;
  TangentialSolution sol =
      SolveTangentialExact(grid, pressure_Pa, input, *reuse->setup, options, start);
  if (sol.status == SolverStatus::kConverged) {
    reuse->last = sol;
  } else {
    reuse->last.reset();
  }
  return sol;
}

TangentialSolution SolveByExact(AccuracyPreset, const PatchGrid& grid,
                                const Eigen::VectorXd& pressure_Pa, const RollingInput& input,
                                const Material& wheel, const Material& rail,
                                TangentialChoice* choice, ExactTangentialReuse* reuse,
                                double exact_tolerance) {
  choice->method = TangentialMethod::kExact;
  return SolveExact(grid, pressure_Pa, input, wheel, rail, reuse, exact_tolerance);
}

// `auto`: FASTSIM first; its patch fit decides whether the exact solver replaces it.
TangentialSolution SolveByAuto(AccuracyPreset accuracy, const PatchGrid& grid,
                               const Eigen::VectorXd& pressure_Pa, const RollingInput& input,
                               const Material& wheel, const Material& rail,
                               TangentialChoice* choice, ExactTangentialReuse* reuse,
                               double exact_tolerance) {
  const FastsimOptions fo = FastsimFor(wheel, rail);
  FastsimPatch fit;
  TangentialSolution fastsim = SolveFastsim(grid, pressure_Pa, input, fo, &fit);
  if (fastsim.status != SolverStatus::kConverged) {
    *choice = {};
    choice->automatic = true;
    choice->reason = "no contact: FASTSIM's empty solution";
    return fastsim;
  }
  const TangentialIndicators ind =
      CalcTangentialIndicators(grid, pressure_Pa, input, fit, fo.poisson_ratio);
  *choice = ChooseTangentialMethod(ind, accuracy);
  if (choice->method == TangentialMethod::kFastsim) return fastsim;
  return SolveExact(grid, pressure_Pa, input, wheel, rail, reuse, exact_tolerance);
}

// The solver of each method (keyed by the method, like kTangentialMethodNames).
struct TangentialEntry {
  TangentialMethod method;
  TangentialSolver solve;
};
constexpr std::array<TangentialEntry, 3> kTangentialSolvers = {{
    {TangentialMethod::kFastsim, &SolveByFastsim},
    {TangentialMethod::kExact, &SolveByExact},
    {TangentialMethod::kAuto, &SolveByAuto},
}};

}  // namespace

std::string_view ToString(TangentialMethod v) { return EnumToString(kTangentialMethodNames, v); }

std::optional<TangentialMethod> TangentialMethodFromString(std::string_view s) {
  return EnumFromString(kTangentialMethodNames, s);
}

AutoTangentialLimits AutoTangentialLimitsFor(AccuracyPreset preset) {
  // Measured (docs/rolling_contact.md, "tangential = auto"): FASTSIM against the exact solver on
  // the same Hertz-patch grids, |dF| / max(|F_exact|, 0.1 mu Fn), worst over 0.1 to 10 times
  // saturation and both signs of spin against lateral creepage:
  //   standard (10 cells per semi-axis, bound 10 %): spin share 0: <= 6.7 % at every a/b;
  //     0.1: <= 7.6 % for a/b >= 0.5 (15 % at 0.2, 26 % at 0.1); 0.2: 8-17 % for a/b >= 0.5;
  //   draft (4 cells, bound 15 %): 0: <= 6.9 %; 0.1: <= 10 % for a/b >= 0.5; 0.2: 11-13 % for
  //     a/b >= 1, 19 % at 0.5; 0.3: 20-40 %.
  // Hence 0.1 at standard and 0.2 at draft, times min(1, a/b). Reference and fine: FASTSIM's
  // error without spin near saturation (5-6.6 % at 24 cells) exceeds their bounds (4 %, 2 %).
  switch (preset) {
    case AccuracyPreset::kDraft:
      return {0.2};
    case AccuracyPreset::kStandard:
      return {0.1};
    case AccuracyPreset::kReference:
    case AccuracyPreset::kFine:
      return {-1.0};
  }
  return {0.1};
}

TangentialIndicators CalcTangentialIndicators(const PatchGrid& grid,
                                              const Eigen::VectorXd& pressure_Pa,
                                              const RollingInput& input, const FastsimPatch& fit,
                                              double nu) {
  TangentialIndicators ind;
  ind.a_over_b = fit.semi_axis_x_m / fit.semi_axis_s_m;
  const CreepCoefficients cc = KalkerCoefficients(ind.a_over_b, nu);
  const double c = std::sqrt(fit.semi_axis_x_m * fit.semi_axis_s_m);
  const double spin = std::abs(c * cc.c23 * fit.phi_per_m);
  const double total = std::abs(cc.c11 * fit.xi) + std::abs(cc.c22 * fit.eta) + spin;
  ind.spin_share = total > 0.0 ? spin / total : 0.0;
  double off = 0.0, all = 0.0;
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const int k = grid.Index(i, j);
      if (pressure_Pa[k] <= 0.0) continue;
      const double xp = grid.X(i) - fit.centroid_x_m, sp = grid.S(j) - fit.centroid_s_m;
      const double dx = input.creep_x[k] - (fit.xi - fit.phi_per_m * sp);
      const double ds = input.creep_s[k] - (fit.eta + fit.phi_per_m * xp);
      off += dx * dx + ds * ds;
      all += input.creep_x[k] * input.creep_x[k] + input.creep_s[k] * input.creep_s[k];
    }
  }
  ind.creepage_residual = all > 0.0 ? std::sqrt(off / all) : 0.0;
  return ind;
}

TangentialChoice ChooseTangentialMethod(const TangentialIndicators& ind, AccuracyPreset preset) {
  const AutoTangentialLimits lim = AutoTangentialLimitsFor(preset);
  TangentialChoice c;
  c.automatic = true;
  c.spin_share = ind.spin_share;
  c.a_over_b = ind.a_over_b;
  c.creepage_residual = ind.creepage_residual;
  if (lim.max_spin_share < 0.0) {
    c.method = TangentialMethod::kExact;
    c.reason = fmt::format("exact: every patch at {} (FASTSIM's error exceeds its creep-force "
                           "bound of {:.0f} %)",
                           ToString(preset), 100.0 * CreepForceTolerance(preset));
    return c;
  }
  const double allowed = lim.max_spin_share * std::min(1.0, ind.a_over_b);
  const bool fastsim = ind.spin_share <= allowed;
  c.method = fastsim ? TangentialMethod::kFastsim : TangentialMethod::kExact;
  c.reason = fmt::format("{}: spin share {:.3f} {} {:.3f} (the limit {:.2f} at {}{})",
                         fastsim ? "fastsim" : "exact", ind.spin_share, fastsim ? "<=" : ">",
                         allowed, lim.max_spin_share, ToString(preset),
                         ind.a_over_b < 1.0 ? fmt::format(" x a/b {:.3g}", ind.a_over_b)
                                            : std::string());
  return c;
}

TangentialSolution SolveTangential(TangentialMethod method, AccuracyPreset accuracy,
                                   const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                   const RollingInput& input, const Material& wheel,
                                   const Material& rail, TangentialChoice* choice,
                                   ExactTangentialReuse* reuse, double exact_tolerance) {
  TangentialChoice local;
  TangentialChoice* out = choice != nullptr ? choice : &local;
  for (const auto& e : kTangentialSolvers) {
    if (e.method == method) {
      return e.solve(accuracy, grid, pressure_Pa, input, wheel, rail, out, reuse, exact_tolerance);
    }
  }
  RAILWEAR_CHECK(false && "a TangentialMethod without a solver");
  return {};
}

}  // namespace railwear
