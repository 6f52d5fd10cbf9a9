// Scene files: defaults, SI conversion, overrides, and one test per class of bad input that
// checks the message (file, line, key, value, what was expected).
#include "app/scene.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "app/scene_template.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"

namespace railwear::app {
namespace {

// Passes when `text` contains `part`; the failure message shows both.
::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n  message: " << text << "\n  lacks:   " << part;
}

// Exact conversions (mm -> m, MPa -> Pa) only lose the last bit.
constexpr double kTight = 1e-12;

const char* const kMinimal = R"(
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460

[rail]
profile = "builtin:UIC60"

[load]
vertical_N = 100000
)";

// The message of the InputError that ParseScene throws for `text` ("" if none).
std::string ErrorOf(const std::string& text, const std::string& path = "scene.toml") {
  try {
    ParseScene(text, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A fresh directory under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / ("railwear_scene_test_" + name)) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    std::ofstream(file) << text;
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

TEST(SceneTest, MinimalSceneGetsDocumentedDefaults) {
  const Scene s = ParseScene(kMinimal, "dir/minimal.toml");
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.effects, std::vector<std::string>{"normal"});
  EXPECT_EQ(s.text, kMinimal);
  EXPECT_EQ(s.problem.model.kind, ModelKind::kConformal);
  EXPECT_EQ(s.problem.model.geometry, GeometryModel::kConformal);
  EXPECT_EQ(s.problem.model.kernel, KernelModel::kGolubenko);
  EXPECT_EQ(s.problem.model.accuracy, AccuracyPreset::kStandard);
  EXPECT_FALSE(s.problem.model.cell_dx_m.has_value());
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_f, 0.75);
  EXPECT_EQ(s.cant_ratio, 0.0);
  EXPECT_EQ(s.problem.placement.lateral_shift_m, 0.0);
  EXPECT_EQ(s.problem.placement.roll_rad, 0.0);
  EXPECT_NEAR(s.problem.placement.rolling_radius_m, 0.46, kTight);
  EXPECT_NEAR(s.problem.wheel_material.youngs_modulus_Pa, 210e9, 1.0);
  EXPECT_DOUBLE_EQ(s.problem.rail_material.poisson_ratio, 0.28);
  EXPECT_NEAR(*s.problem.load.vertical_force_N, 1e5, kTight);
  EXPECT_FALSE(s.problem.load.approach_m.has_value());
  EXPECT_FALSE(s.friction.has_value());
  EXPECT_EQ(s.tangential_method, "fastsim");
  EXPECT_EQ(s.wheel_profile_spec, "builtin:S1002");
  EXPECT_GE(s.problem.wheel_profile.size(), 4);
  EXPECT_GE(s.problem.rail_profile.size(), 4);
}

TEST(SceneTest, FullSceneConvertsToSi) {
  const std::string text = R"(
[scene]
name = "full"
effects = ["normal"]
[model]
kind = "halfspace"
accuracy = "draft"
cell_mm = [0.25, 0.5]
tangential = "exact"
influence_constants = { c_f = 0.7, c_s = -0.1 }
[materials]
wheel = { E_MPa = 200000, nu = 0.3 }
rail = { E_MPa = 190000.5, nu = 0.25, hardness_MPa = 2600, shear_yield_MPa = 350 }
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 450.5
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[load]
approach_mm = 0.05
lateral_shift_mm = -3
roll_rad = 0.001
friction = 0.4
speed_m_s = 20
)";
  const Scene s = ParseScene(text, "full.toml");
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.problem.model.kind, ModelKind::kHalfspace);
  EXPECT_EQ(s.problem.model.geometry, GeometryModel::kPlanar);
  EXPECT_EQ(s.problem.model.kernel, KernelModel::kBoussinesq);
  EXPECT_EQ(s.problem.model.accuracy, AccuracyPreset::kDraft);
  EXPECT_NEAR(*s.problem.model.cell_dx_m, 0.25e-3, kTight);
  EXPECT_NEAR(*s.problem.model.cell_ds_m, 0.5e-3, kTight);
  EXPECT_EQ(s.tangential_method, "exact");
  EXPECT_EQ(s.influence_constants_source, "inline");
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_f, 0.7);
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_z, 1.0);  // default kept
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_s, -0.1);
  EXPECT_NEAR(s.problem.wheel_material.youngs_modulus_Pa, 200e9, 1.0);
  EXPECT_DOUBLE_EQ(s.problem.wheel_material.poisson_ratio, 0.3);
  EXPECT_NEAR(s.problem.rail_material.youngs_modulus_Pa, 190000.5e6, 1.0);
  EXPECT_NEAR(s.problem.rail_material.hardness_Pa, 2600e6, 1.0);
  EXPECT_NEAR(s.problem.rail_material.shear_yield_Pa, 350e6, 1.0);
  EXPECT_NEAR(s.problem.placement.rolling_radius_m, 0.4505, kTight);
  EXPECT_DOUBLE_EQ(s.cant_ratio, 0.025);
  EXPECT_EQ(s.cant, "1:40");
  EXPECT_NEAR(*s.problem.load.approach_m, 0.05e-3, kTight);
  EXPECT_FALSE(s.problem.load.vertical_force_N.has_value());
  EXPECT_NEAR(s.problem.placement.lateral_shift_m, -3e-3, kTight);
  EXPECT_DOUBLE_EQ(s.problem.placement.roll_rad, 0.001);
  EXPECT_DOUBLE_EQ(*s.friction, 0.4);
  EXPECT_DOUBLE_EQ(*s.speed_m_s, 20.0);
}

TEST(SceneTest, HertzKindUsesShorthand) {
  const Scene s = ParseScene(std::string(kMinimal) + "[model]\nkind = \"hertz\"\n", "h.toml");
  EXPECT_EQ(s.problem.model.kind, ModelKind::kHertz);
}

TEST(SceneTest, ExplicitGeometryAndKernelOverrideKind) {
  const Scene custom = ParseScene(
      std::string(kMinimal) + "[model]\nkind = \"conformal\"\nkernel = \"boussinesq\"\n", "c.toml");
  EXPECT_EQ(custom.problem.model.kind, ModelKind::kCustom);
  EXPECT_EQ(custom.problem.model.geometry, GeometryModel::kConformal);
  EXPECT_EQ(custom.problem.model.kernel, KernelModel::kBoussinesq);

  const Scene halfspace = ParseScene(
      std::string(kMinimal) + "[model]\ngeometry = \"planar\"\nkernel = \"boussinesq\"\n",
      "c.toml");
  EXPECT_EQ(halfspace.problem.model.kind, ModelKind::kHalfspace);
}

