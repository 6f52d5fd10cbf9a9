// `railwear accuracy`: models x accuracy levels; time, memory and errors against a reference;
// table, CSV and the Pareto plot.
#include "app/accuracy_command.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "app/gnuplot.h"
#include "app/paths.h"
#include "app/wear_accuracy.h"
#include "core/contact/grid_resolution.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kToMm2 = 1e6, kToMPa = 1e-6, kToMs = 1e3, kToMiB = 1.0 / (1024.0 * 1024.0);
constexpr double kToPercent = 100.0;
// Errors below this are drawn at it on the plot's log axis [%].
constexpr double kPlotErrorFloor_pct = 1e-3;

// ---------------------------------------------------------------------------------------------
// Memory: the peak resident memory a call adds (Linux). malloc_trim returns the heap's free
// pages to the system, writing "5" to /proc/self/clear_refs resets the peak (VmHWM) to the
// current resident size (Linux >= 4.0), and VmHWM after the call less VmRSS before it is what
// the call touched at most at once.
std::optional<double> StatusKiB(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream fields(line.substr(key.size()));
    double kib = 0.0;
    if (fields >> kib) return kib;
  }
  return std::nullopt;
}

class PeakMemoryProbe {
 public:
  void Start() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5" << std::flush;
    ok_ = static_cast<bool>(clear);
    rss_kib_ = StatusKiB("VmRSS:");
  }
  // Bytes, NaN when the platform cannot tell.
  double Stop() const {
    const auto peak = StatusKiB("VmHWM:");
    if (!ok_ || !rss_kib_ || !peak) return kNaN;
    return std::max(0.0, *peak - *rss_kib_) * 1024.0;
  }

 private:
  bool ok_ = false;
  std::optional<double> rss_kib_;
};

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  if (n == 0) return kNaN;
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ---------------------------------------------------------------------------------------------
std::string CanonicalModel(const std::string& name) {
  return name == "conformal" ? "conformal+golubenko" : name;
}

void CheckName(const std::string& name, const std::vector<std::string>& valid,
               const std::string& what) {
  if (std::find(valid.begin(), valid.end(), name) == valid.end()) {
    throw InputError(fmt::format("{} '{}': expected one of {}", what, name,
                                 fmt::join(valid, ", ")));
  }
}

// The model's options; the scene's influence constants stay.
ModelOptions ModelFor(const std::string& model, const ModelOptions& scene_model) {
  ModelOptions o;
  if (model == "hertz") {
    o = MakeModelOptions(ModelKind::kHertz);
  } else if (model == "halfspace") {
    o = MakeModelOptions(ModelKind::kHalfspace);
  } else if (model == "conformal+boussinesq") {
    o = MakeModelOptions(ModelKind::kConformal);
    o.kind = ModelKind::kCustom;
    o.kernel = KernelModel::kBoussinesq;
  } else if (model == "conformal+golubenko") {
    o = MakeModelOptions(ModelKind::kConformal);
  } else {
    o = MakeModelOptions(ModelKind::kAuto);
  }
  o.constants = scene_model.constants;
  return o;
}

AccuracyQuantities QuantitiesOf(const ContactResult& r) {
  AccuracyQuantities q;
  q.area_m2 = r.area_m2;
  q.p_max_Pa = r.p_max_Pa;
  q.vertical_force_N = r.vertical_force_N;
  q.lateral_force_N = r.lateral_force_N;
  if (!r.patches.empty() && r.patches[0].rolling) {
    double fx = 0.0, fy = 0.0;
    for (const auto& p : r.patches) {
      if (!p.rolling) continue;
      fx += p.rolling->tangential.force_x_N;
      fy += p.rolling->tangential.force_s_yz_N.x();
    }
    q.creep_x_N = fx;
    q.creep_y_N = fy;
  }
  return q;
}

