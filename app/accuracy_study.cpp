// `railwear accuracy` on a contact scene: the runs (time, memory), the reference (from the
// reference model's runs or a `contact --json` file) and the errors against it.
#include "app/accuracy_study.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "app/contact_output.h"
#include "core/contact/grid_resolution.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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
                   TangentialMethod tangential, int repeats) {
  ContactProblem p = base;
  p.model = AccuracyModelOptions(model, base.model);
  p.tangential = tangential;
  AccuracyRow row;
  row.model = model;
  row.level = level;
  if (base.rolling) row.tangential = std::string(ToString(tangential));
  // Hertz is analytic, except in a rolling scene: there it is the fast tread path, whose
  // tangential solution runs on a grid over Hertz's ellipse at the level's cells per semi-axis
  // (core/contact/hertz_tread.h), and whose fallback solves at that level.
  if (model != "hertz" || base.rolling) {
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
  row.memory_bytes =
      std::any_of(memory.begin(), memory.end(), [](double m) { return std::isnan(m); })
          ? kNaN
          : Median(memory);
  row.status = r.status;
  row.message = r.message;
  row.iterations = r.iterations;
  row.patches = static_cast<int>(r.patches.size());
  std::vector<std::string> labels, solvers;
  for (const auto& patch : r.patches) {
    row.cells += patch.cells;
    row.cells_in_contact += patch.cells_in_contact;
    labels.push_back(patch.model);
    if (patch.rolling) solvers.emplace_back(ToString(patch.rolling->choice.method));
  }
  row.patch_models = fmt::format("{}", fmt::join(labels, ";"));
  row.tangential_choices = fmt::format("{}", fmt::join(solvers, ";"));
  row.q = QuantitiesOf(r);
  return row;
}

// ---------------------------------------------------------------------------------------------
// The reference from the reference model's runs.
// `tangential`: the rows of that tangential method only ("" for a scene that does not roll).
AccuracyReference ReferenceFromRuns(const std::vector<AccuracyRow>& rows, const std::string& model,
                                    const std::string& tangential, bool rolling) {
  std::vector<const AccuracyRow*> runs;
  for (const auto& r : rows) {
    if (r.model == model && r.tangential == tangential && r.status == SolverStatus::kConverged) {
      runs.push_back(&r);
    }
  }
  if (runs.empty()) {
    throw std::runtime_error(
        fmt::format("the reference model {} converged at no level; no errors can be given", model));
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
      const auto e =
          ExtrapolateRichardson(1.0 / a.cells_per_semi_axis, get(a), 1.0 / b.cells_per_semi_axis,
                                get(b), 1.0 / c.cells_per_semi_axis, get(c));
      if (e) {
        ref.how.emplace_back(name, fmt::format("extrapolated, order {:.2f}", e->order));
        return e->value;
      }
      const double scale = std::max({std::abs(get(a)), std::abs(get(b)), std::abs(get(c))});
      const bool settled =
          std::abs(get(a) - get(b)) <= 1e-9 * scale && std::abs(get(b) - get(c)) <= 1e-9 * scale;
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
  ref.source = tangential.empty() ? fmt::format("{} at {}", model, fmt::join(levels, ", "))
                                  : fmt::format("{} ({} tangential) at {}", model, tangential,
                                                fmt::join(levels, ", "));
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
    throw InputError(
        fmt::format("{}: not JSON ({}); expected the JSON of `railwear contact "
                    "--json`",
                    path, e.what()));
  }
  if (!j.is_object() || !j.contains(contact_json::kTotal) || !j[contact_json::kTotal].is_object()) {
    throw InputError(
        fmt::format("{}: no object 'total'; expected the JSON of `railwear contact --json` with "
                    "total.area_mm2, total.p_max_MPa, ...",
                    path));
  }
  const nlohmann::json& t = j[contact_json::kTotal];
  auto number = [&](const char* key) -> std::optional<double> {
    if (!t.contains(key)) return std::nullopt;
    if (!t[key].is_number() || !std::isfinite(t[key].get<double>())) {
      throw InputError(fmt::format("{}: key 'total.{}' = {}: expected a finite number", path, key,
                                   t[key].dump()));
    }
    return t[key].get<double>();
  };
  AccuracyReference ref;
  ref.source = path;
  if (const auto a = number(contact_json::kAreaMm2)) {
    if (!(*a > 0)) {
      throw InputError(
          fmt::format("{}: key 'total.area_mm2' = {}: expected a positive area", path, *a));
    }
    ref.q.area_m2 = *a / kToMm2;
    ref.has_area = true;
  }
  if (const auto p = number(contact_json::kPMaxMPa)) {
    if (!(*p > 0)) {
      throw InputError(
          fmt::format("{}: key 'total.p_max_MPa' = {}: expected a positive pressure", path, *p));
    }
    ref.q.p_max_Pa = *p / kToMPa;
    ref.has_p_max = true;
  }
  const auto fz = number(contact_json::kVerticalForceN), fy = number(contact_json::kLateralForceN);
  if (fz && fy) {
    ref.q.vertical_force_N = *fz;
    ref.q.lateral_force_N = *fy;
    ref.has_force = true;
  }
  const auto cx = number(contact_json::kCreepForceXN);
  if (rolling && cx && j.contains(contact_json::kPatches) && j[contact_json::kPatches].is_array()) {
    double cy = 0.0;
    bool all = true;
    for (const auto& p : j[contact_json::kPatches]) {
      const char* yz = contact_json::kCreepForceYzN;
      if (p.contains(yz) && p[yz].contains("y") && p[yz]["y"].is_number()) {
        cy += p[yz]["y"].get<double>();
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
        "expected at least one to compare with",
        path));
  }
  for (const char* k : {"area", "p_max", "force", "creep"}) ref.how.emplace_back(k, "file");
  return ref;
}

double RelErr(double value, double reference) { return std::abs(value / reference - 1.0); }

void SetErrors(const AccuracyReference& ref, AccuracyRow* row) {
  const bool ok = row->status == SolverStatus::kConverged;
  row->err_area = ok && ref.has_area ? RelErr(row->q.area_m2, ref.q.area_m2) : kNaN;
  row->err_p_max = ok && ref.has_p_max ? RelErr(row->q.p_max_Pa, ref.q.p_max_Pa) : kNaN;
  row->err_force = ok && ref.has_force
                       ? std::hypot(row->q.lateral_force_N - ref.q.lateral_force_N,
                                    row->q.vertical_force_N - ref.q.vertical_force_N) /
                             std::hypot(ref.q.lateral_force_N, ref.q.vertical_force_N)
                       : kNaN;
  row->err_creep = kNaN;
  if (ok && ref.has_creep && row->q.creep_x_N) {
    const double norm = std::hypot(*ref.q.creep_x_N, *ref.q.creep_y_N);
    if (norm > 0) {
      row->err_creep =
          std::hypot(*row->q.creep_x_N - *ref.q.creep_x_N, *row->q.creep_y_N - *ref.q.creep_y_N) /
          norm;
    }
  }
}

// The creep-force error of each row against the exact solver's row of the same model and level
// (only when the study compares tangential methods and ran the exact one).
void SetErrorsAgainstExact(std::vector<AccuracyRow>* rows) {
  const std::string exact(ToString(TangentialMethod::kExact));
  for (auto& row : *rows) {
    row.err_creep_vs_exact = kNaN;
    if (row.status != SolverStatus::kConverged || !row.q.creep_x_N) continue;
    for (const auto& e : *rows) {
      if (e.model != row.model || e.level != row.level || e.tangential != exact) continue;
      if (e.status != SolverStatus::kConverged || !e.q.creep_x_N) break;
      const double norm = std::hypot(*e.q.creep_x_N, *e.q.creep_y_N);
      if (norm > 0) {
        row.err_creep_vs_exact =
            std::hypot(*row.q.creep_x_N - *e.q.creep_x_N, *row.q.creep_y_N - *e.q.creep_y_N) /
            norm;
      }
      break;
    }
  }
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
        "([load]): `railwear accuracy` compares the models on one contact",
        scene.path));
  }
  const AccuracyPlan plan = MakeAccuracyPlan(o);
  const std::vector<std::string>& levels = plan.levels;
  const std::string& reference_model = plan.reference_model;

  AccuracyStudy study;
  study.scene_name = scene.name;
  study.scene_path = scene.path;
  study.rolling = scene.problem.rolling.has_value();
  if (!plan.tangential.empty() && !study.rolling) {
    throw InputError(fmt::format(
        "{}: --tangential: the scene does not roll; expected a scene with the \"tangential\" "
        "effect (rolling contact) to compare tangential methods on",
        scene.path));
  }
  const std::vector<TangentialMethod> methods =
      plan.tangential.empty() ? std::vector<TangentialMethod>{scene.problem.tangential}
                              : plan.tangential;
  study.compare_tangential = study.rolling && methods.size() > 1;
  // The creep forces' reference: the exact solver's when it runs, else the first method's.
  const TangentialMethod reference_tangential =
      std::find(methods.begin(), methods.end(), TangentialMethod::kExact) != methods.end()
          ? TangentialMethod::kExact
          : methods.front();
  // The reference is read before the runs, so a bad file fails at once.
  std::optional<AccuracyReference> file_reference;
  if (o.reference) file_reference = ReferenceFromFile(*o.reference, study.rolling);
  std::vector<std::string> runs = plan.models;
  if (!o.reference && std::find(runs.begin(), runs.end(), reference_model) == runs.end()) {
    runs.push_back(reference_model);
    study.notes.push_back(fmt::format("{} added: it is the reference model", reference_model));
  }
  if (!o.reference && study.rolling && reference_model == "hertz") {
    throw InputError(
        "--reference-model hertz: the scene rolls, and Hertz with rolling is the fast tread "
        "path, an approximation checked against the grids (not a reference); expected a grid "
        "model");
  }
  for (const auto& model : runs) {
    if (model == "hertz" && study.rolling) {
      study.notes.push_back(
          "hertz: the scene rolls, so hertz is the fast tread path (Hertz's ellipse, the "
          "tangential solution on a grid of the level's cells per semi-axis over it; "
          "docs/library.md); where it does not apply its rows are kind auto's fallback at that "
          "level, and their patches name the grid model instead of hertz");
    }
    const std::vector<std::string> model_levels =
        model == "hertz" && !study.rolling ? std::vector<std::string>{"analytic"} : levels;
    for (const auto& level : model_levels) {
      for (const TangentialMethod method : methods) {
        if (progress) {
          progress(fmt::format("{} {}{} ({} solve{})", model, level,
                               study.compare_tangential
                                   ? fmt::format(" {} tangential", ToString(method))
                                   : std::string(),
                               o.repeats, o.repeats == 1 ? "" : "s"));
        }
        study.rows.push_back(RunOne(scene.problem, model, level, method, o.repeats));
      }
    }
  }
  const std::string ref_tangential =
      study.rolling ? std::string(ToString(reference_tangential)) : std::string();
  study.reference = file_reference ? *file_reference
                                   : ReferenceFromRuns(study.rows, reference_model,
                                                       ref_tangential, study.rolling);
  if (study.compare_tangential && !file_reference) {
    // Only the reference method's rows were used; say so.
    study.reference.source += "; other tangential methods' rows are compared with it";
  }
  for (auto& row : study.rows) SetErrors(study.reference, &row);
  for (auto& row : study.rows) row.err_creep_vs_exact = kNaN;
  if (study.compare_tangential &&
      std::find(methods.begin(), methods.end(), TangentialMethod::kExact) != methods.end()) {
    SetErrorsAgainstExact(&study.rows);
  }
  return study;
}

}  // namespace railwear::app
