#include "wear/wear_simulation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/contact/contact_forces.h"
#include "core/contact/damage.h"
#include "core/contact/rolling_stage.h"
#include "core/geometry/curve_locator.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "core/numerics/parallel.h"
#include "core/profile/builtin_profiles.h"
#include "wear/collective_traffic.h"
#include "wear/spread_step.h"
#include "wear/vehicle_traffic.h"
#include "wear/wheel_wear.h"

namespace railwear {

ContactProblem LoadCaseProblem(const WearStudy& study, const Profile& rail_track,
                               const LoadCase& load_case) {
  // The study's set-up; the wheel from its traffic entry, everything else from the case.
  ContactProblem problem;
  problem.setup() = study.setup();
  problem.wheel_profile = CaseWheelProfile(study.traffic[load_case.traffic_index], load_case);
  problem.rail_profile = rail_track;
  problem.placement = load_case.placement;
  problem.load.vertical_force_N = load_case.vertical_force_N;
  RollingOptions rolling;
  rolling.motion = load_case.motion;
  rolling.friction = load_case.friction;
  problem.rolling = rolling;
  return problem;
}

namespace {

void RequirePositive(const char* key, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("wear: {} = {}: expected a finite number > 0", key, value));
  }
}

// What one load case contributes to a step.
struct CaseOutcome {
  LoadCaseSummary summary;
  std::vector<double> depth_per_pass_m;  // [grid.n]
  std::vector<double> damage_per_pass;   // [grid.n], empty without the damage effect
  // Co-evolution: the depth per pass on the entry's wheel's bins; empty when it does not wear.
  std::vector<double> wheel_depth_per_pass_m;
};

// The hardness the wheel of `traffic` wears with [Pa]: its own, else the study's wheel's.
double WheelHardness(const WearStudy& study, const TrafficCase& traffic) {
  return traffic.wheel_wear->hardness_Pa.value_or(study.wheel_material.hardness_Pa);
}

// The rail a case loads, canted into its track frame, and the bins of its current profile.
struct RailTarget {
  const CurveLocator* locator = nullptr;
  const WearGrid* grid = nullptr;
};

// The friction zones of a solved load case (wear/friction_condition.h). Patches steeper than
// the gauge-face boundary take the entry's gauge-face condition: when its mu differs from the top
// of rail's, the case is solved again at that mu and those patches are replaced by the second
// solution's (matched by the nearest contact point; the contact search does not depend on mu),
// and the result's pressure totals and flange-climb check are made again from the merged
// patches. Returns each patch's wear factor, in result->patches order.
std::vector<double> ApplyFrictionZones(const WearStudy& study, const TrafficCase& traffic,
                                       ContactProblem problem, ContactResult* result) {
  const FrictionConditions& conditions = study.options.conditions;
  const WearLawKind law = study.options.law.kind;
  const double top_factor =
      traffic.condition ? WearFactor(conditions[*traffic.condition], law) : 1.0;
  std::vector<double> factors(result->patches.size(), top_factor);
  if (!traffic.gauge_face_condition) return factors;
  const FrictionConditionParams& gauge = conditions[*traffic.gauge_face_condition];
  std::vector<int> gauge_patches;
  for (size_t i = 0; i < result->patches.size(); ++i) {
    if (result->patches[i].contact_angle_rad > conditions.gauge_face_angle_rad) {
      gauge_patches.push_back(static_cast<int>(i));
      factors[i] = WearFactor(gauge, law);
    }
  }
  if (gauge_patches.empty() || gauge.friction == problem.rolling->friction) return factors;
  problem.rolling->friction = gauge.friction;
  ContactResult at_gauge = SolveContact(problem);
  if (at_gauge.status != SolverStatus::kConverged || at_gauge.patches.empty()) {
    throw std::runtime_error(
        fmt::format("wear: {}: the gauge-face solution at mu {} did not converge: {}", traffic.name,
                    gauge.friction, at_gauge.message));
  }
  for (const int i : gauge_patches) {
    const Eigen::Vector2d& p = result->patches[i].contact_point_yz_m;
    size_t nearest = 0;
    for (size_t j = 1; j < at_gauge.patches.size(); ++j) {
      if ((at_gauge.patches[j].contact_point_yz_m - p).norm() <
          (at_gauge.patches[nearest].contact_point_yz_m - p).norm()) {
        nearest = j;
      }
    }
    result->patches[i] = at_gauge.patches[nearest];
  }
  SumPatchTotals(result);
  result->climb = CheckFlangeClimb(*result, gauge.friction);
  return factors;
}

