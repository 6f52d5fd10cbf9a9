// `railwear wear`: scene -> wear study -> steps stored in the profile history database.
#include "app/cli_checks.h"
#include "app/wear_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/contact_output.h"
#include "app/gnuplot.h"
#include "app/history_plot.h"
#include "app/interrupt_signals.h"
#include "app/number_format.h"
#include "app/scene.h"
#include "app/stored_study.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"
#include "wear/vehicle_traffic.h"
#include "wear/wear_simulation.h"

namespace railwear::app {
namespace {

using nlohmann::json;

json WearLawJson(const WearStudy& study) {
  const WearLaw& law = study.options.law;
  json j;
  j["law"] = std::string(ToString(law.kind));
  switch (law.kind) {
    case WearLawKind::kArchard:
      j["k"] = law.archard_k;
      break;
    case WearLawKind::kKth:
    case WearLawKind::kKthContinuous:
      j["kth_k_seizure"] = law.kth_k_seizure;
      j["kth_k_mild_low"] = law.kth_k_mild_low;
      j["kth_k_severe"] = law.kth_k_severe;
      j["kth_k_mild_high"] = law.kth_k_mild_high;
      j["kth_v1_m_s"] = law.kth_v1_m_s;
      j["kth_v2_m_s"] = law.kth_v2_m_s;
      j["kth_pressure_ratio"] = law.kth_pressure_ratio;
      if (law.kind == WearLawKind::kKthContinuous) {
        j["kth_velocity_band"] = law.kth_velocity_band;
        j["kth_pressure_band"] = law.kth_pressure_band;
      }
      break;
    case WearLawKind::kUsfd:
      j["density_kg_m3"] = law.density_kg_m3;
      break;
  }
  j["hardness_MPa"] = study.rail_material.hardness_Pa * 1e-6;
  j["model"] = ModelJson(study.model);  // kernel and the named constants set (issue 17)
  j["max_depth_per_step_mm"] = study.options.max_depth_per_step_m * 1e3;
  j["smoothing_mm"] = study.options.smoothing.smoothing_length_m * 1e3;
  // The time step, only when it is not the default (older runs' JSON unchanged).
  if (study.options.time_step != WearTimeStep::kEuler) {
    j["time_step"] = ToString(study.options.time_step);
  }
  // Co-evolution (issue 16): the wearing wheels, only when there are (older runs' JSON unchanged).
  json wheels = json::array();
  for (size_t t = 0; t < study.traffic.size(); ++t) {
    const TrafficCase& c = study.traffic[t];
    if (!c.wears_wheel()) continue;
    wheels.push_back({{"traffic_index", t},
                      {"traffic", c.name},
                      {"distance_per_pass_m", c.wheel_wear->distance_per_pass_m},
                      {"hardness_MPa",
                       c.wheel_wear->hardness_Pa.value_or(study.wheel_material.hardness_Pa) *
                           1e-6}});
  }
  if (!wheels.empty()) j["wheel_wear"] = wheels;
  // The spread rule (issue 16): "quadrature_points" stays for the fixed rule's readers.
  if (study.options.integration_tolerance) {
    j["integration"] = {{"rule", "adaptive"},
                        {"tolerance", *study.options.integration_tolerance},
                        {"first_nodes", kSpreadInitialNodes},
                        {"max_nodes", kMaxSpreadNodes}};
  } else if (!study.options.spread_nodes.empty()) {
    // The piecewise-linear rule: its scene key's m when the nodes are LinearSpreadNodes(m).
    const std::vector<double>& x = study.options.spread_nodes;
    json rule = {{"rule", "piecewise-linear"},
                 {"nodes", x.size()},
                 {"first_node", x.front()},
                 {"last_node", x.back()}};
    const int m = static_cast<int>(x.size()) * 4 / 5;
    if (m % 8 == 0 && m >= kMinLinearSpreadNodes && m <= kMaxLinearSpreadNodes &&
        LinearSpreadNodes(m) == x) {
      rule["spread_nodes"] = m;
    }
    j["integration"] = rule;
  } else {
    j["quadrature_points"] = study.options.quadrature_points;
    j["integration"] = {{"rule", "gauss-hermite"},
                        {"quadrature_points", study.options.quadrature_points}};
  }
  return j;
}

// The fixed spread rule's name in the integration lines: " (fixed Gauss-Hermite)" or
// " (fixed piecewise-linear)".
std::string FixedRuleName(const WearStudy& study) {
  return study.options.spread_nodes.empty() ? " (fixed Gauss-Hermite)"
                                            : " (fixed piecewise-linear)";
}

// A step's spread integration, one line: each spread entry's nodes (summed over a vehicle's
// wheelsets) and, for the adaptive rule, the estimated error per rail.
std::string IntegrationLine(const StepResult& step, const WearStudy& study) {
  const SpreadIntegrationSummary& g = step.integration;
  std::vector<std::string> entries;
  for (size_t t = 0; t < g.nodes.size(); ++t) {
    if (g.nodes[t] > 0) entries.push_back(fmt::format("{} {}", study.traffic[t].name, g.nodes[t]));
  }
  if (entries.empty()) return {};
  std::string line = fmt::format("spread nodes: {}", fmt::join(entries, ", "));
  if (!g.adaptive) return line + FixedRuleName(study);
  line += fmt::format(" (adaptive, {} rounds, last change of the worn area {:.2g} %", g.rounds,
                      100.0 * g.last_change[0]);
  if (study.low_rail_profile) line += fmt::format(" high, {:.2g} % low", 100.0 * g.last_change[1]);
  return line + fmt::format(" against {:.2g} %{})", 100.0 * g.tolerance,
                            g.converged ? "" : ", NOT converged: no interval left to bisect");
}

json LoadCaseJson(const LoadCaseSummary& c, const WearStudy& study,
                  const SpreadIntegrationSummary& integration) {
  json j;
  const int t = c.load_case.traffic_index;
  j["traffic"] = study.traffic[t].name;
  j["rail"] = std::string(ToString(c.load_case.rail));
  j["node"] = c.load_case.node;
  if (study.traffic[t].lateral_shift_std_m > 0.0 && !study.traffic[t].is_collective()) {
    // The spread node (standard-normal units) and the nodes its entry used in this step.
    j["spread_x"] = c.load_case.spread_x;
    if (t < static_cast<int>(integration.nodes.size())) j["entry_nodes"] = integration.nodes[t];
  }
  if (study.traffic[t].is_vehicle()) j["wheelset"] = c.load_case.wheelset;
  j["lateral_shift_mm"] = c.load_case.placement.lateral_shift_m * 1e3;
  j["weight"] = c.load_case.weight;
  if (study.traffic[c.load_case.traffic_index].is_vehicle()) {
    j["equilibrium"] = {{"converged", c.load_case.equilibrium_converged},
                        {"largest_scaled_residual", c.load_case.equilibrium_residual}};
  }
  j["status"] = std::string(ToString(c.status));
  j["patches"] = c.patches;
  j["vertical_force_N"] = c.vertical_force_N;
  j["lateral_force_N"] = c.lateral_force_N;
  j["area_mm2"] = c.area_m2 * 1e6;
  j["p_max_MPa"] = c.p_max_Pa * 1e-6;
  if (c.pressure_limit_Pa) {  // only with [model] pressure_limit: older runs' JSON unchanged
    j["plastic"] = {{"pressure_limit_MPa", *c.pressure_limit_Pa * 1e-6},
                    {"cells", c.plastic_cells},
                    {"area_mm2", c.plastic_area_m2 * 1e6},
                    {"normal_force_N", c.plastic_force_N},
                    {"force_share", c.plastic_force_share}};
  }
  j["creep_force_N"] = {{"x", c.creep_force_x_N}, {"s", c.creep_force_s_N}};  // on the wheel
  // The labelled forces (issue 14): on the rail, rail frame, pressure / creep / net parts.
  auto xyz = [](const Eigen::Vector3d& f) {
    return json{{"x", f.x()}, {"y", f.y()}, {"z", f.z()}};
  };
  j["forces"] = {{"on", "rail"},
                 {"frame", "rail"},
                 {"normal", xyz(c.forces.normal_N)},
                 {"creep", xyz(c.forces.creep_N)},
                 {"net", xyz(c.forces.Net())}};
  j["l_over_v"] = c.climb.l_over_v;
  j["nadal_limit"] = c.climb.nadal_limit ? json(*c.climb.nadal_limit) : json(nullptr);
  j["flange_climb"] = c.climb.exceeded;
  j["t_gamma_N"] = c.t_gamma_N;
  j["spin_work_N"] = c.spin_work_N;  // spin's frictional work beside T-gamma [J/m]
  const double work = c.t_gamma_N + c.spin_work_N;
  j["spin_share"] = work > 0.0 ? c.spin_work_N / work : 0.0;
  j["rcf_damage_per_pass"] = c.rcf_damage_per_pass;
  j["worn_area_per_pass_mm2"] = c.worn_area_per_pass_m2 * 1e6;
  if (study.traffic[t].wears_wheel()) {  // co-evolution only: older runs' JSON unchanged
    j["wheel_worn_area_per_pass_mm2"] = c.wheel_worn_area_per_pass_m2 * 1e6;
  }
  j["contact_angle_deg"] = c.contact_angle_rad * 180.0 / M_PI;
  j["contact_y_mm"] = c.contact_y_m * 1e3;
  return j;
}

// A quantity on the bins of `profile` (arc length), with the lateral position of each bin.
Distribution BinDistribution(const std::string& kind, const Profile& profile, const WearGrid& grid,
                             const std::vector<double>& value) {
  Distribution d;
  d.kind = kind;
  d.value = value;
  for (int b = 0; b < grid.n; ++b) {
    const double s = std::min(grid.Centre(b), profile.Length());
    d.s_m.push_back(s);
    d.y_m.push_back(profile.Position(s).x());
  }
  return d;
}

// No NaN or infinity reaches the database: a measure that cannot be taken is a failure.
void RequireFinite(const WearMeasures& m, const StepResult& step, const char* rail) {
  for (const double v :
       {m.worn_area_m2, m.max_depth_m, m.max_depth_y_m, m.vertical_wear_m, m.side_wear_m,
        m.wear_45_m, step.state.passes, step.state.mgt, step.smoothing_area_error}) {
    if (!std::isfinite(v)) {
      throw std::runtime_error(fmt::format(
          "wear step {}: a wear measure of the {} is not finite (a measuring line missed the "
          "worn profile, or the profile degenerated); the run stops before storing it",
          step.state.step, rail));
    }
  }
}

// One rail's part of a step as stored: measures, profile after the step and its distributions
// (`unworn` the rail's step 0, `previous` its profile before the step).
struct RailRecordParts {
  WearMeasures measures;
  std::vector<Distribution> distributions;
};

RailRecordParts MakeRailParts(const WearMeasures& m, const WearGrid& grid,
                              const std::vector<double>& step_depth_m,
                              const std::vector<double>& depth_per_pass_m, const Profile& after,
                              const std::vector<double>& damage, const WearStudy& study,
                              const Profile& unworn, const Profile& previous) {
  RailRecordParts r;
  r.measures = m;
  Distribution depth;
  depth.kind = "wear_depth_mm";
  for (size_t k = 0; k < m.s_m.size(); ++k) {
    // A sample whose normal misses the worn profile has no depth (NaN): left out, never stored.
    if (!std::isfinite(m.depth_m[k])) continue;
    depth.s_m.push_back(m.s_m[k]);
    depth.y_m.push_back(unworn.Position(m.s_m[k]).x());
    depth.value.push_back(m.depth_m[k] * 1e3);
  }
  r.distributions.push_back(std::move(depth));
  std::vector<double> step_mm(step_depth_m), per_pass_nm(depth_per_pass_m);
  for (double& v : step_mm) v *= 1e3;
  for (double& v : per_pass_nm) v *= 1e9;
  r.distributions.push_back(BinDistribution("step_depth_mm", previous, grid, step_mm));
  r.distributions.push_back(BinDistribution("depth_per_pass_nm", previous, grid, per_pass_nm));
  if (study.damage) {
    // Stored as computed (no unit change): --resume reads it back bit for bit.
    const WearGrid after_grid = WearGrid::ForProfile(after, study.options.bin_m);
    r.distributions.push_back(BinDistribution("rcf_damage", after, after_grid, damage));
  }
  return r;
}

// The profiles before a step (to place its bins): the high rail's and the low rail's.
struct PreviousProfiles {
  Profile high;
  std::optional<Profile> low;
};

// A flange measure [m] as stored [mm]: absent where the profile has none (NaN).
std::optional<double> FlangeMm(double metres) {
  return std::isfinite(metres) ? std::optional<double>(metres * 1e3) : std::nullopt;
}

void SetFlange(const WheelFlangeMeasures& f, WheelStepRecord* w) {
  w->flange_height_mm = FlangeMm(f.flange_height_m);
  w->flange_thickness_mm = FlangeMm(f.flange_thickness_m);
  w->flange_slope_mm = FlangeMm(f.flange_slope_m);
}

// The step's warnings (issue 17), stored with it (schema 8) and printed: one per kind, how many
// load cases and the worst. flange_climb: L/V beyond Nadal's limit; hardness: p_max beyond the
// hardness of the softer body (HardnessWarning, as `railwear contact` warns).
std::vector<StepWarningRecord> StepWarnings(const StepResult& step, const WearStudy& study) {
  int climbs = 0, overloads = 0;
  const LoadCaseSummary *worst_climb = nullptr, *worst_p = nullptr;
  for (const LoadCaseSummary& c : step.cases) {
    if (c.climb.exceeded) {
      ++climbs;
      const double margin = c.climb.l_over_v - *c.climb.nadal_limit;
      if (!worst_climb || margin > worst_climb->climb.l_over_v - *worst_climb->climb.nadal_limit)
        worst_climb = &c;
    }
    if (HardnessWarning(study.wheel_material, study.rail_material, c.p_max_Pa, "")) {
      ++overloads;
      if (!worst_p || c.p_max_Pa > worst_p->p_max_Pa) worst_p = &c;
    }
  }
  // "WHAT in K of N load cases (worst: ENTRY[ on the R rail] at lateral shift Y mm: DETAIL)"
  auto line = [&](const char* what, int count, const LoadCaseSummary& worst,
                  const std::string& detail) {
    return fmt::format("{} in {} of {} load cases (worst: {}{} at lateral shift {:.2f} mm: {})",
                       what, count, step.cases.size(),
                       study.traffic[worst.load_case.traffic_index].name,
                       study.low_rail_profile
                           ? fmt::format(" on the {} rail", ToString(worst.load_case.rail))
                           : std::string(),
                       worst.load_case.placement.lateral_shift_m * 1e3, detail);
  };
  std::vector<StepWarningRecord> out;
  if (worst_climb) {
    out.push_back({"flange_climb", line("flange climb possible", climbs, *worst_climb,
                                        FlangeClimbWarning(worst_climb->climb, ""))});
  }
  if (worst_p) {
    out.push_back({"hardness", line("p_max beyond the hardness", overloads, *worst_p,
                                    *HardnessWarning(study.wheel_material, study.rail_material,
                                                     worst_p->p_max_Pa, ""))});
  }
  return out;
}

StepRecord MakeStepRecord(const StepResult& step, const WearStudy& study, const UnwornRails& unworn,
                          const PreviousProfiles& previous) {
  RequireFinite(step.measures, step, step.low_rail ? "high rail" : "rail");
  if (step.low_rail) RequireFinite(step.low_rail->measures, step, "low rail");
  StepRecord r;
  r.step = step.state.step;
  r.passes = step.state.passes;
  r.mgt = step.state.mgt;
  const WearMeasures& m = step.measures;
  r.worn_area_mm2 = m.worn_area_m2 * 1e6;
  r.max_depth_mm = m.max_depth_m * 1e3;
  r.max_depth_y_mm = m.max_depth_y_m * 1e3;
  r.w1_mm = m.vertical_wear_m * 1e3;
  r.w2_mm = m.side_wear_m * 1e3;
  r.w3_mm = m.wear_45_m * 1e3;
  r.smoothing_area_error = step.smoothing_area_error;
  r.profile = step.state.rail;
  r.warnings = StepWarnings(step, study);
  for (const LoadCaseSummary& c : step.cases) {
    const nlohmann::json j = LoadCaseJson(c, study, step.integration);
    RequireFiniteJson(j, fmt::format("wear step {} load case", step.state.step));
    r.load_cases_json.push_back(j.dump());
  }
  r.distributions =
      MakeRailParts(m, step.grid, step.step_depth_m, step.depth_per_pass_m, step.state.rail,
                    step.state.damage, study, unworn.high, previous.high)
          .distributions;
  if (step.low_rail) {
    const RailStepResult& low = *step.low_rail;
    RailStepRecord l;
    l.worn_area_mm2 = low.measures.worn_area_m2 * 1e6;
    l.max_depth_mm = low.measures.max_depth_m * 1e3;
    l.max_depth_y_mm = low.measures.max_depth_y_m * 1e3;
    l.w1_mm = low.measures.vertical_wear_m * 1e3;
    l.w2_mm = low.measures.side_wear_m * 1e3;
    l.w3_mm = low.measures.wear_45_m * 1e3;
    l.smoothing_area_error = low.smoothing_area_error;
    l.profile = *step.state.low_rail;
    l.distributions = MakeRailParts(low.measures, low.grid, low.step_depth_m, low.depth_per_pass_m,
                                    *step.state.low_rail, step.state.low_damage, study, *unworn.low,
                                    *previous.low)
                          .distributions;
    r.low_rail = std::move(l);
  }
  for (const WheelStepResult& w : step.wheels) {
    const WearMeasures& wm = w.measures;
    const std::string name = WheelName(study.traffic[w.traffic_index], w.wheel);
    for (const double v : {wm.worn_area_m2, wm.max_depth_m, wm.max_depth_y_m, w.smoothing_area_error}) {
      if (!std::isfinite(v)) {
        throw std::runtime_error(fmt::format(
            "wear step {}: a wear measure of the wheel of '{}' is not finite (the worn wheel "
            "profile degenerated); the run stops before storing it",
            step.state.step, name));
      }
    }
    WheelStepRecord rec;
    rec.traffic_index = w.traffic_index;
    rec.wheel = w.wheel;
    rec.name = name;
    rec.worn_area_mm2 = wm.worn_area_m2 * 1e6;
    rec.max_depth_mm = wm.max_depth_m * 1e3;
    rec.max_depth_y_mm = wm.max_depth_y_m * 1e3;
    rec.smoothing_area_error = w.smoothing_area_error;
    rec.profile = StateWheel(step.state, w.traffic_index, w.wheel);
    SetFlange(w.flange, &rec);
    r.wheels.push_back(std::move(rec));
  }
  for (size_t t = 0; t < step.state.curving.size(); ++t) {
    const CurvingStart& c = step.state.curving[t];
    if (c.state.size() == 0) continue;
    r.curving_starts.push_back(
        {static_cast<int>(t), std::vector<double>(c.state.data(), c.state.data() + c.state.size()),
         std::vector<double>(c.jacobian.data(), c.jacobian.data() + c.jacobian.size())});
  }
  return r;
}

StepRecord MakeInitialRecord(const WearState& state, const WearStudy& study) {
  StepRecord r;
  r.step = 0;
  r.profile = state.rail;
  if (state.low_rail) {
    r.low_rail.emplace();
    r.low_rail->profile = *state.low_rail;
  }
  for (size_t t = 0; t < state.wheels.size(); ++t) {
    if (state.wheels[t].size() == 0) continue;
    WheelStepRecord w;
    w.traffic_index = static_cast<int>(t);
    w.name = study.traffic[t].name;
    w.profile = state.wheels[t];
    SetFlange(MeasureWheelFlange(w.profile), &w);
    r.wheels.push_back(std::move(w));
  }
  // A vehicle entry's wheels (each wheelset's high and low wheel), in the steps' order.
  for (size_t t = 0; t < state.vehicle_wheels.size(); ++t) {
    for (size_t ws = 0; ws < state.vehicle_wheels[t].size(); ++ws) {
      for (const RailSide side : {RailSide::kHigh, RailSide::kLow}) {
        WheelStepRecord w;
        w.traffic_index = static_cast<int>(t);
        w.wheel = VehicleWheelIndex(static_cast<int>(ws), side);
        w.name = WheelName(study.traffic[t], w.wheel);
        w.profile = StateWheel(state, w.traffic_index, w.wheel);
        SetFlange(MeasureWheelFlange(w.profile), &w);
        r.wheels.push_back(std::move(w));
      }
    }
  }
  // Stored by entry, then wheel (the steps' order puts prescribed wheels first).
  std::stable_sort(r.wheels.begin(), r.wheels.end(),
                   [](const WheelStepRecord& a, const WheelStepRecord& b) {
                     return a.traffic_index < b.traffic_index;
                   });
  return r;
}

std::string Duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long s = std::lround(seconds);
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02}", s / 60, s % 60);
}