AccuracyRow RunOne(const ContactProblem& base, const std::string& model, const std::string& level,
                   int repeats) {
  ContactProblem p = base;
  p.model = ModelFor(model, base.model);
  AccuracyRow row;
  row.model = model;
  row.level = level;
  if (model != "hertz") {
    p.model.accuracy = *AccuracyPresetFromString(level);
    row.cells_per_semi_axis = CellsPerSemiAxis(p.model.accuracy);
  }
  std::vector<double> times, memory;
  ContactResult r;
  PeakMemoryProbe probe;
  for (int k = 0; k < repeats; ++k) {
    probe.Start();
    const auto t0 = std::chrono::steady_clock::now();
    r = SolveContact(p);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    memory.push_back(probe.Stop());
  }
  row.repeats = repeats;
  row.time_median_s = Median(times);
  row.time_min_s = *std::min_element(times.begin(), times.end());
  row.time_max_s = *std::max_element(times.begin(), times.end());
  row.memory_bytes = std::any_of(memory.begin(), memory.end(), [](double m) { return std::isnan(m); })
                         ? kNaN
                         : Median(memory);
  row.status = r.status;
  row.message = r.message;
  row.iterations = r.iterations;
  row.patches = static_cast<int>(r.patches.size());
  std::vector<std::string> labels;
  for (const auto& patch : r.patches) {
    row.cells += patch.cells;
    row.cells_in_contact += patch.cells_in_contact;
    labels.push_back(patch.model);
  }
  row.patch_models = fmt::format("{}", fmt::join(labels, ";"));
  row.q = QuantitiesOf(r);
  return row;
}

// ---------------------------------------------------------------------------------------------
// The reference from the reference model's runs.
AccuracyReference ReferenceFromRuns(const std::vector<AccuracyRow>& rows,
                                    const std::string& model, bool rolling) {
  std::vector<const AccuracyRow*> runs;
  for (const auto& r : rows) {
    if (r.model == model && r.status == SolverStatus::kConverged) runs.push_back(&r);
  }
  if (runs.empty()) {
    throw std::runtime_error(fmt::format(
        "the reference model {} converged at no level; no errors can be given", model));
  }
  std::sort(runs.begin(), runs.end(), [](const AccuracyRow* a, const AccuracyRow* b) {
    return a->cells_per_semi_axis < b->cells_per_semi_axis;
  });
  AccuracyReference ref;
  ref.has_area = ref.has_p_max = ref.has_force = true;
  ref.has_creep = rolling && runs.back()->q.creep_x_N.has_value();
  const size_t n = runs.size();
  std::vector<std::string> levels;
  for (const auto* r : runs) levels.push_back(r->level);
  // One quantity: extrapolated from the three finest levels where they allow, else the finest.
  auto settle = [&](const std::string& name, auto get) {
    const double finest = get(*runs[n - 1]);
    if (n >= 3 && model != "hertz") {
      const AccuracyRow &a = *runs[n - 3], &b = *runs[n - 2], &c = *runs[n - 1];
      const auto e = ExtrapolateRichardson(1.0 / a.cells_per_semi_axis, get(a),
                                           1.0 / b.cells_per_semi_axis, get(b),
                                           1.0 / c.cells_per_semi_axis, get(c));
      if (e) {
        ref.how.emplace_back(name, fmt::format("extrapolated, order {:.2f}", e->order));
        return e->value;
      }
      const double scale = std::max({std::abs(get(a)), std::abs(get(b)), std::abs(get(c))});
      const bool settled = std::abs(get(a) - get(b)) <= 1e-9 * scale &&
                           std::abs(get(b) - get(c)) <= 1e-9 * scale;
      ref.how.emplace_back(
          name, fmt::format("{} level ({})", runs[n - 1]->level,
                            settled ? "the same at every level"
                                    : "the levels do not converge monotonically at order >= 1"));
      return finest;
    }
    ref.how.emplace_back(name, fmt::format("{} level", runs[n - 1]->level));
    return finest;
  };
  ref.q.area_m2 = settle("area", [](const AccuracyRow& r) { return r.q.area_m2; });
  ref.q.p_max_Pa = settle("p_max", [](const AccuracyRow& r) { return r.q.p_max_Pa; });
  ref.q.vertical_force_N =
      settle("vertical force", [](const AccuracyRow& r) { return r.q.vertical_force_N; });
  ref.q.lateral_force_N =
      settle("lateral force", [](const AccuracyRow& r) { return r.q.lateral_force_N; });
  if (ref.has_creep) {
    ref.q.creep_x_N = settle("creep x", [](const AccuracyRow& r) { return *r.q.creep_x_N; });
    ref.q.creep_y_N = settle("creep y", [](const AccuracyRow& r) { return *r.q.creep_y_N; });
  }
  ref.source = fmt::format("{} at {}", model, fmt::join(levels, ", "));
  return ref;
}

