// What SolveContact is asked: the contact set-up shared by every contact of a study (materials,
// model, solver, what the rolling stage computes) and one case's profiles, placement, load and
// motion. Units are SI.
#pragma once

#include <optional>

#include "core/contact/contact_types.h"
#include "core/contact/kinematics.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_method.h"
#include "core/profile/profile.h"

namespace railwear {

// Where the wheel stands on the rail (single wheel; wheelsets come with rolling contact).
struct WheelPlacement {
  double lateral_shift_m = 0.0;  // y of the wheel profile origin in the rail frame [m]
  double roll_rad = 0.0;         // rotation about x; positive turns +y toward +z (field side down)
  double rolling_radius_m = 0.46;  // wheel radius at the wheel profile's z = 0 [m]
  // About +z (down) through the wheel profile origin: positive turns the nose toward +y. In the
  // contact geometry (the yawed wheel touches ahead of or behind its axle, WheelRailGeometry)
  // and in the rigid slip (kinematics.h). |yaw| < 0.1 rad.
  double yaw_rad = 0.0;
};

// Prescribe exactly one of the two.
struct ContactLoad {
  std::optional<double> vertical_force_N;  // > 0, pressing the wheel down onto the rail
  std::optional<double> approach_m;        // vertical approach from first contact
};

// The contact set-up: what stays the same for every contact of a scene or a wear study. Both
// ContactProblem and WearStudy (wear/wear_simulation.h) are a ContactSetup plus their own
// part, so a wear load case copies it whole and fills in only placement, load and motion.
struct ContactSetup {
  Material wheel_material;
  Material rail_material;  // hardness_Pa for wear, shear_yield_Pa for the damage effect
  ModelOptions model;
  NormalSolverOptions solver;
  // The rolling stage's tangential solver (used when a problem carries RollingOptions).
  TangentialMethod tangential = TangentialMethod::kFastsim;
  // The exact tangential solver's stopping tolerance, relative to mu p_max (the largest change
  // one local solve would make to any cell's traction; ExactTangentialOptions::tolerance), > 0.
  // The default keeps the creep forces' 4 significant digits with margin (tangential_exact.cpp);
  // FASTSIM ignores it. A scene's [model] tangential_tolerance.
  double tangential_tolerance = kDefaultExactTangentialTolerance;
  // The elastic-perfectly-plastic pressure limit of the normal solve (contact_types.h); none by
  // default. Needs a grid model (not kind = hertz).
  PressureLimit pressure_limit;
  // The "damage" effect: T-gamma, WLRM RCF damage, FI_surf, shakedown per rolling patch (and,
  // in a wear study, RCF damage per position).
  bool damage = false;

  // The set-up part of a ContactProblem or a WearStudy: `problem.setup() = study.setup();`.
  ContactSetup& setup() { return *this; }
  const ContactSetup& setup() const { return *this; }
};

// The rolling stage (the "tangential" effect): only run when a problem carries these options.
struct RollingOptions {
  WheelMotion motion;                // the wheel's motion, giving the rigid slip per cell ...
  std::optional<Creepage> creepage;  // ... or prescribed creepages about each patch's origin
  double friction = 0.3;             // mu > 0
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

// One contact: the set-up (base) and this case's profiles, placement, load and motion.
struct ContactProblem : ContactSetup {
  Profile wheel_profile;  // in the wheel profile frame
  Profile rail_profile;   // in the rail profile frame (cant already applied)
  WheelPlacement placement;
  ContactLoad load;
  std::optional<RollingOptions> rolling;  // absent: normal contact only, nothing else computed
};

}  // namespace railwear
