// kind = "auto" in scenes and in the output of `railwear contact` (issue 6): the scene accepts it
// (and a kernel for its conformal patches, but no geometry), the JSON reports each patch's model
// and why it was chosen, the summary prints the reasons.
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "app/contact_output.h"
#include "app/scene.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n  text:  " << text << "\n  lacks: " << part;
}

// examples/tread.toml with its [model] table replaced.
std::string TreadScene(const std::string& model_table) {
  std::ifstream in(std::string(RAILWEAR_SOURCE_DIR) + "/examples/tread.toml");
  std::ostringstream os;
  os << in.rdbuf();
  std::string text = os.str();
  const size_t a = text.find("[model]");
  const size_t b = text.find("[materials]");
  return text.substr(0, a) + model_table + "\n" + text.substr(b);
}

TEST(AutoModel, SceneAcceptsAutoAndAKernelButNoGeometry) {
  const Scene s = ParseScene(TreadScene("[model]\nkind = \"auto\"\n"), "tread.toml");
  EXPECT_EQ(s.problem.model.kind, ModelKind::kAuto);
  EXPECT_EQ(s.problem.model.kernel, KernelModel::kBoussinesq);  // FEM evidence, DESIGN.md §1
  const Scene g =
      ParseScene(TreadScene("[model]\nkind = \"auto\"\nkernel = \"golubenko\"\n"), "tread.toml");
  EXPECT_EQ(g.problem.model.kind, ModelKind::kAuto);
  EXPECT_EQ(g.problem.model.kernel, KernelModel::kGolubenko);
  try {
    ParseScene(TreadScene("[model]\nkind = \"auto\"\ngeometry = \"planar\"\n"), "tread.toml");
    FAIL() << "geometry with kind = auto was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "tread.toml:"));
    EXPECT_TRUE(Contains(e.what(),
                         "key 'model.geometry' = \"planar\": expected no geometry "
                         "with kind = 'auto' (it picks one per patch)"));
  }
}

TEST(AutoModel, JsonAndSummaryReportEachPatchsModelAndWhy) {
  Scene s =
      ParseScene(TreadScene("[model]\nkind = \"auto\"\naccuracy = \"draft\"\n"), "tread.toml");
  const ContactResult r = SolveContact(s.problem);
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  const nlohmann::json j = MakeContactJson(s, r);
  EXPECT_EQ(j["model"]["kind"], "auto");
  EXPECT_TRUE(j["model"]["geometry"].is_null());  // per patch
  EXPECT_EQ(j["model"]["kernel"], "boussinesq");
  ASSERT_FALSE(j["patches"].empty());
  for (const auto& p : j["patches"]) {
    EXPECT_EQ(p["model"], "halfspace");
    EXPECT_TRUE(Contains(p["model_reason"].get<std::string>(), "halfspace: over the solved patch"));
  }
  const std::string summary = FormatSummary(s, r);
  EXPECT_TRUE(Contains(summary,
                       "model       auto (per patch: hertz, halfspace or "
                       "conformal+boussinesq), accuracy draft"));
  EXPECT_TRUE(Contains(summary, "patch 1 model: halfspace: over the solved patch"));

  // A fixed model labels its patches too, without a reason.
  s.problem.model = MakeModelOptions(ModelKind::kConformal);
  s.problem.model.accuracy = AccuracyPreset::kDraft;
  const nlohmann::json c = MakeContactJson(s, SolveContact(s.problem));
  EXPECT_EQ(c["patches"][0]["model"], "conformal+golubenko");
  EXPECT_FALSE(c["patches"][0].contains("model_reason"));
}

}  // namespace
}  // namespace railwear::app
