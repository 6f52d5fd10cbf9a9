// Scene files: TOML text -> validated Scene with a ready ContactProblem (DESIGN.md §3).
#include "app/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "app/influence_constants_file.h"
#include "app/load_collective_file.h"
#include "app/paths.h"
#include "app/toml_fields.h"
#include "core/contact/contact_case.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_exact.h"
#include "core/numerics/enum_names.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "core/profile/builtin_profiles.h"
#include "wear/collective_traffic.h"
#include "wear/rail_grade.h"

namespace railwear::app {
namespace {

constexpr double kMPa = 1e6;            // MPa -> Pa
constexpr double kMaxRoll_rad = 0.5;    // a wheel rolls by milliradians; 0.5 rad catches typos
constexpr double kMaxYaw_mrad = 100.0;  // angles of attack are tens of mrad (wear traffic alike)
// Traffic shares are relative weights: a mix whose shares span more than 1e6 to 1 is a typo,
// and sums of shares near the largest double overflow (1e308 gave "0 steps (complete)").
constexpr double kMaxShare = 1e6;
constexpr double kMaxSpeed_m_s = 150.0;  // 540 km/h, above any rail vehicle's

// Ranges the numerics bear (issue 17; the table in docs/testing.md). A value outside is refused
// at input with "expected RANGE (the range the numerics bear)".
// Wheel radii from 50 mm (below any rail wheel: small tram wheels are 250 mm) to 2 m: the patch's
// x extent is sqrt(2 r threshold), and 1e-300 mm left no cell.
NumberRule WheelRadiusRange() { return Closed(50.0, 2000.0); }
// Wheel loads from 1 N to 1 MN (a 40 t axle's wheel carries 200 kN; its dynamic peaks 2-3x):
// the first-contact estimate divides by the load, and 1e308 N overflowed the approach.
NumberRule WheelLoadRange() { return Closed(1.0, 1e6); }
// Lateral positions within 100 mm of the profiles' origins or of the centred wheelset: a flange
// is 30 mm high and a gauge 1435 mm; beyond, the profiles no longer meet (as [load] lateral_mm).
NumberRule LateralRange() { return Closed(-100.0, 100.0); }
// Wheelset speeds up to kMaxSpeed_m_s; its pitch velocity within 1e4 rad/s (150 m/s on a 50 mm
// radius is 3000 rad/s): the creepages divide by the speed.
NumberRule PitchVelocityRange() { return Closed(-1e4, 1e4); }
// Longitudinal (traction, braking) forces within 1 MN per wheel (mu Q of the largest load).
NumberRule LongitudinalForceRange() { return Closed(-1e6, 1e6); }
// Wear coefficients (Archard k, the KTH map's k): from 1e-12 (a step of 0.1 mm would take more
// than 1e9 passes: "nothing wears") to 1 (every pass removes its own contact volume).
NumberRule WearCoefficientRange() { return Closed(1e-12, 1.0); }
NumberRule AxleLoadRange() { return Closed(0.1, 40.0); }  // t

const std::vector<std::string_view> kKnownEffects = {"normal", "tangential", "coupling", "wear",
                                                     "damage"};

// Whether the scene lists `effect` (scene.effects, as read by ReadSceneTable).
bool HasEffect(const Scene& scene, std::string_view effect) {
  return std::find(scene.effects.begin(), scene.effects.end(), effect) != scene.effects.end();
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
    if (!known)
      throw InputError(FieldError(t->file(), e, key, "one of " + JoinQuoted(kKnownEffects)));
    if (*name == "tangential" || *name == "damage" || *name == "coupling" || *name == "wear") {
      // damage, coupling and wear need the tractions and slip of the tangential stage
      scene->tangential = true;
      scene->damage = scene->damage || *name == "damage";
      scene->effects.push_back(*name);
      continue;
    }
  }
  if ((scene->damage || HasEffect(*scene, "coupling") || HasEffect(*scene, "wear")) &&
      std::find(scene->effects.begin(), scene->effects.end(), "tangential") ==
          scene->effects.end()) {
    scene->effects.insert(scene->effects.begin() + 1, "tangential");  // implied
  }
  scene->problem.damage = scene->damage;
}

// [model] constants = "fem" | "paper" (a named set; default "fem", issue 17) or
// influence_constants = { ... } | "FILE" (the constants themselves), not both.
void ReadInfluenceConstants(const Fields& model, const std::string& scene_path, Scene* scene) {
  if (model.Has("constants") && model.Has("influence_constants")) {
    model.Fail("influence_constants",
               "either constants (a named set: \"fem\" or \"paper\") or influence_constants "
               "(a table or file), not both");
  }
  if (const auto name = model.Choice("constants", EnumChoices(kInfluenceConstantsNames))) {
    scene->influence_constants_source = *name;
    scene->problem.model.constants =
        NamedInfluenceConstants(*InfluenceConstantsNameFromString(*name));
    return;
  }
  const toml::node* node = model.Node("influence_constants");
  if (node == nullptr) return;
  const std::string expected = std::string("an inline table ") + kInfluenceConstantsExpected +
                               " or the path of a TOML file with [influence_constants]";
  if (const auto file = node->value_exact<std::string>()) {
    const std::string path = ResolveRelativeTo(DirectoryOf(scene_path), *file);
    scene->influence_constants_source = path;
    scene->problem.model.constants = ReadInfluenceConstantsFile(path);
    return;
  }
  const auto t = model.Table("influence_constants", expected);
  scene->influence_constants_source = "inline";
  scene->problem.model.constants = ReadInfluenceConstantsTable(*t);
}

void ReadGeometryAndKernel(const Fields& t, ModelOptions* model) {
  const auto geometry = t.Choice("geometry", EnumChoices(kGeometryModelNames));
  const auto kernel = t.Choice("kernel", EnumChoices(kKernelModelNames));
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
  // geometry/kernel given explicitly: the kind becomes the shorthand they match, else custom.
  model->kind = MatchingModelKind(model->geometry, model->kernel);
}

constexpr double kMinCell_mm = 0.001, kMaxCell_mm = 20.0;

void ReadCellSize(const Fields& t, ModelOptions* model) {
  const toml::node* node = t.Node("cell_mm");
  if (node == nullptr) return;
  // Cells from 1 um (the lateral walk that sizes a patch steps an eighth of a cell, 0.125 um,
  // still a thousand times the profile projections' rounding; grids too fine for memory are
  // refused by the operator's size estimate before that walk, naming cell_mm) to 20 mm (a
  // whole patch in one cell; 1e308 overflowed the operator).
  const std::string expected = fmt::format(
      "two positive numbers [dx, ds] in mm, each in [{}, {}] (the range the numerics bear)",
      kMinCell_mm, kMaxCell_mm);
  const toml::array* a = node->as_array();
  if (a == nullptr || a->size() != 2) t.Fail("cell_mm", expected);
  double v[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    const toml::node& e = *a->get(i);
    if (const auto n = e.value<double>()) v[i] = *n;  // integers convert
    if (!(e.is_number() && std::isfinite(v[i]) && v[i] >= kMinCell_mm && v[i] <= kMaxCell_mm)) {
      t.Fail("cell_mm", expected);
    }
  }
  model->cell_dx_m = v[0] * kMm;
  model->cell_ds_m = v[1] * kMm;
}

// [model] normal_criterion = "pressure-update" | "gap-residual" and normal_tolerance = eps: the
// normal solver's stopping rule (NormalStopCriterion, issue 18 point 4). "pressure-update", the
// default, stops when the last step changed the pressures by at most eps of their RMS over the
// contact set and left the set as it was (CONTACT's criterion; about eps relative in p_max and
// F_n, docs/speed.md), eps = 1e-4 unless given (4 significant digits with margin).
// "gap-residual" is the strict setting: the deformed gap's residual at eps (1e-10 unless given)
// of the largest elastic displacement. Its range: kMinNormalTolerance to kMaxNormalTolerance.

void ReadNormalSolver(const Fields& t, NormalSolverOptions* solver) {
  const std::string pressure_update(ToString(NormalStopCriterion::kPressureUpdate));
  const std::string gap_residual(ToString(NormalStopCriterion::kGapResidual));
  if (const auto c = t.Choice("normal_criterion", {pressure_update, gap_residual})) {
    const NormalSolverOptions chosen =
        *c == gap_residual ? StrictNormalSolverOptions() : NormalSolverOptions{};
    solver->criterion = chosen.criterion;
    solver->tolerance = chosen.tolerance;
  }
  if (const auto v = t.Number("normal_tolerance", Positive(),
                              Closed(kMinNormalTolerance, kMaxNormalTolerance))) {
    solver->tolerance = *v;
  }
}

// [model] tangential_tolerance = eps: the exact tangential solver's stop, the largest change one
// local solve would make to any cell's traction relative to mu p_max (ExactTangentialOptions::
// tolerance; 1e-6 unless given, 4 significant digits of the creep forces with margin,
// docs/speed.md), in kMinExactTangentialTolerance to kMaxExactTangentialTolerance.

void ReadTangentialTolerance(const Fields& t, ContactSetup* setup) {
  if (const auto v = t.Number("tangential_tolerance", Positive(),
                              Closed(kMinExactTangentialTolerance, kMaxExactTangentialTolerance))) {
    setup->tangential_tolerance = *v;
  }
}

void ReadModel(const Fields& top, Scene* scene) {
  ModelOptions& model = scene->problem.model;
  model = MakeModelOptions(ModelKind::kConformal);
  // The evidence-backed constants unless the scene names others (issue 17, docs/models.md).
  model.constants = NamedInfluenceConstants(kDefaultInfluenceConstants);
  scene->influence_constants_source = std::string(ToString(kDefaultInfluenceConstants));
  const auto t = top.Table("model", "a table");
  if (!t) return;
  t->AllowOnly({"kind", "geometry", "kernel", "constants", "influence_constants", "accuracy",
                "cell_mm", "tangential", "pressure_limit", "pressure_limit_MPa", "normal_criterion",
                "normal_tolerance", "tangential_tolerance"});
  if (const auto kind = t->Choice("kind", EnumChoices(kModelKindNames))) {
    const InfluenceConstants constants = model.constants;
    model = MakeModelOptions(*ModelKindFromString(*kind));
    model.constants = constants;
  }
  ReadGeometryAndKernel(*t, &model);
  if (const auto a = t->Choice("accuracy", EnumChoices(kAccuracyPresetNames))) {
    model.accuracy = *AccuracyPresetFromString(*a);
  }
  ReadCellSize(*t, &model);
  if (const auto tan = t->Choice("tangential", EnumChoices(kTangentialMethodNames))) {
    scene->tangential_method = *tan;
    scene->problem.tangential = *TangentialMethodFromString(*tan);
  }
  ReadInfluenceConstants(*t, scene->path, scene);
  ReadNormalSolver(*t, &scene->problem.solver);
  ReadTangentialTolerance(*t, &scene->problem);
}

// [model] pressure_limit = "none" | "hardness", or pressure_limit_MPa = p_lim: the elastic-
// perfectly-plastic limit of the normal solve (docs/contact_plasticity.md). After ReadMaterials
// (the hardness) and ReadModel (the kind).
void ReadPressureLimit(const Fields& top, Scene* scene) {
  const auto t = top.Table("model", "a table");
  if (!t) return;
  PressureLimit& limit = scene->problem.pressure_limit;
  if (t->Has("pressure_limit") && t->Has("pressure_limit_MPa")) {
    t->Fail("pressure_limit_MPa",
            "either pressure_limit (\"none\" or \"hardness\") or pressure_limit_MPa, not both");
  }
  if (const auto name = t->Choice("pressure_limit", EnumChoices(kPressureLimitKindNames))) {
    limit.kind = *name == "hardness" ? PressureLimitKind::kHardness : PressureLimitKind::kNone;
  }
  // Pressures from 1 MPa (far below any steel's yield) to 1e6 MPa.
  if (const auto v = t->Number("pressure_limit_MPa", Positive(), Closed(1.0, 1e6))) {
    limit.kind = PressureLimitKind::kValue;
    limit.value_Pa = *v * kMPa;
  }
  if (limit.kind == PressureLimitKind::kNone) return;
  const std::string_view key =
      limit.kind == PressureLimitKind::kValue ? "pressure_limit_MPa" : "pressure_limit";
  if (scene->problem.model.kind == ModelKind::kHertz) {
    t->Fail(key,
            "no pressure limit with kind = 'hertz' (the analytic ellipse has no plastic cells; use "
            "'halfspace', 'conformal' or 'auto')");
  }
  const auto lim =
      PressureLimitOf(limit, scene->problem.wheel_material, scene->problem.rail_material);
  if (!(lim && *lim > 0.0)) {
    t->Fail(key,
            "a hardness to take the limit from: give materials.rail.hardness_MPa (or "
            "materials.wheel.hardness_MPa), or the limit itself as pressure_limit_MPa");
  }
}

void ReadMaterials(const Fields& top, Scene* scene) {
  scene->problem.wheel_material = DefaultSteel();
  scene->problem.rail_material = DefaultSteel();
  const auto t = top.Table("materials", "a table");
  if (!t) return;
  t->AllowOnly({"wheel", "rail"});
  scene->problem.wheel_material = ReadMaterial(*t, "wheel", MaterialKeys::kWithHardness);
  scene->problem.rail_material = ReadMaterial(*t, "rail", MaterialKeys::kWithDamage);
}

// Loads a profile spec; errors from the profile reader get the scene key in front.
Profile LoadProfileFor(const Fields& t, std::string_view key, BodyRole role,
                       const std::string& spec, const std::string& scene_path) {
  try {
    return LoadProfileSpec(spec, role, DirectoryOf(scene_path));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}:{}: key '{}' = \"{}\": {}", t.file(), LineOf(*t.Node(key)),
                                 t.KeyName(key), spec, e.what()));
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
      t.RequiredNumber("rolling_radius_mm", Positive(), WheelRadiusRange()) * kMm;
  Profile p =
      LoadProfileFor(t, "profile", BodyRole::kWheel, scene->wheel_profile_spec, scene->path);
  if (t.Bool("mirror_y").value_or(false)) p = p.Mirrored();
  scene->problem.wheel_profile = std::move(p);
}