// The reference from a JSON file as `railwear contact --json` writes it; any of its totals may
// be missing (a FEM result may give area and peak pressure only).
AccuracyReference ReferenceFromFile(const std::string& path, bool rolling) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot read the reference file", path));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({}); expected the JSON of `railwear contact "
                                 "--json`", path, e.what()));
  }
  if (!j.is_object() || !j.contains("total") || !j["total"].is_object()) {
    throw InputError(fmt::format(
        "{}: no object 'total'; expected the JSON of `railwear contact --json` with "
        "total.area_mm2, total.p_max_MPa, ...", path));
  }
  const nlohmann::json& t = j["total"];
  auto number = [&](const char* key) -> std::optional<double> {
    if (!t.contains(key)) return std::nullopt;
    if (!t[key].is_number() || !std::isfinite(t[key].get<double>())) {
      throw InputError(fmt::format("{}: key 'total.{}' = {}: expected a finite number", path,
                                   key, t[key].dump()));
    }
    return t[key].get<double>();
  };
  AccuracyReference ref;
  ref.source = path;
  if (const auto a = number("area_mm2")) {
    if (!(*a > 0)) {
      throw InputError(fmt::format("{}: key 'total.area_mm2' = {}: expected a positive area",
                                   path, *a));
    }
    ref.q.area_m2 = *a / kToMm2;
    ref.has_area = true;
  }
  if (const auto p = number("p_max_MPa")) {
    if (!(*p > 0)) {
      throw InputError(fmt::format(
          "{}: key 'total.p_max_MPa' = {}: expected a positive pressure", path, *p));
    }
    ref.q.p_max_Pa = *p / kToMPa;
    ref.has_p_max = true;
  }
  const auto fz = number("vertical_force_N"), fy = number("lateral_force_N");
  if (fz && fy) {
    ref.q.vertical_force_N = *fz;
    ref.q.lateral_force_N = *fy;
    ref.has_force = true;
  }
  const auto cx = number("creep_force_x_N");
  if (rolling && cx && j.contains("patches") && j["patches"].is_array()) {
    double cy = 0.0;
    bool all = true;
    for (const auto& p : j["patches"]) {
      if (p.contains("creep_force_yz_N") && p["creep_force_yz_N"].contains("y") &&
          p["creep_force_yz_N"]["y"].is_number()) {
        cy += p["creep_force_yz_N"]["y"].get<double>();
      } else {
        all = false;
      }
    }
    if (all) {
      ref.q.creep_x_N = *cx;
      ref.q.creep_y_N = cy;
      ref.has_creep = true;
    }
  }
  if (!ref.has_area && !ref.has_p_max && !ref.has_force) {
    throw InputError(fmt::format(
        "{}: 'total' holds none of area_mm2, p_max_MPa, vertical_force_N + lateral_force_N; "
        "expected at least one to compare with", path));
  }
  for (const char* k : {"area", "p_max", "force", "creep"}) ref.how.emplace_back(k, "file");
  return ref;
}

double RelErr(double value, double reference) { return std::abs(value / reference - 1.0); }