// Progress on stderr: a bar redrawn in place on a terminal, one line per step otherwise.
class Progress {
 public:
  Progress(double total_passes, double start_passes)
      : total_(total_passes),
        start_passes_(start_passes),
        tty_(isatty(fileno(stderr)) != 0),
        start_(std::chrono::steady_clock::now()) {}

  void Step(const StepResult& step, const WearStudy& study) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double done = step.state.passes - start_passes_;
    const double rate = elapsed > 0 ? done / elapsed : 0.0;
    const double eta = rate > 0 ? (total_ - step.state.passes) / rate : -1.0;
    const double fraction = std::min(1.0, step.state.passes / total_);
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = static_cast<int>(fraction * kWidth);
      std::cerr << fmt::format("\r[{}{}] {:5.1f}%  step {}  {:.3g} MGT  {:.3g} passes/s  ETA {}  ",
                               std::string(filled, '#'), std::string(kWidth - filled, '.'),
                               100.0 * fraction, step.state.step, step.state.mgt, rate,
                               Duration(eta))
                << std::flush;
    } else {
      std::cerr << fmt::format(
          "railwear: step {}: {:.4g} passes ({:.3g} MGT, {:.1f} %), max depth {:.3f} mm at y = "
          "{:.2f} mm{}, {:.2f} s\n",
          step.state.step, step.state.passes, step.state.mgt, 100.0 * fraction,
          step.measures.max_depth_m * 1e3, step.measures.max_depth_y_m * 1e3,
          step.low_rail ? fmt::format(" (high rail), {:.3f} mm at y = {:.2f} mm (low rail)",
                                      step.low_rail->measures.max_depth_m * 1e3,
                                      step.low_rail->measures.max_depth_y_m * 1e3)
                        : std::string(),
          step.seconds);
      const std::string nodes = IntegrationLine(step, study);
      if (!nodes.empty())
        std::cerr << fmt::format("railwear: step {}: {}\n", step.state.step, nodes);
      if (step.predictor_load_cases > 0) {  // time_step = "heun": the predictor's cases too
        std::cerr << fmt::format(
            "railwear: step {}: heun: {} load cases, {} more in the predictor\n", step.state.step,
            step.cases.size(), step.predictor_load_cases);
      }
      for (const WheelStepResult& w : step.wheels) {
        std::cerr << fmt::format("railwear: step {}: wheel of '{}': max depth {:.3f} mm at y = {:.2f} mm\n",
                                 step.state.step, WheelName(study.traffic[w.traffic_index], w.wheel),
                                 w.measures.max_depth_m * 1e3, w.measures.max_depth_y_m * 1e3);
      }
    }
  }
  void Finish() {
    if (tty_) std::cerr << "\n";
  }

  // One line per step whose adaptive spread rule stopped at the node limit above its tolerance.
  void WarnOfIntegration(const StepResult& step) {
    const SpreadIntegrationSummary& g = step.integration;
    if (!g.adaptive || g.converged) return;
    std::cerr << fmt::format(
        "{}warning: step {}: the spread integration ran out of intervals to bisect (at most {} "
        "nodes per spread, none narrower than {:.3g} std) before its tolerance of {:.2g} %: last "
        "change of the worn area {:.2g} % (high rail), {:.2g} % (low rail)\n",
        tty_ ? "\n" : "", step.state.step, kMaxSpreadNodes, kMinSpreadInterval, 100.0 * g.tolerance,
        100.0 * g.last_change[0], 100.0 * g.last_change[1]);
  }

  // One line per step whose vehicle equilibria stopped above their tolerance (but within
  // CurvingOptions::usable_multiple of it): which entries, and the largest residual.
  void WarnOfEquilibria(const StepResult& step, const WearStudy& study) {
    std::vector<std::string> names;
    double largest = 0.0;
    for (const LoadCaseSummary& c : step.cases) {
      if (c.load_case.equilibrium_converged) continue;
      const std::string& name = study.traffic[c.load_case.traffic_index].name;
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      largest = std::max(largest, c.load_case.equilibrium_residual);
    }
    if (names.empty()) return;
    std::cerr << fmt::format(
        "{}warning: step {}: the curving of {} stopped above its tolerance (largest scaled "
        "residual {:.1e}, at most {} x the tolerance accepted): its loads are used\n",
        tty_ ? "\n" : "", step.state.step, fmt::join(names, ", "), largest,
        CurvingOptions().usable_multiple);
  }

  // One line per warning of the step (StepWarnings: flange climb, p_max beyond the hardness).
  void WarnOf(const StepRecord& record) {
    for (const StepWarningRecord& w : record.warnings) {
      std::cerr << fmt::format("{}warning: step {}: {}\n", tty_ ? "\n" : "", record.step,
                               w.message);
    }
  }

 private:
  double total_, start_passes_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

