// Scene files: TOML text -> validated Scene with a ready ContactProblem (DESIGN.md §3).
#include "app/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "app/paths.h"
#include "app/toml_fields.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"

namespace railwear::app {
namespace {

constexpr double kMm = 1e-3;   // millimetres -> metres
constexpr double kMPa = 1e6;   // MPa -> Pa
constexpr double kMaxRoll_rad = 0.5;  // a wheel rolls by milliradians; 0.5 rad catches typos

const std::vector<std::string_view> kKnownEffects = {"normal", "tangential", "coupling", "wear",
                                                     "damage"};

std::string ReadTextFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open {}", path, what));
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// [wear] and [[traffic]] describe wear runs, which this version cannot do yet.
void RejectLaterTables(const Fields& top) {
  for (const std::string_view key : {"wear", "traffic"}) {
    if (top.Has(key)) {
      throw InputError(fmt::format(
          "{}: expected contact tables only: [{}] belongs to worn-profile evolution runs, which "
          "this version of railwear does not provide yet",
          FieldPrefix(top.file(), *top.Node(key), key), key));
    }
  }
}

Fields RequiredTable(const Fields& top, std::string_view key, std::string_view expected) {
  auto t = top.Table(key, "a table");
  if (!t) top.FailMissing(key, expected);
  return *t;
}

void ReadSceneTable(const Fields& top, Scene* scene) {
  scene->name = std::filesystem::path(scene->path).stem().string();
  scene->effects = {"normal"};
  const auto t = top.Table("scene", "a table");
  if (!t) return;
  t->AllowOnly({"name", "effects"});
  if (auto name = t->String("name")) scene->name = *name;
  const toml::node* effects = t->Node("effects");
  if (effects == nullptr) return;
  const std::string expected = "an array of effect names, of " + JoinQuoted(kKnownEffects);
  if (!effects->is_array()) t->Fail("effects", expected);
  for (const auto& e : *effects->as_array()) {
    const auto name = e.value_exact<std::string>();
    const std::string key = t->KeyName("effects");
    if (!name) throw InputError(FieldError(t->file(), e, key, expected));
    if (*name == "normal") continue;
    bool known = false;
    for (const auto& k : kKnownEffects) known = known || *name == k;
    if (!known) throw InputError(FieldError(t->file(), e, key, "one of " + JoinQuoted(kKnownEffects)));
    if (*name == "tangential" || *name == "damage" || *name == "coupling") {
      // damage and coupling need the tractions and slip of the tangential stage
      scene->tangential = true;
      scene->damage = scene->damage || *name == "damage";
      scene->coupling = scene->coupling || *name == "coupling";
      scene->effects.push_back(*name);
      continue;
    }
    throw InputError(fmt::format(
        "{}: expected 'normal', 'tangential', 'coupling' or 'damage': effect '{}' is not "
        "available in this version of railwear",
        FieldPrefix(t->file(), e, key), *name));
  }
  if ((scene->damage || scene->coupling) &&
      std::find(scene->effects.begin(), scene->effects.end(), "tangential") ==
          scene->effects.end()) {
    scene->effects.insert(scene->effects.begin() + 1, "tangential");  // implied
  }
}

InfluenceConstants ReadConstants(const Fields& t) {
  t.AllowOnly({"c_f", "c_z", "c_s"});
  InfluenceConstants c;
  c.c_f = t.Number("c_f", Positive()).value_or(c.c_f);
  c.c_z = t.Number("c_z", Positive()).value_or(c.c_z);
  c.c_s = t.Number("c_s", AnyFinite()).value_or(c.c_s);
  return c;
}

InfluenceConstants ReadConstantsFile(const std::string& path) {
  const std::string text = ReadTextFile(path, "influence constants file");
  const toml::table root = ParseToml(text, path);
  const Fields top(root, "", path);
  const auto t = top.Table("influence_constants", "a table { c_f, c_z, c_s }");
  if (!t) {
    top.FailMissing("influence_constants", "an [influence_constants] table with c_f, c_z, c_s");
  }
  return ReadConstants(*t);
}

void ReadInfluenceConstants(const Fields& model, const std::string& scene_path, Scene* scene) {
  const toml::node* node = model.Node("influence_constants");
  if (node == nullptr) return;
  const std::string expected =
      "an inline table { c_f, c_z, c_s } or the path of a TOML file with [influence_constants]";
  if (const auto file = node->value_exact<std::string>()) {
    const std::string path = ResolveRelativeTo(DirectoryOf(scene_path), *file);
    scene->influence_constants_source = path;
    scene->problem.model.constants = ReadConstantsFile(path);
    return;
  }
  const auto t = model.Table("influence_constants", expected);
  scene->influence_constants_source = "inline";
  scene->problem.model.constants = ReadConstants(*t);
}

// geometry/kernel given explicitly: the kind becomes the shorthand they match, else custom.
ModelKind KindOf(GeometryModel geometry, KernelModel kernel) {
  for (const ModelKind k : {ModelKind::kHalfspace, ModelKind::kConformal}) {
    const ModelOptions o = MakeModelOptions(k);
    if (o.geometry == geometry && o.kernel == kernel) return k;
  }
  return ModelKind::kCustom;
}

void ReadGeometryAndKernel(const Fields& t, ModelOptions* model) {
  const auto geometry = t.Choice("geometry", {"planar", "conformal"});
  const auto kernel = t.Choice("kernel", {"boussinesq", "golubenko"});
  if (!geometry && !kernel) return;
  if (model->kind == ModelKind::kHertz) {
    t.Fail(geometry ? "geometry" : "kernel",
           "no geometry or kernel with kind = 'hertz' (Hertz is analytic; use kind = "
           "'halfspace' or 'conformal', or drop this key)");
  }
  if (model->kind == ModelKind::kAuto) {  // auto picks the geometry per patch
    if (geometry) t.Fail("geometry", "no geometry with kind = 'auto' (it picks one per patch)");
    model->kernel = *KernelModelFromString(*kernel);  // of its conformal patches
    return;
  }
  if (geometry) model->geometry = *GeometryModelFromString(*geometry);
  if (kernel) model->kernel = *KernelModelFromString(*kernel);
  model->kind = KindOf(model->geometry, model->kernel);
}

void ReadCellSize(const Fields& t, ModelOptions* model) {
  const toml::node* node = t.Node("cell_mm");
  if (node == nullptr) return;
  const std::string expected = "two positive numbers [dx, ds] in mm";
  const toml::array* a = node->as_array();
  if (a == nullptr || a->size() != 2) t.Fail("cell_mm", expected);
  double v[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    const toml::node& e = *a->get(i);
    if (const auto n = e.value<double>()) v[i] = *n;  // integers convert
    if (!(e.is_number() && std::isfinite(v[i]) && v[i] > 0.0)) t.Fail("cell_mm", expected);
  }
  model->cell_dx_m = v[0] * kMm;
  model->cell_ds_m = v[1] * kMm;
}

void ReadModel(const Fields& top, Scene* scene) {
  ModelOptions& model = scene->problem.model;
  model = MakeModelOptions(ModelKind::kConformal);
  const auto t = top.Table("model", "a table");
  if (!t) return;
  t->AllowOnly({"kind", "geometry", "kernel", "influence_constants", "accuracy", "cell_mm",
                "tangential"});
  if (const auto kind = t->Choice("kind", {"hertz", "halfspace", "conformal", "auto"})) {
    model = MakeModelOptions(*ModelKindFromString(*kind));
  }
  ReadGeometryAndKernel(*t, &model);
  if (const auto a = t->Choice("accuracy", {"draft", "standard", "reference", "fine"})) {
    model.accuracy = *AccuracyPresetFromString(*a);
  }
  ReadCellSize(*t, &model);
  if (const auto tan = t->Choice("tangential", {"fastsim", "exact"})) {
    scene->tangential_method = *tan;
  }
  ReadInfluenceConstants(*t, scene->path, scene);
}

Material ReadMaterial(const Fields& materials, std::string_view body, bool rail) {
  const auto t = materials.Table(body, "an inline table { E_MPa, nu }");
  if (!t) materials.FailMissing(body, "an inline table { E_MPa, nu }");
  if (rail) {
    t->AllowOnly({"E_MPa", "nu", "hardness_MPa", "shear_yield_MPa"});
  } else {
    t->AllowOnly({"E_MPa", "nu"});
  }
  Material m;
  m.youngs_modulus_Pa = t->RequiredNumber("E_MPa", Positive()) * kMPa;
  m.poisson_ratio = t->RequiredNumber("nu", InRange(0.0, 0.5));
  if (const auto h = t->Number("hardness_MPa", Positive())) m.hardness_Pa = *h * kMPa;
  if (const auto y = t->Number("shear_yield_MPa", Positive())) m.shear_yield_Pa = *y * kMPa;
  return m;
}

void ReadMaterials(const Fields& top, Scene* scene) {
  scene->problem.wheel_material = DefaultSteel();
  scene->problem.rail_material = DefaultSteel();
  const auto t = top.Table("materials", "a table");
  if (!t) return;
  t->AllowOnly({"wheel", "rail"});
  scene->problem.wheel_material = ReadMaterial(*t, "wheel", false);
  scene->problem.rail_material = ReadMaterial(*t, "rail", true);
}

// Loads a profile spec; errors from the profile reader get the scene key in front.
Profile LoadProfile(const Fields& t, BodyRole role, const std::string& spec,
                    const std::string& scene_path) {
  try {
    return LoadProfileSpec(spec, role, DirectoryOf(scene_path));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}:{}: key '{}' = \"{}\": {}", t.file(), LineOf(*t.Node("profile")),
                                 t.KeyName("profile"), spec, e.what()));
  }
}

