// `railwear fem-reference`'s config: TOML -> FemReferenceConfig. See fem_reference_config.h.
#include "app/fem_reference_config.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <regex>

#include <fmt/format.h>

#include "app/paths.h"
#include "app/toml_fields.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace {

namespace fs = std::filesystem;

constexpr double kMPa = 1e6;

// The finite ranges the mesher and the solver bear (issue 17; docs/testing.md's table): element
// sizes from 5 um (a twentieth of the default h0, 0.1 mm) to 1 m, body sizes from 1 mm and
// radii from 0.1 mm to 10 m, distances from 1 um, loads to 1e7 N. Finer meshes inside these are
// caught by the node estimate below.
NumberRule ElementSizeRange() { return Closed(0.005, 1000.0); }  // [mm]
NumberRule BodySizeRange() { return Closed(1.0, 10000.0); }      // [mm]
NumberRule RadiusRange() { return Closed(0.1, 10000.0); }        // [mm]
NumberRule DistanceRange() { return Closed(0.001, 10000.0); }    // [mm]

// A mesh estimated larger than this many nodes is refused before gmsh runs (issue 17): the
// finest documented mesh, 96,209 nodes, took 2.9 GB and 5-8 min per ccx solve
// (docs/fem_reference.md), so 500,000 would take at least 15 GB (memory grows faster than the
// node count with a direct solver) and hours.
constexpr double kMaxFemNodes = 5e5;

const std::vector<std::string_view> kCommonKeys = {
    "mesh_size_at_load_mm", "mesh_growth", "max_element_mm", "min_distance_mm",
    "max_distance_mm",      "supports",    "material",       "loads",
    "compare_range_mm"};

std::string ReadConfigText(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: cannot read the fem-reference config: no such file", path));
  }
  return ReadInputFile(path, "the fem-reference config");
}

void ReadCompareRange(const Fields& t, FemExperiment* e) {
  const std::string expected = "two distances [from, to] in mm with 0 < from < to";
  const std::array<double, 2> v = *t.NumberPair("compare_range_mm", expected);
  if (!(v[0] > 0.0 && v[1] > v[0])) t.Fail("compare_range_mm", expected);
  e->compare_from_m = v[0] * kMm;
  e->compare_to_m = v[1] * kMm;
}

// The keys [fem] and [[experiment]] share, applied on top of *e.
void ReadCommonKeys(const Fields& t, FemExperiment* e) {
  FemDisplacementOptions& o = e->options;
  if (auto v = t.Number("mesh_size_at_load_mm", Positive(), ElementSizeRange())) {
    o.mesh_size_at_load_m = *v * kMm;
  }
  if (auto v = t.Number("mesh_growth", OpenClosed(0.0, 2.0))) o.mesh_growth = *v;
  if (auto v = t.Number("max_element_mm", Positive(), ElementSizeRange())) {
    o.max_element_m = *v * kMm;
  }
  if (auto v = t.Number("min_distance_mm", Positive(), DistanceRange())) {
    o.min_distance_m = *v * kMm;
  }
  if (auto v = t.Number("max_distance_mm", Positive(), DistanceRange())) {
    o.max_distance_m = *v * kMm;
  }
  if (auto s = t.Choice("supports", {"bottom", "far_faces"})) {
    o.supports = *FemSupportsFromString(*s);
  }
  if (t.Has("material")) o.material = ReadMaterial(t, "material", MaterialKeys::kElastic);
  if (t.Has("loads")) {
    o.loads = EnumArray<CurveLoad>(
        t, "loads", CurveLoadFromString,
        "a non-empty array of distinct loads, of 'normal', 'axial', 'circumferential'");
  }
  if (t.Has("compare_range_mm")) ReadCompareRange(t, e);
}

// The keys of a contact experiment (kind = "contact").
const std::vector<std::string_view> kContactKeys = {"name",
                                                    "kind",
                                                    "case",
                                                    "scene",
                                                    "convex_radius_mm",
                                                    "groove_radius_mm",
                                                    "rolling_radius_mm",
                                                    "load_N",
                                                    "material",
                                                    "length_mm",
                                                    "width_mm",
                                                    "depth_mm",
                                                    "zone_x_mm",
                                                    "zone_s_mm",
                                                    "zone_depth_mm",
                                                    "mesh_sizes_mm",
                                                    "mesh_growth",
                                                    "max_element_mm",
                                                    "penalty_MPa_per_mm",
                                                    "initial_overlap_mm",
                                                    "spring_N_per_mm",
                                                    "sectors",
                                                    "output"};

