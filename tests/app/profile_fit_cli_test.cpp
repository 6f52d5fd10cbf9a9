// `railwear profile fit` end to end: the report on stdout, the fitted profile written as CSV or
// .ban, a given smoothing length, and exit code 2 with a clear message for a missing file, a bad
// --smoothing value or an unsupported --out extension. Runs the built binary (RAILWEAR_BINARY)
// in a temporary directory.
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/profile_command.h"
#include "core/numerics/input_error.h"
#include "core/profile/profile_io.h"

#include "tests/app/cli_runner.h"

namespace {

namespace fs = std::filesystem;

using railwear::test::Contains;
using railwear::test::Outcome;
using railwear::test::ReadFile;

constexpr double kRadius_mm = 50.0;

class ProfileFitCliTest : public railwear::test::CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    // A rail-head-like arc of radius 50 mm, 300 points 0.2 mm apart, with 1 um of normal noise
    // (fixed seed), and one 0.5 mm scan glitch at point 151 (1-based).
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 1e-3);
    std::string csv = "y_mm,z_mm\n";
    for (int i = 0; i < 300; ++i) {
      const double phi = (i - 150) * 0.2 / kRadius_mm;
      double y = kRadius_mm * std::sin(phi), z = kRadius_mm * (1.0 - std::cos(phi));
      const double e = noise(rng) + (i == 150 ? 0.5 : 0.0);
      y -= e * std::sin(phi);  // along the normal, into the rail (+z at the crown)
      z += e * std::cos(phi);
      csv += fmt::format("{:.5f},{:.5f}\n", y, z);
    }
    std::ofstream(dir_ / "arc.csv") << csv;
  }
};

TEST_F(ProfileFitCliTest, ReportsResidualsOutliersLambdaAndCurvatureAndWritesBan) {
  const Outcome o = Run("profile fit arc.csv --out fit.ban");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "points          300 (1 rejected as gross outliers"));
  EXPECT_TRUE(Contains(o.out, "rejected        points 151 (lines 152)\n"));  // after the header
  EXPECT_TRUE(Contains(o.out, "(GCV)"));
  EXPECT_TRUE(Contains(o.out, "lambda"));
  EXPECT_TRUE(Contains(o.out, "mm normal distance (0.000"));  // 1 um noise without the glitch
  EXPECT_TRUE(Contains(o.out, "max residual    0.49"));       // the 0.5 mm glitch
  EXPECT_TRUE(Contains(o.out, "at point 151 (line 152)"));
  EXPECT_TRUE(Contains(o.out, "noise           0.00"));
  EXPECT_TRUE(Contains(o.out, "curvature       0.0"));  // around 1/50 mm = 0.02 1/mm
  EXPECT_TRUE(Contains(o.err, "wrote fit.ban"));
  EXPECT_TRUE(fs::exists(dir_ / "fit.ban"));
}

