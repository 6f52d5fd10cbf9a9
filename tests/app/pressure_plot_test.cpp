// Issue 17, point 8: the contact plot. What can be checked without eyes: the script's panels
// have equal aspect, the cross-section's data blocks (rail, wheel, patch on the rail, contact
// points with their angles) exist for every wheel of a wheelset, the cross-section's z axis
// points down, and gnuplot renders the script (exit 0, a PNG) when it is installed.
#include <algorithm>
#include <cstdlib>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app/pressure_plot.h"
#include "app/scene.h"
#include "core/contact/wheelset_contact.h"

#include "tests/app/cli_runner.h"

namespace railwear::test {
namespace {

const std::string kWheelset = RAILWEAR_SOURCE_DIR "/examples/wheelset.toml";
const std::string kGaugeCorner = RAILWEAR_SOURCE_DIR "/examples/gauge_corner.toml";

size_t Count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(ContactPlotScript, AWheelsetHasARowPerWheelWithProfilesContactsAndEqualAspect) {
  app::Scene scene = app::LoadScene(kWheelset);
  ASSERT_TRUE(scene.wheelset.has_value());
  scene.problem.model.accuracy = AccuracyPreset::kDraft;
  WheelsetProblem problem;
  problem.wheel_rail = scene.problem;
  problem.track = *scene.track;
  problem.wheelset = *scene.wheelset;
  const WheelsetResult r = SolveWheelset(problem);
  ASSERT_FALSE(r.right.patches.empty());
  ASSERT_FALSE(r.left.patches.empty());
  const Profile& wheel = problem.wheel_rail.wheel_profile;
  const Profile& rail = problem.wheel_rail.rail_profile;
  const std::string script = app::ContactPlotScript(
      scene,
      {{"right wheel", &r.right, r.placement.right, &wheel, &rail},
       {"left wheel", &r.left, r.placement.left, &wheel, &rail}},
      "out.png");
  // Both wheels' rows: their profiles, patches on the rail and contact points.
  for (const int k : {1, 2}) {
    for (const char* block : {"rail", "wheel", "patch", "contact"}) {
      EXPECT_EQ(Count(script, fmt::format("${}_{} << EOD", block, k)), 1u) << block << k;
    }
    EXPECT_EQ(Count(script, fmt::format("$map_{}_1 << EOD", k)), 1u) << k;
  }
  EXPECT_TRUE(Contains(script, "'right wheel: cross-section at first contact"));
  EXPECT_TRUE(Contains(script, "'left wheel: cross-section at first contact"));
  // The contact points and their angles, as the summary has them.
  for (const ContactResult* w : {&r.right, &r.left}) {
    const PatchResult& p = w->patches[0];
    EXPECT_TRUE(Contains(script, fmt::format("{:.5f} {:.5f} {:.3f}\n",
                                             p.contact_point_yz_m.x() * 1e3,
                                             p.contact_point_yz_m.y() * 1e3,
                                             p.contact_angle_rad * 180.0 / std::numbers::pi)));
    EXPECT_TRUE(Contains(script, fmt::format("1: {:.1f} deg", p.contact_angle_rad * 180.0 /
                                                                  std::numbers::pi)));
  }
  // Equal aspect in every panel: two cross-sections, and each patch's maps (rolling: three).
  const size_t patches = r.right.patches.size() + r.left.patches.size();
  const bool rolling = r.right.patches[0].rolling.has_value();
  EXPECT_EQ(Count(script, "set size ratio -1\n"), 2 + patches);
  EXPECT_EQ(Count(script, " with image notitle"), patches * (rolling ? 3 : 1));
  EXPECT_TRUE(Contains(script, "set multiplot layout 2,"));
  EXPECT_FALSE(Contains(script, "reverse"));  // gnuplot ignores it on explicit ranges
}

TEST(ContactPlotScript, TheCrossSectionsZAxisPointsDownAroundThePatch) {
  app::Scene scene = app::LoadScene(kGaugeCorner);
  scene.problem.model.accuracy = AccuracyPreset::kDraft;
  const ContactResult r = SolveContact(scene.problem);
  ASSERT_EQ(r.patches.size(), 1u);
  const WheelPlacement& pl = scene.problem.placement;
  const std::string script = app::ContactPlotScript(
      scene,
      {{"wheel", &r, WheelPose{pl.lateral_shift_m, pl.roll_rad, pl.rolling_radius_m, 0.0},
        &scene.problem.wheel_profile, &scene.problem.rail_profile}},
      "out.png");
  // The first yrange is the cross-section's: high to low (z down), around the contact point.
  const size_t at = script.find("set yrange [");
  ASSERT_NE(at, std::string::npos);
  double z0 = 0, z1 = 0, y0 = 0, y1 = 0;
  ASSERT_EQ(std::sscanf(script.c_str() + at, "set yrange [%lf:%lf]", &z0, &z1), 2);
  ASSERT_EQ(std::sscanf(script.c_str() + script.find("set xrange ["), "set xrange [%lf:%lf]", &y0,
                        &y1),
            2);
  EXPECT_GT(z0, z1);
  const Eigen::Vector2d c = r.patches[0].contact_point_yz_m * 1e3;
  EXPECT_LT(y0, c.x());
  EXPECT_GT(y1, c.x());
  EXPECT_LT(z1, c.y());
  EXPECT_GT(z0, c.y());
  EXPECT_TRUE(Contains(script, "title 'contact point'"));
  EXPECT_TRUE(Contains(script, "constants fem"));
}

TEST_F(CliFixture, GnuplotRendersTheWheelsetPlot) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "gnuplot is not installed; the script is checked by ContactPlotScript.*";
  }
  const Outcome o = Run("contact '" + kWheelset + "' --accuracy draft --plot w.png");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::string png = ReadFile(dir_ / "w.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

}  // namespace
}  // namespace railwear::test