// The rail inclination under `key` ([rail] cant, [track] inclination).
double ReadCant(const Fields& t, Scene* scene, std::string_view key = "cant") {
  const toml::node* node = t.Node(key);
  if (node == nullptr) return 0.0;
  const std::string expected = "a cant ratio \"1:N\" (e.g. \"1:40\") or 0";
  if (const auto i = node->value_exact<int64_t>(); i && *i == 0) return 0.0;
  const auto text = node->value_exact<std::string>();
  if (!text) t.Fail(key, expected);
  scene->cant = *text;
  try {
    return ParseCant(*text);
  } catch (const InputError&) {
    t.Fail(key, expected);
  }
}

void ReadRail(const Fields& top, Scene* scene) {
  const Fields t = RequiredTable(top, "rail", "a [rail] table with profile");
  t.AllowOnly({"profile", "cant", "mirror_y"});
  scene->rail_profile_spec = t.RequiredString("profile", kProfileExpected);
  scene->cant_ratio = ReadCant(t, scene);
  Profile p = LoadProfileFor(t, "profile", BodyRole::kRail, scene->rail_profile_spec, scene->path);
  if (t.Bool("mirror_y").value_or(false)) p = p.Mirrored();
  if (HasEffect(*scene, "wear")) {
    // A wear run cants each worn profile itself (with the motion of the unworn one).
    scene->wear.emplace().rail_profile = p;
  }
  if (scene->cant_ratio != 0.0) p = ApplyCant(p, scene->cant_ratio);
  scene->problem.rail_profile = std::move(p);
}

// [track] of a wear scene (issue 15): both rails, each in its own rail frame, and their
// inclination; replaces [rail]. The one place the wear scene's track is read (curve radius,
// superelevation and gauge are added here when vehicles run on it).
void ReadTrackTable(const Fields& top, Scene* scene) {
  const Fields t = RequiredTable(top, "track", "a [track] table with high_rail");
  t.AllowOnly({"high_rail", "low_rail", "inclination", "gauge_mm", "gauge_height_mm", "radius_m",
               "cant_mm"});
  scene->rail_profile_spec = t.RequiredString("high_rail", kProfileExpected);
  scene->low_rail_profile_spec = t.String("low_rail").value_or(scene->rail_profile_spec);
  scene->cant_ratio = ReadCant(t, scene, "inclination");
  Profile high =
      LoadProfileFor(t, "high_rail", BodyRole::kRail, scene->rail_profile_spec, scene->path);
  Profile low = LoadProfileFor(t, t.Has("low_rail") ? "low_rail" : "high_rail", BodyRole::kRail,
                               scene->low_rail_profile_spec, scene->path);
  // A wear run cants each worn profile itself (with the motion of the unworn one).
  WearStudy& study = scene->wear.emplace();
  study.rail_profile = high;
  study.low_rail_profile = std::move(low);
  // The track's gauge and curve, for vehicle traffic (a curve turns toward the low rail).
  study.track.gauge_m = t.Number("gauge_mm", InRange(1000.0, 1700.0)).value_or(1435.0) * kMm;
  study.track.gauge_height_m = t.Number("gauge_height_mm", InRange(0.0, 30.0)).value_or(14.0) * kMm;
  // Curves from R 50 m (a tram's tightest) to 100 km (tangent track within the curving's
  // tolerance): 1e308 m gave a curvature below the smallest double's resolution of the forces.
  study.curve.radius_m = t.Number("radius_m", AtLeast(50.0), Closed(50.0, 1e5)).value_or(0.0);
  study.curve.cant_m = t.Number("cant_mm", InRange(0.0, 250.0)).value_or(0.0) * kMm;
  if (scene->cant_ratio != 0.0) high = ApplyCant(high, scene->cant_ratio);
  scene->problem.rail_profile = std::move(high);
}

