// Wear scenes with collective traffic: a [[traffic]] entry `collective = "FILE"` (a collective
// written by `railwear traffic import`, relative to the scene) with its share, friction, axle
// load and wheel; every bad key or file is an InputError naming the scene file and key, and
// `railwear wear` exits 2 on it without touching the database; the shipped example runs a step
// that wears both rails.
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "app/load_collective_file.h"
#include "app/scene.h"
#include "core/numerics/input_error.h"
#include "tests/app/cli_runner.h"
#include "wear/collective_traffic.h"
#include "wear/load_collective.h"

namespace railwear::test {
namespace {

using CollectiveSceneTest = CliFixture;

const std::string kExamples = RAILWEAR_SOURCE_DIR "/examples";

// A two-rail wear scene whose one [[traffic]] entry holds `entry` (keys after [[traffic]]).
std::string Scene(const std::string& entry, const std::string& rails =
                                                "[track]\n"
                                                "high_rail = "
                                                "\"builtin:UIC60\"\n"
                                                "inclination = \"1:40\"\n"
                                                "radius_m = 600\n") {
  return "[scene]\neffects = [\"wear\"]\n[model]\nkind = \"auto\"\naccuracy = \"draft\"\n"
         "tangential = \"fastsim\"\n[materials]\nwheel = { E_MPa = 210000, nu = 0.28 }\n"
         "rail = { E_MPa = 210000, nu = 0.28, "
         "hardness_MPa = 2600 }\n" +
         rails +
         "[wheel]\nprofile = \"builtin:S1002\"\nrolling_radius_mm = 460\n[wear]\nlaw = "
         "\"archard\"\nk = 1e-4\ntotal_passes = 1e4\n[[traffic]]\n" +
         entry;
}

const std::string kBase = "name = \"mbs\"\ncollective = \"mbs/curve_r600_collective.toml\"\n";
const std::string kEntry = kBase + "share = 2\n";

// ParseScene's InputError message for `text` as a scene in examples/ ("" when it parses).
std::string SceneError(const std::string& text) {
  try {
    app::ParseScene(text, kExamples + "/x.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CollectiveSceneParseTest, EntryReadsItsCollectiveRelativeToTheScene) {
  const app::Scene s = app::ParseScene(Scene(kEntry), kExamples + "/x.toml");
  ASSERT_EQ(s.wear->traffic.size(), 1u);
  const TrafficCase& c = s.wear->traffic[0];
  ASSERT_TRUE(c.is_collective());
  EXPECT_FALSE(c.is_vehicle());
  const LoadCollective& lc = c.collective->collective;
  EXPECT_EQ(EntryCount(lc, RailSide::kHigh), 44);
  EXPECT_EQ(EntryCount(lc, RailSide::kLow), 35);
  EXPECT_TRUE(c.RunsOn(RailSide::kHigh));
  EXPECT_TRUE(c.RunsOn(RailSide::kLow));
  EXPECT_EQ(c.share, 2.0);
  EXPECT_EQ(c.rolling_radius_m, 0.46);
  EXPECT_EQ(c.collective->flange_back_distance_m, 1.360);
  EXPECT_EQ(c.collective->flange_back_position_m, -0.070);
  EXPECT_EQ(c.axle_load_t, CollectiveAxleLoad_t(lc));
  // The example's wheel loads are about 78 kN: an axle of about 16 t.
  EXPECT_NEAR(c.axle_load_t, 16.0, 0.3);

  const app::Scene given = app::ParseScene(
      Scene(kEntry + "axle_load_t = 20\nfriction = 0.4\nrolling_radius_mm = 450\n"
                     "flange_back_distance_mm = 1358\nflange_back_position_mm = -69\n"),
      kExamples + "/x.toml");
  const TrafficCase& g = given.wear->traffic[0];
  EXPECT_EQ(g.axle_load_t, 20.0);
  EXPECT_EQ(g.friction, 0.4);
  EXPECT_DOUBLE_EQ(g.rolling_radius_m, 0.45);
  EXPECT_DOUBLE_EQ(g.collective->flange_back_distance_m, 1.358);
  EXPECT_DOUBLE_EQ(g.collective->flange_back_position_m, -0.069);
}

TEST(CollectiveSceneParseTest, BadKeysAreInputErrorsWithFileAndKey) {
  const struct {
    std::string text, expected;
  } cases[] = {
      {Scene(kEntry + "speed_m_s = 20\n"), "x.toml:"},
      {Scene(kEntry + "speed_m_s = 20\n"), "traffic[0].speed_m_s"},
      {Scene(kBase + "share = 0\n"), "traffic[0].share' = 0"},
      {Scene(kBase + "share = -1\n"), "traffic[0].share' = -1"},
      {Scene(kEntry + "friction = 3\n"), "traffic[0].friction' = 3"},
      {Scene(kEntry + "axle_load_t = 0\n"), "traffic[0].axle_load_t' = 0"},
      {Scene(kEntry + "flange_back_distance_mm = 500\n"), "traffic[0].flange_back_distance_mm"},
      {Scene(kEntry + "flange_back_position_mm = 10\n"), "traffic[0].flange_back_position_mm"},
      {Scene("collective = 5\n"), "traffic[0].collective' = 5"},
      {Scene("collective = \"nowhere.toml\"\n"), "traffic[0].collective' = \"nowhere.toml\""},
      // The collective file's own errors name that file, behind the scene's key.
      {Scene("collective = \"curve_r600_vehicles.toml\"\n"),
       "traffic[0].collective' = \"curve_r600_vehicles.toml\": "},
      // A collective needs both rails.
      {Scene(kEntry, "[rail]\nprofile = \"builtin:UIC60\"\n"), "[track]"},
  };
  for (const auto& c : cases) {
    const std::string error = SceneError(c.text);
    EXPECT_TRUE(Contains(error, c.expected)) << c.text;
  }
}

// A collective whose CSV had no mu needs the entry's friction.
TEST_F(CollectiveSceneTest, FrictionIsRequiredWhenBinsHaveNoMu) {
  const LoadCollective lc =
      BinLoadCollective(ParseMbsTimeHistory("weight_passes,side,V_m_s,y_mm,yaw_mrad,Q_N\n"
                                            "1,high,20,2.0,1.0,82000\n1,low,20,2.0,1.0,78000\n",
                                            "no_mu.csv"),
                        {});
  Write("no_mu.toml", app::LoadCollectiveFileText(lc, ""));
  const std::string entry = "collective = \"no_mu.toml\"\n";
  try {
    app::ParseScene(Scene(entry), (dir_ / "s.toml").string());
    ADD_FAILURE() << "no error without friction";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "traffic[0].friction")) << e.what();
  }
  const app::Scene s =
      app::ParseScene(Scene(entry + "friction = 0.4\n"), (dir_ / "s.toml").string());
  EXPECT_EQ(s.wear->traffic[0].friction, 0.4);
  // 2 Q / g averaged over both rails: (82 + 78) kN / g.
  EXPECT_NEAR(s.wear->traffic[0].axle_load_t, 160000.0 / kGravity_m_s2 / 1000.0, 1e-6);
}

TEST_F(CollectiveSceneTest, BadKeyExitsTwoAndOneStepWearsBothRails) {
  Write("mbs.toml", ReadFile(kExamples + "/mbs/curve_r600_collective.toml"));
  Write("bad.toml", Scene("collective = \"mbs.toml\"\nspeed_m_s = 20\n"));
  const Outcome bad = Run("wear bad.toml --db bad.sqlite");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "traffic[0].speed_m_s")) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.sqlite"));

  Write("good.toml", Scene("collective = \"mbs.toml\"\n"));
  const Outcome good = Run("wear good.toml --db good.sqlite --steps 1");
  ASSERT_EQ(good.exit_code, 0) << good.err;
  // Both rails' tables: step 1 has a worn area (area_mm2, the fourth column) on each.
  for (const std::string rail : {"high rail:", "low rail:"}) {
    const size_t at = good.out.find(rail);
    ASSERT_NE(at, std::string::npos) << good.out;
    std::istringstream rows(good.out.substr(at));
    std::string line;
    for (int skip = 0; skip < 3; ++skip) std::getline(rows, line);  // title, header, step 0
    std::getline(rows, line);
    std::istringstream cells(line);
    int step = 0;
    double passes = 0.0, mgt = 0.0, area_mm2 = 0.0;
    cells >> step >> passes >> mgt >> area_mm2;
    EXPECT_EQ(step, 1) << line;
    EXPECT_GT(area_mm2, 0.0) << rail << " " << line;
  }
}

}  // namespace
}  // namespace railwear::test
