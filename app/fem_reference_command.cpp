// `railwear fem-reference`: config -> FEM displacement experiments -> displacement-curve CSVs,
// with a summary and comparisons on stdout and progress on stderr.
#include "app/fem_reference_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/fem_contact_result.h"
#include "app/paths.h"
#include "app/toml_fields.h"
#include "calibration/curve_comparison.h"
#include "calibration/fem/ccx_deck.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

namespace fs = std::filesystem;

constexpr double kMm = 1e-3;
constexpr double kMPa = 1e6;
constexpr double kNmPerN = 1e-9;
// Distances [mm] whose nearest curve points the comparison tables show.
constexpr double kTableDistances_mm[] = {0.5, 1.0, 2.0, 5.0, 10.0, 20.0};

const std::vector<std::string_view> kCommonKeys = {
    "mesh_size_at_load_mm", "mesh_growth", "max_element_mm", "min_distance_mm",
    "max_distance_mm",      "supports",    "material",       "loads",
    "compare_range_mm"};

std::string ReadText(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: cannot read the fem-reference config: no such file", path));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the fem-reference config", path));
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

int IntegerAtLeast(const Fields& t, std::string_view key, int lo, int fallback) {
  const std::string expected = fmt::format("an integer >= {}", lo);
  const auto v = t.Number(key, {[lo](double x) { return x >= lo && x == std::floor(x) && x < 1e6; },
                                expected});
  return v ? static_cast<int>(*v) : fallback;
}

Material ReadMaterial(const Fields& t) {
  const auto m = t.Table("material", "an inline table { E_MPa, nu }");
  m->AllowOnly({"E_MPa", "nu"});
  Material material;
  material.youngs_modulus_Pa = m->RequiredNumber("E_MPa", Positive()) * kMPa;
  material.poisson_ratio = m->RequiredNumber("nu", InRange(0.0, 0.5));
  return material;
}

std::vector<CurveLoad> ReadLoads(const Fields& t) {
  const std::string expected =
      "a non-empty array of distinct loads, of 'normal', 'axial', 'circumferential'";
  const toml::node* node = t.Node("loads");
  const toml::array* a = node->as_array();
  if (a == nullptr || a->empty()) t.Fail("loads", expected);
  std::vector<CurveLoad> loads;
  for (const toml::node& e : *a) {
    const auto name = e.value_exact<std::string>();
    const auto load = name ? CurveLoadFromString(*name) : std::nullopt;
    if (!load || std::find(loads.begin(), loads.end(), *load) != loads.end()) t.Fail("loads", expected);
    loads.push_back(*load);
  }
  return loads;
}

void ReadCompareRange(const Fields& t, FemExperiment* e) {
  const std::string expected = "two distances [from, to] in mm with 0 < from < to";
  const toml::array* a = t.Node("compare_range_mm")->as_array();
  if (a == nullptr || a->size() != 2) t.Fail("compare_range_mm", expected);
  double v[2];
  for (int i = 0; i < 2; ++i) {
    const toml::node& n = *a->get(static_cast<size_t>(i));
    const auto x = n.value<double>();  // integers convert
    if (!n.is_number() || !x || !std::isfinite(*x)) t.Fail("compare_range_mm", expected);
    v[i] = *x;
  }
  if (!(v[0] > 0.0 && v[1] > v[0])) t.Fail("compare_range_mm", expected);
  e->compare_from_m = v[0] * kMm;
  e->compare_to_m = v[1] * kMm;
}

