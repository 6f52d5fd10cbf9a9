// Parity: the C API gives bit-identical results to `railwear contact` on every shipped contact
// example (examples/**/*.toml with a [scene] table and no [wear] table, the examples.cmake rule).
// The CLI solves SolveContactCase(ToContactCase(scene)) (app/contact_command.cpp); the C API is
// set up from the scene's values through its own calls (scene_to_api.h) and must give the same
// numbers, bit for bit: both front ends run the one engine.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/contact_command.h"
#include "app/scene.h"
#include "core/contact/contact_forces.h"
#include "core/numerics/units.h"
#include "railwear/railwear.h"
#include "tests/api/scene_to_api.h"

namespace railwear::test {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// The contact examples, relative to examples/.
std::vector<std::string> ContactExamples() {
  std::vector<std::string> out;
  const fs::path root = fs::path(RAILWEAR_SOURCE_DIR) / "examples";
  const std::regex scene_table("(^|\n)\\[scene\\]"), wear_table("(^|\n)\\[wear\\]");
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.path().extension() != ".toml") continue;
    const std::string text = Slurp(e.path());
    if (std::regex_search(text, scene_table) && !std::regex_search(text, wear_table)) {
      out.push_back(fs::relative(e.path(), root).string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

class ApiParity : public ::testing::TestWithParam<std::string> {};

// Every double compared with EXPECT_EQ: bit-identical, not close.
void ExpectSamePatch(const rw_patch& a, const PatchResult& p, const std::string& where) {
  SCOPED_TRACE(where);
  EXPECT_EQ(a.area_m2, p.area_m2);
  EXPECT_EQ(a.p_max_Pa, p.p_max_Pa);
  EXPECT_EQ(a.normal_force_N, p.normal_force_N);
  EXPECT_EQ(a.contact_x_m, p.contact_x_m);
  EXPECT_EQ(a.contact_y_m, p.contact_point_yz_m.x());
  EXPECT_EQ(a.contact_z_m, p.contact_point_yz_m.y());
  EXPECT_EQ(a.contact_angle_rad, p.contact_angle_rad);
  const Eigen::Vector3d f = PatchForcesOnRail(p).Net();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.force_on_rail_N[i], f[i]);
  EXPECT_EQ(a.cells, p.cells);
  EXPECT_EQ(a.cells_in_contact, p.cells_in_contact);
  if (p.rolling) {
    EXPECT_EQ(a.creepage_xi, p.rolling->creepage.xi);
    EXPECT_EQ(a.creepage_eta, p.rolling->creepage.eta);
    EXPECT_EQ(a.creepage_spin_per_m, p.rolling->creepage.spin_per_m);
    EXPECT_EQ(a.creep_force_x_N, p.rolling->tangential.force_x_N);
    EXPECT_EQ(a.creep_force_s_N, p.rolling->tangential.force_s_N);
    EXPECT_EQ(a.spin_moment_Nm, p.rolling->tangential.spin_moment_Nm);
    if (p.rolling->damage) {
      EXPECT_EQ(a.t_gamma_N, p.rolling->damage->t_gamma_N);
    }
  }
}

// The CLI's solve of `scene` against the C API set up from it, every patch and cell compared.
void ExpectParity(const app::Scene& scene, const std::string& name) {
  const ContactCaseResult cli = SolveContactCase(app::ToContactCase(scene));

  rw_problem* p = nullptr;
  ASSERT_EQ(rw_create(scene.wheelset ? RW_PROBLEM_WHEELSET : RW_PROBLEM_WHEEL, &p), RW_OK);
  SetUpFromScene(p, scene);
  const rw_status status = rw_calculate(p);

  std::vector<const ContactResult*> wheels;
  if (cli.wheelset) {
    wheels = {&cli.wheelset->right, &cli.wheelset->left};
  } else {
    wheels = {&cli.wheel};
  }
  bool converged = true;
  for (const ContactResult* w : wheels) converged &= w->status == SolverStatus::kConverged;
  EXPECT_EQ(status == RW_OK, converged) << rw_last_error(p);

  rw_summary s{};
  s.struct_size = sizeof s;
  ASSERT_EQ(rw_get_summary(p, &s), RW_OK) << rw_last_error(p);
  int count = -1;
  ASSERT_EQ(rw_get_patch_count(p, &count), RW_OK);
  int index = 0;
  for (size_t w = 0; w < wheels.size(); ++w) {
    EXPECT_EQ(s.approach_m[w], wheels[w]->approach_m);
    EXPECT_EQ(s.l_over_v[w], wheels[w]->climb.l_over_v);
    for (const PatchResult& patch : wheels[w]->patches) {
      ASSERT_LT(index, count);
      rw_patch a{};
      a.struct_size = sizeof a;
      ASSERT_EQ(rw_get_patch(p, index, &a), RW_OK) << rw_last_error(p);
      EXPECT_EQ(a.wheel, static_cast<int>(w));
      const std::string where = name + " patch " + std::to_string(index);
      ExpectSamePatch(a, patch, where);
      size_t n = 0;
      ASSERT_EQ(rw_get_cell_count(p, index, &n), RW_OK);
      ASSERT_EQ(n, static_cast<size_t>(patch.grid.cells()));
      std::vector<double> pressure(n), tx(n);
      ASSERT_EQ(rw_get_cells(p, index, n, nullptr, nullptr, pressure.data(), tx.data(), nullptr,
                             nullptr, nullptr),
                RW_OK)
          << rw_last_error(p);
      for (size_t k = 0; k < n; ++k) {
        ASSERT_EQ(pressure[k], patch.pressure_Pa[static_cast<Eigen::Index>(k)])
            << where << " cell " << k;
        if (patch.rolling) {
          ASSERT_EQ(tx[k], patch.rolling->tangential.traction_x_Pa[static_cast<Eigen::Index>(k)])
              << where << " cell " << k;
        }
      }
      ++index;
    }
  }
  EXPECT_EQ(index, count);
  rw_destroy(p);
}

TEST_P(ApiParity, CApiEqualsTheCliBitForBit) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / GetParam();
  const std::string text = Slurp(path);
  if (text.find("shared/data") != std::string::npos &&
      !fs::exists(fs::path(RAILWEAR_SHARED_DIR) / "data" / "profiles")) {
    GTEST_SKIP() << GetParam() << " reads profiles from ../shared/data/profiles, which is absent ("
                 << RAILWEAR_SHARED_DIR << ")";
  }
  ExpectParity(app::LoadScene(path.string()), GetParam());
}

// rw_set_pressure_limit (API 1.1): no shipped contact example has a pressure limit, so the
// gauge-corner example with one, as a scene's [model] pressure_limit_MPa or pressure_limit =
// "hardness" sets it; a limit below the elastic p_max, so that it acts.
TEST(ApiPressureLimit, CApiEqualsTheCliBitForBit) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / "rolling_gauge_corner.toml";
  app::Scene scene = app::LoadScene(path.string());
  const ContactCaseResult elastic = SolveContactCase(app::ToContactCase(scene));
  ASSERT_FALSE(elastic.wheel.patches.empty());
  double p_max = 0.0;
  for (const PatchResult& patch : elastic.wheel.patches) p_max = std::max(p_max, patch.p_max_Pa);
  scene.problem.pressure_limit = {PressureLimitKind::kValue, 0.8 * p_max};
  ExpectParity(scene, "pressure_limit_MPa");
  const ContactCaseResult limited = SolveContactCase(app::ToContactCase(scene));
  for (const PatchResult& patch : limited.wheel.patches) {
    EXPECT_LE(patch.p_max_Pa, 0.8 * p_max * (1.0 + 1e-12));  // the limit acts
  }
  scene.problem.pressure_limit = {PressureLimitKind::kHardness, 0.0};
  scene.problem.rail_material.hardness_Pa = 0.8 * p_max;
  ExpectParity(scene, "pressure_limit = hardness");
}

