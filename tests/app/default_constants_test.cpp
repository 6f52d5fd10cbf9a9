// Issue 17, point 7: the default model follows the project's evidence. Scenes use the
// FEM-calibrated influence constants unless they name others (the FEM contact cases put them
// within 2 % on peak pressure, the paper's 29 % high: docs/fem_contact_cases.md); the paper's
// stay available by name (`[model] constants = "paper"`, `contact --constants paper`), and the
// contact and wear summaries and JSON name the set used.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/influence_constants_file.h"
#include "app/scene.h"
#include "core/contact/influence_constant_sets.h"

#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"

namespace railwear::test {
namespace {

const std::string kGaugeCorner = RAILWEAR_SOURCE_DIR "/examples/gauge_corner.toml";
const std::string kCalibrated = RAILWEAR_SOURCE_DIR "/examples/calibration/calibrated_paper.toml";

class ConstantsCli : public CliFixture {
 protected:
  nlohmann::json ContactJson(const std::string& args) const {
    const Outcome o = Run("contact " + args + " --json -");
    EXPECT_EQ(o.exit_code, 0) << o.err;
    return nlohmann::json::parse(o.out);
  }
};

// The built-in "fem" set is the committed calibration file, to the last bit.
TEST(DefaultConstants, TheFemSetIsTheCommittedCalibration) {
  const InfluenceConstants file = app::ReadInfluenceConstantsFile(kCalibrated);
  EXPECT_EQ(file, NamedInfluenceConstants(InfluenceConstantsName::kFem));
  EXPECT_EQ(NameOf(file), InfluenceConstantsName::kFem);
  EXPECT_EQ(NamedInfluenceConstants(InfluenceConstantsName::kPaper), InfluenceConstants());
  EXPECT_EQ(app::ConstantsSetName(InfluenceConstants{.c_f = 0.9}), "custom");
}

TEST(DefaultConstants, AScenesDefaultIsTheFemSet) {
  const app::Scene scene = app::LoadScene(kGaugeCorner);
  EXPECT_EQ(scene.problem.model.constants,
            NamedInfluenceConstants(app::kDefaultInfluenceConstants));
  EXPECT_EQ(app::kDefaultInfluenceConstants, InfluenceConstantsName::kFem);
  EXPECT_EQ(scene.influence_constants_source, "fem");
}

TEST_F(ConstantsCli, TheContactSaysWhichConstantsAndThePapersAreNamed) {
  const nlohmann::json fem = ContactJson("'" + kGaugeCorner + "'");
  EXPECT_EQ(fem["model"]["constants"], "fem");
  const nlohmann::json paper = ContactJson("'" + kGaugeCorner + "' --constants paper");
  EXPECT_EQ(paper["model"]["constants"], "paper");
  EXPECT_EQ(paper["model"]["influence_constants"]["c_f"], 0.75);
  // The softer calibrated kernel: a larger patch and a lower peak (docs/models.md: 108 mm2 /
  // 2056 MPa against 84 mm2 / 2581 MPa at standard accuracy; the ratio is the FEM cases' 1.28
  // within the geometry's share, so only the direction and a 15 % margin are pinned here).
  const double p_fem = fem["total"]["p_max_MPa"].get<double>();
  const double p_paper = paper["total"]["p_max_MPa"].get<double>();
  EXPECT_GT(p_paper, 1.15 * p_fem);
  EXPECT_GT(fem["total"]["area_mm2"].get<double>(), 1.15 * paper["total"]["area_mm2"].get<double>());

  // The same sets by scene key: bit-identical to the command-line choice and to the file.
  std::string text = ReadFile(kGaugeCorner);
  const std::string model = "[model]\n";
  ASSERT_NE(text.find(model), std::string::npos);
  Write("paper.toml", std::string(text).replace(text.find(model), model.size(),
                                                model + "constants = \"paper\"\n"));
  EXPECT_EQ(ContactJson("paper.toml")["total"], paper["total"]);
  Write("file.toml", std::string(text).replace(
                         text.find(model), model.size(),
                         model + "influence_constants = '" + kCalibrated + "'\n"));
  const nlohmann::json file = ContactJson("file.toml");
  EXPECT_EQ(file["total"], fem["total"]);
  EXPECT_EQ(file["model"]["constants"], "fem");  // named by value, wherever it came from

  const Outcome summary = Run("contact '" + kGaugeCorner + "'");
  EXPECT_TRUE(Contains(summary.out, ", constants fem (convex c_f 1.109")) << summary.out;

  // Both ways of choosing at once: exit 2 naming the key.
  Write("both.toml", std::string(text).replace(
                         text.find(model), model.size(),
                         model + "constants = \"paper\"\ninfluence_constants = { c_f = 1 }\n"));
  const Outcome both = Run("contact both.toml");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_TRUE(Contains(both.err, "model.influence_constants")) << both.err;
  EXPECT_TRUE(Contains(both.err, "not both")) << both.err;
  Write("bad.toml", std::string(text).replace(text.find(model), model.size(),
                                              model + "constants = \"seed\"\n"));
  const Outcome bad = Run("contact bad.toml");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "model.constants")) << bad.err;
}

TEST_F(CliFixture, TheWearRunSaysWhichConstants) {
  Write("study.toml", kSmallWearStudy);
  const Outcome o = Run("wear study.toml --db s.sqlite --steps 1");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "model custom (geometry conformal, kernel boussinesq), accuracy "
                              "draft, constants fem"))
      << o.out;
  const Outcome q = Run("history --db s.sqlite sql \"SELECT wear_law_json FROM runs\"");
  ASSERT_EQ(q.exit_code, 0) << q.err;
  EXPECT_TRUE(Contains(q.out, "\"constants\":\"fem\"")) << q.out;
}

}  // namespace
}  // namespace railwear::test