// The keys [fem] and [[experiment]] share, applied on top of *e.
void ReadCommonKeys(const Fields& t, FemExperiment* e) {
  FemDisplacementOptions& o = e->options;
  if (auto v = t.Number("mesh_size_at_load_mm", Positive())) o.mesh_size_at_load_m = *v * kMm;
  if (auto v = t.Number("mesh_growth", OpenClosed(0.0, 2.0))) o.mesh_growth = *v;
  if (auto v = t.Number("max_element_mm", Positive())) o.max_element_m = *v * kMm;
  if (auto v = t.Number("min_distance_mm", Positive())) o.min_distance_m = *v * kMm;
  if (auto v = t.Number("max_distance_mm", Positive())) o.max_distance_m = *v * kMm;
  if (auto s = t.Choice("supports", {"bottom", "far_faces"})) {
    o.supports = *FemSupportsFromString(*s);
  }
  if (t.Has("material")) o.material = ReadMaterial(t);
  if (t.Has("loads")) o.loads = ReadLoads(t);
  if (t.Has("compare_range_mm")) ReadCompareRange(t, e);
}

// The keys of a contact experiment (kind = "contact").
const std::vector<std::string_view> kContactKeys = {
    "name",          "kind",           "case",               "scene",
    "convex_radius_mm", "groove_radius_mm", "rolling_radius_mm", "load_N",
    "material",      "length_mm",      "width_mm",           "depth_mm",
    "zone_x_mm",     "zone_s_mm",      "zone_depth_mm",      "mesh_sizes_mm",
    "mesh_growth",   "max_element_mm", "penalty_MPa_per_mm", "initial_overlap_mm",
    "spring_N_per_mm", "sectors",      "output"};

std::vector<double> ReadMeshSizes(const Fields& t) {
  const std::string expected = "a non-empty array of element sizes in mm, each > 0";
  const toml::array* a = t.Node("mesh_sizes_mm")->as_array();
  if (a == nullptr || a->empty()) t.Fail("mesh_sizes_mm", expected);
  std::vector<double> sizes;
  for (const toml::node& n : *a) {
    const auto x = n.value<double>();
    if (!n.is_number() || !x || !std::isfinite(*x) || !(*x > 0.0)) t.Fail("mesh_sizes_mm", expected);
    sizes.push_back(*x * kMm);
  }
  return sizes;
}

// A contact experiment's keys on top of the case defaults (and [fem]'s material, threads and
// timeout already in e->contact).
void ReadContactKeys(const Fields& t, FemExperiment* e) {
  const auto contact_case = t.Choice("case", {"wheel_in_groove", "rail_in_wheel_groove"});
  if (!contact_case) t.FailMissing("case", "'wheel_in_groove' or 'rail_in_wheel_groove'");
  FemContactOptions o = DefaultFemContactOptions(*FemContactCaseFromString(*contact_case));
  o.material = e->contact.material;
  o.threads_per_job = e->contact.threads_per_job;
  o.timeout_s = e->contact.timeout_s;
  o.work_dir = e->contact.work_dir;
  if (auto v = t.Number("convex_radius_mm", Positive())) o.convex_radius_m = *v * kMm;
  if (auto v = t.Number("groove_radius_mm", Positive())) o.groove_radius_m = *v * kMm;
  if (auto v = t.Number("rolling_radius_mm", Positive())) o.rolling_radius_m = *v * kMm;
  if (auto v = t.Number("load_N", Positive())) o.load_N = *v;
  if (t.Has("material")) o.material = ReadMaterial(t);
  if (auto v = t.Number("length_mm", Positive())) o.length_m = *v * kMm;
  if (auto v = t.Number("width_mm", Positive())) o.width_m = *v * kMm;
  if (auto v = t.Number("depth_mm", Positive())) o.depth_m = *v * kMm;
  if (auto v = t.Number("zone_x_mm", Positive())) o.zone_x_m = *v * kMm;
  if (auto v = t.Number("zone_s_mm", Positive())) o.zone_s_m = *v * kMm;
  if (auto v = t.Number("zone_depth_mm", Positive())) o.zone_depth_m = *v * kMm;
  if (t.Has("mesh_sizes_mm")) o.mesh_sizes_m = ReadMeshSizes(t);
  if (auto v = t.Number("mesh_growth", OpenClosed(0.0, 2.0))) o.mesh_growth = *v;
  if (auto v = t.Number("max_element_mm", Positive())) o.max_element_m = *v * kMm;
  if (auto v = t.Number("penalty_MPa_per_mm", Positive())) o.penalty_Pa_per_m = *v * kMPa / kMm;
  if (auto v = t.Number("initial_overlap_mm", AtLeast(0.0))) o.initial_overlap_m = *v * kMm;
  if (auto v = t.Number("spring_N_per_mm", Positive())) o.spring_N_per_m = *v / kMm;
  o.sectors = IntegerAtLeast(t, "sectors", 2, o.sectors);
  e->contact = o;
  e->scene = t.String("scene").value_or("");
  if (!e->scene.empty()) {
    const std::string resolved = ResolveRelativeTo(DirectoryOf(t.file()), e->scene);
    std::error_code ec;
    if (!fs::is_regular_file(resolved, ec)) {
      t.Fail("scene", fmt::format("an existing railwear scene file ({} does not exist)", resolved));
    }
    e->scene = resolved;
  }
}