CaseOutcome SolveLoadCase(const WearStudy& study, const RailTarget& target,
                          const LoadCase& load_case) {
  const CurveLocator& rail = *target.locator;
  const WearGrid& grid = *target.grid;
  const Profile& rail_track = rail.profile();
  const TrafficCase& traffic = study.traffic[load_case.traffic_index];
  const ContactProblem problem = LoadCaseProblem(study, rail_track, load_case);
  ContactResult result = SolveContact(problem);
  // The wear factor of each patch: its zone's friction condition (top of rail, or gauge face
  // when the patch is steeper than the boundary and the entry has a gauge-face condition).
  std::vector<double> factors;
  if (result.status == SolverStatus::kConverged) {
    factors = ApplyFrictionZones(study, traffic, problem, &result);
  }
  CaseOutcome out;
  out.depth_per_pass_m.assign(grid.n, 0.0);
  if (study.damage) out.damage_per_pass.assign(grid.n, 0.0);
  // Co-evolution: the entry's current wheel (the stepped study's wheel_profile) and its bins.
  std::optional<PlacedWheel> wheel;
  WearGrid wheel_grid;
  if (traffic.wears_wheel()) {
    wheel_grid = WearGrid::ForProfile(problem.wheel_profile, study.options.bin_m);
    out.wheel_depth_per_pass_m.assign(wheel_grid.n, 0.0);
  }
  LoadCaseSummary& s = out.summary;
  s.load_case = load_case;
  s.status = result.status;
  s.message = result.message;
  if (result.status == SolverStatus::kNotConverged) {
    throw std::runtime_error(fmt::format(
        "wear: {} on the {} rail at lateral shift {:.3f} mm: the contact solution did not "
        "converge: {}",
        traffic.name, ToString(load_case.rail), load_case.placement.lateral_shift_m * 1e3,
        result.message));
  }
  if (result.status == SolverStatus::kNoContact) return out;
  if (traffic.wears_wheel()) {
    wheel = PlaceWheelProfile(problem.wheel_profile, rail_track, load_case.placement);
  }
  s.patches = static_cast<int>(result.patches.size());
  s.vertical_force_N = result.vertical_force_N;
  s.lateral_force_N = result.lateral_force_N;
  s.forces = TotalForcesOnRail(result);
  s.climb = result.climb;
  s.area_m2 = result.area_m2;
  s.p_max_Pa = result.p_max_Pa;
  s.pressure_limit_Pa = result.pressure_limit_Pa;
  s.plastic_cells = result.plastic_cells;
  s.plastic_area_m2 = result.plastic_area_m2;
  s.plastic_force_N = result.plastic_force_N;
  const double normal_N = TotalNormalForce(result);
  s.plastic_force_share = normal_N > 0.0 ? result.plastic_force_N / normal_N : 0.0;
  double largest = -1.0;
  for (const PatchResult& patch : result.patches) {
    const std::vector<double> depth =
        CalcPatchPassDepth(patch, rail, study.options.law, study.rail_material.hardness_Pa,
                           load_case.motion.speed_m_s, grid);
    const double factor = factors[&patch - result.patches.data()];
    for (int b = 0; b < grid.n; ++b) out.depth_per_pass_m[b] += factor * depth[b];
    if (wheel) {
      // The same patch on the wheel (wear/wheel_wear.h), with the wheel's hardness and the
      // zone's friction-condition factor, which scales the law for both bodies.
      const std::vector<double> on_wheel = CalcPatchWheelPassDepth(
          patch, *wheel, study.options.law, WheelHardness(study, traffic),
          load_case.motion.speed_m_s, traffic.wheel_wear->distance_per_pass_m, wheel_grid);
      for (int b = 0; b < wheel_grid.n; ++b) out.wheel_depth_per_pass_m[b] += factor * on_wheel[b];
    }
    if (patch.rolling) {
      s.creep_force_x_N += patch.rolling->tangential.force_x_N;
      s.creep_force_s_N += patch.rolling->tangential.force_s_N;
      if (patch.rolling->damage) {
        s.t_gamma_N += patch.rolling->damage->t_gamma_N;
        s.spin_work_N += patch.rolling->damage->spin_work_N;
        s.rcf_damage_per_pass = std::max(s.rcf_damage_per_pass, patch.rolling->damage->wlrm_damage);
      }
    }
    if (study.damage) {
      const std::vector<double> damage = CalcPatchDamageSpread(patch, rail, grid);
      for (int b = 0; b < grid.n; ++b) out.damage_per_pass[b] += damage[b];
    }
    if (patch.normal_force_N > largest) {
      largest = patch.normal_force_N;
      s.contact_angle_rad = patch.contact_angle_rad;
      s.contact_y_m = patch.contact_point_yz_m.x();
    }
  }
  for (int b = 0; b < grid.n; ++b) s.worn_area_per_pass_m2 += out.depth_per_pass_m[b] * grid.h_m;
  for (int b = 0; b < wheel_grid.n && wheel; ++b) {
    s.wheel_worn_area_per_pass_m2 += out.wheel_depth_per_pass_m[b] * wheel_grid.h_m;
  }
  return out;
}

// Solves every case on the study's workers, each against its rail (targets[RailSide]), each
// result in its own slot (core/numerics/parallel.h). With `failed` (one flag per case), a case
// whose contact does not converge is flagged there instead of failing the step (the adaptive
// rule's refinement nodes: it leaves such a node out).
std::vector<CaseOutcome> SolveLoadCases(const WearStudy& study, const RailTarget targets[2],
                                        const std::vector<LoadCase>& cases,
                                        std::vector<char>* failed = nullptr) {
  if (failed) failed->assign(cases.size(), 0);
  std::vector<CaseOutcome> outcomes(cases.size());
  const std::function<bool()>& cancel = study.options.cancel;
  std::atomic<bool> cancelled{false};
  ParallelFor(static_cast<int>(cases.size()), study.options.threads, [&](int c) {
    if (cancel && (cancelled || cancel())) {
      cancelled = true;  // the remaining cases are skipped and the step dropped
      return;
    }
    if (!failed) {
      outcomes[c] = SolveLoadCase(study, targets[static_cast<int>(cases[c].rail)], cases[c]);
      return;
    }
    try {
      outcomes[c] = SolveLoadCase(study, targets[static_cast<int>(cases[c].rail)], cases[c]);
    } catch (const std::runtime_error&) {
      (*failed)[c] = 1;
    }
  });
  if (cancelled) throw WearCancelled();
  return outcomes;
}

// The fixed rule's nodes per traffic entry: one per node of a spread (each of a vehicle's
// wheelsets counted; the high rail's case of each node), 0 without spread.
SpreadIntegrationSummary FixedRuleSummary(const WearStudy& study,
                                          const std::vector<LoadCase>& cases) {
  SpreadIntegrationSummary s;
  s.nodes.assign(study.traffic.size(), 0);
  for (const LoadCase& c : cases) {
    const TrafficCase& t = study.traffic[c.traffic_index];
    if (t.is_collective() || !(t.lateral_shift_std_m > 0.0)) continue;
    if (!t.is_vehicle() || c.rail == RailSide::kHigh) ++s.nodes[c.traffic_index];
  }
  return s;
}

// sum_c weight_c * field_c[b] per bin over the cases `take` accepts, adding the terms of each bin
// in increasing order so the sum does not depend on the order of the cases.
template <typename Take>
std::vector<double> WeightedSum(const std::vector<CaseOutcome>& outcomes,
                                const std::vector<LoadCase>& cases, const Take& take, int n,
                                std::vector<double> CaseOutcome::*field) {
  std::vector<double> sum(n, 0.0), terms(outcomes.size());
  for (int b = 0; b < n; ++b) {
    int count = 0;
    for (size_t c = 0; c < outcomes.size(); ++c) {
      if (!take(cases[c])) continue;
      const std::vector<double>& f = outcomes[c].*field;
      if (!f.empty() && f[b] != 0.0) terms[count++] = cases[c].weight * f[b];
    }
    std::sort(terms.begin(), terms.begin() + count);
    double s = 0.0;
    for (int k = 0; k < count; ++k) s += terms[k];
    sum[b] = s;
  }
  return sum;
}

// Value at arc length s of a field given at the bin centres (linear; constant beyond the ends).
double AtArcLength(const WearGrid& grid, const std::vector<double>& field, double s) {
  const double u = s / grid.h_m - 0.5;
  if (u <= 0.0) return field.front();
  const int b = static_cast<int>(u);
  if (b >= grid.n - 1) return field.back();
  const double t = u - b;
  return (1.0 - t) * field[b] + t * field[b + 1];
}