TEST(SceneTest, GeometryWithHertzIsAnError) {
  const std::string msg =
      ErrorOf(std::string(kMinimal) + "[model]\nkind = \"hertz\"\ngeometry = \"planar\"\n");
  EXPECT_TRUE(Contains(msg,
                       "scene.toml:13: key 'model.geometry' = \"planar\": expected no "
                       "geometry or kernel with kind = 'hertz'"));
}

TEST(SceneTest, UnknownKeyListsAllowedKeys) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "lateral_shfit_mm = 3\n");
  EXPECT_TRUE(Contains(msg,
                       "scene.toml:11: key 'load.lateral_shfit_mm' = 3: expected one of "
                       "the keys allowed in [load]:"));
  EXPECT_TRUE(Contains(msg,
                       "'vertical_N', 'approach_mm', 'lateral_shift_mm', 'roll_rad', "
                       "'friction', 'speed_m_s'"));
}

TEST(SceneTest, UnknownKeyInInlineTable) {
  const std::string msg = ErrorOf(std::string(kMinimal) +
                                  "[materials]\nwheel = { E_MPa = 1, nu = 0.3, G_MPa = 3 }\n"
                                  "rail = { E_MPa = 1, nu = 0.3 }\n");
  EXPECT_TRUE(Contains(msg,
                       "scene.toml:12: key 'materials.wheel.G_MPa' = 3: expected one of "
                       "the keys allowed in [materials.wheel]: 'E_MPa', 'nu'"));
}

TEST(SceneTest, UnknownTableListsAllowedTables) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "\n[loads]\nx = 1\n");
  EXPECT_TRUE(Contains(msg,
                       "scene.toml:12: key 'loads' = (table): expected one of the keys "
                       "allowed at the top level: 'scene', 'model', 'materials', 'wheel', "
                       "'rail', 'load'"));
}

TEST(SceneTest, MissingKeyNamesItsTableLine) {
  const std::string text = R"([wheel]
profile = "builtin:S1002"
[rail]
profile = "builtin:UIC60"
[load]
vertical_N = 1000
)";
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:1: key 'wheel.rolling_radius_mm' is missing: "
                       "expected a number > 0"));
}

TEST(SceneTest, MissingTableUsesLineOne) {
  const std::string text =
      "[wheel]\nprofile = \"builtin:S1002\"\nrolling_radius_mm = 460\n"
      "[rail]\nprofile = \"builtin:UIC60\"\n";
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:1: key 'load' is missing: expected a [load] "
                       "table with vertical_N or approach_mm"));
}

TEST(SceneTest, WrongTypeNamesValueAndExpectation) {
  std::string text = kMinimal;
  text.replace(text.find("100000"), 6, "\"100000\"");
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:10: key 'load.vertical_N' = \"100000\": expected a number > 0"));
}

TEST(SceneTest, WrongTypeForTable) {
  EXPECT_TRUE(Contains(ErrorOf(std::string(kMinimal) + "[model]\ncell_mm = 0.2\n"),
                       "scene.toml:12: key 'model.cell_mm' = 0.2: expected two positive numbers "
                       "[dx, ds] in mm"));
  EXPECT_TRUE(Contains(ErrorOf(std::string("scene = 3\n") + kMinimal),
                       "scene.toml:1: key 'scene' = 3: expected a table"));
  EXPECT_TRUE(Contains(ErrorOf(std::string(kMinimal) + "[wheel.x]\n"), "key 'wheel.x'"));
  EXPECT_TRUE(Contains(ErrorOf(std::string(kMinimal) + "[scene]\neffects = \"normal\"\n"),
                       "scene.toml:12: key 'scene.effects' = \"normal\": expected an array"));
}

TEST(SceneTest, OutOfRangeValues) {
  const std::string m = kMinimal;
  const std::string materials = "[materials]\nrail = { E_MPa = 210000, nu = 0.28 }\n";
  EXPECT_TRUE(Contains(ErrorOf(m + materials + "wheel = { E_MPa = 210000, nu = 0.5 }\n"),
                       "scene.toml:13: key 'materials.wheel.nu' = 0.5: expected a number in "
                       "[0, 0.5)"));
  EXPECT_TRUE(Contains(ErrorOf(m + materials + "wheel = { E_MPa = -1, nu = 0.3 }\n"),
                       "scene.toml:13: key 'materials.wheel.E_MPa' = -1: expected a number > 0"));
  EXPECT_TRUE(Contains(ErrorOf(m + "friction = 0\n"),
                       "scene.toml:11: key 'load.friction' = 0: expected a number in (0, 2]"));
  EXPECT_TRUE(Contains(ErrorOf(m + "friction = 2.5\n"),
                       "key 'load.friction' = 2.5: expected a number in (0, 2]"));
  EXPECT_TRUE(Contains(ErrorOf(m + "friction = nan\n"), "key 'load.friction' = nan"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\ncell_mm = [0.2, -1]\n"),
                       "scene.toml:12: key 'model.cell_mm' = [0.2, -1]: expected two positive "
                       "numbers"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\ncell_mm = [0.2]\n"), "key 'model.cell_mm'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\naccuracy = \"ultra\"\n"),
                       "scene.toml:12: key 'model.accuracy' = \"ultra\": expected one of "
                       "'draft', 'standard', 'reference', 'fine'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\nkind = \"fem\"\n"),
                       "key 'model.kind' = \"fem\": expected one of 'hertz', 'halfspace', "
                       "'conformal', 'auto'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\ngeometry = \"curved\"\n"),
                       "expected one of 'planar', 'conformal'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\nkernel = \"kelvin\"\n"),
                       "expected one of 'boussinesq', 'golubenko'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\ntangential = \"kalker\"\n"),
                       "scene.toml:12: key 'model.tangential' = \"kalker\": expected one of "
                       "'fastsim', 'exact', 'auto'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "[model]\ninfluence_constants = { c_f = 0 }\n"),
                       "key 'model.influence_constants.c_f' = 0: expected a number > 0"));
}