// The spread nodes of the steps of this call: per traffic entry the fewest and most, and the
// largest last change of the worn area (adaptive rule), for the summary.
class IntegrationTally {
 public:
  void Add(const SpreadIntegrationSummary& g) {
    if (steps_ == 0) {
      first_ = g;
      fewest_ = most_ = g.nodes;
    }
    for (size_t t = 0; t < g.nodes.size() && t < fewest_.size(); ++t) {
      fewest_[t] = std::min(fewest_[t], g.nodes[t]);
      most_[t] = std::max(most_[t], g.nodes[t]);
    }
    for (int r = 0; r < 2; ++r) largest_change_[r] = std::max(largest_change_[r], g.last_change[r]);
    all_converged_ = all_converged_ && g.converged;
    ++steps_;
  }

  // "spread integration ..." line, empty without steps or spreads.
  std::string Line(const WearStudy& study) const {
    std::vector<std::string> entries;
    for (size_t t = 0; t < most_.size(); ++t) {
      if (most_[t] == 0) continue;
      entries.push_back(fewest_[t] == most_[t]
                            ? fmt::format("{} {}", study.traffic[t].name, most_[t])
                            : fmt::format("{} {}-{}", study.traffic[t].name, fewest_[t], most_[t]));
    }
    if (steps_ == 0 || entries.empty()) return {};
    if (!first_.adaptive) {
      return fmt::format("spread integration: fixed {} rule, nodes per step: {}\n",
                         study.options.spread_nodes.empty() ? "Gauss-Hermite" : "piecewise-linear",
                         fmt::join(entries, ", "));
    }
    return fmt::format(
        "spread integration: adaptive to {:.2g} % of the step's worn area and {:.2g} % of its "
        "depth field, nodes per step: {}; largest last change {:.2g} % (high rail){}{}\n",
        100.0 * first_.tolerance, 100.0 * kSpreadFieldChangeFactor * first_.tolerance,
        fmt::join(entries, ", "), 100.0 * largest_change_[0],
        study.low_rail_profile ? fmt::format(", {:.2g} % (low rail)", 100.0 * largest_change_[1])
                               : std::string(),
        all_converged_ ? "" : "; NOT converged in every step (see the warnings)");
  }

