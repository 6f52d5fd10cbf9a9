// Helpers shared by the profile tests: distance from a point to a profile curve, and the
// location of the shared profile files (../shared/data/profiles, see tests/CMakeLists.txt).
#pragma once

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <Eigen/Core>

#include "core/profile/profile.h"

namespace railwear::testing {

// Directory of the shared profile files (not part of the repository; tests skip without it).
inline std::string SharedProfilesDir() {
  return std::string(RAILWEAR_SHARED_DIR) + "/data/profiles";
}

// Distance [m] from q_m to the profile's spline curve: nearest knot, then golden-section search
// over the two neighbouring intervals. Valid when q is much closer to the curve than the
// curve's radius of curvature (all uses here).
inline double DistanceToProfile(const Profile& profile, const Eigen::Vector2d& q_m) {
  const auto& pts = profile.points();
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < profile.size(); ++i) {
    const double d = (pts[i] - q_m).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  double a = profile.KnotS(std::max(best - 1, 0));
  double b = profile.KnotS(std::min(best + 1, profile.size() - 1));
  const auto dist = [&](double s) { return (profile.Position(s) - q_m).norm(); };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 100; ++it) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (dist(c) < dist(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return dist(0.5 * (a + b));
}

// Largest distance [m] of `points` (metres) to `profile`, over the points that satisfy `keep`.
template <class Keep>
double MaxDistance(const Profile& profile, const std::vector<Eigen::Vector2d>& points, Keep keep,
                   int* count = nullptr) {
  double worst = 0.0;
  int n = 0;
  for (const auto& p : points) {
    if (!keep(p)) continue;
    ++n;
    worst = std::max(worst, DistanceToProfile(profile, p));
  }
  if (count) *count = n;
  return worst;
}

}  // namespace railwear::testing
