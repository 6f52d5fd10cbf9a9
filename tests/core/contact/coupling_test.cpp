#include "core/contact/coupling.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/contact/contact_forces.h"
#include "core/contact/contact_solver.h"
#include "tests/core/contact/hertz_grid.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

TEST(Coupling, CoefficientOfSeedEq4CrossTerms) {
  const Material steel{210e9, 0.28};
  const double kd = 1.0 / (8.0 * std::numbers::pi * (1.0 - 0.28) * steel.ShearModulus());
  const InfluenceConstants c;  // c_s = 0.25
  // Concave wheel (flange root) on a convex rail (gauge corner): 2 c_s k_d.
  EXPECT_NEAR(CouplingCoefficient(c, steel, +1, steel, -1), 2 * 0.25 * kd, 1e-12 * kd);
  // Equal curvature signs and identical materials: no coupling.
  EXPECT_EQ(CouplingCoefficient(c, steel, -1, steel, -1), 0.0);
  InfluenceConstants none = c;
  none.c_s = 0.0;
  EXPECT_EQ(CouplingCoefficient(none, steel, +1, steel, -1), 0.0);
}

TEST(Coupling, UniformTractionGivesAnOddField) {
  // A uniform q_x on a symmetric planar patch: u(x) = -u(-x), zero on x = 0, linear in kappa.
  const PatchGrid g = testing::MakeHertzGrid(4e-3, 3e-3, 21, 15);
  TangentialSolution t = EmptyTangentialSolution(g.cells());
  t.traction_x_Pa.setConstant(100e6);
  const Eigen::VectorXd u = CouplingDisplacement(g, t, 1e-12);
  const Eigen::VectorXd u2 = CouplingDisplacement(g, t, 2e-12);
  double umax = u.cwiseAbs().maxCoeff();
  ASSERT_GT(umax, 0.0);
  for (int j = 0; j < g.ns; ++j) {
    EXPECT_NEAR(u[g.Index(10, j)], 0.0, 1e-12 * umax);
    for (int i = 0; i < g.nx; ++i) {
      EXPECT_NEAR(u[g.Index(i, j)], -u[g.Index(g.nx - 1 - i, j)], 1e-12 * umax);
      EXPECT_NEAR(u2[g.Index(i, j)], 2 * u[g.Index(i, j)], 1e-12 * umax);
    }
  }
}

// The sign convention, pinned against Cerruti's half-space solution (Landau & Lifshitz §8): a
// tangential point load Q on a body moves its surface into the body ahead of the load,
// u_z = (1 - 2 nu)/(4 pi G) Q / x at distance x along the load. Eq. 4 gives exactly that with
// c_t k_d = (1 - 2 nu)/(4 pi G), i.e. c_t = 2 (1 - 2 nu)(1 - nu). One loaded cell on a flat
// grid, the other body rigid, so that only one body deforms:
//  - the wheel carries q: ahead of q its surface moves into the wheel, the gap opens;
//  - the rail carries -q: ahead of q (behind its own load) its surface rises, the gap closes.
TEST(Coupling, SignFollowsCerrutiForEachBody) {
  const Material steel{210e9, 0.28};
  const Material rigid{210e21, 0.28};  // k_d 1e-12 of steel's: a rigid body
  const double nu = steel.poisson_ratio;
  const double cerruti = (1.0 - 2.0 * nu) / (4.0 * std::numbers::pi * steel.ShearModulus());
  InfluenceConstants c;
  // Convex bodies: c_t = 1 - c_s = 2 (1 - 2 nu)(1 - nu).
  c.c_s = 1.0 - 2.0 * (1.0 - 2.0 * nu) * (1.0 - nu);
  const double kappa_wheel = CouplingCoefficient(c, steel, -1, rigid, -1);
  const double kappa_rail = CouplingCoefficient(c, rigid, -1, steel, -1);
  EXPECT_NEAR(kappa_wheel, cerruti, 1e-9 * cerruti);
  EXPECT_NEAR(kappa_rail, -cerruti, 1e-9 * cerruti);

  const PatchGrid g = testing::MakeHertzGrid(10e-3, 1e-3, 41, 3);  // 0.49 mm cells
  const int centre = g.Index(20, 1);
  TangentialSolution t = EmptyTangentialSolution(g.cells());
  const double q = 50e6;  // toward +x, on the wheel
  t.traction_x_Pa[centre] = q;
  const double load_N = q * g.CellArea();
  const Eigen::VectorXd u_wheel = CouplingDisplacement(g, t, kappa_wheel);
  const Eigen::VectorXd u_rail = CouplingDisplacement(g, t, kappa_rail);
  // Beyond the Gauss-integrated near cells (2 cells) the source cell acts as a point load.
  for (int i : {25, 30, 40}) {
    const double x = g.X(i) - g.X(20);
    const double ahead_wheel = u_wheel[g.Index(i, 1)];
    const double behind_wheel = u_wheel[g.Index(40 - i, 1)];
    EXPECT_GT(ahead_wheel, 0.0) << "the wheel's surface must move into the wheel ahead of q";
    EXPECT_LT(behind_wheel, 0.0);
    EXPECT_NEAR(ahead_wheel, cerruti * load_N / x, 1e-9 * cerruti * load_N / x) << i;
    EXPECT_LT(u_rail[g.Index(i, 1)], 0.0) << "the rail's surface must rise ahead of q";
    EXPECT_NEAR(u_rail[g.Index(i, 1)], -ahead_wheel, 1e-12 * ahead_wheel);
  }
}

