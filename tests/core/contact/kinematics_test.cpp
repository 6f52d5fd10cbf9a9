#include "core/contact/kinematics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/geometry/patch_builder.h"
#include "core/geometry/wheelset.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// A planar grid on the first contact of a wheel profile z_W(y) on a 300 mm crown.
struct ContactScene {
  Profile wheel, rail;
  std::unique_ptr<WheelRailGeometry> geom;
  PatchGrid grid;
};
ContactScene MakeScene(double wheel_slope, double rail_R = 0.3, double half_angle = 0.1,
                       double yaw_rad = 0.0, double lateral_shift_m = 0.0) {
  ContactScene s;
  s.rail = testing::ArcProfile(rail_R, +1.0, half_angle, 2001);
  s.wheel =
      testing::FunctionProfile([&](double y) { return 0.002 + wheel_slope * y; }, -0.05, 0.05, 201);
  WheelPose pose;
  pose.rolling_radius_m = 0.46;
  pose.yaw_rad = yaw_rad;
  pose.lateral_shift_m = lateral_shift_m;
  s.geom = std::make_unique<WheelRailGeometry>(s.wheel, s.rail, pose);
  const auto c = s.geom->FindCandidates(1e-4);
  PatchGridOptions o;
  o.geometry = GeometryModel::kConformal;
  o.cell_dx_m = o.cell_ds_m = 5e-4;
  o.threshold_m = 1e-4;
  s.grid = BuildPatchGrid(*s.geom, c.at(0), o).grid;
  return s;
}

// Kinematics are exact rigid-body formulas evaluated at cell centres: compare to 1e-9.
constexpr double kCreepTolerance = 1e-9;

TEST(Kinematics, RollingRadiusDifferenceGivesLongitudinalCreepage) {
  // The wheel's z = 2 mm line touches the crown: the rolling radius there is r0 + 2 mm, so pure
  // rolling at r0 leaves xi = (r0 - r)/r0 at the contact point.
  const ContactScene s = MakeScene(0.0);
  WheelMotion m;
  m.speed_m_s = 20.0;
  const RollingInput in = RigidSlipFromMotion(*s.geom, s.grid, m, 0.3);
  const int ic = (s.grid.nx - 1) / 2;
  const int jc = static_cast<int>(std::lround(-s.grid.s0_m / s.grid.ds_m));
  const double r = 0.462, r0 = 0.46;
  EXPECT_NEAR(in.creep_x[s.grid.Index(ic, jc)], (r0 - r) / r0, kCreepTolerance);
  EXPECT_NEAR(in.creep_s[s.grid.Index(ic, jc)], 0.0, kCreepTolerance);
  // Pitch velocity for pure rolling at the contact radius: no longitudinal slip there.
  m.pitch_velocity_rad_s = -m.speed_m_s / r;
  const RollingInput in2 = RigidSlipFromMotion(*s.geom, s.grid, m, 0.3);
  EXPECT_NEAR(in2.creep_x[s.grid.Index(ic, jc)], 0.0, kCreepTolerance);
}

TEST(Kinematics, YawGivesLateralCreepageMinusPsi) {
  constexpr double kYaw = 0.005;
  const ContactScene s = MakeScene(0.0, 0.3, 0.1, kYaw);
  WheelMotion m;
  m.speed_m_s = 10.0;
  m.pitch_velocity_rad_s = -m.speed_m_s / 0.462;  // pure rolling at the contact radius
  const RollingInput in = RigidSlipFromMotion(*s.geom, s.grid, m, 0.3);
  // v = V (1 - cos psi, -sin psi) at the contact point, where the radius is the contact radius.
  const int ic = (s.grid.nx - 1) / 2;
  const int jc = static_cast<int>(std::lround(-s.grid.s0_m / s.grid.ds_m));
  EXPECT_NEAR(in.creep_s[s.grid.Index(ic, jc)], -std::sin(kYaw), kCreepTolerance);
  EXPECT_NEAR(in.creep_x[s.grid.Index(ic, jc)], 1.0 - std::cos(kYaw), kCreepTolerance);
}