 private:
  int steps_ = 0;
  SpreadIntegrationSummary first_;
  std::vector<int> fewest_, most_;
  std::array<double, 2> largest_change_ = {0.0, 0.0};
  bool all_converged_ = true;
};

// One rail's step table: the first, every k-th and the last step, at most about 25 lines.
void PrintStepTable(const std::vector<StepRecord>& steps) {
  std::cout << fmt::format("{:>5} {:>12} {:>9} {:>12} {:>10} {:>9} {:>7} {:>7} {:>7}\n", "step",
                           "passes", "MGT", "area_mm2", "depth_mm", "at_y_mm", "W1_mm", "W2_mm",
                           "W3_mm");
  const int n = static_cast<int>(steps.size());
  const int every = std::max(1, n / 24);
  for (int i = 0; i < n; ++i) {
    if (i % every != 0 && i != n - 1) continue;
    const StepRecord& s = steps[i];
    std::cout << fmt::format(
        "{:>5} {:>12.5g} {:>9.4g} {:>12} {:>10} {:>9} {:>7} {:>7} {:>7}\n", s.step, s.passes, s.mgt,
        FixedNoNegativeZero(s.worn_area_mm2, 4), FixedNoNegativeZero(s.max_depth_mm, 4),
        FixedNoNegativeZero(s.max_depth_y_mm, 2), FixedNoNegativeZero(s.w1_mm, 3),
        FixedNoNegativeZero(s.w2_mm, 3), FixedNoNegativeZero(s.w3_mm, 3));
  }
}

