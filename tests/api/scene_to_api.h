// Test support: a contact scene (app/scene.h) posed through the C API's calls, field by field,
// so that the C API's result can be compared with the CLI's (SolveContactCase(ToContactCase)).
// The wheel profile goes in as points, the rail as its spec (a built-in or a file) with the cant
// in rw_geometry, so both profile paths and the cant path are exercised.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/scene.h"
#include "core/contact/normal_solver.h"
#include "railwear/railwear.h"

namespace railwear::test {

// Fails the current test (ADD_FAILURE) with the handle's message when a call does not return
// RW_OK.
#define RW_EXPECT_OK(p, call)                                                           \
  do {                                                                                  \
    const rw_status rw_status_ = (call);                                                \
    EXPECT_EQ(rw_status_, RW_OK) << #call << ": " << rw_status_name(rw_status_) << ": " \
                                 << rw_last_error(p);                                   \
  } while (0)

inline rw_material ToApi(const Material& m) {
  rw_material out{};
  out.struct_size = sizeof out;
  rw_init_material(&out);
  out.youngs_modulus_Pa = m.youngs_modulus_Pa;
  out.poisson_ratio = m.poisson_ratio;
  out.hardness_Pa = m.hardness_Pa;
  out.shear_yield_Pa = m.shear_yield_Pa;
  return out;
}

// The rail's spec as the C API reads it: built-ins as written, files resolved against the
// scene's directory (the scene reader's rule).
inline std::string RailSpec(const app::Scene& scene) {
  const std::string& spec = scene.rail_profile_spec;
  if (spec.rfind("builtin:", 0) == 0 || spec.rfind("circle:", 0) == 0 ||
      spec.rfind("groove:", 0) == 0) {
    return spec;
  }
  return (std::filesystem::path(scene.path).parent_path() / spec).string();
}

// Sets `p` up with the scene's profiles, materials, model, constants, friction, geometry and
// state. The handle's kind must match the scene (scene.wheelset: RW_PROBLEM_WHEELSET).
inline void SetUpFromScene(rw_problem* p, const app::Scene& scene) {
  const ContactProblem& problem = scene.problem;
  const std::vector<Eigen::Vector2d>& wheel = problem.wheel_profile.points();
  std::vector<double> yz;
  for (const Eigen::Vector2d& q : wheel) {
    yz.push_back(q.x());
    yz.push_back(q.y());
  }
  RW_EXPECT_OK(p, rw_set_profile_points(p, RW_BODY_WHEEL, yz.data(), wheel.size()));
  RW_EXPECT_OK(p, rw_set_profile_file(p, RW_BODY_RAIL, RailSpec(scene).c_str()));

  const rw_material wm = ToApi(problem.wheel_material), rm = ToApi(problem.rail_material);
  RW_EXPECT_OK(p, rw_set_materials(p, &wm, &rm));

  rw_model m{};
  m.struct_size = sizeof m;
  rw_init_model(&m);
  const ModelOptions& mo = problem.model;
  switch (mo.kind) {
    case ModelKind::kHertz:
      m.kind = RW_MODEL_HERTZ;
      break;
    case ModelKind::kHalfspace:
      m.kind = RW_MODEL_HALFSPACE;
      break;
    case ModelKind::kConformal:
      m.kind = RW_MODEL_CONFORMAL;
      break;
    case ModelKind::kAuto:
      m.kind = RW_MODEL_AUTO;
      m.kernel = mo.kernel == KernelModel::kBoussinesq ? RW_KERNEL_BOUSSINESQ : RW_KERNEL_GOLUBENKO;
      break;
    case ModelKind::kCustom:
      m.kind = RW_MODEL_CUSTOM;
      m.geometry =
          mo.geometry == GeometryModel::kPlanar ? RW_GEOMETRY_PLANAR : RW_GEOMETRY_CONFORMAL;
      m.kernel = mo.kernel == KernelModel::kBoussinesq ? RW_KERNEL_BOUSSINESQ : RW_KERNEL_GOLUBENKO;
      break;
  }
  m.accuracy = static_cast<int>(mo.accuracy);
  m.tangential = static_cast<int>(problem.tangential);
  if (scene.tangential) m.effects |= RW_EFFECT_TANGENTIAL;
  if (scene.damage) m.effects |= RW_EFFECT_DAMAGE;
  if (problem.rolling && problem.rolling->coupling) m.effects |= RW_EFFECT_COUPLING;
  if (mo.cell_dx_m) m.cell_dx_m = *mo.cell_dx_m;
  if (mo.cell_ds_m) m.cell_ds_m = *mo.cell_ds_m;
  // The normal solver's stopping rule (API 1.5): the criterion, and the tolerance only when it is
  // not the criterion's own (0 stands for that), as a caller would set them.
  const bool strict = problem.solver.criterion == NormalStopCriterion::kGapResidual;
  m.normal_criterion = strict ? RW_NORMAL_GAP_RESIDUAL : RW_NORMAL_PRESSURE_UPDATE;
  const double own_tolerance = strict ? kStrictNormalTolerance : kDefaultNormalTolerance;
  if (problem.solver.tolerance != own_tolerance) m.normal_tolerance = problem.solver.tolerance;
  if (problem.tangential_tolerance != kDefaultExactTangentialTolerance) {
    m.tangential_tolerance = problem.tangential_tolerance;
  }
  RW_EXPECT_OK(p, rw_set_model(p, &m));

  rw_influence_constants k{};
  k.struct_size = sizeof k;
  rw_init_influence_constants(&k);
  const InfluenceConstants& c = mo.constants;
  k.c_f = c.c_f;
  k.c_z = c.c_z;
  k.c_s = c.c_s;
  if (c.separate) {
    k.separate = 1;
    k.convex_c_f = c.separate->convex.c_f;
    k.convex_c_z = c.separate->convex.c_z;
    k.convex_c_s = c.separate->convex.c_s;
    k.concave_c_f = c.separate->concave.c_f;
    k.concave_c_z = c.separate->concave.c_z;
    k.concave_c_s = c.separate->concave.c_s;
  }
  RW_EXPECT_OK(p, rw_set_influence_constants(p, &k));
  if (scene.friction) RW_EXPECT_OK(p, rw_set_friction(p, *scene.friction));
  switch (problem.pressure_limit.kind) {
    case PressureLimitKind::kNone:
      break;
    case PressureLimitKind::kHardness:
      RW_EXPECT_OK(p, rw_set_pressure_limit(p, RW_PRESSURE_LIMIT_HARDNESS, NAN));
      break;
    case PressureLimitKind::kValue:
      RW_EXPECT_OK(p, rw_set_pressure_limit(p, RW_PRESSURE_LIMIT_VALUE,
                                            problem.pressure_limit.value_Pa));
      break;
  }

  rw_geometry g{};
  g.struct_size = sizeof g;
  rw_init_geometry(&g);
  g.rolling_radius_m = problem.placement.rolling_radius_m;
  g.rail_cant = scene.cant_ratio;
  if (scene.wheelset) {
    g.gauge_m = scene.track->gauge_m;
    g.gauge_height_m = scene.track->gauge_height_m;
    g.flange_back_distance_m = scene.wheelset->flange_back_distance_m;
    g.flange_back_position_m = scene.wheelset->flange_back_position_m;
  }
  RW_EXPECT_OK(p, rw_set_geometry(p, &g));

  rw_state s{};
  s.struct_size = sizeof s;
  rw_init_state(&s);
  if (scene.wheelset) {
    s.lateral_m = scene.wheelset->lateral_displacement_m;
    s.yaw_rad = scene.wheelset->yaw_rad;
    s.roll_rad = scene.wheelset->roll_rad;
  } else {
    s.lateral_m = problem.placement.lateral_shift_m;
    s.yaw_rad = problem.placement.yaw_rad;
    s.roll_rad = problem.placement.roll_rad;
  }
  if (problem.load.vertical_force_N) s.vertical_force_N = *problem.load.vertical_force_N;
  if (problem.load.approach_m) s.approach_m = *problem.load.approach_m;
  if (problem.rolling) {
    const WheelMotion& w = problem.rolling->motion;
    s.speed_m_s = w.speed_m_s;
    if (w.pitch_velocity_rad_s) s.pitch_velocity_rad_s = *w.pitch_velocity_rad_s;
    s.lateral_velocity_m_s = w.lateral_velocity_m_s;
    s.yaw_velocity_rad_s = w.yaw_velocity_rad_s;
    if (problem.rolling->longitudinal_force_N) {
      s.longitudinal_force_N = *problem.rolling->longitudinal_force_N;
    }
    if (problem.rolling->creepage) {
      s.flags |= RW_STATE_CREEPAGE;
      s.creepage_xi = problem.rolling->creepage->xi;
      s.creepage_eta = problem.rolling->creepage->eta;
      s.creepage_spin_per_m = problem.rolling->creepage->spin_per_m;
    }
  }
  RW_EXPECT_OK(p, rw_set_state(p, &s));
}

}  // namespace railwear::test
