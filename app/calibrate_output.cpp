// The outputs of `railwear calibrate`: report, constants-file header, JSON, CSV, database
// record. See calibrate_output.h.
#include "app/calibrate_output.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "app/influence_constants_file.h"
#include "app/paths.h"
#include "app/toml_fields.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

constexpr double kToNm = 1e9;  // m/N -> nm/N

// ---------------------------------------------------------------------------------------------
// JSON (every number; NaN -> null).

nlohmann::json Num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json ConstantsJson(const InfluenceFitSummary& s) {
  nlohmann::json list = nlohmann::json::array();
  for (const FittedConstant& c : s.constants) {
    list.push_back({{"name", c.name},
                    {"start", c.start},
                    {"value", c.value},
                    {"standard_error", Num(c.standard_error)},
                    {"determined", c.determined},
                    {"at_bound", c.at_bound},
                    {"why_not_determined", c.why_not_determined}});
  }
  return list;
}

nlohmann::json CorrelationJson(const InfluenceFitSummary& s) {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& c : s.constants) names.push_back(c.name);
  nlohmann::json matrix = nlohmann::json::array();
  for (int a = 0; a < s.correlation.rows(); ++a) {
    nlohmann::json row = nlohmann::json::array();
    for (int b = 0; b < s.correlation.cols(); ++b) row.push_back(Num(s.correlation(a, b)));
    matrix.push_back(row);
  }
  return {{"names", names}, {"matrix", matrix}};
}

nlohmann::json CurveJson(const CurveFitReport& c, bool points) {
  nlohmann::json j = {
      {"file", c.file},
      {"body", ToString(c.body)},
      {"radius_mm", c.radius_m / kMm},
      {"load", ToString(c.load)},
      {"path", ToString(c.path)},
      {"weight", c.weight},
      {"points", c.points.size()},
      {"points_left_out", c.points_left_out},
      {"scale_nm_per_N", c.scale_m_per_N * kToNm},
      {"offset_before_nm_per_N", c.offset_before_m_per_N * kToNm},
      {"offset_after_nm_per_N", c.offset_after_m_per_N * kToNm},
      {"offset_standard_error_nm_per_N", Num(c.offset_standard_error_m_per_N * kToNm)},
      {"rms_before", c.rms_before},
      {"max_before", c.max_before},
      {"rms_after", c.rms_after},
      {"max_after", c.max_after}};
  if (!points) return j;
  nlohmann::json list = nlohmann::json::array();
  for (const CurvePointResidual& p : c.points) {
    const double before = p.model_before_m_per_N - p.data_m_per_N;
    const double after = p.model_after_m_per_N - p.data_m_per_N;
    list.push_back({{"line", p.line},
                    {"distance_mm", p.distance_m / kMm},
                    {"data_nm_per_N", p.data_m_per_N * kToNm},
                    {"model_before_nm_per_N", p.model_before_m_per_N * kToNm},
                    {"model_after_nm_per_N", p.model_after_m_per_N * kToNm},
                    {"residual_before_nm_per_N", before * kToNm},
                    {"residual_after_nm_per_N", after * kToNm},
                    {"relative_before", before / c.scale_m_per_N},
                    {"relative_after", after / c.scale_m_per_N}});
  }
  j["point_residuals"] = list;
  return j;
}

nlohmann::json ContactJson(const ContactFitReport& c) {
  return {{"scene", c.name},
          {"weight", c.weight},
          {"target_area_mm2", c.target_area_m2 * kToMm2},
          {"target_p_max_MPa", c.target_p_max_Pa * kToMPa},
          {"area_before_mm2", c.area_before_m2 * kToMm2},
          {"p_max_before_MPa", c.p_max_before_Pa * kToMPa},
          {"area_after_mm2", c.area_after_m2 * kToMm2},
          {"p_max_after_MPa", c.p_max_after_Pa * kToMPa},
          {"area_error_before", c.area_before_m2 / c.target_area_m2 - 1.0},
          {"p_max_error_before", c.p_max_before_Pa / c.target_p_max_Pa - 1.0},
          {"area_error_after", c.area_after_m2 / c.target_area_m2 - 1.0},
          {"p_max_error_after", c.p_max_after_Pa / c.target_p_max_Pa - 1.0}};
}

nlohmann::json ResidualsJson(const InfluenceFitSummary& s, bool points) {
  nlohmann::json curves = nlohmann::json::array();
  for (const auto& c : s.curves) curves.push_back(CurveJson(c, points));
  nlohmann::json contacts = nlohmann::json::array();
  for (const auto& c : s.contacts) contacts.push_back(ContactJson(c));
  return {{"cost_before", s.cost_before},
          {"cost_after", s.cost_after},
          {"curves", curves},
          {"contacts", contacts}};
}

