// Wheelset placement on a track (see wheelset.h).
#include "core/geometry/wheelset.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "core/geometry/curve_locator.h"
#include "core/numerics/input_error.h"

namespace railwear {

Eigen::Vector2d RailGaugePoint(const Profile& rail, double gauge_height_m) {
  const Profile::Bounds b = rail.bounds();
  const double level = b.z_min + gauge_height_m;
  // Gauge-side crossing: scan the polyline of the spline for the smallest y at this level.
  const CurveLocator loc(rail, /*material_toward_plus_z=*/true);
  std::optional<double> y_best;
  double best_s = 0.0;
  const int n = std::max(2, static_cast<int>(std::ceil(rail.Length() / 1e-5)));
  Eigen::Vector2d prev = rail.Position(0.0);
  for (int i = 1; i <= n; ++i) {
    const double s = rail.Length() * i / n;
    const Eigen::Vector2d cur = rail.Position(s);
    if ((prev.y() - level) * (cur.y() - level) <= 0 && prev.y() != cur.y()) {
      const double f = (level - prev.y()) / (cur.y() - prev.y());
      const double y = prev.x() + f * (cur.x() - prev.x());
      if (!y_best || y < *y_best) {
        y_best = y;
        best_s = s;
      }
    }
    prev = cur;
  }
  if (!y_best) {
    throw InputError(fmt::format(
        "{}: the rail profile does not reach {:.3f} mm below its top on the gauge side; "
        "expected a rail head at least as deep as the gauge height",
        rail.source().empty() ? "rail profile" : rail.source(), gauge_height_m * 1e3));
  }
  // Refine on the spline: the level crossing near best_s.
  const auto c =
      loc.IntersectLine({*y_best - 1e-3, level}, {1.0, 0.0}, best_s - 1e-3, best_s + 1e-3);
  return {c ? *y_best - 1e-3 + c->lambda : *y_best, level};
}

WheelsetPlacement PlaceWheelset(const Profile& rail, const TrackSpec& track,
                                const WheelsetSpec& ws) {
  const double y_g = RailGaugePoint(rail, track.gauge_height_m).x();
  return PlaceWheelsetAt({y_g, y_g}, track, ws);
}

WheelsetPlacement PlaceWheelsetAt(const RailGaugePoints& gauge_points, const TrackSpec& track,
                                  const WheelsetSpec& ws) {
  WheelsetPlacement out;
  out.rail_gauge_point_y_m = gauge_points.right_y_m;
  // Right rail: its gauge point at Y = gauge/2, so its origin at Y = gauge/2 - y_g; the left
  // rail's at Y = -(gauge/2 - y_g,left), its y pointing to -Y.
  out.right_rail_origin_Y_m = 0.5 * track.gauge_m - gauge_points.right_y_m;
  out.left_rail_origin_Y_m = -(0.5 * track.gauge_m - gauge_points.left_y_m);
  // Right wheel: flange back at Y = fbd/2 + displacement, so its origin at that minus y_fb; the
  // wheelset yaws about its centre, so the origin lies (fbd/2 - y_fb) cos(yaw) from it in Y (and
  // (fbd/2 - y_fb) sin(yaw) behind the centre in x, which a prismatic rail does not see).
  const double half_span =
      (0.5 * ws.flange_back_distance_m - ws.flange_back_position_m) * std::cos(ws.yaw_rad);
  out.right.lateral_shift_m = half_span + ws.lateral_displacement_m - out.right_rail_origin_Y_m;
  out.right.roll_rad = ws.roll_rad;
  out.right.rolling_radius_m = ws.rolling_radius_m;
  out.right.yaw_rad = ws.yaw_rad;
  // Left: the mirror image, seen in its own (mirrored) frame: the wheel origin at
  // Y = -half_span + displacement, so y = -(Y - Y_left_origin); roll and yaw change sign.
  out.left = out.right;
  out.left.lateral_shift_m = half_span - ws.lateral_displacement_m + out.left_rail_origin_Y_m;
  out.left.roll_rad = -ws.roll_rad;
  out.left.yaw_rad = -ws.yaw_rad;
  return out;
}

KinematicRollResult KinematicRoll(const Profile& right_wheel, const Profile& right_rail,
                                  const Profile& left_wheel, const Profile& left_rail,
                                  const RailGaugePoints& gauge_points, const TrackSpec& track,
                                  WheelsetSpec wheelset, double sampling_m) {
  wheelset.yaw_rad = 0.0;
  const double half_span = 0.5 * wheelset.flange_back_distance_m - wheelset.flange_back_position_m;
  KinematicRollResult out;
  for (int step = 0; step < 2; ++step) {
    wheelset.roll_rad = out.roll_rad;
    const WheelsetPlacement placed = PlaceWheelsetAt(gauge_points, track, wheelset);
    const WheelRailGeometry right(right_wheel, right_rail, placed.right, sampling_m);
    const WheelRailGeometry left(left_wheel, left_rail, placed.left, sampling_m);
    if (!right.has_overlap() || !left.has_overlap()) {
      out.both_touch = false;
      return out;
    }
    // z is down: the right wheel's origin lower by dz_R - dz_L over the span 2 half_span.
    out.roll_rad =
        std::asin(std::clamp((right.dz_m() - left.dz_m()) / (2.0 * half_span), -0.1, 0.1));
  }
  return out;
}

}  // namespace railwear