// [model] tangential = "auto" (issue 16): read into the problem; the exact solver and FASTSIM
// are chosen per patch by the rolling stage (core/contact/tangential_method.h).
TEST(SceneTest, TangentialAutoIsAMethod) {
  const Scene s = ParseScene(std::string(kMinimal) + "[model]\ntangential = \"auto\"\n", "a.toml");
  EXPECT_EQ(s.tangential_method, "auto");
  EXPECT_EQ(s.problem.tangential, TangentialMethod::kAuto);
  EXPECT_EQ(ParseScene(kMinimal, "a.toml").problem.tangential, TangentialMethod::kFastsim);
}

// [model] normal_criterion and normal_tolerance (issue 18 point 4): absent, the default (the
// pressure update at 1e-4); "gap-residual" the strict setting (1e-10); normal_tolerance sets the
// chosen criterion's tolerance. A tolerance outside [1e-13, 1e-2] or not a number, or another
// criterion, refused with the key, the value and what was expected.
TEST(SceneTest, NormalCriterionAndToleranceSelectTheNormalSolversStop) {
  const Scene d = ParseScene(kMinimal, "a.toml");
  EXPECT_EQ(d.problem.solver.criterion, NormalStopCriterion::kPressureUpdate);
  EXPECT_EQ(d.problem.solver.tolerance, 1e-4);
  const Scene s =
      ParseScene(std::string(kMinimal) + "[model]\nnormal_tolerance = 1e-6\n", "a.toml");
  EXPECT_EQ(s.problem.solver.criterion, NormalStopCriterion::kPressureUpdate);
  EXPECT_EQ(s.problem.solver.tolerance, 1e-6);
  const Scene strict = ParseScene(
      std::string(kMinimal) + "[model]\nnormal_criterion = \"gap-residual\"\n", "a.toml");
  EXPECT_EQ(strict.problem.solver.criterion, NormalStopCriterion::kGapResidual);
  EXPECT_EQ(strict.problem.solver.tolerance, 1e-10);
  const Scene strict12 = ParseScene(std::string(kMinimal) +
                                        "[model]\nnormal_criterion = \"gap-residual\"\n"
                                        "normal_tolerance = 1e-12\n",
                                    "a.toml");
  EXPECT_EQ(strict12.problem.solver.criterion, NormalStopCriterion::kGapResidual);
  EXPECT_EQ(strict12.problem.solver.tolerance, 1e-12);
  const std::string m = std::string(kMinimal) + "[model]\n";
  EXPECT_TRUE(Contains(ErrorOf(m + "normal_tolerance = 0.1\n"),
                       "scene.toml:12: key 'model.normal_tolerance' = 0.1: expected a number in "
                       "[1e-13, 0.01]"));
  EXPECT_TRUE(Contains(ErrorOf(m + "normal_tolerance = 0\n"),
                       "key 'model.normal_tolerance' = 0: expected a number > 0"));
  EXPECT_TRUE(Contains(ErrorOf(m + "normal_tolerance = 1e-20\n"), "[1e-13, 0.01]"));
  EXPECT_TRUE(Contains(ErrorOf(m + "normal_tolerance = nan\n"), "key 'model.normal_tolerance'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "normal_tolerance = \"tight\"\n"),
                       "key 'model.normal_tolerance' = \"tight\""));
  EXPECT_TRUE(Contains(ErrorOf(m + "normal_criterion = \"strict\"\n"),
                       "key 'model.normal_criterion' = \"strict\": expected one of "
                       "'pressure-update', 'gap-residual'"));
}

// [model] tangential_tolerance (issue 18): absent, the exact solver's default (1e-6 of mu p_max,
// kDefaultExactTangentialTolerance); given, taken as it is. Outside [1e-10, 1e-2] or not a
// number refused with the key, the value and what was expected.
TEST(SceneTest, TangentialToleranceSetsTheExactSolversStop) {
  EXPECT_EQ(ParseScene(kMinimal, "a.toml").problem.tangential_tolerance,
            kDefaultExactTangentialTolerance);
  EXPECT_EQ(kDefaultExactTangentialTolerance, 1e-6);
  const Scene s = ParseScene(
      std::string(kMinimal) + "[model]\ntangential = \"exact\"\ntangential_tolerance = 1e-9\n",
      "a.toml");
  EXPECT_EQ(s.problem.tangential_tolerance, 1e-9);
  const std::string m = std::string(kMinimal) + "[model]\n";
  EXPECT_TRUE(Contains(ErrorOf(m + "tangential_tolerance = 0.1\n"),
                       "scene.toml:12: key 'model.tangential_tolerance' = 0.1: expected a number "
                       "in [1e-10, 0.01]"));
  EXPECT_TRUE(Contains(ErrorOf(m + "tangential_tolerance = 0\n"),
                       "key 'model.tangential_tolerance' = 0: expected a number > 0"));
  EXPECT_TRUE(Contains(ErrorOf(m + "tangential_tolerance = -1e-6\n"),
                       "key 'model.tangential_tolerance' = -1e-06: expected a number > 0"));
  EXPECT_TRUE(Contains(ErrorOf(m + "tangential_tolerance = 1e-12\n"), "[1e-10, 0.01]"));
  EXPECT_TRUE(
      Contains(ErrorOf(m + "tangential_tolerance = inf\n"), "key 'model.tangential_tolerance'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "tangential_tolerance = \"loose\"\n"),
                       "key 'model.tangential_tolerance' = \"loose\""));
}

TEST(SceneTest, RollingRadiusAndLoadMustBePositive) {
  std::string text = kMinimal;
  text.replace(text.find("460"), 3, "0");
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:4: key 'wheel.rolling_radius_mm' = 0: expected a number > 0"));
  text = kMinimal;
  text.replace(text.find("100000"), 6, "-5");
  EXPECT_TRUE(Contains(ErrorOf(text), "key 'load.vertical_N' = -5: expected a number > 0"));
}

TEST(SceneTest, IntegersAreAcceptedWhereFloatsAreExpected) {
  const Scene s = ParseScene(std::string(kMinimal) + "lateral_shift_mm = 6\n", "i.toml");
  EXPECT_NEAR(s.problem.placement.lateral_shift_m, 6e-3, kTight);
}

