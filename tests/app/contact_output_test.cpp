// Output of `railwear contact` on hand-made results: JSON keys and units, the non-finite guard,
// CSV rows per cell, Hertz sampling, and the summary table.
#include "app/contact_output.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace railwear::app {
namespace {

// A converged result with one 3 x 2 grid patch.
ContactResult GridResult() {
  ContactResult r;
  r.status = SolverStatus::kConverged;
  r.model = MakeModelOptions(ModelKind::kConformal);
  r.approach_m = 2e-5;
  r.time_s = 0.004;
  r.stages = {{"solve", 0.003}};
  r.area_m2 = 50e-6;
  r.p_max_Pa = 1.2e9;
  r.vertical_force_N = 1e4;
  PatchResult p;
  p.area_m2 = 50e-6;
  p.p_max_Pa = 1.2e9;
  p.normal_force_N = 1e4;
  p.contact_point_yz_m = {-0.03, 0.012};
  p.contact_angle_rad = 0.5;
  p.grid.nx = 3;
  p.grid.ns = 2;
  p.grid.dx_m = 1e-3;
  p.grid.ds_m = 0.5e-3;
  p.grid.point_yz_m = {{-0.03, 0.012}, {-0.0305, 0.0125}};
  p.pressure_Pa = Eigen::VectorXd::LinSpaced(6, 0.0, 1.2e9);
  p.cells = 6;
  p.cells_in_contact = 5;
  r.patches.push_back(p);
  return r;
}

Scene NamedScene() {
  Scene s;
  s.name = "test";
  s.path = "test.toml";
  return s;
}

TEST(ContactOutputTest, JsonCarriesUnitsInKeyNames) {
  const nlohmann::json j = MakeContactJson(NamedScene(), GridResult());
  EXPECT_EQ(j["status"], "converged");
  EXPECT_EQ(j["scene"], "test");
  EXPECT_DOUBLE_EQ(j["approach_mm"].get<double>(), 0.02);
  EXPECT_DOUBLE_EQ(j["time_ms"].get<double>(), 4.0);
  EXPECT_EQ(j["stages"][0]["name"], "solve");
  EXPECT_DOUBLE_EQ(j["total"]["area_mm2"].get<double>(), 50.0);
  EXPECT_DOUBLE_EQ(j["total"]["p_max_MPa"].get<double>(), 1200.0);
  const auto& p = j["patches"][0];
  EXPECT_DOUBLE_EQ(p["contact_y_mm"].get<double>(), -30.0);
  EXPECT_NEAR(p["contact_angle_deg"].get<double>(), 28.6479, 1e-4);
  EXPECT_DOUBLE_EQ(p["cell_mm"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(p["cell_mm"][1].get<double>(), 0.5);
  EXPECT_EQ(p["cells_in_contact"], 5);
}

// tangential = "auto" (issue 16): the solver it chose per patch, its indicators and the rule in
// the JSON and the summary; a fixed method's outputs carry none of it (unchanged).
TEST(ContactOutputTest, AutoTangentialReportsItsChoice) {
  ContactResult r = GridResult();
  RollingPatch rolling;
  rolling.tangential = EmptyTangentialSolution(6);
  rolling.tangential.status = SolverStatus::kConverged;
  rolling.choice.method = TangentialMethod::kFastsim;
  r.patches[0].rolling = rolling;
  nlohmann::json j = MakeContactJson(NamedScene(), r);
  EXPECT_FALSE(j["patches"][0].contains("tangential_method"));
  EXPECT_EQ(FormatSummary(NamedScene(), r).find("tangential auto"), std::string::npos);
  r.patches[0].rolling->choice =
      ChooseTangentialMethod({0.276, 18.0, 0.0}, AccuracyPreset::kStandard);
  j = MakeContactJson(NamedScene(), r);
  const auto& p = j["patches"][0];
  EXPECT_EQ(p["tangential_method"], "exact");
  EXPECT_DOUBLE_EQ(p["tangential_spin_share"].get<double>(), 0.276);
  EXPECT_DOUBLE_EQ(p["tangential_a_over_b"].get<double>(), 18.0);
  EXPECT_EQ(p["tangential_reason"], "exact: spin share 0.276 > 0.100 (the limit 0.10 at standard)");
  EXPECT_NE(FormatSummary(NamedScene(), r)
                .find("tangential auto: exact: spin share 0.276 > 0.100 (the limit 0.10 at standard)"),
            std::string::npos);
}

TEST(ContactOutputTest, NonFiniteNumbersNeverReachJson) {
  ContactResult r = GridResult();
  r.patches[0].lateral_force_N = std::numeric_limits<double>::quiet_NaN();
  try {
    MakeContactJson(NamedScene(), r);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("$.patches[0].lateral_force_N"), std::string::npos)
        << e.what();
  }
  r = GridResult();
  r.approach_m = std::numeric_limits<double>::infinity();
  EXPECT_THROW(MakeContactJson(NamedScene(), r), std::runtime_error);
}

TEST(ContactOutputTest, CsvHasOneRowPerCell) {
  std::ostringstream out;
  WritePressureCsv(GridResult(), out);
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa");
  int rows = 0;
  std::string last;
  while (std::getline(in, line)) {
    ++rows;
    last = line;
  }
  EXPECT_EQ(rows, 6);
  // Last cell (ix 2, js 1): x = 2 mm, s = 0.5 mm, point of js 1, p = 1200 MPa.
  EXPECT_EQ(last, "1,2,1,2.000000,0.500000,-30.500000,12.500000,1200.000000");
}

TEST(ContactOutputTest, MismatchedPressureIsAnError) {
  ContactResult r = GridResult();
  r.patches[0].pressure_Pa.resize(4);
  std::ostringstream out;
  EXPECT_THROW(WritePressureCsv(r, out), std::runtime_error);
}

TEST(ContactOutputTest, HertzSamplesAnalyticEllipse) {
  PatchResult p;
  HertzSolution h;
  h.semi_axis_x_m = 4e-3;
  h.semi_axis_y_m = 2e-3;
  h.p0_Pa = 1e9;
  p.hertz = h;
  const auto samples = PressureSamples(p, 1);
  ASSERT_EQ(samples.size(), static_cast<size_t>(kHertzSamples * kHertzSamples));
  const int mid = kHertzSamples / 2;
  const auto& centre = samples[mid * kHertzSamples + mid];
  EXPECT_NEAR(centre.x_mm, 0.0, 1e-12);
  EXPECT_NEAR(centre.p_MPa, 1000.0, 1e-9);
  EXPECT_NEAR(samples.front().x_mm, -4.0, 1e-12);
  EXPECT_NEAR(samples.front().s_mm, -2.0, 1e-12);
  EXPECT_EQ(samples.front().p_MPa, 0.0);  // bounding-box corner lies outside the ellipse
  // On the x axis at x = a/2: p0 sqrt(1 - 1/4).
  const auto& half = samples[mid * kHertzSamples + mid + mid / 2];
  EXPECT_NEAR(half.x_mm, 2.0, 1e-12);
  EXPECT_NEAR(half.p_MPa, 1000.0 * std::sqrt(0.75), 1e-9);
}

TEST(ContactOutputTest, SummaryHasStatusTotalsAndPatchRow) {
  const std::string s = FormatSummary(NamedScene(), GridResult());
  EXPECT_NE(s.find("status      converged"), std::string::npos) << s;
  EXPECT_NE(s.find("area 50.00 mm2, p_max 1200.0 MPa"), std::string::npos) << s;
  EXPECT_NE(s.find("5/6"), std::string::npos) << s;
}

}  // namespace
}  // namespace railwear::app
