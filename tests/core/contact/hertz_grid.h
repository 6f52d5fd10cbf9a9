// A planar patch grid of nx x ns cells covering the Hertz rectangle [-a, a] x [-b, b] exactly,
// zero gap, and Kalker's planar creepage field on it: what the tangential solvers' tests and
// benchmarks put a Hertz pressure and creepages on.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear::testing {

inline PatchGrid MakeHertzGrid(double a_m, double b_m, int nx, int ns) {
  PatchGrid g;
  g.nx = nx;
  g.ns = ns;
  g.dx_m = 2.0 * a_m / nx;
  g.ds_m = 2.0 * b_m / ns;
  g.x0_m = -a_m + 0.5 * g.dx_m;
  g.s0_m = -b_m + 0.5 * g.ds_m;
  g.planar = true;
  for (int j = 0; j < ns; ++j) {
    g.point_yz_m.emplace_back(g.S(j), 0.0);
    g.tangent_yz.emplace_back(1.0, 0.0);
    g.normal_yz.emplace_back(0.0, -1.0);
  }
  g.gap_m = Eigen::VectorXd::Zero(g.cells());
  return g;
}

// Hertz pressure p0 sqrt(1 - x^2/a^2 - s^2/b^2) on the grid, scaled so that sum p dA = fn.
inline Eigen::VectorXd HertzPressure(const PatchGrid& g, double a_m, double b_m, double fn_N) {
  Eigen::VectorXd p(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.X(i) / a_m, s = g.S(j) / b_m;
      p[g.Index(i, j)] = std::sqrt(std::max(0.0, 1.0 - x * x - s * s));
    }
  }
  return p * (fn_N / (p.sum() * g.CellArea()));
}

// Kalker's planar creepage field about the grid origin, w_x = xi - phi s, w_s = eta + phi x
// (phi in 1/m), at speed V and friction mu.
inline RollingInput KalkerCreepage(const PatchGrid& g, double xi, double eta, double phi,
                                   double speed_m_s, double friction) {
  RollingInput in;
  in.creep_x.resize(g.cells());
  in.creep_s.resize(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      in.creep_x[g.Index(i, j)] = xi - phi * g.S(j);
      in.creep_s[g.Index(i, j)] = eta + phi * g.X(i);
    }
  }
  in.speed_m_s = speed_m_s;
  in.friction = friction;
  return in;
}

}  // namespace railwear::testing