void SetErrors(const AccuracyReference& ref, AccuracyRow* row) {
  const bool ok = row->status == SolverStatus::kConverged;
  row->err_area = ok && ref.has_area ? RelErr(row->q.area_m2, ref.q.area_m2) : kNaN;
  row->err_p_max = ok && ref.has_p_max ? RelErr(row->q.p_max_Pa, ref.q.p_max_Pa) : kNaN;
  row->err_force =
      ok && ref.has_force
          ? std::hypot(row->q.lateral_force_N - ref.q.lateral_force_N,
                       row->q.vertical_force_N - ref.q.vertical_force_N) /
                std::hypot(ref.q.lateral_force_N, ref.q.vertical_force_N)
          : kNaN;
  row->err_creep = kNaN;
  if (ok && ref.has_creep && row->q.creep_x_N) {
    const double norm = std::hypot(*ref.q.creep_x_N, *ref.q.creep_y_N);
    if (norm > 0) {
      row->err_creep = std::hypot(*row->q.creep_x_N - *ref.q.creep_x_N,
                                  *row->q.creep_y_N - *ref.q.creep_y_N) /
                       norm;
    }
  }
}

// ---------------------------------------------------------------------------------------------
std::string Pct(double e) { return std::isnan(e) ? "-" : fmt::format("{:.3f}", e * kToPercent); }

std::string CsvNumber(double v, const char* format = "{:.6g}") {
  return std::isnan(v) ? std::string() : fmt::format(fmt::runtime(format), v);
}

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::optional<Richardson> ExtrapolateRichardson(double h1, double f1, double h2, double f2,
                                                double h3, double f3) {
  if (!(h1 > h2 && h2 > h3 && h3 > 0)) return std::nullopt;
  const double d1 = f1 - f2, d2 = f2 - f3;
  if (!(d1 * d2 > 0) || !(std::abs(d2) < std::abs(d1))) return std::nullopt;
  const double target = d1 / d2;
  // ratio(p) = (h1^p - h2^p) / (h2^p - h3^p) grows with p.
  auto ratio = [&](double p) {
    return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p));
  };
  // Below first order the sequence is not in its asymptotic range (the grids converge at
  // first order or better), and the extrapolation would reach far beyond the finest value.
  double lo = 1.0, hi = 6.0;
  if (!(ratio(lo) <= target && target <= ratio(hi))) return std::nullopt;
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ratio(mid) < target ? lo : hi) = mid;
  }
  const double p = 0.5 * (lo + hi);
  const double c = d2 / (std::pow(h2, p) - std::pow(h3, p));
  return Richardson{f3 - c * std::pow(h3, p), p};
}

