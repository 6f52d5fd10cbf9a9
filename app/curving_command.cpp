// `railwear curving`: steady-state curving of a scene's vehicle traffic (see curving_command.h).
#include "app/curving_command.h"

#include <iostream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/interrupt_signals.h"
#include "app/scene.h"
#include "app/stored_study.h"
#include "app/toml_fields.h"
#include "core/contact/contact_forces.h"
#include "core/numerics/enum_names.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "core/profile/builtin_profiles.h"
#include "wear/vehicle_traffic.h"

namespace railwear::app {
namespace {

std::string NadalText(const FlangeClimbCheck& c) {
  return c.nadal_limit ? fmt::format("{:5.2f}", *c.nadal_limit) : std::string("    -");
}

void Print(const TrafficCase& c, const CurvingProblem& p, const CurvingResult& r) {
  std::cout << fmt::format(
      "{}: vehicle \"{}\" at {:.1f} m/s on R {} m, cant {:.0f} mm: cant deficiency {:.0f} mm "
      "(a_u {:.3f} m/s^2)\n",
      c.name, p.vehicle.name, p.speed_m_s,
      p.curve.radius_m > 0 ? fmt::format("{:.0f}", p.curve.radius_m) : std::string("inf"),
      p.curve.cant_m * kToMm, r.cant_deficiency_m * kToMm, r.unbalanced_acceleration_m_s2);
  std::cout << "  ws      x_m    y_mm  yaw_mrad  Q_high_kN  Q_low_kN  Y_high_kN  angle_deg  "
               "L/V_high  Nadal\n";
  for (size_t i = 0; i < r.wheelsets.size(); ++i) {
    const CurvedWheelset& w = r.wheelsets[i];
    std::cout << fmt::format(
        "  {:2d} {:8.2f} {:7.2f} {:9.2f} {:10.1f} {:9.1f} {:10.1f} {:10.1f} "
        "{:9.2f}  {}\n",
        i, w.x_m, w.lateral_m * kToMm, w.yaw_rad * 1e3, w.high_load_N * 1e-3, w.low_load_N * 1e-3,
        w.high_lateral_N * 1e-3, w.high_climb.contact_angle_rad * 180.0 / M_PI,
        w.high_climb.l_over_v, NadalText(w.high_climb));
  }
  if (r.attempts.size() > 1) {  // a start failed: each start's solves
    std::string starts;
    for (const CurvingAttempt& a : r.attempts) {
      starts += fmt::format("{}{}: {} solves{}", starts.empty() ? "" : "; ", a.start,
                            a.contact_solves, a.converged ? ", converged" : "");
    }
    std::cout << "  starts: " << starts << "\n";
  }
  std::cout << fmt::format(
      "  status {}{}; residuals: lateral {:.1f} N, yaw {:.1f} N m, longitudinal {:.1f} N; "
      "{} + {} iterations, {} wheelset contact solves, {:.1f} s{}\n",
      ToString(r.status), r.message.empty() ? "" : " (" + r.message + ")", r.lateral_residual_N,
      r.yaw_residual_Nm, r.longitudinal_residual_N, r.predictor_iterations, r.full_iterations,
      r.contact_solves, r.time_s,
      p.options.ColdPredictorFor(p.contact.model) == CurvingPredictor::kTable
          ? fmt::format("; table predictor {} ({} evaluations, built in {:.2f} s)",
                        ToString(r.table_predictor), r.table_evaluations, r.table_build_s)
          : std::string());
}

nlohmann::json Json(const TrafficCase& c, const CurvingProblem& p, const CurvingResult& r) {
  nlohmann::json j = {{"traffic", c.name},
                      {"vehicle", p.vehicle.name},
                      {"speed_m_s", p.speed_m_s},
                      {"radius_m", p.curve.radius_m},
                      {"cant_mm", p.curve.cant_m * kToMm},
                      {"cant_deficiency_mm", r.cant_deficiency_m * kToMm},
                      {"status", ToString(r.status)},
                      {"message", r.message},
                      {"residuals",
                       {{"lateral_N", r.lateral_residual_N},
                        {"yaw_Nm", r.yaw_residual_Nm},
                        {"longitudinal_N", r.longitudinal_residual_N}}},
                      {"largest_scaled_residual", r.largest_scaled_residual},
                      {"contact_solves", r.contact_solves},
                      {"predictor", ToString(p.options.ColdPredictorFor(p.contact.model))},
                      {"table_predictor", ToString(r.table_predictor)},
                      {"time_s", r.time_s}};
  j["starts"] = nlohmann::json::array();
  for (const CurvingAttempt& a : r.attempts) {
    j["starts"].push_back({{"start", a.start},
                           {"contact_solves", a.contact_solves},
                           {"converged", a.converged},
                           {"largest_scaled_residual", a.largest_scaled_residual},
                           {"message", a.message}});
  }
  for (const CurvedWheelset& w : r.wheelsets) {
    j["wheelsets"].push_back(
        {{"x_m", w.x_m},
         {"y_mm", w.lateral_m * kToMm},
         {"yaw_mrad", w.yaw_rad * 1e3},
         {"roll_mrad", w.roll_rad * 1e3},
         {"pitch_velocity_rad_s", w.pitch_velocity_rad_s},
         {"Q_high_N", w.high_load_N},
         {"Q_low_N", w.low_load_N},
         {"Y_high_N", w.high_lateral_N},
         {"force_on_wheelset_N", {w.force_N.x(), w.force_N.y(), w.force_N.z()}},
         {"yaw_moment_Nm", w.yaw_moment_Nm},
         {"high_l_over_v", w.high_climb.l_over_v},
         {"high_contact_angle_deg", w.high_climb.contact_angle_rad * 180 / M_PI},
         {"high_nadal_limit", w.high_climb.nadal_limit ? nlohmann::json(*w.high_climb.nadal_limit)
                                                       : nlohmann::json(nullptr)}});
  }
  return j;
}

// A stored wear step's rails in the track frame, and its state (each entry's curving solution),
// and the run's step 0 (its unworn rails, own frames).
struct StoredRails {
  TrackRails rails;
  WearState state;
  WearState unworn;
  std::string where;  // "run 'NAME' step N (M MGT) in FILE"
};

StoredRails StoredStepRails(const CurvingOptions& o, const Scene& scene) {
  const WearStudy& study = *scene.wear;
  if (o.step && *o.step < 0) {
    throw InputError(fmt::format("--step {}: expected a stored step number (0 or more)", *o.step));
  }
  const ProfileStore db = OpenExistingStudy(*o.db);
  const RunInfo run = FindRunOrThrow(db, o.run.value_or(scene.name));
  if (run.scene_text != scene.text) {
    throw InputError(fmt::format(
        "database '{}': run '{}' was stored from a different scene than {}: expected the run's "
        "own scene (its rails' places and vehicles come from it)",
        db.path(), run.name, o.scene));
  }
  const std::optional<int> last = db.LastStep(run.id);
  if (!last) {
    throw InputError(fmt::format("database '{}': run '{}' has no steps yet", db.path(), run.name));
  }
  const int step = o.step.value_or(*last);
  if (step > *last) {
    throw InputError(fmt::format("--step {}: run '{}' in '{}' has steps 0 to {}", step, run.name,
                                 db.path(), *last));
  }
  StoredRails out;
  out.unworn = StateFromStore(db, run.id, 0);
  out.state = StateFromStore(db, run.id, step);
  out.rails.high = RailInTrack(study, out.unworn.rail, out.state.rail);
  out.rails.low = RailInTrack(study, *out.unworn.low_rail, *out.state.low_rail);
  out.where =
      fmt::format("run '{}' step {} ({:.4g} MGT) in {}", run.name, step, out.state.mgt, db.path());
  return out;
}

}  // namespace

void SetupCurving(CLI::App& app) {
  auto o = std::make_shared<CurvingOptions>();
  CLI::App* cmd = app.add_subcommand(
      "curving",
      "Steady-state curving of a wear scene's vehicle traffic on its unworn rails, or with --db "
      "on a stored wear step's worn rails (docs/curving.md)");
  cmd->add_option("scene", o->scene, "Wear scene with [track], [[vehicle]] and vehicle traffic")
      ->required();
  cmd->add_option("--json", o->json, "Write the equilibria as JSON to FILE ('-': stdout)");
  CLI::Option* db = cmd->add_option("--db", o->db,
                                    "A wear run's database: solve on a stored step's worn rails, "
                                    "from its stored curving (read only)");
  cmd->add_option("--run", o->run, "With --db: the run (default: the scene's name)")->needs(db);
  cmd->add_option("--step", o->step, "With --db: the step (default: the run's last)")->needs(db);
  cmd->add_option("--predictor", o->predictor,
                  "A cold solve's predictor: model (the draft grid) or table (tabulated rigid "
                  "contact geometry with Hertz and Kalker; docs/curving.md \"The table "
                  "predictor\"); default: the scene's [curving] predictor, else table at standard "
                  "and finer, model at draft")
      ->check(CLI::IsMember(EnumChoiceStrings(kCurvingPredictorNames)));
  cmd->add_option("--start", o->start,
                  "With --db: the first start, 'stored' (the step's stored solution, then the "
                  "vehicle's equilibrium on the run's unworn rails, then centred: the run's next "
                  "step), 'unworn' (from the unworn rails' equilibrium) or 'centred' (a cold "
                  "solve)")
      ->check(CLI::IsMember({"stored", "unworn", "centred"}))
      ->needs(db);
  cmd->callback([o]() { RunCurving(*o); });
}

void RunCurving(const CurvingOptions& o) {
  // SIGINT / SIGTERM stop the solve in flight (CurvingOptions::cancel, asked before every Newton
  // iteration and contact evaluation) and end the command with 130 / 143 (issue 17), as `wear`
  // does (app/interrupt_signals.h). Installed first, so a signal at any moment is handled.
  const InterruptSignals signals;
  const Scene scene = LoadScene(o.scene);
  if (!scene.wear || scene.wear->vehicles.empty()) {
    throw InputError(fmt::format(
        "{}: expected a wear scene with [track], [[vehicle]] tables and [[traffic]] entries "
        "naming a vehicle",
        o.scene));
  }
  WearStudy study = *scene.wear;
  nlohmann::json all = nlohmann::json::array();
  std::string failures;
  const StoredRails stored = o.db ? StoredStepRails(o, scene) : StoredRails{};
  study.options.cancel = [] { return InterruptSignals::Received() != 0; };
  // On a stored step, a vehicle's equilibrium on the run's unworn rails, as RunWear solves it:
  // the start of an entry without a stored solution (or with --start unworn), solved first, and
  // the fallback of a stored solution, solved only when that fails (CurvingStart::lazy).
  const bool unworn_starts = o.db && o.start != "centred";
  study.vehicle_starts.assign(study.traffic.size(), CurvingStart{});
  auto unworn_start = [&study, &stored, &o](int t) {
    std::cerr << fmt::format(
        "railwear: curving: solving traffic entry '{}' on the run's unworn rails (its {} start)\n",
        study.traffic[t].name,
        o.start == "stored" && t < static_cast<int>(stored.state.curving.size()) &&
                stored.state.curving[t].state.size() > 0
            ? "fallback"
            : "first");
    bool cancelled = false;
    CurvingStart s =
        VehicleStart(study, t, stored.unworn.rail, *stored.unworn.low_rail, &cancelled);
    s.label = kUnwornEquilibriumStart;
    return s;  // cancelled: empty (the entry's solve then stops on the same signal)
  };
  const TrackRails rails = o.db ? stored.rails : UnwornRailsInTrack(study);
  if (o.db && (!o.json || *o.json != "-")) {
    std::cout << "on the worn rails of " << stored.where << ", from its stored curving\n";
  }
  for (int t = 0; t < static_cast<int>(study.traffic.size()); ++t) {
    const TrafficCase& c = study.traffic[t];
    if (!c.is_vehicle()) continue;
    // An entry without a stored solution (state empty) starts from the unworn rails'
    // equilibrium when there is one, else centred (VehicleCurvingProblem).
    const CurvingStart* start =
        o.start == "stored" && t < static_cast<int>(stored.state.curving.size())
            ? &stored.state.curving[t]
            : nullptr;
    const bool stored_start = start && start->state.size() > 0;
    if (unworn_starts && !stored_start) study.vehicle_starts[t] = unworn_start(t);
    CurvingProblem p = VehicleCurvingProblem(study, t, rails.high, rails.low, start);
    if (unworn_starts && stored_start) {
      CurvingStart lazy;
      lazy.label = kUnwornEquilibriumStart;
      lazy.lazy = [&unworn_start, t] { return unworn_start(t); };
      p.options.fallback_starts.push_back(std::move(lazy));
    }
    p.options.cancel = [] { return InterruptSignals::Received() != 0; };
    if (o.predictor) {
      p.options.cold_predictor = *EnumFromString(kCurvingPredictorNames, *o.predictor);
    }
    std::cerr << fmt::format("railwear: curving: solving traffic entry '{}'\n", c.name);
    const CurvingResult r = SolveCurving(p);
    if (const int signal = InterruptSignals::Received()) {
      throw Interrupted(signal,
                        fmt::format("{}: curving of {} stopped in the solve of traffic entry '{}' "
                                    "(stopped, not a solution){}; nothing else was solved{}",
                                    SignalName(signal), o.scene, c.name,
                                    all.empty() ? "" : ", the entries before it are printed above",
                                    o.json ? fmt::format(" and {} was not written", *o.json) : ""));
    }
    if (!o.json || *o.json != "-") Print(c, p, r);
    if (r.status == CurvingStatus::kFlangeClimb) {
      std::cerr << "warning: " << c.name << ": " << r.message << "\n";
    }
    if (r.status == CurvingStatus::kNotConverged || r.status == CurvingStatus::kNoEquilibrium) {
      failures += fmt::format("{}{}: {}: {}", failures.empty() ? "" : "; ", c.name,
                              ToString(r.status), r.message);
    }
    all.push_back(Json(c, p, r));
  }
  if (o.json) WriteOutputFile(*o.json, all.dump(2) + "\n", "JSON");
  if (!failures.empty()) throw std::runtime_error("curving: " + failures);
}

}  // namespace railwear::app
