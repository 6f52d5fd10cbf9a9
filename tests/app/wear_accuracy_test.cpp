// `railwear accuracy` on a wear scene: the wear study at each accuracy level and step limit,
// run time and the error of the final worn profile against the finest run; bad options refused.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"

namespace railwear::test {
namespace {

using WearAccuracyTest = CliFixture;

std::vector<std::vector<std::string>> ReadCsv(const fs::path& file) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(ReadFile(file));
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream cells_in(line);
    std::string cell;
    while (std::getline(cells_in, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// Two step limits at draft accuracy on the small study (2e5 passes, 0.1 mm deep): the finer
// step is the reference, the coarser run's profile differs from it by a small, finite amount.
TEST_F(WearAccuracyTest, StepLimitsAgainstTheFinestRun) {
  std::string scene = kSmallWearStudy;
  scene.replace(scene.find("total_passes = 4e5"), 18, "total_passes = 2e5");
  Write("study.toml", scene);
  const Outcome o =
      Run("accuracy study.toml --levels draft --step-limits 0.05,0.025 --out acc --no-plot");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "reference   draft level, step limit 0.025 mm"));
  EXPECT_TRUE(Contains(o.out, "step limit 0.05 -> 0.025 mm at draft changes the final profile"));
  const auto rows = ReadCsv(dir_ / "acc" / "wear_accuracy.csv");
  ASSERT_EQ(rows.size(), 3u);  // header + 2 runs
  ASSERT_EQ(rows[0][0], "level");
  EXPECT_EQ(rows[1][1], "0.05");
  EXPECT_EQ(rows[2][1], "0.025");
  EXPECT_EQ(rows[2].back(), "1");  // the reference
  EXPECT_EQ(std::stod(rows[2][9]), 0.0);
  const double coarse_steps = std::stod(rows[1][3]), fine_steps = std::stod(rows[2][3]);
  EXPECT_GT(fine_steps, coarse_steps);  // a smaller limit takes more profile updates
  const double max_depth_mm = std::stod(rows[2][6]);
  const double err_profile_mm = std::stod(rows[1][9]);
  EXPECT_GT(max_depth_mm, 0.05);
  EXPECT_TRUE(std::isfinite(err_profile_mm));
  // Halving the step limit moves the final profile by a fraction of its depth (README: 2 %
  // on the max depth for 0.1 -> 0.05 mm on the default study); 20 % bounds it loosely.
  EXPECT_LT(err_profile_mm, 0.2 * max_depth_mm);
}

TEST_F(WearAccuracyTest, BadOptionsAreRefusedWithExitCode2) {
  Write("study.toml", kSmallWearStudy);
  Outcome o = Run("accuracy study.toml --step-limits 0.1,0 --no-plot");
  EXPECT_EQ(o.exit_code, 2);
  // The options' ranges (issue 17, app/cli_checks.h), as the scene keys they stand for.
  EXPECT_TRUE(Contains(o.err, "--step-limits: 0: expected a number in [0.001, 1]"));
  o = Run("accuracy study.toml --mgt -1");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "--mgt: -1: expected a number in [1e-06, 10000]"));
  o = Run("accuracy study.toml --models hertz");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "a wear scene runs with its own [model]"));
  o = Run("accuracy study.toml --levels coarse");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "--levels: level 'coarse'"));
  o = Run(std::string("accuracy '") + RAILWEAR_SOURCE_DIR + "/examples/gauge_corner.toml' --mgt 1");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "--step-limits, --mgt and --threads are for wear scenes"));
}

}  // namespace
}  // namespace railwear::test