constexpr std::string_view kProfileExpected =
    "a profile: \"builtin:S1002\", \"builtin:UIC60\", \"circle:R_mm\", \"groove:R_mm\" or a "
    "file (.csv, .ban, .whl, .prr, .prw) relative to the scene";

void ReadWheel(const Fields& top, Scene* scene) {
  const Fields t = RequiredTable(top, "wheel", "a [wheel] table with profile, rolling_radius_mm");
  t.AllowOnly({"profile", "rolling_radius_mm", "mirror_y"});
  scene->wheel_profile_spec = t.RequiredString("profile", kProfileExpected);
  scene->problem.placement.rolling_radius_m =
      t.RequiredNumber("rolling_radius_mm", Positive()) * kMm;
  Profile p = LoadProfile(t, BodyRole::kWheel, scene->wheel_profile_spec, scene->path);
  if (t.Bool("mirror_y").value_or(false)) p = p.Mirrored();
  scene->problem.wheel_profile = std::move(p);
}

double ReadCant(const Fields& t, Scene* scene) {
  const toml::node* node = t.Node("cant");
  if (node == nullptr) return 0.0;
  const std::string expected = "a cant ratio \"1:N\" (e.g. \"1:40\") or 0";
  if (const auto i = node->value_exact<int64_t>(); i && *i == 0) return 0.0;
  const auto text = node->value_exact<std::string>();
  if (!text) t.Fail("cant", expected);
  scene->cant = *text;
  try {
    return ParseCant(*text);
  } catch (const InputError&) {
    t.Fail("cant", expected);
  }
}