std::string Rate(double mm_per_mgt) {
  return std::isfinite(mm_per_mgt) ? FixedNoNegativeZero(mm_per_mgt, 4) : std::string("n/a");
}

// Each rail's W2 and W3 rate over the run and over its last half (by MGT).
void PrintRates(const std::vector<StepRecord>& high, const std::vector<StepRecord>& low) {
  if (high.size() < 2) return;
  std::cout << fmt::format(
      "wear rates [mm/MGT], over the run (MGT {:.4g} to {:.4g}) and its last half (MGT {:.4g} "
      "to {:.4g}):\n",
      high.front().mgt, high.back().mgt, 0.5 * high.back().mgt, high.back().mgt);
  const auto line = [&](const char* rail, const std::vector<StepRecord>& steps) {
    const WearRates run = RatesBetween(steps.front(), steps.back());
    const WearRates last = LastHalfRates(steps);
    std::cout << fmt::format("  {:<10} W2 {:>8} (last half {:>8})   W3 {:>8} (last half {:>8})\n",
                             rail, Rate(run.w2_mm_per_mgt), Rate(last.w2_mm_per_mgt),
                             Rate(run.w3_mm_per_mgt), Rate(last.w3_mm_per_mgt));
  };
  line(low.empty() ? "rail" : "high rail", high);
  if (!low.empty()) line("low rail", low);
}

