// Rigid slip from the wheel's motion, prescribed creepage, and patch-average creepage.
#include "core/contact/kinematics.h"

#include <cmath>

#include <Eigen/Dense>

#include "core/contact/rigid_motion.h"
#include "core/numerics/check.h"

namespace railwear {

WheelRigidMotion MakeWheelRigidMotion(const Eigen::Vector2d& axle_yz,
                                      const Eigen::Vector2d& origin_yz, double roll, double yaw,
                                      double r0, const WheelMotion& motion) {
  RAILWEAR_CHECK(motion.speed_m_s > 0);
  WheelRigidMotion m;
  m.speed_m_s = motion.speed_m_s;
  m.pitch_velocity_rad_s = motion.pitch_velocity_rad_s.value_or(-motion.speed_m_s / r0);
  m.lateral_velocity_m_s = motion.lateral_velocity_m_s;
  m.yaw_velocity_rad_s = motion.yaw_velocity_rad_s;
  m.axle_point_m = Eigen::Vector3d(0.0, axle_yz.x(), axle_yz.y());
  // Axle direction in R: e_y yawed about z, then rolled about x (the geometry's order).
  m.axle_direction = Eigen::Vector3d(-std::sin(yaw), std::cos(yaw) * std::cos(roll),
                                     std::cos(yaw) * std::sin(roll));
  m.origin_yz_m = origin_yz;
  return m;
}

Eigen::Vector3d WheelRigidMotion::SlipVelocity(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d& a = axle_direction;
  const Eigen::Vector3d d = p - axle_point_m;
  const Eigen::Vector3d r = d - d.dot(a) * a;  // perpendicular from the axle
  Eigen::Vector3d v = Eigen::Vector3d(speed_m_s, lateral_velocity_m_s, 0.0) +
                      pitch_velocity_rad_s * a.cross(r);
  if (yaw_velocity_rad_s != 0.0) {
    v += yaw_velocity_rad_s * Eigen::Vector3d(-(p.y() - origin_yz_m.x()), p.x(), 0.0);
  }
  return v;
}

RollingInput RigidSlipOfMotion(const WheelRigidMotion& motion, const PatchGrid& grid,
                               double friction) {
  const double V = motion.speed_m_s;
  RollingInput in;
  in.speed_m_s = V;
  in.friction = friction;
  in.creep_x.resize(grid.cells());
  in.creep_s.resize(grid.cells());
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector3d t(0.0, grid.tangent_yz[j].x(), grid.tangent_yz[j].y());
    for (int i = 0; i < grid.nx; ++i) {
      const Eigen::Vector3d v = motion.SlipVelocity(grid.Point(i, j));
      in.creep_x[grid.Index(i, j)] = v.x() / V;
      in.creep_s[grid.Index(i, j)] = v.dot(t) / V;
    }
  }
  return in;
}

RollingInput RigidSlipFromMotion(const WheelRailGeometry& geom, const PatchGrid& grid,
                                 const WheelMotion& motion, double friction) {
  const double r0 = geom.pose().rolling_radius_m;
  return RigidSlipOfMotion(
      MakeWheelRigidMotion(geom.WheelToRail({0.0, -r0}), geom.WheelToRail({0.0, 0.0}),
                           geom.pose().roll_rad, geom.pose().yaw_rad, r0, motion),
      grid, friction);
}

Eigen::Vector2d PressureCentre(const PatchGrid& grid, const Eigen::VectorXd& weight) {
  double W = 0.0, xc = 0.0, sc = 0.0;
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const double w = std::max(0.0, weight[grid.Index(i, j)]);
      W += w;
      xc += w * grid.X(i);
      sc += w * grid.S(j);
    }
  }
  return W > 0 ? Eigen::Vector2d(xc / W, sc / W) : Eigen::Vector2d::Zero();
}

RollingInput RigidSlipFromCreepage(const PatchGrid& grid, const Eigen::VectorXd& pressure,
                                   const Creepage& c, double speed_m_s, double friction) {
  const Eigen::Vector2d centre = PressureCentre(grid, pressure);
  RollingInput in;
  in.speed_m_s = speed_m_s;
  in.friction = friction;
  in.creep_x.resize(grid.cells());
  in.creep_s.resize(grid.cells());
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      in.creep_x[grid.Index(i, j)] = c.xi - c.spin_per_m * (grid.S(j) - centre.y());
      in.creep_s[grid.Index(i, j)] = c.eta + c.spin_per_m * (grid.X(i) - centre.x());
    }
  }
  return in;
}

Creepage AverageCreepage(const PatchGrid& grid, const Eigen::VectorXd& weight,
                         const RollingInput& in) {
  // Minimise sum w [(w_x - xi + phi s')^2 + (w_s - eta - phi x')^2], x' = x - x_c, s' = s - s_c.
  Creepage c;
  if (!(weight.maxCoeff() > 0)) return c;
  const Eigen::Vector2d centre = PressureCentre(grid, weight);
  const double xc = centre.x(), sc = centre.y();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const int k = grid.Index(i, j);
      const double w = std::max(0.0, weight[k]);
      if (w == 0) continue;
      const double xp = grid.X(i) - xc, sp = grid.S(j) - sc;
      // Rows: w_x = xi - phi s', w_s = eta + phi x'.
      const Eigen::Vector3d gx(1.0, 0.0, -sp), gs(0.0, 1.0, xp);
      A += w * (gx * gx.transpose() + gs * gs.transpose());
      b += w * (gx * in.creep_x[k] + gs * in.creep_s[k]);
    }
  }
  const Eigen::Vector3d sol = A.ldlt().solve(b);
  c.xi = sol[0];
  c.eta = sol[1];
  c.spin_per_m = sol[2];
  return c;
}

}  // namespace railwear