AccuracyStudy RunAccuracyStudy(const Scene& scene, const AccuracyOptions& o,
                               const std::function<void(const std::string&)>& progress) {
  if (scene.wheelset) {
    throw InputError(fmt::format(
        "{}: the scene places a wheelset ([track], [wheelset]); expected one wheel on one rail "
        "([load]): `railwear accuracy` compares the models on one contact", scene.path));
  }
  if (o.repeats < 1) {
    throw InputError(fmt::format("--repeats {}: expected at least 1", o.repeats));
  }
  std::vector<std::string> models;
  for (const auto& m : o.models) {
    const std::string c = CanonicalModel(m);
    CheckName(c, kAccuracyModels, "--models: model");
    if (std::find(models.begin(), models.end(), c) == models.end()) models.push_back(c);
  }
  if (models.empty()) throw InputError("--models: expected at least one model");
  std::vector<std::string> levels;
  for (const auto& l : kAccuracyLevels) {  // coarse to fine, whatever order they were given in
    for (const auto& given : o.levels) CheckName(given, kAccuracyLevels, "--levels: level");
    if (std::find(o.levels.begin(), o.levels.end(), l) != o.levels.end()) levels.push_back(l);
  }
  if (levels.empty()) throw InputError("--levels: expected at least one level");
  const std::string reference_model = CanonicalModel(o.reference_model);
  CheckName(reference_model, kAccuracyModels, "--reference-model: model");

  AccuracyStudy study;
  study.scene_name = scene.name;
  study.scene_path = scene.path;
  study.rolling = scene.problem.rolling.has_value();
  // The reference is read before the runs, so a bad file fails at once.
  std::optional<AccuracyReference> file_reference;
  if (o.reference) file_reference = ReferenceFromFile(*o.reference, study.rolling);
  std::vector<std::string> runs = models;
  if (!o.reference && std::find(runs.begin(), runs.end(), reference_model) == runs.end()) {
    runs.push_back(reference_model);
    study.notes.push_back(fmt::format("{} added: it is the reference model", reference_model));
  }
  if (!o.reference && study.rolling && reference_model == "hertz") {
    throw InputError(
        "--reference-model hertz: the scene rolls, and Hertz has no grid for rolling contact; "
        "expected a grid model");
  }
  for (const auto& model : runs) {
    if (model == "hertz" && study.rolling) {
      study.notes.push_back("hertz left out: the scene rolls and Hertz has no grid for the "
                            "tangential stage");
      continue;
    }
    const std::vector<std::string> model_levels =
        model == "hertz" ? std::vector<std::string>{"analytic"} : levels;
    for (const auto& level : model_levels) {
      if (progress) progress(fmt::format("{} {} ({} solve{})", model, level, o.repeats,
                                         o.repeats == 1 ? "" : "s"));
      study.rows.push_back(RunOne(scene.problem, model, level, o.repeats));
    }
  }
  study.reference = file_reference ? *file_reference
                                   : ReferenceFromRuns(study.rows, reference_model, study.rolling);
  for (auto& row : study.rows) SetErrors(study.reference, &row);
  return study;
}

std::string FormatAccuracyTable(const AccuracyStudy& s) {
  std::string out;
  out += fmt::format("scene       {} ({})\n", s.scene_name, s.scene_path);
  out += fmt::format("reference   {}\n", s.reference.source);
  std::vector<std::string> how;
  for (const auto& [name, text] : s.reference.how) how.push_back(name + ": " + text);
  out += fmt::format("            {}\n", fmt::join(how, "; "));
  const AccuracyQuantities& r = s.reference.q;
  std::string values;
  if (s.reference.has_area) values += fmt::format("area {:.2f} mm2  ", r.area_m2 * kToMm2);
  if (s.reference.has_p_max) values += fmt::format("p_max {:.1f} MPa  ", r.p_max_Pa * kToMPa);
  if (s.reference.has_force) {
    values += fmt::format("vertical {:.1f} N  lateral {:.1f} N  ", r.vertical_force_N,
                          r.lateral_force_N);
  }
  if (s.reference.has_creep) {
    values += fmt::format("creep x {:.1f} N  creep y {:.1f} N", *r.creep_x_N, *r.creep_y_N);
  }
  out += fmt::format("            {}\n", values);
  for (const auto& n : s.notes) out += fmt::format("note        {}\n", n);
  out += "\n";
  out += fmt::format("{:<21} {:<9} {:>4} {:>9} {:>8} {:>15} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8}",
                     "model", "level", "n/b", "time_ms", "mem_MiB", "cells(contact)", "area_mm2",
                     "p_max_MPa", "lateral_N", "e_area%", "e_pmax%", "e_force%");
  out += s.rolling ? fmt::format(" {:>8}", "e_creep%") : std::string();
  out += "  patches\n";
  for (const auto& row : s.rows) {
    const std::string n = row.cells_per_semi_axis > 0 ? fmt::format("{:.0f}", row.cells_per_semi_axis) : "-";
    const std::string mem =
        std::isnan(row.memory_bytes) ? "-" : fmt::format("{:.1f}", row.memory_bytes * kToMiB);
    const std::string cells =
        row.cells > 0 ? fmt::format("{}({})", row.cells, row.cells_in_contact) : "analytic";
    out += fmt::format("{:<21} {:<9} {:>4} {:>9.2f} {:>8} {:>15} {:>9.2f} {:>9.1f} {:>9.1f} {:>8} "
                       "{:>8} {:>8}",
                       row.model, row.level, n, row.time_median_s * kToMs, mem, cells,
                       row.q.area_m2 * kToMm2, row.q.p_max_Pa * kToMPa, row.q.lateral_force_N,
                       Pct(row.err_area), Pct(row.err_p_max), Pct(row.err_force));
    if (s.rolling) out += fmt::format(" {:>8}", Pct(row.err_creep));
    out += fmt::format("  {}", row.patch_models);
    if (row.status != SolverStatus::kConverged) {
      out += fmt::format("  [{}: {}]", ToString(row.status), row.message);
    }
    out += "\n";
  }
  return out;
}

