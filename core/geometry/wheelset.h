// A wheelset on a track: where each wheel stands on its rail.
//
// Track frame T (core/notation.md): x forward, Y lateral positive to the right, z down, origin
// at the track centre line. The right rail's profile frame has y = Y - Y_right (toward its field
// side); the left rail is the mirror image: its profile frame has y = -(Y - Y_left), so both
// rails, and both wheels, are described with the same (right-hand) profiles: in the track the
// left ones are mirror images, in their own frames they are the same curves. Gauge is measured
// between the gauge faces at `gauge_height` below the top of rail; the flange backs of the wheels
// are `flange_back_distance` apart when the wheelset is centred.
#pragma once

#include "core/geometry/wheel_rail_geometry.h"
#include "core/profile/profile.h"

namespace railwear {

struct TrackSpec {
  double gauge_m = 1.435;         // between the gauge faces, > 0
  double gauge_height_m = 0.014;  // below the top of rail where the gauge is measured, >= 0
};

struct WheelsetSpec {
  double flange_back_distance_m = 1.360;
  // y of the flange back in the wheel profile frame (S1002: -70 mm, the taping line being 70 mm
  // from the flange back).
  double flange_back_position_m = -0.070;
  double lateral_displacement_m = 0.0;  // of the wheelset toward +Y (flange contact on the right)
  double yaw_rad = 0.0;                 // about +z (down): positive turns the nose toward +Y
  double roll_rad = 0.0;                // about +x: positive lowers the right wheel
  double rolling_radius_m = 0.46;
};

struct WheelsetPlacement {
  WheelPose right;  // in the right rail's profile frame
  WheelPose left;   // in the left rail's own profile frame (y toward its field side)
  double right_rail_origin_Y_m = 0.0;  // Y of the right rail profile's origin
  double left_rail_origin_Y_m = 0.0;   // Y of the left rail profile's origin (negative)
  double rail_gauge_point_y_m = 0.0;   // the right rail's gauge point in its frame (negative)
};

// Where each rail's gauge point lies in its own profile frame [m] (negative: gauge side). A worn
// rail keeps the unworn rail's place in the track: its placement uses the unworn gauge points.
struct RailGaugePoints {
  double right_y_m = 0.0;
  double left_y_m = 0.0;
};

// The gauge point of a rail profile: the gauge-side crossing (smallest y) of the level
// gauge_height below its highest point. Throws InputError when the profile does not reach that
// depth on its gauge side.
Eigen::Vector2d RailGaugePoint(const Profile& rail, double gauge_height_m);

// Places both wheels. `rail` is the right-hand rail profile; `left` holds the left wheel's pose
// in the left rail's own frame, where the same profiles describe the mirrored pair.
WheelsetPlacement PlaceWheelset(const Profile& rail, const TrackSpec& track,
                                const WheelsetSpec& wheelset);

// Places both wheels on rails whose gauge points are given (each in its own rail's frame): the
// rails may differ (a worn high rail and a worn low rail), and stay where the gauge points put
// them.
WheelsetPlacement PlaceWheelsetAt(const RailGaugePoints& gauge_points, const TrackSpec& track,
                                  const WheelsetSpec& wheelset);

// The wheelset's kinematic roll: the roll at which both wheels touch their rails, at the
// wheelset's lateral displacement and yaw 0 (its roll and yaw are not read). Two fixed-point
// steps on the wheels' heights from roll 0 (the roll moves them by roll x the wheel's lateral
// slope, a contraction of about 0.05), each on both wheels' placed geometries sampled at
// sampling_m. both_touch is false when a wheel has no overlap with its rail at a step; roll_rad
// is then the roll reached before it.
struct KinematicRollResult {
  double roll_rad = 0.0;
  bool both_touch = true;
};
KinematicRollResult KinematicRoll(const Profile& right_wheel, const Profile& right_rail,
                                  const Profile& left_wheel, const Profile& left_rail,
                                  const RailGaugePoints& gauge_points, const TrackSpec& track,
                                  WheelsetSpec wheelset, double sampling_m);

}  // namespace railwear