std::vector<double> ReadMeshSizes(const Fields& t) {
  const std::string expected =
      "a non-empty array of element sizes in mm, each in [0.005, 1000] (the range the numerics "
      "bear)";
  const toml::array* a = t.Node("mesh_sizes_mm")->as_array();
  if (a == nullptr || a->empty()) t.Fail("mesh_sizes_mm", expected);
  std::vector<double> sizes;
  for (const toml::node& n : *a) {
    const auto x = n.value<double>();
    if (!n.is_number() || !x || !std::isfinite(*x) || !(*x >= 0.005 && *x <= 1000.0))
      t.Fail("mesh_sizes_mm", expected);
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
  const auto mm = [&](std::string_view key, const NumberRule& range, double* out) {
    if (auto v = t.Number(key, Positive(), range)) *out = *v * kMm;
  };
  mm("convex_radius_mm", RadiusRange(), &o.convex_radius_m);
  mm("groove_radius_mm", RadiusRange(), &o.groove_radius_m);
  mm("rolling_radius_mm", Closed(10.0, 10000.0), &o.rolling_radius_m);
  if (auto v = t.Number("load_N", Positive(), Closed(1.0, 1e7))) o.load_N = *v;
  if (t.Has("material")) o.material = ReadMaterial(t, "material", MaterialKeys::kElastic);
  mm("length_mm", BodySizeRange(), &o.length_m);
  mm("width_mm", BodySizeRange(), &o.width_m);
  mm("depth_mm", BodySizeRange(), &o.depth_m);
  mm("zone_x_mm", DistanceRange(), &o.zone_x_m);
  mm("zone_s_mm", DistanceRange(), &o.zone_s_m);
  mm("zone_depth_mm", DistanceRange(), &o.zone_depth_m);
  if (t.Has("mesh_sizes_mm")) o.mesh_sizes_m = ReadMeshSizes(t);
  if (auto v = t.Number("mesh_growth", OpenClosed(0.0, 2.0))) o.mesh_growth = *v;
  mm("max_element_mm", ElementSizeRange(), &o.max_element_m);
  if (auto v = t.Number("penalty_MPa_per_mm", Positive(), Closed(1.0, 1e12))) {
    o.penalty_Pa_per_m = *v * kMPa / kMm;
  }
  if (auto v = t.Number("initial_overlap_mm", AtLeast(0.0), Closed(0.0, 10.0))) {
    o.initial_overlap_m = *v * kMm;
  }
  if (auto v = t.Number("spring_N_per_mm", Positive(), Closed(1e-6, 1e12))) {
    o.spring_N_per_m = *v / kMm;
  }
  o.sectors = t.Integer("sectors", IntegerAtLeast(2), IntegerInRange(2, 360)).value_or(o.sectors);
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

}  // namespace

FemReferenceConfig ReadFemReferenceConfig(const std::string& path, const std::string& out_dir) {
  const std::string text = ReadConfigText(path);
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
    defaults.options.jobs = fem->Integer("jobs", IntegerAtLeast(1), IntegerInRange(1, 256))
                                .value_or(defaults.options.jobs);
    defaults.options.threads_per_job =
        fem->Integer("threads_per_job", IntegerAtLeast(1), IntegerInRange(1, 256))
            .value_or(defaults.options.threads_per_job);
    defaults.options.timeout_s =
        fem->Number("timeout_s", AtLeast(0.0), Closed(0.0, 1e7)).value_or(3600.0);
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
      t.Fail("output",
             fmt::format("a file no other experiment writes ('{}' writes it)", it->second));
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
      const FemContactOptions resolved = ResolvedFemContactOptions(e.contact);
      for (const double h : resolved.mesh_sizes_m) {
        const double nodes = EstimateFemContactNodes(resolved, h);
        if (nodes > kMaxFemNodes) {
          throw InputError(fmt::format(
              "{}:{}: experiment '{}': the mesh level of {:g} mm would have about {:.3g} nodes "
              "(estimated before meshing from mesh_sizes_mm, mesh_growth = {:g}, max_element_mm "
              "= {:g}, the body and the zone; gmsh's counts are within 15 % of it), more than "
              "{:g} (at least 15 GB and hours per CalculiX solve); expected a coarser mesh: "
              "larger mesh_sizes_mm or mesh_growth",
              path, e.line, e.name, h / kMm, nodes, resolved.mesh_growth,
              resolved.max_element_m / kMm, kMaxFemNodes));
        }
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
      o.radius_m = t.RequiredNumber("radius_mm", Positive(), RadiusRange()) * kMm;
    }
    if (o.body == CurveBody::kConvex && t.Has("width_mm")) {
      t.Fail("width_mm", "no width for a convex body (it is 2R wide; drop this key)");
    }
    o.length_m = t.Number("length_mm", Positive(), BodySizeRange()).value_or(0.0) * kMm;
    o.width_m = t.Number("width_mm", Positive(), BodySizeRange()).value_or(0.0) * kMm;
    o.depth_m = t.Number("depth_mm", Positive(), BodySizeRange()).value_or(0.0) * kMm;
    ReadCommonKeys(t, &e);
    e.output = ResolveRelativeTo(base, t.String("output").value_or(e.name + ".csv"));
    claim_output(t, e);
    e.compare_with = t.String("compare_with").value_or("");
    std::string error;
    if (!o.IsValid(&error)) {
      throw InputError(fmt::format("{}:{}: experiment '{}': {}", path, e.line, e.name, error));
    }
    if (const double nodes = EstimateFemDisplacementNodes(o); nodes > kMaxFemNodes) {
      const FemBodySize size = FemBodySizeUsed(o);
      throw InputError(fmt::format(
          "{}:{}: experiment '{}': the mesh would have about {:.3g} nodes (estimated before "
          "meshing from mesh_size_at_load_mm = {:g}, mesh_growth = {:g}, max_element_mm = {:g} "
          "and the body {:g} x {:g} x {:g} mm; gmsh's counts are within a factor 1.5 of it), "
          "more than {:g} (at least 15 GB and hours per CalculiX solve); expected a coarser "
          "mesh: a larger mesh_size_at_load_mm, mesh_growth or max_element_mm",
          path, e.line, e.name, nodes, o.mesh_size_at_load_m / kMm, o.mesh_growth,
          o.max_element_m / kMm, size.length_m / kMm, size.width_m / kMm, size.depth_m / kMm,
          kMaxFemNodes));
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

}  // namespace railwear::app