bool ValidName(const std::string& name) {
  static const std::regex kName("[A-Za-z0-9_.-]+");
  return std::regex_match(name, kName);
}

// Created empty; removed when the experiment succeeds unless kept. On failure it stays, so the
// logs an error message names can be read.
class WorkFolder {
 public:
  WorkFolder(const std::string& out_dir, const std::string& name, bool keep) : keep_(keep) {
    if (keep) {
      path_ = fs::path(out_dir) / (name + ".work");
      fs::remove_all(path_);
      fs::create_directories(path_);
    } else {
      std::string pattern =
          (fs::temp_directory_path() / ("railwear-fem-" + name + "-XXXXXX")).string();
      if (mkdtemp(pattern.data()) == nullptr) {
        throw std::runtime_error("cannot create a temporary directory " + pattern);
      }
      path_ = pattern;
    }
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  ~WorkFolder() {
    if (keep_ || std::uncaught_exceptions() > 0) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  bool keep_;
};

// The point nearest (in log distance, within 15 %) to `distance_m` on one curve, or nullptr.
const ComparedPoint* Nearest(const std::vector<ComparedPoint>& points, double distance_m) {
  const ComparedPoint* best = nullptr;
  for (const ComparedPoint& p : points) {
    if (best == nullptr || std::abs(std::log(p.distance_m / distance_m)) <
                               std::abs(std::log(best->distance_m / distance_m))) {
      best = &p;
    }
  }
  if (best == nullptr || std::abs(std::log(best->distance_m / distance_m)) > std::log(1.15)) {
    return nullptr;
  }
  return best;
}

// Comparison of `curves` with `reference`: per curve the offset fitted over the compare range
// and the largest raw and offset-removed errors there, then a table at a few distances (taken
// from all points the reference covers, with the same offset).
std::string ComparisonText(const FemExperiment& e, const DisplacementCurves& curves,
                           const CurveReference& reference, const std::string& title,
                           const std::string& ref_name) {
  const double from = e.compare_from_m, to = e.compare_to_m;
  const auto in_range = CompareCurves(curves, reference, from, to);
  const auto all = CompareCurves(curves, reference, 0.0, 1e9);
  std::string out = fmt::format("  {} from {:g} to {:g} mm; offset = mean({} - {}) there:\n",
                                title, from / kMm, to / kMm, "w", ref_name);
  out += fmt::format("    {:<16} {:<5} {:>6} {:>16} {:>14} {:>22}\n", "load", "path", "points",
                     "offset_nm_per_N", "max_error_%", "max_error_no_offset_%");
  size_t skipped = 0;
  for (const CurveComparison& c : in_range) {
    out += fmt::format("    {:<16} {:<5} {:>6} {:>16.5f} {:>14.2f} {:>22.2f}\n",
                       ToString(c.load), ToString(c.path), c.points.size(),
                       c.offset_m_per_N / kNmPerN, 100.0 * c.max_raw_error,
                       100.0 * c.max_corrected_error);
    skipped += c.num_skipped;
  }
  if (skipped > 0) {
    out += fmt::format("    ({} point(s) near a zero crossing, where |{}| < {:g} % of its largest, "
                       "are left out of the errors)\n",
                       skipped, ref_name, 100.0 * kSmallReferenceFraction);
  }
  for (const CurveComparison& c : in_range) {
    const auto full = std::find_if(all.begin(), all.end(), [&](const CurveComparison& a) {
      return a.load == c.load && a.path == c.path;
    });
    out += fmt::format("    {} load, {} path:\n", ToString(c.load), ToString(c.path));
    out += fmt::format("      {:>11} {:>13} {:>13} {:>8} {:>17}\n", "distance_mm", "w_nm_per_N",
                       ref_name + "_nm_per_N", "ratio", "ratio_no_offset");
    for (double d : kTableDistances_mm) {
      const ComparedPoint* p = Nearest(full->points, d * kMm);
      if (p == nullptr) continue;
      out += fmt::format("      {:>11.3f} {:>13.6f} {:>13.6f} {:>8.4f} {:>17.4f}\n",
                         p->distance_m / kMm, p->w_m_per_N / kNmPerN,
                         p->reference_m_per_N / kNmPerN, c.RawRatio(*p), c.CorrectedRatio(*p));
    }
  }
  return out;
}

std::string SummaryText(const FemExperiment& e, const FemDisplacementResult& r, int jobs) {
  const FemDisplacementOptions& o = e.options;
  const FemDisplacementSummary& s = r.summary;
  std::string out = fmt::format("{}: {} body", e.name, ToString(o.body));
  if (o.body != CurveBody::kFlat) out += fmt::format(" R = {:g} mm", o.radius_m / kMm);
  out += fmt::format(", E = {:g} MPa, nu = {:g}\n", o.material.youngs_modulus_Pa / kMPa,
                     o.material.poisson_ratio);
  out += fmt::format("  body      {:g} x {:g} x {:g} mm (length x width x depth), supports {}\n",
                     s.body_size.length_m / kMm, s.body_size.width_m / kMm,
                     s.body_size.depth_m / kMm, ToString(o.supports));
  out += fmt::format("  mesh      {} nodes, {} C3D10 elements (quarter model; h0 {:g} mm, growth "
                     "{:g}, max {:g} mm), gmsh {:.1f} s\n",
                     s.nodes, s.elements, o.mesh_size_at_load_m / kMm, o.mesh_growth,
                     o.max_element_m / kMm, s.mesh_time_s);
  std::string solves;
  for (const auto& [load, t] : s.solve_time_s) {
    solves += fmt::format("{}{} {:.1f} s", solves.empty() ? "" : ", ", ToString(load), t);
  }
  out += fmt::format("  solves    {} (ccx, {} at a time)\n", solves, jobs);
  out += fmt::format("  points    {} written to {}\n", s.points, e.output);
  out += fmt::format("  time      {:.1f} s\n", s.wall_time_s);
  return out;
}

std::string ContactSummaryText(const FemExperiment& e, const FemContactResult& r) {
  const FemContactOptions& o = r.options;
  std::string out = fmt::format(
      "{}: contact case {}, convex R {:g} mm in groove R {:g} mm, rolling radius {:g} mm, load "
      "{:g} N, E = {:g} MPa, nu = {:g}\n",
      e.name, ToString(o.contact_case), o.convex_radius_m / kMm, o.groove_radius_m / kMm,
      o.rolling_radius_m / kMm, o.load_N, o.material.youngs_modulus_Pa / kMPa,
      o.material.poisson_ratio);
  out += fmt::format(
      "  model     quarter; bodies {:g} x {:g} x {:g} mm (length x width x depth); zone {:g} x "
      "{:g} x {:g} mm; penalty {:g} MPa/mm; C3D10, growth {:g}\n",
      o.length_m / kMm, o.width_m / kMm, o.depth_m / kMm, o.zone_x_m / kMm, o.zone_s_m / kMm,
      o.zone_depth_m / kMm, o.penalty_Pa_per_m / kMPa * kMm, o.mesh_growth);
  out += fmt::format("  {:>6} {:>7} {:>6} {:>7} {:>8} {:>5} {:>9} {:>10} {:>8} {:>8} {:>9} {:>8} "
                     "{:>10}  {}\n",
                     "h_mm", "nodes", "faces", "mesh_s", "solve_s", "iter", "area_mm2",
                     "p_max_MPa", "a_x_mm", "b_s_mm", "force_N", "force_%", "area_nd_mm2",
                     "status");
  for (const FemContactLevel& L : r.levels) {
    const FemContactPatch& p = L.patch;
    out += fmt::format(
        "  {:>6.3f} {:>7} {:>6} {:>7.1f} {:>8.1f} {:>5} {:>9.3f} {:>10.2f} {:>8.3f} {:>8.3f} "
        "{:>9.1f} {:>8.2f} {:>10.3f}  {}\n",
        L.mesh_size_m / kMm, L.nodes, L.slave_faces, L.mesh_time_s, L.solve_time_s, L.iterations,
        p.area_m2 / (kMm * kMm), p.p_max_Pa / kMPa, p.half_length_x_m / kMm,
        p.half_width_s_m / kMm, p.vertical_force_N, 100.0 * (p.vertical_force_N / o.load_N - 1.0),
        p.area_nodes_m2 / (kMm * kMm), ToString(p.status));
    if (!p.message.empty()) out += "         " + p.message + "\n";
  }
  out += fmt::format("  result    written to {}\n  time      {:.1f} s\n", e.output, r.wall_time_s);
  return out;
}

}  // namespace

FemReferenceConfig ReadFemReferenceConfig(const std::string& path, const std::string& out_dir) {
  const std::string text = ReadText(path);
  const toml::table root = ParseToml(text, path);
  const Fields top(root, "", path);
  top.AllowOnly({"fem", "experiment"});

  FemExperiment defaults;
  defaults.options.work_dir = DirectoryOf(path);  // exists; replaced when an experiment runs
  if (const auto fem = top.Table("fem", "a [fem] table")) {
    std::vector<std::string_view> allowed = kCommonKeys;
    allowed.insert(allowed.end(), {"jobs", "threads_per_job", "timeout_s"});
    fem->AllowOnly(allowed);
    ReadCommonKeys(*fem, &defaults);
    defaults.options.jobs = IntegerAtLeast(*fem, "jobs", 1, defaults.options.jobs);
    defaults.options.threads_per_job =
        IntegerAtLeast(*fem, "threads_per_job", 1, defaults.options.threads_per_job);
    defaults.options.timeout_s = fem->Number("timeout_s", AtLeast(0.0)).value_or(3600.0);
  }

  const toml::node* node = top.Node("experiment");
  if (node == nullptr || !node->is_array_of_tables()) {
    if (node != nullptr) top.Fail("experiment", "[[experiment]] tables, one per FEM experiment");
    top.FailMissing("experiment", "at least one [[experiment]] table");
  }
  FemReferenceConfig config;
  config.path = path;
  const std::string base = out_dir.empty() ? DirectoryOf(path) : out_dir;
  std::map<std::string, std::string> outputs;  // output path -> experiment
  // Each output file is written by one experiment.
  auto claim_output = [&outputs](const Fields& t, const FemExperiment& e) {
    if (const auto it = outputs.find(e.output); it != outputs.end()) {
      t.Fail("output", fmt::format("a file no other experiment writes ('{}' writes it)", it->second));
    }
    outputs[e.output] = e.name;
  };
  int index = 0;
  for (const toml::node& entry : *node->as_array()) {
    const Fields t(*entry.as_table(), fmt::format("experiment[{}]", index++), path);
    const auto kind = t.Choice("kind", {"displacement", "contact"});
    const bool contact = kind && *kind == "contact";
    std::vector<std::string_view> allowed = contact ? kContactKeys : kCommonKeys;
    if (!contact) {
      allowed.insert(allowed.end(), {"name", "kind", "body", "radius_mm", "length_mm", "width_mm",
                                     "depth_mm", "output", "compare_with"});
    }
    t.AllowOnly(allowed);
    FemExperiment e = defaults;
    if (contact) {
      e.kind = FemExperimentKind::kContact;
      e.contact.material = defaults.options.material;
      e.contact.threads_per_job = defaults.options.threads_per_job;
      e.contact.timeout_s = defaults.options.timeout_s;
      e.contact.work_dir = defaults.options.work_dir;
    }
    e.line = t.Line();
    e.name = t.RequiredString("name", "a name of letters, digits, '_', '-' and '.'");
    if (!ValidName(e.name)) t.Fail("name", "a name of letters, digits, '_', '-' and '.'");
    for (const FemExperiment& other : config.experiments) {
      if (other.name == e.name) {
        t.Fail("name", fmt::format("a name not used before (line {} has it)", other.line));
      }
    }
    if (e.kind == FemExperimentKind::kContact) {
      ReadContactKeys(t, &e);
      e.output = ResolveRelativeTo(base, t.String("output").value_or(e.name + ".toml"));
      claim_output(t, e);
      std::string error;
      if (!e.contact.IsValid(&error)) {
        throw InputError(fmt::format("{}:{}: experiment '{}': {}", path, e.line, e.name, error));
      }
      config.experiments.push_back(std::move(e));
      continue;
    }
    const auto body = t.Choice("body", {"flat", "convex", "concave"});
    if (!body) t.FailMissing("body", "one of 'flat', 'convex', 'concave'");
    FemDisplacementOptions& o = e.options;
    o.body = *CurveBodyFromString(*body);
    if (o.body == CurveBody::kFlat) {
      if (t.Has("radius_mm")) t.Fail("radius_mm", "no radius for a flat body (drop this key)");
    } else {
      o.radius_m = t.RequiredNumber("radius_mm", Positive()) * kMm;
    }
    if (o.body == CurveBody::kConvex && t.Has("width_mm")) {
      t.Fail("width_mm", "no width for a convex body (it is 2R wide; drop this key)");
    }
    o.length_m = t.Number("length_mm", Positive()).value_or(0.0) * kMm;
    o.width_m = t.Number("width_mm", Positive()).value_or(0.0) * kMm;
    o.depth_m = t.Number("depth_mm", Positive()).value_or(0.0) * kMm;
    ReadCommonKeys(t, &e);
    e.output = ResolveRelativeTo(base, t.String("output").value_or(e.name + ".csv"));
    claim_output(t, e);
    e.compare_with = t.String("compare_with").value_or("");
    std::string error;
    if (!o.IsValid(&error)) {
      throw InputError(fmt::format("{}:{}: experiment '{}': {}", path, e.line, e.name, error));
    }
    config.experiments.push_back(std::move(e));
  }
  // compare_with names an earlier experiment of the file (run before it, or read from its file).
  index = 0;
  for (const toml::node& entry : *node->as_array()) {
    const Fields t(*entry.as_table(), fmt::format("experiment[{}]", index), path);
    const FemExperiment& e = config.experiments[static_cast<size_t>(index++)];
    if (e.compare_with.empty()) continue;
    std::vector<std::string_view> names;
    for (const FemExperiment& other : config.experiments) {
      if (other.name == e.name) break;
      if (other.kind == FemExperimentKind::kDisplacement) names.push_back(other.name);
    }
    if (std::find(names.begin(), names.end(), e.compare_with) == names.end()) {
      // Contact experiments have no curves to compare with: only displacement ones are named.
      t.Fail("compare_with", names.empty() ? std::string("the name of an earlier experiment of "
                                                         "this file (there is none)")
                                           : "the name of an earlier experiment of this file: " +
                                                 JoinQuoted(names));
    }
  }
  return config;
}

void SetupFemReference(CLI::App& app) {
  auto options = std::make_shared<FemReferenceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fem-reference",
      "Build FEM reference data with gmsh + CalculiX: the seed paper's displacement experiment "
      "(displacement-curve CSVs) and conformal contact cases (contact result TOML files) that "
      "calibration reads");
  cmd->add_option("config", options->config, "Experiment config (TOML)")->required();
  cmd->add_option("--out-dir", options->out_dir,
                  "Write the CSVs here (created) instead of next to the config");
  cmd->add_flag("--keep-work", options->keep_work,
                "Keep each experiment's .geo, .msh, .inp, .frd and logs in OUT/NAME.work");
  cmd->add_option("--only", options->only, "Run only this experiment (repeatable)");
  cmd->add_option("--jobs", options->jobs, "ccx solves at once (default: [fem] jobs, else 2)")
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--report-only", options->report_only,
                "Run nothing: print the comparisons of the CSVs an earlier run wrote");
  cmd->callback([options]() { RunFemReference(*options); });
}

