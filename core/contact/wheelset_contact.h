// A wheelset on a track: both wheels' contact, each on its rail (core/geometry/wheelset.h).
//
// The right-hand wheel and rail profiles of `wheel_rail` serve both sides: in the track the left
// wheel and rail are their mirror images, which in the left rail's own frame (y toward its field
// side, core/notation.md) are the same profiles; so results of the left wheel (positions,
// lateral forces, lateral creepage, spin) are in the left rail profile's own coordinates. Both
// wheels carry the same vertical load and share the axle's pitch velocity; the left wheel sees the
// mirrored yaw and roll. Prescribed creepages (RollingOptions::creepage) apply to each wheel in its
// own frame. Under a prescribed load each wheel is balanced vertically with its creep forces
// (SolveContact); with an axle force target the balanced solves and the pitch-velocity search
// alternate until both hold, each round's balance starting from the last round's balanced state
// (a warm NormalPartMemo, normal_part_memo.h: the balance to its tolerance from a nearer start).
// Each wheel's FlangeClimbCheck (L/V, Nadal) is in its own rail frame.
//
// kind = hertz with rolling contact puts both wheels on the fast tread path (hertz_tread.h): each
// wheel is placed, solved and balanced as a single wheel's fast path does it, and an axle force
// target is met by a pitch search over those whole solves. When either wheel's contact is not one
// Hertzian patch (at the search's pitch velocities too), the whole wheelset is solved by the full
// path with kind = auto at the same accuracy, and every patch's model_reason starts with "fast
// tread path not valid: " and the wheel and reason.
#pragma once

#include "core/contact/contact_solver.h"
#include "core/contact/hertz_tread.h"
#include "core/contact/placement_cache.h"
#include "core/geometry/wheelset.h"

namespace railwear {

struct WheelsetProblem {
  ContactProblem wheel_rail;  // right-hand profiles, materials, model, load per wheel, rolling
  TrackSpec track;
  WheelsetSpec wheelset;
  // Two different rails, unequal loads and a curve (the defaults: the same rail and load on both
  // sides, tangent track).
  std::optional<Profile> left_rail_profile;  // the left rail in its own frame (y to its field)
  // The left wheel in its own frame (mirrored as the left rail's) when it differs from the right
  // one (worn wheels of a wheelset wear differently in a curve); absent: wheel_rail.wheel_profile.
  std::optional<Profile> left_wheel_profile;
  // Where the rails stand (each gauge point in its own rail's frame); absent: from the profiles.
  // A worn rail keeps its unworn place: pass the unworn rails' gauge points.
  std::optional<RailGaugePoints> gauge_points;
  // The left wheel's vertical load [N] when it differs from wheel_rail.load (curving's load
  // transfer); only with a prescribed vertical load.
  std::optional<double> left_vertical_force_N;
  // Track curvature 1/R [1/m], >= 0, the curve turning left (toward -Y, the right rail high):
  // each wheel's origin moves forward at V (1 + curvature Y_w), Y_w its Y, V the speed of the
  // wheelset centre (wheel_rail.rolling->motion.speed_m_s), and the wheelset turns at -V/R
  // (WheelMotion::yaw_velocity_rad_s), so every cell slips with its own distance from the
  // curve's centre. Without a prescribed pitch velocity the axle rolls at -V/r0. The axle's
  // lateral and yaw velocity (wheel_rail.rolling->motion) are the wheelset's in the track frame,
  // mirrored for the left wheel (CurveWheelMotions), with or without curvature.
  double curvature_per_m = 0.0;
  // How closely the wheels' F_x must add up to an axle force target [N]; absent: 1e-6 mu F_n
  // (F_n both wheels' normal forces). Each round of the search solves both wheels again, so a
  // caller with a coarser tolerance of its own (steady-state curving) passes it here.
  std::optional<double> axle_force_tolerance_N;
};

struct WheelsetResult {
  WheelsetPlacement placement;
  ContactResult right;
  ContactResult left;
  // Each wheel's contact point in its wheel frame when the wheelset took the fast tread path
  // (kind = hertz with rolling: hertz_tread.h); absent on every other path.
  std::optional<HertzTreadPoint> right_tread_point, left_tread_point;
};

// Each wheel's motion on a curve of the given curvature (1/R, turning toward -Y), with the
// wheelset's own lateral and yaw velocity (`axle`, in the track frame: dY/dt, and the yaw rate
// against the curve, e.g. a co-simulation's wheelset moving across the track): the wheel's
// origin moves at V (1 + curvature Y_w) - yaw_rate Y_w, the wheelset turns at
// yaw_rate - V curvature, each wheel moves across at the lateral velocity (the left rail's frame
// mirrors the last two), and both share the axle's pitch velocity (-V/r0 when `axle` has none).
// `axle` is the wheelset centre's motion; with curvature 0 and no lateral or yaw velocity both
// wheels get it unchanged.
struct WheelMotions {
  WheelMotion right, left;
};
WheelMotions CurveWheelMotions(const WheelMotion& axle, const WheelsetPlacement& placed,
                               double curvature_per_m, double rolling_radius_m);

// Throws InputError as SolveContact does, and when the rail is too shallow for the gauge height.
// `cache` (optional) keeps both wheels' placed geometries between calls (placement_cache.h):
// the same results, bit for bit.
// right_warm, left_warm (optional, in/out, both or neither): each wheel's grid solve starts
// from its last call's measured patch and balance as a single wheel's does
// (contact_warm_start.h) and keeps its own; not used on the fast tread path. With an axle force
// target the first solve of each wheel starts warm and keeps its state, and the balance rounds
// continue from that solve's normal part (its memo) as a cold call's rounds continue from the
// cold solve's: a warm attempt that does not fit falls back to the cold call, bit for bit.
WheelsetResult SolveWheelset(const WheelsetProblem& problem, PlacementCache* cache = nullptr,
                             ContactWarmStart* right_warm = nullptr,
                             ContactWarmStart* left_warm = nullptr);

}  // namespace railwear