// [load] creepage = { xi, eta, spin_per_mm }: prescribed creepages instead of kinematics.
Creepage ReadCreepage(const Fields& load) {
  const auto t = load.Table("creepage", "an inline table { xi, eta, spin_per_mm }");
  t->AllowOnly({"xi", "eta", "spin_per_mm"});
  Creepage c;
  c.xi = t->Number("xi", InRange(-1.0, 1.0)).value_or(0.0);
  c.eta = t->Number("eta", InRange(-1.0, 1.0)).value_or(0.0);
  // Spin up to 0.1 /mm: sin(contact angle) / r is 2e-3 /mm at a 90 degree flange on a 460 mm
  // wheel, and the tangential solvers' slip grows with spin times the patch size.
  c.spin_per_m = t->Number("spin_per_mm", AnyFinite(), Closed(-0.1, 0.1)).value_or(0.0) / kMm;
  return c;
}

// The rolling keys shared by the single wheel ([load]) and the wheelset ([wheelset]).
void ReadMotion(const Fields& t, Scene* scene) {
  if (const auto v = t.Number("speed_m_s", AtLeast(0.0), Closed(0.0, kMaxSpeed_m_s))) {
    scene->speed_m_s = *v;
  }
  // As for traffic: yaw is tens of milliradians; the yawed outline needs |yaw| < 0.5 rad.
  if (const auto yaw = t.Number("yaw_mrad", InRange(-kMaxYaw_mrad, kMaxYaw_mrad))) {
    scene->problem.placement.yaw_rad = *yaw * 1e-3;
  }
  scene->motion.pitch_velocity_rad_s =
      t.Number("pitch_velocity_rad_s", AnyFinite(), PitchVelocityRange());
  scene->longitudinal_force_N =
      t.Number("longitudinal_force_N", AnyFinite(), LongitudinalForceRange());
  if (scene->longitudinal_force_N && t.Has("pitch_velocity_rad_s")) {
    t.Fail("longitudinal_force_N",
           "either longitudinal_force_N or pitch_velocity_rad_s (the force sets the pitch "
           "velocity), not both");
  }
}

// [load] lateral_mm (and the reference track and wheelset beside it): the wheel's lateral
// position from the centred wheelset, the alternative to lateral_shift_mm. The wheel is placed
// once the rail is read (PlaceFromCentre).
void ReadCentredPlacement(const Fields& t, Scene* scene) {
  constexpr std::string_view kReference[] = {"gauge_mm", "gauge_height_mm",
                                             "flange_back_distance_mm", "flange_back_position_mm"};
  if (!t.Has("lateral_mm")) {
    for (const std::string_view key : kReference) {
      if (t.Has(key)) {
        t.Fail(key,
               "no reference wheelset without 'load.lateral_mm' (it only sets where "
               "lateral_mm = 0 lies)");
      }
    }
    return;
  }
  if (t.Has("lateral_shift_mm")) {
    t.Fail("lateral_shift_mm",
           "either lateral_mm (from the centred wheelset) or lateral_shift_mm (the wheel "
           "profile's origin from the rail's), not both");
  }
  Scene::CentredPlacement c;
  c.lateral_m = t.RequiredNumber("lateral_mm", Closed(-100.0, 100.0)) * kMm;
  c.track.gauge_m = t.Number("gauge_mm", InRange(1000.0, 1700.0)).value_or(1435.0) * kMm;
  c.track.gauge_height_m = t.Number("gauge_height_mm", InRange(0.0, 30.0)).value_or(14.0) * kMm;
  c.wheelset.flange_back_distance_m = t.Number("flange_back_distance_mm", InRange(900.0, 1700.0))
                                          .value_or(c.wheelset.flange_back_distance_m / kMm) *
                                      kMm;
  c.wheelset.flange_back_position_m = t.Number("flange_back_position_mm", InRange(-200.0, 200.0))
                                          .value_or(c.wheelset.flange_back_position_m / kMm) *
                                      kMm;
  scene->centred = c;
}

// The wheel of [load] lateral_mm placed as the right wheel of the reference wheelset displaced
// by lateral_mm (with the wheel's yaw and roll) on the scene's rail, cant applied: the wheelset
// code's placement (core/geometry/wheelset.h), so 0 is the centred wheelset on that gauge.
void PlaceFromCentre(const Fields& top, Scene* scene) {
  if (!scene->centred) return;
  Scene::CentredPlacement& c = *scene->centred;
  WheelPlacement& placement = scene->problem.placement;
  WheelsetSpec ws = c.wheelset;
  ws.yaw_rad = placement.yaw_rad;
  ws.roll_rad = placement.roll_rad;
  ws.rolling_radius_m = placement.rolling_radius_m;
  ws.lateral_displacement_m = 0.0;  // the centred wheelset; lateral_mm is added below
  try {
    c.centred_shift_m =
        PlaceWheelset(scene->problem.rail_profile, c.track, ws).right.lateral_shift_m;
  } catch (const InputError& e) {
    const Fields t = RequiredTable(top, "load", "a [load] table");
    t.Fail("lateral_mm", fmt::format("a rail that has a gauge point: {}", e.what()));
  }
  placement.lateral_shift_m = c.centred_shift_m + c.lateral_m;
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
  t.AllowOnly({"vertical_N", "approach_mm", "lateral_shift_mm", "roll_rad", "friction", "speed_m_s",
               "yaw_mrad", "pitch_velocity_rad_s", "longitudinal_force_N", "creepage", "lateral_mm",
               "gauge_mm", "gauge_height_mm", "flange_back_distance_mm",
               "flange_back_position_mm"});
  ContactLoad& load = scene->problem.load;
  load.vertical_force_N = t.Number("vertical_N", Positive(), WheelLoadRange());
  // Approaches from 1 nm (the first-contact search's tolerance is 0.1 nm) to 1 mm (ten times a
  // heavy wheel's on the tread; 1e308 mm overflowed the potential area).
  if (const auto a = t.Number("approach_mm", Positive(), Closed(1e-6, 1.0))) {
    load.approach_m = *a * kMm;
  }
  if (load.vertical_force_N && load.approach_m) {
    t.Fail("approach_mm", "exactly one of 'load.vertical_N' and 'load.approach_mm' (both given)");
  }
  if (!load.vertical_force_N && !load.approach_m) {
    t.FailMissing("vertical_N", "exactly one of 'load.vertical_N' and 'load.approach_mm'");
  }
  WheelPlacement& placement = scene->problem.placement;
  placement.lateral_shift_m =
      t.Number("lateral_shift_mm", AnyFinite(), LateralRange()).value_or(0.0) * kMm;
  ReadCentredPlacement(t, scene);
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
    top.Fail("track", "a [wheelset] table next to [track] (a track alone places nothing)");
  }
  if (!ws) return;
  TrackSpec tr;
  if (track) {
    track->AllowOnly({"gauge_mm", "gauge_height_mm"});
    // As [load]'s reference track: metre to broad gauges, the gauge point within the flange.
    tr.gauge_m =
        track->Number("gauge_mm", Positive(), InRange(1000.0, 1700.0)).value_or(tr.gauge_m / kMm) *
        kMm;
    tr.gauge_height_m = track->Number("gauge_height_mm", AtLeast(0.0), InRange(0.0, 30.0))
                            .value_or(tr.gauge_height_m / kMm) *
                        kMm;
  }
  ws->AllowOnly({"flange_back_distance_mm", "flange_back_position_mm", "lateral_displacement_mm",
                 "yaw_mrad", "roll_rad", "vertical_load_per_wheel_N", "speed_m_s",
                 "pitch_velocity_rad_s", "longitudinal_force_N"});
  WheelsetSpec w;
  w.flange_back_distance_m =
      ws->Number("flange_back_distance_mm", Positive(), InRange(900.0, 1700.0))
          .value_or(w.flange_back_distance_m / kMm) *
      kMm;
  w.flange_back_position_m =
      ws->Number("flange_back_position_mm", AnyFinite(), InRange(-200.0, 200.0))
          .value_or(w.flange_back_position_m / kMm) *
      kMm;
  w.lateral_displacement_m =
      ws->Number("lateral_displacement_mm", AnyFinite(), LateralRange()).value_or(0.0) * kMm;
  w.roll_rad = ws->Number("roll_rad", InRange(-kMaxRoll_rad, kMaxRoll_rad)).value_or(0.0);
  w.rolling_radius_m = scene->problem.placement.rolling_radius_m;
  ReadMotion(*ws, scene);
  w.yaw_rad = scene->problem.placement.yaw_rad;
  if (scene->creepage &&
      (ws->Has("yaw_mrad") || ws->Has("pitch_velocity_rad_s") || ws->Has("longitudinal_force_N"))) {
    ws->Fail(ws->Has("yaw_mrad")               ? "yaw_mrad"
             : ws->Has("pitch_velocity_rad_s") ? "pitch_velocity_rad_s"
                                               : "longitudinal_force_N",
             "no wheelset motion next to prescribed creepages in [load]");
  }
  scene->problem.load = {};
  scene->problem.load.vertical_force_N =
      ws->RequiredNumber("vertical_load_per_wheel_N", Positive(), WheelLoadRange());
  scene->track = tr;
  scene->wheelset = w;
}

