// Damage indices of one contact patch: the energy index T-gamma, the Whole Life Rail Model's
// rolling contact fatigue damage per axle pass, Ekberg's surface fatigue index and the position
// on Johnson's shakedown map (reference README §6; DESIGN.md §1 "Damage").
//
// Units: SI. T-gamma is a force [N] = energy dissipated per metre rolled [J/m]. Traction
// coefficient mu_eff = |F_t| / F_n [-]. Shear yield stress k [Pa].
#pragma once

#include <string_view>

namespace railwear {

// T-gamma = |F_x xi| + |F_y eta|  [N = J/m]. F_x, F_y the creep forces [N] (either body's: only
// magnitudes enter), xi, eta the patch creepages [-]. The spin term |M_z phi| is not included
// (the WLRM is calibrated on the two-term form).
double TGamma(double force_x_N, double force_y_N, double xi, double eta);

// Whole Life Rail Model RCF damage function for R260 rail (Burstow 2003, as used by Network Rail;
// reference README §6 gives the 15-20 J/m threshold range). Piecewise linear in T-gamma:
//   0                                  for T-gamma <= 15 J/m (threshold, the lower end),
//   rising to 1e-5 per axle at 65 J/m  (the peak),
//   falling to 0 at 175 J/m            (wear removes the cracks faster than they grow),
//   0 beyond.
// Returns damage per axle pass [-]; crack initiation when the accumulated damage reaches 1.
// Throws std::invalid_argument on a negative or non-finite T-gamma.
constexpr double kWlrmThreshold_N = 15.0;
constexpr double kWlrmPeak_N = 65.0;
constexpr double kWlrmPeakDamage = 1e-5;
constexpr double kWlrmWearOnly_N = 175.0;
double WlrmRcfDamage(double t_gamma_N);

// Ekberg, Kabo & Andersson (2002) surface fatigue index
//   FI_surf = mu_eff - 2 pi a b k / (3 F_n) = mu_eff - k / p0,
// with p0 = 3 F_n/(2 pi a b) the Hertz peak pressure. FI_surf > 0 predicts surface-initiated RCF
// (the load lies beyond the surface shakedown limit p0/k = 1/mu_eff). a, b semi-axes [m] > 0,
// F_n > 0 [N], k > 0 [Pa]. Throws std::invalid_argument otherwise.
double SurfaceFatigueIndex(double traction_coefficient, double semi_axis_x_m, double semi_axis_y_m,
                           double normal_force_N, double shear_yield_Pa);

// Regions of Johnson's shakedown map (point contact), by increasing load factor p0/k.
enum class ShakedownRegime { kElastic, kElasticShakedown, kPlasticShakedown, kRatchetting };
std::string_view ToString(ShakedownRegime v);

// What the damage effect needs and a scene lacks without materials.rail.shear_yield_MPa: the one
// wording of that message for scenes, contact problems and wear studies.
inline constexpr std::string_view kShearYieldExpected =
    "the rail's shear yield stress k in MPa for the damage effect (FI_surf and the shakedown map "
    "need it)";  // "elastic", "elastic shakedown", ...

// Limit curves used (Johnson, Contact Mechanics 1985, ch. 9; Ponter, Hearle & Johnson 1985 for
// point contact), a simplified, documented envelope:
//   elastic limit    E(mu) = min(3.2, 1/mu)   first yield: 3.2 = 1/0.31, the subsurface
//                                             Tresca maximum 0.31 p0 of frictionless point
//                                             contact (nu = 0.3); at the surface ~1/mu.
//   shakedown limit  S(mu) = min(4.7, 1/mu)   4.7: point-contact subsurface elastic shakedown
//                                             (frictionless); 1/mu: surface shakedown limit,
//                                             the line FI_surf = 0.
// Both subsurface values are held constant in mu (the exact subsurface limits fall gently with
// mu, so this is slightly optimistic below mu ~ 0.2); the envelope is continuous, unlike a switch
// from 4.7 to 1/mu at mu = 0.3. Above S the response is "plastic shakedown" (cyclic subsurface
// plasticity) where the subsurface branch binds (mu < 1/4.7) and "ratchetting" where the surface
// branch binds (mu >= 1/4.7), the region Ekberg's FI_surf > 0 flags.
constexpr double kElasticLimitPointContact = 3.2;
constexpr double kShakedownLimitPointContact = 4.7;
struct ShakedownPoint {
  double load_factor = 0.0;           // p0 / k [-]
  double traction_coefficient = 0.0;  // mu_eff [-]
  double elastic_limit = 0.0;         // E(mu_eff) [-]
  double shakedown_limit = 0.0;       // S(mu_eff) [-]
  double margin = 0.0;                // S(mu_eff) - p0/k; negative beyond shakedown
  ShakedownRegime regime = ShakedownRegime::kElastic;
};
// p0 > 0 [Pa] peak pressure, k > 0 [Pa] shear yield, mu_eff >= 0. Throws std::invalid_argument
// otherwise.
ShakedownPoint CalcShakedownPoint(double p0_Pa, double shear_yield_Pa, double traction_coefficient);

// All indices of one patch from its totals.
struct PatchDamageInput {
  double force_x_N = 0.0, force_y_N = 0.0;          // creep forces [N]
  double normal_force_N = 0.0;                      // F_n > 0 [N]
  double xi = 0.0, eta = 0.0;                       // patch creepages [-]
  double semi_axis_x_m = 0.0, semi_axis_y_m = 0.0;  // a, b [m]
  double shear_yield_Pa = 0.0;                      // k [Pa]
};
struct PatchDamage {
  double t_gamma_N = 0.0;             // [N = J/m]
  double wlrm_damage = 0.0;           // per axle pass [-]
  double traction_coefficient = 0.0;  // |F_t| / F_n
  double fi_surf = 0.0;               // Ekberg's FI_surf [-]
  ShakedownPoint shakedown;           // with p0 = 3 F_n / (2 pi a b)
};
PatchDamage CalcPatchDamage(const PatchDamageInput& in);

}  // namespace railwear