// The normal solver's stopping rule (API 1.5; issue 18's open point: the C API had no switch for
// the strict setting): the rolling gauge-corner example with the scene's [model] normal_criterion
// = "gap-residual" (rw_model.normal_criterion with tolerance 0, the criterion's own 1e-10) and
// with normal_tolerance = 1e-12 besides (an explicit rw_model.normal_tolerance), and the default
// with normal_tolerance = 1e-6: each equals the CLI's solve bit for bit (SetUpFromScene maps the
// keys). The strict setting changes p_max from the default's, so the switch reaches the solver.
TEST(ApiNormalCriterion, CApiEqualsTheCliWithTheSceneKeyBitForBit) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / "rolling_gauge_corner.toml";
  const std::string text = Slurp(path);
  const std::string model = "[model]\n";
  ASSERT_NE(text.find(model), std::string::npos);
  auto with_keys = [&](const std::string& keys) {
    std::string t = text;
    t.replace(t.find(model), model.size(), model + keys);
    return app::ParseScene(t, path.string());
  };
  const app::Scene strict = with_keys("normal_criterion = \"gap-residual\"\n");
  ASSERT_EQ(strict.problem.solver.criterion, NormalStopCriterion::kGapResidual);
  ExpectParity(strict, "gap-residual");
  const app::Scene strict_12 =
      with_keys("normal_criterion = \"gap-residual\"\nnormal_tolerance = 1e-12\n");
  ASSERT_EQ(strict_12.problem.solver.tolerance, 1e-12);
  ExpectParity(strict_12, "gap-residual at 1e-12");
  const app::Scene default_6 = with_keys("normal_tolerance = 1e-6\n");
  ASSERT_EQ(default_6.problem.solver.criterion, NormalStopCriterion::kPressureUpdate);
  ExpectParity(default_6, "pressure-update at 1e-6");

  const ContactCaseResult a = SolveContactCase(app::ToContactCase(app::LoadScene(path.string())));
  const ContactCaseResult b = SolveContactCase(app::ToContactCase(strict));
  ASSERT_FALSE(a.wheel.patches.empty());
  ASSERT_EQ(a.wheel.patches.size(), b.wheel.patches.size());
  EXPECT_NE(a.wheel.patches[0].p_max_Pa, b.wheel.patches[0].p_max_Pa);
}