// Every point of `body` (a rail or a wheel, own frame) moved along the body's inward normal by
// depth(s): point i of the result is point i of `body`.
std::vector<Eigen::Vector2d> MoveAlongInwardNormal(const Profile& body, const WearGrid& grid,
                                                   const std::vector<double>& depth_m,
                                                   bool material_toward_plus_z) {
  const CurveLocator locator(body, material_toward_plus_z);
  std::vector<Eigen::Vector2d> points = body.points();
  for (int i = 0; i < body.size(); ++i) {
    const double s = body.KnotS(i);
    const double dz = AtArcLength(grid, depth_m, s);
    if (dz != 0.0) points[i] -= dz * locator.OutwardNormal(s);
  }
  return points;
}

}  // namespace

std::string_view ToString(WearTimeStep v) { return EnumToString(kWearTimeStepNames, v); }

SpreadRule SpreadRuleOf(const WearOptions& o) {
  if (o.integration_tolerance) return SpreadRule::kAdaptive;
  return o.spread_nodes.empty() ? SpreadRule::kGaussHermite : SpreadRule::kPiecewiseLinear;
}

void ValidateWearStudy(const WearStudy& study) {
  const WearOptions& o = study.options;
  ValidateWearLaw(o.law);
  ValidateFrictionConditions(o.conditions);
  ValidateTraffic(study.traffic);
  ValidateCurve(study.curve);
  for (const TrafficCase& c : study.traffic) {
    if (!c.is_vehicle()) continue;
    if (c.vehicle >= static_cast<int>(study.vehicles.size())) {
      throw InputError(fmt::format("{}: vehicle index {}: expected one of the study's {} vehicles",
                                   c.name, c.vehicle, study.vehicles.size()));
    }
    ValidateVehicle(study.vehicles[c.vehicle], c.name);
    if (!study.low_rail_profile) {
      throw InputError(fmt::format(
          "{}: a vehicle runs on both rails: expected a study with a low rail (a scene's [track] "
          "table instead of [rail])",
          c.name));
    }
  }
  if (!study.low_rail_profile) {
    for (const TrafficCase& c : study.traffic) {
      if (c.is_collective()) {
        throw InputError(fmt::format(
            "{}: a load collective places wheelsets on both rails: expected a study with a low "
            "rail (a scene's [track] table instead of [rail])",
            c.name));
      }
      if (c.rail == RailSide::kLow) {
        throw InputError(fmt::format(
            "{}: rail = \"low\": expected a study with a low rail (a scene's [track] table "
            "with high_rail and low_rail instead of [rail])",
            c.name));
      }
    }
  }
  if (study.model.kind == ModelKind::kHertz) {
    throw InputError(
        "wear: model.kind = \"hertz\": expected a grid model (halfspace or conformal):"
        " wear needs the pressure and slip of every cell");
  }
  if (o.law.kind != WearLawKind::kUsfd && !(study.rail_material.hardness_Pa > 0.0)) {
    throw InputError(
        fmt::format("wear: materials.rail.hardness_MPa is missing: expected the rail"
                    " hardness for the {} law",
                    ToString(o.law.kind)));
  }
  if (o.law.kind != WearLawKind::kUsfd) {
    for (const TrafficCase& c : study.traffic) {
      if (c.wears_wheel() && !(c.wheel_wear->hardness_Pa || study.wheel_material.hardness_Pa > 0.0)) {
        throw InputError(fmt::format(
            "{}: wheel_wear: the wheel's hardness is missing: expected materials.wheel."
            "hardness_MPa (or a wheel grade), or the entry's wheel_wear.hardness_MPa, for the {} "
            "law",
            c.name, ToString(o.law.kind)));
      }
    }
  }
  if (study.damage && !(study.rail_material.shear_yield_Pa > 0.0)) {
    throw InputError(fmt::format("wear: materials.rail.shear_yield_MPa is missing: expected {}",
                                 kShearYieldExpected));
  }
  if (o.total_passes.has_value() == o.total_mgt.has_value()) {
    throw InputError("wear: expected exactly one of total_passes and total_MGT");
  }
  if (o.total_passes) RequirePositive("total_passes", *o.total_passes);
  if (o.total_mgt) RequirePositive("total_MGT", *o.total_mgt);
  RequirePositive("max_depth_per_step_mm", o.max_depth_per_step_m * 1e3);
  RequirePositive("bin_mm", o.bin_m * 1e3);
  RequirePositive("profile_spacing_mm", o.profile_spacing_m * 1e3);
  if (o.damage_layer_m) RequirePositive("damage_layer_mm", *o.damage_layer_m * 1e3);
  ValidateQuadraturePoints(o.quadrature_points);
  for (size_t k = 0; k < o.spread_nodes.size(); ++k) {
    if (!std::isfinite(o.spread_nodes[k]) ||
        (k > 0 && !(o.spread_nodes[k] > o.spread_nodes[k - 1]))) {
      throw InputError(
          fmt::format("wear: spread_nodes[{}] = {}: expected finite nodes in strictly "
                      "increasing order",
                      k, o.spread_nodes[k]));
    }
  }
  if (o.integration_tolerance && !o.spread_nodes.empty()) {
    throw InputError(fmt::format(
        "wear: integration_tolerance = {} with {} spread_nodes: expected either the adaptive rule "
        "or the fixed piecewise-linear rule, not both",
        *o.integration_tolerance, o.spread_nodes.size()));
  }
  if (o.integration_tolerance && !(*o.integration_tolerance >= kMinIntegrationTolerance &&
                                   *o.integration_tolerance <= kMaxIntegrationTolerance)) {
    throw InputError(fmt::format("wear: integration_tolerance = {}: expected {} to {}",
                                 *o.integration_tolerance, kMinIntegrationTolerance,
                                 kMaxIntegrationTolerance));
  }
  if (o.threads < 0) {
    throw InputError(fmt::format("wear: threads = {}: expected >= 0 (0: all cores)", o.threads));
  }
  if (o.time_step == WearTimeStep::kHeun) {
    for (const TrafficCase& c : study.traffic) {
      if (c.wears_wheel()) {
        throw InputError(fmt::format(
            "{}: wheel_wear with time_step = \"heun\": expected time_step = \"euler\" for an "
            "entry whose wheels wear (Heun's predictor does not move the wheels yet)",
            c.name));
      }
    }
  }
}

double TotalPasses(const WearStudy& study) {
  if (study.options.total_passes) return *study.options.total_passes;
  return *study.options.total_mgt / MgtPerPass(study.traffic);
}

