// Placed wheel-rail geometries kept between the solves of one caller (a C API handle stepping
// an MBS time loop, issue 20): a WheelRailGeometry is a pure function of the wheel and rail
// profiles and the pose (lateral shift, roll, rolling radius, yaw), so a solve on the same
// profiles at the same pose reuses the one built before instead of placing the wheel again
// (the yawed outline, both locators and the gap function: about 40 % of a draft tread call,
// docs/library.md). The reuse is exact: the cached geometry is the object a new placement would
// build, bit for bit. A different profile or pose replaces the entry; profiles are compared by
// their points (a Profile is a function of its points). A wheelset's rails' gauge points
// (RailGaugePoint, wheelset.h: 1.4 ms of a 1.6 ms fast-tread wheelset call, which depend on the
// rail and the gauge height alone) are kept the same way.
#pragma once

#include <memory>

#include "core/geometry/wheel_rail_geometry.h"
#include "core/profile/profile.h"

namespace railwear {

class PlacementCache {
 public:
  // One entry per wheel of a problem: kRight (a single wheel, or a wheelset's right one) and
  // kLeft.
  enum Slot { kRight = 0, kLeft = 1 };

  // The geometry of `wheel` placed on `rail` at `pose`: the cached one when the slot holds the
  // same profiles and pose, else built (and kept). The reference is valid until the next Get of
  // the same slot. Throws as WheelRailGeometry's constructor does.
  const WheelRailGeometry& Get(Slot slot, const Profile& wheel, const Profile& rail,
                               const WheelPose& pose);

  // The geometry the last Get of `slot` returned (null before the first): the C API reads the
  // wheel's placement of its last solve here (the wheel-frame contact location).
  const WheelRailGeometry* Last(Slot slot) const { return entries_[slot].geometry.get(); }

  // RailGaugePoint(rail, gauge_height_m) (core/geometry/wheelset.h): the kept one when the slot
  // holds the same rail and height, else computed (and kept). Throws as RailGaugePoint does.
  // Not counted in hits() and misses().
  Eigen::Vector2d GaugePoint(Slot slot, const Profile& rail, double gauge_height_m);

  int hits() const { return hits_; }      // calls that reused a geometry
  int misses() const { return misses_; }  // calls that built one

 private:
  struct Entry {
    // Owned copies: the geometry's locators refer to these profiles.
    std::unique_ptr<const Profile> wheel, rail;
    WheelPose pose;
    std::unique_ptr<const WheelRailGeometry> geometry;
  };
  Entry entries_[2];
  struct GaugeEntry {
    std::unique_ptr<const Profile> rail;
    double height_m = 0.0;
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
  };
  GaugeEntry gauge_[2];
  int hits_ = 0, misses_ = 0;
};

}  // namespace railwear
