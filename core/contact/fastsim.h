// FASTSIM: Kalker's simplified theory of rolling contact, strip by strip on the patch grid.
//
// The elastic surface displacement is taken proportional to the local traction, u = L q
// (Kalker 1982). In steady rolling the material moves through the patch from its leading edge
// (largest x) to its trailing edge at the rolling speed V, so the slip of a cell is
//   s = V (w - du/dx),   w = (creep_x, creep_s) the rigid creepage of the cell,
// and sticking cells carry du/dx = w. Each s strip j is marched from its leading edge down
// (default march; kContactEuler below differs in h and in where w is taken):
//   q_trial = q_prev - (w / L) h,   h = dx between cell centres (dx/2 from the leading face of
//                                   the first cell, where q = 0),
//   q = q_trial            if |q_trial| <= g   (stick),
//   q = g q_trial/|q_trial| otherwise          (slip; q = -g v/|v| with v the slip velocity),
// with g = mu * (bound pressure). The traction is that of the rail on the wheel and opposes the
// creepage (tangential_types.h); for small creepage this reproduces Kalker's linear theory with
// the flexibilities below.
//
// Flexibilities (reference README §4, C from KalkerCoefficients at the patch's a/b):
//   L1 = 8a/(3 C11 G),  L2 = 8a/(3 C22 G),  L3 = pi a sqrt(a/b)/(4 C23 G).
// The per-cell creepage cannot be split into its xi/eta/spin parts cell by cell, so unless the
// options give them, patch-average creepages (xi, eta, phi) are fitted by least squares over the
// contact cells to Kalker's planar field  w_x = xi - phi (s - s_c),  w_s = eta + phi (x - x_c)
// about the contact centroid (x_c, s_c) (exact when the field has that form). Three models:
//   kThree (default): Kalker's simplified theory with three flexibilities (CONTACT's M=3): the
//     fitted spin part of each cell's creepage goes with L3, the rest (xi, eta and whatever the
//     planar field does not explain) with L1 along x and L2 along s. Reproduces linear theory for
//     pure xi, pure eta AND pure spin, on any mix. u = L q holds with a different L per part, so
//     the slip magnitude uses the weighted L below and its direction is set to -q/|q|.
//   kWeighted: Kalker's single flexibility for both components,
//     L = (|xi| L1 + |eta| L2 + |phi| c L3) / (|xi| + |eta| + |phi| c),  c = sqrt(a b);
//     exact for each pure creepage, not for mixes (on the README check case it underestimates
//     |Fy| by ~7 %); the slip is exactly opposite the traction.
//   kSeparate: L1 for x, L2 for s, no spin flexibility (the classical choice when creepage varies
//     across the patch); wrong by the ratio L3/L2 for spin. Slip direction set to -q/|q|.
// Discretisation (FastsimMarch):
//   kTrapezoidal (default): cell-centre values; the traction rate w/L is integrated between
//     centres by the trapezoidal rule (second order, so a spin's linearly varying creepage costs
//     no first-order error), from the leading face of each strip's first contact cell where
//     q = 0. Converges to the continuum simplified theory as the cells shrink.
//   kContactEuler: the march of Vollebregt's CONTACT (open-source CONTACT, src/m_solvpt.f90
//     modif_fastsim with T=3, M=3): implicit Euler in x, q_i = q_(i-1) - (w_i/L) dx with a full
//     step dx also at the first contact cell of a strip (q_(i-1) = 0), and the creepage taken
//     kContactSpinShift = 1/6 of a cell upstream (CONTACT applies its default FACPHI = 1/6 to the
//     spin term, w_s = eta + phi (x + dx/6), src/m_sdis.f90 set_tang_rhs; here the whole
//     per-cell rate is interpolated linearly toward the upstream neighbour, the same for Kalker's
//     planar field). First order: its error falls like dx.
// blend_flexibilities (kThree only): CONTACT's simpflex (src/m_hertz.f90) blends L1, L2, L3
//   toward one combined flexibility as the creepage grows,
//     L_comb = (xi^2 + eta^2 + (phi f)^2) / (xi^2/L1 + eta^2/L2 + (phi f)^2/L3),  f = 3 pi a/32,
//     w = min(1, |(xi, eta, phi)| / (3 |(ch_xi, ch_eta, ch_phi)|)),  L_k <- (1 - w) L_k + w L_comb,
//   with ch_xi = mu Fn/(c^2 G C11), ch_eta = mu Fn/(c^2 G C22), ch_phi = mu Fn/(c^3 G C23). The
//   weight mixes the dimensionless xi, eta with phi; as in CONTACT, phi and ch_phi enter it in
//   1/mm (kContactLengthUnit_m).
//
// Why the README §4 FASTSIM figures (Fy/(mu Fn) = -0.6118 parabolic bound, -0.6016 elliptic)
// were missed by 5.6 % with the parabolic bound: they are not continuum values of the simplified
// theory but CONTACT's FASTSIM on its own example (examples/fastsim.inp, the case of the README:
// cases 2 and 3, M=3, 40 x 40 cells in the contact on a 44 x 44 grid over 1.1 times the Hertz
// rectangle), i.e. the first-order march and the blended flexibilities above on a coarse grid.
// That algorithm, re-implemented here from CONTACT's open source (its output for the example was
// not available), gives -0.6095 and -0.6004 on that grid: 0.4 % and 0.2 % from the README
// (fastsim_test.cpp). The converged simplified theory with the README's L1..L3 is -0.647
// (parabolic) and -0.596 (elliptic), which the default kTrapezoidal march reaches (-0.646 on
// 200 x 200 cells); CONTACT's 40-cell first-order march lies 4.6 % below it with the parabolic
// bound, and the blending removes another 1.2 %.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear {

// Which pressure bounds the traction, g = mu * p_bound.
enum class TractionBound {
  kActualPressure,  // the grid's pressure (Hertz pressure: the "elliptic" bound)
  // Kalker's original FASTSIM bound: p = 2 Fn/(pi a b) (1 - x'^2/a^2 - s'^2/b^2), x', s' from
  // the contact centroid, Fn = sum p dA; cells of the contact outside that ellipse get 0, and the
  // field is rescaled so that its discrete sum is Fn exactly.
  kParabolic,
};
std::string_view ToString(TractionBound v);

enum class FlexibilityModel { kWeighted, kSeparate, kThree };
std::string_view ToString(FlexibilityModel v);

// How each strip is marched from its leading edge (see the file comment).
enum class FastsimMarch { kTrapezoidal, kContactEuler };
std::string_view ToString(FastsimMarch v);
// "trapezoidal", "contact_euler"; nullopt for anything else.
std::optional<FastsimMarch> FastsimMarchFromString(std::string_view s);

// CONTACT's FACPHI default: the creepage of a cell is taken this fraction of a cell upstream in
// the kContactEuler march.
inline constexpr double kContactSpinShift = 1.0 / 6.0;
// CONTACT works in mm: the unit in which phi enters the blending weight [m].
inline constexpr double kContactLengthUnit_m = 1e-3;

struct FastsimOptions {
  // Combined elastic constants of the two bodies: 2/G = 1/G1 + 1/G2, nu = (G/2)(nu1/G1 +
  // nu2/G2) (CombineElastic below). Defaults: steel, E = 210 GPa, nu = 0.28.
  double shear_modulus_Pa = 210e9 / (2.0 * 1.28);  // G > 0
  double poisson_ratio = 0.28;                     // nu in [0, 0.5]
  TractionBound bound = TractionBound::kActualPressure;
  FlexibilityModel flexibility = FlexibilityModel::kThree;
  FastsimMarch march = FastsimMarch::kTrapezoidal;
  // CONTACT's blending of L1..L3 toward one flexibility (file comment); needs kThree.
  bool blend_flexibilities = false;
  // Semi-axes of the contact along x and s [m] used for a/b and the flexibilities. When not
  // given: the ratio a/b is that of the extents of the contact cells (cells with p > 0, counted
  // to their faces) and the size follows from the contact area, pi a b = (number of cells) dA.
  std::optional<double> semi_axis_x_m, semi_axis_s_m;
  // Patch-average creepages used for the flexibilities: xi, eta [-], phi [1/m]. Any not given
  // is fitted to the per-cell creepage (see the file comment).
  std::optional<double> xi, eta, phi_per_m;

  // True when the options are usable; otherwise fills *error (if non-null) with the reason.
  bool IsValid(std::string* error) const;
};

// Patch quantities FASTSIM used, reported next to the solution (for tests and reports).
struct FastsimPatch {
  double semi_axis_x_m = 0.0, semi_axis_s_m = 0.0;
  double centroid_x_m = 0.0, centroid_s_m = 0.0;  // area centroid of the contact cells
  double xi = 0.0, eta = 0.0, phi_per_m = 0.0;    // patch-average creepages used for L
  double flexibility_x_m_Pa = 0.0;     // L used for the x component (L1 for kThree) [m/Pa]
  double flexibility_s_m_Pa = 0.0;     // L used for the s component (L2 for kThree) [m/Pa]
  double flexibility_spin_m_Pa = 0.0;  // L3 for kThree, else 0 [m/Pa]
  double blend_weight = 0.0;           // w of blend_flexibilities (0 when not blending)
  double normal_force_N = 0.0;         // sum p dA over the grid
};

// The contact region of a patch (cells with p > 0) as an equivalent ellipse: a/b from the
// extents of those cells (to their faces), size from their area (pi a b = cells dA); the area
// centroid and the normal force sum p dA. All zero when no cell carries pressure.
struct ContactEllipse {
  int cells = 0;
  double semi_axis_x_m = 0.0, semi_axis_s_m = 0.0;
  double centroid_x_m = 0.0, centroid_s_m = 0.0;
  double normal_force_N = 0.0;
};
ContactEllipse EstimateContactEllipse(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa);

// Solves the tangential problem by FASTSIM.
//   grid: the patch grid (cells k = j*nx + i).
//   pressure_Pa: size grid.cells(), p >= 0 [Pa]; cells with p <= 0 are outside the contact
//     (zero traction, stick = -1).
//   in: per-cell creepages (size grid.cells()), speed V > 0 [m/s], friction mu > 0.
//   patch (optional out): the patch quantities used.
// Returns tractions [Pa], slip velocities [m/s], stick flags and totals per tangential_types.h;
// status kConverged (one direct sweep, iterations = 1) or kNoContact when no cell carries
// pressure. Throws std::invalid_argument on mismatched sizes, non-finite input, V <= 0,
// mu <= 0, or invalid options (message names the field and value).
TangentialSolution SolveFastsim(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                const RollingInput& in, const FastsimOptions& opt,
                                FastsimPatch* patch = nullptr);

// Combined G [Pa] and nu of two bodies (Kalker): 2/G = 1/G1 + 1/G2, nu = (G/2)(nu1/G1 + nu2/G2).
struct CombinedElastic {
  double shear_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
};
CombinedElastic CombineElastic(const Material& a, const Material& b);

}  // namespace railwear
