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
// wheel's contact (the study's elastic contact model) would first have a patch at 45 degrees or
// steeper (the flange's onset, FlangeOnsetOffset, found on the step's rails), and at the
// equilibrium when the wheel is in flange contact already (its flange force is the
// equilibrium's: an imposed position there would be wheel climb, not a vehicle's state).
// Weights: the entry's share (normalised per rail) times the node's weight over the vehicle's
// wheelsets.
#pragma once

#include <array>
#include <limits>
#include <string_view>
#include <vector>

#include "wear/traffic.h"
#include "wear/wear_simulation.h"

namespace railwear {

// The rails' gauge points in their own track-frame profiles: where the unworn rails stand.
RailGaugePoints UnwornGaugePoints(const WearStudy& study);

// The labels of a vehicle entry's curving starts (CurvingStart::label): the previous step's
// solution (WearState::curving), and the vehicle's equilibrium on the unworn rails
// (WearStudy::vehicle_starts).
inline constexpr std::string_view kPreviousStepStart = "the previous step's solution";
inline constexpr std::string_view kUnwornEquilibriumStart = "the unworn rails' equilibrium";

// The curving problem of study.traffic[traffic_index] (a vehicle entry) on these rails (track
// frame): the study's contact set-up, the unworn rails' places, its track, curve, vehicle, speed
// and friction, and its starts: `start` when it has a state, with study.vehicle_starts' as its
// fallback (CurvingOptions::fallback_starts) when there is one, else study.vehicle_starts'
// alone; the centred start after them (SolveCurving).
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
// curving did not converge there (its steps then start centred). Throws WearCancelled when
// study.options.cancel stopped a curving solve (it is passed on to every curving solve).
std::vector<CurvingStart> VehicleStarts(const WearStudy& study, const Profile& unworn_high,
                                        const Profile& unworn_low);
// VehicleStarts' entry `traffic_index` alone (a vehicle entry), without throwing: empty when its
// curving did not converge, and empty with *cancelled set when study.options.cancel stopped it
// (a lazy start's, CurvingStart::lazy).
CurvingStart VehicleStart(const WearStudy& study, int traffic_index, const Profile& unworn_high,
                          const Profile& unworn_low, bool* cancelled);

// A vehicle entry's curving on the rails of a step (both in the track frame, canted): the problem
// it solved and its solution, and whether that solution is only usable (stopped above its
// tolerance but within CurvingOptions::usable_multiple of it). Throws std::runtime_error naming
// the entry and the vehicle when the curving has no usable equilibrium (a flange-climb
// equilibrium is kept: its cases carry their L/V checks), WearCancelled when study.options.cancel
// stopped it mid-solve. The curving starts from `start`.
// With a spread, it also holds each wheelset's flange onsets (FlangeOnsetOffset, found once per
// step and side).
struct VehicleEquilibrium {
  CurvingProblem problem;
  CurvingResult result;
  bool usable = false;
  // Per wheelset, [0] toward the high rail and [1] toward the low rail: the largest lateral
  // offset [m, >= 0; infinity: none] a spread node takes from the equilibrium in that direction
  // (FlangeOnsetOffset, elastic, bounded by the study's rule's outermost node on that side:
  // OutermostSpreadNodes; beyond that node it is only a lower bound of the onset, so it holds
  // the rule's own nodes, not farther ones); empty without a spread.
  std::vector<std::array<double, 2>> flange_onset_m;
};
VehicleEquilibrium SolveVehicleEquilibrium(const WearStudy& study, int traffic_index,
                                           const Profile& high_track, const Profile& low_track,
                                           const CurvingStart* start = nullptr);

// The scan of FlangeOnsetOffset's bracket [spread standard deviations]: its first offset in flange
// contact and the one before it (0 first). Up to 32 std, beyond the outermost node of every rule
// (Gauss-Hermite's at kMaxQuadraturePoints: 16.9 std; the adaptive and piecewise-linear rules':
// 5), and independent of the rule, so every rule holds its nodes at the same position.
inline constexpr std::array<double, 8> kFlangeOnsetScanStd = {0.25, 0.5, 1.0,  2.0,
                                                              4.0,  8.0, 16.0, 32.0};
// FlangeOnsetOffset's bisection stops when its bracket is this narrow [m].
inline constexpr double kFlangeOnsetResolution_m = 1e-5;

// The rigid onset of flange contact of one wheel of a wheelset of a vehicle equilibrium, as the
// lateral offset [m, >= 0] from the equilibrium toward the rail of `side`: the last position of a
// bisection on kFlangeOnsetScanStd's bracket (scaled by the spread's standard deviation
// spread_std_m > 0) where that wheel's rigid first contact (its smallest vertical gap, on a 0.1
// mm sampling) stays below kFlangeContactAngle_rad, to kFlangeOnsetResolution_m; 0 when the
// wheel is in flange contact at the equilibrium already, infinity when it is not within 32 std.
// Geometry only: the elastic approach brings the flange into contact before this (below).
double RigidFlangeOnsetOffset(const VehicleEquilibrium& eq, int wheelset, RailSide side,
                              double spread_std_m);

// The onset of flange contact of one wheel of a wheelset of study.traffic[traffic_index] (a
// vehicle entry with a spread) at its equilibrium eq, as the lateral offset [m, >= 0] toward the
// rail of `side` that every spread node beyond it is held at: the last position below the first
// one where the contact the nodes solve (LoadCaseProblem, the study's contact model, elastic) has
// a patch at kFlangeContactAngle_rad or steeper (or does not converge), found on
// kFlangeOnsetScanStd's offsets below the rigid onset and the rigid onset itself, then bisected
// to kFlangeOnsetResolution_m. The rigid onset (RigidFlangeOnsetOffset) when no such position
// lies below it; 0 and infinity as there. So a node never puts a flange patch into the contact
// (its approach of about 0.1 mm brings one in up to 0.06 mm before the rigid onset on a worn
// gauge corner: docs/wear.md, "The spike below the flange onset"). A few contact solves per
// wheelset and side with a finite rigid onset. Found once per wheelset, side and step
// (SolveVehicleEquilibrium), so every node beyond it is held at exactly this offset.
// enough_m: as soon as the scan or the bisection has shown that the onset lies at or beyond this
// offset, their bracket's lower end is returned instead (at or beyond enough_m, at or below the
// onset): a node at or below enough_m is then held by neither value, so the nodes' cases are the
// same as with the onset itself, for fewer contact solves (SolveVehicleEquilibrium passes the
// rule's outermost node).
double FlangeOnsetOffset(const WearStudy& study, int traffic_index, const VehicleEquilibrium& eq,
                         int wheelset, RailSide side,
                         double enough_m = std::numeric_limits<double>::infinity());

// The outermost nodes of the options' spread rule (SpreadRuleOf) [standard-normal units, >= 0]:
// [0] the largest node toward the high rail (x > 0), [1] toward the low rail (-x for x < 0):
// the Gauss-Hermite rule's outer node, the piecewise-linear rule's ends, the adaptive rule's
// first nodes (kSpreadInitialNodes: it only bisects between nodes).
std::array<double, 2> OutermostSpreadNodes(const WearOptions& o);

// The two load cases (high rail, then low) of one wheelset of a vehicle entry at the spread
// node x [standard-normal units]: the wheelset displaced by lateral_shift_std_m x from its
// equilibrium, held at eq.flange_onset_m beyond it (see above), numbered `node`, weighted by the
// entry's share over its rail's total x node_weight / wheelsets.
std::vector<LoadCase> VehicleNodeCases(const WearStudy& study, int traffic_index,
                                       const VehicleEquilibrium& eq, int wheelset, double x,
                                       int node, double node_weight);

namespace internal {
// VehicleNodeCases at the lateral offset offset_m [m] from the equilibrium (toward the high rail
// for > 0) as given, without the hold at the flange onset; x is the cases' spread_x.
std::vector<LoadCase> VehicleCasesAtOffset(const WearStudy& study, int traffic_index,
                                           const VehicleEquilibrium& eq, int wheelset,
                                           double offset_m, double x, int node, double node_weight);
}  // namespace internal

// The load cases of study.traffic[traffic_index] (a vehicle entry) on the rails of this step,
// both in the track frame (canted). Throws std::runtime_error naming the entry and the vehicle
// when the curving has no equilibrium or does not converge (a flange-climb equilibrium is kept:
// its cases carry their L/V checks). The curving starts from `start` (VehicleCurvingProblem) and,
// when `solved` is given, leaves its solution there (the next step's start). Each wheelset at
// the fixed rule's Gauss-Hermite nodes (WearOptions::quadrature_points), one node without spread.
std::vector<LoadCase> VehicleLoadCases(const WearStudy& study, int traffic_index,
                                       const Profile& high_track, const Profile& low_track,
                                       const CurvingStart* start = nullptr,
                                       CurvingStart* solved = nullptr);

}  // namespace railwear
