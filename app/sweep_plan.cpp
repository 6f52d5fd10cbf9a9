// Sweep plans: reading a plan (toml++), expanding its axes into lines, and setting a line's
// values in the base scene's TOML before the scene reader sees it.
#include "app/sweep_plan.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "app/paths.h"
#include "app/toml_fields.h"
#include "core/contact/grid_resolution.h"
#include "core/numerics/input_error.h"
#include "wear/collective_traffic.h"
#include "wear/load_collective.h"
#include "wear/traffic.h"

namespace railwear::app {
namespace {

// One axis: its values, each a list of overrides (one for a key axis, a row's for a cases file).
using Axis = std::vector<std::vector<SweepOverride>>;

// A key path segment: a table key, or an entry of an array of tables ("traffic[0]").
struct Segment {
  std::string name;
  int index = -1;  // >= 0: the entry of an array
};

// "wear.k" -> {wear, k}; "traffic[1].friction" -> {traffic[1], friction}. Throws InputError
// naming `origin` for anything else.
std::vector<Segment> ParseKeyPath(const std::string& key, const std::string& origin) {
  static const std::regex kSegment(R"(([A-Za-z0-9_-]+)(\[([0-9]{1,6})\])?)");
  std::vector<Segment> out;
  std::string rest = key;
  while (true) {
    const size_t dot = rest.find('.');
    const std::string part = rest.substr(0, dot);
    std::smatch m;
    if (!std::regex_match(part, m, kSegment)) {
      throw InputError(fmt::format(
          "{}: axis key '{}': expected a dotted scene key such as wear.k, track.radius_m or "
          "traffic[0].friction",
          origin, key));
    }
    out.push_back({m[1].str(), m[3].matched ? std::stoi(m[3].str()) : -1});
    if (dot == std::string::npos) break;
    rest = rest.substr(dot + 1);
  }
  return out;
}

// The TOML value text of an override, parsed (the value is the key "v").
toml::table ParseValue(const std::string& text, const std::string& origin) {
  return ParseToml("v = " + text, origin);
}

// Sets `override` in `root` (the base scene's table). Throws InputError naming the override's
// origin when a path step is missing or not a table.
void Apply(const SweepOverride& o, const std::string& base, toml::table* root) {
  const std::vector<Segment> path = ParseKeyPath(o.key, o.origin);
  const toml::table holder = ParseValue(o.value, o.origin);
  toml::table* t = root;
  for (size_t i = 0; i < path.size(); ++i) {
    const Segment& s = path[i];
    const bool last = i + 1 == path.size();
    if (s.index >= 0) {
      toml::array* a = (*t)[s.name].as_array();
      if (a == nullptr || static_cast<size_t>(s.index) >= a->size()) {
        throw InputError(fmt::format(
            "{}: axis key '{}': the base scene {} has {} '{}' entries; expected an entry it has",
            o.origin, o.key, base, a ? a->size() : 0, s.name));
      }
      if (last) {
        a->replace(a->begin() + s.index, *holder["v"].node());
        return;
      }
      t = (*a)[static_cast<size_t>(s.index)].as_table();
    } else if (last) {
      t->insert_or_assign(s.name, *holder["v"].node());
      return;
    } else {
      if (!t->contains(s.name)) t->insert(s.name, toml::table{});
      t = (*t)[s.name].as_table();
    }
    if (t == nullptr) {
      throw InputError(fmt::format(
          "{}: axis key '{}': '{}' of the base scene {} is not a table; expected a path of tables "
          "to a key",
          o.origin, o.key, s.name, base));
    }
  }
}

uint32_t Fnv1a32(const std::string& text) {
  uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return static_cast<uint32_t>(h ^ (h >> 32));
}

// A number of a range as TOML: an integer when `integer`, else a float rounded to 12
// significant digits (so 0.1 + 2 * 0.1 is 0.3).
std::string RangeValue(double v, bool integer) {
  if (integer) return fmt::format("{}", std::llround(v));
  const double rounded = std::stod(fmt::format("{:.12g}", v));
  std::string text = fmt::format("{}", rounded == 0.0 ? 0.0 : rounded);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

Axis RangeAxis(const Fields& axis, const std::string& key, const std::string& origin) {
  const std::optional<Fields> r = axis.Table("range", "a table { start, stop, step or count }");
  r->AllowOnly({"start", "stop", "step", "count"});
  const double start = r->RequiredNumber("start", AnyFinite());
  const double stop = r->RequiredNumber("stop", AnyFinite());
  if (r->Has("step") == r->Has("count")) {
    r->Fail(r->Has("step") ? "count" : "step", "exactly one of step and count");
  }
  bool integer = r->Node("start")->is_integer() && r->Node("stop")->is_integer();
  std::vector<double> values;
  if (r->Has("step")) {
    const double step = *r->Number("step", {[&](double s) {
                                              return s != 0.0 && (stop - start) / s >= 0.0 &&
                                                     (stop - start) / s < kMaxSweepLines;
                                            },
                                            fmt::format("a step from start {} toward stop {} "
                                                        "(at most {} values)",
                                                        start, stop, kMaxSweepLines)});
    integer = integer && r->Node("step")->is_integer();
    const auto n = static_cast<int>(std::floor((stop - start) / step + 1e-9)) + 1;
    for (int i = 0; i < n; ++i) values.push_back(start + i * step);
  } else {
    const int count = *r->Integer("count", IntegerInRange(1, kMaxSweepLines));
    if (count == 1) values.push_back(start);
    for (int i = 0; count > 1 && i < count; ++i) {
      values.push_back(start + (stop - start) * i / (count - 1));
      integer = integer && values.back() == std::round(values.back());
    }
  }
  Axis out;
  for (const double v : values) out.push_back({{key, RangeValue(v, integer), origin}});
  return out;
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    const size_t a = cell.find_first_not_of(" \t\r");
    const size_t b = cell.find_last_not_of(" \t\r");
    cells.push_back(a == std::string::npos ? std::string() : cell.substr(a, b - a + 1));
  }
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// A cell as a TOML value: itself when it is one (0.3, "x", true, { std = 2 }), else a string
// (builtin:S1002). Cells are split at every comma: a value with a comma (an inline table of
// two keys, an array) goes into a [[axis]] values list instead.
std::string CellValue(const std::string& cell) {
  try {
    const toml::table t = toml::parse("v = " + cell);
    return TomlValueText(*t["v"].node());
  } catch (const toml::parse_error&) {
    toml::table t;
    t.insert("v", cell);
    return TomlValueText(*t["v"].node());
  }
}

// A cases file: a header of keys, then one case per row ('#' lines and empty lines skipped).
Axis CasesAxis(const std::string& file, const std::string& plan_origin) {
  const std::string text = ReadInputFile(file, "cases file of a sweep plan");
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> keys;
  Axis out;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string trimmed = line.substr(0, line.find_last_not_of(" \t\r") + 1);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const std::vector<std::string> cells = SplitCsv(trimmed);
    const std::string origin = fmt::format("{}:{}", file, number);
    if (keys.empty()) {
      for (const std::string& k : cells) ParseKeyPath(k, origin);
      keys = cells;
      continue;
    }
    if (cells.size() != keys.size()) {
      throw InputError(fmt::format("{}: {} values; expected {} (one per key of the header: {})",
                                   origin, cells.size(), keys.size(), trimmed.substr(0, 60)));
    }
    std::vector<SweepOverride> row;
    for (size_t i = 0; i < keys.size(); ++i) {
      if (cells[i].empty()) {
        throw InputError(fmt::format("{}: no value for key '{}'; expected a value in every column",
                                     origin, keys[i]));
      }
      row.push_back({keys[i], CellValue(cells[i]), origin});
    }
    out.push_back(std::move(row));
  }
  if (out.empty()) {
    throw InputError(fmt::format(
        "{}: cases file {} has no cases; expected a header of scene keys and at least one row",
        plan_origin, file));
  }
  return out;
}

Axis ReadAxis(const Fields& axis, const std::string& plan_dir) {
  axis.AllowOnly({"key", "values", "range", "cases", "distribution"});
  const std::string origin = fmt::format("{}:{}", axis.file(), axis.Line());
  const int kinds =
      axis.Has("values") + axis.Has("range") + axis.Has("cases") + axis.Has("distribution");
  if (kinds != 1) {
    throw InputError(fmt::format(
        "{}: [[axis]] table with {} of values, range, cases and distribution; expected exactly one",
        origin, kinds));
  }
  if (axis.Has("cases")) {
    if (axis.Has("key")) axis.Fail("key", "no key with cases (the cases file's header names them)");
    const std::string file = ResolveRelativeTo(plan_dir, *axis.String("cases"));
    return CasesAxis(file, origin);
  }
  const std::string key = axis.RequiredString("key", "a dotted scene key such as wear.k");
  ParseKeyPath(key, fmt::format("{}:{}", axis.file(), LineOf(*axis.Node("key"))));
  if (axis.Has("range")) return RangeAxis(axis, key, origin);
  const toml::array* values = axis.Node("values")->as_array();
  if (values == nullptr || values->empty()) axis.Fail("values", "a non-empty array of values");
  Axis out;
  for (const toml::node& v : *values) {
    out.push_back({{key, TomlValueText(v), fmt::format("{}:{}", axis.file(), LineOf(v))}});
  }
  return out;
}

// The number at `key` in the base scene (the default median of a log-normal axis); nullopt when
// the base scene has no number there.
std::optional<double> BaseNumber(const toml::table& base, const std::string& key,
                                 const std::string& origin) {
  const toml::node* node = &base;
  for (const Segment& s : ParseKeyPath(key, origin)) {
    const toml::table* t = node->as_table();
    if (t == nullptr) return std::nullopt;
    node = t->get(s.name);
    if (node == nullptr) return std::nullopt;
    if (s.index >= 0) {
      const toml::array* a = node->as_array();
      if (a == nullptr || static_cast<size_t>(s.index) >= a->size()) return std::nullopt;
      node = a->get(static_cast<size_t>(s.index));
    }
  }
  return node->value<double>();
}

struct DistributionAxis {
  std::string key;
  SampleDistribution distribution;
  std::string origin;
};

// `distribution = { kind, ... }` of an [[axis]] (ensemble.h's kinds and parameters).
DistributionAxis ReadDistributionAxis(const Fields& axis, const toml::table& base,
                                      const std::string& base_path) {
  DistributionAxis out;
  out.key = axis.RequiredString("key", "a dotted scene key such as wear.k");
  out.origin = fmt::format("{}:{}", axis.file(), LineOf(*axis.Node("distribution")));
  ParseKeyPath(out.key, out.origin);
  const std::optional<Fields> d = axis.Table(
      "distribution", "a table { kind = \"uniform\" | \"normal\" | \"lognormal\", ... }");
  const std::optional<std::string> kind = d->Choice("kind", {"uniform", "normal", "lognormal"});
  if (!kind) d->FailMissing("kind", "\"uniform\", \"normal\" or \"lognormal\"");
  SampleDistribution& s = out.distribution;
  if (*kind == "uniform") {
    d->AllowOnly({"kind", "min", "max"});
    s.kind = SampleDistributionKind::kUniform;
    s.a = d->RequiredNumber("min", AnyFinite());
    s.b = d->RequiredNumber("max", AnyFinite());
  } else {
    if (*kind == "normal") {
      d->AllowOnly({"kind", "mean", "std", "min", "max"});
      s.kind = SampleDistributionKind::kNormal;
      s.a = d->RequiredNumber("mean", AnyFinite());
      s.b = d->RequiredNumber("std", Positive());
    } else {
      d->AllowOnly({"kind", "median", "sigma_ln", "min", "max"});
      s.kind = SampleDistributionKind::kLognormal;
      if (d->Has("median")) {
        s.a = *d->Number("median", Positive());
      } else {
        const std::optional<double> v = BaseNumber(base, out.key, out.origin);
        if (!v || !(*v > 0.0)) {
          d->FailMissing("median", fmt::format("a number > 0 (the default, the base scene {}'s "
                                               "'{}', is {})",
                                               base_path, out.key,
                                               v ? fmt::format("{}", *v) : "not there"));
        }
        s.a = *v;
      }
      s.b = d->Number("sigma_ln", Positive()).value_or(kWearCoefficientSigmaLn);
    }
    s.lower = d->Number("min", AnyFinite()).value_or(-INFINITY);
    s.upper = d->Number("max", AnyFinite()).value_or(INFINITY);
  }
  ValidateSampleDistribution(s, fmt::format("{}: axis '{}' distribution", out.origin, out.key));
  return out;
}

// A drawn value as TOML: its shortest round-trip form, always a float (1.0, 2.5e-05).
std::string SampleValue(double v) {
  std::string text = fmt::format("{}", v);
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

// [life]: limits, annual tonnage, curve-class lengths.
SweepLife ReadLife(const Fields& top) {
  SweepLife life;
  const std::optional<Fields> t = top.Table("life", "a table [life] with [[life.limit]] tables");
  if (!t) return life;
  t->AllowOnly({"annual_mgt", "limit", "class"});
  life.annual_mgt = t->Number("annual_mgt", Positive());
  std::vector<std::string_view> measures(kEnsembleMeasures.begin(), kEnsembleMeasures.end());
  for (const Fields& l : ArrayOfTables(*t, "limit", "[[life.limit]] tables")) {
    l.AllowOnly({"name", "measure", "value"});
    LifeLimit limit;
    const std::optional<std::string> m = l.Choice("measure", measures);
    if (!m) l.FailMissing("measure", JoinQuoted(measures));
    limit.measure = *m;
    limit.value = l.RequiredNumber("value", Positive());
    limit.name = l.String("name").value_or(fmt::format("{} {}", limit.measure, limit.value));
    limit.origin = fmt::format("{}:{}", l.file(), l.Line());
    life.limits.push_back(std::move(limit));
  }
  for (const Fields& c : ArrayOfTables(*t, "class", "[[life.class]] tables")) {
    c.AllowOnly({"match", "length_km"});
    LifeClassLength length;
    length.match = c.RequiredString("match", "a curve class label of the manifest, e.g. "
                                             "\"track.radius_m=600\"");
    length.length_km = c.RequiredNumber("length_km", Positive());
    length.origin = fmt::format("{}:{}", c.file(), LineOf(*c.Node("match")));
    life.classes.push_back(std::move(length));
  }
  return life;
}

}  // namespace

std::string ToString(SamplingMethod method) {
  return method == SamplingMethod::kSobol ? "sobol" : "latin-hypercube";
}

std::string SweepLine::Differences() const {
  std::string out;
  for (const SweepOverride& o : overrides) {
    out += fmt::format("{}{}={}", out.empty() ? "" : " ", o.key, o.value);
  }
  return out;
}

SweepPlan LoadSweepPlan(const std::string& path) {
  const toml::table root = ParseToml(ReadInputFile(path, "sweep plan"), path);
  const Fields top(root, "", path);
  top.AllowOnly({"sweep", "axis", "life"});
  const std::optional<Fields> sweep = top.Table("sweep", "a table [sweep] with scene");
  if (!sweep) {
    throw InputError(fmt::format(
        "{}:1: table [sweep] is missing: expected [sweep] with scene = \"BASE.toml\" (the base "
        "wear scene)",
        path));
  }
  sweep->AllowOnly({"scene", "out_dir", "samples", "seed", "sampling"});
  SweepPlan plan;
  plan.path = path;
  const std::string dir = DirectoryOf(path);
  plan.scene_path = ResolveRelativeTo(
      dir, sweep->RequiredString("scene", "the base wear scene, relative to the plan"));
  plan.out_dir = ResolveRelativeTo(dir, sweep->String("out_dir").value_or(
                                            std::filesystem::path(path).stem().string() + "_runs"));

  const std::string base_text = ReadInputFile(plan.scene_path, "base scene of a sweep plan");
  const toml::table base = ParseToml(base_text, plan.scene_path);

  std::vector<Axis> axes;
  std::vector<DistributionAxis> distributions;
  size_t ensemble_axis = 0;  // where the ensemble's axis goes among `axes`
  for (const Fields& axis : ArrayOfTables(top, "axis", "[[axis]] tables")) {
    if (axis.Has("distribution")) {
      axis.AllowOnly({"key", "distribution"});
      if (distributions.empty()) ensemble_axis = axes.size();
      distributions.push_back(ReadDistributionAxis(axis, base, plan.scene_path));
      continue;
    }
    axes.push_back(ReadAxis(axis, dir));
  }
  plan.life = ReadLife(top);
  if (distributions.empty()) {
    for (const char* key : {"samples", "seed", "sampling"}) {
      if (sweep->Has(key)) {
        sweep->Fail(key, "no such key without a distribution axis ([[axis]] with distribution "
                         "= { kind = ... })");
      }
    }
  } else {
    SweepEnsemble e;
    if (!sweep->Has("samples")) {
      sweep->FailMissing("samples", "the ensemble's size, an integer >= 1 (the plan has "
                                    "distribution axes)");
    }
    e.samples = *sweep->Integer("samples", IntegerInRange(1, kMaxSweepLines));
    e.seed = static_cast<uint64_t>(
        sweep->Integer("seed", IntegerInRange(0, 2147483647)).value_or(1));
    e.method = sweep->Choice("sampling", {"latin-hypercube", "sobol"}).value_or("") == "sobol"
                   ? SamplingMethod::kSobol
                   : SamplingMethod::kLatinHypercube;
    if (e.method == SamplingMethod::kSobol &&
        distributions.size() > static_cast<size_t>(kMaxSobolDimensions)) {
      sweep->Fail("sampling", fmt::format("latin-hypercube with {} distribution axes (sobol "
                                          "draws at most {})",
                                          distributions.size(), kMaxSobolDimensions));
    }
    for (const DistributionAxis& d : distributions) {
      e.keys.push_back(d.key);
      e.distributions.push_back(d.distribution);
    }
    e.values = DrawSamples(e.distributions, e.samples, e.method, e.seed);
    Axis samples;
    for (const std::vector<double>& row : e.values) {
      std::vector<SweepOverride> overrides;
      for (size_t k = 0; k < row.size(); ++k) {
        overrides.push_back({distributions[k].key, SampleValue(row[k]), distributions[k].origin,
                             true});
      }
      samples.push_back(std::move(overrides));
    }
    axes.insert(axes.begin() + static_cast<std::ptrdiff_t>(ensemble_axis), std::move(samples));
    plan.ensemble = std::move(e);
  }
  double count = 1.0;
  for (const Axis& a : axes) count *= static_cast<double>(a.size());
  if (count > kMaxSweepLines) {
    throw InputError(fmt::format("{}: the axes give {:.0f} runs; expected at most {}", path, count,
                                 kMaxSweepLines));
  }

  const int n = static_cast<int>(count);
  for (int index = 0; index < n; ++index) {
    SweepLine line;
    line.index = index;
    int rest = index;  // mixed radix, the last axis fastest
    std::vector<size_t> pick(axes.size());
    for (size_t a = axes.size(); a-- > 0;) {
      pick[a] = static_cast<size_t>(rest) % axes[a].size();
      rest /= static_cast<int>(axes[a].size());
    }
    for (size_t a = 0; a < axes.size(); ++a) {
      for (const SweepOverride& o : axes[a][pick[a]]) line.overrides.push_back(o);
      if (plan.ensemble && a == ensemble_axis) line.sample = static_cast<int>(pick[a]);
    }
    for (const SweepOverride& o : line.overrides) {
      if (!o.sampled) line.group += fmt::format("{}{}={}", line.group.empty() ? "" : " ", o.key, o.value);
    }
    if (line.group.empty()) line.group = "(base scene)";
    toml::table scene = base;
    for (const SweepOverride& o : line.overrides) Apply(o, plan.scene_path, &scene);
    std::ostringstream text;
    // No paths here: the text (and so the run id) is the same from any folder.
    text << fmt::format("# railwear sweep line {}: the base scene with {}\n", index,
                        line.overrides.empty() ? "no changes" : line.Differences());
    if (plan.ensemble) {
      text << fmt::format("# railwear ensemble sample {} of {} ({}, seed {})\n", line.sample,
                          plan.ensemble->samples, ToString(plan.ensemble->method),
                          plan.ensemble->seed);
    }
    text << scene << "\n";
    line.scene_text = text.str();
    line.id = fmt::format("{:04}-{:08x}", index, Fnv1a32(line.scene_text));
    plan.lines.push_back(std::move(line));
  }
  return plan;
}

Scene SweepLineScene(const SweepPlan& plan, const SweepLine& line) {
  Scene scene;
  try {
    scene = ParseScene(line.scene_text, plan.scene_path);
  } catch (const InputError& e) {
    // The scene's message names a line of the generated text: name the plan's axis instead.
    std::string message = e.what();
    const std::string prefix = plan.scene_path + ":";
    if (message.rfind(prefix, 0) == 0) {
      const size_t end = message.find(": ", prefix.size());
      if (end != std::string::npos &&
          message.substr(prefix.size(), end - prefix.size()).find_first_not_of("0123456789:") ==
              std::string::npos) {
        message = message.substr(end + 2);
      }
    }
    if (line.overrides.empty()) throw;  // the base scene itself
    // The axis the message names: its key, else the nearest table on its path ('track' for
    // track.radius_m); none: every value of the line is named.
    const SweepOverride* culprit = nullptr;
    size_t best = 0;
    for (const SweepOverride& o : line.overrides) {
      for (std::string key = o.key; !key.empty();) {
        if (key.size() > best && message.find("'" + key + "'") != std::string::npos) {
          culprit = &o;
          best = key.size();
        }
        const size_t dot = key.find_last_of(".[");
        key = dot == std::string::npos ? std::string() : key.substr(0, dot);
      }
    }
    if (culprit == nullptr) {
      throw InputError(fmt::format(
          "{}: run {} ({}): the scene rejects its values: {} (the base scene {} with them)",
          line.overrides.front().origin, line.id, line.Differences(), message, plan.scene_path));
    }
    throw InputError(fmt::format(
        "{}: axis '{}' = {} (run {}): the scene rejects it: {} (the base scene {} with the run's "
        "values: {})",
        culprit->origin, culprit->key, culprit->value, line.id, message, plan.scene_path,
        line.Differences()));
  }
  if (!scene.wear) {
    throw InputError(fmt::format(
        "{}: [sweep] scene = {}: not a wear scene; expected a scene with effect \"wear\", [wear] "
        "and [[traffic]]",
        plan.path, plan.scene_path));
  }
  return scene;
}

double SweepLineCost(const Scene& scene) {
  if (!scene.wear) return 0.0;
  const WearStudy& study = *scene.wear;
  const WearOptions& o = study.options;
  // Nodes per spread: the fixed rule's, or the adaptive rule's typical count (7 to start, a few
  // midpoints added).
  constexpr double kAdaptiveNodes = 11.0;
  const double nodes = o.integration_tolerance   ? kAdaptiveNodes
                       : !o.spread_nodes.empty() ? static_cast<double>(o.spread_nodes.size())
                                                 : o.quadrature_points;
  double cases = 0.0;
  for (const TrafficCase& t : study.traffic) {
    const double spread = t.lateral_shift_std_m > 0.0 ? nodes : 1.0;
    if (t.is_collective()) {
      cases += static_cast<double>(t.collective->collective.entries.size());
    } else if (t.is_vehicle()) {
      cases += 2.0 * study.vehicles[static_cast<size_t>(t.vehicle)].wheelsets() * spread;
    } else {
      cases += spread;
    }
  }
  const bool explicit_cells =
      study.model.cell_dx_m.has_value() || study.model.cell_ds_m.has_value();
  const double per_axis =
      CellsPerSemiAxis(explicit_cells ? AccuracyPreset::kStandard : study.model.accuracy);
  const double mgt = TotalPasses(study) * MgtPerPass(study.traffic);
  return mgt * cases * per_axis * per_axis;
}

}  // namespace railwear::app
