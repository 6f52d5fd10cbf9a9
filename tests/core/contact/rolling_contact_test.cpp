// Rolling contact through SolveContact: the tangential stage runs only when asked, kinematic
// creepage varying across a conformal patch, and the damage stage.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/contact/contact_solver.h"
#include "core/contact/kinematics.h"
#include "core/contact/placement_stage.h"
#include "core/contact/rolling_stage.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// CONTACT's conformal example (reference README §3): rail gauge corner R 10 mm against a worn
// wheel flange root of -10.2 mm, wheel radius 460 mm, contact angle 45 degrees, G = 82 GPa,
// nu = 0.28, mu = 0.3, creepages xi = -0.004, eta = -0.0098995, phi = -0.0015372 /mm.
ContactProblem ConformalExample() {
  const double gamma = -std::numbers::pi / 4;  // tilts the contact normal toward the gauge side
  // Arcs of +-30 degrees about the contact point (a rail corner and a wheel fillet, not whole
  // circles, whose far sides a vertical approach would run into once tilted by 45 degrees).
  ContactProblem p;
  p.rail_profile = testing::ArcProfile(0.010, +1.0, 0.52).Transformed(gamma, {0.0, 0.0});
  p.wheel_profile = testing::ArcProfile(0.0102, +1.0, 0.52).Transformed(gamma, {0.0, 0.0});
  const double E = 82e9 * 2 * 1.28;
  p.wheel_material = p.rail_material = {E, 0.28};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 92e3 * std::cos(std::numbers::pi / 4);  // Fn about 92 kN
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.kernel = KernelModel::kBoussinesq;  // CONTACT's cases 2 and 4 use half-space influence
  p.model.accuracy = AccuracyPreset::kStandard;
  RollingOptions r;
  r.friction = 0.3;
  r.motion.speed_m_s = 10.0;
  // xi = -0.004 at the contact point from the pitch velocity; a lateral velocity dy/dt gives the
  // horizontal slip dy/dt, which along the 45-degree tangent is eta = dy/dt cos(45) / V. (The
  // example's creepages are prescribed on the unyawed geometry: a yaw would move the contact
  // point along the flange, yawed_wheel.h.)
  r.motion.pitch_velocity_rad_s = (-0.004 - 1.0) * r.motion.speed_m_s / 0.46;
  r.motion.lateral_velocity_m_s = -0.0098995 / std::cos(std::numbers::pi / 4) * r.motion.speed_m_s;
  p.rolling = r;
  return p;
}

TEST(RollingContact, NormalOnlyComputesNoTraction) {
  ContactProblem p = ConformalExample();
  p.rolling.reset();
  const ContactResult r = SolveContact(p);
  ASSERT_EQ(r.status, SolverStatus::kConverged);
  for (const auto& patch : r.patches) EXPECT_FALSE(patch.rolling.has_value());
  for (const auto& s : r.stages) EXPECT_NE(s.name, "tangential");
}

TEST(RollingContact, KinematicCreepageMatchesTheConformalExample) {
  const ContactResult r = SolveContact(ConformalExample());
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  ASSERT_EQ(r.patches.size(), 1u);
  const RollingPatch& rp = *r.patches[0].rolling;
  // At the first contact point (grid origin) the kinematics give the example's xi and eta; the
  // spin of the 45-degree contact, -sin(45)/r0 = -1.5372e-3 /mm, is the example's value. Over the
  // patch the rolling radius and angle vary, so the patch averages differ (that is the point).
  const PatchGrid& g = r.patches[0].grid;
  const int i0 = static_cast<int>(std::lround(-g.x0_m / g.dx_m));
  const int j0 = static_cast<int>(std::lround(-g.s0_m / g.ds_m));
  RollingInput in = RigidSlipFromMotion(
      WheelRailGeometry(ConformalExample().wheel_profile, ConformalExample().rail_profile,
                        WheelPose{0.0, 0.0, 0.46}),
      g, ConformalExample().rolling->motion, 0.3);
  EXPECT_NEAR(in.creep_x[g.Index(i0, j0)], -0.004, 1e-4);
  EXPECT_NEAR(in.creep_s[g.Index(i0, j0)], -0.0098995, 1e-4);
  EXPECT_LT(rp.creepage.spin_per_m, 0.0);
  EXPECT_EQ(rp.tangential.status, SolverStatus::kConverged);
  // Traction within the Coulomb bound everywhere.
  const auto& t = rp.tangential;
  for (int k = 0; k < t.traction_x_Pa.size(); ++k) {
    const double q = std::hypot(t.traction_x_Pa[k], t.traction_s_Pa[k]);
    EXPECT_LE(q, 0.3 * r.patches[0].pressure_Pa[k] * (1 + 1e-9) + 1e-6);
  }
}