// Rolling contact needs a friction coefficient and a speed, and a model with a grid.
void CheckRolling(const Fields& top, const Scene& scene) {
  if (!scene.tangential) return;
  if (const auto model = top.Table("model", "a table")) {
    // kind = "hertz" rolls on the fast tread path (core/contact/hertz_tread.h, a single wheel or
    // both wheels of a wheelset, docs/library.md): not with coupling.
    if (scene.problem.model.kind == ModelKind::kHertz && HasEffect(scene, "coupling")) {
      model->Fail("kind",
                  "\"halfspace\", \"conformal\" or \"auto\" with the coupling effect (the hertz "
                  "model rolls only on the fast tread path, without coupling)");
    }
  }
  if (scene.damage && !(scene.problem.rail_material.shear_yield_Pa > 0)) {
    throw InputError(fmt::format(
        "{}:{}: key 'materials.rail.shear_yield_MPa' is missing: expected {}", top.file(),
        top.Has("materials") ? LineOf(*top.Node("materials")) : 1, kShearYieldExpected));
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

// ---- wear scenes: [wear] and [[traffic]] ----

// The KTH map's keys: coefficients as Archard's k; slip velocities up to kMaxSpeed_m_s from
// 1 um/s (the continuous map blends in ln v_s); p/H ratios and the blends' half-widths from
// 1e-3 (a band of 1e-300 divided the blend by nothing) to 10.
NumberRule KthRange(std::string_view key) {
  if (key.starts_with("kth_k_")) return WearCoefficientRange();
  if (key.ends_with("_m_s")) return Closed(1e-6, kMaxSpeed_m_s);
  return Closed(1e-3, 10.0);
}

WearLaw ReadWearLaw(const Fields& t) {
  WearLaw law;
  if (const auto name = t.Choice("law", EnumChoices(kWearLawKindNames))) {
    law.kind = *WearLawKindFromString(*name);
  }
  law.archard_k = t.Number("k", Positive(), WearCoefficientRange()).value_or(law.archard_k);
  if (t.Has("k") && law.kind != WearLawKind::kArchard) {
    t.Fail("k", "no 'k' with this law (the constant coefficient belongs to law = \"archard\")");
  }
  const bool kth = law.kind == WearLawKind::kKth || law.kind == WearLawKind::kKthContinuous;
  const std::vector<std::pair<std::string_view, double*>> kth_keys = {
      {"kth_k_seizure", &law.kth_k_seizure},
      {"kth_k_mild_low", &law.kth_k_mild_low},
      {"kth_k_severe", &law.kth_k_severe},
      {"kth_k_mild_high", &law.kth_k_mild_high},
      {"kth_v1_m_s", &law.kth_v1_m_s},
      {"kth_v2_m_s", &law.kth_v2_m_s},
      {"kth_pressure_ratio", &law.kth_pressure_ratio},
      {"kth_velocity_band", &law.kth_velocity_band},
      {"kth_pressure_band", &law.kth_pressure_band}};
  for (const auto& [key, value] : kth_keys) {
    if (!t.Has(key)) continue;
    if (!kth) t.Fail(key, "KTH map keys only with law = \"kth\" or \"kth-continuous\"");
    *value = t.RequiredNumber(key, Positive(), KthRange(key));
  }
  if (law.kth_v1_m_s >= law.kth_v2_m_s) {
    t.Fail("kth_v2_m_s", fmt::format("a speed above kth_v1_m_s = {}", law.kth_v1_m_s));
  }
  if (t.Has("density_kg_m3")) {
    if (law.kind != WearLawKind::kUsfd) t.Fail("density_kg_m3", "density only with law = \"usfd\"");
    // Densities from 1000 kg/m^3 to 30 000 (steel 7850, tungsten 19 300).
    law.density_kg_m3 = t.RequiredNumber("density_kg_m3", Positive(), Closed(1000.0, 3e4));
  }
  return law;
}

// [wear.conditions.NAME] overrides (friction, archard_factor, kth_factor, usfd_factor) and
// [wear] gauge_face_angle_deg (wear/friction_condition.h).
void ReadFrictionConditions(const Fields& t, FrictionConditions* conditions) {
  const NumberRule below_right_angle{[](double v) { return v > 0.0 && v < 90.0; },
                                     "an angle in (0, 90) degrees"};
  if (const auto angle = t.Number("gauge_face_angle_deg", below_right_angle)) {
    conditions->gauge_face_angle_rad = *angle * std::numbers::pi / 180.0;
  }
  const auto table = t.Table("conditions", "a table of friction conditions by name");
  if (!table) return;
  table->AllowOnly(EnumChoices(kFrictionConditionNames));
  for (const auto& entry : kFrictionConditionNames) {
    const auto c =
        table->Table(entry.name, "a table { friction, archard_factor, kth_factor, usfd_factor }");
    if (!c) continue;
    c->AllowOnly({"friction", "archard_factor", "kth_factor", "usfd_factor"});
    FrictionConditionParams& p = (*conditions)[entry.value];
    p.friction = c->Number("friction", OpenClosed(0.0, 2.0)).value_or(p.friction);
    p.archard_factor =
        c->Number("archard_factor", OpenClosed(0.0, 10.0)).value_or(p.archard_factor);
    p.kth_factor = c->Number("kth_factor", OpenClosed(0.0, 10.0)).value_or(p.kth_factor);
    p.usfd_factor = c->Number("usfd_factor", OpenClosed(0.0, 10.0)).value_or(p.usfd_factor);
  }
}

void ReadWearTable(const Fields& top, Scene* scene) {
  const Fields t = RequiredTable(top, "wear", "a [wear] table (law, total_passes or total_MGT)");
  t.AllowOnly({"law",
               "k",
               "kth_k_seizure",
               "kth_k_mild_low",
               "kth_k_severe",
               "kth_k_mild_high",
               "kth_v1_m_s",
               "kth_v2_m_s",
               "kth_pressure_ratio",
               "kth_velocity_band",
               "kth_pressure_band",
               "density_kg_m3",
               "conditions",
               "gauge_face_angle_deg",
               "max_depth_per_step_mm",
               "time_step",
               "total_passes",
               "total_MGT",
               "quadrature_points",
               "integration_tolerance",
               "spread_rule",
               "spread_nodes",
               "bin_mm",
               "profile_spacing_mm",
               "smoothing_mm",
               "damage_layer_mm",
               "threads",
               "db"});
  WearOptions& o = scene->wear->options;
  o.law = ReadWearLaw(t);
  ReadFrictionConditions(t, &o.conditions);
  // Steps from 1 um of depth (below it the step count grows without a change the profile's
  // 10 um bins and resampling can show: 1e-300 mm meant endless steps) to 1 mm.
  o.max_depth_per_step_m = t.Number("max_depth_per_step_mm", OpenClosed(0.0, 1.0), Closed(0.001, 1.0))
                               .value_or(o.max_depth_per_step_m / kMm) *
                           kMm;
  // The time step (WearTimeStep): "euler" (the default) or "heun".
  if (const auto step = t.Choice("time_step", EnumChoices(kWearTimeStepNames))) {
    o.time_step = *EnumFromString(kWearTimeStepNames, *step);
  }
  // A rail's life is of the order of 1000 MGT (1e8 axle passes): ten times that is the bound.
  o.total_passes = t.Number("total_passes", OpenClosed(0.0, 1e9));
  o.total_mgt = t.Number("total_MGT", OpenClosed(0.0, 1e4));
  if (o.total_passes && o.total_mgt) {
    t.Fail("total_MGT", "exactly one of 'wear.total_passes' and 'wear.total_MGT' (both given)");
  }
  if (!o.total_passes && !o.total_mgt) {
    t.FailMissing("total_passes", "exactly one of 'wear.total_passes' and 'wear.total_MGT'");
  }
  const auto whole = [&](std::string_view key, double lo, double hi, int fallback) {
    const auto v = t.Number(key, InRange(lo, hi + 1.0));
    if (!v) return fallback;
    if (*v != std::floor(*v)) t.Fail(key, fmt::format("a whole number from {} to {}", lo, hi));
    return static_cast<int>(*v);
  };
  o.quadrature_points = whole("quadrature_points", 1, kMaxQuadraturePoints, o.quadrature_points);
  // The spread rule (wear/spread_integration.h, SpreadRule): spread_rule names it; without it,
  // fixed Gauss-Hermite nodes when the scene gives quadrature_points, else the adaptive rule at
  // its tolerance (default kDefaultIntegrationTolerance), as every scene before spread_rule.
  // Each rule's own key: integration_tolerance (adaptive), quadrature_points (gauss_hermite),
  // spread_nodes (piecewise_linear, required); another rule's key is an error.
  const std::optional<double> tolerance =
      t.Number("integration_tolerance", Closed(kMinIntegrationTolerance, kMaxIntegrationTolerance));
  const std::optional<std::string> rule_name =
      t.Choice("spread_rule", EnumChoices(kSpreadRuleNames));
  SpreadRule rule = t.Has("quadrature_points") ? SpreadRule::kGaussHermite : SpreadRule::kAdaptive;
  if (rule_name) rule = *EnumFromString(kSpreadRuleNames, *rule_name);
  const auto refuse = [&](std::string_view key, SpreadRule owner) {
    if (!t.Has(key) || rule == owner) return;
    if (rule_name) {
      t.Fail(key, fmt::format("no '{}' with spread_rule = \"{}\" (it is the \"{}\" rule's key)",
                              key, ToString(rule), ToString(owner)));
    }
    if (owner == SpreadRule::kPiecewiseLinear) {
      t.Fail(key, "spread_rule = \"piecewise_linear\" beside it (its node count)");
    }
    t.Fail("integration_tolerance",
           "either 'wear.quadrature_points' (the fixed Gauss-Hermite rule) or "
           "'wear.integration_tolerance' (the adaptive rule), not both");
  };
  refuse("integration_tolerance", SpreadRule::kAdaptive);
  refuse("quadrature_points", SpreadRule::kGaussHermite);
  refuse("spread_nodes", SpreadRule::kPiecewiseLinear);
  if (rule == SpreadRule::kAdaptive) {
    o.integration_tolerance = tolerance.value_or(kDefaultIntegrationTolerance);
  } else if (rule == SpreadRule::kPiecewiseLinear) {
    const std::string expected = fmt::format(
        "a multiple of 8 from {} to {} (the piecewise-linear rule's nodes within +-3 "
        "std; m/8 more in each tail)",
        kMinLinearSpreadNodes, kMaxLinearSpreadNodes);
    if (!t.Has("spread_nodes")) t.FailMissing("spread_nodes", expected);
    const int m = whole("spread_nodes", kMinLinearSpreadNodes, kMaxLinearSpreadNodes, 0);
    if (m % 8 != 0) t.Fail("spread_nodes", expected);
    o.spread_nodes = LinearSpreadNodes(m);
  }
  o.threads = whole("threads", 0, 256, o.threads);
  // Bins and profile points finer than 10 um are below every contact grid (the finest preset's
  // cells are tenths of a millimetre): the depth per bin becomes noise and the profile huge.
  o.bin_m = t.Number("bin_mm", Closed(0.01, 1.0)).value_or(o.bin_m / kMm) * kMm;
  o.profile_spacing_m =
      t.Number("profile_spacing_mm", Closed(0.01, 2.0)).value_or(o.profile_spacing_m / kMm) * kMm;
  o.smoothing.smoothing_length_m = t.Number("smoothing_mm", OpenClosed(0.0, 20.0))
                                       .value_or(o.smoothing.smoothing_length_m / kMm) *
                                   kMm;
  // A layer from 1 um to 10 mm (the old rule's 0.5 mm; dz / 1e-300 overflowed).
  if (const auto layer_mm = t.Number("damage_layer_mm", Positive(), Closed(1e-3, 10.0))) {
    o.damage_layer_m = *layer_mm * kMm;
  }
  if (const auto db = t.String("db")) {
    scene->wear_db = ResolveRelativeTo(DirectoryOf(scene->path), *db);
  }
}

// lateral_shift_mm = 5.0 or { mean = 5.0, std = 1.5 }
void ReadLateralShift(const Fields& t, TrafficCase* c) {
  const toml::node* node = t.Node("lateral_shift_mm");
  if (node == nullptr) {
    t.FailMissing("lateral_shift_mm", "a lateral shift in mm, or { mean, std }");
  }
  if (node->is_table()) {
    const auto d = t.Table("lateral_shift_mm", "{ mean, std }");
    d->AllowOnly({"mean", "std"});
    c->lateral_shift_mean_m = d->RequiredNumber("mean", AnyFinite(), LateralRange()) * kMm;
    // As a vehicle entry's lateral_spread_mm: the spread's nodes reach 3-5 std.
    c->lateral_shift_std_m = d->Number("std", AtLeast(0.0), Closed(0.0, 20.0)).value_or(0.0) * kMm;
    return;
  }
  c->lateral_shift_mean_m = t.RequiredNumber("lateral_shift_mm", AnyFinite(), LateralRange()) * kMm;
}

// [curving] (issue 15): how the vehicles' steady-state curving is solved. predictor: the cold
// solve's predictor (CurvingOptions::cold_predictor): "model" (the draft grid) or "table" (the
// contact table, docs/curving.md "The table predictor"). warm_contact: each wheelset's contact
// solves start from its last one in the full model's phases (CurvingOptions::warm_contact,
// docs/curving.md "Kept placements and warm contact solves"). Absent, each: the table and warm
// contact solves at standard accuracy and finer, the model predictor and cold contact solves at
// draft (CurvingOptions::ColdPredictorFor, WarmContactFor). Only beside [[vehicle]] tables.
void ReadCurvingTable(const Fields& top, Scene* scene) {
  const auto t = top.Table("curving", "a table { predictor, warm_contact }");
  if (!t) return;
  t->AllowOnly({"predictor", "warm_contact"});
  if (scene->wear->vehicles.empty()) {
    top.Fail("curving",
             "a [curving] table only beside [[vehicle]] tables (it sets how their curving is "
             "solved)");
  }
  if (const auto name = t->Choice("predictor", EnumChoices(kCurvingPredictorNames))) {
    scene->wear->curving_predictor = *EnumFromString(kCurvingPredictorNames, *name);
  }
  scene->wear->curving_warm_contact = t->Bool("warm_contact");
}

// [[vehicle]]: the vehicles that vehicle traffic names (core/vehicle/vehicle.h). Units as in
// the literature: stiffnesses in MN/m and kN m/rad, lengths in m, profile positions in mm.
void ReadVehicles(const Fields& top, Scene* scene) {
  const std::vector<Fields> tables =
      ArrayOfTables(top, "vehicle", "[[vehicle]] tables, one per vehicle");
  if (!tables.empty() && !top.Has("track")) {
    tables.front().Fail("name",
                        "no [[vehicle]] without a [track] table (a vehicle runs on both "
                        "rails of a track)");
  }
  for (const Fields& t : tables) {
    t.AllowOnly({"name", "source", "kind", "axle_load_t", "wheel_profile", "mirror_y",
                 "rolling_radius_mm", "flange_back_distance_mm", "flange_back_position_mm",
                 "wheelbase_m", "bogie_spacing_m", "primary_kx_MN_m", "primary_ky_MN_m",
                 "primary_semi_spacing_m", "secondary_ky_MN_m", "secondary_yaw_kNm_rad",
                 "cg_height_m", "traction_kN_per_axle"});
    VehicleSpec v;
    v.name = t.RequiredString("name", "the vehicle's name, which [[traffic]] entries use");
    for (const VehicleSpec& other : scene->wear->vehicles) {
      if (other.name == v.name) t.Fail("name", "a name no other [[vehicle]] has");
    }
    v.source = t.String("source").value_or("");
    if (const auto kind = t.Choice("kind", EnumChoices(kVehicleKindNames))) {
      v.kind = *EnumFromString(kVehicleKindNames, *kind);
    }
    // Axle loads from 0.1 t (below any rail vehicle's; 1e-300 t left the wheels no load) to 40 t.
    v.axle_load_N =
        t.RequiredNumber("axle_load_t", OpenClosed(0.0, 40.0), AxleLoadRange()) * 1000.0 * kGravity_m_s2;
    if (const auto spec = t.String("wheel_profile")) {
      Profile p = LoadProfileFor(t, "wheel_profile", BodyRole::kWheel, *spec, scene->path);
      if (t.Bool("mirror_y").value_or(false)) p = p.Mirrored();
      v.wheel_profile = std::move(p);
    } else if (top.Has("wheel")) {
      v.wheel_profile = scene->problem.wheel_profile;
    } else {
      t.FailMissing("wheel_profile", std::string(kProfileExpected) + " (or a [wheel] table)");
    }
    v.rolling_radius_m = t.Number("rolling_radius_mm", Positive(), WheelRadiusRange())
                             .value_or(scene->problem.placement.rolling_radius_m / kMm) *
                         kMm;
    v.flange_back_distance_m =
        t.Number("flange_back_distance_mm", InRange(1000.0, 1700.0)).value_or(1360.0) * kMm;
    v.flange_back_position_m =
        t.Number("flange_back_position_mm", InRange(-200.0, 0.0)).value_or(-70.0) * kMm;
    v.cg_height_m = t.Number("cg_height_m", InRange(0.0, 5.0)).value_or(v.cg_height_m);
    // Traction or braking within 500 kN per axle (mu Q of a 40 t axle is about 240 kN).
    v.traction_N_per_axle =
        t.Number("traction_kN_per_axle", AnyFinite(), Closed(-500.0, 500.0)).value_or(0.0) * 1e3;
    if (v.kind == VehicleKind::kBogie) {
      v.wheelbase_m = t.RequiredNumber("wheelbase_m", OpenClosed(0.0, 10.0));
      v.bogie_spacing_m = t.RequiredNumber("bogie_spacing_m", OpenClosed(0.0, 40.0));
      // Suspension stiffnesses over eight decades around the literature's (primary 1-100 MN/m,
      // secondary lateral 0.1-5 MN/m, secondary yaw 100-5000 kN m/rad): the equilibrium's
      // Jacobian adds them to the contact's (1e7-1e8 N/m), so 1e308 made it singular.
      v.primary_kx_N_m = t.RequiredNumber("primary_kx_MN_m", Positive(), Closed(1e-3, 1e4)) * 1e6;
      v.primary_ky_N_m = t.RequiredNumber("primary_ky_MN_m", Positive(), Closed(1e-3, 1e4)) * 1e6;
      v.primary_semi_spacing_m = t.RequiredNumber("primary_semi_spacing_m", OpenClosed(0.0, 2.0));
      v.secondary_ky_N_m =
          t.RequiredNumber("secondary_ky_MN_m", Positive(), Closed(1e-4, 1e3)) * 1e6;
      v.secondary_yaw_Nm_rad =
          t.RequiredNumber("secondary_yaw_kNm_rad", Positive(), Closed(1e-2, 1e6)) * 1e3;
    }
    try {
      ValidateVehicle(v, fmt::format("vehicle \"{}\"", v.name));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}:{}: {}", t.file(), t.Line(), e.what()));
    }
    scene->wear->vehicles.push_back(std::move(v));
  }
}

// An entry's friction conditions (wear/friction_condition.h) and its top-of-rail mu: `friction`
// when given, else its condition's. `required`: an entry without either is refused (a
// collective whose every bin has mu needs neither).
void ReadEntryFriction(const Fields& t, const FrictionConditions& conditions, bool required,
                       TrafficCase* c) {
  const std::vector<std::string_view> names = EnumChoices(kFrictionConditionNames);
  if (const auto n = t.Choice("condition", names)) {
    c->condition = *FrictionConditionFromString(*n);
  }
  if (const auto n = t.Choice("gauge_face_condition", names)) {
    c->gauge_face_condition = *FrictionConditionFromString(*n);
  }
  if (const auto mu = t.Number("friction", OpenClosed(0.0, 2.0))) {
    c->friction = *mu;
  } else if (c->condition) {
    c->friction = conditions[*c->condition].friction;
  } else if (required) {
    t.FailMissing("friction",
                  "a friction coefficient in (0, 2], or a condition (\"dry\", \"wet\", "
                  "\"lubricated\" or \"friction_modified\") whose mu it takes");
  }
}

void ReadWheelWear(const Fields& t, const Scene& scene, TrafficCase* c);

// A [[traffic]] entry that names a vehicle: its wheels and positions come from curving.
void ReadVehicleTraffic(const Fields& t, Scene* scene, TrafficCase* c) {
  if (t.Has("wheel_population")) {
    t.Fail("wheel_population",
           "no wheel population on a vehicle entry (a vehicle's wheels are its own, [[vehicle]] "
           "wheel_profile; wheel_wear wears them): use a prescribed or collective entry");
  }
  t.AllowOnly({"name", "vehicle", "speed_m_s", "friction", "condition", "gauge_face_condition",
               "share", "lateral_spread_mm", "wheel_wear"});
  const std::string name = t.RequiredString("vehicle", "the name of a [[vehicle]]");
  const std::vector<VehicleSpec>& vehicles = scene->wear->vehicles;
  for (int i = 0; i < static_cast<int>(vehicles.size()); ++i) {
    if (vehicles[i].name == name) c->vehicle = i;
  }
  if (c->vehicle < 0) {
    std::vector<std::string_view> names;
    for (const VehicleSpec& v : vehicles) names.push_back(v.name);
    t.Fail("vehicle", names.empty() ? std::string("a [[vehicle]] table of that name")
                                    : "one of " + JoinQuoted(names));
  }
  const VehicleSpec& v = vehicles[c->vehicle];
  c->wheel_profile = v.wheel_profile;
  c->rolling_radius_m = v.rolling_radius_m;
  c->axle_load_t = v.axle_load_N / kGravity_m_s2 / 1000.0;
  c->vertical_force_N = 0.5 * v.axle_load_N;  // static; curving sets each wheel's load
  c->lateral_shift_std_m = t.Number("lateral_spread_mm", Closed(0.0, 20.0)).value_or(0.0) * kMm;
  ReadEntryFriction(t, scene->wear->options.conditions, /*required=*/true, c);
  c->speed_m_s = t.RequiredNumber("speed_m_s", OpenClosed(0.0, kMaxSpeed_m_s));
  c->share = t.Number("share", OpenClosed(0.0, kMaxShare)).value_or(1.0);
  ReadWheelWear(t, *scene, c);  // co-evolution: every wheel of every wheelset wears
}

// The wheel of a prescribed or collective entry: its profile and rolling radius (from the
// entry, else from the scene's [wheel]).
void ReadTrafficWheel(const Fields& t, Scene* scene, bool has_wheel, TrafficCase* c) {
  if (t.Has("wheel_population")) {
    // The wheels come from the population (ReadWheelPopulation), each with its own radius or
    // the entry's.
    if (t.Has("wheel_profile")) {
      t.Fail("wheel_population", "either wheel_profile or wheel_population, not both");
    }
    return;
  }
  if (const auto spec = t.String("wheel_profile")) {
    Profile p = LoadProfileFor(t, "wheel_profile", BodyRole::kWheel, *spec, scene->path);
    if (t.Bool("mirror_y").value_or(false)) p = p.Mirrored();
    c->wheel_profile = std::move(p);
  } else if (has_wheel) {
    c->wheel_profile = scene->problem.wheel_profile;
  } else {
    t.FailMissing("wheel_profile", std::string(kProfileExpected) + " (or a [wheel] table)");
  }
  if (const auto r = t.Number("rolling_radius_mm", Positive(), WheelRadiusRange())) {
    c->rolling_radius_m = *r * kMm;
  } else if (has_wheel) {
    c->rolling_radius_m = scene->problem.placement.rolling_radius_m;
  } else {
    t.FailMissing("rolling_radius_mm",
                  "the wheel radius at the profile's z = 0 in mm (or a [wheel] table)");
  }
}

// [[traffic]] wheel_wear = { distance_per_pass_m, grade or hardness_MPa }: the entry's wheel wears
// with the rail (co-evolution, wear/wheel_wear.h). After ReadMaterials and ReadWearTable.
void ReadWheelWear(const Fields& t, const Scene& scene, TrafficCase* c) {
  const auto w = t.Table("wheel_wear",
                         "an inline table { distance_per_pass_m, grade or hardness_MPa }");
  if (!w) return;
  if (scene.wear->options.time_step == WearTimeStep::kHeun) {
    // Heun's predictor moves the rails only (wear/wear_simulation.h; ValidateWearStudy).
    t.Fail("wheel_wear",
           "no wheel_wear with time_step = \"heun\" (its predictor moves the rails only): "
           "time_step = \"euler\" for an entry whose wheels wear");
  }
  w->AllowOnly({"distance_per_pass_m", "grade", "hardness_MPa"});
  WheelWear wear;
  // Up to 1e7 m (10 000 km) per pass.
  wear.distance_per_pass_m =
      w->RequiredNumber("distance_per_pass_m", Positive(), OpenClosed(0.0, 1e7));
  if (w->Has("grade") && w->Has("hardness_MPa")) {
    w->Fail("hardness_MPa", "either grade or hardness_MPa, not both");
  }
  if (const auto grade = w->Choice("grade", EnumChoices(kWheelGradeNames))) {
    wear.hardness_Pa = WheelGradeOf(*WheelGradeFromString(*grade)).hardness_Pa;
  }
  if (const auto h = w->Number("hardness_MPa", Positive(), Closed(1.0, 1e6))) {
    wear.hardness_Pa = *h * kMPa;
  }
  const WearLawKind law = scene.wear->options.law.kind;
  if (!wear.hardness_Pa && law != WearLawKind::kUsfd &&
      !(scene.problem.wheel_material.hardness_Pa > 0.0)) {
    w->FailMissing("hardness_MPa",
                   fmt::format("the wheel's hardness for the {} law: materials.wheel.hardness_MPa "
                               "or grade (\"R7\", \"R8\"), or wheel_wear.grade or hardness_MPa",
                               ToString(law)));
  }
  c->wheel_wear = wear;
}

// One wheel of a population: { name, profile, weight, rolling_radius_mm, mirror_y }; profile
// paths relative to `base_path`'s directory (the scene, or the population file).
PopulationWheel ReadPopulationWheel(const Fields& w, const std::string& base_path,
                                    std::optional<double> default_radius_m, bool mirror) {
  w.AllowOnly({"name", "profile", "weight", "rolling_radius_mm", "mirror_y"});
  PopulationWheel wheel;
  const std::string spec = w.RequiredString("profile", kProfileExpected);
  wheel.profile = LoadProfileFor(w, "profile", BodyRole::kWheel, spec, base_path);
  if (w.Bool("mirror_y").value_or(mirror)) wheel.profile = wheel.profile.Mirrored();
  wheel.name = w.String("name").value_or(spec);
  // A share of the entry's passes, relative to the other wheels': counts or fractions alike.
  wheel.weight = w.RequiredNumber("weight", Positive(), OpenClosed(0.0, 1e9));
  if (const auto r = w.Number("rolling_radius_mm", Positive(), WheelRadiusRange())) {
    wheel.rolling_radius_m = *r * kMm;
  } else if (default_radius_m) {
    wheel.rolling_radius_m = *default_radius_m;
  } else {
    w.FailMissing("rolling_radius_mm",
                  "the wheel radius at the profile's z = 0 in mm (or the entry's "
                  "rolling_radius_mm, or a [wheel] table)");
  }
  return wheel;
}

// [[traffic]] wheel_population: a measured wheel population (issue 16 point 6), inline
//   wheel_population = [ { profile = "...", weight = 3 }, ... ]
// or a TOML file of [[wheel]] tables with the same keys (profiles relative to that file):
//   wheel_population = "fleet.toml"
// Empty when the entry has none.
std::vector<PopulationWheel> ReadWheelPopulation(const Fields& t, const Scene& scene,
                                                 bool has_wheel) {
  std::vector<PopulationWheel> wheels;
  const toml::node* node = t.Node("wheel_population");
  if (node == nullptr) return wheels;
  std::optional<double> radius;
  if (const auto r = t.Number("rolling_radius_mm", Positive(), WheelRadiusRange())) {
    radius = *r * kMm;
  } else if (has_wheel) {
    radius = scene.problem.placement.rolling_radius_m;
  }
  const bool mirror = t.Bool("mirror_y").value_or(false);
  const std::string expected =
      "a non-empty array of wheels [{ profile, weight, name, rolling_radius_mm, mirror_y }, ...], "
      "or the path of a TOML file of [[wheel]] tables with those keys";
  std::vector<std::string> names;
  const auto add = [&](const Fields& w, const std::string& base_path) {
    PopulationWheel wheel = ReadPopulationWheel(w, base_path, radius, mirror);
    if (std::find(names.begin(), names.end(), wheel.name) != names.end()) {
      if (w.Has("name")) w.Fail("name", "a name no other wheel of the population has");
      w.Fail("profile", "a profile no other unnamed wheel has (or give each a name)");
    }
    names.push_back(wheel.name);
    wheels.push_back(std::move(wheel));
  };
  if (const auto file = node->value_exact<std::string>()) {
    const std::string path = ResolveRelativeTo(DirectoryOf(scene.path), *file);
    std::string text;
    try {
      text = ReadInputFile(path, "the wheel population file");
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", FieldPrefix(t.file(), *node, t.KeyName("wheel_population")),
                                   e.what()));
    }
    const toml::table root = ParseToml(text, path);
    const Fields top(root, "", path);
    top.AllowOnly({"wheel"});
    const std::vector<Fields> tables =
        ArrayOfTables(top, "wheel", "[[wheel]] tables { profile, weight, name, rolling_radius_mm, "
                                    "mirror_y }");
    if (tables.empty()) top.FailMissing("wheel", "at least one [[wheel]] table");
    for (const Fields& w : tables) add(w, path);
    return wheels;
  }
  const toml::array* array = node->as_array();
  if (array == nullptr || array->empty() || !array->is_array_of_tables()) {
    t.Fail("wheel_population", expected);
  }
  int index = 0;
  for (const toml::node& entry : *array) {
    add(Fields(*entry.as_table(), t.KeyName(fmt::format("wheel_population[{}]", index++)),
               t.file()),
        scene.path);
  }
  return wheels;
}

