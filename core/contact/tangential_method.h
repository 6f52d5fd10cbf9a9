// TangentialMethod: which tangential solver a rolling contact uses, and the one seam that
// dispatches to it. A new method is one enum value, one name in kTangentialMethodNames and one
// entry in the solver table of tangential_method.cpp; the rolling stage (rolling_stage.h) only
// calls SolveTangential.
//
// `auto` (issue 16): per patch, Kalker's exact theory where FASTSIM would leave the accuracy
// preset's creep-force tolerance (CreepForceTolerance in grid_resolution.h), FASTSIM elsewhere.
// FASTSIM runs first (a fraction of a millisecond); its patch fit gives the indicators:
//   - the spin share: Kalker's linear theory split into its translational and spin parts,
//       spin_share = |c C23 phi| / (|C11 xi| + |C22 eta| + |c C23 phi|),  c = sqrt(a b),
//     with the patch-average creepages (xi, eta, phi) and C_ij at the patch's a/b;
//   - the axis ratio a/b of the patch's equivalent ellipse (a along x).
// The exact solver runs when the spin share exceeds the preset's limit, scaled down on patches
// short along the rolling direction (AutoTangentialLimits). The limits come from measurements of
// FASTSIM against the exact solver on the same grids (docs/rolling_contact.md, "tangential =
// auto"): Hertz patches a/b = 0.1 ... 20 from 0.1 to 10 times saturation, and S1002/UIC60 tread,
// gauge-corner and flange patches. Since FASTSIM's own error near saturation (5-7 % on Hertz
// patches without spin) exceeds the creep-force bound of `reference` and `fine`, `auto` takes
// the exact solver on every patch at those presets.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/fastsim.h"
#include "core/contact/tangential_exact.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"
#include "core/numerics/enum_names.h"

namespace railwear {

// Which tangential solver a rolling contact uses.
enum class TangentialMethod {
  kFastsim,  // Kalker's simplified theory, strip by strip (core/contact/fastsim.h)
  kExact,    // steady rolling with half-space tangential influence (tangential_exact.h)
  kAuto,     // per patch: kExact where FASTSIM leaves the preset's tolerance, else kFastsim
};
inline constexpr std::array<EnumName<TangentialMethod>, 3> kTangentialMethodNames = {{
    {TangentialMethod::kFastsim, "fastsim"},
    {TangentialMethod::kExact, "exact"},
    {TangentialMethod::kAuto, "auto"},
}};
std::string_view ToString(TangentialMethod v);
std::optional<TangentialMethod> TangentialMethodFromString(std::string_view s);

// The limit of `auto` at one accuracy preset: FASTSIM is kept when
//   spin_share <= max_spin_share * min(1, a/b),
// i.e. the allowed spin share shrinks on patches short along the rolling direction (a/b < 1),
// where FASTSIM's spin error grows fastest. max_spin_share < 0: never FASTSIM (the exact solver
// on every patch).
struct AutoTangentialLimits {
  double max_spin_share = 0.0;
};
AutoTangentialLimits AutoTangentialLimitsFor(AccuracyPreset preset);

// What a patch's tangential stage ran, and for `auto` why.
struct TangentialChoice {
  TangentialMethod method = TangentialMethod::kFastsim;  // kFastsim or kExact: the solver that ran
  bool automatic = false;                                // chosen by `auto`
  double spin_share = 0.0;                               // the indicators (auto only)
  double a_over_b = 0.0;
  double creepage_residual = 0.0;  // reported, not in the rule (docs/rolling_contact.md)
  std::string reason;                                    // auto only: the rule that decided
};

// The indicators of `auto` on one patch.
struct TangentialIndicators {
  // Kalker's linear creep force split into its translational and spin parts:
  // |c C23 phi| / (|C11 xi| + |C22 eta| + |c C23 phi|), c = sqrt(a b), in [0, 1].
  double spin_share = 0.0;
  double a_over_b = 0.0;  // of the patch's equivalent ellipse, a along x
  // How far the per-cell creepage is from Kalker's planar field w_x = xi - phi s',
  // w_s = eta + phi x' that FASTSIM's flexibilities assume (curved patches: the rolling radius
  // and the contact angle change across the patch): sqrt(sum |w - w_planar|^2 / sum |w|^2) over
  // the contact cells, in [0, 1].
  double creepage_residual = 0.0;
};
// From a FASTSIM patch fit (fastsim.h: patch-average xi, eta, phi [1/m], centroid, semi-axes),
// the per-cell creepage `input` and pressure_Pa on `grid`, and the pair's Poisson ratio nu.
TangentialIndicators CalcTangentialIndicators(const PatchGrid& grid,
                                              const Eigen::VectorXd& pressure_Pa,
                                              const RollingInput& input, const FastsimPatch& fit,
                                              double nu);

// The rule of `auto`: kExact or kFastsim for indicators at a preset, with the reason.
TangentialChoice ChooseTangentialMethod(const TangentialIndicators& indicators,
                                        AccuracyPreset preset);

// What the exact solver keeps between the solves of one patch when a caller solves it again and
// again on the same grid (SolveContact's search for the pitch velocity under a prescribed
// longitudinal force, and its vertical balance, which moves the pressure but not the grid):
//   setup  the grid's ExactTangentialSetup (rolling operator and kernel tables), rebuilt only
//          when the grid's shape changes; the results are those of a fresh setup, bit for bit;
//   last   the last converged exact solution, the warm start of the next solve on a grid of the
//          same shape (results to the solver's tolerance; docs/speed.md, the groove's free
//          rolling).
// For one pair of materials: a caller keeps one per patch for the duration of one contact solve.
// Not for concurrent use (the setup's scratch buffers).
struct ExactTangentialReuse {
  std::optional<ExactTangentialSetup> setup;
  std::optional<TangentialSolution> last;
};

// The tangential solution of one patch by `method`: grid and pressure_Pa (per cell, shape
// [grid.cells()]) of the normal solution, the rigid slip `input` (kinematics.h), and the two
// bodies' materials (the solvers' elastic constants). `accuracy` is the preset `auto` keeps to
// (ignored by the fixed methods). choice (optional out): what ran and, for auto, why.
// reuse (optional, in/out): the exact solver's set-up and warm start kept from the previous
// solve of this patch (the same materials), updated by this one; FASTSIM does not use it.
// exact_tolerance: the exact solver's stopping tolerance relative to mu p_max
// (ExactTangentialOptions::tolerance, > 0; ContactSetup::tangential_tolerance); FASTSIM
// ignores it.
TangentialSolution SolveTangential(TangentialMethod method, AccuracyPreset accuracy,
                                   const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                   const RollingInput& input, const Material& wheel,
                                   const Material& rail, TangentialChoice* choice = nullptr,
                                   ExactTangentialReuse* reuse = nullptr,
                                   double exact_tolerance = kDefaultExactTangentialTolerance);

}  // namespace railwear
