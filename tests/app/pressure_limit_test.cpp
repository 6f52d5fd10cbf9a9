// The pressure limit from the scene to the outputs (issue 16 point 2): [model] pressure_limit and
// pressure_limit_MPa parsed and refused where they cannot apply; `railwear contact` prints and
// writes the plastic share only when a limit is set; a wear run stores it in each load case's
// JSON.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/scene.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"

namespace railwear::test {
namespace {

using app::ParseScene;
using app::Scene;

// S1002 on UIC60 1:40 at the gauge corner (examples/gauge_corner.toml's placement), 100 kN,
// normal contact, with a rail hardness the elastic peak passes.
const char* const kGaugeCorner = R"([model]
kind = "conformal"
accuracy = "draft"
{model_extra}
[materials]
wheel = {{ E_MPa = 210000, nu = 0.28 }}
rail = {{ E_MPa = 210000, nu = 0.28, hardness_MPa = 1200 }}
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[load]
vertical_N = 100000
lateral_shift_mm = -4.0
)";

std::string GaugeCorner(const std::string& model_extra) {
  std::string s = kGaugeCorner;
  s.replace(s.find("{model_extra}"), 13, model_extra);
  for (size_t at = s.find("{{"); at != std::string::npos; at = s.find("{{")) s.replace(at, 2, "{");
  for (size_t at = s.find("}}"); at != std::string::npos; at = s.find("}}")) s.replace(at, 2, "}");
  return s;
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseScene(text, "scene.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PressureLimitScene, OffByDefault) {
  const Scene s = ParseScene(GaugeCorner(""), "scene.toml");
  EXPECT_EQ(s.problem.pressure_limit.kind, PressureLimitKind::kNone);
}

TEST(PressureLimitScene, HardnessAndExplicitValue) {
  const Scene h = ParseScene(GaugeCorner("pressure_limit = \"hardness\""), "scene.toml");
  EXPECT_EQ(h.problem.pressure_limit.kind, PressureLimitKind::kHardness);
  EXPECT_EQ(
      *PressureLimitOf(h.problem.pressure_limit, h.problem.wheel_material, h.problem.rail_material),
      1200e6);
  const Scene v = ParseScene(GaugeCorner("pressure_limit_MPa = 1800"), "scene.toml");
  EXPECT_EQ(v.problem.pressure_limit.kind, PressureLimitKind::kValue);
  EXPECT_EQ(v.problem.pressure_limit.value_Pa, 1800e6);
  const Scene none = ParseScene(GaugeCorner("pressure_limit = \"none\""), "scene.toml");
  EXPECT_EQ(none.problem.pressure_limit.kind, PressureLimitKind::kNone);
}

TEST(PressureLimitScene, SofterBodyDecides) {
  std::string text = GaugeCorner("pressure_limit = \"hardness\"");
  const std::string wheel = "wheel = { E_MPa = 210000, nu = 0.28 }";
  text.replace(text.find(wheel), wheel.size(),
               "wheel = { E_MPa = 210000, nu = 0.28, hardness_MPa = 1000 }");
  const Scene s = ParseScene(text, "scene.toml");
  EXPECT_EQ(
      *PressureLimitOf(s.problem.pressure_limit, s.problem.wheel_material, s.problem.rail_material),
      1000e6);
}

TEST(PressureLimitScene, BadInputNamesTheKey) {
  EXPECT_NE(ErrorOf(GaugeCorner("pressure_limit = \"yield\"")).find("model.pressure_limit"),
            std::string::npos);
  const std::string both =
      ErrorOf(GaugeCorner("pressure_limit = \"hardness\"\npressure_limit_MPa = 2000"));
  EXPECT_NE(both.find("not both"), std::string::npos) << both;
  EXPECT_NE(ErrorOf(GaugeCorner("pressure_limit_MPa = 0")).find("pressure_limit_MPa"),
            std::string::npos);
  std::string hertz = GaugeCorner("pressure_limit = \"hardness\"");
  hertz.replace(hertz.find("kind = \"conformal\""), 18, "kind = \"hertz\"");
  EXPECT_NE(ErrorOf(hertz).find("no pressure limit with kind = 'hertz'"), std::string::npos)
      << ErrorOf(hertz);
  std::string no_hardness = GaugeCorner("pressure_limit = \"hardness\"");
  no_hardness.replace(no_hardness.find(", hardness_MPa = 1200"), 21, "");
  const std::string e = ErrorOf(no_hardness);
  EXPECT_NE(e.find("materials.rail.hardness_MPa"), std::string::npos) << e;
}

using PressureLimitCli = CliFixture;

TEST_F(PressureLimitCli, ContactReportsThePlasticShareOnlyWithALimit) {
  Write("elastic.toml", GaugeCorner(""));
  Write("limited.toml", GaugeCorner("pressure_limit = \"hardness\""));
  const Outcome e = Run("contact elastic.toml --json elastic.json");
  const Outcome l = Run("contact limited.toml --json limited.json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_FALSE(Contains(e.out, "plastic"));
  EXPECT_TRUE(Contains(l.out, "plastic     pressure limit 1200.0 MPa: "));
  const nlohmann::json je = nlohmann::json::parse(ReadFile(dir_ / "elastic.json"));
  const nlohmann::json jl = nlohmann::json::parse(ReadFile(dir_ / "limited.json"));
  EXPECT_FALSE(je["total"].contains("plastic"));
  ASSERT_TRUE(jl["total"].contains("plastic"));
  const nlohmann::json& p = jl["total"]["plastic"];
  EXPECT_EQ(p["pressure_limit_MPa"].get<double>(), 1200.0);
  EXPECT_GT(p["cells"].get<int>(), 0);
  EXPECT_GT(p["area_mm2"].get<double>(), 0.0);
  EXPECT_GT(p["force_share"].get<double>(), 0.0);
  EXPECT_LE(p["force_share"].get<double>(), 1.0);
  EXPECT_LE(jl["total"]["p_max_MPa"].get<double>(), 1200.0);
  EXPECT_GT(je["total"]["p_max_MPa"].get<double>(), 1200.0);
  EXPECT_GT(jl["total"]["area_mm2"].get<double>(), je["total"]["area_mm2"].get<double>());
  EXPECT_TRUE(jl["patches"][0].contains("plastic"));
}

TEST_F(PressureLimitCli, WearLoadCasesStoreThePlasticShare) {
  std::string study = kSmallWearStudy;
  study.replace(study.find("accuracy = \"draft\""), 18,
                "accuracy = \"draft\"\npressure_limit_MPa = 1000");
  Write("study.toml", study);
  const Outcome o = Run("wear study.toml --db a.sqlite --steps 1");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  ProfileStore store = ProfileStore::Open((dir_ / "a.sqlite").string());
  const auto run = store.FindRun("small study");
  ASSERT_TRUE(run.has_value());
  const StepRecord step = store.LoadStep(run->id, 1);
  ASSERT_FALSE(step.load_cases_json.empty());
  int plastic_cases = 0;
  for (const std::string& text : step.load_cases_json) {
    const nlohmann::json j = nlohmann::json::parse(text);
    ASSERT_TRUE(j.contains("plastic")) << text;
    EXPECT_EQ(j["plastic"]["pressure_limit_MPa"].get<double>(), 1000.0);
    EXPECT_LE(j["p_max_MPa"].get<double>(), 1000.0);
    plastic_cases += j["plastic"]["cells"].get<int>() > 0;
  }
  EXPECT_GT(plastic_cases, 0);
}

}  // namespace
}  // namespace railwear::test
