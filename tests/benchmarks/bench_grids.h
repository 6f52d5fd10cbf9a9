// Grids for the benchmarks: nx x ns square cells of 0.1 mm on a straight line (planar) or on a
// circular arc of radius 10 mm (a rail crown), zero gap. Shared by influence_bench and
// contact_bench so both time the same geometry.
#pragma once

#include <cmath>

#include "core/geometry/patch_grid.h"

namespace railwear::bench {

constexpr double kCell_m = 1e-4;
constexpr double kArcRadius_m = 10e-3;

inline PatchGrid MakeBenchGrid(int nx, int ns, bool planar) {
  PatchGrid g;
  g.nx = nx;
  g.ns = ns;
  g.dx_m = g.ds_m = kCell_m;
  g.x0_m = -0.5 * (nx - 1) * kCell_m;
  g.s0_m = -0.5 * (ns - 1) * kCell_m;
  g.planar = planar;
  for (int j = 0; j < ns; ++j) {
    if (planar) {
      g.point_yz_m.emplace_back(g.S(j), 0.0);
      g.tangent_yz.emplace_back(1.0, 0.0);
      g.normal_yz.emplace_back(0.0, -1.0);
    } else {
      const double theta = g.S(j) / kArcRadius_m;
      const Eigen::Vector2d n(std::sin(theta), -std::cos(theta));
      g.point_yz_m.push_back(Eigen::Vector2d(0.0, kArcRadius_m) + kArcRadius_m * n);
      g.tangent_yz.emplace_back(std::cos(theta), std::sin(theta));
      g.normal_yz.push_back(n);
    }
  }
  g.gap_m = Eigen::VectorXd::Zero(nx * ns);
  return g;
}

}  // namespace railwear::bench