TEST(SceneTest, LoadNeedsExactlyOneOfForceAndApproach) {
  EXPECT_TRUE(Contains(ErrorOf(std::string(kMinimal) + "approach_mm = 0.1\n"),
                       "scene.toml:11: key 'load.approach_mm' = 0.1: expected exactly one of "
                       "'load.vertical_N' and 'load.approach_mm' (both given)"));
  std::string text = kMinimal;
  text.replace(text.find("vertical_N = 100000"), 19, "friction = 0.3");
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:9: key 'load.vertical_N' is missing: expected "
                       "exactly one of 'load.vertical_N' and "
                       "'load.approach_mm'"));
}

TEST(SceneTest, SyntaxErrorGivesLineAndColumn) {
  const std::string msg = ErrorOf("[wheel]\nprofile = \"builtin:S1002\nrolling_radius_mm = 460\n");
  EXPECT_TRUE(Contains(msg, "scene.toml:2:"));
  EXPECT_TRUE(Contains(msg, "TOML syntax error"));
  EXPECT_TRUE(Contains(ErrorOf("[load]\nvertical_N = = 3\n"), "scene.toml:2:14: TOML syntax"));
}

TEST(SceneTest, EffectsAreCheckedAndWearNeedsItsTables) {
  const std::string text = std::string("[scene]\neffects = [\"normal\", \"wear\"]\n") + kMinimal;
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:11: key 'load' = (table): expected no [load] in a wear scene"));
  const std::string unknown = std::string("[scene]\neffects = [\"friction\"]\n") + kMinimal;
  EXPECT_TRUE(Contains(ErrorOf(unknown),
                       "key 'scene.effects' = \"friction\": expected one of 'normal', "
                       "'tangential', 'coupling', 'wear', 'damage'"));
  // damage implies tangential; both need friction and speed.
  const std::string rolling =
      std::string(
          "[scene]\neffects = [\"damage\"]\n[materials]\nwheel = { E_MPa = 210000, "
          "nu = 0.28 }\nrail = { E_MPa = 210000, nu = 0.28, shear_yield_MPa = 350 }\n") +
      kMinimal + "friction = 0.3\nspeed_m_s = 20\n";
  const Scene s = ParseScene(rolling, "scene.toml");
  EXPECT_TRUE(s.tangential);
  EXPECT_TRUE(s.damage);
  EXPECT_EQ(s.effects, (std::vector<std::string>{"normal", "tangential", "damage"}));
  EXPECT_DOUBLE_EQ(s.motion.speed_m_s, 20.0);
  EXPECT_FALSE(s.motion.pitch_velocity_rad_s.has_value());  // pure rolling
}

TEST(SceneTest, TangentialNeedsFrictionAndSpeed) {
  const std::string head = "[scene]\neffects = [\"tangential\"]\n";
  EXPECT_TRUE(Contains(ErrorOf(head + kMinimal + "speed_m_s = 20\n"),
                       "key 'load.friction' is missing: expected a friction coefficient in "
                       "(0, 2] for the tangential effect"));
  EXPECT_TRUE(Contains(ErrorOf(head + kMinimal + "friction = 0.3\n"),
                       "key 'load.speed_m_s' is missing: expected a speed > 0 m/s for the "
                       "tangential effect"));
}

TEST(SceneTest, PrescribedCreepageOrMotionNotBoth) {
  const std::string base = std::string(kMinimal) + "friction = 0.3\nspeed_m_s = 20\n";
  const Scene s = ParseScene(
      base + "creepage = { xi = -0.004, eta = 0.001, spin_per_mm = -0.0015 }\n", "scene.toml");
  ASSERT_TRUE(s.creepage.has_value());
  EXPECT_DOUBLE_EQ(s.creepage->xi, -0.004);
  EXPECT_DOUBLE_EQ(s.creepage->eta, 0.001);
  EXPECT_NEAR(s.creepage->spin_per_m, -1.5, kTight);  // per mm -> per m
  EXPECT_TRUE(Contains(ErrorOf(base + "yaw_mrad = 2\ncreepage = { xi = 0.001 }\n"),
                       "key 'load.creepage' = { xi = 0.001 }: expected either prescribed "
                       "creepages or the wheel's motion"));
  EXPECT_TRUE(Contains(ErrorOf(base + "creepage = { xi = 0.001, zeta = 1 }\n"),
                       "key 'load.creepage.zeta' = 1: expected one of the keys allowed"));
  const Scene yawed = ParseScene(base + "yaw_mrad = 5\npitch_velocity_rad_s = -43\n", "s.toml");
  EXPECT_NEAR(yawed.problem.placement.yaw_rad, 0.005, kTight);
  EXPECT_EQ(yawed.motion.pitch_velocity_rad_s, -43.0);
}

TEST(SceneTest, LongitudinalForceInsteadOfPitchVelocity) {
  const std::string base = std::string("[scene]\neffects = [\"tangential\"]\n") + kMinimal +
                           "friction = 0.3\nspeed_m_s = 20\n";
  const Scene s = ParseScene(base + "longitudinal_force_N = -12000\n", "scene.toml");
  ASSERT_TRUE(s.problem.rolling.has_value());
  EXPECT_EQ(s.problem.rolling->longitudinal_force_N, -12000.0);
  EXPECT_TRUE(Contains(ErrorOf(base + "longitudinal_force_N = 1\npitch_velocity_rad_s = -43\n"),
                       "key 'load.longitudinal_force_N' = 1: expected either "
                       "longitudinal_force_N or pitch_velocity_rad_s"));
  EXPECT_TRUE(Contains(ErrorOf(base + "longitudinal_force_N = 1\ncreepage = { xi = 0.001 }\n"),
                       "expected either prescribed creepages or the wheel's motion"));
}

