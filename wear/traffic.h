// Traffic mix of a wear run: the wheels that pass over the rails, each with its share of passes,
// and their expansion into the load cases one wear step solves.
//
// Two rails (issue 15): an entry loads the high (outer, right, +Y of the track frame) or the low
// rail (`rail`, default high). A pass is one axle, one wheel on each rail: shares are normalised
// per rail, so each rail's case weights sum to 1, and the MGT of a pass is counted from the high
// rail's entries (from the low rail's when the mix has no high-rail entry).
//
// A traffic entry's lateral wheel position is normally distributed (mean, standard deviation):
// the expectation over it is integrated by Gauss-Hermite quadrature (probabilists' form, nodes
// and weights by the Golub-Welsch eigenvalue method), so a load case is one traffic entry at one
// quadrature node, weighted by share x quadrature weight. With std = 0 an entry is one load case.
//
// Totals: a wheel pass of entry c carries axle_load_t of gross tonnage, so one pass of the mix
// is sum_c share_c axle_load_t_c / (1e6 sum_c share_c) MGT (million gross tonnes), over the
// entries of the high rail (or of the low rail when there are none on the high rail). Vehicle
// and collective entries count on every rail they run on (TrafficCase::RunsOn).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/contact/contact_problem.h"
#include "core/contact/kinematics.h"
#include "core/numerics/enum_names.h"
#include "core/profile/profile.h"
#include "core/vehicle/curving.h"
#include "wear/friction_condition.h"