void ReadRail(const Fields& top, Scene* scene) {
  const Fields t = RequiredTable(top, "rail", "a [rail] table with profile");
  t.AllowOnly({"profile", "cant", "mirror_y"});
  scene->rail_profile_spec = t.RequiredString("profile", kProfileExpected);
  scene->cant_ratio = ReadCant(t, scene);
  Profile p = LoadProfile(t, BodyRole::kRail, scene->rail_profile_spec, scene->path);
  if (t.Bool("mirror_y").value_or(false)) p = p.Mirrored();
  if (scene->cant_ratio != 0.0) p = ApplyCant(p, scene->cant_ratio);
  scene->problem.rail_profile = std::move(p);
}

// [load] creepage = { xi, eta, spin_per_mm }: prescribed creepages instead of kinematics.
Creepage ReadCreepage(const Fields& load) {
  const auto t = load.Table("creepage", "an inline table { xi, eta, spin_per_mm }");
  t->AllowOnly({"xi", "eta", "spin_per_mm"});
  Creepage c;
  c.xi = t->Number("xi", InRange(-1.0, 1.0)).value_or(0.0);
  c.eta = t->Number("eta", InRange(-1.0, 1.0)).value_or(0.0);
  c.spin_per_m = t->Number("spin_per_mm", AnyFinite()).value_or(0.0) / kMm;
  return c;
}