TEST_F(ProfileFitCliTest, GivenSmoothingLengthKeepsTheRadiusInTheCsv) {
  const Outcome o = Run("profile fit arc.csv --smoothing 2 --out fit.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "length 2.0000 mm, lambda 1.6e-11 m^4 (given)"));
  const railwear::ProfileFile fitted = railwear::ReadProfileFile((dir_ / "fit.csv").string());
  EXPECT_NEAR(fitted.profile.Length(), 59.8e-3, 0.1e-3);  // 299 spacings of 0.2 mm
  // A 2 mm smoothing length leaves 1 um of noise ~1e-4 1/mm of curvature noise (sigma / l^2):
  // the 50 mm radius is kept within a few per cent. (GCV's choice, ~0.35 mm, is best for
  // positions, not for curvature.)
  const double crown = fitted.profile.Length() / 2;
  EXPECT_NEAR(fitted.profile.Curvature(crown) * kRadius_mm * 1e-3, 1.0, 0.03);
  const Outcome upper = Run("profile fit arc.csv --smoothing AUTO");
  EXPECT_EQ(upper.exit_code, 0) << upper.err;
  EXPECT_TRUE(Contains(upper.out, "(GCV)"));
}

TEST_F(ProfileFitCliTest, BadInputExitsTwoWithAClearMessage) {
  const Outcome missing = Run("profile fit none.csv");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(Contains(missing.err, "railwear: error: none.csv"));
  for (const char* bad : {"abc", "-1", "0", "0.5mm"}) {
    const Outcome o = Run(std::string("profile fit arc.csv --smoothing ") + bad);
    EXPECT_EQ(o.exit_code, 2) << bad;
    EXPECT_TRUE(Contains(o.err, fmt::format("--smoothing '{}': expected AUTO or a smoothing "
                                            "length in mm greater than 0",
                                            bad)));
    EXPECT_EQ(o.out, "") << bad;
  }
  const Outcome ext = Run("profile fit arc.csv --out fit.txt");
  EXPECT_EQ(ext.exit_code, 2);
  EXPECT_TRUE(Contains(ext.err, "--out 'fit.txt': expected a file name ending in .csv or .ban"));
  EXPECT_EQ(ext.out, "");
  EXPECT_FALSE(fs::exists(dir_ / "fit.txt"));
}

// The raw scan: a 1 mm spike on one point of a scan taken every 0.1 mm turns the polyline
// back by 168 degrees. `profile show` refuses it as a profile; `profile fit` drops it as a scan
// glitch, names its line in the report and the JSON, and fits the rest.
TEST_F(ProfileFitCliTest, OnePointSpikeIsDroppedAndReportedWithItsLine) {
  std::string csv = "# a raw scan\ny_mm,z_mm\n";  // points start on line 3
  for (int i = 0; i < 400; ++i) {
    const double phi = (i - 200) * 0.1 / kRadius_mm;
    const double e = i == 120 ? 1.0 : 0.0;  // point 121, line 123
    csv += fmt::format("{:.5f},{:.5f}\n", (kRadius_mm - e) * std::sin(phi),
                       kRadius_mm - (kRadius_mm - e) * std::cos(phi));
  }
  Write("spike.csv", csv);
  const Outcome show = Run("profile show spike.csv");
  EXPECT_EQ(show.exit_code, 2);
  EXPECT_TRUE(Contains(show.err, "spike.csv:124:")) << show.err;
  EXPECT_TRUE(Contains(show.err, "turns the profile back by 168.")) << show.err;

  const Outcome o = Run("profile fit spike.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "points          400 (1 dropped as scan glitches, 0 rejected"))
      << o.out;
  EXPECT_TRUE(Contains(o.out,
                       "dropped         point 121 (line 123) (y = -7.807, z = 1.626 mm): "
                       "turned the scan back by 168.6 degrees at line 123"))
      << o.out;
  EXPECT_TRUE(Contains(o.out, "RMS residual    0.00")) << o.out;  // the clean arc fits

  const Outcome j = Run("profile fit spike.csv --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const nlohmann::json fit = nlohmann::json::parse(j.out);
  ASSERT_EQ(fit["dropped"].size(), 1u);
  EXPECT_EQ(fit["dropped"][0]["line"], 123);
  EXPECT_EQ(fit["dropped"][0]["point"], 121);
  EXPECT_EQ(fit["points"], 400);
  EXPECT_LT(fit["rms_distance_mm"].get<double>(), 1e-3);
}

// The rejected points of the robust fit carry their lines in the JSON too.
TEST_F(ProfileFitCliTest, JsonNamesRejectedPointsByLine) {
  const Outcome o = Run("profile fit arc.csv --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json fit = nlohmann::json::parse(o.out);
  ASSERT_EQ(fit["rejected"].size(), 1u);
  EXPECT_EQ(fit["rejected"][0]["point"], 151);
  EXPECT_EQ(fit["rejected"][0]["line"], 152);
  EXPECT_NEAR(fit["rejected"][0]["distance_mm"].get<double>(), 0.5, 0.01);
  EXPECT_EQ(fit["dropped"].size(), 0u);
}

TEST(ParseSmoothingLengthTest, AutoOrMillimetres) {
  EXPECT_FALSE(railwear::app::ParseSmoothingLength("auto").has_value());
  EXPECT_FALSE(railwear::app::ParseSmoothingLength("Auto").has_value());
  EXPECT_DOUBLE_EQ(*railwear::app::ParseSmoothingLength("0.25"), 0.25e-3);
  EXPECT_DOUBLE_EQ(*railwear::app::ParseSmoothingLength("2e-1"), 0.2e-3);
  EXPECT_THROW(railwear::app::ParseSmoothingLength(""), railwear::InputError);
  EXPECT_THROW(railwear::app::ParseSmoothingLength("nan"), railwear::InputError);
  EXPECT_THROW(railwear::app::ParseSmoothingLength("inf"), railwear::InputError);
}

}  // namespace
