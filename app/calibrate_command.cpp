// `railwear calibrate`: config -> reference data -> FitInfluenceConstants -> report, constants
// TOML, JSON, CSV, database. See calibrate_command.h.
#include "app/calibrate_command.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/contact_output.h"
#include "app/fem_contact_result.h"
#include "app/paths.h"
#include "app/scene.h"
#include "app/toml_fields.h"
#include "calibration/displacement_curves.h"
#include "calibration/influence_fit.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

constexpr double kMm = 1e-3;
constexpr double kToNm = 1e9;  // m/N -> nm/N
constexpr double kToMm2 = 1e6;
constexpr double kToMPa = 1e-6;

struct CurveEntry {
  std::string file;  // resolved
  CurveDataSet data;
};

struct ContactEntry {
  std::string scene;  // resolved
  std::string fem_result;  // resolved fem-reference result file, when the target came from one
  Scene loaded;
  ContactTarget target;
};

struct Config {
  std::string path;
  std::string text;
  std::string name;
  InfluenceFitOptions fit;
  std::string out;  // resolved
  std::string db;   // resolved; empty: none
  std::vector<CurveEntry> curves;
  std::vector<ContactEntry> contacts;
};

std::string ReadText(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the {}", path, what));
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// A file named by `key` in `t`, resolved against the config's folder; it must exist.
std::string ExistingFile(const Fields& t, std::string_view key, const std::string& config,
                         std::string_view what) {
  const std::string written = t.RequiredString(key, fmt::format("the path of {}", what));
  const std::string path = ResolveRelativeTo(DirectoryOf(config), written);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    t.Fail(key, fmt::format("an existing file with {} (looked for {})", what, path));
  }
  return path;
}

std::vector<InfluenceConstantName> ReadFitList(const Fields& t) {
  std::vector<InfluenceConstantName> out;
  const toml::node* node = t.Node("fit");
  if (node == nullptr) return InfluenceFitOptions{}.fit;
  const std::string expected = "a non-empty array of distinct names of 'c_f', 'c_z', 'c_s'";
  const toml::array* a = node->as_array();
  if (a == nullptr || a->empty()) t.Fail("fit", expected);
  for (const toml::node& e : *a) {
    const auto s = e.value_exact<std::string>();
    const auto name = s ? InfluenceConstantNameFromString(*s) : std::nullopt;
    if (!name || std::find(out.begin(), out.end(), *name) != out.end()) t.Fail("fit", expected);
    out.push_back(*name);
  }
  return out;
}

void ReadCalibrationTable(const Fields& top, Config* c) {
  c->name = fs::path(c->path).stem().string();
  c->out = ResolveRelativeTo(DirectoryOf(c->path), c->name + "_constants.toml");
  const auto t = top.Table("calibration", "a table");
  if (!t) return;
  t->AllowOnly({"name", "fit", "separate_bodies", "start", "fit_offsets", "out", "db",
                "contact_relative_step", "max_iterations"});
  if (const auto name = t->String("name")) c->name = *name;
  c->fit.fit = ReadFitList(*t);
  c->fit.separate_bodies = t->Bool("separate_bodies").value_or(false);
  if (const auto start = t->Table("start", "an inline table { c_f, c_z, c_s } or "
                                           "{ convex = {...}, concave = {...} }")) {
    c->fit.start = ReadInfluenceConstantsTable(*start);
    if (c->fit.start.IsSeparate() && !c->fit.separate_bodies) {
      t->Fail("start", "one set { c_f, c_z, c_s } (separate_bodies = false)");
    }
  }
  c->fit.fit_offsets = t->Bool("fit_offsets").value_or(true);
  if (const auto out = t->String("out")) {
    if (out->empty()) t->Fail("out", "the path of the constants file to write");
    c->out = ResolveRelativeTo(DirectoryOf(c->path), *out);
  }
  if (const auto db = t->String("db")) {
    if (db->empty()) t->Fail("db", "the path of a study database");
    c->db = ResolveRelativeTo(DirectoryOf(c->path), *db);
  }
  if (const auto step = t->Number("contact_relative_step", OpenClosed(0.0, 0.5))) {
    c->fit.contact_relative_step = *step;
  }
  if (const auto n = t->Number("max_iterations", AtLeast(1.0))) {
    if (*n != std::floor(*n) || *n > 100000) t->Fail("max_iterations", "an integer in [1, 100000]");
    c->fit.max_num_iterations = static_cast<int>(*n);
  }
  std::string error;
  if (!c->fit.IsValid(&error)) {
    throw InputError(fmt::format("{}:{}: [calibration]: {}", c->path, t->Line(), error));
  }
}