std::string FlangeText(const std::optional<double>& mm) {
  return mm ? FixedNoNegativeZero(*mm, 2) : std::string("n/a");
}

// Each wearing wheel's last stored step (co-evolution): worn area, max depth, Sh, Sd, qR.
void PrintWheels(const ProfileStore& store, int64_t run) {
  const std::vector<WheelStepRecord> wheels = store.WheelSteps(run);
  for (size_t i = 0; i < wheels.size(); ++i) {
    if (i + 1 < wheels.size() && wheels[i + 1].traffic_index == wheels[i].traffic_index &&
        wheels[i + 1].wheel == wheels[i].wheel) {
      continue;
    }
    const WheelStepRecord& w = wheels[i];
    std::cout << fmt::format(
        "wheel of '{}' (traffic entry {}) at step {}: worn area {} mm2, max depth {} mm at y = {} "
        "mm, Sh {} Sd {} qR {} mm (history steps/profile/diff --wheel {})\n",
        w.name, w.traffic_index, w.step, FixedNoNegativeZero(w.worn_area_mm2, 4),
        FixedNoNegativeZero(w.max_depth_mm, 4), FixedNoNegativeZero(w.max_depth_y_mm, 2),
        FlangeText(w.flange_height_mm), FlangeText(w.flange_thickness_mm),
        FlangeText(w.flange_slope_mm),
        w.wheel == 0 ? std::to_string(w.traffic_index) : fmt::format("'{}'", w.name));
  }
}

