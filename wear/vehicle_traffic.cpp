// Vehicle traffic in a wear step (see vehicle_traffic.h).
#include "wear/vehicle_traffic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "core/contact/contact_solver.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "core/numerics/check.h"
#include "core/profile/builtin_profiles.h"
#include "wear/spread_integration.h"

namespace railwear {

namespace {

// The contact angle of a wheel's rigid first contact (its smallest vertical gap) on its rail,
// both in the rail's frame [rad]; 0 without overlap. Geometry only, on a 0.1 mm sampling.
double RigidContactAngle(const Profile& wheel, const Profile& rail, const WheelPose& pose) {
  constexpr double kSampling_m = 1e-4, kThreshold_m = 1e-5;
  const WheelRailGeometry g(wheel, rail, pose, kSampling_m);
  if (!g.has_overlap()) return 0.0;
  const std::vector<ContactCandidate> candidates = g.FindCandidates(kThreshold_m);
  if (candidates.empty()) return 0.0;
  const ContactCandidate& first = *std::min_element(
      candidates.begin(), candidates.end(),
      [](const ContactCandidate& a, const ContactCandidate& b) { return a.gap_m < b.gap_m; });
  return std::atan2(std::abs(first.normal.x()), std::abs(first.normal.y()));
}

// Whether the wheel of `side` of the wheelset at `at_equilibrium` displaced laterally by d [m]
// (toward the high rail for d > 0) has its rigid first contact in flange contact (at least
// kFlangeContactAngle_rad), on the step's rails.
bool Flanging(const WheelsetSpec& at_equilibrium, double d, RailSide side, const CurvingProblem& p,
              int wheelset) {
  // The wheel on that rail: the wheelset's own (worn wheels, CurvingProblem::wheels), else the
  // vehicle's.
  const Profile& wheel =
      p.wheels.empty() ? p.vehicle.wheel_profile
                       : (side == RailSide::kHigh ? p.wheels[wheelset].high : p.wheels[wheelset].low);
  WheelsetSpec ws = at_equilibrium;
  ws.lateral_displacement_m += d;
  const WheelsetPlacement placed = PlaceWheelsetAt(*p.gauge_points, p.track, ws);
  const double angle = side == RailSide::kHigh ? RigidContactAngle(wheel, p.high_rail, placed.right)
                                               : RigidContactAngle(wheel, p.low_rail, placed.left);
  return angle >= kFlangeContactAngle_rad;
}

// The last point below the switch of `test` (false at lo, true at hi) by bisection to
// kFlangeOnsetResolution_m: lo's side of the final bracket; or, as soon as lo reaches
// `enough` (the result cannot lie below it), that lo.
template <typename Test>
double BisectLastBelow(double lo, double hi, const Test& test,
                       double enough = std::numeric_limits<double>::infinity()) {
  while (hi - lo > kFlangeOnsetResolution_m && lo < enough) {
    const double mid = 0.5 * (lo + hi);
    (test(mid) ? hi : lo) = mid;
  }
  return lo;
}

// The wheelset's position at its equilibrium (the nodes' common yaw and roll).
WheelsetSpec EquilibriumWheelset(const VehicleEquilibrium& eq, int wheelset) {
  const CurvedWheelset& w = eq.result.wheelsets[wheelset];
  return eq.problem.vehicle.WheelsetAt(w.lateral_m, w.yaw_rad, w.roll_rad);
}

}  // namespace

double RigidFlangeOnsetOffset(const VehicleEquilibrium& eq, int wheelset, RailSide side,
                              double spread_std_m) {
  RAILWEAR_CHECK(spread_std_m > 0.0);
  const CurvedWheelset& w = eq.result.wheelsets[wheelset];
  const CurvingProblem& p = eq.problem;
  const bool high = side == RailSide::kHigh;
  // In flange contact at the equilibrium already: its flange force is the equilibrium's.
  if ((high ? w.high_climb : w.low_climb).contact_angle_rad > kFlangeContactAngle_rad) return 0.0;
  const WheelsetSpec at_equilibrium = EquilibriumWheelset(eq, wheelset);
  const double sign = high ? 1.0 : -1.0;
  const auto flanging = [&](double d) {
    return Flanging(at_equilibrium, sign * d, side, p, wheelset);
  };
  if (flanging(0.0)) return 0.0;
  // The bracket: the first of kFlangeOnsetScanStd's offsets that is in flange contact.
  double lo = 0.0, hi = -1.0;
  for (const double x : kFlangeOnsetScanStd) {
    if (flanging(x * spread_std_m)) {
      hi = x * spread_std_m;
      break;
    }
    lo = x * spread_std_m;
  }
  if (hi < 0.0) return std::numeric_limits<double>::infinity();
  return BisectLastBelow(lo, hi, flanging);
}

double FlangeOnsetOffset(const WearStudy& study, int traffic_index, const VehicleEquilibrium& eq,
                         int wheelset, RailSide side, double enough_m) {
  const double spread_std_m = study.traffic[traffic_index].lateral_shift_std_m;
  const double rigid = RigidFlangeOnsetOffset(eq, wheelset, side, spread_std_m);
  if (!(rigid > 0.0) || !std::isfinite(rigid)) return rigid;
  const bool high = side == RailSide::kHigh;
  const Profile& rail = high ? eq.problem.high_rail : eq.problem.low_rail;
  // Whether the contact the nodes solve at offset d toward this rail has a flange patch (a
  // contact that does not converge counts as one: the hold stays below what the model cannot
  // solve).
  const auto flanging = [&](double d) {
    const LoadCase c = internal::VehicleCasesAtOffset(study, traffic_index, eq, wheelset,
                                                      high ? d : -d, 0.0, 0, 1.0)[high ? 0 : 1];
    const ContactResult r = SolveContact(LoadCaseProblem(study, rail, c));
    if (r.status == SolverStatus::kNotConverged) return true;
    if (r.status != SolverStatus::kConverged) return false;
    for (const PatchResult& patch : r.patches) {
      if (patch.contact_angle_rad >= kFlangeContactAngle_rad) return true;
    }
    return false;
  };
  // The first of kFlangeOnsetScanStd's offsets below the rigid onset, then the rigid onset itself,
  // that has a flange patch; none: the rigid onset stands.
  // Every offset this returns is at or above the bracket's lo: once lo reaches enough_m, so has
  // the onset, and the scan stops there.
  double lo = 0.0;
  for (const double x : kFlangeOnsetScanStd) {
    if (lo >= enough_m) return lo;
    const double d = std::min(x * spread_std_m, rigid);
    if (flanging(d)) return BisectLastBelow(lo, d, flanging, enough_m);
    if (d == rigid) break;
    lo = d;
  }
  return rigid;
}

std::array<double, 2> OutermostSpreadNodes(const WearOptions& o) {
  std::vector<double> nodes, weights;
  if (SpreadRuleOf(o) == SpreadRule::kAdaptive) {
    nodes.assign(kSpreadInitialNodes.begin(), kSpreadInitialNodes.end());
  } else {
    FixedSpreadRule(o.quadrature_points, o.spread_nodes, &nodes, &weights);
  }
  const auto [lowest, highest] = std::minmax_element(nodes.begin(), nodes.end());
  return {std::max(0.0, *highest), std::max(0.0, -*lowest)};
}

RailGaugePoints UnwornGaugePoints(const WearStudy& study) {
  auto in_track = [&](const Profile& rail) {
    return RailGaugePoint(RailInTrack(study, rail, rail), study.track.gauge_height_m).x();
  };
  const Profile& low = study.low_rail_profile ? *study.low_rail_profile : study.rail_profile;
  return {in_track(study.rail_profile), in_track(low)};
}

CurvingProblem VehicleCurvingProblem(const WearStudy& study, int traffic_index,
                                     const Profile& high_track, const Profile& low_track,
                                     const CurvingStart* start) {
  const TrafficCase& c = study.traffic[traffic_index];
  CurvingProblem p;
  p.contact = study.setup();
  p.high_rail = high_track;
  p.low_rail = low_track;
  p.gauge_points = UnwornGaugePoints(study);
  p.track = study.track;
  p.curve = study.curve;
  p.vehicle = study.vehicles[c.vehicle];
  p.wheels = c.vehicle_wheels;  // its wheelsets' worn wheels when they wear (co-evolution)
  p.speed_m_s = c.speed_m_s;
  p.friction = c.friction;
  p.options.threads = study.options.threads;
  p.options.cold_predictor = study.curving_predictor;
  p.options.warm_contact = study.curving_warm_contact;
  p.options.cancel = study.options.cancel;  // a signal stops the solve, not only the step after it
  // The previous step's solution, then the equilibrium on the unworn rails (SolveCurving skips
  // it when it is the same state: step 1's start), then the centred start.
  std::optional<CurvingStart> unworn;
  if (traffic_index < static_cast<int>(study.vehicle_starts.size()) &&
      study.vehicle_starts[traffic_index].state.size() > 0) {
    unworn = study.vehicle_starts[traffic_index];
    unworn->label = kUnwornEquilibriumStart;
  }
  if (start && start->state.size() > 0) {
    p.options.start = *start;
    p.options.start->label = kPreviousStepStart;
    if (unworn) p.options.fallback_starts.push_back(*unworn);
  } else {
    p.options.start = unworn;
  }
  return p;
}

Profile RailInTrack(const WearStudy& study, const Profile& unworn, const Profile& current) {
  const CantTransform cant = CalcCantTransform(unworn, study.cant_ratio);
  return current.Transformed(cant.angle_rad, cant.shift_m);
}

TrackRails UnwornRailsInTrack(const WearStudy& study) {
  return {RailInTrack(study, study.rail_profile, study.rail_profile),
          RailInTrack(study, *study.low_rail_profile, *study.low_rail_profile)};
}

CurvingStart VehicleStart(const WearStudy& study, int traffic_index, const Profile& unworn_high,
                          const Profile& unworn_low, bool* cancelled) {
  *cancelled = false;
  CurvingProblem p =
      VehicleCurvingProblem(study, traffic_index, RailInTrack(study, unworn_high, unworn_high),
                            RailInTrack(study, unworn_low, unworn_low));
  p.options.start.reset();  // centred (no fallback either)
  p.options.fallback_starts.clear();
  const CurvingResult r = SolveCurving(p);
  *cancelled = r.status == CurvingStatus::kCancelled;
  if (r.status == CurvingStatus::kConverged || r.status == CurvingStatus::kFlangeClimb) {
    return r.Start();
  }
  return {};
}

std::vector<CurvingStart> VehicleStarts(const WearStudy& study, const Profile& unworn_high,
                                        const Profile& unworn_low) {
  std::vector<CurvingStart> starts(study.traffic.size());
  for (int t = 0; t < static_cast<int>(study.traffic.size()); ++t) {
    if (!study.traffic[t].is_vehicle()) continue;
    bool cancelled = false;
    starts[t] = VehicleStart(study, t, unworn_high, unworn_low, &cancelled);
    if (cancelled) throw WearCancelled();
  }
  return starts;
}

VehicleEquilibrium SolveVehicleEquilibrium(const WearStudy& study, int traffic_index,
                                           const Profile& high_track, const Profile& low_track,
                                           const CurvingStart* start) {
  const TrafficCase& c = study.traffic[traffic_index];
  const VehicleSpec& v = study.vehicles[c.vehicle];
  VehicleEquilibrium eq;
  eq.problem = VehicleCurvingProblem(study, traffic_index, high_track, low_track, start);
  eq.result = SolveCurving(eq.problem);
  const CurvingProblem& p = eq.problem;
  const CurvingResult& r = eq.result;
  if (r.status == CurvingStatus::kCancelled) throw WearCancelled();  // the step is dropped
  // An equilibrium stopped just above the tolerance (the contact grid's force noise in flange
  // contact on a worn rail: measured 1.1e-2 Q0 against 3e-3) still gives the wear its loads: it
  // is used, and its cases say so (LoadCase::equilibrium_converged, the step's warning).
  eq.usable = r.status == CurvingStatus::kNotConverged &&
              r.largest_scaled_residual <= p.options.usable_multiple * p.options.tolerance;
  if (r.status != CurvingStatus::kConverged && r.status != CurvingStatus::kFlangeClimb &&
      !eq.usable) {
    throw std::runtime_error(fmt::format(
        "wear: {}: steady-state curving of vehicle \"{}\" at {} m/s on the current rails: {}: {}",
        c.name, v.name, c.speed_m_s, ToString(r.status), r.message));
  }
  if (c.lateral_shift_std_m > 0.0) {
    // The rule's outermost nodes bound the search: an onset beyond them holds no node.
    const std::array<double, 2> outermost = OutermostSpreadNodes(study.options);
    const double std_m = c.lateral_shift_std_m;
    for (int w = 0; w < static_cast<int>(r.wheelsets.size()); ++w) {
      eq.flange_onset_m.push_back(
          {FlangeOnsetOffset(study, traffic_index, eq, w, RailSide::kHigh, outermost[0] * std_m),
           FlangeOnsetOffset(study, traffic_index, eq, w, RailSide::kLow, outermost[1] * std_m)});
    }
  }
  return eq;
}

std::vector<LoadCase> internal::VehicleCasesAtOffset(const WearStudy& study, int traffic_index,
                                                     const VehicleEquilibrium& eq, int wheelset,
                                                     double offset_m, double x, int node,
                                                     double node_weight) {
  const TrafficCase& c = study.traffic[traffic_index];
  const VehicleSpec& v = study.vehicles[c.vehicle];
  const CurvingProblem& p = eq.problem;
  const CurvingResult& r = eq.result;
  const CurvedWheelset& w = r.wheelsets[wheelset];
  const std::array<double, 2> totals = RailShareTotals(study.traffic);
  const double kappa = study.curve.curvature_per_m();
  const int n_ws = static_cast<int>(r.wheelsets.size());
  WheelsetSpec ws = EquilibriumWheelset(eq, wheelset);
  ws.lateral_displacement_m = w.lateral_m + offset_m;
  const WheelsetPlacement placed = PlaceWheelsetAt(*p.gauge_points, p.track, ws);
  WheelMotion axle;
  axle.speed_m_s = c.speed_m_s;
  axle.pitch_velocity_rad_s = w.pitch_velocity_rad_s;
  const WheelMotions motions = CurveWheelMotions(axle, placed, kappa, v.rolling_radius_m);
  std::vector<LoadCase> cases;
  for (const RailSide side : {RailSide::kHigh, RailSide::kLow}) {
    const bool high = side == RailSide::kHigh;
    const WheelPose& pose = high ? placed.right : placed.left;
    LoadCase lc;
    lc.traffic_index = traffic_index;
    lc.node = node;
    lc.wheelset = wheelset;
    lc.spread_x = x;
    lc.rail = side;
    lc.placement = {pose.lateral_shift_m, pose.roll_rad, pose.rolling_radius_m, pose.yaw_rad};
    lc.vertical_force_N = high ? w.high_load_N : w.low_load_N;
    lc.motion = high ? motions.right : motions.left;
    lc.friction = c.friction;
    lc.weight = c.share / totals[static_cast<int>(side)] * node_weight / n_ws;
    lc.equilibrium_residual = r.largest_scaled_residual;
    lc.equilibrium_converged = !eq.usable;
    cases.push_back(lc);
  }
  return cases;
}

std::vector<LoadCase> VehicleNodeCases(const WearStudy& study, int traffic_index,
                                       const VehicleEquilibrium& eq, int wheelset, double x,
                                       int node, double node_weight) {
  double offset = study.traffic[traffic_index].lateral_shift_std_m * x;
  // A node pushing a wheel toward its rail's flange stops at the wheelset's one onset of flange
  // contact on that side (at the equilibrium when that wheel is in flange contact already), so
  // every node beyond it is the same position, bit for bit.
  if (offset > 0.0) offset = std::min(offset, eq.flange_onset_m[wheelset][0]);
  if (offset < 0.0) offset = std::max(offset, -eq.flange_onset_m[wheelset][1]);
  return internal::VehicleCasesAtOffset(study, traffic_index, eq, wheelset, offset, x, node,
                                        node_weight);
}

std::vector<LoadCase> VehicleLoadCases(const WearStudy& study, int traffic_index,
                                       const Profile& high_track, const Profile& low_track,
                                       const CurvingStart* start, CurvingStart* solved) {
  const TrafficCase& c = study.traffic[traffic_index];
  const VehicleEquilibrium eq =
      SolveVehicleEquilibrium(study, traffic_index, high_track, low_track, start);
  if (solved) *solved = eq.result.Start();
  std::vector<double> nodes = {0.0}, weights = {1.0};
  if (c.lateral_shift_std_m > 0.0) {
    FixedSpreadRule(study.options.quadrature_points, study.options.spread_nodes, &nodes, &weights);
  }
  std::vector<LoadCase> cases;
  for (int w = 0; w < static_cast<int>(eq.result.wheelsets.size()); ++w) {
    for (int k = 0; k < static_cast<int>(nodes.size()); ++k) {
      const std::vector<LoadCase> more =
          VehicleNodeCases(study, traffic_index, eq, w, nodes[k], k, weights[k]);
      cases.insert(cases.end(), more.begin(), more.end());
    }
  }
  return cases;
}

}  // namespace railwear