TEST(SceneTest, WheelsetOnTrackReplacesThePlacementOfLoad) {
  const char* const kWheelset = R"(
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[track]
gauge_mm = 1435
gauge_height_mm = 14
[wheelset]
flange_back_distance_mm = 1360
flange_back_position_mm = -70
lateral_displacement_mm = 5.0
yaw_mrad = 12.0
roll_rad = -0.0006
vertical_load_per_wheel_N = 10000
speed_m_s = 2.0
)";
  const Scene s = ParseScene(kWheelset, "scene.toml");
  ASSERT_TRUE(s.wheelset.has_value());
  ASSERT_TRUE(s.track.has_value());
  EXPECT_NEAR(s.track->gauge_m, 1.435, kTight);
  EXPECT_NEAR(s.wheelset->lateral_displacement_m, 0.005, kTight);
  EXPECT_NEAR(s.wheelset->yaw_rad, 0.012, kTight);
  EXPECT_NEAR(s.wheelset->rolling_radius_m, 0.46, kTight);
  EXPECT_EQ(s.problem.load.vertical_force_N, 10000.0);
  EXPECT_DOUBLE_EQ(s.motion.speed_m_s, 2.0);
  // Placement keys of [load] do not go with a wheelset; a track needs a wheelset.
  EXPECT_TRUE(Contains(ErrorOf(std::string(kWheelset) + "[load]\nvertical_N = 1\n"),
                       "key 'load.vertical_N' = 1: expected one of the keys allowed in [load]: "
                       "'friction', 'creepage'"));
  EXPECT_TRUE(Contains(ErrorOf(std::string(kMinimal) + "[track]\ngauge_mm = 1435\n"),
                       "expected a [wheelset] table next to [track]"));
  std::string no_load = kWheelset;
  const std::string line = "vertical_load_per_wheel_N = 10000\n";
  no_load.erase(no_load.find(line), line.size());
  EXPECT_TRUE(Contains(ErrorOf(no_load), "key 'wheelset.vertical_load_per_wheel_N' is missing"));
}

// kind = "hertz" rolls on the fast tread path on a wheelset too (both wheels, or the whole
// wheelset on the auto model's fallback: core/contact/wheelset_contact.h); the coupling effect
// still needs a patch grid.
TEST(SceneTest, HertzRollsOnAWheelsetButNotWithCoupling) {
  std::ifstream in(RAILWEAR_SOURCE_DIR "/examples/wheelset.toml");
  std::string hertz((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string kind = "kind = \"conformal\"", effects = "\"tangential\"]";
  ASSERT_NE(hertz.find(kind), std::string::npos);
  hertz.replace(hertz.find(kind), kind.size(), "kind = \"hertz\"");
  const Scene s = ParseScene(hertz, "wheelset.toml");
  EXPECT_EQ(s.problem.model.kind, ModelKind::kHertz);
  ASSERT_TRUE(s.wheelset.has_value());
  EXPECT_TRUE(s.tangential);
  std::string coupled = hertz;
  ASSERT_NE(coupled.find(effects), std::string::npos);
  coupled.replace(coupled.find(effects), effects.size(), "\"tangential\", \"coupling\"]");
  EXPECT_TRUE(Contains(ErrorOf(coupled, "wheelset.toml"),
                       "key 'model.kind' = \"hertz\": expected \"halfspace\", \"conformal\" or "
                       "\"auto\" with the coupling effect"));
}

TEST(SceneTest, WearTablesNeedTheWearEffect) {
  for (const std::string table : {"[wear]\nk = 1e-4\n", "[[traffic]]\nshare = 1\n"}) {
    const std::string msg = ErrorOf(std::string(kMinimal) + table);
    EXPECT_TRUE(Contains(msg, "scene.toml:11: key '")) << table;
    EXPECT_TRUE(Contains(msg, "only in a wear scene: add \"wear\" to scene.effects")) << table;
  }
}

TEST(SceneTest, CantMustBeARatio) {
  const std::string base = std::string(kMinimal);
  const std::string with_cant = [&] {
    std::string t = base;
    t.replace(t.find("profile = \"builtin:UIC60\""), 25, "profile = \"builtin:UIC60\"\ncant = 7");
    return t;
  }();
  EXPECT_TRUE(Contains(ErrorOf(with_cant),
                       "scene.toml:8: key 'rail.cant' = 7: expected a cant "
                       "ratio \"1:N\" (e.g. \"1:40\") or 0"));
}

TEST(SceneTest, ProfileErrorsNameTheSceneKey) {
  std::string text = kMinimal;
  text.replace(text.find("builtin:S1002"), 13, "no_such_profile.csv");
  const std::string msg = ErrorOf(text, "dir/scene.toml");
  EXPECT_TRUE(Contains(msg, "dir/scene.toml:3: key 'wheel.profile' = \"no_such_profile.csv\": "));
  EXPECT_TRUE(Contains(msg, "no_such_profile.csv"));
}

TEST(SceneTest, ProfilePathsAreRelativeToTheSceneAndMirrorYFlips) {
  const TempDir dir("mirror");
  dir.Write("wheel.csv", "y_mm,z_mm\n0,0\n2,-0.01\n4,-0.04\n6,-0.09\n8,-0.16\n");
  std::string text = kMinimal;
  text.replace(text.find("\"builtin:S1002\""), 15, "\"wheel.csv\"\nmirror_y = true");
  const Scene s = LoadScene(dir.Write("scene.toml", text));
  const auto b = s.problem.wheel_profile.bounds();
  EXPECT_NEAR(b.y_min, -8e-3, kTight);
  EXPECT_NEAR(b.y_max, 0.0, kTight);
}

TEST(SceneTest, MirrorYMustBeBoolean) {
  std::string text = kMinimal;
  text.replace(text.find("rolling_radius_mm"), 0, "mirror_y = \"yes\"\n");
  EXPECT_TRUE(Contains(ErrorOf(text),
                       "scene.toml:4: key 'wheel.mirror_y' = \"yes\": expected true or false"));
}

TEST(SceneTest, InfluenceConstantsFromFile) {
  const TempDir dir("constants");
  dir.Write("fit.toml", "[influence_constants]\nc_f = 0.68\nc_z = 1.1\nc_s = 0.2\n");
  const Scene s = LoadScene(dir.Write(
      "scene.toml", std::string(kMinimal) + "[model]\ninfluence_constants = \"fit.toml\"\n"));
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_f, 0.68);
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_z, 1.1);
  EXPECT_DOUBLE_EQ(s.problem.model.constants.c_s, 0.2);
  EXPECT_TRUE(Contains(s.influence_constants_source, "fit.toml"));
}

