// The rolling stage of SolveContact (rolling_stage.h).
#include "core/contact/rolling_stage.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/contact/damage.h"
#include "core/contact/fastsim.h"
#include "core/contact/kinematics.h"
#include "core/contact/rolling_patch.h"
#include "core/contact/tangential_method.h"
#include "core/numerics/check.h"

namespace railwear {

namespace {

// The rolling stage on every numerical patch: rigid slip per cell (from the wheel's motion or
// prescribed creepages), its patch average, and the tangential solution by the problem's method
// (the one seam: SolveTangential).
// reuse (optional): one entry per patch, see internal::RunRollingStage.
void SolveRolling(const ContactProblem& problem, const WheelRailGeometry& geom,
                  ContactResult* result, std::vector<ExactTangentialReuse>* reuse = nullptr) {
  const RollingOptions& o = *problem.rolling;
  result->pitch_velocity_rad_s = o.motion.pitch_velocity_rad_s.value_or(
      -o.motion.speed_m_s / problem.placement.rolling_radius_m);
  if (reuse != nullptr) reuse->resize(result->patches.size());
  for (size_t k = 0; k < result->patches.size(); ++k) {
    PatchResult& patch = result->patches[k];
    const RollingInput in = o.creepage
                                ? RigidSlipFromCreepage(patch.grid, patch.pressure_Pa, *o.creepage,
                                                        o.motion.speed_m_s, o.friction)
                                : RigidSlipFromMotion(geom, patch.grid, o.motion, o.friction);
    patch.rolling =
        internal::SolveRollingPatch(problem, patch, in, reuse != nullptr ? &(*reuse)[k] : nullptr);
  }
}

// The rolling stage with a prescribed total longitudinal force: the pitch velocity is solved for.
void SolveRollingForForce(const ContactProblem& problem, const WheelRailGeometry& geom,
                          ContactResult* result, RollingStageMemory* memory) {
  ContactProblem trial = problem;
  const RollingOptions& o = *problem.rolling;
  const double target = *o.longitudinal_force_N;
  std::vector<ExactTangentialReuse>* reuse = memory != nullptr ? &memory->patches : nullptr;
  auto fx = [&](double omega) {
    trial.rolling->motion.pitch_velocity_rad_s = omega;
    SolveRolling(trial, geom, result, reuse);
    return TotalForceX(*result);
  };
  const double tolerance = 1e-6 * o.friction * TotalNormalForce(*result);
  const double r0 = problem.placement.rolling_radius_m;
  const bool restart = memory != nullptr && memory->spin_up_creepage.has_value();
  const auto omega = SolvePitchVelocityForForce(fx, target, o.motion.speed_m_s, r0, tolerance,
                                                restart ? *memory->spin_up_creepage : 0.0,
                                                restart ? kPitchRestartStep : 1e-4);
  if (memory != nullptr) {
    memory->spin_up_creepage.reset();
    if (omega) memory->spin_up_creepage = -*omega * r0 / o.motion.speed_m_s - 1.0;
  }
  if (!omega) {
    result->status = SolverStatus::kNotConverged;
    result->message = fmt::format(
        "the longitudinal force {:.1f} N cannot be carried: friction limits it to about "
        "{:.1f} N here (mu F_n = {:.1f} N)",
        target, std::abs(TotalForceX(*result)), o.friction * TotalNormalForce(*result));
    return;
  }
  fx(*omega);  // leave the result at the solution
}

}  // namespace

double TotalForceX(const ContactResult& r) {
  double fx = 0.0;
  for (const auto& p : r.patches) fx += p.rolling ? p.rolling->tangential.force_x_N : 0.0;
  return fx;
}

double TotalNormalForce(const ContactResult& r) {
  double fn = 0.0;
  for (const auto& p : r.patches) fn += p.normal_force_N;
  return fn;
}

std::optional<double> SolvePitchVelocityForForce(const std::function<double(double)>& fx,
                                                 double target_N, double speed_m_s,
                                                 double rolling_radius_m, double tolerance_N,
                                                 double start_c, double first_step_c) {
  RAILWEAR_CHECK(first_step_c > 0.0);
  auto omega_of = [&](double c) { return -speed_m_s * (1.0 + c) / rolling_radius_m; };
  auto g = [&](double c) { return fx(omega_of(c)) - target_N; };
  // Bracket: step the creepage c outward from start_c (doubling) in the direction that moves fx
  // toward the target, until g changes sign.
  double a = start_c, ga = g(start_c);
  if (std::abs(ga) <= tolerance_N) return omega_of(start_c);
  const double dir = ga < 0 ? 1.0 : -1.0;
  double b = a, gb = ga;
  for (double step = first_step_c;; step *= 2.0) {
    if (step > 1.0) return std::nullopt;  // beyond adhesion: the force never reaches the target
    b = start_c + dir * step;
    gb = g(b);
    if ((gb > 0) != (ga > 0)) break;
    a = b;
    ga = gb;
  }
  double lo = std::min(a, b), hi = std::max(a, b);
  double f_lo = lo == a ? ga : gb, f_hi = hi == a ? ga : gb;
  // Now f_lo < 0 < f_hi on [lo, hi]: bisection with secant (regula falsi, Illinois) steps.
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    double c = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(c > lo && c < hi)) c = 0.5 * (lo + hi);
    const double f = g(c);
    if (std::abs(f) <= tolerance_N || hi - lo < 1e-14) return omega_of(c);
    if (f < 0) {
      lo = c;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = c;
      f_hi = f;
      if (side == +1) f_lo *= 0.5;
      side = +1;
    }
  }
  return omega_of(0.5 * (lo + hi));
}

