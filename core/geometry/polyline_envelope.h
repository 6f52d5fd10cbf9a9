// The lower or upper envelope of a polyline in (y, z) on a uniform grid of y: the vertical-gap
// sampling of WheelRailGeometry and the fast tread path's coarse gap (core/contact/hertz_tread.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace railwear::internal {

// For every grid point y_i = y0 + i h (i in [0, n)) that a segment of `pts` spans, the segment's
// linearly interpolated z folded into (*z)[i] by min (take_min: the upper surface, z being down)
// or max (the lower surface). *z has size n and starts at +inf (take_min) or -inf; grid points no
// segment spans keep it. pts: (y, z) [m], any order of y along the polyline.
inline void RasteriseEnvelope(const std::vector<Eigen::Vector2d>& pts, double y0, double h, int n,
                              bool take_min, std::vector<double>* z) {
  for (size_t k = 0; k + 1 < pts.size(); ++k) {
    const Eigen::Vector2d& a = pts[k];
    const Eigen::Vector2d& b = pts[k + 1];
    const double ya = std::min(a.x(), b.x()), yb = std::max(a.x(), b.x());
    int i0 = static_cast<int>(std::ceil((ya - y0) / h));
    int i1 = static_cast<int>(std::floor((yb - y0) / h));
    i0 = std::max(i0, 0);
    i1 = std::min(i1, n - 1);
    for (int i = i0; i <= i1; ++i) {
      const double y = y0 + i * h;
      const double t = (b.x() == a.x()) ? 0.0 : (y - a.x()) / (b.x() - a.x());
      const double zi = a.y() + t * (b.y() - a.y());
      double& slot = (*z)[i];
      slot = take_min ? std::min(slot, zi) : std::max(slot, zi);
      if (b.x() == a.x()) slot = take_min ? std::min(slot, b.y()) : std::max(slot, b.y());
    }
  }
}

}  // namespace railwear::internal