// The rolling keys shared by the single wheel ([load]) and the wheelset ([wheelset]).
void ReadMotion(const Fields& t, Scene* scene) {
  if (const auto v = t.Number("speed_m_s", AtLeast(0.0))) scene->speed_m_s = *v;
  if (const auto yaw = t.Number("yaw_mrad", InRange(-kMaxRoll_rad * 1e3, kMaxRoll_rad * 1e3))) {
    scene->motion.yaw_rad = *yaw * 1e-3;
  }
  scene->motion.pitch_velocity_rad_s = t.Number("pitch_velocity_rad_s", AnyFinite());
  scene->longitudinal_force_N = t.Number("longitudinal_force_N", AnyFinite());
  if (scene->longitudinal_force_N && t.Has("pitch_velocity_rad_s")) {
    t.Fail("longitudinal_force_N",
           "either longitudinal_force_N or pitch_velocity_rad_s (the force sets the pitch "
           "velocity), not both");
  }
}

void ReadLoad(const Fields& top, Scene* scene) {
  const bool wheelset = top.Has("wheelset");
  if (wheelset) {
    // With a wheelset, [load] is optional and holds only what is not placement.
    const auto t = top.Table("load", "a table");
    if (!t) return;
    t->AllowOnly({"friction", "creepage"});
    scene->friction = t->Number("friction", OpenClosed(0.0, 2.0));
    if (t->Has("creepage")) scene->creepage = ReadCreepage(*t);
    return;
  }
  const Fields t = RequiredTable(top, "load", "a [load] table with vertical_N or approach_mm");
  t.AllowOnly({"vertical_N", "approach_mm", "lateral_shift_mm", "roll_rad", "friction",
               "speed_m_s", "yaw_mrad", "pitch_velocity_rad_s", "longitudinal_force_N",
               "creepage"});
  ContactLoad& load = scene->problem.load;
  load.vertical_force_N = t.Number("vertical_N", Positive());
  if (const auto a = t.Number("approach_mm", Positive())) load.approach_m = *a * kMm;
  if (load.vertical_force_N && load.approach_m) {
    t.Fail("approach_mm", "exactly one of 'load.vertical_N' and 'load.approach_mm' (both given)");
  }
  if (!load.vertical_force_N && !load.approach_m) {
    t.FailMissing("vertical_N", "exactly one of 'load.vertical_N' and 'load.approach_mm'");
  }
  WheelPlacement& placement = scene->problem.placement;
  placement.lateral_shift_m = t.Number("lateral_shift_mm", AnyFinite()).value_or(0.0) * kMm;
  placement.roll_rad = t.Number("roll_rad", InRange(-kMaxRoll_rad, kMaxRoll_rad)).value_or(0.0);
  scene->friction = t.Number("friction", OpenClosed(0.0, 2.0));
  ReadMotion(t, scene);
  if (t.Has("creepage")) {
    if (t.Has("yaw_mrad") || t.Has("pitch_velocity_rad_s") || t.Has("longitudinal_force_N")) {
      t.Fail("creepage",
             "either prescribed creepages or the wheel's motion (yaw_mrad, "
             "pitch_velocity_rad_s, longitudinal_force_N), not both");
    }
    scene->creepage = ReadCreepage(t);
  }
}

// [track] and [wheelset]: a wheelset on a track (DESIGN.md §3) instead of the single wheel.
void ReadWheelset(const Fields& top, Scene* scene) {
  const auto track = top.Table("track", "a table");
  const auto ws = top.Table("wheelset", "a table");
  if (track && !ws) {
    track->Fail("gauge_mm", "a [wheelset] table next to [track] (a track alone places nothing)");
  }
  if (!ws) return;
  TrackSpec tr;
  if (track) {
    track->AllowOnly({"gauge_mm", "gauge_height_mm"});
    tr.gauge_m = track->Number("gauge_mm", Positive()).value_or(tr.gauge_m / kMm) * kMm;
    tr.gauge_height_m =
        track->Number("gauge_height_mm", AtLeast(0.0)).value_or(tr.gauge_height_m / kMm) * kMm;
  }
  ws->AllowOnly({"flange_back_distance_mm", "flange_back_position_mm", "lateral_displacement_mm",
                 "yaw_mrad", "roll_rad", "vertical_load_per_wheel_N", "speed_m_s",
                 "pitch_velocity_rad_s", "longitudinal_force_N"});
  WheelsetSpec w;
  w.flange_back_distance_m =
      ws->Number("flange_back_distance_mm", Positive()).value_or(w.flange_back_distance_m / kMm) *
      kMm;
  w.flange_back_position_m =
      ws->Number("flange_back_position_mm", AnyFinite()).value_or(w.flange_back_position_m / kMm) *
      kMm;
  w.lateral_displacement_m = ws->Number("lateral_displacement_mm", AnyFinite()).value_or(0.0) * kMm;
  w.roll_rad = ws->Number("roll_rad", InRange(-kMaxRoll_rad, kMaxRoll_rad)).value_or(0.0);
  w.rolling_radius_m = scene->problem.placement.rolling_radius_m;
  ReadMotion(*ws, scene);
  w.yaw_rad = scene->motion.yaw_rad;
  if (scene->creepage &&
      (ws->Has("yaw_mrad") || ws->Has("pitch_velocity_rad_s") || ws->Has("longitudinal_force_N"))) {
    ws->Fail(ws->Has("yaw_mrad")             ? "yaw_mrad"
             : ws->Has("pitch_velocity_rad_s") ? "pitch_velocity_rad_s"
                                               : "longitudinal_force_N",
             "no wheelset motion next to prescribed creepages in [load]");
  }
  scene->problem.load = {};
  scene->problem.load.vertical_force_N = ws->RequiredNumber("vertical_load_per_wheel_N", Positive());
  scene->track = tr;
  scene->wheelset = w;
}

