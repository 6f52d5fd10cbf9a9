// Issue 17's first run: `railwear init` then `railwear contact` gives a tread contact below the
// rail's hardness and Nadal's limit; [load] lateral_mm places the wheel from the centred
// wheelset (0 = centred on the stated gauge) while lateral_shift_mm keeps the profile-origin
// meaning; p_max beyond the hardness and L/V beyond Nadal's limit are warned of in the summary,
// the JSON and on stderr.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/scene.h"
#include "app/scene_template.h"
#include "core/geometry/wheelset.h"

#include "tests/app/cli_runner.h"

namespace railwear::test {
namespace {

// The template with its [load] lateral line replaced.
std::string TemplateWith(const std::string& lateral_line) {
  std::string text(app::SceneTemplate());
  const std::string from = "lateral_mm = 0.0";
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos);
  return text.replace(at, from.size(), lateral_line);
}

TEST_F(CliFixture, InitThenContactIsATreadContactBelowHardnessAndNadal) {
  ASSERT_EQ(Run("init scene.toml").exit_code, 0);
  const Outcome o = Run("contact scene.toml --json -");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.err, "");  // no warning
  const nlohmann::json j = nlohmann::json::parse(o.out);
  const app::Scene scene = app::LoadScene((dir_ / "scene.toml").string());
  const double hardness_MPa = scene.problem.rail_material.hardness_Pa * 1e-6;
  ASSERT_GT(hardness_MPa, 0.0);
  const double p_max = j["total"]["p_max_MPa"].get<double>();
  EXPECT_LT(p_max, hardness_MPa);
  // A tread or gauge-corner contact: one patch, contact angle well below the flange's 60-70 deg.
  ASSERT_EQ(j["patches"].size(), 1u);
  const double angle_deg = j["patches"][0]["contact_angle_deg"].get<double>();
  EXPECT_LT(std::abs(angle_deg), 30.0);
  const nlohmann::json& climb = j["flange_climb_check"];
  EXPECT_EQ(climb["friction"], 0.3);  // the scene's friction sets the limit, normal contact too
  if (!climb["nadal_limit"].is_null()) {
    EXPECT_LT(climb["l_over_v"].get<double>(), climb["nadal_limit"].get<double>());
  }
  EXPECT_FALSE(j["flange_climb"].get<bool>());
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];
  EXPECT_EQ(j["placement"]["lateral_mm"], 0.0);
  std::cout << "[figure] init -> contact: p_max " << p_max << " MPa (hardness " << hardness_MPa
            << "), contact angle " << angle_deg << " deg, L/V " << climb["l_over_v"] << ", Nadal "
            << climb["nadal_limit"] << ", wheel origin at " << j["placement"]["lateral_shift_mm"]
            << " mm\n";
}

TEST(FirstRunPlacement, LateralZeroIsTheCentredWheelset) {
  // Centred: the flange back stands (gauge - flange back distance) / 2 = 37.5 mm inside the
  // rail's gauge point, whatever the rail's cant does to the gauge point's place.
  const app::Scene centred = app::ParseScene(std::string(app::SceneTemplate()), "t.toml");
  ASSERT_TRUE(centred.centred.has_value());
  const double gauge_point_y = RailGaugePoint(centred.problem.rail_profile, 0.014).x();
  const double flange_back_y = centred.problem.placement.lateral_shift_m - 0.070;
  EXPECT_NEAR(flange_back_y, gauge_point_y - 0.0375, 1e-12);
  // lateral_mm moves the wheel by itself; another gauge moves it by half the change.
  const app::Scene moved = app::ParseScene(TemplateWith("lateral_mm = 4.5"), "t.toml");
  EXPECT_NEAR(moved.problem.placement.lateral_shift_m - centred.problem.placement.lateral_shift_m,
              4.5e-3, 1e-12);
  const app::Scene wide =
      app::ParseScene(TemplateWith("lateral_mm = 0\ngauge_mm = 1445"), "t.toml");
  EXPECT_NEAR(wide.problem.placement.lateral_shift_m - centred.problem.placement.lateral_shift_m,
              -5e-3, 1e-12);
  // The old key keeps its meaning: the wheel profile's origin relative to the rail's.
  const app::Scene old = app::ParseScene(TemplateWith("lateral_shift_mm = -10.4"), "t.toml");
  EXPECT_FALSE(old.centred.has_value());
  EXPECT_DOUBLE_EQ(old.problem.placement.lateral_shift_m, -10.4e-3);
}

TEST_F(CliFixture, FlangeContactWarnsOfHardnessAndNadal) {
  // The old template's position: the profiles' origins aligned puts the wheel on its flange.
  Write("scene.toml", TemplateWith("lateral_shift_mm = 0"));
  const Outcome o = Run("contact scene.toml --json out.json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  for (const std::string& text : {o.out, o.err}) {
    EXPECT_TRUE(Contains(text, "exceeds the rail's hardness 2600 MPa")) << text;
    EXPECT_TRUE(Contains(text, "exceeds Nadal's limit")) << text;
  }
  EXPECT_TRUE(Contains(o.out, "WARNING     p_max"));
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir_ / "out.json"));
  ASSERT_EQ(j["warnings"].size(), 2u);
  EXPECT_TRUE(j["flange_climb"].get<bool>());
  // With the pressure limited to the hardness the pressure warning goes, the climb one stays.
  std::string limited = TemplateWith("lateral_shift_mm = 0");
  limited.replace(limited.find("# pressure_limit = \"hardness\""), 30,
                  "pressure_limit = \"hardness\"  ");
  Write("limited.toml", limited);
  const Outcome l = Run("contact limited.toml");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_FALSE(Contains(l.out, "hardness 2600 MPa: the elastic")) << l.out;
  EXPECT_TRUE(Contains(l.out, "exceeds Nadal's limit")) << l.out;
}

}  // namespace
}  // namespace railwear::test