namespace {

// `profile` at m + 1 points of uniform arc length, both ends included.
Profile ResampleProfileIntervals(const Profile& profile, int m) {
  const double length = profile.Length();
  std::vector<Eigen::Vector2d> points(m + 1);
  for (int k = 0; k <= m; ++k) points[k] = profile.Position(length * k / m);
  return Profile(std::move(points), profile.source());
}

}  // namespace

Profile ResampleProfile(const Profile& profile, double spacing_m) {
  RAILWEAR_CHECK(spacing_m > 0.0);
  return ResampleProfileIntervals(
      profile, std::max(3, static_cast<int>(std::ceil(profile.Length() / spacing_m))));
}

WearMeasures CompareWheelWithUnworn(const Profile& unworn, const Profile& worn) {
  if (worn.points() == unworn.points()) return CompareWheelProfiles(unworn, worn);
  // The reference: the unworn curve at the feet of the worn profile's points (wear moved each
  // point along the normal from its foot). Off the worn band the feet are the points themselves,
  // so the two splines coincide there to rounding; on it the reference samples the unworn curve
  // where the worn one's material came from, with the same spacing. Each foot is searched near
  // its uniform place, within twice the change of length plus 1 mm.
  const int m = worn.size() - 1;
  const double length = unworn.Length();
  const double window = 2.0 * std::abs(worn.Length() - length) + 1e-3;
  const CurveLocator locator(unworn, /*material_toward_plus_z=*/false);
  std::vector<Eigen::Vector2d> feet(m + 1);
  double previous_s = -1.0;
  for (int k = 0; k <= m; ++k) {
    const double guess = length * k / m;
    const CurveLocator::Projection foot =
        locator.Project(worn.points()[k], guess - window, guess + window);
    if (!(foot.s > previous_s + Profile::kDuplicateDistance_m)) {
      // Feet out of order (wear deeper than the curve's radius bunched them): the unworn curve
      // at the worn profile's uniform spacing instead.
      return CompareWheelProfiles(ResampleProfileIntervals(unworn, m), worn);
    }
    previous_s = foot.s;
    feet[k] = foot.point;
  }
  return CompareWheelProfiles(Profile(std::move(feet), unworn.source()), worn);
}

const Profile& StateWheel(const WearState& state, int traffic_index, int wheel) {
  if (wheel == 0) {
    RAILWEAR_CHECK(traffic_index < static_cast<int>(state.wheels.size()));
    return state.wheels[traffic_index];
  }
  RAILWEAR_CHECK(traffic_index < static_cast<int>(state.vehicle_wheels.size()) &&
                 WheelsetOfWheel(wheel) < static_cast<int>(state.vehicle_wheels[traffic_index].size()));
  const WheelsetWheels& pair = state.vehicle_wheels[traffic_index][WheelsetOfWheel(wheel)];
  return RailOfWheel(wheel) == RailSide::kHigh ? pair.high : pair.low;
}

Profile& StateWheelSlot(WearState* state, int traffic_index, int wheel) {
  RAILWEAR_CHECK(traffic_index >= 0 && wheel >= 0);
  if (wheel == 0) {
    if (traffic_index >= static_cast<int>(state->wheels.size())) {
      state->wheels.resize(traffic_index + 1);
    }
    return state->wheels[traffic_index];
  }
  if (traffic_index >= static_cast<int>(state->vehicle_wheels.size())) {
    state->vehicle_wheels.resize(traffic_index + 1);
  }
  std::vector<WheelsetWheels>& pairs = state->vehicle_wheels[traffic_index];
  if (WheelsetOfWheel(wheel) >= static_cast<int>(pairs.size())) {
    pairs.resize(WheelsetOfWheel(wheel) + 1);
  }
  WheelsetWheels& pair = pairs[WheelsetOfWheel(wheel)];
  return RailOfWheel(wheel) == RailSide::kHigh ? pair.high : pair.low;
}

WearState MakeInitialState(const WearStudy& study) {
  ValidateWearStudy(study);
  return internal::InitialState(study);
}

namespace internal {

WearState InitialState(const WearStudy& study) {
  WearState state;
  state.rail = ResampleProfile(study.rail_profile, study.options.profile_spacing_m);
  if (study.low_rail_profile) {
    state.low_rail = ResampleProfile(*study.low_rail_profile, study.options.profile_spacing_m);
  }
  const int n_traffic = static_cast<int>(study.traffic.size());
  for (int t = 0; t < n_traffic; ++t) {
    const TrafficCase& c = study.traffic[t];
    if (!c.wears_wheel()) continue;
    if (c.is_vehicle()) {  // every wheel of every wheelset starts as the vehicle's
      const VehicleSpec& v = study.vehicles[c.vehicle];
      state.vehicle_wheels.resize(n_traffic);
      state.vehicle_wheels[t].assign(v.wheelsets(), {v.wheel_profile, v.wheel_profile});
      continue;
    }
    state.wheels.resize(n_traffic);
    state.wheels[t] = c.wheel_profile;
  }
  return state;
}

std::vector<LoadCase> StepLoadCases(const WearStudy& study, const Profile& high_rail_track,
                                    const std::optional<Profile>& low_rail_track,
                                    const std::vector<CurvingStart>& curving_starts,
                                    std::vector<CurvingStart>* curving_solved) {
  // Prescribed traffic and imported collectives: positions fixed in each rail's unworn track
  // frame, so the current profiles are not needed. Vehicle entries: curving on the current rails.
  std::vector<LoadCase> cases = ExpandValidTraffic(study.traffic, study.options.quadrature_points,
                                                   study.options.spread_nodes);
  const int n_traffic = static_cast<int>(study.traffic.size());
  if (curving_solved) curving_solved->assign(n_traffic, CurvingStart{});
  for (int t = 0; t < n_traffic; ++t) {
    std::vector<LoadCase> more;
    if (study.traffic[t].is_vehicle()) {
      const CurvingStart* start =
          t < static_cast<int>(curving_starts.size()) ? &curving_starts[t] : nullptr;
      more = VehicleLoadCases(study, t, high_rail_track, *low_rail_track, start,
                              curving_solved ? &(*curving_solved)[t] : nullptr);
    } else if (study.traffic[t].is_collective()) {
      more = CollectiveLoadCases(study, t);
    }
    cases.insert(cases.end(), more.begin(), more.end());
  }
  return cases;
}

}  // namespace internal

namespace {

// A body's per-pass depth field summed over its cases, and the field smoothed (scaled to a unit
// maximum: the smoothing is homogeneous in the field). Shared by the rails and the wheels.
struct SmoothedPerPass {
  std::vector<double> depth_per_pass_m;  // the weighted sum over the body's cases
  double deepest = 0.0;                  // max of depth_per_pass_m
  DepthSmoothing smoothed;               // of depth_per_pass_m / deepest
  double peak = 0.0;                     // max of smoothed.depth_m

