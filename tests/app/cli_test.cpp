// The railwear executable end to end: exit codes (0 ok, 1 failure, 2 bad input/usage), error
// messages on stderr, `init` -> `contact`, JSON on stdout, CSV, `profile show|convert`.
// Runs the built binary (RAILWEAR_BINARY) in a temporary directory; draft accuracy keeps each
// test well under a second.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/scene_template.h"
#include "tests/app/cli_runner.h"

namespace {

namespace fs = std::filesystem;
using railwear::test::Contains;
using railwear::test::Outcome;
using railwear::test::ReadFile;
using CliTest = railwear::test::CliFixture;

const char* const kScene = R"([wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[load]
vertical_N = 100000
)";

TEST_F(CliTest, HelpAndVersionExitZero) {
  const Outcome help = Run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(Contains(help.out, "contact"));
  EXPECT_TRUE(Contains(help.out, "profile"));
  EXPECT_TRUE(Contains(help.out, "init"));
  EXPECT_EQ(Run("contact --help").exit_code, 0);
  const Outcome version = Run("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_TRUE(Contains(version.out, "railwear "));
}

TEST_F(CliTest, UsageErrorsExitTwo) {
  const Outcome none = Run("");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_TRUE(Contains(none.err, "railwear: error: "));
  const Outcome unknown = Run("contact scene.toml --bogus");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(Contains(unknown.err, "railwear: error: "));
  EXPECT_TRUE(Contains(unknown.err, "--bogus"));
  const Outcome model = Run("contact scene.toml --model fem");
  EXPECT_EQ(model.exit_code, 2);
  EXPECT_TRUE(Contains(model.err, "--model"));
  EXPECT_EQ(Run("contact scene.toml --accuracy ultra").exit_code, 2);
  EXPECT_EQ(Run("frobnicate").exit_code, 2);
}

TEST_F(CliTest, MissingSceneFileExitsTwo) {
  const Outcome o = Run("contact no_such_scene.toml");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "railwear: error: no_such_scene.toml: cannot open scene file"));
}

TEST_F(CliTest, BadSceneExitsTwoWithFileLineAndKey) {
  std::string text = kScene;
  text.replace(text.find("100000"), 6, "\"heavy\"");
  Write("bad.toml", text);
  const Outcome o = Run("contact bad.toml");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err,
                       "railwear: error: bad.toml:8: key 'load.vertical_N' = \"heavy\": "
                       "expected a number > 0"));
  EXPECT_EQ(o.out, "");
}

TEST_F(CliTest, InitWritesATemplateThatContactAccepts) {
  const Outcome init = Run("init scene.toml");
  ASSERT_EQ(init.exit_code, 0) << init.err;
  EXPECT_EQ(ReadFile(dir_ / "scene.toml"), railwear::app::SceneTemplate());
  const Outcome contact = Run("contact scene.toml --accuracy draft");
  EXPECT_EQ(contact.exit_code, 0) << contact.err;
  EXPECT_TRUE(Contains(contact.out, "status      converged"));
  EXPECT_TRUE(Contains(contact.out, "area_mm2"));
}

TEST_F(CliTest, InitNeverOverwrites) {
  Write("scene.toml", "keep me");
  const Outcome o = Run("init scene.toml");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "railwear: error: scene.toml: file exists"));
  EXPECT_EQ(ReadFile(dir_ / "scene.toml"), "keep me");
}

TEST_F(CliTest, InitWithoutFileWritesStdout) {
  const Outcome o = Run("init");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.out, railwear::app::SceneTemplate());
}

TEST_F(CliTest, JsonOnStdoutIsOneObjectWithTheRequiredKeys) {
  Write("scene.toml", kScene);
  const Outcome o = Run("contact scene.toml --accuracy draft --json -");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);  // throws on anything but one object
  for (const char* key : {"status", "message", "scene", "model", "approach_mm", "iterations",
                          "time_ms", "stages", "total", "patches"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["status"], "converged");
  EXPECT_EQ(j["model"]["accuracy"], "draft");
  for (const char* key : {"kind", "geometry", "kernel", "accuracy", "influence_constants"}) {
    EXPECT_TRUE(j["model"].contains(key)) << key;
  }
  // The default set (issue 17): FEM-calibrated, a convex and a concave set.
  EXPECT_EQ(j["model"]["constants"], "fem");
  for (const char* body : {"convex", "concave"}) {
    for (const char* key : {"c_f", "c_z", "c_s"}) {
      EXPECT_TRUE(j["model"]["influence_constants"][body].contains(key)) << body << key;
    }
  }
  for (const char* key : {"area_mm2", "p_max_MPa", "vertical_force_N", "lateral_force_N"}) {
    EXPECT_TRUE(j["total"].contains(key)) << key;
  }
  ASSERT_FALSE(j["patches"].empty());
  for (const char* key : {"area_mm2", "p_max_MPa", "normal_force_N", "vertical_force_N",
                          "lateral_force_N", "contact_y_mm", "contact_z_mm", "contact_angle_deg",
                          "cells", "cells_in_contact", "cell_mm"}) {
    EXPECT_TRUE(j["patches"][0].contains(key)) << key;
  }
  EXPECT_GT(j["total"]["area_mm2"].get<double>(), 0.0);
}