// What the database keeps as constants_json: the fit's numbers without the residuals.
nlohmann::json FitJson(const CalibrateConfig& c, const InfluenceFitSummary& s) {
  nlohmann::json fit = nlohmann::json::array();
  for (auto name : c.fit.fit) fit.push_back(ToString(name));
  return {{"fit", fit},
          {"separate_bodies", c.fit.separate_bodies},
          {"fit_offsets", c.fit.fit_offsets},
          {"start", InfluenceConstantsJson(s.start)},
          {"fitted", InfluenceConstantsJson(s.fitted)},
          {"constants", ConstantsJson(s)},
          {"residual_variance", s.residual_variance},
          {"num_residuals", s.num_residuals},
          {"num_free_parameters", s.num_free_parameters},
          {"condition_number", Num(s.condition_number)},
          {"singular_values", s.singular_values},
          {"covariance_available", s.covariance_available},
          {"covariance_message", s.covariance_message},
          {"well_conditioned", s.well_conditioned},
          {"warnings", s.warnings}};
}

// The text report: a relative error as a percentage.
std::string Pct(double relative) { return fmt::format("{:.3f} %", 100.0 * relative); }

// The database record: whether a scene's profile spec names a file (not a generated profile).
bool IsProfileFile(const std::string& spec) {
  for (const char* prefix : {"builtin:", "circle:", "groove:"}) {
    if (spec.rfind(prefix, 0) == 0) return false;
  }
  return true;
}

// Every input, verbatim, for the database: the config, the CSVs, the scenes and the profile
// files they name.
std::vector<CalibrationInput> Inputs(const CalibrateConfig& c) {
  std::vector<CalibrationInput> in;
  in.push_back({"config", c.path, c.text});
  for (const CalibrateCurveEntry& e : c.curves) {
    in.push_back({"displacement_curves", e.file, ReadInputFile(e.file, "the displacement curves")});
  }
  for (const CalibrateContactEntry& e : c.contacts) {
    if (!e.fem_result.empty()) {
      in.push_back(
          {"fem_result", e.fem_result, ReadInputFile(e.fem_result, "the fem-reference result")});
    }
    in.push_back({"scene", e.scene, e.loaded.text});
    for (const std::string& spec : {e.loaded.wheel_profile_spec, e.loaded.rail_profile_spec}) {
      if (!IsProfileFile(spec)) continue;
      const std::string path = ResolveRelativeTo(DirectoryOf(e.scene), spec);
      in.push_back({"profile", path, ReadInputFile(path, "the profile file")});
    }
  }
  return in;
}

}  // namespace

nlohmann::json CalibrateJson(const CalibrateConfig& c, const InfluenceFitSummary& s,
                             const std::string& out, const std::string& db) {
  nlohmann::json j = FitJson(c, s);
  j["name"] = c.name;
  j["config"] = c.path;
  j["status"] = ToString(s.status);
  j["message"] = s.message;
  j["correlation"] = CorrelationJson(s);
  j["residuals"] = ResidualsJson(s, true);
  j["iterations"] = s.iterations;
  j["contact_solves"] = s.contact_solves;
  j["time_s"] = s.time_s;
  j["ceres_brief_report"] = s.ceres_brief_report;
  j["ceres_full_report"] = s.ceres_full_report;
  j["outputs"] = {{"constants_toml", out.empty() ? nlohmann::json() : nlohmann::json(out)},
                  {"db", db.empty() ? nlohmann::json() : nlohmann::json(db)}};
  return j;
}

