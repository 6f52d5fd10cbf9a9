// Normal displacement from tangential tractions through seed eq. 4's cross terms.
#include "core/contact/coupling.h"

#include <cmath>

#include "core/contact/seed_kernel.h"

namespace railwear {

double CouplingCoefficient(const InfluenceConstants& c, const Material& wheel, int wheel_sign,
                           const Material& rail, int rail_sign) {
  return SeedKernelCt(c.ForBody(wheel_sign), wheel_sign) * SeedKernelKd(wheel) -
         SeedKernelCt(c.ForBody(rail_sign), rail_sign) * SeedKernelKd(rail);
}

Eigen::VectorXd CouplingDisplacement(const PatchGrid& g, const TangentialSolution& t,
                                     double kappa) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(g.cells());
  if (kappa == 0.0) return u;
  static constexpr double kGx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                    0.8611363115940526};
  static constexpr double kGw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                    0.3478548451374538};
  const double area = g.CellArea();
  for (int jb = 0; jb < g.ns; ++jb) {
    const Eigen::Vector3d tj(0.0, g.tangent_yz[jb].x(), g.tangent_yz[jb].y());
    for (int ib = 0; ib < g.nx; ++ib) {
      const int src = g.Index(ib, jb);
      const double qx = t.traction_x_Pa[src], qs = t.traction_s_Pa[src];
      if (qx == 0.0 && qs == 0.0) continue;
      const Eigen::Vector3d pj = g.Point(ib, jb);
      for (int j = 0; j < g.ns; ++j) {
        for (int i = 0; i < g.nx; ++i) {
          const int dst = g.Index(i, j);
          if (dst == src) continue;  // odd kernel: the cell's own contribution is zero
          const Eigen::Vector3d d = g.Point(i, j) - pj;
          const double dx = d.x(), ds = d.dot(tj);
          const double dn2 = std::max(0.0, d.squaredNorm() - dx * dx - ds * ds);
          double sum = 0.0;
          if (std::abs(i - ib) <= 2 && std::abs(j - jb) <= 2) {
            // Gauss points over the source cell's tangent rectangle.
            for (int a = 0; a < 4; ++a) {
              for (int b = 0; b < 4; ++b) {
                const double ex = dx - 0.5 * g.dx_m * kGx[a];
                const double es = ds - 0.5 * g.ds_m * kGx[b];
                const double r2 = ex * ex + es * es + dn2;
                sum += 0.25 * kGw[a] * kGw[b] * (qx * ex + qs * es) / r2;
              }
            }
          } else {
            sum = (qx * dx + qs * ds) / (dx * dx + ds * ds + dn2);
          }
          u[dst] += kappa * area * sum;
        }
      }
    }
  }
  return u;
}

}  // namespace railwear