TEST(RollingContact, VaryingCreepageChangesFxMarkedly) {
  // Issue 3: on the conformal gauge-corner patch, creepage varying cell by cell (rolling radius
  // and contact angle change across the patch) against the same creepage held constant (its
  // patch average): CONTACT's example goes from Fx = 8.96 kN (case 2) to 10.50 kN (case 4), +17 %.
  const ContactProblem varying = ConformalExample();
  const ContactResult rv = SolveContact(varying);
  ASSERT_EQ(rv.status, SolverStatus::kConverged);
  ContactProblem constant = varying;
  constant.rolling->creepage = rv.patches[0].rolling->creepage;  // the average, held constant
  const ContactResult rc = SolveContact(constant);
  ASSERT_EQ(rc.status, SolverStatus::kConverged);
  const double fx_v = rv.patches[0].rolling->tangential.force_x_N;
  const double fx_c = rc.patches[0].rolling->tangential.force_x_N;
  std::printf(
      "[ measured ] conformal example Fx: constant creepage %.0f N, varying %.0f N "
      "(%+.1f %%)\n",
      fx_c, fx_v, 100 * (fx_v / fx_c - 1));
  // Same sign, and |Fx| larger by more than 5 % with the varying creepage.
  EXPECT_GT(fx_v * fx_c, 0.0);
  EXPECT_GT(std::abs(fx_v), 1.05 * std::abs(fx_c));
}

TEST(RollingContact, DamageOnlyWhenAskedAndNeedsShearYield) {
  ContactProblem p = ConformalExample();
  EXPECT_FALSE(SolveContact(p).patches[0].rolling->damage.has_value());
  p.damage = true;
  EXPECT_THROW(SolveContact(p), InputError);  // no shear yield given
  p.rail_material.shear_yield_Pa = 350e6;
  const ContactResult r = SolveContact(p);
  ASSERT_TRUE(r.patches[0].rolling->damage.has_value());
  const PatchDamage& d = *r.patches[0].rolling->damage;
  EXPECT_GT(d.t_gamma_N, 0.0);
  EXPECT_NEAR(d.traction_coefficient,
              std::hypot(r.patches[0].rolling->tangential.force_x_N,
                         r.patches[0].rolling->tangential.force_s_N) /
                  r.patches[0].normal_force_N,
              1e-9);
}

TEST(RollingContact, PitchSearchFromANearbyStartFindsTheSameRoot) {
  // SolvePitchVelocityForForce started at a guess with a small first step (the restart of
  // RollingStageMemory): the same root to the force tolerance from a near guess, from a guess on
  // the wrong side and from one far off, in fewer evaluations from the near one. The force is a
  // saturating creep curve, F = mu Fn tanh(c / c_s) (Kalker's linear slope, then full slip).
  const double mu_fn = 3e3, c_s = 2e-3, v = 20.0, r0 = 0.46, tol = 1e-6 * mu_fn;
  for (const double target : {0.0, 0.4 * mu_fn, -0.9 * mu_fn}) {
    int calls = 0;
    auto fx = [&](double omega) {
      ++calls;
      const double c = -omega * r0 / v - 1.0;
      return mu_fn * std::tanh(c / c_s);
    };
    const double root = c_s * std::atanh(target / mu_fn);
    const auto cold = SolvePitchVelocityForForce(fx, target, v, r0, tol);
    const int cold_calls = calls;
    ASSERT_TRUE(cold.has_value());
    for (const double guess : {root + 3e-7, root - 5e-6, root + 0.05}) {
      calls = 0;
      const auto warm =
          SolvePitchVelocityForForce(fx, target, v, r0, tol, guess, kPitchRestartStep);
      ASSERT_TRUE(warm.has_value()) << target << " " << guess;
      EXPECT_NEAR(fx(*warm), target, tol) << target << " " << guess;
      // Both within tol of the target in force: 2 tol over the curve's slope at the root in c.
      const double slope = mu_fn / c_s * (1.0 - (target / mu_fn) * (target / mu_fn));
      EXPECT_NEAR(*warm, *cold, 2.0 * tol / slope * v / r0) << target << " " << guess;
      // (the cold search finds a zero target at its first evaluation, c = 0)
      if (guess == root + 3e-7 && target != 0.0) {
        EXPECT_LT(calls, cold_calls) << target;
      }
    }
  }
}

