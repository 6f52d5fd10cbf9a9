// SolveContact: one wheel on one rail, end to end. Placement -> contact search -> patch grids
// and gaps -> influence operators -> normal solve -> patch results.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/damage.h"
#include "core/contact/hertz.h"
#include "core/contact/kinematics.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "core/contact/patch_grid.h"
#include "core/profile/profile.h"

namespace railwear {

// Where the wheel stands on the rail (single wheel; wheelsets come with rolling contact).
struct WheelPlacement {
  double lateral_shift_m = 0.0;   // y of the wheel profile origin in the rail frame [m]
  double roll_rad = 0.0;          // rotation about x; positive turns +y toward +z (field side down)
  double rolling_radius_m = 0.46; // wheel radius at the wheel profile's z = 0 [m]
};

// Prescribe exactly one of the two.
struct ContactLoad {
  std::optional<double> vertical_force_N;  // > 0, pressing the wheel down onto the rail
  std::optional<double> approach_m;        // vertical approach from first contact
};

// Which tangential solver a rolling contact uses.
enum class TangentialMethod {
  kFastsim,  // Kalker's simplified theory, strip by strip (core/contact/fastsim.h)
  kExact,    // steady rolling with half-space tangential influence (tangential_exact.h)
};
std::string_view ToString(TangentialMethod v);
std::optional<TangentialMethod> TangentialMethodFromString(std::string_view s);

// The rolling stage (the "tangential" effect): only run when a problem carries these options.
struct RollingOptions {
  TangentialMethod method = TangentialMethod::kFastsim;
  WheelMotion motion;                 // the wheel's motion, giving the rigid slip per cell ...
  std::optional<Creepage> creepage;   // ... or prescribed creepages about each patch's origin
  double friction = 0.3;              // mu > 0
  bool damage = false;  // the "damage" effect: T-gamma, WLRM RCF damage, FI_surf, shakedown
  // Prescribed total longitudinal creep force on the wheel [N] (> 0 traction: the rail pushes
  // the wheel forward; < 0 braking) instead of a prescribed pitch velocity: the pitch velocity
  // is found so that the patches' F_x add up to it. Not with prescribed creepages.
  std::optional<double> longitudinal_force_N;
  // The "coupling" effect: the tangential tractions change the normal gap through the cross
  // terms of seed eq. 4 (core/contact/coupling.h); normal and tangential solutions are iterated
  // until the pressure changes by less than coupling_tolerance of its maximum.
  bool coupling = false;
  double coupling_tolerance = 1e-6;
  int coupling_max_iterations = 50;
};

struct ContactProblem {
  Profile wheel_profile;  // in the wheel profile frame
  Profile rail_profile;   // in the rail profile frame (cant already applied)
  Material wheel_material;
  Material rail_material;
  WheelPlacement placement;
  ContactLoad load;
  ModelOptions model;
  NormalSolverOptions solver;
  std::optional<RollingOptions> rolling;  // absent: normal contact only, nothing else computed
};

// Rolling-contact results of one patch.
struct RollingPatch {
  Creepage creepage;  // pressure-weighted patch average of the rigid creepage (kinematics.h)
  TangentialSolution tangential;
  double semi_axis_x_m = 0.0, semi_axis_s_m = 0.0;  // of the contact, as the solver used them
  std::optional<PatchDamage> damage;                // when the damage effect was asked for
};

struct PatchResult {
  double area_m2 = 0.0;
  double p_max_Pa = 0.0;
  double normal_force_N = 0.0;    // magnitude of the resultant of p over the patch
  double vertical_force_N = 0.0;  // on the rail, positive downward (+z)
  double lateral_force_N = 0.0;   // on the rail, positive toward +y (field side)
  // Pressure centre mapped onto the rail profile, rail profile coordinates [m].
  Eigen::Vector2d contact_point_yz_m = Eigen::Vector2d::Zero();
  // Angle of the resultant force on the rail against the vertical [rad]: atan2(lateral,
  // vertical). Flange-root and gauge-corner contact push the rail toward the field side (+y) and
  // have large positive angles (40-70 degrees); tread contact a few degrees.
  double contact_angle_rad = 0.0;
  int cells = 0;
  int cells_in_contact = 0;
  PatchGrid grid;               // empty for the Hertz model
  Eigen::VectorXd pressure_Pa;  // per grid cell
  std::optional<HertzSolution> hertz;  // the Hertz model's ellipse
  std::optional<RollingPatch> rolling;  // when the problem asked for rolling contact
  // The model this patch was solved with ("hertz", "halfspace", "conformal+boussinesq", ...;
  // model_selection.h PatchModelLabel), and with kind = auto why it was chosen (empty otherwise).
  std::string model;
  std::string model_reason;
};

struct StageTime {
  std::string name;
  double seconds = 0.0;
};

struct ContactResult {
  SolverStatus status = SolverStatus::kNotConverged;
  std::string message;
  ModelOptions model;
  double approach_m = 0.0;
  int iterations = 0;
  double time_s = 0.0;
  double area_m2 = 0.0;
  double p_max_Pa = 0.0;
  double vertical_force_N = 0.0;
  double lateral_force_N = 0.0;
  std::vector<PatchResult> patches;
  std::vector<StageTime> stages;
  double pitch_velocity_rad_s = 0.0;  // of the rolling stage (0 without one)
  // The coupling effect: normal-tangential iterations, and the relative change coupling made to
  // the total area and the peak pressure against the uncoupled solution (0 without coupling).
  int coupling_iterations = 0;
  double coupling_area_change = 0.0;
  double coupling_p_max_change = 0.0;
};

// The rolling stage alone on a result of SolveContact (its normal patches): rigid slip, the
// tangential solution and, when asked, damage per patch. The pitch velocity used is stored in
// result->pitch_velocity_rad_s. problem.rolling must be set (and not hold a force target: that
// is SolveContact's and SolveWheelset's business).
// `geometry` is the problem's placed wheel and rail (to reuse it across repeated calls).
void ApplyRolling(const ContactProblem& problem, const WheelRailGeometry& geometry,
                  ContactResult* result);

// The pitch velocity Omega = -V (1 + c) / r0 for which fx(Omega) = target_N, with fx increasing
// in the spin-up creepage c (a driving wheel turns faster than it rolls). Brackets c outward up
// to |c| = 1, then bisection with secant steps to |fx - target| <= tolerance_N. nullopt when the
// target lies beyond the largest force the bracket reaches (beyond adhesion).
std::optional<double> SolvePitchVelocityForForce(const std::function<double(double)>& fx,
                                                 double target_N, double speed_m_s,
                                                 double rolling_radius_m, double tolerance_N);

// Throws InputError for inconsistent input (both or neither load given, non-positive radius,
// rolling contact asked of the Hertz model, which has no grid; damage without the rail's shear
// yield stress).
ContactResult SolveContact(const ContactProblem& problem);

}  // namespace railwear