namespace {

// The curves of an experiment that is not run now: its output file, which must exist.
DisplacementCurves ReadOutput(const FemReferenceConfig& config, const FemExperiment& e,
                              const std::string& why) {
  std::error_code ec;
  if (!fs::exists(e.output, ec)) {
    throw InputError(fmt::format("{}:{}: experiment '{}': {} its output {}, which does not exist; "
                                 "run that experiment first",
                                 config.path, e.line, e.name, why, e.output));
  }
  return ReadDisplacementCurves(e.output);
}

// The comparisons of one experiment's curves: with the half-space (for a flat body the
// validation, for a curved one how far curvature and size take it from flat), and with the
// compare_with experiment (from `done`, or read from its file).
std::string ComparisonsText(const FemReferenceConfig& config, const FemExperiment& e,
                            const DisplacementCurves& curves,
                            std::map<std::string, DisplacementCurves>* done) {
  std::string text = ComparisonText(e, curves, HalfSpaceReference(e.options.material),
                                    "half-space (Boussinesq normal, Cerruti tangential)",
                                    "halfspace");
  if (e.compare_with.empty()) return text;
  if (done->count(e.compare_with) == 0) {
    const auto other = std::find_if(config.experiments.begin(), config.experiments.end(),
                                    [&](const FemExperiment& x) { return x.name == e.compare_with; });
    (*done)[e.compare_with] = ReadOutput(config, *other, "compare_with reads");
  }
  return text + ComparisonText(e, curves, CurvesReference(done->at(e.compare_with)),
                               fmt::format("against '{}'", e.compare_with), "other");
}

}  // namespace

