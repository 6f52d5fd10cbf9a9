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
//   FI_surf = mu_eff - k / p_max,
// with p_max the patch's own peak pressure [Pa] > 0 (issue 16). Ekberg's form writes p0 =
// 3 F_n/(2 pi a b), the Hertz peak; for a Hertzian patch the two agree, but a conformal or
// non-elliptic patch (and one capped by the pressure limit) has its own peak, which is what the
// surface layer carries, so railwear reads that. FI_surf > 0 predicts surface-initiated RCF (the
// load lies beyond the surface shakedown limit p_max/k = 1/mu_eff). k > 0 [Pa]. Throws
// std::invalid_argument otherwise.
double SurfaceFatigueIndex(double traction_coefficient, double peak_pressure_Pa,
                           double shear_yield_Pa);
// The Hertz peak pressure p0 = 3 F_n / (2 pi a b) [Pa] of a patch with semi-axes a, b [m] > 0
// carrying F_n > 0 [N]. Throws std::invalid_argument otherwise.
double HertzPeakPressure(double semi_axis_x_m, double semi_axis_y_m, double normal_force_N);

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
// p0 > 0 [Pa] peak pressure (the patch's own p_max, as FI_surf), k > 0 [Pa] shear yield, mu_eff >=
// 0. Throws std::invalid_argument otherwise.
ShakedownPoint CalcShakedownPoint(double p0_Pa, double shear_yield_Pa, double traction_coefficient);

// Spin's part of the frictional work per metre rolled [N = J/m]: |M_z phi|, M_z the spin moment
// [N m], phi the spin creepage [1/m]. T-gamma leaves it out (the WLRM is calibrated without
// it); on a spin-dominated flange patch it can be most of the work, so it is reported next to
// T-gamma as the share spin / (T-gamma + spin) of the total (issue 16, point 7).
double SpinWork(double spin_moment_Nm, double spin_per_m);

// All indices of one patch from its totals.
struct PatchDamageInput {
  double force_x_N = 0.0, force_y_N = 0.0;  // creep forces [N]
  double normal_force_N = 0.0;              // F_n > 0 [N]
  double xi = 0.0, eta = 0.0;               // patch creepages [-]
  double spin_moment_Nm = 0.0;              // M_z [N m] (either body's: only |M_z phi| enters)
  double spin_per_m = 0.0;                  // phi [1/m]
  double peak_pressure_Pa = 0.0;            // the patch's own p_max > 0 [Pa]
  double shear_yield_Pa = 0.0;              // k [Pa]
};
struct PatchDamage {
  double t_gamma_N = 0.0;             // [N = J/m]
  double spin_work_N = 0.0;           // |M_z phi| [N = J/m]
  double spin_share = 0.0;            // spin_work / (t_gamma + spin_work) [-]; 0 when both are 0
  double wlrm_damage = 0.0;           // per axle pass [-]
  double traction_coefficient = 0.0;  // |F_t| / F_n
  double fi_surf = 0.0;               // Ekberg's FI_surf [-]
  ShakedownPoint shakedown;           // with the patch's own p_max as p0
};
PatchDamage CalcPatchDamage(const PatchDamageInput& in);

}  // namespace railwear