TEST_F(CliTest, JsonAndCsvFilesAndSummary) {
  Write("scene.toml", kScene);
  const Outcome o = Run("contact scene.toml --accuracy draft --json r.json --csv p.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "model       conformal"));
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir_ / "r.json"));
  std::istringstream csv(ReadFile(dir_ / "p.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa");
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 7) << line;
  }
  int cells = 0;
  for (const auto& p : j["patches"]) cells += p["cells"].get<int>();
  EXPECT_EQ(rows, cells);
}

TEST_F(CliTest, HertzCsvSamplesTheEllipse) {
  Write("scene.toml", kScene);
  const Outcome o = Run("contact scene.toml --model hertz --csv p.csv --json -");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["model"]["kind"], "hertz");
  EXPECT_TRUE(j["model"]["geometry"].is_null());
  const std::string csv = ReadFile(dir_ / "p.csv");
  const auto rows = std::count(csv.begin(), csv.end(), '\n') - 1;
  EXPECT_EQ(rows, static_cast<long>(j["patches"].size()) * 41 * 41);
}

TEST_F(CliTest, PlotWritesAPng) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  Write("scene.toml", kScene);
  const Outcome o = Run("contact scene.toml --accuracy draft --plot p.png");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::string png = ReadFile(dir_ / "p.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST_F(CliTest, PlotWithoutGnuplotExitsOneNamingIt) {
  Write("scene.toml", kScene);
  const Outcome o = Run("contact scene.toml --accuracy draft --plot p.png", "PATH=/nonexistent");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_TRUE(Contains(o.err, "railwear: error: --plot needs the program 'gnuplot'"));
  EXPECT_EQ(o.out, "");  // checked before the solve
}

TEST_F(CliTest, JsonAndCsvCannotBothUseStdout) {
  Write("scene.toml", kScene);
  const Outcome o = Run("contact scene.toml --json - --csv -");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "both want stdout"));
}

// The examples run as tests of their own, one ctest per file found by CMake
// (tests/examples.cmake, tests/tools/run_example.cmake): `contact FILE --accuracy draft --json -`
// exits 0 and prints one JSON object with status "converged" for every contact scene.

TEST_F(CliTest, GaugeCornerExampleRunsWithAllThreeModels) {
  // Issue 2: the gauge-corner example runs with hertz, halfspace and conformal; the contact sits
  // on the gauge corner (contact angle 20-45 degrees), and the conformal model gives a smaller
  // patch with a higher peak than the half-space model, as the seed paper reports.
  nlohmann::json r[3];
  const char* models[3] = {"hertz", "halfspace", "conformal"};
  for (int m = 0; m < 3; ++m) {
    const Outcome o = Run(std::string("contact '" RAILWEAR_SOURCE_DIR
                                      "/examples/gauge_corner.toml' --accuracy draft --model ") +
                          models[m] + " --json -");
    ASSERT_EQ(o.exit_code, 0) << models[m] << ": " << o.err;
    r[m] = nlohmann::json::parse(o.out);
    EXPECT_EQ(r[m]["status"], "converged") << models[m];
    ASSERT_EQ(r[m]["patches"].size(), 1u) << models[m];
    const double angle = r[m]["patches"][0]["contact_angle_deg"];
    EXPECT_GT(angle, 20.0) << models[m];
    EXPECT_LT(angle, 45.0) << models[m];
    EXPECT_NEAR(double(r[m]["total"]["vertical_force_N"]), 100000.0, 1e-6) << models[m];
  }
  EXPECT_LT(double(r[2]["total"]["area_mm2"]), double(r[1]["total"]["area_mm2"]));
  EXPECT_GT(double(r[2]["total"]["p_max_MPa"]), double(r[1]["total"]["p_max_MPa"]));
}

TEST_F(CliTest, ContactModelAutoReportsItsChoicePerPatch) {
  // Issue 6: --model auto on the gauge corner chooses the conformal geometry for the patch and
  // says why.
  const Outcome o = Run("contact '" RAILWEAR_SOURCE_DIR
                        "/examples/gauge_corner.toml' --accuracy draft --model auto --json -");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json r = nlohmann::json::parse(o.out);
  ASSERT_EQ(r["patches"].size(), 1u);
  EXPECT_EQ(r["patches"][0]["model"], "conformal+boussinesq");
  EXPECT_FALSE(std::string(r["patches"][0]["model_reason"]).empty());
}