TEST(RollingContact, RollingStageMemoryAgreesWithFreshSolves) {
  // RollingStageMemory (rolling_stage.h): the exact solver's set-up kept per patch, its warm
  // start and the pitch search restarted at the last solution. On the conformal example under a
  // prescribed longitudinal force (the exact solver; the stage alone on the normal solution), the
  // rolling stage run with the memory of an earlier run agrees with a fresh run (set-ups rebuilt,
  // cold starts, the search from c = 0) to the pitch search's force tolerance; repeated on the same
  // pressure it finds the root at its first evaluation and needs no sweep there.
  ContactProblem p = ConformalExample();
  p.tangential = TangentialMethod::kExact;
  p.rolling->motion.lateral_velocity_m_s = 0.0;
  p.rolling->motion.pitch_velocity_rad_s.reset();
  const ContactResult normal_only = [&] {
    ContactProblem q = p;
    q.rolling.reset();
    return SolveContact(q);
  }();
  ASSERT_EQ(normal_only.status, SolverStatus::kConverged) << normal_only.message;
  double fn = 0.0;
  for (const auto& patch : normal_only.patches) fn += patch.normal_force_N;
  const double mu_fn = p.rolling->friction * fn;
  const double tol = 1e-6 * mu_fn;  // SolvePitchVelocityForForce's tolerance in the stage
  p.rolling->longitudinal_force_N = 0.4 * mu_fn;
  const WheelRailGeometry geom = internal::PlaceWheel(p);
  ContactResult fresh = normal_only;
  internal::RunRollingStage(p, geom, &fresh);
  ASSERT_EQ(fresh.status, SolverStatus::kConverged) << fresh.message;
  ContactResult kept = normal_only;
  RollingStageMemory memory;
  internal::RunRollingStage(p, geom, &kept, &memory);
  ASSERT_TRUE(memory.spin_up_creepage.has_value());
  ASSERT_EQ(memory.patches.size(), kept.patches.size());
  for (const auto& m : memory.patches) EXPECT_TRUE(m.setup.has_value() && m.last.has_value());
  internal::RunRollingStage(p, geom, &kept, &memory);  // again, from the memory
  ASSERT_EQ(kept.status, SolverStatus::kConverged) << kept.message;
  EXPECT_NEAR(TotalForceX(fresh), 0.4 * mu_fn, tol);
  EXPECT_NEAR(TotalForceX(kept), 0.4 * mu_fn, tol);
  // The pitch velocities: within the force tolerance over the creep curve's slope, at least
  // mu Fn / 1 (the search's whole range of c); measured far closer.
  const double v = p.rolling->motion.speed_m_s, r0 = p.placement.rolling_radius_m;
  EXPECT_NEAR(kept.pitch_velocity_rad_s, fresh.pitch_velocity_rad_s, 2.0 * tol / mu_fn * v / r0);
  ASSERT_EQ(kept.patches.size(), fresh.patches.size());
  for (size_t k = 0; k < kept.patches.size(); ++k) {
    const TangentialSolution& a = kept.patches[k].rolling->tangential;
    const TangentialSolution& b = fresh.patches[k].rolling->tangential;
    EXPECT_EQ(a.iterations, 0) << k;  // the warm start is the solution already
    EXPECT_NEAR(a.force_x_N, b.force_x_N, 2.0 * tol) << k;
    EXPECT_NEAR(a.force_s_N, b.force_s_N, 2.0 * tol) << k;
  }
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

TEST(RollingContact, PrescribedLongitudinalForceUpToFullSliding) {
  // Issue 3: a total longitudinal force instead of a pitch velocity, robust up to full sliding:
  // the pitch velocity is found so that F_x meets the target; beyond adhesion it is a status,
  // not an exception.
  ContactProblem p = ConformalExample();
  p.rolling->motion.lateral_velocity_m_s = 0.0;
  p.rolling->motion.pitch_velocity_rad_s.reset();
  const ContactResult free_rolling = SolveContact(p);
  double fn = 0.0;
  for (const auto& patch : free_rolling.patches) fn += patch.normal_force_N;
  const double mu_fn = 0.3 * fn;
  for (double share : {-0.98, -0.5, 0.2, 0.9, 0.99}) {
    p.rolling->longitudinal_force_N = share * mu_fn;
    const ContactResult r = SolveContact(p);
    ASSERT_EQ(r.status, SolverStatus::kConverged) << share << ": " << r.message;
    double fx = 0.0;
    for (const auto& patch : r.patches) fx += patch.rolling->tangential.force_x_N;
    EXPECT_NEAR(fx, share * mu_fn, 1e-5 * mu_fn) << share;  // the solver's 1e-6 mu Fn, rounded
    // Traction needs the wheel to turn faster than it rolls (Omega more negative), braking slower.
    EXPECT_EQ(r.pitch_velocity_rad_s<free_rolling.pitch_velocity_rad_s, share> 0) << share;
  }
  p.rolling->longitudinal_force_N = 1.2 * mu_fn;
  const ContactResult beyond = SolveContact(p);
  EXPECT_EQ(beyond.status, SolverStatus::kNotConverged);
  EXPECT_NE(beyond.message.find("cannot be carried"), std::string::npos) << beyond.message;
}

}  // namespace
}  // namespace railwear