  void Smooth(double h_m, const DepthSmoothingOptions& options) {
    deepest = *std::max_element(depth_per_pass_m.begin(), depth_per_pass_m.end());
    if (deepest <= 0.0) return;
    std::vector<double> unit(depth_per_pass_m.size());
    for (size_t b = 0; b < unit.size(); ++b) unit[b] = depth_per_pass_m[b] / deepest;
    smoothed = SmoothDepthField(unit, h_m, options);
    peak = *std::max_element(smoothed.depth_m.begin(), smoothed.depth_m.end());
  }
  // The deepest smoothed wear of one pass [m] (0 when nothing wears the body).
  double SmoothedDeepest() const { return deepest > 0.0 ? deepest * peak : 0.0; }
  // The smoothed depth of `passes` passes, per bin [m].
  std::vector<double> StepDepth(double passes) const {
    std::vector<double> step(depth_per_pass_m.size(), 0.0);
    if (deepest <= 0.0) return step;
    for (size_t b = 0; b < step.size(); ++b) step[b] = passes * deepest * smoothed.depth_m[b];
    return step;
  }

  // A field from its summed per-pass depth `raw` and its smoothed per-pass depth
  // `smoothed_m` [m] (not scaled), both per bin, with the smoothing's area error.
  static SmoothedPerPass FromFields(std::vector<double> raw, const std::vector<double>& smoothed_m,
                                    double area_error) {
    SmoothedPerPass m;
    m.depth_per_pass_m = std::move(raw);
    m.deepest = *std::max_element(m.depth_per_pass_m.begin(), m.depth_per_pass_m.end());
    if (m.deepest <= 0.0) return m;
    m.smoothed.depth_m.resize(smoothed_m.size());
    for (size_t b = 0; b < smoothed_m.size(); ++b)
      m.smoothed.depth_m[b] = smoothed_m[b] / m.deepest;
    m.smoothed.area_error = area_error;
    m.peak = *std::max_element(m.smoothed.depth_m.begin(), m.smoothed.depth_m.end());
    return m;
  }

  // Heun's field (WearTimeStep::kHeun): the mean of `a` and `b` (on the same bins) bin by bin,
  // both the summed per-pass depth and the smoothed one; its smoothing area error the larger of
  // theirs.
  static SmoothedPerPass Mean(const SmoothedPerPass& a, const SmoothedPerPass& b) {
    const size_t n = a.depth_per_pass_m.size();
    RAILWEAR_CHECK(b.depth_per_pass_m.size() == n);
    std::vector<double> raw(n);
    for (size_t i = 0; i < n; ++i) raw[i] = 0.5 * (a.depth_per_pass_m[i] + b.depth_per_pass_m[i]);
    const std::vector<double> sa = a.StepDepth(1.0), sb = b.StepDepth(1.0);
    std::vector<double> smoothed_m(n);
    for (size_t i = 0; i < n; ++i) smoothed_m[i] = 0.5 * (sa[i] + sb[i]);
    return FromFields(std::move(raw), smoothed_m,
                      std::abs(a.smoothed.area_error) >= std::abs(b.smoothed.area_error)
                          ? a.smoothed.area_error
                          : b.smoothed.area_error);
  }

  // This field on the bins `from` of the profile a step led to, brought back onto the bins `to`
  // of the profile the step started from: each bin of `to` takes the value (linear between bin
  // centres, AtArcLength) at the arc length its centre's material went to (map.ToNext), for both
  // the summed and the smoothed per-pass depth.
  SmoothedPerPass OnStartBins(const WearGrid& from, const MaterialMap& map,
                              const WearGrid& to) const {
    std::vector<double> raw(to.n, 0.0);
    if (deepest <= 0.0) return FromFields(std::move(raw), {}, 0.0);
    std::vector<double> smoothed_m(to.n);
    for (int b = 0; b < to.n; ++b) {
      const double t = map.ToNext(to.Centre(b));
      raw[b] = AtArcLength(from, depth_per_pass_m, t);
      smoothed_m[b] = deepest * AtArcLength(from, smoothed.depth_m, t);
    }
    return FromFields(std::move(raw), smoothed_m, smoothed.area_error);
  }
};

// One rail through a step: its current profile in the track frame, its bins, and its summed and
// smoothed per-pass depth.
struct RailWork {
  RailSide side = RailSide::kHigh;
  const Profile* current = nullptr;             // own frame
  const Profile* unworn = nullptr;              // own frame
  const std::vector<double>* damage = nullptr;  // accumulated, per bin of `current`
  Profile track;                                // `current` canted into the track frame
  std::optional<CurveLocator> locator;          // on `track`
  WearGrid grid;                                // bins of `current`
  SmoothedPerPass field;                        // summed over the rail's cases, and smoothed

  RailWork(RailSide s, const Profile& now, const Profile& step0, const std::vector<double>& d,
           const WearStudy& study)
      : side(s), current(&now), unworn(&step0), damage(&d) {
    // The track frame is fixed by the unworn rail: the same rigid motion cants every worn profile.
    const CantTransform cant = CalcCantTransform(step0, study.cant_ratio);
    track = now.Transformed(cant.angle_rad, cant.shift_m);
    locator.emplace(track, /*material_toward_plus_z=*/true);
    grid = WearGrid::ForProfile(now, study.options.bin_m);
  }

  bool OnThisRail(const LoadCase& c) const { return c.rail == side; }

  // Sums the cases on this rail and smooths the field.
  void Collect(const std::vector<CaseOutcome>& outcomes, const std::vector<LoadCase>& cases,
               const DepthSmoothingOptions& options) {
    field.depth_per_pass_m =
        WeightedSum(outcomes, cases, [this](const LoadCase& c) { return OnThisRail(c); }, grid.n,
                    &CaseOutcome::depth_per_pass_m);
    field.Smooth(grid.h_m, options);
  }

  // The deepest smoothed wear of one pass [m] (0 when nothing wears this rail).
  double SmoothedDeepest() const { return field.SmoothedDeepest(); }