std::string CalibrateReportText(const CalibrateConfig& c, const InfluenceFitSummary& s,
                                bool verbose) {
  std::string o;
  o += fmt::format("calibration  {} ({})\n", c.name, c.path);
  int points = 0, left_out = 0;
  for (const auto& r : s.curves) {
    points += static_cast<int>(r.points.size());
    left_out += r.points_left_out;
  }
  o += fmt::format(
      "data         {} displacement-curve file(s), {} curve(s), {} point(s) ({} "
      "outside the windows); {} contact result(s)\n",
      c.curves.size(), s.curves.size(), points, left_out, c.contacts.size());
  for (const CalibrateCurveEntry& e : c.curves) {
    const DisplacementCurves& d = e.data.curves;
    const std::string body = d.body == CurveBody::kFlat
                                 ? std::string("flat")
                                 : fmt::format("{} R {:g} mm", ToString(d.body), d.radius_m / kMm);
    const std::string window =
        std::isfinite(e.data.max_distance_m)
            ? fmt::format("{:g}-{:g} mm", e.data.min_distance_m / kMm, e.data.max_distance_m / kMm)
            : fmt::format(">= {:g} mm", e.data.min_distance_m / kMm);
    o += fmt::format("  {}: {}, E {:g} MPa, nu {:g}, weight {:g}, window {}\n", e.file, body,
                     d.material.youngs_modulus_Pa * kToMPa, d.material.poisson_ratio, e.data.weight,
                     window);
  }
  for (const CalibrateContactEntry& e : c.contacts) {
    o += fmt::format("  {}: target area {:.2f} mm2, p_max {:.1f} MPa, weight {:g} ({} accuracy)\n",
                     e.scene, e.target.area_m2 * kToMm2, e.target.p_max_Pa * kToMPa,
                     e.target.weight, ToString(e.target.problem.model.accuracy));
  }
  std::string fit;
  for (auto n : c.fit.fit) fit += fmt::format("{}{}", fit.empty() ? "" : " ", ToString(n));
  o += fmt::format("fit          {}, {}, {}\n", fit,
                   c.fit.separate_bodies ? "a convex and a concave set" : "one set for both bodies",
                   c.fit.fit_offsets ? "an offset per curve" : "no offsets");
  o += fmt::format("status       {} ({}; {} iterations, {} contact solves, {:.2f} s)\n",
                   ToString(s.status), s.message, s.iterations, s.contact_solves, s.time_s);
  o += fmt::format("fitted       {}\n\n", InfluenceConstantsText(s.fitted));

  o += fmt::format("{:<14} {:>10} {:>10} {:>12}\n", "constant", "start", "fitted", "std.error");
  for (const FittedConstant& k : s.constants) {
    std::string note;
    if (!k.determined) note = "  not determined: held at start";
    if (k.at_bound) note = "  at its bound";
    o += fmt::format("{:<14} {:>10.5g} {:>10.5g} {:>12}{}\n", k.name, k.start, k.value,
                     std::isfinite(k.standard_error) ? fmt::format("{:.3g}", k.standard_error)
                                                     : std::string("-"),
                     note);
  }
  if (s.correlation.size() > 0) {
    o += "\ncorrelation\n" + fmt::format("{:<14}", "");
    for (const auto& k : s.constants) o += fmt::format(" {:>12}", k.name);
    o += "\n";
    for (int a = 0; a < s.correlation.rows(); ++a) {
      o += fmt::format("{:<14}", s.constants[a].name);
      for (int b = 0; b < s.correlation.cols(); ++b) {
        const double r = s.correlation(a, b);
        o += std::isfinite(r) ? fmt::format(" {:>12.4f}", r) : fmt::format(" {:>12}", "-");
      }
      o += "\n";
    }
  } else {
    o += "\ncorrelation  unavailable: " + s.covariance_message + "\n";
  }
  std::string sv;
  for (double v : s.singular_values) sv += fmt::format("{}{:.3g}", sv.empty() ? "" : " ", v);
  o += fmt::format(
      "\nconditioning {}: condition number {:.3g} of the column-scaled Jacobian "
      "(singular values {}); residual s = {:.4g} (relative to each curve's RMS); "
      "{} residuals, {} free parameters\n",
      s.well_conditioned ? "well conditioned" : "BADLY CONDITIONED", s.condition_number,
      sv.empty() ? "-" : sv, std::sqrt(s.residual_variance), s.num_residuals,
      s.num_free_parameters);
  for (const auto& w : s.warnings) o += "  warning: " + w + "\n";

  if (!s.curves.empty()) {
    o += fmt::format("\n{:<46} {:>6} {:>11} {:>11} {:>11} {:>11} {:>12}\n",
                     "curve (residual / curve RMS)", "points", "rms before", "max before",
                     "rms after", "max after", "offset nm/N");
    for (const auto& r : s.curves) {
      o += fmt::format("{:<46} {:>6} {:>11} {:>11} {:>11} {:>11} {:>12.4g}\n", r.Name(),
                       r.points.size(), Pct(r.rms_before), Pct(r.max_before), Pct(r.rms_after),
                       Pct(r.max_after), r.offset_after_m_per_N * kToNm);
    }
  }
  if (!s.contacts.empty()) {
    o += fmt::format("\n{:<40} {:>25} {:>25}\n", "contact result", "area mm2 target/bef/aft",
                     "p_max MPa target/bef/aft");
    for (const auto& r : s.contacts) {
      o += fmt::format("{:<40} {:>25} {:>25}\n", fs::path(r.name).filename().string(),
                       fmt::format("{:.2f} {:.2f} {:.2f}", r.target_area_m2 * kToMm2,
                                   r.area_before_m2 * kToMm2, r.area_after_m2 * kToMm2),
                       fmt::format("{:.1f} {:.1f} {:.1f}", r.target_p_max_Pa * kToMPa,
                                   r.p_max_before_Pa * kToMPa, r.p_max_after_Pa * kToMPa));
      o += fmt::format("{:<40} {:>25} {:>25}\n", "  error before -> after",
                       Pct(r.area_before_m2 / r.target_area_m2 - 1.0) + " -> " +
                           Pct(r.area_after_m2 / r.target_area_m2 - 1.0),
                       Pct(r.p_max_before_Pa / r.target_p_max_Pa - 1.0) + " -> " +
                           Pct(r.p_max_after_Pa / r.target_p_max_Pa - 1.0));
    }
  }
  o += "\nCeres: " + s.ceres_brief_report + "\n";
  if (verbose) o += "\n" + s.ceres_full_report;
  return o;
}