// Adds a prescribed or collective entry to the study: with its wheel wear, and once per wheel of
// its population when it has one (ExpandWheelPopulation).
void AddTrafficEntry(const Fields& t, Scene* scene, bool has_wheel, TrafficCase c) {
  ReadWheelWear(t, *scene, &c);
  const std::vector<PopulationWheel> population = ReadWheelPopulation(t, *scene, has_wheel);
  if (population.empty()) {
    scene->wear->traffic.push_back(std::move(c));
    return;
  }
  for (TrafficCase& e : ExpandWheelPopulation(c, population)) {
    scene->wear->traffic.push_back(std::move(e));
  }
}

// A [[traffic]] entry that names an imported load collective (`railwear traffic import`): each
// bin is one load case at its wheelset state on the unworn rails (wear/collective_traffic.h).
void ReadCollectiveTraffic(const Fields& t, Scene* scene, bool has_wheel, TrafficCase* c) {
  t.AllowOnly({"name", "collective", "share", "friction", "condition", "gauge_face_condition",
               "axle_load_t", "wheel_profile", "mirror_y", "rolling_radius_mm",
               "flange_back_distance_mm", "flange_back_position_mm", "wheel_wear",
               "wheel_population"});
  const std::string file =
      t.RequiredString("collective",
                       "the path of a load-collective TOML file (railwear traffic import), "
                       "relative to the scene");
  if (!scene->wear->low_rail_profile) {
    t.Fail("collective",
           "a [track] table with high_rail and low_rail instead of [rail] (a collective places "
           "wheelsets on both rails)");
  }
  auto traffic = std::make_shared<CollectiveTraffic>();
  const std::string path = ResolveRelativeTo(DirectoryOf(scene->path), file);
  try {
    traffic->collective = ReadLoadCollective(path);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}:{}: key '{}' = \"{}\": {}", t.file(),
                                 LineOf(*t.Node("collective")), t.KeyName("collective"), file,
                                 e.what()));
  }
  ReadTrafficWheel(t, scene, has_wheel, c);
  traffic->flange_back_distance_m =
      t.Number("flange_back_distance_mm", InRange(1000.0, 1700.0)).value_or(1360.0) * kMm;
  traffic->flange_back_position_m =
      t.Number("flange_back_position_mm", InRange(-200.0, 0.0)).value_or(-70.0) * kMm;
  c->share = t.Number("share", OpenClosed(0.0, kMaxShare)).value_or(1.0);
  const LoadCollective& lc = traffic->collective;
  const bool every_bin_has_mu =
      std::all_of(lc.entries.begin(), lc.entries.end(),
                  [](const LoadCollectiveEntry& e) { return e.friction.has_value(); });
  if (!every_bin_has_mu && !t.Has("friction") && !t.Has("condition")) {
    t.FailMissing("friction",
                  "the friction coefficient of the bins without mu (the collective's CSV had no "
                  "mu column), or a condition whose mu they take");
  }
  ReadEntryFriction(t, scene->wear->options.conditions, /*required=*/false, c);
  c->axle_load_t =
      t.Number("axle_load_t", OpenClosed(0.0, 40.0), AxleLoadRange()).value_or(CollectiveAxleLoad_t(lc));
  c->collective = std::move(traffic);
}

