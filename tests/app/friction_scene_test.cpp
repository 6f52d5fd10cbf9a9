// Scene keys of issue 16 points 1 and 3: friction conditions per [[traffic]] entry
// (condition, gauge_face_condition), their overrides ([wear.conditions.NAME],
// gauge_face_angle_deg) and rail grades ([materials] rail = { grade = "R350HT" }); bad values
// name file, line, key and value and exit 2.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "app/scene.h"
#include "core/numerics/input_error.h"
#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"
#include "wear/rail_grade.h"

namespace railwear::app {
namespace {

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) return "MISSING '" + from + "'";
  return text.replace(at, from.size(), to);
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseScene(text, "s.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n  message: " << text << "\n  lacks:   " << part;
}

const std::string kBase = test::kSmallWearStudy;

TEST(FrictionSceneTest, ConditionsAndTheirOverridesReachTheStudy) {
  // Without any of the new keys nothing changes: no condition, factor 1, the entry's mu.
  {
    const Scene s = ParseScene(kBase, "s.toml");
    EXPECT_FALSE(s.wear->traffic[0].condition.has_value());
    EXPECT_FALSE(s.wear->traffic[0].gauge_face_condition.has_value());
    EXPECT_DOUBLE_EQ(s.wear->traffic[0].friction, 0.4);
  }
  // A condition without friction gives its mu; a gauge-face condition is kept.
  std::string text = Replace(kBase, "friction = 0.4\n",
                             "condition = \"wet\"\ngauge_face_condition = \"lubricated\"\n");
  text = Replace(text, "quadrature_points = 3\n",
                 "quadrature_points = 3\ngauge_face_angle_deg = 20\n"
                 "[wear.conditions.lubricated]\nfriction = 0.12\nkth_factor = 0.15\n");
  const Scene s = ParseScene(text, "s.toml");
  const TrafficCase& c = s.wear->traffic[0];
  EXPECT_EQ(c.condition, FrictionCondition::kWet);
  EXPECT_EQ(c.gauge_face_condition, FrictionCondition::kLubricated);
  EXPECT_DOUBLE_EQ(c.friction, 0.25);
  const FrictionConditions& fc = s.wear->options.conditions;
  EXPECT_DOUBLE_EQ(fc[FrictionCondition::kLubricated].friction, 0.12);
  EXPECT_DOUBLE_EQ(fc[FrictionCondition::kLubricated].kth_factor, 0.15);
  EXPECT_DOUBLE_EQ(fc[FrictionCondition::kLubricated].archard_factor, 0.1);  // default kept
  EXPECT_NEAR(fc.gauge_face_angle_rad, 20.0 * M_PI / 180.0, 1e-15);
  // An explicit friction beside a condition is the top of rail's mu.
  const Scene t = ParseScene(Replace(kBase, "friction = 0.4\n",
                                     "friction = 0.45\ncondition = "
                                     "\"dry\"\n"),
                             "s.toml");
  EXPECT_DOUBLE_EQ(t.wear->traffic[0].friction, 0.45);
  EXPECT_EQ(t.wear->traffic[0].condition, FrictionCondition::kDry);
}

TEST(FrictionSceneTest, BadConditionValuesNameFileKeyAndValue) {
  const auto with = [](const std::string& from, const std::string& to) {
    return ErrorOf(Replace(kBase, from, to));
  };
  EXPECT_TRUE(Contains(with("friction = 0.4\n", "condition = \"greasy\"\n"),
                       "s.toml:28: key 'traffic[0].condition' = \"greasy\": expected one of "
                       "'dry', 'wet', 'lubricated', 'friction_modified'"));
  EXPECT_TRUE(Contains(with("friction = 0.4\n", "friction = 0.4\ngauge_face_condition = 1\n"),
                       "key 'traffic[0].gauge_face_condition'"));
  EXPECT_TRUE(Contains(with("friction = 0.4\n", ""),
                       "key 'traffic[0].friction' is missing: expected a friction coefficient "
                       "in (0, 2], or a condition"));
  EXPECT_TRUE(Contains(with("quadrature_points = 3\n",
                            "quadrature_points = 3\n[wear.conditions.wet]\nkth_factor = -1\n"),
                       "s.toml:24: key 'wear.conditions.wet.kth_factor' = -1: expected a number "
                       "in (0, 10]"));
  EXPECT_TRUE(Contains(with("quadrature_points = 3\n",
                            "quadrature_points = 3\n[wear.conditions.wet]\nfriction = 3\n"),
                       "key 'wear.conditions.wet.friction' = 3: expected a number in (0, 2]"));
  EXPECT_TRUE(Contains(with("quadrature_points = 3\n",
                            "quadrature_points = 3\n[wear.conditions.icy]\nfriction = 0.05\n"),
                       "wear.conditions"));
  EXPECT_TRUE(Contains(
      with("quadrature_points = 3\n", "quadrature_points = 3\n[wear.conditions.wet]\nmu = 0.2\n"),
      "wear.conditions.wet"));
  EXPECT_TRUE(Contains(with("quadrature_points = 3\n",
                            "quadrature_points = 3\n"
                            "gauge_face_angle_deg = 95\n"),
                       "key 'wear.gauge_face_angle_deg' = 95: expected an angle in (0, 90)"));
}

TEST(FrictionSceneTest, ARailGradePresetsTheRailAndKeysBesideItOverride) {
  const std::string rail_line =
      "rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600, shear_yield_MPa = 350 }";
  const Scene s = ParseScene(Replace(kBase, rail_line, "rail = { grade = \"R350HT\" }"), "s.toml");
  const RailGradeProperties g = RailGradeOf(RailGrade::kR350HT);
  EXPECT_DOUBLE_EQ(s.wear->rail_material.hardness_Pa, g.hardness_Pa);
  EXPECT_DOUBLE_EQ(s.wear->rail_material.shear_yield_Pa, g.shear_yield_Pa);
  EXPECT_DOUBLE_EQ(s.wear->rail_material.youngs_modulus_Pa, 210e9);
  EXPECT_DOUBLE_EQ(s.wear->rail_material.poisson_ratio, 0.28);
  const Scene t = ParseScene(
      Replace(kBase, rail_line, "rail = { grade = \"R200\", hardness_MPa = 2300 }"), "s.toml");
  EXPECT_DOUBLE_EQ(t.wear->rail_material.hardness_Pa, 2300e6);
  EXPECT_DOUBLE_EQ(t.wear->rail_material.shear_yield_Pa,
                   RailGradeOf(RailGrade::kR200).shear_yield_Pa);
  EXPECT_TRUE(Contains(ErrorOf(Replace(kBase, rail_line, "rail = { grade = \"R400HT\" }")),
                       "s.toml:10: key 'materials.rail.grade' = \"R400HT\": expected one of "
                       "'R200', 'R260', 'R350HT'"));
  // Without a grade E and nu stay required.
  EXPECT_TRUE(Contains(ErrorOf(Replace(kBase, rail_line, "rail = { hardness_MPa = 2600 }")),
                       "key 'materials.rail.E_MPa' is missing"));
}

std::string ReadSource(const std::string& path) {
  std::ifstream in(std::string(RAILWEAR_SOURCE_DIR) + "/" + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(FrictionSceneTest, VehicleAndCollectiveEntriesTakeConditions) {
  const std::string dir = std::string(RAILWEAR_SOURCE_DIR) + "/examples/";
  // A vehicle entry: the condition gives mu (the curving equilibrium's and the top of rail's).
  const std::string vehicles = ReadSource("examples/curve_r600_vehicles.toml");
  const Scene v = ParseScene(
      Replace(vehicles, "friction = 0.35\n",
              "condition = \"friction_modified\"\ngauge_face_condition = \"lubricated\"\n"),
      dir + "v.toml");
  const TrafficCase& vc = v.wear->traffic[0];
  ASSERT_TRUE(vc.is_vehicle());
  EXPECT_EQ(vc.condition, FrictionCondition::kFrictionModified);
  EXPECT_EQ(vc.gauge_face_condition, FrictionCondition::kLubricated);
  EXPECT_DOUBLE_EQ(vc.friction, 0.35);
  // A collective whose bins carry mu: the condition adds its factors, the bins keep their mu.
  const std::string collective = ReadSource("examples/curve_r600_mbs_collective.toml");
  const size_t at = collective.find("\ncollective = ") + 1;
  ASSERT_NE(at, 0u);
  std::string text = collective;
  text.insert(at, "gauge_face_condition = \"lubricated\"\n");
  const Scene c = ParseScene(text, dir + "c.toml");
  ASSERT_TRUE(c.wear->traffic[0].is_collective());
  EXPECT_EQ(c.wear->traffic[0].gauge_face_condition, FrictionCondition::kLubricated);
  EXPECT_FALSE(c.wear->traffic[0].condition.has_value());
}

class FrictionCli : public test::CliFixture {};

TEST_F(FrictionCli, BadConditionValueExitsWithTwo) {
  Write("s.toml", Replace(kBase, "quadrature_points = 3\n",
                          "quadrature_points = 3\n[wear.conditions.lubricated]\n"
                          "archard_factor = 0\n"));
  const test::Outcome o = Run("wear s.toml --db s.sqlite --steps 1");
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_TRUE(Contains(o.err, "s.toml:24: key 'wear.conditions.lubricated.archard_factor' = 0"));
}

TEST_F(FrictionCli, ALubricatedGaugeFaceRunsAndWearsLess) {
  Write("dry.toml", kBase);
  Write("lub.toml", Replace(kBase, "friction = 0.4\n",
                            "condition = \"dry\"\nfriction = 0.4\n"
                            "gauge_face_condition = \"lubricated\"\n"));
  // Each step removes at most 0.05 mm: the passes it takes are the inverse of the wear rate.
  const auto step_passes = [&](const std::string& args) {
    const test::Outcome o = Run(args);
    EXPECT_EQ(o.exit_code, 0) << o.err;
    const size_t at = o.err.find("step 1: ");
    if (at == std::string::npos) return 0.0;
    return std::stod(o.err.substr(at + 8));
  };
  const double dry = step_passes("wear dry.toml --db dry.sqlite --steps 1");
  const double lubricated = step_passes("wear lub.toml --db lub.sqlite --steps 1");
  EXPECT_GT(dry, 0.0);
  EXPECT_GE(lubricated, 3.0 * dry);
}

}  // namespace
}  // namespace railwear::app