namespace railwear {

// Which rail a wheel runs on. The high rail is the outer (right, +Y) rail of a curve, the low rail
// the inner (left) one; on tangent track simply right and left (core/notation.md). Each rail is
// described in its own rail frame (the low rail's mirrored, y toward its own field side).
enum class RailSide { kHigh, kLow };
inline constexpr std::array<EnumName<RailSide>, 2> kRailSideNames = {{
    {RailSide::kHigh, "high"},
    {RailSide::kLow, "low"},
}};
std::string_view ToString(RailSide side);
// std::nullopt for anything but "high" and "low".
std::optional<RailSide> RailSideFromString(std::string_view name);

struct CollectiveTraffic;  // wear/collective_traffic.h

// Co-evolution (issue 16 point 6, wear/wheel_wear.h): the wheel of a traffic entry wears with the
// rail, from the same contact solutions, and its profile is updated every step.
struct WheelWear {
  // The distance the entry's wheel rolls, on track with this section's contact conditions, each
  // time the entry passes the section [m], > 0. Each wheel point passes the patch once per
  // revolution, so per pass a wheel point at radius r meets the patch L / (2 pi r) times
  // (wear/wheel_wear.h). E.g. a vehicle on a loop whose curves are like this one: their length
  // per lap; a fleet of N wheels sharing the entry's passes: that length over N.
  double distance_per_pass_m = 0.0;
  // The wheel's hardness [Pa] for Archard and KTH; absent: the study's wheel_material's.
  std::optional<double> hardness_Pa;
};

struct TrafficCase {
  std::string name;                   // for messages and reports, e.g. "traffic[0]"
  Profile wheel_profile;              // wheel profile frame (core/notation.md)
  double rolling_radius_m = 0.46;     // wheel radius at the wheel profile's z = 0, > 0
  double vertical_force_N = 0.0;      // wheel load on this rail, > 0
  double axle_load_t = 0.0;           // axle load for the MGT count [tonnes], > 0
  double lateral_shift_mean_m = 0.0;  // wheel profile origin in the track frame [m]
  double lateral_shift_std_m = 0.0;   // >= 0
  double roll_rad = 0.0;
  double yaw_rad = 0.0;   // angle of attack of the wheel [rad]
  double friction = 0.3;  // > 0, the top of rail's mu (a condition's unless the scene gave it)
  // Friction conditions (issue 16, wear/friction_condition.h): the top of rail's, absent for
  // none (the laws' dry coefficients, factor 1, at `friction`), and the gauge face's (patches
  // steeper than WearOptions::conditions.gauge_face_angle_rad), absent for the top of rail's.
  // The gauge face is solved at its condition's mu and both zones' wear follows their factors.
  std::optional<FrictionCondition> condition;
  std::optional<FrictionCondition> gauge_face_condition;
  double speed_m_s = 20.0;  // > 0
  double share = 1.0;       // relative share of passes, > 0 (normalised over its rail's entries)
  RailSide rail = RailSide::kHigh;  // the rail this wheel runs on
  // Vehicle traffic (issue 15): the index of a vehicle (WearStudy::vehicles), -1 for prescribed
  // traffic. A vehicle entry's load cases come from steady-state curving on the current rails,
  // on both rails; it uses name, speed_m_s, friction, share, lateral_shift_std_m (the spread of
  // every wheelset around its equilibrium) and axle_load_t (the vehicle's, for MGT); its wheel is
  // the vehicle's.
  int vehicle = -1;
  bool is_vehicle() const { return vehicle >= 0; }
  // Collective traffic (issue 15, wear/collective_traffic.h): an imported MBS load collective,
  // null for other entries. Each bin is one load case on its rail, at its wheelset state placed
  // on the unworn rails; the entry uses name, wheel_profile, rolling_radius_m, friction (for
  // bins without mu), share (counted on each rail where the collective has bins) and
  // axle_load_t (one axle pass: CollectiveAxleLoad_t unless the scene gives it).
  std::shared_ptr<const CollectiveTraffic> collective;
  bool is_collective() const { return collective != nullptr; }
  // Co-evolution (issue 16): present when this entry's wheel wears. A prescribed or collective
  // entry's one wheel: its current profile is then WearState::wheels[index of this entry];
  // wheel_profile stays the unworn one. A vehicle entry's wheels: both wheels of every wheelset
  // wear, each on its own (WearState::vehicle_wheels), from the vehicle's wheel_profile.
  std::optional<WheelWear> wheel_wear;
  bool wears_wheel() const { return wheel_wear.has_value(); }
  // A vehicle entry whose wheels wear: each wheelset's current wheels, from the front (set by the
  // wear step from WearState::vehicle_wheels), run by its curving and its load cases; empty: the
  // vehicle's wheel_profile on every wheel.
  std::vector<WheelsetWheels> vehicle_wheels;
  // Whether this entry's wheels load `side`: a vehicle both rails, a collective the rails it has
  // bins on, a prescribed entry its `rail`.
  bool RunsOn(RailSide side) const;
};

// One contact problem of a wear step, self-contained: everything the contact needs for one wheel
// except the wheel itself (profile, name, from study.traffic[traffic_index]). Prescribed traffic,
// imported collectives and vehicle curving all produce these.
struct LoadCase {
  int traffic_index = 0;            // the entry it comes from (name, wheel profile, axle load)
  int node = 0;                     // quadrature node (0 without spread), in order of spread_x
  int wheelset = 0;                 // vehicle entries: the wheelset of the vehicle; else 0
  double spread_x = 0.0;            // the node in standard-normal units (0 without spread)
  RailSide rail = RailSide::kHigh;  // which rail it loads
  // In that rail's own frame (mirrored for the low rail): lateral shift [m], roll, yaw [rad] and
  // the rolling radius at the wheel profile's z = 0 [m].
  WheelPlacement placement;
  double vertical_force_N = 0.0;  // wheel load, > 0
  // The wheel's forward speed and, when set, its pitch velocity (absent: pure rolling at r0).
  WheelMotion motion;
  double friction = 0.3;  // > 0
  double weight = 0.0;    // share (normalised per rail) x quadrature weight; sums to 1 per rail
  // Vehicle cases: the curving equilibrium's largest scaled residual (CurvingResult) and whether
  // it met the tolerance (false: accepted within CurvingOptions::usable_multiple x tolerance, with
  // a warning).
  double equilibrium_residual = 0.0;
  bool equilibrium_converged = true;
};

// The wheel profile a load case of `entry` runs: a vehicle entry's wheelset's wheel on the case's
// rail when the entry carries its wheelsets' wheels (TrafficCase::vehicle_wheels), else the
// entry's wheel_profile.
const Profile& CaseWheelProfile(const TrafficCase& entry, const LoadCase& load_case);

// The index of a wearing wheel within its traffic entry (co-evolution's steps and storage,
// profiles_db wheel_steps.wheel): 0 is a prescribed or collective entry's one wheel; a vehicle
// entry's wheels are 1 + 2 x wheelset + (0 for the high rail's wheel, 1 for the low rail's).
inline int VehicleWheelIndex(int wheelset, RailSide side) {
  return 1 + 2 * wheelset + (side == RailSide::kLow ? 1 : 0);
}
// The wheelset and rail of a vehicle wheel index (>= 1).
inline int WheelsetOfWheel(int wheel) { return (wheel - 1) / 2; }
inline RailSide RailOfWheel(int wheel) { return (wheel - 1) % 2 == 0 ? RailSide::kHigh : RailSide::kLow; }
// A wearing wheel's name for reports and storage: the entry's, and for a vehicle wheel
// "ENTRY / wheelset W high" (or low).
std::string WheelName(const TrafficCase& entry, int wheel);

// The most fixed Gauss-Hermite nodes per spread: at least the adaptive rule's most nodes per
// spread (kMaxSpreadNodes, wear/spread_integration.h), so that fixed rules as fine as the adaptive
// one can be compared with it (issue 16's studies of 15 to 61 fixed nodes, docs/wear.md). Was 20,
// then 41.
inline constexpr int kMaxQuadraturePoints = 81;

// Nodes x_k and weights w_k (sum 1) with E[f(X)] ~ sum_k w_k f(x_k) for X ~ N(0, 1), exact for
// polynomials up to degree 2n - 1. n in [1, kMaxQuadraturePoints].
void GaussHermiteProbabilists(int n, std::vector<double>* nodes, std::vector<double>* weights);

// The fixed rule's nodes and weights over a spread [standard-normal units]: the piecewise-linear
// rule on linear_nodes (LinearGaussianWeights) when it is not empty, else quadrature_points
// Gauss-Hermite nodes (WearOptions::spread_nodes, quadrature_points).
void FixedSpreadRule(int quadrature_points, const std::vector<double>& linear_nodes,
                     std::vector<double>* nodes, std::vector<double>* weights);

// Checks every entry (positive loads, radii, speeds, friction, shares; std >= 0; finite values;
// wheel wear only on prescribed and collective entries, with a positive distance and hardness)
// and throws InputError naming the entry and the value.
void ValidateTraffic(const std::vector<TrafficCase>& traffic);

// Throws InputError unless quadrature_points (Gauss-Hermite nodes per entry) is 1 to
// kMaxQuadraturePoints.
void ValidateQuadraturePoints(int quadrature_points);

// The load cases of the mix's prescribed entries (vehicle entries give theirs in the wear step,
// from curving; collective entries theirs from wear/collective_traffic.h): each entry at
// `quadrature_points` Gauss-Hermite nodes (1 when its std is 0), in entry order. The weights of
// each rail's cases sum to 1. Validates the traffic and quadrature_points.
std::vector<LoadCase> ExpandTraffic(const std::vector<TrafficCase>& traffic, int quadrature_points);

namespace internal {
// ExpandTraffic without its checks, for the wear loop, whose study was validated once at its
// entry (ValidateWearStudy): the traffic is not checked again at every step. With linear_nodes
// (WearOptions::spread_nodes, not empty) every spread takes the piecewise-linear rule on those
// nodes (LinearGaussianWeights) instead of quadrature_points Gauss-Hermite nodes.
std::vector<LoadCase> ExpandValidTraffic(const std::vector<TrafficCase>& traffic,
                                         int quadrature_points,
                                         const std::vector<double>& linear_nodes = {});

// The load case of prescribed entry traffic[t] at the spread node x [standard-normal units]:
// lateral shift mean + std x, numbered `node`, weighted by the entry's share over its rail's
// total (rail_share_totals, RailShareTotals) x node_weight.
LoadCase PrescribedNodeCase(const std::vector<TrafficCase>& traffic, int t,
                            const std::array<double, 2>& rail_share_totals, double x, int node,
                            double node_weight);
}  // namespace internal

// A measured wheel population (issue 16 point 6): one wheel of a traffic entry's population,
// e.g. a measured worn profile, with its weight (its share of the entry's passes, relative).
struct PopulationWheel {
  std::string name;                // for messages and the traffic entry's name, not empty
  Profile profile;                 // wheel profile frame
  double rolling_radius_m = 0.46;  // at the profile's z = 0, > 0
  double weight = 1.0;             // relative, > 0 and finite
};

// The entry `entry` drawing its wheel from `wheels`: one traffic entry per wheel, each a copy of
// `entry` with that wheel's profile and rolling radius, named "ENTRY / WHEEL", and share
// entry.share * weight / sum of the weights, so each wheel's load cases carry its share of the
// entry's passes and the entry's total share (and MGT per pass: every wheel has the entry's axle
// load) is unchanged. Throws InputError naming the entry and the wheel for an empty population, a
// weight that is not finite and > 0, an empty profile or name, a non-positive radius, two wheels
// of one name, or a vehicle entry (its wheels are the vehicle's).
std::vector<TrafficCase> ExpandWheelPopulation(const TrafficCase& entry,
                                               const std::vector<PopulationWheel>& wheels);

// Million gross tonnes per axle pass of the mix: sum_c share_c axle_load_t_c / (1e6 sum share)
// over the high rail's entries, or over the low rail's when no entry is on the high rail.
double MgtPerPass(const std::vector<TrafficCase>& traffic);

// The sum of the shares of each rail's entries ([0] high, [1] low): a vehicle entry counts on
// both rails, a collective entry on each rail it has bins on.
std::array<double, 2> RailShareTotals(const std::vector<TrafficCase>& traffic);

// Whether any entry runs on `side` (TrafficCase::RunsOn).
bool HasTrafficOn(const std::vector<TrafficCase>& traffic, RailSide side);

}  // namespace railwear