void RunFemReference(const FemReferenceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!options.out_dir.empty()) fs::create_directories(options.out_dir);
  FemReferenceConfig config = ReadFemReferenceConfig(options.config, options.out_dir);
  for (const std::string& name : options.only) {
    const bool known = std::any_of(config.experiments.begin(), config.experiments.end(),
                                   [&](const FemExperiment& e) { return e.name == name; });
    if (!known) {
      std::vector<std::string_view> names;
      for (const FemExperiment& e : config.experiments) names.push_back(e.name);
      throw InputError(fmt::format("--only {}: no such experiment in {}; expected one of {}", name,
                                   options.config, JoinQuoted(names)));
    }
  }
  auto selected = [&](const FemExperiment& e) {
    return options.only.empty() ||
           std::find(options.only.begin(), options.only.end(), e.name) != options.only.end();
  };
  std::map<std::string, DisplacementCurves> done;
  if (options.report_only) {  // the tables of an earlier run, from its files
    for (const FemExperiment& e : config.experiments) {
      if (!selected(e)) continue;
      if (e.kind == FemExperimentKind::kContact) {
        const FemContactTarget t = ReadFemContactTarget(e.output);
        std::cout << fmt::format(
            "{}: area {:.2f} mm2, p_max {:.1f} MPa, half-length x {:.3f} mm, half-width s {:.3f} "
            "mm, pressure resultant {:.1f} N of {:g} N ({} mesh levels), read from {}\n",
            e.name, t.area_mm2, t.p_max_MPa, t.half_length_x_mm, t.half_width_s_mm,
            t.total_force_N, t.load_N, t.levels, e.output);
        continue;
      }
      const DisplacementCurves curves = ReadOutput(config, e, "--report-only reads");
      std::cout << fmt::format("{}: {} points read from {}\n", e.name, curves.points.size(),
                               e.output)
                << ComparisonsText(config, e, curves, &done) << std::flush;
      done[e.name] = curves;
    }
    return;
  }
  FemPrograms programs;
  {
    ScopedTempDir probe("railwear-fem-probe");
    programs = FindFemPrograms(probe.path().string());
  }
  std::cerr << fmt::format("fem-reference: gmsh {} ({}), CalculiX {} ({})\n",
                           programs.gmsh_version, programs.gmsh, programs.ccx_version,
                           programs.ccx);
  const std::string out_dir =
      options.out_dir.empty() ? DirectoryOf(options.config) : options.out_dir;
  int run = 0;
  for (FemExperiment& e : config.experiments) {
    if (!selected(e)) continue;
    if (options.jobs > 0) e.options.jobs = options.jobs;
    WorkFolder work(out_dir, e.name, options.keep_work);
    e.options.work_dir = work.path().string();
    const std::string name = e.name;
    e.options.progress = [name](std::string_view message) {
      std::cerr << fmt::format("fem-reference: {}: {}\n", name, message);
    };
    if (e.kind == FemExperimentKind::kContact) {
      e.contact.work_dir = work.path().string();
      e.contact.progress = e.options.progress;
      const FemContactResult r = RunFemContact(e.contact, programs);
      const fs::path folder = fs::absolute(e.output).parent_path();
      const std::string scene =
          e.scene.empty()
              ? ""
              : fs::absolute(e.scene).lexically_normal().lexically_relative(folder).string();
      fs::create_directories(folder);
      WriteTextFile(
          e.output,
          FemContactResultText(
              e.name, r, scene,
              {{"generated_by", fmt::format("railwear {} fem-reference {}, experiment {}",
                                            RAILWEAR_VERSION, options.config, e.name)},
               {"gmsh_version", programs.gmsh_version},
               {"ccx_version", programs.ccx_version}}));
      std::cout << ContactSummaryText(e, r) << std::flush;
      ++run;
      continue;
    }
    FemDisplacementResult r = RunFemDisplacement(e.options, programs);
    r.curves.metadata.insert(
        r.curves.metadata.begin(),
        {"generated_by", fmt::format("railwear {} fem-reference {}, experiment {}",
                                     RAILWEAR_VERSION, options.config, e.name)});
    const fs::path parent = fs::path(e.output).parent_path();
    if (!parent.empty()) fs::create_directories(parent);
    WriteDisplacementCurves(r.curves, e.output);
    const int jobs = std::min(e.options.jobs, static_cast<int>(e.options.loads.size()));
    std::cout << SummaryText(e, r, jobs) << ComparisonsText(config, e, r.curves, &done)
              << std::flush;
    done[e.name] = r.curves;
    ++run;
  }
  std::cout << fmt::format("fem-reference: {} experiment(s) in {:.1f} s\n", run,
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                               .count());
}

}  // namespace railwear::app