// The [[NAME]] tables of `top` (none when absent).
std::vector<Fields> ArrayOfTables(const Fields& top, std::string_view key,
                                  std::string_view expected) {
  std::vector<Fields> out;
  const toml::node* node = top.Node(key);
  if (node == nullptr) return out;
  if (!node->is_array_of_tables()) top.Fail(key, expected);
  int index = 0;
  for (const toml::node& entry : *node->as_array()) {
    out.emplace_back(*entry.as_table(), fmt::format("{}[{}]", key, index++), top.file());
  }
  return out;
}

void ReadCurveEntries(const Fields& top, Config* c) {
  for (const Fields& t : ArrayOfTables(top, "displacement_curves",
                                       "[[displacement_curves]] tables with file, weight, "
                                       "min_distance_mm, max_distance_mm")) {
    t.AllowOnly({"file", "weight", "min_distance_mm", "max_distance_mm"});
    CurveEntry e;
    e.file = ExistingFile(t, "file", c->path, "displacement curves (CSV)");
    e.data.weight = t.Number("weight", Positive()).value_or(1.0);
    e.data.min_distance_m = t.Number("min_distance_mm", AtLeast(0.0)).value_or(0.0) * kMm;
    if (const auto max = t.Number("max_distance_mm", Positive())) {
      e.data.max_distance_m = *max * kMm;
      if (!(e.data.max_distance_m > e.data.min_distance_m)) {
        t.Fail("max_distance_mm", "a distance larger than min_distance_mm");
      }
    }
    e.data.curves = ReadDisplacementCurves(e.file);  // its own FILE:LINE messages
    c->curves.push_back(std::move(e));
  }
}

void ReadContactEntries(const Fields& top, Config* c) {
  for (const Fields& t : ArrayOfTables(top, "contact_results",
                                       "[[contact_results]] tables with scene, area_mm2, "
                                       "p_max_MPa (or fem_result), weight")) {
    t.AllowOnly({"scene", "area_mm2", "p_max_MPa", "weight", "fem_result"});
    ContactEntry e;
    std::string prefix;
    if (t.Has("fem_result")) {
      // A fem-reference result file: its scene and its finest level's area and peak pressure.
      for (const char* key : {"scene", "area_mm2", "p_max_MPa"}) {
        if (t.Has(key)) {
          t.Fail(key, "no scene, area_mm2 or p_max_MPa with fem_result (the result file holds "
                      "them)");
        }
      }
      e.fem_result = ExistingFile(t, "fem_result", c->path, "a fem-reference contact result");
      const FemContactTarget fem = ReadFemContactTarget(e.fem_result);  // FILE:LINE messages
      prefix = FieldPrefix(t.file(), *t.Node("fem_result"), t.KeyName("fem_result"));
      if (fem.status != "ok" || fem.scene.empty()) {
        throw InputError(fmt::format(
            "{}: the result has status '{}'{}; expected status 'ok' and a scene", prefix,
            fem.status, fem.scene.empty() ? " and no scene" : ""));
      }
      e.scene = fem.scene;
      e.target.area_m2 = fem.area_mm2 / kToMm2;
      e.target.p_max_Pa = fem.p_max_MPa / kToMPa;
    } else {
      e.scene = ExistingFile(t, "scene", c->path, "a contact scene (TOML)");
      e.target.area_m2 = t.RequiredNumber("area_mm2", Positive()) / kToMm2;
      e.target.p_max_Pa = t.RequiredNumber("p_max_MPa", Positive()) / kToMPa;
      prefix = FieldPrefix(t.file(), *t.Node("scene"), t.KeyName("scene"));
    }
    e.target.weight = t.Number("weight", Positive()).value_or(1.0);
    e.loaded = LoadScene(e.scene);  // its own FILE:LINE messages
    if (e.loaded.wear || e.loaded.track) {
      throw InputError(fmt::format("{}: expected a single-wheel contact scene ([load]), not a {}",
                                   prefix, e.loaded.wear ? "wear scene" : "wheelset"));
    }
    const ModelOptions& m = e.loaded.problem.model;
    if (m.kind == ModelKind::kHertz || m.kernel != KernelModel::kGolubenko) {
      throw InputError(fmt::format("{}: its model ({}, kernel {}) does not use the influence "
                                   "constants; expected kind = \"conformal\" (golubenko kernel)",
                                   prefix, ToString(m.kind), ToString(m.kernel)));
    }
    e.target.name = e.scene;
    e.target.problem = e.loaded.problem;
    c->contacts.push_back(std::move(e));
  }
}