// Rolling contact needs a friction coefficient and a speed, and a model with a grid.
void CheckRolling(const Fields& top, const Scene& scene) {
  if (!scene.tangential) return;
  if (const auto model = top.Table("model", "a table")) {
    if (scene.problem.model.kind == ModelKind::kHertz) {
      model->Fail("kind",
                  "\"halfspace\" or \"conformal\" with the tangential effect (rolling contact "
                  "is solved on the patch grid, which the analytic Hertz model has not)");
    }
  }
  if (scene.damage && !(scene.problem.rail_material.shear_yield_Pa > 0)) {
    throw InputError(fmt::format(
        "{}:{}: key 'materials.rail.shear_yield_MPa' is missing: expected the rail's shear yield "
        "stress k in MPa for the damage effect (FI_surf and the shakedown map need it)",
        top.file(), top.Has("materials") ? LineOf(*top.Node("materials")) : 1));
  }
  const std::string_view where = scene.wheelset ? "wheelset" : "load";
  if (!scene.friction) {
    throw InputError(fmt::format(
        "{}:{}: key 'load.friction' is missing: expected a friction coefficient in (0, 2] for "
        "the tangential effect",
        top.file(), top.Has("load") ? LineOf(*top.Node("load")) : 1));
  }
  if (!scene.speed_m_s || !(*scene.speed_m_s > 0)) {
    throw InputError(fmt::format(
        "{}:{}: key '{}.speed_m_s' {}: expected a speed > 0 m/s for the tangential effect",
        top.file(), top.Has(where) ? LineOf(*top.Node(where)) : 1, where,
        scene.speed_m_s ? "= 0" : "is missing"));
  }
}

}  // namespace

Material DefaultSteel() {
  Material m;
  m.youngs_modulus_Pa = 210000.0 * kMPa;
  m.poisson_ratio = 0.28;
  return m;
}

Scene ParseScene(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  const Fields top(root, "", path);
  RejectLaterTables(top);
  top.AllowOnly({"scene", "model", "materials", "wheel", "rail", "load", "track", "wheelset"});
  Scene scene;
  scene.path = path;
  scene.text = text;
  ReadSceneTable(top, &scene);
  ReadModel(top, &scene);
  ReadMaterials(top, &scene);
  ReadLoad(top, &scene);
  ReadWheel(top, &scene);
  ReadRail(top, &scene);
  ReadWheelset(top, &scene);
  CheckRolling(top, scene);
  if (scene.speed_m_s) scene.motion.speed_m_s = *scene.speed_m_s;
  if (scene.tangential) {
    RollingOptions rolling;
    rolling.method = *TangentialMethodFromString(scene.tangential_method);
    rolling.motion = scene.motion;
    rolling.creepage = scene.creepage;
    rolling.friction = *scene.friction;
    rolling.damage = scene.damage;
    rolling.longitudinal_force_N = scene.longitudinal_force_N;
    rolling.coupling = scene.coupling;
    scene.problem.rolling = rolling;
  }
  return scene;
}

Scene LoadScene(const std::string& path) {
  return ParseScene(ReadTextFile(path, "scene file"), path);
}

}  // namespace railwear::app
