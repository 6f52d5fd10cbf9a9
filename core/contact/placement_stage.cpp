// The placement stage of SolveContact (placement_stage.h).
#include "core/contact/placement_stage.h"

#include <cmath>

#include <fmt/format.h>

#include "core/contact/damage.h"

#include "core/numerics/input_error.h"

namespace railwear::internal {

void CheckContactProblem(const ContactProblem& problem) {
  if (problem.load.vertical_force_N.has_value() == problem.load.approach_m.has_value()) {
    throw InputError("contact load: give exactly one of the vertical force and the approach");
  }
  if (!(problem.placement.rolling_radius_m > 0)) {
    throw InputError(fmt::format("wheel rolling radius = {} mm: expected a positive radius",
                                 problem.placement.rolling_radius_m * 1e3));
  }
  const std::string invalid = problem.solver.Validate();
  if (!invalid.empty()) throw InputError("normal solver options: " + invalid);
  if (const auto lim =
          PressureLimitOf(problem.pressure_limit, problem.wheel_material, problem.rail_material)) {
    if (!(*lim > 0.0) || !std::isfinite(*lim)) {
      throw InputError(fmt::format(
          "pressure limit ({}) = {} MPa: expected a positive finite pressure (with \"hardness\", "
          "give materials.rail.hardness_MPa)",
          ToString(problem.pressure_limit.kind), *lim * 1e-6));
    }
    if (problem.model.kind == ModelKind::kHertz) {
      throw InputError(
          "a pressure limit needs a patch grid: use the halfspace, conformal or auto model, not "
          "hertz (the analytic ellipse has no plastic cells)");
    }
  }
}

void CheckRollingProblem(const ContactProblem& problem, bool hertz_tread) {
  if (problem.rolling && problem.model.kind == ModelKind::kHertz && !hertz_tread) {
    throw InputError(
        "rolling contact with the hertz model is the fast tread path (hertz_tread.h); a patch "
        "grid needs the halfspace, conformal or auto model");
  }
  if (problem.rolling && problem.damage && !(problem.rail_material.shear_yield_Pa > 0)) {
    throw InputError(
        fmt::format("materials.rail.shear_yield_MPa is missing: expected {}", kShearYieldExpected));
  }
  if (problem.rolling &&
      !(problem.rolling->motion.speed_m_s > 0 && problem.rolling->friction > 0)) {
    throw InputError(
        fmt::format("rolling contact: speed = {} m/s and friction = {}: expected both > 0",
                    problem.rolling->motion.speed_m_s, problem.rolling->friction));
  }
}

WheelPose PoseOf(const ContactProblem& problem) {
  return {problem.placement.lateral_shift_m, problem.placement.roll_rad,
          problem.placement.rolling_radius_m, problem.placement.yaw_rad};
}

WheelRailGeometry PlaceWheel(const ContactProblem& problem) {
  return WheelRailGeometry(problem.wheel_profile, problem.rail_profile, PoseOf(problem));
}

std::optional<std::string> NoContactBeforeGrid(const ContactProblem& problem,
                                               const WheelRailGeometry& geom) {
  if (!geom.has_overlap()) return "the wheel and rail profiles do not overlap laterally";
  const bool load_given = problem.load.vertical_force_N.has_value();
  if ((load_given && !(*problem.load.vertical_force_N > 0)) ||
      (!load_given && !(*problem.load.approach_m > 0))) {
    return load_given ? std::string("no load: the wheel only touches the rail")
                      : std::string("no contact: the approach leaves the profiles apart");
  }
  return std::nullopt;
}

}  // namespace railwear::internal