  // The profile after the smoothed depth `step_depth_m` (per bin): every point moved along the
  // rail's inward normal, then resampled; unchanged when nothing wears the rail. Returns the
  // material map from this profile's arc length to the next one's (damage_transport.h).
  MaterialMap Move(const std::vector<double>& step_depth_m, double profile_spacing_m,
                   Profile* next_profile) const {
    if (!(field.deepest > 0.0)) {
      *next_profile = *current;
      return IdentityMaterialMap(current->Length());
    }
    const std::vector<Eigen::Vector2d> moved_points =
        MoveAlongInwardNormal(*current, grid, step_depth_m, /*material_toward_plus_z=*/true);
    const Profile moved(moved_points, current->source());
    *next_profile = ResampleProfile(moved, profile_spacing_m);
    return MaterialMapOfStep(*current, moved_points, moved, *next_profile);
  }

  // Applies `passes` of wear: the rail's part of the step, its next profile and damage.
  RailStepResult Apply(double passes, const std::vector<CaseOutcome>& outcomes,
                       const std::vector<LoadCase>& cases, const WearStudy& study,
                       Profile* next_profile, std::vector<double>* next_damage) const {
    const WearOptions& o = study.options;
    const int n = grid.n;
    RailStepResult r;
    r.grid = grid;
    r.depth_per_pass_m = field.depth_per_pass_m;
    if (field.deepest > 0.0) r.smoothing_area_error = field.smoothed.area_error;
    r.step_depth_m = field.StepDepth(passes);
    r.material_map = Move(r.step_depth_m, o.profile_spacing_m, next_profile);
    const MaterialMap& map = r.material_map;
    if (study.damage) {
      r.damage_per_pass =
          WeightedSum(outcomes, cases, [this](const LoadCase& c) { return OnThisRail(c); }, n,
                      &CaseOutcome::damage_per_pass);
      const std::vector<double>& damage_per_pass = r.damage_per_pass;
      // The step's damage adds to the accumulated damage on this profile's bins. Wear's removal
      // of cracks is already in the WLRM damage function (its falling branch, 65-175 J/m), so by
      // default nothing more is removed; damage_layer_m (opt-in) is the pre-issue-16 rule.
      std::vector<double> grown(n);
      for (int b = 0; b < n; ++b) {
        const double previous = b < static_cast<int>(damage->size()) ? (*damage)[b] : 0.0;
        const double removed =
            o.damage_layer_m ? std::min(1.0, r.step_depth_m[b] / *o.damage_layer_m) : 0.0;
        grown[b] = (previous + passes * damage_per_pass[b]) * (1.0 - removed);
      }
      // Then it moves with the material onto the next profile's bins.
      *next_damage =
          RemapDamage(grown, grid, current->Length(), WearGrid::ForProfile(*next_profile, o.bin_m),
                      next_profile->Length(), map);
    }
    r.measures = CompareProfiles(*unworn, *next_profile);
    return r;
  }
};

// The wheel of an entry that wears its own (co-evolution) through a step: its current profile,
// its bins, and its per-pass depth summed over the entry's cases (their weights: the wheel's
// depth per axle pass of the mix) and smoothed like a rail's.
struct WheelWork {
  int traffic_index = 0;
  // A vehicle entry's wheel: its wheelset and rail (VehicleWheelIndex); absent: the entry's one.
  std::optional<std::pair<int, RailSide>> vehicle_wheel;
  const Profile* current = nullptr;  // wheel profile frame
  const Profile* unworn = nullptr;   // the entry's wheel_profile (a vehicle's) as given
  WearGrid grid;
  SmoothedPerPass field;

  WheelWork(int t, const Profile& now, const Profile& step0, double bin_m,
            std::optional<std::pair<int, RailSide>> of_vehicle = std::nullopt)
      : traffic_index(t),
        vehicle_wheel(of_vehicle),
        current(&now),
        unworn(&step0),
        grid(WearGrid::ForProfile(now, bin_m)) {}

  // Whether a case runs this wheel: the entry's, and for a vehicle its wheelset on its rail.
  bool Runs(const LoadCase& c) const {
    return c.traffic_index == traffic_index &&
           (!vehicle_wheel || (c.wheelset == vehicle_wheel->first && c.rail == vehicle_wheel->second));
  }
  int WheelIndex() const {
    return vehicle_wheel ? VehicleWheelIndex(vehicle_wheel->first, vehicle_wheel->second) : 0;
  }

  void Collect(const std::vector<CaseOutcome>& outcomes, const std::vector<LoadCase>& cases,
               const DepthSmoothingOptions& options) {
    field.depth_per_pass_m =
        WeightedSum(outcomes, cases, [this](const LoadCase& c) { return Runs(c); }, grid.n,
                    &CaseOutcome::wheel_depth_per_pass_m);
    field.Smooth(grid.h_m, options);
  }