TEST(SceneTest, InfluenceConstantsFileErrorsNameThatFile) {
  const TempDir dir("constants_bad");
  const std::string fit = dir.Write("fit.toml", "[influence_constants]\nc_f = -1\n");
  const std::string scene = dir.Write(
      "scene.toml", std::string(kMinimal) + "[model]\ninfluence_constants = \"fit.toml\"\n");
  try {
    LoadScene(scene);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), fit + ":2: key 'influence_constants.c_f' = -1: expected a "
                                         "number > 0"));
  }
  dir.Write("fit.toml", "[constants]\nc_f = 1\n");
  try {
    LoadScene(scene);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), fit + ":1: key 'influence_constants' is missing"));
  }
}

TEST(SceneTest, SeparateInfluenceConstantsInlineAndFromFile) {
  const Scene inline_scene =
      ParseScene(std::string(kMinimal) +
                     "[model]\ninfluence_constants = { convex = { c_f = 0.9, c_s = 0.1 }, "
                     "concave = { c_f = 0.8, c_z = 1.2 } }\n",
                 "scene.toml");
  const InfluenceConstants& c = inline_scene.problem.model.constants;
  ASSERT_TRUE(c.IsSeparate());
  EXPECT_DOUBLE_EQ(c.separate->convex.c_f, 0.9);
  EXPECT_DOUBLE_EQ(c.separate->convex.c_z, 1.0);  // default kept
  EXPECT_DOUBLE_EQ(c.separate->convex.c_s, 0.1);
  EXPECT_DOUBLE_EQ(c.separate->concave.c_f, 0.8);
  EXPECT_DOUBLE_EQ(c.separate->concave.c_z, 1.2);
  EXPECT_DOUBLE_EQ(c.separate->concave.c_s, 0.25);
  EXPECT_EQ(c.ForBody(-1).c_f, 0.9);
  EXPECT_EQ(c.ForBody(+1).c_f, 0.8);

  const TempDir dir("constants_separate");
  dir.Write("fit.toml",
            "[influence_constants.convex]\nc_f = 1.1\nc_z = 0.7\nc_s = 0.2\n"
            "[influence_constants.concave]\nc_f = 0.95\nc_z = 0.5\nc_s = 0.4\n");
  const Scene from_file = LoadScene(dir.Write(
      "scene.toml", std::string(kMinimal) + "[model]\ninfluence_constants = \"fit.toml\"\n"));
  const InfluenceConstants& f = from_file.problem.model.constants;
  ASSERT_TRUE(f.IsSeparate());
  EXPECT_DOUBLE_EQ(f.separate->convex.c_z, 0.7);
  EXPECT_DOUBLE_EQ(f.separate->concave.c_s, 0.4);
  // One set stays one set; without constants the default is the FEM-calibrated pair of sets
  // (issue 17), and the paper's set is one set.
  EXPECT_FALSE(ParseScene(std::string(kMinimal) + "[model]\ninfluence_constants = { c_f = 0.8 }\n",
                          "scene.toml")
                   .problem.model.constants.IsSeparate());
  EXPECT_TRUE(ParseScene(kMinimal, "scene.toml").problem.model.constants.IsSeparate());
  EXPECT_FALSE(ParseScene(std::string(kMinimal) + "[model]\nconstants = \"paper\"\n", "scene.toml")
                   .problem.model.constants.IsSeparate());
}

TEST(SceneTest, SeparateInfluenceConstantsErrors) {
  const std::string m = std::string(kMinimal) + "[model]\ninfluence_constants = ";
  EXPECT_TRUE(Contains(ErrorOf(m + "{ c_f = 0.8, convex = { c_f = 0.9 }, concave = {} }\n"),
                       "key 'model.influence_constants.c_f' = 0.8: expected either one set or "
                       "convex and concave sets, not both"));
  EXPECT_TRUE(Contains(ErrorOf(m + "{ convex = { c_f = 0.9 } }\n"),
                       "key 'model.influence_constants.concave' is missing: expected the concave "
                       "set too"));
  EXPECT_TRUE(Contains(ErrorOf(m + "{ convex = {}, concave = { c_f = -1 } }\n"),
                       "scene.toml:12: key 'model.influence_constants.concave.c_f' = -1: expected "
                       "a number > 0"));
  EXPECT_TRUE(Contains(ErrorOf(m + "{ convex = {}, concave = { c_t = 1 } }\n"),
                       "key 'model.influence_constants.concave.c_t' = 1: expected one of the keys "
                       "allowed in [model.influence_constants.concave]: 'c_f', 'c_z', 'c_s'"));
  EXPECT_TRUE(Contains(ErrorOf(m + "{ convex = 0.9, concave = {} }\n"),
                       "key 'model.influence_constants.convex' = 0.9: expected a table "
                       "{ c_f, c_z, c_s }"));
  EXPECT_TRUE(Contains(ErrorOf(m + "{ flat = {} }\n"),
                       "expected one of the keys allowed in [model.influence_constants]: 'c_f', "
                       "'c_z', 'c_s', 'convex', 'concave'"));
}

TEST(SceneTest, MaterialsTableNeedsBothBodies) {
  EXPECT_TRUE(
      Contains(ErrorOf(std::string(kMinimal) + "[materials]\nwheel = { E_MPa = 1, nu = 0.3 }\n"),
               "scene.toml:11: key 'materials.rail' is missing: expected an inline table "
               "{ E_MPa, nu }"));
}

TEST(SceneTest, MissingFileIsAnInputError) {
  EXPECT_THROW(LoadScene("/nonexistent/railwear/scene.toml"), InputError);
}

TEST(SceneTest, TemplateLoads) {
  const Scene s = ParseScene(std::string(SceneTemplate()), "template.toml");
  EXPECT_EQ(s.name, "S1002 on UIC60");
  EXPECT_EQ(s.problem.model.kind, ModelKind::kConformal);
  EXPECT_DOUBLE_EQ(s.cant_ratio, 0.025);
  EXPECT_TRUE(s.problem.load.vertical_force_N.has_value());
}

