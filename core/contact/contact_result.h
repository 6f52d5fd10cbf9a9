// What SolveContact returns: per patch the pressure on its grid (or the Hertz ellipse), the
// forces and, with rolling contact, the tangential solution and damage; totals and stage times.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/damage.h"
#include "core/contact/hertz.h"
#include "core/contact/kinematics.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_method.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear {

// Rolling-contact results of one patch.
struct RollingPatch {
  Creepage creepage;  // pressure-weighted patch average of the rigid creepage (kinematics.h)
  TangentialSolution tangential;
  TangentialChoice choice;  // the solver that ran (for tangential = "auto": chosen, and why)
  double semi_axis_x_m = 0.0, semi_axis_s_m = 0.0;  // of the contact, as the solver used them
  std::optional<PatchDamage> damage;                // when the damage effect was asked for
};

struct PatchResult {
  double area_m2 = 0.0;
  double p_max_Pa = 0.0;
  double normal_force_N = 0.0;  // magnitude of the resultant of p over the patch
  // The pressure's resultant on the rail in the rail frame (the creep forces' part is in
  // rolling->tangential, on the wheel; contact_forces.h sums both on the rail):
  double vertical_force_N = 0.0;  // on the rail, positive downward (+z)
  double lateral_force_N = 0.0;   // on the rail, positive toward +y (field side)
  // Pressure centre mapped onto the rail profile, rail profile coordinates [m].
  Eigen::Vector2d contact_point_yz_m = Eigen::Vector2d::Zero();
  // Longitudinal position of the pressure centre [m], R, from the wheel profile origin's
  // cross-section (the axle's, without yaw): a yawed wheel touches ahead of or behind its axle.
  double contact_x_m = 0.0;
  // Angle of the resultant force on the rail against the vertical [rad]: atan2(lateral,
  // vertical). Flange-root and gauge-corner contact push the rail toward the field side (+y) and
  // have large positive angles (40-70 degrees); tread contact a few degrees.
  double contact_angle_rad = 0.0;
  int cells = 0;
  int cells_in_contact = 0;
  // With a pressure limit p_lim (ContactSetup::pressure_limit): the cells at p_lim (plastic),
  // their area (whole cells) [m^2] and the normal load they carry, sum of p A over them [N] (a
  // part of normal_force_N). 0 without a limit.
  int plastic_cells = 0;
  double plastic_area_m2 = 0.0;
  double plastic_force_N = 0.0;
  PatchGrid grid;                       // empty for the Hertz model
  Eigen::VectorXd pressure_Pa;          // per grid cell
  std::optional<HertzSolution> hertz;   // the Hertz model's ellipse
  std::optional<RollingPatch> rolling;  // when the problem asked for rolling contact
  // The model this patch was solved with ("hertz", "halfspace", "conformal+boussinesq", ...;
  // model_selection.h PatchModelLabel), and with kind = auto why it was chosen (empty otherwise).
  std::string model;
  std::string model_reason;
};

// L/V of one wheel and its check against Nadal's limit (core/contact/contact_forces.h).
// A wheel is in flange contact when its steepest patch is steeper than this: Nadal's
// flange-climb limit applies there.
inline constexpr double kFlangeContactAngle_rad = 45.0 * 3.14159265358979323846 / 180.0;

struct FlangeClimbCheck {
  // |net lateral force on the rail| / net vertical force on the rail, both in R (0 without a
  // positive vertical force).
  double l_over_v = 0.0;
  double contact_angle_rad = 0.0;     // of the steepest patch (largest contact angle)
  std::optional<double> friction;     // the scene's mu; absent for normal contact
  std::optional<double> nadal_limit;  // absent without friction or below atan(mu)
  // L/V > Nadal's limit in flange contact (contact_angle_rad >= kFlangeContactAngle_rad):
  // flange climb possible. Below, on the tread or the gauge corner, a wheel whose L/V passes the
  // limit at its angle slides up onto its flange: that is reported (l_over_v, nadal_limit), but
  // it is no climb.
  bool exceeded = false;
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
  // The pressure limit p_lim [Pa] the normal solve bounded the pressure by (absent: elastic),
  // and the sums of the patches' plastic cells, area and load (PatchResult).
  std::optional<double> pressure_limit_Pa;
  int plastic_cells = 0;
  double plastic_area_m2 = 0.0;
  double plastic_force_N = 0.0;
  // Sums of the patches' vertical_force_N and lateral_force_N: the pressure's part only; the net
  // forces with the creep parts are TotalForcesOnRail (core/contact/contact_forces.h).
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
  // The vertical balance (with a prescribed vertical load and rolling contact): iterations of
  // the normal-tangential loop that made the net vertical force on the rail (pressure and creep
  // forces) equal the load, and its final |V_net - Q| / Q (0 without the balance).
  int balance_iterations = 0;
  double balance_residual = 0.0;
  FlangeClimbCheck climb;  // L/V and Nadal's limit of this wheel
};

}  // namespace railwear