// At most this many load cases per wear step (about 20 ms each at draft accuracy: under two
// minutes a step on one thread).
constexpr size_t kMaxLoadCasesPerStep = 5000;

void ReadTraffic(const Fields& top, Scene* scene) {
  // A [wheel] table, when a wear scene has one, gives each entry its default wheel.
  const bool has_wheel = top.Has("wheel");
  const toml::node* node = top.Node("traffic");
  if (node == nullptr || !node->is_array_of_tables()) {
    if (node != nullptr) top.Fail("traffic", "[[traffic]] tables, one per load case");
    top.FailMissing("traffic", "at least one [[traffic]] table for the wear effect");
  }
  const toml::array& entries = *node->as_array();
  // The time and memory estimate of a step, before any entry is read (each loads its wheel):
  // every entry is at least one contact solve per step and a spread entry one per quadrature
  // node. 100 000 entries once ran out of memory at 8 GB.
  // The adaptive rule counts its most nodes per spread (kMaxSpreadNodes).
  const bool adaptive = scene->wear->options.integration_tolerance.has_value();
  const WearOptions& wo = scene->wear->options;
  const int nodes = adaptive                   ? kMaxSpreadNodes
                    : !wo.spread_nodes.empty() ? static_cast<int>(wo.spread_nodes.size())
                                               : wo.quadrature_points;
  const auto refuse = [&](size_t cases) {
    throw InputError(fmt::format(
        "{}: {} [[traffic]] entries give up to {} load cases per wear step (each a contact "
        "solve, stored per step); expected at most {}: merge similar entries (their shares add) "
        "or {}",
        FieldPrefix(top.file(), *node, "traffic"), entries.size(), cases, kMaxLoadCasesPerStep,
        adaptive ? fmt::format("give 'wear.quadrature_points' (the fixed rule; the adaptive "
                               "rule takes up to {} nodes per spread)",
                               kMaxSpreadNodes)
        : !wo.spread_nodes.empty()
            ? fmt::format("lower 'wear.spread_nodes' (now {} nodes per spread)", nodes)
            : fmt::format("lower 'wear.quadrature_points' (now {})", nodes)));
  };
  if (entries.size() > kMaxLoadCasesPerStep) refuse(entries.size());
  size_t cases = 0;
  int index = 0;
  for (const toml::node& entry : entries) {
    const Fields t(*entry.as_table(), fmt::format("traffic[{}]", index), top.file());
    // A vehicle entry and a spread entry take every node, a fixed position one case.
    const toml::node* shift = t.Node("lateral_shift_mm");
    cases += (t.Has("vehicle") || (shift != nullptr && shift->is_table())) ? nodes : 1;
    if (cases > kMaxLoadCasesPerStep) refuse(cases);
    if (t.Has("vehicle")) {
      TrafficCase c;
      c.name = t.String("name").value_or(fmt::format("traffic[{}]", index));
      ReadVehicleTraffic(t, scene, &c);
      scene->wear->traffic.push_back(std::move(c));
      ++index;
      continue;
    }
    if (t.Has("collective")) {
      TrafficCase c;
      c.name = t.String("name").value_or(fmt::format("traffic[{}]", index));
      ReadCollectiveTraffic(t, scene, has_wheel, &c);
      // Each bin of a collective is a load case of its own (counted 1 above).
      const size_t bins = c.collective->collective.entries.size();
      cases += bins > 0 ? bins - 1 : 0;
      if (cases > kMaxLoadCasesPerStep) {
        t.Fail("collective",
               fmt::format("a load collective of at most {} bins with the other entries' {} "
                           "load cases ({} per wear step, each a contact solve; this one has {} "
                           "bins): import it with wider bins (railwear traffic import "
                           "--bin-y-mm, --bin-yaw-mrad, ...)",
                           kMaxLoadCasesPerStep - (cases - bins), cases - bins,
                           kMaxLoadCasesPerStep, bins));
      }
      AddTrafficEntry(t, scene, has_wheel, std::move(c));
      ++index;
      continue;
    }
    t.AllowOnly({"name", "wheel_profile", "mirror_y", "rolling_radius_mm", "vertical_N",
                 "axle_load_t", "lateral_shift_mm", "roll_rad", "yaw_mrad", "friction", "condition",
                 "gauge_face_condition", "speed_m_s", "share", "rail", "wheel_wear",
                 "wheel_population"});
    TrafficCase c;
    c.name = t.String("name").value_or(fmt::format("traffic[{}]", index));
    if (const auto rail = t.Choice("rail", EnumChoices(kRailSideNames))) {
      c.rail = *RailSideFromString(*rail);
      if (c.rail == RailSide::kLow && !scene->wear->low_rail_profile) {
        t.Fail("rail",
               "\"high\" in a scene with [rail] (a low-rail entry needs a [track] table with "
               "high_rail and low_rail instead of [rail])");
      }
    }
    ReadTrafficWheel(t, scene, has_wheel, &c);
    c.vertical_force_N = t.RequiredNumber("vertical_N", Positive(), WheelLoadRange());
    c.axle_load_t = t.Number("axle_load_t", Positive(), AxleLoadRange())
                        .value_or(2.0 * c.vertical_force_N / kGravity_m_s2 / 1000.0);
    ReadLateralShift(t, &c);
    c.roll_rad = t.Number("roll_rad", InRange(-kMaxRoll_rad, kMaxRoll_rad)).value_or(0.0);
    c.yaw_rad = t.Number("yaw_mrad", InRange(-100.0, 100.0)).value_or(0.0) * 1e-3;
    ReadEntryFriction(t, scene->wear->options.conditions, /*required=*/true, &c);
    c.speed_m_s = t.RequiredNumber("speed_m_s", OpenClosed(0.0, kMaxSpeed_m_s));
    c.share = t.Number("share", OpenClosed(0.0, kMaxShare)).value_or(1.0);
    AddTrafficEntry(t, scene, has_wheel, std::move(c));
    ++index;
  }
  // A wheel population makes one entry per wheel: count the load cases again.
  size_t expanded = 0;
  for (const TrafficCase& c : scene->wear->traffic) {
    expanded += c.is_collective()                               ? c.collective->collective.entries.size()
                : (c.is_vehicle() || c.lateral_shift_std_m > 0.0) ? nodes
                                                                  : 1;
  }
  if (expanded > kMaxLoadCasesPerStep) refuse(expanded);
}

