// Effects decide which stages run (issue 6, DESIGN.md §2): a normal-only scene computes no
// traction, slip or damage and does less work than the same scene with them; every result
// reports which stages ran and their time. The scene is examples/rolling_gauge_corner.toml
// (effects normal, tangential, damage) and the same text with effects = ["normal"].
#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "app/contact_output.h"
#include "app/scene.h"

namespace railwear::app {
namespace {

std::string RollingSceneText() {
  std::ifstream in(std::string(RAILWEAR_SOURCE_DIR) + "/examples/rolling_gauge_corner.toml");
  std::ostringstream os;
  os << in.rdbuf();
  std::string text = os.str();
  const size_t a = text.find("accuracy = \"standard\"");
  EXPECT_NE(a, std::string::npos);
  return text.replace(a, 21, "accuracy = \"draft\"  ");  // fast; the stages are the same
}

std::string NormalOnly(std::string text) {
  const std::string rolling = "effects = [\"normal\", \"tangential\", \"damage\"]";
  const size_t a = text.find(rolling);
  EXPECT_NE(a, std::string::npos);
  return text.replace(a, rolling.size(), "effects = [\"normal\"]");
}

std::set<std::string> StageNames(const ContactResult& r) {
  std::set<std::string> names;
  for (const auto& s : r.stages) names.insert(s.name);
  return names;
}

TEST(Effects, NormalOnlySceneComputesNoTractionSlipOrDamageAndDoesLessWork) {
  const Scene rolling = ParseScene(RollingSceneText(), "rolling_gauge_corner.toml");
  const Scene normal = ParseScene(NormalOnly(RollingSceneText()), "rolling_gauge_corner.toml");
  ASSERT_TRUE(rolling.problem.rolling.has_value());
  ASSERT_FALSE(normal.problem.rolling.has_value());  // the stage is never constructed
  const ContactResult r = SolveContact(rolling.problem);
  const ContactResult n = SolveContact(normal.problem);
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  ASSERT_EQ(n.status, SolverStatus::kConverged) << n.message;

  // No traction, slip or damage anywhere in the normal-only result, its JSON or its CSV.
  for (const auto& p : n.patches) EXPECT_FALSE(p.rolling.has_value());
  const nlohmann::json jn = MakeContactJson(normal, n);
  EXPECT_FALSE(jn["total"].contains("creep_force_x_N"));
  EXPECT_FALSE(jn.contains("pitch_velocity_rad_s"));
  for (const auto& p : jn["patches"]) {
    for (const char* key :
         {"creep_force_N", "stick_area_mm2", "slip_area_mm2", "damage", "frictional_power_W"}) {
      EXPECT_FALSE(p.contains(key)) << key;
    }
  }
  std::ostringstream csv;
  WritePressureCsv(n, csv);
  EXPECT_EQ(csv.str().substr(0, csv.str().find('\n')), "patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa");
  // ... while the rolling scene has them on every patch.
  for (const auto& p : r.patches) {
    ASSERT_TRUE(p.rolling.has_value());
    EXPECT_TRUE(p.rolling->damage.has_value());
    EXPECT_GT(p.rolling->tangential.slip_area_m2 + p.rolling->tangential.stick_area_m2, 0.0);
  }

  // Less work: the normal-only stages are a strict subset of the rolling scene's (the rolling
  // scene runs the same normal stages, the tangential one on top and, under its prescribed load,
  // the vertical balance with the creep forces, issue 14, which re-solves the normal problem).
  const std::set<std::string> sn = StageNames(n), sr = StageNames(r);
  EXPECT_TRUE(std::includes(sr.begin(), sr.end(), sn.begin(), sn.end()));
  EXPECT_EQ(sr.size(), sn.size() + 2);
  EXPECT_EQ(sr.count("tangential"), 1u);
  EXPECT_EQ(sr.count("balance"), 1u);
  EXPECT_EQ(sn.count("tangential") + sn.count("coupling") + sn.count("balance"), 0u);
  EXPECT_GE(r.balance_iterations, 1);
  EXPECT_EQ(n.balance_iterations, 0);
  EXPECT_LT(n.iterations, r.iterations);
}

TEST(Effects, EveryResultReportsItsStagesAndTheirTimes) {
  const Scene rolling = ParseScene(RollingSceneText(), "rolling_gauge_corner.toml");
  const ContactResult r = SolveContact(rolling.problem);
  const std::set<std::string> known = {"placement",  "model selection", "hertz",
                                       "grid",       "influence",       "solve",
                                       "tangential", "coupling",        "balance"};
  double sum = 0.0;
  for (const auto& s : r.stages) {
    EXPECT_EQ(known.count(s.name), 1u) << s.name;
    EXPECT_GE(s.seconds, 0.0) << s.name;
    sum += s.seconds;
  }
  // The stages are timed inside the whole solve's time.
  EXPECT_LE(sum, r.time_s * (1.0 + 1e-9));
  EXPECT_EQ(StageNames(r), (std::set<std::string>{"placement", "grid", "influence", "solve",
                                                  "tangential", "balance"}));
  const nlohmann::json j = MakeContactJson(rolling, r);
  ASSERT_EQ(j["stages"].size(), r.stages.size());
  for (size_t k = 0; k < r.stages.size(); ++k) {
    EXPECT_EQ(j["stages"][k]["name"], r.stages[k].name);
    EXPECT_DOUBLE_EQ(j["stages"][k]["time_ms"].get<double>(), r.stages[k].seconds * 1e3);
  }
}

}  // namespace
}  // namespace railwear::app