void ApplyRolling(const ContactProblem& problem, const WheelRailGeometry& geometry,
                  ContactResult* result) {
  RAILWEAR_CHECK(problem.rolling.has_value());
  SolveRolling(problem, geometry, result);
}

namespace internal {

RollingPatch SolveRollingPatch(const ContactProblem& problem, const PatchResult& patch,
                               const RollingInput& in, ExactTangentialReuse* reuse) {
  RollingPatch rolling;
  rolling.creepage = AverageCreepage(patch.grid, patch.pressure_Pa, in);
  rolling.tangential =
      SolveTangential(problem.tangential, problem.model.accuracy, patch.grid, patch.pressure_Pa, in,
                      problem.wheel_material, problem.rail_material, &rolling.choice, reuse,
                      problem.tangential_tolerance);
  // The patch's equivalent ellipse (the semi-axes FASTSIM uses), reported with the patch.
  const ContactEllipse used = EstimateContactEllipse(patch.grid, patch.pressure_Pa);
  rolling.semi_axis_x_m = used.semi_axis_x_m;
  rolling.semi_axis_s_m = used.semi_axis_s_m;
  if (problem.damage && rolling.tangential.status == SolverStatus::kConverged) {
    PatchDamageInput d;
    d.force_x_N = rolling.tangential.force_x_N;
    d.force_y_N = rolling.tangential.force_s_N;
    d.normal_force_N = patch.normal_force_N;
    d.xi = rolling.creepage.xi;
    d.eta = rolling.creepage.eta;
    d.spin_moment_Nm = rolling.tangential.spin_moment_Nm;
    d.spin_per_m = rolling.creepage.spin_per_m;
    d.peak_pressure_Pa = patch.p_max_Pa;  // the patch's own peak (issue 16), not Hertz's p0
    d.shear_yield_Pa = problem.rail_material.shear_yield_Pa;
    rolling.damage = CalcPatchDamage(d);
  }
  return rolling;
}

void RunRollingStage(const ContactProblem& problem, const WheelRailGeometry& geom,
                     ContactResult* result, RollingStageMemory* memory) {
  if (problem.rolling->longitudinal_force_N) {
    SolveRollingForForce(problem, geom, result, memory);
  } else {
    SolveRolling(problem, geom, result, memory != nullptr ? &memory->patches : nullptr);
  }
}

}  // namespace internal

}  // namespace railwear