// A wear scene: model, materials, rail or track, optional default wheel, [wear] and [[traffic]].
void ReadWearScene(const Fields& top, Scene* scene) {
  for (const std::string_view key : {"load", "wheelset"}) {
    if (top.Has(key)) {
      throw InputError(fmt::format(
          "{}: expected no [{}] in a wear scene: its wheels, loads and positions come from the "
          "[[traffic]] entries",
          FieldPrefix(top.file(), *top.Node(key), key), key));
    }
  }
  if (top.Has("wheel")) ReadWheel(top, scene);
  if (top.Has("track") && top.Has("rail")) {
    throw InputError(fmt::format(
        "{}: expected either [rail] (one rail) or [track] (both rails) in a wear scene, not both",
        FieldPrefix(top.file(), *top.Node("track"), "track")));
  }
  if (top.Has("track")) {
    ReadTrackTable(top, scene);
  } else {
    if (!top.Has("rail")) {
      top.FailMissing("rail",
                      "a [rail] table with profile (one rail), or a [track] table with "
                      "high_rail and low_rail (both rails)");
    }
    ReadRail(top, scene);
  }
  ReadWearTable(top, scene);
  ReadVehicles(top, scene);
  ReadCurvingTable(top, scene);
  ReadTraffic(top, scene);
  if (scene->problem.model.kind == ModelKind::kHertz) {
    const auto model = top.Table("model", "a table");
    model->Fail("kind",
                "\"halfspace\" or \"conformal\" for a wear run (wear needs the "
                "pressure and slip of every cell of the patch grid)");
  }
  WearStudy& study = *scene->wear;
  study.cant_ratio = scene->cant_ratio;
  study.setup() = scene->problem.setup();
  if (study.options.law.kind != WearLawKind::kUsfd && !(study.rail_material.hardness_Pa > 0)) {
    throw InputError(fmt::format(
        "{}:{}: key 'materials.rail.hardness_MPa' is missing: expected the rail hardness in MPa "
        "for the {} wear law",
        top.file(), top.Has("materials") ? LineOf(*top.Node("materials")) : 1,
        ToString(study.options.law.kind)));
  }
  if (scene->damage && !(study.rail_material.shear_yield_Pa > 0)) {
    throw InputError(fmt::format(
        "{}:{}: key 'materials.rail.shear_yield_MPa' is missing: expected {}", top.file(),
        top.Has("materials") ? LineOf(*top.Node("materials")) : 1, kShearYieldExpected));
  }
  if (HasEffect(*scene, "coupling")) {
    throw InputError(
        fmt::format("{}: effect 'coupling' is not available in wear runs (each load case is solved "
                    "uncoupled); remove it from scene.effects",
                    top.file()));
  }
  ValidateWearStudy(study);
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
  top.AllowOnly({"scene", "model", "materials", "wheel", "rail", "load", "track", "wheelset",
                 "wear", "traffic", "vehicle", "curving"});
  Scene scene;
  scene.path = path;
  scene.text = text;
  ReadSceneTable(top, &scene);
  if (!HasEffect(scene, "wear")) {
    for (const std::string_view key : {"wear", "traffic", "curving"}) {
      if (top.Has(key)) {
        throw InputError(fmt::format(
            "{}: expected [{}] only in a wear scene: add \"wear\" to scene.effects to run the "
            "traffic mix with `railwear wear`",
            FieldPrefix(top.file(), *top.Node(key), key), key));
      }
    }
  }
  ReadModel(top, &scene);
  ReadMaterials(top, &scene);
  ReadPressureLimit(top, &scene);
  if (HasEffect(scene, "wear")) {
    ReadWearScene(top, &scene);
    return scene;
  }
  ReadLoad(top, &scene);
  ReadWheel(top, &scene);
  ReadRail(top, &scene);
  ReadWheelset(top, &scene);
  PlaceFromCentre(top, &scene);
  CheckRolling(top, scene);
  if (scene.speed_m_s) scene.motion.speed_m_s = *scene.speed_m_s;
  if (scene.tangential) {
    RollingOptions rolling;
    rolling.motion = scene.motion;
    rolling.creepage = scene.creepage;
    rolling.friction = *scene.friction;
    rolling.longitudinal_force_N = scene.longitudinal_force_N;
    rolling.coupling = HasEffect(scene, "coupling");
    scene.problem.rolling = rolling;
  }
  return scene;
}

Scene LoadScene(const std::string& path) {
  return ParseScene(ReadInputFile(path, "scene file"), path);
}

}  // namespace railwear::app
