// A planar patch grid of nx x ns cells covering the Hertz rectangle [-a, a] x [-b, b] exactly,
// zero gap: the grid the tangential solvers' tests and benchmarks put a Hertz pressure on.
#pragma once

#include "core/contact/patch_grid.h"

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

}  // namespace railwear::testing