// Separate convex and concave sets: each body's c_t uses the c_s of its own set.
TEST(Coupling, SeparateSetsUseEachBodysOwnCs) {
  const Material steel{210e9, 0.28};
  const double kd = 1.0 / (8.0 * std::numbers::pi * (1.0 - 0.28) * steel.ShearModulus());
  InfluenceConstants c;
  c.separate = SeparateInfluenceConstants{{0.9, 1.0, 0.1}, {0.8, 1.0, 0.4}};
  // Concave wheel (c_t = 1 + 0.4) on a convex rail (c_t = 1 - 0.1).
  EXPECT_NEAR(CouplingCoefficient(c, steel, +1, steel, -1), (1.4 - 0.9) * kd, 1e-12 * kd);
  // Convex wheel on a concave rail.
  EXPECT_NEAR(CouplingCoefficient(c, steel, -1, steel, +1), (0.9 - 1.4) * kd, 1e-12 * kd);
}

// The flange-root-on-gauge-corner pair of CONTACT's conformal example (as in
// rolling_contact_test.cpp), tilted 45 degrees, rolling with longitudinal creepage.
ContactProblem Tilted(double c_s) {
  const double gamma = -std::numbers::pi / 4;
  ContactProblem p;
  p.rail_profile = testing::ArcProfile(0.010, +1.0, 0.52).Transformed(gamma, {0.0, 0.0});
  p.wheel_profile = testing::ArcProfile(0.0102, +1.0, 0.52).Transformed(gamma, {0.0, 0.0});
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 65e3;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.constants.c_s = c_s;
  p.model.accuracy = AccuracyPreset::kDraft;
  RollingOptions r;
  r.friction = 0.3;
  r.motion.speed_m_s = 10.0;
  r.motion.pitch_velocity_rad_s = (-0.002 - 1.0) * 10.0 / 0.46;
  r.coupling = true;
  p.rolling = r;
  return p;
}

TEST(Coupling, IteratesToATolerancePreservingLoadAndTractionBound) {
  const ContactResult r = SolveContact(Tilted(0.25));
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  EXPECT_GE(r.coupling_iterations, 2);  // the tractions did change the gap
  // The load is carried by the pressure and the creep forces' vertical parts together (issue 14:
  // the vertical balance); the pressure's part alone was the load before.
  const ForceParts f = TotalForcesOnRail(r);
  EXPECT_NEAR(f.Net().z(), 65e3, 1e-8 * 65e3);
  EXPECT_NEAR(r.vertical_force_N, 65e3 - f.creep_N.z(), 1e-8 * 65e3);
  EXPECT_NE(r.coupling_p_max_change, 0.0);
  EXPECT_LT(std::abs(r.coupling_p_max_change), 0.1);  // a correction, not a different solution
  for (const auto& patch : r.patches) {
    const auto& t = patch.rolling->tangential;
    for (int k = 0; k < t.traction_x_Pa.size(); ++k) {
      EXPECT_LE(std::hypot(t.traction_x_Pa[k], t.traction_s_Pa[k]),
                0.3 * patch.pressure_Pa[k] * (1 + 1e-9) + 1e-6);
    }
  }
  // Without the curvature-dependent term the cross terms cancel: one iteration, no change.
  const ContactResult none = SolveContact(Tilted(0.0));
  ASSERT_EQ(none.status, SolverStatus::kConverged);
  EXPECT_EQ(none.coupling_iterations, 1);
  EXPECT_EQ(none.coupling_area_change, 0.0);
  // A larger c_s couples more strongly.
  const ContactResult strong = SolveContact(Tilted(0.5));
  ASSERT_EQ(strong.status, SolverStatus::kConverged);
  EXPECT_GT(std::abs(strong.coupling_p_max_change), std::abs(r.coupling_p_max_change));
}

}  // namespace
}  // namespace railwear
