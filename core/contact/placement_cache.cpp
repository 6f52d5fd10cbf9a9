// Placed geometries kept between solves (placement_cache.h).
#include "core/contact/placement_cache.h"

#include "core/geometry/wheelset.h"

namespace railwear {

namespace {

bool SamePose(const WheelPose& a, const WheelPose& b) {
  return a.lateral_shift_m == b.lateral_shift_m && a.roll_rad == b.roll_rad &&
         a.rolling_radius_m == b.rolling_radius_m && a.yaw_rad == b.yaw_rad;
}

}  // namespace

const WheelRailGeometry& PlacementCache::Get(Slot slot, const Profile& wheel, const Profile& rail,
                                             const WheelPose& pose) {
  Entry& e = entries_[slot];
  if (e.geometry && SamePose(e.pose, pose) && e.wheel->points() == wheel.points() &&
      e.rail->points() == rail.points()) {
    ++hits_;
    return *e.geometry;
  }
  ++misses_;
  // A failed construction leaves the slot empty, not half replaced.
  e.geometry.reset();
  if (!e.wheel || e.wheel->points() != wheel.points()) e.wheel = std::make_unique<Profile>(wheel);
  if (!e.rail || e.rail->points() != rail.points()) e.rail = std::make_unique<Profile>(rail);
  e.pose = pose;
  e.geometry = std::make_unique<const WheelRailGeometry>(*e.wheel, *e.rail, pose);
  return *e.geometry;
}

Eigen::Vector2d PlacementCache::GaugePoint(Slot slot, const Profile& rail, double gauge_height_m) {
  GaugeEntry& e = gauge_[slot];
  if (e.rail && e.height_m == gauge_height_m && e.rail->points() == rail.points()) return e.point;
  const Eigen::Vector2d point = RailGaugePoint(rail, gauge_height_m);  // throws: nothing kept
  e.rail = std::make_unique<const Profile>(rail);
  e.height_m = gauge_height_m;
  e.point = point;
  return point;
}

}  // namespace railwear