void WriteAccuracyCsv(const AccuracyStudy& s, std::ostream& out) {
  out << "model,level,cells_per_semi_axis,status,repeats,time_ms_median,time_ms_min,time_ms_max,"
         "memory_MiB,patches,cells,cells_in_contact,iterations,area_mm2,p_max_MPa,vertical_N,"
         "lateral_N,creep_x_N,creep_y_N,err_area_pct,err_p_max_pct,err_force_pct,err_creep_pct,"
         "patch_models\n";
  auto opt = [](const std::optional<double>& v) { return v ? CsvNumber(*v) : std::string(); };
  for (const auto& r : s.rows) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       CsvField(r.model), CsvField(r.level), CsvNumber(r.cells_per_semi_axis),
                       ToString(r.status), r.repeats, CsvNumber(r.time_median_s * kToMs),
                       CsvNumber(r.time_min_s * kToMs), CsvNumber(r.time_max_s * kToMs),
                       CsvNumber(r.memory_bytes * kToMiB), r.patches, r.cells,
                       r.cells_in_contact, r.iterations, CsvNumber(r.q.area_m2 * kToMm2, "{:.9g}"),
                       CsvNumber(r.q.p_max_Pa * kToMPa, "{:.9g}"),
                       CsvNumber(r.q.vertical_force_N, "{:.9g}"),
                       CsvNumber(r.q.lateral_force_N, "{:.9g}"), opt(r.q.creep_x_N),
                       opt(r.q.creep_y_N), CsvNumber(r.err_area * kToPercent),
                       CsvNumber(r.err_p_max * kToPercent), CsvNumber(r.err_force * kToPercent),
                       CsvNumber(r.err_creep * kToPercent), CsvField(r.patch_models));
  }
  const AccuracyReference& ref = s.reference;
  auto if_has = [](bool has, double v) { return has ? CsvNumber(v, "{:.9g}") : std::string(); };
  out << fmt::format("reference,{},,,,,,,,,,,,{},{},{},{},{},{},,,,,\n", CsvField(ref.source),
                     if_has(ref.has_area, ref.q.area_m2 * kToMm2),
                     if_has(ref.has_p_max, ref.q.p_max_Pa * kToMPa),
                     if_has(ref.has_force, ref.q.vertical_force_N),
                     if_has(ref.has_force, ref.q.lateral_force_N),
                     ref.has_creep ? opt(ref.q.creep_x_N) : std::string(),
                     ref.has_creep ? opt(ref.q.creep_y_N) : std::string());
}

