// Vehicle traffic in a wear step: the load cases of a traffic entry that names a vehicle, from
// steady-state curving (core/vehicle/curving.h) on the current worn rails.
//
// Each step solves the vehicle's equilibrium on the step's rails (both canted into the track
// frame; the rails keep the unworn rails' places, so the wheels follow the worn gauge face) and
// emits, per wheelset and rail, that wheel's contact: its placement in the rail's own frame, its
// vertical load (with the load transfer), its own forward speed, the axle's pitch velocity from
// the free-rolling (or traction) balance and the curve's yaw rate. With a lateral spread
// (lateral_shift_std_m: track irregularity, hunting) every wheelset is also placed at the
// Gauss-Hermite nodes around its equilibrium at the same yaw, roll, loads and pitch velocity;
// a node never pushes a wheel into flange contact: its offset toward a rail stops where that
// wheel's rigid contact reaches 45 degrees (the flange's onset, found on the step's rails), and
// at the equilibrium when the wheel is in flange contact already (its flange force is the
// equilibrium's: an imposed position there would be wheel climb, not a vehicle's state). Weights:
// the entry's share (normalised per
// rail) times the node's weight over the vehicle's wheelsets.
#pragma once

#include <vector>

#include "wear/traffic.h"
#include "wear/wear_simulation.h"

namespace railwear {

// The rails' gauge points in their own track-frame profiles: where the unworn rails stand.
RailGaugePoints UnwornGaugePoints(const WearStudy& study);

// The curving problem of study.traffic[traffic_index] (a vehicle entry) on these rails (track
// frame): the study's contact set-up, the unworn rails' places, its track, curve, vehicle, speed
// and friction, and its start: `start` when it has a state, else study.vehicle_starts' when
// there is one.
CurvingProblem VehicleCurvingProblem(const WearStudy& study, int traffic_index,
                                     const Profile& high_track, const Profile& low_track,
                                     const CurvingStart* start = nullptr);

// A rail of a study in the track frame: each canted with its unworn profile's motion.
Profile RailInTrack(const WearStudy& study, const Profile& unworn, const Profile& current);

// Both unworn rails of a two-rail study (as the scene gives them) in the track frame: where
// `railwear curving` and its accuracy study solve each vehicle.
struct TrackRails {
  Profile high, low;
};
TrackRails UnwornRailsInTrack(const WearStudy& study);

// Each vehicle entry's curving solution on the unworn rails (own frames, as in a step-0 state),
// for WearStudy::vehicle_starts: an empty vector for prescribed entries and for a vehicle whose
// curving did not converge there (its steps then start centred).
std::vector<CurvingStart> VehicleStarts(const WearStudy& study, const Profile& unworn_high,
                                        const Profile& unworn_low);

// The load cases of study.traffic[traffic_index] (a vehicle entry) on the rails of this step,
// both in the track frame (canted). Throws std::runtime_error naming the entry and the vehicle
// when the curving has no equilibrium or does not converge (a flange-climb equilibrium is kept:
// its cases carry their L/V checks). The curving starts from `start` (VehicleCurvingProblem) and,
// when `solved` is given, leaves its solution there (the next step's start).
std::vector<LoadCase> VehicleLoadCases(const WearStudy& study, int traffic_index,
                                       const Profile& high_track, const Profile& low_track,
                                       const CurvingStart* start = nullptr,
                                       CurvingStart* solved = nullptr);

}  // namespace railwear