TEST_F(CliTest, RollingContactReportsCreepForcesSlipAndDamage) {
  // Issue 3: the tangential and damage effects add creep forces, spin moment, creepages, stick
  // and slip areas, frictional power and the damage block to each patch; --csv adds traction,
  // slip velocity and stick per cell.
  std::string scene = R"(
[scene]
effects = ["tangential", "damage"]
[model]
kind = "conformal"
accuracy = "draft"
[materials]
wheel = { E_MPa = 210000, nu = 0.28 }
rail = { E_MPa = 210000, nu = 0.28, shear_yield_MPa = 350 }
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[load]
vertical_N = 100000
lateral_shift_mm = -4.0
friction = 0.3
speed_m_s = 20
yaw_mrad = 5
)";
  Write("rolling.toml", scene);
  const Outcome o = Run("contact rolling.toml --json - ");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  const auto& p = j["patches"][0];
  for (const char* key : {"creep_force_N", "spin_moment_Nmm", "creepage", "stick_area_mm2",
                          "slip_area_mm2", "frictional_power_W", "damage"}) {
    EXPECT_TRUE(p.contains(key)) << key;
  }
  const double fx = p["creep_force_N"]["x"], fy = p["creep_force_N"]["y"];
  EXPECT_LE(std::hypot(fx, fy), 0.3 * double(p["normal_force_N"]) * (1 + 1e-9));
  // Whole-cell count against the level-set area: at draft the yawed patch (issue 14) has 43
  // cells, about half of them on its edge, and the count exceeds the area by 11 % (measured;
  // 2 % on the unyawed patch before). Both converge together on finer grids.
  EXPECT_NEAR(double(p["stick_area_mm2"]) + double(p["slip_area_mm2"]), double(p["area_mm2"]),
              0.15 * double(p["area_mm2"]));
  for (const char* key : {"t_gamma_J_per_m", "wlrm_rcf_damage_per_axle", "fi_surf", "shakedown"}) {
    EXPECT_TRUE(p["damage"].contains(key)) << key;
  }
  const Outcome csv = Run("contact rolling.toml --csv cells.csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  std::ifstream in(dir_ / "cells.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header,
            "patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa,qx_MPa,qs_MPa,slip_x_m_s,slip_s_m_s,stick");
  // --plot draws the traction and slip maps under the pressure map.
  const Outcome plot = Run("contact rolling.toml --plot maps.png");
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_GT(std::filesystem::file_size(dir_ / "maps.png"), 1000u);
  // The exact steady-rolling solver gives the same kind of result, within the Coulomb bound.
  Write("exact.toml",
        std::string(scene).replace(scene.find("accuracy"), 0, "tangential = \"exact\"\n"));
  const Outcome exact = Run("contact exact.toml --json -");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  const auto pe = nlohmann::json::parse(exact.out)["patches"][0];
  EXPECT_LE(std::hypot(double(pe["creep_force_N"]["x"]), double(pe["creep_force_N"]["y"])),
            0.3 * double(pe["normal_force_N"]) * (1 + 1e-6));
  // The damage effect is refused without the rail's shear yield, with file, line and key.
  Write("nok.toml", std::string(scene).replace(scene.find(", shear_yield_MPa = 350"), 23, ""));
  const Outcome nok = Run("contact nok.toml");
  EXPECT_EQ(nok.exit_code, 2);
  EXPECT_TRUE(Contains(nok.err, "key 'materials.rail.shear_yield_MPa' is missing"));
}

TEST_F(CliTest, ProfileShowJsonAndConvert) {
  Write("rail.csv", "y_mm,z_mm\n-10,0.5\n-5,0.125\n0,0\n5,0.125\n10,0.5\n");
  const Outcome show = Run("profile show rail.csv --json");
  ASSERT_EQ(show.exit_code, 0) << show.err;
  const nlohmann::json j = nlohmann::json::parse(show.out);
  EXPECT_EQ(j["format"], "csv");
  EXPECT_EQ(j["points"], 5);
  EXPECT_DOUBLE_EQ(j["y_range_mm"][0].get<double>(), -10.0);
  EXPECT_DOUBLE_EQ(j["y_range_mm"][1].get<double>(), 10.0);
  EXPECT_NEAR(j["z_range_mm"][1].get<double>(), 0.5, 1e-9);
  EXPECT_GT(j["arc_length_mm"].get<double>(), 20.0);  // longer than the chord
  EXPECT_TRUE(j.contains("notes"));
  EXPECT_TRUE(j.contains("source"));

  const Outcome text = Run("profile show rail.csv");
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_TRUE(Contains(text.out, "points      5"));

  const Outcome convert = Run("profile convert rail.csv copy.csv");
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  EXPECT_TRUE(Contains(convert.err, "copy.csv"));
  EXPECT_EQ(convert.out, "");
  EXPECT_TRUE(fs::exists(dir_ / "copy.csv"));
}

TEST_F(CliTest, ProfileShowMissingFileExitsTwo) {
  const Outcome o = Run("profile show none.csv");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "railwear: error: "));
  EXPECT_TRUE(Contains(o.err, "none.csv"));
}

}  // namespace