// The exact tangential solver's stop (API 1.5, a scene's [model] tangential_tolerance): the rolling
// gauge-corner example on the exact solver at 1e-9 and at 1e-3 equals the CLI's solve bit for bit
// through rw_model.tangential_tolerance; the two differ in F_x, so the field reaches the solver.
TEST(ApiTangentialTolerance, CApiEqualsTheCliWithTheSceneKeyBitForBit) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / "rolling_gauge_corner.toml";
  const std::string text = Slurp(path);
  const std::string fastsim = "tangential = \"fastsim\"\n";
  ASSERT_NE(text.find(fastsim), std::string::npos);
  auto with_tolerance = [&](const std::string& tolerance) {
    std::string t = text;
    t.replace(t.find(fastsim), fastsim.size(),
              "tangential = \"exact\"\ntangential_tolerance = " + tolerance + "\n");
    return app::ParseScene(t, path.string());
  };
  const app::Scene tight = with_tolerance("1e-9");
  ASSERT_EQ(tight.problem.tangential_tolerance, 1e-9);
  ExpectParity(tight, "exact at 1e-9");
  const app::Scene loose = with_tolerance("1e-3");
  ExpectParity(loose, "exact at 1e-3");

  const ContactCaseResult a = SolveContactCase(app::ToContactCase(tight));
  const ContactCaseResult b = SolveContactCase(app::ToContactCase(loose));
  ASSERT_FALSE(a.wheel.patches.empty());
  ASSERT_EQ(a.wheel.patches.size(), b.wheel.patches.size());
  ASSERT_TRUE(a.wheel.patches[0].rolling && b.wheel.patches[0].rolling);
  EXPECT_NE(a.wheel.patches[0].rolling->tangential.force_x_N,
            b.wheel.patches[0].rolling->tangential.force_x_N);
}

// The same through the railwear executable itself: `railwear contact SCENE --json FILE` gives per
// patch the numbers the C API gives (the JSON's doubles round-trip exactly; its unit factors are
// applied to the C API's values the same way). The top-level examples only, to keep this fast.
std::vector<std::string> TopLevelContactExamples() {
  std::vector<std::string> out;
  for (const std::string& e : ContactExamples()) {
    if (e.find('/') == std::string::npos) out.push_back(e);
  }
  return out;
}

class ApiCliParity : public ::testing::TestWithParam<std::string> {};

TEST_P(ApiCliParity, TheCliJsonEqualsTheCApi) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / GetParam();
  const fs::path json_path = fs::temp_directory_path() /
                             ("railwear_api_cli_parity_" + std::to_string(::getpid()) + ".json");
  const std::string command = std::string(RAILWEAR_BINARY) + " contact " + path.string() +
                              " --json " + json_path.string() + " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const nlohmann::json json = nlohmann::json::parse(Slurp(json_path));
  fs::remove(json_path);

  const app::Scene scene = app::LoadScene(path.string());
  rw_problem* p = nullptr;
  ASSERT_EQ(rw_create(scene.wheelset ? RW_PROBLEM_WHEELSET : RW_PROBLEM_WHEEL, &p), RW_OK);
  SetUpFromScene(p, scene);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  std::vector<nlohmann::json> patches;
  if (scene.wheelset) {
    for (const char* w : {"right", "left"}) {
      for (const auto& q : json.at("wheels").at(w).at("patches")) patches.push_back(q);
    }
  } else {
    for (const auto& q : json.at("patches")) patches.push_back(q);
  }
  int count = 0;
  ASSERT_EQ(rw_get_patch_count(p, &count), RW_OK);
  ASSERT_EQ(static_cast<size_t>(count), patches.size());
  for (int i = 0; i < count; ++i) {
    SCOPED_TRACE(GetParam() + " patch " + std::to_string(i));
    rw_patch a{};
    a.struct_size = sizeof a;
    ASSERT_EQ(rw_get_patch(p, i, &a), RW_OK);
    const nlohmann::json& q = patches[static_cast<size_t>(i)];
    EXPECT_EQ(q.at("normal_force_N").get<double>(), a.normal_force_N);
    EXPECT_EQ(q.at("p_max_MPa").get<double>(), a.p_max_Pa * kToMPa);
    EXPECT_EQ(q.at("area_mm2").get<double>(), a.area_m2 * kToMm2);
    EXPECT_EQ(q.at("contact_y_mm").get<double>(), a.contact_y_m * kToMm);
    EXPECT_EQ(q.at("cells_in_contact").get<int>(), a.cells_in_contact);
  }
  rw_destroy(p);
}

INSTANTIATE_TEST_SUITE_P(Examples, ApiCliParity, ::testing::ValuesIn(TopLevelContactExamples()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(0, info.param.size() - 5);
                         });

INSTANTIATE_TEST_SUITE_P(Examples, ApiParity, ::testing::ValuesIn(ContactExamples()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.substr(0, info.param.size() - 5);
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace railwear::test