  // The wheel's part of the step and its next profile (moved along its inward normal, then
  // resampled at the study's profile spacing; unchanged when nothing wore it).
  WheelStepResult Apply(double passes, const WearOptions& o, Profile* next_profile) const {
    WheelStepResult r;
    r.traffic_index = traffic_index;
    r.wheel = WheelIndex();
    r.grid = grid;
    r.depth_per_pass_m = field.depth_per_pass_m;
    r.step_depth_m = field.StepDepth(passes);
    if (field.deepest > 0.0) {
      r.smoothing_area_error = field.smoothed.area_error;
      const Profile moved(
          MoveAlongInwardNormal(*current, grid, r.step_depth_m, /*material_toward_plus_z=*/false),
          current->source());
      *next_profile = ResampleProfile(moved, o.profile_spacing_m);
    } else {
      *next_profile = *current;
    }
    r.measures = CompareWheelWithUnworn(*unworn, *next_profile);
    r.flange = MeasureWheelFlange(*next_profile);
    return r;
  }
};

// The load cases of a step on the rails of `high` and `low` (their current profiles), solved:
// the adaptive rule's in rounds, or the fixed rule's at once. Vehicle entries' curving starts
// from `curving_starts` (per traffic entry; WearState::curving).
struct SolvedStepCases {
  std::vector<LoadCase> cases;        // in StepLoadCases order
  std::vector<CaseOutcome> outcomes;  // per case
  SpreadIntegrationSummary integration;
  std::vector<CurvingStart> curving;  // per traffic entry: its curving solution (vehicles)
};

SolvedStepCases SolveStepCases(const WearStudy& study, const RailWork& high,
                               const std::optional<RailWork>& low,
                               const std::vector<CurvingStart>& curving_starts) {
  const WearOptions& o = study.options;
  std::optional<Profile> low_track;
  if (low) low_track = low->track;
  const RailTarget targets[2] = {{&*high.locator, &high.grid},
                                 {low ? &*low->locator : nullptr, low ? &low->grid : nullptr}};
  SolvedStepCases out;
  std::vector<LoadCase>& cases = out.cases;
  std::vector<CaseOutcome>& outcomes = out.outcomes;
  if (o.integration_tolerance) {
    // The adaptive rule: rounds of cases, each solved on the workers; kept in solving order,
    // then put in StepLoadCases order with their final weights.
    std::vector<CaseOutcome> solved;
    SpreadStep spread = IntegrateSpreads(
        study, high.track, low_track, curving_starts, &out.curving, *o.integration_tolerance,
        [&](const std::vector<LoadCase>& batch, bool refinement) {
          for (const LoadCase& c : batch) RAILWEAR_CHECK(targets[static_cast<int>(c.rail)].locator);
          std::vector<char> failed;
          std::vector<CaseOutcome> more =
              SolveLoadCases(study, targets, batch, refinement ? &failed : nullptr);
          std::vector<SolvedCase> integrands;
          for (size_t i = 0; i < more.size(); ++i) {
            if (refinement && failed[i]) {
              integrands.push_back({std::nan(""), {}});
            } else {
              integrands.push_back(
                  {more[i].summary.worn_area_per_pass_m2, more[i].depth_per_pass_m});
            }
            solved.push_back(std::move(more[i]));
          }
          return integrands;
        },
        SpreadRailBins{{high.grid.n, low ? low->grid.n : 0},
                       {high.grid.h_m, low ? low->grid.h_m : 0.0}});
    for (const int i : spread.order) {
      cases.push_back(spread.cases[i]);
      outcomes.push_back(std::move(solved[i]));
      outcomes.back().summary.load_case = spread.cases[i];
    }
    out.integration = std::move(spread.summary);
  } else {
    cases = internal::StepLoadCases(study, high.track, low_track, curving_starts, &out.curving);
    for (const LoadCase& c : cases) RAILWEAR_CHECK(targets[static_cast<int>(c.rail)].locator);
    outcomes = SolveLoadCases(study, targets, cases);
    out.integration = FixedRuleSummary(study, cases);
  }
  return out;
}

// Heun's corrector (WearTimeStep::kHeun) of one rail whose field `rail` holds the step's first
// per-pass depth f0 and fixed the step's `passes`: the predictor profile (the rail moved by
// passes x f0) and its cases' field f1 (from `predicted`, solved on the predictor's rails),
// brought onto the step's bins through the predictor step's material map
// (SmoothedPerPass::OnStartBins); the rail's field becomes (f0 + f1) / 2.
void AverageWithPredictor(const MaterialMap& to_predictor, const SolvedStepCases& predicted,
                          const DepthSmoothingOptions& options, RailWork* predictor,
                          RailWork* rail) {
  predictor->Collect(predicted.outcomes, predicted.cases, options);
  rail->field = SmoothedPerPass::Mean(
      rail->field, predictor->field.OnStartBins(predictor->grid, to_predictor, rail->grid));
}

}  // namespace