// Issue 14: a yawed cone (slope angle gamma) on a cylinder touches ahead of its axle, and the
// lateral creepage there is -psi sec(gamma) (classical: eta = (dy/dt / V - psi) / cos(gamma)),
// not -psi cos(gamma) as at the unyawed contact point. Within 1 % up to 70 degrees and 20 mrad,
// with the pitch velocity of pure rolling at the contact radius. The closed form neglects
// O(psi^2) terms: 1 % of psi sec(gamma) covers them.
TEST(Kinematics, YawedConeGivesLateralCreepageMinusPsiSecGamma) {
  for (double gamma_deg : {10.0, 45.0, 70.0}) {
    const double gamma = gamma_deg * M_PI / 180.0;
    for (double psi : {0.002, 0.0156, 0.02, -0.01}) {
      // The cone z = -tan(gamma) y over a 300 mm crown, placed so that it touches at the
      // crown's point of slope angle gamma (y = -R sin(gamma)).
      const ContactScene s = MakeScene(-std::tan(gamma), 0.3, 1.3, psi, -0.3 * std::sin(gamma));
      const auto c = s.geom->FindCandidates(1e-4).at(0);
      WheelMotion m;
      m.speed_m_s = 10.0;
      m.pitch_velocity_rad_s = -m.speed_m_s / c.wheel_radius_m;
      const RollingInput in = RigidSlipFromMotion(*s.geom, s.grid, m, 0.3);
      const int ic = (s.grid.nx - 1) / 2;
      const int jc = static_cast<int>(std::lround(-s.grid.s0_m / s.grid.ds_m));
      const double eta = in.creep_s[s.grid.Index(ic, jc)];
      EXPECT_NEAR(eta, -psi / std::cos(gamma), 0.01 * std::abs(psi) / std::cos(gamma))
          << "gamma " << gamma_deg << " psi " << psi;
    }
  }
}

TEST(Kinematics, InclinedContactHasSpinSinGammaOverR) {
  // A wheel cone of slope 0.3 on a 100 mm crown: contact where the crown has the same slope,
  // gamma = atan(0.3). The spin of a wheel turning at Omega = -V/r0 about a level axle is
  // Omega a . n, so the spin creepage is sin(gamma) / r0 in magnitude.
  const ContactScene s = MakeScene(0.3, 0.1, 0.5);
  WheelMotion m;
  m.speed_m_s = 10.0;
  const RollingInput in = RigidSlipFromMotion(*s.geom, s.grid, m, 0.3);
  // Weight the fit on the cells nearest the contact point (the crown turns the normal by
  // ds/R per cell; within 1 mm that changes sin(gamma) by < 1 %).
  Eigen::VectorXd w = Eigen::VectorXd::Zero(s.grid.cells());
  for (int j = 0; j < s.grid.ns; ++j)
    for (int i = 0; i < s.grid.nx; ++i)
      if (std::abs(s.grid.S(j)) < 1e-3 && std::abs(s.grid.X(i)) < 1e-3) w[s.grid.Index(i, j)] = 1;
  const Creepage c = AverageCreepage(s.grid, w, in);
  const double gamma = std::atan(0.3);
  EXPECT_NEAR(std::abs(c.spin_per_m), std::sin(gamma) / 0.46, 0.01 * std::sin(gamma) / 0.46);
}

TEST(Kinematics, PrescribedCreepageRoundTrips) {
  // Prescribed about the pressure centre and fitted about it: the same creepages come back.
  const ContactScene s = MakeScene(0.0);
  Eigen::VectorXd p(s.grid.cells());
  for (int k = 0; k < p.size(); ++k) p[k] = 1.0 + 0.3 * std::sin(0.7 * k);  // any positive field
  const Creepage c{-0.004, 0.0021, -1.5};
  const RollingInput in = RigidSlipFromCreepage(s.grid, p, c, 20.0, 0.3);
  const Creepage back = AverageCreepage(s.grid, p, in);
  EXPECT_NEAR(back.xi, c.xi, 1e-12);
  EXPECT_NEAR(back.eta, c.eta, 1e-12);
  EXPECT_NEAR(back.spin_per_m, c.spin_per_m, 1e-9);
}

TEST(Wheelset, CentredS1002OnCantedUic60) {
  // Gauge point of the canted UIC60 14 mm below its top; the centred wheel's taping line then
  // lies 10.4 mm gauge-side of the rail's origin (README, examples/gauge_corner.toml).
  const Profile rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  const Eigen::Vector2d g = RailGaugePoint(rail, 0.014);
  EXPECT_NEAR(g.y(), 0.014, 1e-8);  // level from the sampled top of the spline
  EXPECT_LT(g.x(), -0.04);
  const WheelsetPlacement p = PlaceWheelset(rail, TrackSpec{}, WheelsetSpec{});
  EXPECT_NEAR(p.right.lateral_shift_m, 0.750 - (0.7175 - g.x()), 1e-12);
  EXPECT_NEAR(p.right.lateral_shift_m, -0.0104, 2e-4);
  // Centred and unrolled: the left wheel sees the same placement in its mirrored frame.
  EXPECT_DOUBLE_EQ(p.left.lateral_shift_m, p.right.lateral_shift_m);
  WheelsetSpec moved;
  moved.lateral_displacement_m = 0.005;
  moved.roll_rad = 0.001;
  const WheelsetPlacement q = PlaceWheelset(rail, TrackSpec{}, moved);
  EXPECT_NEAR(q.right.lateral_shift_m - p.right.lateral_shift_m, 0.005, 1e-12);
  EXPECT_NEAR(q.left.lateral_shift_m - p.left.lateral_shift_m, -0.005, 1e-12);
  EXPECT_DOUBLE_EQ(q.left.roll_rad, -q.right.roll_rad);
}

}  // namespace
}  // namespace railwear