TEST(SceneTest, ExamplesLoad) {
  for (const char* name : {"gauge_corner.toml", "tread.toml", "groove_conformal.toml",
                           "rolling_gauge_corner.toml", "wheelset.toml"}) {
    const Scene s = LoadScene(std::string(RAILWEAR_SOURCE_DIR) + "/examples/" + name);
    EXPECT_FALSE(s.name.empty()) << name;
    EXPECT_EQ(s.problem.model.kind, ModelKind::kConformal) << name;
  }
}

}  // namespace
}  // namespace railwear::app

namespace railwear::app {
namespace {

const char* const kWearScene = R"([scene]
name = "wear test"
effects = ["wear", "damage"]
[model]
geometry = "conformal"
kernel = "boussinesq"
accuracy = "draft"
[materials]
wheel = { E_MPa = 210000, nu = 0.28 }
rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600, shear_yield_MPa = 350 }
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[wear]
law = "kth"
total_MGT = 2.0
max_depth_per_step_mm = 0.05
db = "study.sqlite"
[[traffic]]
name = "freight"
vertical_N = 110000
axle_load_t = 22.5
lateral_shift_mm = { mean = -4.5, std = 1.0 }
yaw_mrad = 4.0
friction = 0.35
speed_m_s = 22.0
share = 0.4
[[traffic]]
wheel_profile = "circle:460"
rolling_radius_mm = 450
vertical_N = 80000
lateral_shift_mm = -5
friction = 0.3
speed_m_s = 33.0
)";

TEST(SceneTest, WearSceneBecomesAStudyInSi) {
  const Scene s = ParseScene(kWearScene, "dir/wear.toml");
  ASSERT_TRUE(s.wear.has_value());
  const WearStudy& w = *s.wear;
  EXPECT_EQ(s.effects, (std::vector<std::string>{"normal", "tangential", "wear", "damage"}));
  EXPECT_TRUE(w.damage);
  EXPECT_EQ(w.options.law.kind, WearLawKind::kKth);
  EXPECT_EQ(*w.options.total_mgt, 2.0);
  EXPECT_FALSE(w.options.total_passes.has_value());
  EXPECT_NEAR(w.options.max_depth_per_step_m, 0.05e-3, 1e-18);
  EXPECT_EQ(s.wear_db, "dir/study.sqlite");  // relative to the scene, like profile paths
  EXPECT_NEAR(w.cant_ratio, 0.025, kTight);
  // The study keeps the rail before cant: the loop cants each worn profile itself.
  EXPECT_EQ(w.rail_profile.points(), MakeUic60().points());
  ASSERT_EQ(w.traffic.size(), 2u);
  const TrafficCase& a = w.traffic[0];
  EXPECT_EQ(a.name, "freight");
  EXPECT_NEAR(a.lateral_shift_mean_m, -4.5e-3, kTight);
  EXPECT_NEAR(a.lateral_shift_std_m, 1.0e-3, kTight);
  EXPECT_NEAR(a.yaw_rad, 4e-3, kTight);
  EXPECT_NEAR(a.rolling_radius_m, 0.46, kTight);  // from [wheel]
  const TrafficCase& b = w.traffic[1];
  EXPECT_EQ(b.name, "traffic[1]");
  EXPECT_NEAR(b.rolling_radius_m, 0.45, kTight);
  EXPECT_EQ(b.lateral_shift_std_m, 0.0);
  EXPECT_NEAR(b.axle_load_t, 2 * 80000 / 9.80665 / 1000, 1e-12);  // default: twice the wheel load
  EXPECT_EQ(b.share, 1.0);
}

// Issue 16: wear removes no damage beyond the WLRM function unless damage_layer_mm asks for the
// pre-issue-16 layer rule.
TEST(SceneTest, DamageLayerIsOptIn) {
  EXPECT_FALSE(ParseScene(kWearScene, "dir/wear.toml").wear->options.damage_layer_m.has_value());
  std::string scene = kWearScene;
  const std::string key = "max_depth_per_step_mm";
  scene.insert(scene.find(key), "damage_layer_mm = 0.5\n");
  const Scene s = ParseScene(scene, "dir/wear.toml");
  ASSERT_TRUE(s.wear->options.damage_layer_m.has_value());
  EXPECT_NEAR(*s.wear->options.damage_layer_m, 0.5e-3, 1e-18);
}

// The spread rule: without spread_rule as every scene before it (the adaptive rule at 0.005, or
// Gauss-Hermite with quadrature_points); by name each rule with its own key, the
// piecewise-linear rule on LinearSpreadNodes(spread_nodes). (Bad values: the bad-input corpus.)
TEST(SceneTest, SpreadRuleSelectsTheRuleAndKeepsOldScenes) {
  const auto options = [](const std::string& keys) {
    std::string scene = kWearScene;
    scene.insert(scene.find("max_depth_per_step_mm"), keys);
    return ParseScene(scene, "dir/wear.toml").wear->options;
  };
  const WearOptions old_default = options("");
  EXPECT_EQ(SpreadRuleOf(old_default), SpreadRule::kAdaptive);
  EXPECT_EQ(*old_default.integration_tolerance, kDefaultIntegrationTolerance);
  const WearOptions old_fixed = options("quadrature_points = 20\n");
  EXPECT_EQ(SpreadRuleOf(old_fixed), SpreadRule::kGaussHermite);
  EXPECT_EQ(old_fixed.quadrature_points, 20);
  const WearOptions adaptive =
      options("spread_rule = \"adaptive\"\nintegration_tolerance = 0.01\n");
  EXPECT_EQ(SpreadRuleOf(adaptive), SpreadRule::kAdaptive);
  EXPECT_EQ(*adaptive.integration_tolerance, 0.01);
  const WearOptions gh = options("spread_rule = \"gauss_hermite\"\n");
  EXPECT_EQ(SpreadRuleOf(gh), SpreadRule::kGaussHermite);
  EXPECT_EQ(gh.quadrature_points, WearOptions{}.quadrature_points);
  const WearOptions linear = options("spread_rule = \"piecewise_linear\"\nspread_nodes = 128\n");
  EXPECT_EQ(SpreadRuleOf(linear), SpreadRule::kPiecewiseLinear);
  EXPECT_FALSE(linear.integration_tolerance.has_value());
  EXPECT_EQ(linear.spread_nodes, LinearSpreadNodes(128));
  EXPECT_THROW(options("spread_rule = \"adaptive\"\nquadrature_points = 5\n"), InputError);
  EXPECT_THROW(options("spread_rule = \"gauss_hermite\"\nintegration_tolerance = 0.01\n"),
               InputError);
}

