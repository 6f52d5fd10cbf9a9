// IsUniformArc (patch_grid.h).
#include "core/geometry/patch_grid.h"

#include <cmath>

namespace railwear {
namespace {

// sin(u) / u, 1 at u = 0.
double Sinc(double u) { return u == 0.0 ? 1.0 : std::sin(u) / u; }

Eigen::Vector2d Rotate(const Eigen::Vector2d& v, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

bool IsUniformArc(const PatchGrid& grid, double tolerance) {
  const int ns = grid.ns;
  if (ns < 1 || static_cast<int>(grid.point_yz_m.size()) != ns ||
      static_cast<int>(grid.tangent_yz.size()) != ns ||
      static_cast<int>(grid.normal_yz.size()) != ns || !(grid.ds_m > 0.0)) {
    return false;
  }
  const Eigen::Vector2d t0 = grid.tangent_yz[0], n0 = grid.normal_yz[0];
  if (!(std::abs(t0.norm() - 1.0) <= tolerance && std::abs(n0.norm() - 1.0) <= tolerance &&
        std::abs(t0.dot(n0)) <= tolerance)) {
    return false;
  }
  if (ns == 1) return true;
  const Eigen::Vector2d left(-t0.y(), t0.x());  // t0 turned by +90 degrees
  // Curvature from the end tangents: the signed angle between them over the arc length.
  const Eigen::Vector2d t_end = grid.tangent_yz[ns - 1];
  const double turn = std::atan2(t0.x() * t_end.y() - t0.y() * t_end.x(), t0.dot(t_end));
  const double kappa = turn / ((ns - 1) * grid.ds_m);
  for (int j = 1; j < ns; ++j) {
    const double s = j * grid.ds_m;
    const double phi = kappa * s;
    // The arc from point 0: s sinc(phi) along t0, s sin(phi/2) sinc(phi/2) to its left
    // ((1 - cos phi) / kappa without the cancellation).
    const Eigen::Vector2d expected = grid.point_yz_m[0] + (s * Sinc(phi)) * t0 +
                                     (s * std::sin(0.5 * phi) * Sinc(0.5 * phi)) * left;
    if (!((grid.point_yz_m[j] - expected).norm() <= tolerance * grid.ds_m)) return false;
    if (!((grid.tangent_yz[j] - Rotate(t0, phi)).norm() <= tolerance)) return false;
    if (!((grid.normal_yz[j] - Rotate(n0, phi)).norm() <= tolerance)) return false;
  }
  return true;
}

}  // namespace railwear
