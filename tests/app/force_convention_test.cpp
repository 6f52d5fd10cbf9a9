// The labelled forces of `railwear contact` (issue 14): the JSON's "forces" totals are the sums
// of its per-patch forces, L/V computed from the JSON is the printed one, and a flange case
// beyond Nadal's limit carries the warning and the status a tread case does not.
#include <cmath>
#include <regex>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app/contact_output.h"
#include "app/scene.h"
#include "core/contact/contact_solver.h"

namespace railwear::app {
namespace {

// S1002 on UIC60 1:40, 80 kN, mu 0.35, rolling at 20 m/s with the given shift and yaw.
Scene RollingScene(double shift_mm, double yaw_mrad) {
  return ParseScene(fmt::format(R"(
[scene]
name = "labelled forces"
effects = ["normal", "tangential"]
[model]
kind = "conformal"
accuracy = "standard"
[materials]
wheel = {{ E_MPa = 210000, nu = 0.28 }}
rail = {{ E_MPa = 210000, nu = 0.28 }}
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[load]
vertical_N = 80000
lateral_shift_mm = {}
friction = 0.35
speed_m_s = 20.0
yaw_mrad = {}
)",
                                shift_mm, yaw_mrad),
                    "<text>");
}

struct Solved {
  ContactResult result;
  nlohmann::json json;
  std::string summary;
};

Solved Solve(const Scene& scene) {
  Solved s;
  s.result = SolveContact(scene.problem);
  s.json = MakeContactJson(scene, s.result);
  s.summary = FormatSummary(scene, s.result);
  return s;
}

Eigen::Vector3d Xyz(const nlohmann::json& j) {
  return {j["x"].get<double>(), j["y"].get<double>(), j["z"].get<double>()};
}

TEST(ForceConvention, FlangeBeyondNadalWarnsTreadDoesNot) {
  // Flange contact at 65 degrees, yaw 15 mrad: L/V about 1.7 against Nadal's 1.03.
  const Solved flange = Solve(RollingScene(-1.5, 15.0));
  ASSERT_EQ(flange.result.status, SolverStatus::kConverged) << flange.result.message;
  EXPECT_TRUE(flange.json["flange_climb"].get<bool>());
  EXPECT_TRUE(flange.json["flange_climb_check"]["exceeded"].get<bool>());
  ASSERT_EQ(flange.json["warnings"].size(), 1u);
  EXPECT_NE(flange.json["warnings"][0].get<std::string>().find("Nadal"), std::string::npos);
  EXPECT_NE(flange.summary.find("WARNING"), std::string::npos);

  const Solved tread = Solve(RollingScene(-8.0, 0.0));
  ASSERT_EQ(tread.result.status, SolverStatus::kConverged) << tread.result.message;
  EXPECT_FALSE(tread.json["flange_climb"].get<bool>());
  EXPECT_TRUE(tread.json["warnings"].empty());
  EXPECT_EQ(tread.summary.find("WARNING"), std::string::npos);
}

TEST(ForceConvention, TotalsArePatchSumsAndLOverVIsThePrintedOne) {
  const Solved s = Solve(RollingScene(-1.5, 15.0));
  ASSERT_EQ(s.result.status, SolverStatus::kConverged) << s.result.message;
  const nlohmann::json& forces = s.json["forces"];
  EXPECT_EQ(forces["on"], "rail");
  for (const char* frame : {"rail", "track"}) {
    for (const char* part : {"normal", "creep", "net"}) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const auto& p : forces["patches"]) sum += Xyz(p[frame][part]);
      const Eigen::Vector3d total = Xyz(forces["total"][frame][part]);
      EXPECT_LT((sum - total).norm(), 1e-9 * 80e3) << frame << " " << part;
    }
    // net = normal + creep
    const Eigen::Vector3d net = Xyz(forces["total"][frame]["net"]);
    const Eigen::Vector3d parts =
        Xyz(forces["total"][frame]["normal"]) + Xyz(forces["total"][frame]["creep"]);
    EXPECT_LT((net - parts).norm(), 1e-9 * 80e3) << frame;
  }
  // The old keys are the pressure's part on the rail.
  EXPECT_NEAR(s.json["total"]["vertical_force_N"].get<double>(),
              Xyz(forces["total"]["rail"]["normal"]).z(), 1e-9 * 80e3);
  // The load is carried by the net force (vertical balance).
  const Eigen::Vector3d net = Xyz(forces["total"]["rail"]["net"]);
  EXPECT_NEAR(net.z(), 80e3, 1e-6 * 80e3);
  // L/V from the JSON's forces, the JSON's own L/V, and the printed one.
  const double l_over_v = std::abs(net.y()) / net.z();
  EXPECT_NEAR(s.json["flange_climb_check"]["l_over_v"].get<double>(), l_over_v, 1e-12);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(s.summary, m, std::regex(R"(L/V +([0-9.]+))"))) << s.summary;
  EXPECT_NEAR(std::stod(m[1]), l_over_v, 5e-4);
  // The summary's lateral is the net force on the rail.
  ASSERT_TRUE(std::regex_search(s.summary, m, std::regex(R"(lateral (-?[0-9.]+) N)")));
  EXPECT_NEAR(std::stod(m[1]), net.y(), 0.05);
}

TEST(ForceConvention, NormalContactHasLOverVButNoLimit) {
  Scene scene = RollingScene(-1.5, 15.0);
  scene.problem.rolling.reset();
  const Solved s = Solve(scene);
  ASSERT_EQ(s.result.status, SolverStatus::kConverged);
  EXPECT_GT(s.json["flange_climb_check"]["l_over_v"].get<double>(), 0.0);
  EXPECT_TRUE(s.json["flange_climb_check"]["nadal_limit"].is_null());
  EXPECT_FALSE(s.json["flange_climb"].get<bool>());
  EXPECT_FALSE(s.json.contains("balance"));
}

}  // namespace
}  // namespace railwear::app
