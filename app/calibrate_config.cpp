// `railwear calibrate`'s config: TOML -> CalibrateConfig. See calibrate_config.h.
#include "app/calibrate_config.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "app/fem_contact_result.h"
#include "app/influence_constants_file.h"
#include "app/paths.h"
#include "app/toml_fields.h"
#include "calibration/displacement_curves.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

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

void ReadCalibrationTable(const Fields& top, CalibrateConfig* c) {
  c->name = fs::path(c->path).stem().string();
  c->out = ResolveRelativeTo(DirectoryOf(c->path), c->name + "_constants.toml");
  const auto t = top.Table("calibration", "a table");
  if (!t) return;
  t->AllowOnly({"name", "fit", "separate_bodies", "start", "fit_offsets", "out", "db",
                "contact_relative_step", "max_iterations"});
  if (const auto name = t->String("name")) c->name = *name;
  if (t->Has("fit")) {
    c->fit.fit = EnumArray<InfluenceConstantName>(
        *t, "fit", InfluenceConstantNameFromString,
        "a non-empty array of distinct names of 'c_f', 'c_z', 'c_s'");
  }
  c->fit.separate_bodies = t->Bool("separate_bodies").value_or(false);
  if (const auto start = t->Table("start",
                                  "an inline table { c_f, c_z, c_s } or "
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
  if (const auto n = t->Integer("max_iterations", AtLeast(1.0), IntegerInRange(1, 100000))) {
    c->fit.max_num_iterations = *n;
  }
  std::string error;
  if (!c->fit.IsValid(&error)) {
    throw InputError(fmt::format("{}:{}: [calibration]: {}", c->path, t->Line(), error));
  }
}

void ReadCurveEntries(const Fields& top, CalibrateConfig* c) {
  for (const Fields& t : ArrayOfTables(top, "displacement_curves",
                                       "[[displacement_curves]] tables with file, weight, "
                                       "min_distance_mm, max_distance_mm")) {
    t.AllowOnly({"file", "weight", "min_distance_mm", "max_distance_mm"});
    CalibrateCurveEntry e;
    e.file = ExistingFile(t, "file", c->path, "displacement curves (CSV)");
    // Weights are relative, as traffic shares: up to 1e6 (a sum near the largest double made
    // the objective infinite). Distances from the load within 1 m (the curves are millimetres).
    e.data.weight = t.Number("weight", Positive(), OpenClosed(0.0, 1e6)).value_or(1.0);
    e.data.min_distance_m =
        t.Number("min_distance_mm", AtLeast(0.0), Closed(0.0, 1000.0)).value_or(0.0) * kMm;
    if (const auto max = t.Number("max_distance_mm", Positive(), OpenClosed(0.0, 1000.0))) {
      e.data.max_distance_m = *max * kMm;
      if (!(e.data.max_distance_m > e.data.min_distance_m)) {
        t.Fail("max_distance_mm", "a distance larger than min_distance_mm");
      }
    }
    e.data.curves = ReadDisplacementCurves(e.file);  // its own FILE:LINE messages
    c->curves.push_back(std::move(e));
  }
}

constexpr double kMinArea_mm2 = 1e-3, kMaxArea_mm2 = 1e5, kMinP_MPa = 1.0, kMaxP_MPa = 1e5;

void ReadContactEntries(const Fields& top, CalibrateConfig* c) {
  for (const Fields& t : ArrayOfTables(top, "contact_results",
                                       "[[contact_results]] tables with scene, area_mm2, "
                                       "p_max_MPa (or fem_result), weight")) {
    t.AllowOnly({"scene", "area_mm2", "p_max_MPa", "weight", "fem_result"});
    CalibrateContactEntry e;
    std::string prefix;
    if (t.Has("fem_result")) {
      // A fem-reference result file: its scene and its finest level's area and peak pressure.
      for (const char* key : {"scene", "area_mm2", "p_max_MPa"}) {
        if (t.Has(key)) {
          t.Fail(key,
                 "no scene, area_mm2 or p_max_MPa with fem_result (the result file holds "
                 "them)");
        }
      }
      e.fem_result = ExistingFile(t, "fem_result", c->path, "a fem-reference contact result");
      const FemContactTarget fem = ReadFemContactTarget(e.fem_result);  // FILE:LINE messages
      prefix = FieldPrefix(t.file(), *t.Node("fem_result"), t.KeyName("fem_result"));
      if (fem.status != "ok" || fem.scene.empty()) {
        throw InputError(
            fmt::format("{}: the result has status '{}'{}; expected status 'ok' and a scene",
                        prefix, fem.status, fem.scene.empty() ? " and no scene" : ""));
      }
      if (!(fem.area_mm2 >= kMinArea_mm2 && fem.area_mm2 <= kMaxArea_mm2 &&
            fem.p_max_MPa >= kMinP_MPa && fem.p_max_MPa <= kMaxP_MPa)) {
        throw InputError(fmt::format(
            "{}: the result's area_mm2 = {} and p_max_MPa = {}; expected area_mm2 in [{}, {}] "
            "and p_max_MPa in [{}, {}] (the range the fit bears)",
            prefix, fem.area_mm2, fem.p_max_MPa, kMinArea_mm2, kMaxArea_mm2, kMinP_MPa, kMaxP_MPa));
      }
      e.scene = fem.scene;
      e.target.area_m2 = fem.area_mm2 / kToMm2;
      e.target.p_max_Pa = fem.p_max_MPa / kToMPa;
    } else {
      e.scene = ExistingFile(t, "scene", c->path, "a contact scene (TOML)");
      // Ranges the fit bears (area_mm2 = 1e-300 gave an infinite residual): patches of a
      // thousandth to a hundred thousand square millimetres, pressures up to 1e5 MPa.
      e.target.area_m2 =
          t.RequiredNumber("area_mm2", Positive(), Closed(kMinArea_mm2, kMaxArea_mm2)) / kToMm2;
      e.target.p_max_Pa =
          t.RequiredNumber("p_max_MPa", Positive(), Closed(kMinP_MPa, kMaxP_MPa)) / kToMPa;
      prefix = FieldPrefix(t.file(), *t.Node("scene"), t.KeyName("scene"));
    }
    e.target.weight = t.Number("weight", Positive(), OpenClosed(0.0, 1e6)).value_or(1.0);
    e.loaded = LoadScene(e.scene);  // its own FILE:LINE messages
    if (e.loaded.wear || e.loaded.track) {
      throw InputError(fmt::format("{}: expected a single-wheel contact scene ([load]), not a {}",
                                   prefix, e.loaded.wear ? "wear scene" : "wheelset"));
    }
    const ModelOptions& m = e.loaded.problem.model;
    if (m.kind == ModelKind::kHertz || m.kernel != KernelModel::kGolubenko) {
      throw InputError(
          fmt::format("{}: its model ({}, kernel {}) does not use the influence "
                      "constants; expected kind = \"conformal\" (golubenko kernel)",
                      prefix, ToString(m.kind), ToString(m.kernel)));
    }
    e.target.name = e.scene;
    e.target.problem = e.loaded.problem;
    c->contacts.push_back(std::move(e));
  }
}

}  // namespace

CalibrateConfig ReadCalibrateConfig(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: no such file; expected a calibration config (TOML)", path));
  }
  CalibrateConfig c;
  c.path = path;
  c.text = ReadInputFile(path, "the calibration config");
  const toml::table root = ParseToml(c.text, path);
  const Fields top(root, "", path);
  top.AllowOnly({"calibration", "displacement_curves", "contact_results"});
  ReadCalibrationTable(top, &c);
  ReadCurveEntries(top, &c);
  ReadContactEntries(top, &c);
  if (c.curves.empty() && c.contacts.empty()) {
    throw InputError(
        fmt::format("{}:1: no data: expected at least one [[displacement_curves]] "
                    "or [[contact_results]] table",
                    path));
  }
  return c;
}

}  // namespace railwear::app