TEST(SceneTest, WearSceneErrorsNameTheKey) {
  const std::string scene = kWearScene;
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string t = scene;
    t.replace(t.find(from), from.size(), to);
    return ErrorOf(t);
  };
  EXPECT_TRUE(Contains(with("law = \"kth\"", "law = \"kth2\""),
                       "scene.toml:18: key 'wear.law' = \"kth2\": expected one of 'archard', "
                       "'kth', 'kth-continuous', 'usfd'"));
  EXPECT_TRUE(Contains(with("law = \"kth\"", "law = \"kth\"\nk = 1e-4"),
                       "key 'wear.k' = 0.0001: expected no 'k' with this law"));
  EXPECT_TRUE(Contains(with("total_MGT = 2.0", "total_MGT = 2.0\ntotal_passes = 1e6"),
                       "expected exactly one of 'wear.total_passes' and 'wear.total_MGT'"));
  EXPECT_TRUE(Contains(with("total_MGT = 2.0", ""),
                       "key 'wear.total_passes' is missing: expected exactly one of"));
  EXPECT_TRUE(Contains(with("lateral_shift_mm = -5", "lateral_shift_mm = { mean = -5, sd = 1 }"),
                       "key 'traffic[1].lateral_shift_mm.sd'"));
  EXPECT_TRUE(Contains(with("share = 0.4", "share = -0.4"),
                       "key 'traffic[0].share' = -0.4: expected a number in (0, 1000000]"));
  EXPECT_TRUE(Contains(with("friction = 0.3\n", ""), "key 'traffic[1].friction' is missing"));
  EXPECT_TRUE(Contains(with("hardness_MPa = 2600, ", ""),
                       "key 'materials.rail.hardness_MPa' is missing: expected the rail hardness "
                       "in MPa for the kth wear law"));
  EXPECT_TRUE(
      Contains(with("geometry = \"conformal\"\nkernel = \"boussinesq\"", "kind = \"hertz\""),
               "key 'model.kind' = \"hertz\": expected \"halfspace\" or \"conformal\" for a "
               "wear run"));
  EXPECT_TRUE(Contains(with("effects = [\"wear\", \"damage\"]", "effects = [\"damage\"]"),
                       "expected [wear] only in a wear scene: add \"wear\" to scene.effects"));
  EXPECT_TRUE(Contains(with("[[traffic]]\nname", "[traffic_]\nname"), "traffic_"));
}

}  // namespace
}  // namespace railwear::app

namespace railwear::app {
namespace {

TEST(SceneTest, YawBeyondAnglesOfAttackIsRefused) {
  // Yaw enters the contact geometry (issue 14): -500 mrad passed the old range and then tripped
  // the yawed outline's internal check; angles of attack are tens of milliradians.
  const std::string base = std::string(kMinimal) + "friction = 0.3\nspeed_m_s = 20\n";
  EXPECT_TRUE(Contains(ErrorOf(base + "yaw_mrad = -500\n"),
                       "key 'load.yaw_mrad' = -500: expected a number in [-100, 100)"));
  EXPECT_NEAR(ParseScene(base + "yaw_mrad = -99\n", "s.toml").problem.placement.yaw_rad, -0.099,
              1e-15);
}

// Wheel wear keys (issue 16 point 6): a wheel grade presets the wheel's hardness, wheel_wear
// makes the entry's wheel wear (its own grade overriding), and a population makes one entry per
// wheel with the entry's share split by weight.
TEST(SceneTest, WheelGradeWheelWearAndPopulationAreRead) {
  const std::string base = R"([scene]
effects = ["wear"]
[materials]
wheel = { grade = "R7" }
rail = { grade = "R260" }
[rail]
profile = "builtin:UIC60"
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[wear]
law = "archard"
total_passes = 1e4
[[traffic]]
name = "a"
vertical_N = 80000
lateral_shift_mm = -4.5
friction = 0.4
speed_m_s = 20
share = 2
wheel_wear = { distance_per_pass_m = 250, grade = "R8" }
[[traffic]]
name = "b"
vertical_N = 80000
lateral_shift_mm = -4.5
friction = 0.4
speed_m_s = 20
wheel_population = [ { name = "new", profile = "builtin:S1002", weight = 3 },
                     { name = "small", profile = "builtin:S1002", weight = 1, rolling_radius_mm = 420 } ]
)";
  const Scene s = ParseScene(base, "w.toml");
  EXPECT_DOUBLE_EQ(s.problem.wheel_material.hardness_Pa, 235.0 * 9.80665e6);
  EXPECT_DOUBLE_EQ(s.problem.wheel_material.youngs_modulus_Pa, 210e9);
  const std::vector<TrafficCase>& traffic = s.wear->traffic;
  ASSERT_EQ(traffic.size(), 3u);
  ASSERT_TRUE(traffic[0].wheel_wear.has_value());
  EXPECT_DOUBLE_EQ(traffic[0].wheel_wear->distance_per_pass_m, 250.0);
  EXPECT_DOUBLE_EQ(*traffic[0].wheel_wear->hardness_Pa, 245.0 * 9.80665e6);
  EXPECT_EQ(traffic[1].name, "b / new");
  EXPECT_EQ(traffic[2].name, "b / small");
  EXPECT_DOUBLE_EQ(traffic[1].share, 0.75);
  EXPECT_DOUBLE_EQ(traffic[2].share, 0.25);
  EXPECT_DOUBLE_EQ(traffic[1].rolling_radius_m, 0.46);
  EXPECT_DOUBLE_EQ(traffic[2].rolling_radius_m, 0.42);
  EXPECT_FALSE(traffic[1].wheel_wear.has_value());
  // The initial state carries the wearing wheel as given.
  const WearState start = MakeInitialState(*s.wear);
  ASSERT_EQ(start.wheels.size(), 3u);
  EXPECT_EQ(start.wheels[0].points(), traffic[0].wheel_profile.points());
  EXPECT_EQ(start.wheels[1].size(), 0);
}

}  // namespace
}  // namespace railwear::app
