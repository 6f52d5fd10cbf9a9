// Small profile generators for geometry tests (independent of the built-in profile code).
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "core/profile/profile.h"

namespace railwear::testing {

// Points of z(y) for y in [y0, y1] with n points.
template <typename F>
Profile FunctionProfile(F&& z_of_y, double y0, double y1, int n) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double y = y0 + (y1 - y0) * i / (n - 1);
    pts.emplace_back(y, z_of_y(y));
  }
  return Profile(std::move(pts), "test");
}

// Circular arc of radius R [m] with lowest (sign = -1) or highest (sign = +1) point at the
// origin, sampled by angle over +-half_angle. sign = +1: convex rail crown z = R - sqrt(R^2-y^2);
// sign = -1: convex wheel / concave groove z = -(R - sqrt(R^2 - y^2)).
inline Profile ArcProfile(double R, double sign, double half_angle = 1.2, int n = 801) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = -half_angle + 2 * half_angle * i / (n - 1);
    pts.emplace_back(R * std::sin(a), sign * (R - R * std::cos(a)));
  }
  return Profile(std::move(pts), "arc");
}

}  // namespace railwear::testing