void PrintSummary(const ProfileStore& store, int64_t run, const std::string& name, bool finished,
                  double seconds, int new_steps) {
  const std::vector<StepRecord> steps = store.Steps(run);
  const std::vector<StepRecord> low = LowRailSteps(steps);
  std::cout << fmt::format("run '{}' in {}: {} steps{}, {} new in {:.1f} s\n", name, store.path(),
                           steps.size() - 1, finished ? " (complete)" : " (not complete: --resume)",
                           new_steps, seconds);
  if (!low.empty()) std::cout << "high rail:\n";
  PrintStepTable(steps);
  if (!low.empty()) {
    std::cout << "low rail:\n";
    PrintStepTable(low);
  }
  PrintRates(steps, low);
  PrintWheels(store, run);
}

}  // namespace

void SetupWear(CLI::App& app) {
  auto options = std::make_shared<WearCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "wear",
      "Worn-profile evolution: wear the rail by the scene's traffic mix, step by step, "
      "storing every step in the profile history database");
  cmd->add_option("scene", options->scene_path,
                  "Scene file (TOML) with effect \"wear\", [wear] "
                  "and [[traffic]]")
      ->required();
  cmd->add_option(
      "--db", options->db,
      fmt::format("Database file (default: the scene's [wear] db, else {})", kDefaultDatabase));
  cmd->add_option("--run", options->run, "Run name (default: the scene's name)");
  cmd->add_flag("--resume", options->resume, "Continue the named run from its last complete step");
  cmd->add_option("--steps", options->steps, "Stop after N new steps (continue with --resume)")
      ->check(IntegerIn(1, 1000000000));
  cmd->add_option("--threads", options->threads, "Worker threads (0: all cores)")
      ->check(IntegerIn(0, 256));  // as [wear] threads
  cmd->add_option("--plot", options->plot,
                  "Write the history plots of the run to PREFIX_*.png when it ends");
  cmd->callback([options]() { RunWearCommand(*options); });
}

void RunWearCommand(const WearCommandOptions& options) {
  RunWearScene(LoadScene(options.scene_path), options);
}