void PlotAccuracy(const AccuracyStudy& s, const std::string& png_path) {
  RequireGnuplotFor("railwear accuracy's Pareto plot", "pass --no-plot");
  ScopedTempDir dir("railwear-accuracy");
  // One data file per model: time_ms, the errors [%] (floored for the log axis), level.
  std::vector<std::string> models;
  for (const auto& r : s.rows) {
    if (std::find(models.begin(), models.end(), r.model) == models.end()) models.push_back(r.model);
  }
  auto floored = [](double e) {
    return std::isnan(e) ? std::string("NaN")
                         : fmt::format("{:.6g}", std::max(e * kToPercent, kPlotErrorFloor_pct));
  };
  std::vector<std::string> files;
  for (size_t m = 0; m < models.size(); ++m) {
    std::string data;
    for (const auto& r : s.rows) {
      if (r.model != models[m] || r.status != SolverStatus::kConverged) continue;
      data += fmt::format("{:.6g} {} {} {} {} {}\n", r.time_median_s * kToMs, floored(r.err_area),
                          floored(r.err_p_max), floored(r.err_force), floored(r.err_creep),
                          r.level);
    }
    const fs::path file = dir.path() / fmt::format("model{}.dat", m);
    std::ofstream(file) << data;
    files.push_back(file.string());
  }
  struct Panel {
    int column;
    const char* label;
  };
  std::vector<Panel> panels = {{2, "area error [%]"}, {3, "peak pressure error [%]"},
                               {4, "total force error [%]"}};
  if (s.rolling && s.reference.has_creep) panels.push_back({5, "creep force error [%]"});
  std::ostringstream g;
  g << GnuplotPngTerminal(520 * static_cast<int>(panels.size()), 560);
  g << "set output " << GnuplotQuote(png_path) << "\n";
  g << "set multiplot layout 1," << panels.size() << " title "
    << GnuplotQuote(fmt::format("{}: error against time per solve (reference: {}; errors below "
                                "{:g} % drawn at it)",
                                s.scene_name, s.reference.source, kPlotErrorFloor_pct))
    << "\n";
  g << "set logscale xy\nset grid\nset key below\nset xlabel 'time per solve [ms]'\n";
  g << "set format y '%g'\nset format x '%g'\n";
  for (const auto& panel : panels) {
    g << "set ylabel " << GnuplotQuote(panel.label) << "\nplot ";
    for (size_t m = 0; m < models.size(); ++m) {
      const std::string f = GnuplotQuote(files[m]);
      g << (m ? ", " : "") << f << fmt::format(" using 1:{} with linespoints pt 7 lw 2 lc {} title ",
                                               panel.column, m + 1)
        << GnuplotQuote(models[m]) << ", " << f
        << fmt::format(" using 1:{}:6 with labels offset 0,0.8 font ',8' tc lt {} notitle",
                       panel.column, m + 1);
    }
    g << "\n";
  }
  g << "unset multiplot\n";
  RunGnuplot(g.str(), dir, {png_path});
}

void SetupAccuracy(CLI::App& app) {
  auto options = std::make_shared<AccuracyOptions>();
  auto no_plot = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "accuracy", "What accuracy costs in time: each model at each accuracy level, time, "
                  "memory and errors against a reference (table, CSV, Pareto plot)");
  sub->add_option("scene", options->scene_path, "Scene file (TOML), one wheel on one rail")
      ->required();
  CLI::Option* models = sub->add_option("--models", options->models,
                  "Models, comma-separated: hertz, halfspace, conformal+boussinesq, "
                  "conformal+golubenko (or conformal), auto (default: all)")
      ->delimiter(',');
  CLI::Option* levels = sub->add_option("--levels", options->levels,
                  "Accuracy levels, comma-separated: draft, standard, reference, fine "
                  "(default: all; a wear scene: draft, standard, reference)")
      ->delimiter(',');
  sub->add_option("--repeats", options->repeats, "Solves per run; the time is their median")
      ->check(CLI::PositiveNumber);
  sub->add_option("--out", options->out_dir,
                  "Write DIR/accuracy.csv and the Pareto plot DIR/accuracy.png");
  sub->add_flag("--no-plot", *no_plot, "With --out: no plot (gnuplot not needed)");
  CLI::Option* reference = sub->add_option("--reference", options->reference,
                  "Compare against this JSON (as `railwear contact --json` writes it; any of "
                  "total.area_mm2, p_max_MPa, vertical_force_N + lateral_force_N)");
  CLI::Option* reference_model = sub->add_option("--reference-model", options->reference_model,
                  "Model whose finest (extrapolated) solution is the reference "
                  "(default conformal+boussinesq)");
  sub->add_option("--step-limits", options->step_limits_mm,
                  "Wear scenes: step limits (max_depth_per_step) in mm, comma-separated "
                  "(default 0.2,0.1,0.05)")
      ->delimiter(',');
  sub->add_option("--mgt", options->total_mgt,
                  "Wear scenes: run every study to this many MGT instead of the scene's total");
  sub->add_option("--threads", options->threads, "Wear scenes: load-case workers (0: the scene's)")
      ->check(CLI::NonNegativeNumber);
  sub->callback([options, no_plot, levels, models, reference, reference_model]() {
    options->plot = !*no_plot;
    options->levels_given = levels->count() > 0;
    options->contact_options_given =
        models->count() + reference->count() + reference_model->count() > 0;
    RunAccuracy(*options);
  });
}