Config ReadConfig(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: no such file; expected a calibration config (TOML)", path));
  }
  Config c;
  c.path = path;
  c.text = ReadText(path, "calibration config");
  const toml::table root = ParseToml(c.text, path);
  const Fields top(root, "", path);
  top.AllowOnly({"calibration", "displacement_curves", "contact_results"});
  ReadCalibrationTable(top, &c);
  ReadCurveEntries(top, &c);
  ReadContactEntries(top, &c);
  if (c.curves.empty() && c.contacts.empty()) {
    throw InputError(fmt::format("{}:1: no data: expected at least one [[displacement_curves]] "
                                 "or [[contact_results]] table",
                                 path));
  }
  return c;
}

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
  nlohmann::json j = {{"file", c.file},
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
                      {"offset_standard_error_nm_per_N",
                       Num(c.offset_standard_error_m_per_N * kToNm)},
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
nlohmann::json FitJson(const Config& c, const InfluenceFitSummary& s) {
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

nlohmann::json MakeJson(const Config& c, const InfluenceFitSummary& s, const std::string& out,
                        const std::string& db) {
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

// ---------------------------------------------------------------------------------------------
// The text report.

std::string Pct(double relative) { return fmt::format("{:.3f} %", 100.0 * relative); }

std::string FormatReport(const Config& c, const InfluenceFitSummary& s, bool verbose) {
  std::string o;
  o += fmt::format("calibration  {} ({})\n", c.name, c.path);
  int points = 0, left_out = 0;
  for (const auto& r : s.curves) {
    points += static_cast<int>(r.points.size());
    left_out += r.points_left_out;
  }
  o += fmt::format("data         {} displacement-curve file(s), {} curve(s), {} point(s) ({} "
                   "outside the windows); {} contact result(s)\n",
                   c.curves.size(), s.curves.size(), points, left_out, c.contacts.size());
  for (const CurveEntry& e : c.curves) {
    const DisplacementCurves& d = e.data.curves;
    const std::string body = d.body == CurveBody::kFlat
                                 ? std::string("flat")
                                 : fmt::format("{} R {:g} mm", ToString(d.body), d.radius_m / kMm);
    const std::string window =
        std::isfinite(e.data.max_distance_m)
            ? fmt::format("{:g}-{:g} mm", e.data.min_distance_m / kMm, e.data.max_distance_m / kMm)
            : fmt::format(">= {:g} mm", e.data.min_distance_m / kMm);
    o += fmt::format("  {}: {}, E {:g} MPa, nu {:g}, weight {:g}, window {}\n", e.file, body,
                     d.material.youngs_modulus_Pa * kToMPa, d.material.poisson_ratio,
                     e.data.weight, window);
  }
  for (const ContactEntry& e : c.contacts) {
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
  o += fmt::format("\nconditioning {}: condition number {:.3g} of the column-scaled Jacobian "
                   "(singular values {}); residual s = {:.4g} (relative to each curve's RMS); "
                   "{} residuals, {} free parameters\n",
                   s.well_conditioned ? "well conditioned" : "BADLY CONDITIONED",
                   s.condition_number, sv.empty() ? "-" : sv, std::sqrt(s.residual_variance),
                   s.num_residuals, s.num_free_parameters);
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
    o += fmt::format("\n{:<40} {:>25} {:>25}\n", "contact result",
                     "area mm2 target/bef/aft", "p_max MPa target/bef/aft");
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

// ---------------------------------------------------------------------------------------------
// The constants file: an [influence_constants] table that ReadInfluenceConstantsFile reads, with
// the provenance in comments.

std::string NowUtc() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(now));
}

std::string ConstantsToml(const Config& c, const InfluenceFitSummary& s, const std::string& out,
                          const std::string& created) {
  // Paths relative to the constants file's folder, so the file can move with its data.
  const fs::path base = fs::absolute(fs::path(out)).parent_path();
  auto where = [&](const std::string& file) {
    return fs::absolute(file).lexically_normal().lexically_relative(base).string();
  };
  std::string t;
  t += "# Influence constants of the seed's eq. 4, fitted by `railwear calibrate`.\n";
  t += fmt::format("# Use in a scene:  [model] influence_constants = \"{}\" (relative to the scene)\n",
                   fs::path(out).filename().string());
  t += fmt::format("# calibration: {}\n", c.name);
  t += fmt::format("# config:      {}\n", where(c.path));
  t += fmt::format("# created:     {} by railwear {}\n", created, RAILWEAR_VERSION);
  for (const CurveEntry& e : c.curves) {
    t += fmt::format("# data:        {} (weight {:g}, {:g} to {:g} mm)\n",
                     where(e.file), e.data.weight,
                     e.data.min_distance_m / kMm, e.data.max_distance_m / kMm);
  }
  for (const ContactEntry& e : c.contacts) {
    t += fmt::format("# data:        {} (area {:g} mm2, p_max {:g} MPa, weight {:g})\n",
                     where(e.scene),
                     e.target.area_m2 * kToMm2, e.target.p_max_Pa * kToMPa, e.target.weight);
  }
  t += fmt::format("# status:      {}, {} (condition number {:.3g}), residual s = {:.4g}\n",
                   ToString(s.status),
                   s.well_conditioned ? "well conditioned" : "badly conditioned",
                   s.condition_number, std::sqrt(s.residual_variance));
  t += "# fitted:      start -> value +- standard error\n";
  for (const FittedConstant& k : s.constants) {
    t += fmt::format("#   {:<12} {:.6g} -> {:.6g}{}\n", k.name, k.start, k.value,
                     !k.determined ? " (not determined by the data: start kept)"
                     : std::isfinite(k.standard_error)
                         ? fmt::format(" +- {:.3g}", k.standard_error)
                         : std::string(" (no standard error)"));
  }
  for (const auto& w : s.warnings) t += "# warning:     " + w + "\n";
  auto set = [](const InfluenceConstantSet& v) {
    return fmt::format("c_f = {}\nc_z = {}\nc_s = {}\n", v.c_f, v.c_z, v.c_s);
  };
  if (s.fitted.separate) {
    t += "\n[influence_constants.convex]\n" + set(s.fitted.separate->convex);
    t += "\n[influence_constants.concave]\n" + set(s.fitted.separate->concave);
  } else {
    t += "\n[influence_constants]\n" + set({s.fitted.c_f, s.fitted.c_z, s.fitted.c_s});
  }
  return t;
}

void WriteFile(const std::string& path, const std::string& text, const std::string& what) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  if (!out) throw InputError(fmt::format("{}: cannot write the {}", path, what));
}

std::string PointCsv(const InfluenceFitSummary& s) {
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

bool IsProfileFile(const std::string& spec) {
  for (const char* prefix : {"builtin:", "circle:", "groove:"}) {
    if (spec.rfind(prefix, 0) == 0) return false;
  }
  return true;
}

// Every input, verbatim, for the database: the config, the CSVs, the scenes and the profile
// files they name.
std::vector<CalibrationInput> Inputs(const Config& c) {
  std::vector<CalibrationInput> in;
  in.push_back({"config", c.path, c.text});
  for (const CurveEntry& e : c.curves) {
    in.push_back({"displacement_curves", e.file, ReadText(e.file, "displacement curves")});
  }
  for (const ContactEntry& e : c.contacts) {
    if (!e.fem_result.empty()) {
      in.push_back({"fem_result", e.fem_result, ReadText(e.fem_result, "fem-reference result")});
    }
    in.push_back({"scene", e.scene, e.loaded.text});
    for (const std::string& spec : {e.loaded.wheel_profile_spec, e.loaded.rail_profile_spec}) {
      if (!IsProfileFile(spec)) continue;
      const std::string path = ResolveRelativeTo(DirectoryOf(e.scene), spec);
      in.push_back({"profile", path, ReadText(path, "profile file")});
    }
  }
  return in;
}

}  // namespace

void SetupCalibrate(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit the influence constants c_f, c_z, c_s (seed eq. 4) to displacement curves and contact "
      "results; write an influence-constants TOML for scenes");
  cmd->add_option("config", o->config, "Calibration config (TOML; see `railwear calibrate "
                                       "--help` and the README)")
      ->required();
  cmd->add_option("--out", o->out, "Constants file to write (default: [calibration] out, else "
                                   "CONFIG-STEM_constants.toml beside the config)");
  cmd->add_option("--db", o->db, "Store the calibration and its inputs in this study database "
                                 "(default: [calibration] db, if any)");
  cmd->add_option("--json", o->json, "Write everything as JSON to FILE, or '-' for stdout");
  cmd->add_option("--csv", o->csv, "Write every point's residual before and after to FILE");
  cmd->add_flag("--verbose", o->verbose, "Print Ceres's full report");
  cmd->callback([o]() { RunCalibrate(*o); });
}

void RunCalibrate(const CalibrateOptions& o) {
  Config config = ReadConfig(o.config);
  const std::string out = o.out ? *o.out : config.out;
  const std::string db = o.db ? *o.db : config.db;
  if (o.json && *o.json != "-" && o.csv && *o.json == *o.csv) {
    throw InputError(fmt::format("--json and --csv both name '{}'; expected two files", *o.csv));
  }

  InfluenceFitData data;
  for (const CurveEntry& e : config.curves) data.curves.push_back(e.data);
  for (const ContactEntry& e : config.contacts) data.contacts.push_back(e.target);
  std::cerr << fmt::format("railwear: fitting {} constant(s) to {} curve file(s) and {} contact "
                           "result(s)...\n",
                           config.fit.fit.size() * (config.fit.separate_bodies ? 2 : 1),
                           config.curves.size(), config.contacts.size());
  const InfluenceFitSummary s = FitInfluenceConstants(data, config.fit);

  const bool json_stdout = o.json && *o.json == "-";
  std::ostream& report = json_stdout ? std::cerr : std::cout;
  if (s.status == InfluenceFitStatus::kFailure) {
    report << FormatReport(config, s, o.verbose);
    throw std::runtime_error("calibration failed: " + s.message + "; nothing written");
  }
  for (const auto& w : s.warnings) std::cerr << "railwear: warning: " << w << "\n";

  // The constants file, checked by reading it back as a scene would.
  const std::string created = NowUtc();
  const std::string toml = ConstantsToml(config, s, out, created);
  WriteFile(out, toml, "influence constants file");
  const InfluenceConstants back = ReadInfluenceConstantsFile(out);
  if (InfluenceConstantsText(back) != InfluenceConstantsText(s.fitted)) {
    throw std::runtime_error(fmt::format("{}: reads back as {}, not {}", out,
                                         InfluenceConstantsText(back),
                                         InfluenceConstantsText(s.fitted)));
  }
  report << FormatReport(config, s, o.verbose);
  report << fmt::format("wrote {}\n", out);

  if (o.csv) {
    WriteFile(*o.csv, PointCsv(s), "residual CSV");
    report << fmt::format("wrote {}\n", *o.csv);
  }
  if (!db.empty()) {
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
    r.constants_toml = toml;
    r.inputs = Inputs(config);
    ProfileStore store = ProfileStore::Open(db);
    const int64_t id = store.AddCalibration(r);
    report << fmt::format("stored calibration {} in {}\n", id, db);
  }
  if (o.json) {
    const std::string text = MakeJson(config, s, out, db).dump(2) + "\n";
    if (json_stdout) {
      std::cout << text << std::flush;
    } else {
      WriteFile(*o.json, text, "JSON");
      report << fmt::format("wrote {}\n", *o.json);
    }
  }
  if (s.status == InfluenceFitStatus::kNoConvergence) {
    throw std::runtime_error("Ceres stopped without converging (" + s.message +
                             "); the outputs were written from the last iterate");
  }
}

}  // namespace railwear::app