StepResult RunWearStep(const WearStudy& given, const UnwornRails& unworn, const WearState& state,
                       double passes_left) {
  const auto start = std::chrono::steady_clock::now();
  // Co-evolution: the step's contacts run the entries' current wheels. `given` keeps the unworn
  // ones (each wheel's measures are taken against them).
  std::optional<WearStudy> stepped;
  std::vector<WheelWork> wheels;
  for (int t = 0; t < static_cast<int>(given.traffic.size()); ++t) {
    if (!given.traffic[t].wears_wheel()) continue;
    if (given.traffic[t].is_vehicle()) {
      // Both wheels of each wheelset, each its own; the curving and the cases run them.
      const VehicleSpec& v = given.vehicles[given.traffic[t].vehicle];
      RAILWEAR_CHECK(t < static_cast<int>(state.vehicle_wheels.size()) &&
                     static_cast<int>(state.vehicle_wheels[t].size()) == v.wheelsets());
      if (!stepped) stepped = given;
      stepped->traffic[t].vehicle_wheels = state.vehicle_wheels[t];
      for (int w = 0; w < v.wheelsets(); ++w) {
        const WheelsetWheels& now = state.vehicle_wheels[t][w];
        wheels.emplace_back(t, now.high, v.wheel_profile, given.options.bin_m,
                            std::make_pair(w, RailSide::kHigh));
        wheels.emplace_back(t, now.low, v.wheel_profile, given.options.bin_m,
                            std::make_pair(w, RailSide::kLow));
      }
      continue;
    }
    RAILWEAR_CHECK(t < static_cast<int>(state.wheels.size()) && state.wheels[t].size() > 0);
    if (!stepped) stepped = given;
    stepped->traffic[t].wheel_profile = state.wheels[t];
    wheels.emplace_back(t, state.wheels[t], given.traffic[t].wheel_profile, given.options.bin_m);
  }
  const WearStudy& study = stepped ? *stepped : given;
  const WearOptions& o = study.options;
  RAILWEAR_CHECK(state.low_rail.has_value() == unworn.low.has_value());
  RailWork high(RailSide::kHigh, state.rail, unworn.high, state.damage, study);
  std::optional<RailWork> low;
  if (state.low_rail)
    low.emplace(RailSide::kLow, *state.low_rail, *unworn.low, state.low_damage, study);

  // The step's own per-pass depth f0: its load cases on the step's rails.
  SolvedStepCases solved = SolveStepCases(study, high, low, state.curving);
  std::vector<LoadCase>& cases = solved.cases;
  std::vector<CaseOutcome>& outcomes = solved.outcomes;
  StepResult step;
  step.integration = std::move(solved.integration);
  std::vector<CurvingStart>& curving = solved.curving;
  for (const CaseOutcome& c : outcomes) {
    step.cases.push_back(c.summary);
    step.cases.back().depth_per_pass_m = c.depth_per_pass_m;
  }
  high.Collect(outcomes, cases, o.smoothing);
  if (low) low->Collect(outcomes, cases, o.smoothing);
  for (WheelWork& w : wheels) w.Collect(outcomes, cases, o.smoothing);

  // Step control: the deepest smoothed wear of either rail and of every wearing wheel in the step
  // equals max_depth_per_step, or the passes left when they are fewer.
  double deepest = std::max(high.SmoothedDeepest(), low ? low->SmoothedDeepest() : 0.0);
  for (const WheelWork& w : wheels) deepest = std::max(deepest, w.field.SmoothedDeepest());
  step.step_passes = deepest > 0.0 ? std::min(passes_left, o.max_depth_per_step_m / deepest)
                                   : passes_left;  // nothing wears: the rest in one step
  if (o.time_step == WearTimeStep::kHeun && deepest > 0.0) {
    // Heun's corrector: the predictor's rails (each moved by the step's passes of f0; no damage,
    // no measures), their cases solved as the step's own (a vehicle's curving started from the
    // step's equilibrium), and each rail's field averaged with the predictor's. The damage and
    // the cases reported are f0's; the next step's curving starts from the predictor's solution
    // (the rails nearest the next step's).
    // Step control on the mean: where the predictor's contact moved onto a band f0 barely wore
    // (a new flange or gauge-corner contact), N (f0 + f1) / 2 can exceed the limit several times
    // over. Such a step is predicted again with the passes at which the mean reaches the limit
    // (up to kHeunRepredictions times), and what is still above it after them is cut to the
    // limit by the passes alone (that last predictor then lies a little beyond the step's end).
    constexpr int kHeunRepredictions = 2;
    constexpr double kHeunAcceptedOvershoot = 1.1;  // the mean's deepest up to 10 % above the limit
    RAILWEAR_CHECK(wheels.empty());  // ValidateWearStudy refuses wheel wear with Heun
    const SmoothedPerPass high_f0 = high.field;
    std::optional<SmoothedPerPass> low_f0;
    if (low) low_f0 = low->field;
    const std::vector<double> no_damage;
    for (int attempt = 0;; ++attempt) {
      high.field = high_f0;
      if (low) low->field = *low_f0;
      Profile high_predicted;
      const MaterialMap high_map =
          high.Move(high.field.StepDepth(step.step_passes), o.profile_spacing_m, &high_predicted);
      RailWork high_predictor(RailSide::kHigh, high_predicted, unworn.high, no_damage, study);
      Profile low_predicted;
      MaterialMap low_map;
      std::optional<RailWork> low_predictor;
      if (low) {
        low_map =
            low->Move(low->field.StepDepth(step.step_passes), o.profile_spacing_m, &low_predicted);
        low_predictor.emplace(RailSide::kLow, low_predicted, *unworn.low, no_damage, study);
      }
      SolvedStepCases predicted = SolveStepCases(study, high_predictor, low_predictor, curving);
      AverageWithPredictor(high_map, predicted, o.smoothing, &high_predictor, &high);
      if (low) AverageWithPredictor(low_map, predicted, o.smoothing, &*low_predictor, &*low);
      step.predictor_load_cases += static_cast<int>(predicted.cases.size());
      const double mean_deepest =
          std::max(high.SmoothedDeepest(), low ? low->SmoothedDeepest() : 0.0);
      const double applied = step.step_passes * mean_deepest;
      if (applied <= kHeunAcceptedOvershoot * o.max_depth_per_step_m ||
          attempt == kHeunRepredictions) {
        if (applied > o.max_depth_per_step_m) {
          step.step_passes = o.max_depth_per_step_m / mean_deepest;
        }
        curving = std::move(predicted.curving);
        break;
      }
      step.step_passes = o.max_depth_per_step_m / mean_deepest;
    }
  }
  WearState& next = step.state;
  next.step = state.step + 1;
  RailStepResult high_step =
      high.Apply(step.step_passes, outcomes, cases, study, &next.rail, &next.damage);
  step.grid = std::move(high_step.grid);
  step.depth_per_pass_m = std::move(high_step.depth_per_pass_m);
  step.step_depth_m = std::move(high_step.step_depth_m);
  step.damage_per_pass = std::move(high_step.damage_per_pass);
  step.material_map = std::move(high_step.material_map);
  step.smoothing_area_error = high_step.smoothing_area_error;
  step.measures = std::move(high_step.measures);
  if (low) {
    next.low_rail.emplace();
    step.low_rail =
        low->Apply(step.step_passes, outcomes, cases, study, &*next.low_rail, &next.low_damage);
  }
  for (const WheelWork& w : wheels) {
    Profile* next_wheel = nullptr;
    if (w.vehicle_wheel) {
      next.vehicle_wheels.resize(study.traffic.size());
      std::vector<WheelsetWheels>& pairs = next.vehicle_wheels[w.traffic_index];
      pairs.resize(state.vehicle_wheels[w.traffic_index].size());
      WheelsetWheels& pair = pairs[w.vehicle_wheel->first];
      next_wheel = w.vehicle_wheel->second == RailSide::kHigh ? &pair.high : &pair.low;
    } else {
      next.wheels.resize(study.traffic.size());
      next_wheel = &next.wheels[w.traffic_index];
    }
    step.wheels.push_back(w.Apply(step.step_passes, o, next_wheel));
  }
  if (std::any_of(curving.begin(), curving.end(),
                  [](const CurvingStart& c) { return c.state.size() > 0; })) {
    next.curving = std::move(curving);
  }
  next.passes = state.passes + step.step_passes;
  next.mgt = state.mgt + step.step_passes * MgtPerPass(study.traffic);
  step.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return step;
}

WearRunSummary RunWear(const WearStudy& study, const UnwornRails& unworn, WearState start,
                       const WearStepCallback& on_step, int max_steps) {
  // Vehicle traffic starts a step's curving from the step before's solution (WearState::curving)
  // and, where the state carries none (step 0, or a run stored without them) or that start fails,
  // from its equilibrium on the unworn rails (VehicleCurvingProblem): solved here whenever the
  // study has a vehicle entry, so a resumed run has the same fallback as an uninterrupted one.
  const bool needs_starts = std::any_of(study.traffic.begin(), study.traffic.end(),
                                        [](const TrafficCase& c) { return c.is_vehicle(); });
  std::optional<WearStudy> prepared;
  WearRunSummary summary;
  if (study.vehicle_starts.empty() && unworn.low && needs_starts) {
    prepared = study;
    try {
      prepared->vehicle_starts = VehicleStarts(study, unworn.high, *unworn.low);
    } catch (const WearCancelled&) {  // before any step: nothing in flight
      summary.state = std::move(start);
      summary.cancelled = true;
      return summary;
    }
  }
  const WearStudy& run = prepared ? *prepared : study;
  const double total = TotalPasses(run);
  summary.state = std::move(start);
  while (true) {
    const double left = total - summary.state.passes;
    if (left <= 1e-12 * total) {
      summary.finished = true;
      break;
    }
    if (max_steps > 0 && summary.steps_done >= max_steps) break;
    StepResult step;
    try {
      if (run.options.cancel && run.options.cancel()) throw WearCancelled();
      step = RunWearStep(run, unworn, summary.state, left);
    } catch (const WearCancelled&) {
      summary.cancelled = true;
      break;
    }
    ++summary.steps_done;
    summary.state = step.state;
    if (on_step && !on_step(step)) break;
  }
  if (total - summary.state.passes <= 1e-12 * total) summary.finished = true;
  return summary;
}

}  // namespace railwear