void RunWearScene(const Scene& scene, const WearCommandOptions& options) {
  if (!scene.wear) {
    throw InputError(fmt::format(
        "{}: scene.effects has no \"wear\": expected a wear scene with [wear] and [[traffic]] "
        "(use `railwear contact` for a single contact)",
        options.scene_path));
  }
  // Before the run, so nobody waits for nothing.
  if (options.plot) RequireGnuplotFor("wear --plot", "leave out --plot");
  WearStudy study = *scene.wear;
  if (options.threads) study.options.threads = *options.threads;
  const std::string db = options.db               ? *options.db
                         : !scene.wear_db.empty() ? scene.wear_db
                                                  : std::string(kDefaultDatabase);
  const std::string name = options.run.value_or(scene.name);

  // From here on SIGINT and SIGTERM only set a flag: the wear loop stops between load cases
  // (dropping the step in flight) or after a step's commit, and the run is marked interrupted.
  const InterruptSignals signals;
  study.options.cancel = [] { return InterruptSignals::Received() != 0; };
  ProfileStore store = ProfileStore::Open(db);
  int64_t run_id = 0;
  WearState state;
  UnwornRails unworn{Profile()};
  const std::optional<RunInfo> existing = store.FindRun(name);
  if (options.resume) {
    if (!existing) {
      throw InputError(
          fmt::format("{}: no run '{}' to resume: expected one of the runs listed "
                      "by `railwear history --db {} runs`",
                      db, name, db));
    }
    if (existing->scene_text != scene.text) {
      throw InputError(fmt::format(
          "{}: run '{}' was started from a different scene than {}: expected the same scene "
          "text to resume (start a new run with --run NAME)",
          db, name, options.scene_path));
    }
    run_id = existing->id;
    std::optional<int> last = store.LastStep(run_id);
    if (!last) {
      // A run whose creation and step 0 were two commits (railwear before issue 17), killed
      // between them. Step 0 is the scene's unworn rails, and the scene text is the stored one.
      store.AppendStep(run_id, MakeInitialRecord(internal::InitialState(study), study));
      last = 0;
      std::cerr << fmt::format(
          "railwear: run '{}' had no stored step (its start was interrupted): stored its step 0 "
          "from the scene\n",
          name);
    }
    unworn = UnwornRails::Of(StateFromStore(store, run_id, 0));
    state = StateFromStore(store, run_id, *last);
    if (state.low_rail.has_value() != study.low_rail_profile.has_value() ||
        unworn.low.has_value() != study.low_rail_profile.has_value()) {
      throw InputError(fmt::format(
          "{}: run '{}' stored {} but the scene has {}: expected the same rails to resume", db,
          name, state.low_rail ? "two rails" : "one rail",
          study.low_rail_profile ? "two ([track])" : "one ([rail])"));
    }
    for (size_t t = 0; t < study.traffic.size(); ++t) {
      const TrafficCase& c = study.traffic[t];
      const bool stored =
          c.is_vehicle()
              ? t < state.vehicle_wheels.size() &&
                    static_cast<int>(state.vehicle_wheels[t].size()) ==
                        study.vehicles[c.vehicle].wheelsets() &&
                    std::all_of(state.vehicle_wheels[t].begin(), state.vehicle_wheels[t].end(),
                                [](const WheelsetWheels& w) {
                                  return w.high.size() > 0 && w.low.size() > 0;
                                })
              : t < state.wheels.size() && state.wheels[t].size() > 0;
      if (c.wears_wheel() && !stored) {
        throw InputError(fmt::format(
            "{}: run '{}' step {} stored no wheel of traffic entry '{}', whose wheel wears in the "
            "scene: expected the run's wheels to resume (start a new run with --run NAME)",
            db, name, state.step, study.traffic[t].name));
      }
    }
    std::cerr << fmt::format(
        "railwear: resuming run '{}' from step {} ({:.4g} passes; it was {})\n", name, state.step,
        state.passes, ToString(existing->state));
    store.SetRunState(run_id, RunState::kRunning);
  } else {
    if (existing) {
      throw InputError(fmt::format(
          "{}: run '{}' exists already: expected a new run name (--run NAME), or --resume to "
          "continue it",
          db, name));
    }
    state = internal::InitialState(study);  // the scene reader validated the study
    unworn = UnwornRails::Of(state);
    RunInfo info;
    info.name = name;
    info.program_version = RAILWEAR_VERSION;
    info.scene_text = scene.text;
    info.wear_law_json = WearLawJson(study).dump();
    // One transaction: a kill at any moment leaves either no run or a run with its step 0.
    run_id = store.CreateRun(info, MakeInitialRecord(state, study));
  }

  const double total = TotalPasses(study);
  Progress progress(total, state.passes);
  const auto start = std::chrono::steady_clock::now();
  PreviousProfiles previous{state.rail, state.low_rail};
  WearRunSummary summary;
  IntegrationTally integration;
  try {
    summary = railwear::RunWear(
        study, unworn, state,
        [&](const StepResult& step) {
          const StepRecord record = MakeStepRecord(step, study, unworn, previous);
          store.AppendStep(run_id, record);
          previous = {step.state.rail, step.state.low_rail};
          progress.Step(step, study);
          progress.WarnOfIntegration(step);
          integration.Add(step.integration);
          progress.WarnOf(record);
          progress.WarnOfEquilibria(step, study);
          return true;
        },
        options.steps);
  } catch (const std::exception& failure) {
    progress.Finish();
    try {
      // The run is aborted and says why (issue 19: a sweep names its failed runs).
      store.SetRunFailed(run_id, failure.what());
    } catch (const std::exception&) {
      // The failure itself says more (e.g. the database file was deleted under the run).
    }
    throw;
  } catch (...) {
    progress.Finish();
    try {
      store.SetRunState(run_id, RunState::kAborted);
    } catch (const std::exception&) {
    }
    throw;
  }
  progress.Finish();
  if (const int signal = InterruptSignals::Received()) {
    store.SetRunState(run_id, summary.finished ? RunState::kComplete : RunState::kInterrupted);
    throw Interrupted(
        signal,
        summary.finished
            ? fmt::format("{}: run '{}' in {} is complete ({} steps); nothing to resume",
                          SignalName(signal), name, db, summary.state.step)
            : fmt::format(
                  "{}: run '{}' in {} interrupted after step {} ({:.4g} passes; the step in "
                  "flight, if any, was not stored); continue it with `{}`",
                  SignalName(signal), name, db, summary.state.step, summary.state.passes,
                  options.resume_command.empty()
                      ? fmt::format("railwear wear {} --db {} --run '{}' --resume",
                                    options.scene_path, db, name)
                      : options.resume_command));
  }
  store.SetRunState(run_id, summary.finished ? RunState::kComplete : RunState::kRunning);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << fmt::format("model {}\n", ModelLine(study.model));
  PrintSummary(store, run_id, name, summary.finished, seconds, summary.steps_done);
  std::cout << integration.Line(study);
  if (options.plot) {
    std::vector<StepRecord> steps;
    for (const StepRecord& s : store.Steps(run_id)) steps.push_back(store.LoadStep(run_id, s.step));
    for (const std::string& png : PlotHistory(name, steps, *options.plot)) {
      std::cout << "wrote " << png << "\n";
    }
  }
}

}  // namespace railwear::app
