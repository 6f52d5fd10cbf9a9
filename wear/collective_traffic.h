// Imported load collectives as wear traffic: a [[traffic]] entry that names a collective
// (wear/load_collective.h, an MBS time history binned per rail) gives each of its bins as one
// load case on the bin's rail (docs/mbs_import.md, "How it becomes traffic").
//
// A collective is prescribed traffic in wheelset terms: each bin's wheelset state (lateral
// displacement y, yaw, roll in the track frame) is placed with PlaceWheelsetAt on the unworn
// rails' gauge points (UnwornGaugePoints, as vehicle traffic does), and the positions stay fixed
// in the unworn track frame at every step: the wheels do not follow the worn gauge face (vehicle
// traffic does). A bin of the high rail loads the right wheel of that placement, a bin of the
// low rail the left wheel in its mirrored rail frame. Each case carries the bin's wheel load Q,
// its speed V (the wheelset centre's), each wheel's motion on the curve (CurveWheelMotions:
// speed V (1 + Y_w / R), yaw rate -V / R) and the bin's friction (else the entry's).
//
// Pitch velocity: pure rolling at r0 (none set) unless the bin has a longitudinal creepage xi.
// Then the wheel's pitch velocity Omega makes the creepage of its rolling circle at the rigid
// contact point xi (core/notation.md: slip v_x = V_w + Omega r_c, xi = v_x / V_w):
//   Omega = -(1 - xi) V_w / r_c,
// V_w the wheel's own forward speed (CurveWheelMotions), r_c the wheel's rolling radius at its
// rigid contact point (the smallest gap of the placed wheel on the unworn rail, canted into the
// track frame). xi > 0: the wheel turns slower than it would roll there, as under braking (the
// creep force on the wheel opposes the slip: F_x = -G c^2 C11 xi points backward). xi = 0 is
// pure rolling at the contact point; the rolling-radius difference of a shifted wheelset is part
// of xi, as in MBS codes, which give xi at their contact point.
//
// Weights and passes: the entry's share is normalised per rail with the other entries (a
// collective entry counts on each rail where it has bins), and each case's weight is that times
// the bin's share on its rail, so each rail's weights sum to 1. A collective's weights count
// wheel passes; one axle pass of the entry is one wheel on each rail, so its axle load for the
// MGT count is the mean of the two rails' share-weighted axle loads (CollectiveAxleLoad_t).
#pragma once

#include <memory>
#include <vector>

#include "core/profile/profile.h"
#include "wear/load_collective.h"
#include "wear/traffic.h"

namespace railwear {

struct WearStudy;

// What a collective traffic entry needs besides TrafficCase's wheel profile, rolling radius
// (r0 at the profile's z = 0), friction (for bins without mu), share and axle load: the collective
// and the wheelset's geometry for PlaceWheelsetAt.
struct CollectiveTraffic {
  LoadCollective collective;
  double flange_back_distance_m = 1.360;   // between the flange backs, > 0
  double flange_back_position_m = -0.070;  // y of the flange back in the wheel profile frame
};

// The axle load of one axle pass of a collective [t]: the mean of the high and low rail's
// share-weighted mean bin axle_load_t (a rail without bins left out). With axle loads from
// 2 Q / g this is (mean Q_high + mean Q_low) / g, the load transfer cancelling.
double CollectiveAxleLoad_t(const LoadCollective& collective);

// The wheel's rolling radius at its rigid contact point [m]: the wheel placed by `pose` on
// `rail_track` (the rail canted into the track frame, own frame), lowered to first contact; the
// candidate of smallest gap. Throws std::runtime_error when the wheel does not reach the rail.
double RigidContactRadius(const Profile& wheel, const Profile& rail_track, const WheelPose& pose);

// Omega [rad/s] such that the longitudinal creepage at the contact radius r_c [m] of a wheel
// moving forward at wheel_speed [m/s] is xi: -(1 - xi) wheel_speed / r_c.
double PitchVelocityForCreepage(double xi, double wheel_speed_m_s, double contact_radius_m);
// The inverse: xi = 1 + Omega r_c / wheel_speed (for writing a CSV from known motions).
double CreepageForPitchVelocity(double pitch_velocity_rad_s, double wheel_speed_m_s,
                                double contact_radius_m);

// The load cases of study.traffic[traffic_index] (a collective entry), one per bin in the
// collective's order (high rail first), node 0. Needs a study with a low rail (its track and
// curve give the placement and the motions).
std::vector<LoadCase> CollectiveLoadCases(const WearStudy& study, int traffic_index);

}  // namespace railwear