std::string NowUtc() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(now));
}

std::string CalibrateConstantsHeader(const CalibrateConfig& c, const InfluenceFitSummary& s,
                                     const std::string& out, const std::string& created) {
  // Paths relative to the constants file's folder, so the file can move with its data.
  const fs::path base = fs::absolute(fs::path(out)).parent_path();
  auto where = [&](const std::string& file) {
    return fs::absolute(file).lexically_normal().lexically_relative(base).string();
  };
  std::string t;
  t += "# Influence constants of the seed's eq. 4, fitted by `railwear calibrate`.\n";
  t += fmt::format(
      "# Use in a scene:  [model] influence_constants = \"{}\" (relative to the scene)\n",
      fs::path(out).filename().string());
  t += fmt::format("# calibration: {}\n", c.name);
  t += fmt::format("# config:      {}\n", where(c.path));
  t += fmt::format("# created:     {} by railwear {}\n", created, RAILWEAR_VERSION);
  for (const CalibrateCurveEntry& e : c.curves) {
    t += fmt::format("# data:        {} (weight {:g}, {:g} to {:g} mm)\n", where(e.file),
                     e.data.weight, e.data.min_distance_m / kMm, e.data.max_distance_m / kMm);
  }
  for (const CalibrateContactEntry& e : c.contacts) {
    t += fmt::format("# data:        {} (area {:g} mm2, p_max {:g} MPa, weight {:g})\n",
                     where(e.scene), e.target.area_m2 * kToMm2, e.target.p_max_Pa * kToMPa,
                     e.target.weight);
  }
  t +=
      fmt::format("# status:      {}, {} (condition number {:.3g}), residual s = {:.4g}\n",
                  ToString(s.status), s.well_conditioned ? "well conditioned" : "badly conditioned",
                  s.condition_number, std::sqrt(s.residual_variance));
  t += "# fitted:      start -> value +- standard error\n";
  for (const FittedConstant& k : s.constants) {
    t += fmt::format("#   {:<12} {:.6g} -> {:.6g}{}\n", k.name, k.start, k.value,
                     !k.determined                     ? " (not determined by the data: start kept)"
                     : std::isfinite(k.standard_error) ? fmt::format(" +- {:.3g}", k.standard_error)
                                                       : std::string(" (no standard error)"));
  }
  for (const auto& w : s.warnings) t += "# warning:     " + w + "\n";
  return t;
}

std::string CalibratePointCsv(const InfluenceFitSummary& s) {
  std::string t =
      "file,load,path,line,distance_mm,data_nm_per_N,model_before_nm_per_N,model_after_nm_per_N,"
      "residual_before_nm_per_N,residual_after_nm_per_N,relative_before,relative_after\n";
  for (const auto& c : s.curves) {
    for (const auto& p : c.points) {
      const double before = p.model_before_m_per_N - p.data_m_per_N;
      const double after = p.model_after_m_per_N - p.data_m_per_N;
      t += fmt::format("{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.6g},{:.6g},{:.6g},{:.6g}\n",
                       c.file, ToString(c.load), ToString(c.path), p.line, p.distance_m / kMm,
                       p.data_m_per_N * kToNm, p.model_before_m_per_N * kToNm,
                       p.model_after_m_per_N * kToNm, before * kToNm, after * kToNm,
                       before / c.scale_m_per_N, after / c.scale_m_per_N);
    }
  }
  return t;
}

CalibrationRecord CalibrateRecord(const CalibrateConfig& config, const InfluenceFitSummary& s,
                                  const std::string& constants_toml) {
  CalibrationRecord r;
  r.name = config.name;
  r.created_utc = "";
  r.program_version = RAILWEAR_VERSION;
  r.config_path = config.path;
  r.config_text = config.text;
  r.status = std::string(ToString(s.status));
  r.well_conditioned = s.well_conditioned;
  r.constants_json = FitJson(config, s).dump();
  r.correlation_json = CorrelationJson(s).dump();
  r.residuals_json = ResidualsJson(s, false).dump();
  r.ceres_report = s.ceres_full_report;
  r.constants_toml = constants_toml;
  r.inputs = Inputs(config);
  return r;
}

}  // namespace railwear::app