namespace {

fs::path CreateOutDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError(fmt::format("--out {}: cannot create the directory ({})", dir,
                                 ec ? ec.message() : "a file of that name exists"));
  }
  return fs::path(dir);
}

void RunWearAccuracy(const Scene& scene, const AccuracyOptions& o) {
  if (o.contact_options_given) {
    throw InputError(fmt::format("{}: a wear scene runs with its own [model]; --models, "
                                 "--reference and --reference-model are for contact scenes",
                                 o.scene_path));
  }
  WearAccuracyOptions w;
  if (o.levels_given) w.levels = o.levels;
  if (o.step_limits_mm) w.step_limits_mm = *o.step_limits_mm;
  w.total_mgt = o.total_mgt;
  w.threads = o.threads;
  const WearAccuracyStudy study = RunWearAccuracyStudy(
      scene, w, [](const std::string& line) { std::cerr << "railwear accuracy: " << line << "\n"; });
  std::cout << FormatWearAccuracyTable(study) << std::flush;
  if (!o.out_dir) return;
  const fs::path csv = CreateOutDir(*o.out_dir) / "wear_accuracy.csv";
  {
    std::ofstream out(csv);
    WriteWearAccuracyCsv(study, out);
    if (!out) throw InputError(fmt::format("{}: cannot write the CSV", csv.string()));
  }
  std::cerr << "railwear accuracy: wrote " << csv.string() << "\n";
  if (o.plot) {
    const fs::path png = fs::path(*o.out_dir) / "wear_accuracy.png";
    PlotWearAccuracy(study, png.string());
    std::cerr << "railwear accuracy: wrote " << png.string() << "\n";
  }
}

}  // namespace

void RunAccuracy(const AccuracyOptions& o) {
  // Before the runs, so nobody waits for nothing.
  if (o.out_dir && o.plot) RequireGnuplotFor("railwear accuracy's Pareto plot", "pass --no-plot");
  const Scene scene = LoadScene(o.scene_path);
  if (scene.wear) {
    RunWearAccuracy(scene, o);
    return;
  }
  if (o.step_limits_mm || o.total_mgt || o.threads > 0) {
    throw InputError(fmt::format("{}: --step-limits, --mgt and --threads are for wear scenes; "
                                 "this scene has no wear study", o.scene_path));
  }
  const AccuracyStudy study = RunAccuracyStudy(
      scene, o, [](const std::string& line) { std::cerr << "railwear accuracy: " << line << "\n"; });
  std::cout << FormatAccuracyTable(study) << std::flush;
  if (!o.out_dir) return;
  const fs::path csv = CreateOutDir(*o.out_dir) / "accuracy.csv";
  {
    std::ofstream out(csv);
    WriteAccuracyCsv(study, out);
    if (!out) throw InputError(fmt::format("{}: cannot write the CSV", csv.string()));
  }
  std::cerr << "railwear accuracy: wrote " << csv.string() << "\n";
  if (o.plot) {
    const fs::path png = fs::path(*o.out_dir) / "accuracy.png";
    PlotAccuracy(study, png.string());
    std::cerr << "railwear accuracy: wrote " << png.string() << "\n";
  }
}

}  // namespace railwear::app
