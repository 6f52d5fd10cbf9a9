// Rail grades (issue 16 point 3): the EN 13674-1 presets, and on the default study's set-up one
// wear step per grade showing that a harder grade wears less, by the factor the laws give
// (Archard: the hardness ratio exactly; KTH: at least that, as its seizure region p > 0.8 H
// shrinks), documented in docs/wear.md next to the published evidence.
#include "wear/rail_grade.h"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tests/wear/default_study.h"

namespace railwear {
namespace {

TEST(RailGradeTest, PresetsFollowEn13674) {
  for (const auto& e : kRailGradeNames) EXPECT_EQ(RailGradeFromString(e.name), e.value);
  EXPECT_FALSE(RailGradeFromString("R400").has_value());
  const RailGradeProperties r200 = RailGradeOf(RailGrade::kR200);
  const RailGradeProperties r260 = RailGradeOf(RailGrade::kR260);
  const RailGradeProperties r350 = RailGradeOf(RailGrade::kR350HT);
  // Middle of the Brinell range, 1 HB = 9.80665 MPa.
  EXPECT_NEAR(r200.hardness_Pa, 220.0 * 9.80665e6, 1.0);
  EXPECT_NEAR(r260.hardness_Pa, 280.0 * 9.80665e6, 1.0);
  EXPECT_NEAR(r350.hardness_Pa, 370.0 * 9.80665e6, 1.0);
  EXPECT_DOUBLE_EQ(r260.shear_yield_Pa, 350e6);  // the project's R260-type value
  EXPECT_LT(r200.shear_yield_Pa, r260.shear_yield_Pa);
  EXPECT_LT(r260.shear_yield_Pa, r350.shear_yield_Pa);
  EXPECT_DOUBLE_EQ(r350.density_kg_m3, 7850.0);
}

WearStudy WithGrade(WearStudy study, RailGrade grade) {
  const RailGradeProperties g = RailGradeOf(grade);
  study.rail_material.youngs_modulus_Pa = g.youngs_modulus_Pa;
  study.rail_material.poisson_ratio = g.poisson_ratio;
  study.rail_material.hardness_Pa = g.hardness_Pa;
  study.rail_material.shear_yield_Pa = g.shear_yield_Pa;
  for (TrafficCase& c : study.traffic) c.friction = 0.35;
  return study;
}

TEST(RailGradeTest, AHarderGradeWearsLessByAtLeastTheHardnessRatio) {
  const double h260 = RailGradeOf(RailGrade::kR260).hardness_Pa;
  const double h350 = RailGradeOf(RailGrade::kR350HT).hardness_Pa;
  const double h200 = RailGradeOf(RailGrade::kR200).hardness_Pa;
  for (const WearLawKind law :
       {WearLawKind::kArchard, WearLawKind::kKth, WearLawKind::kKthContinuous}) {
    const WearStudy base = DefaultStudy(law);
    const double a200 = WornAreaPerPass(WithGrade(base, RailGrade::kR200));
    const double a260 = WornAreaPerPass(WithGrade(base, RailGrade::kR260));
    const double a350 = WornAreaPerPass(WithGrade(base, RailGrade::kR350HT));
    std::printf(
        "%-15s R200 %.4e  R260 %.4e  R350HT %.4e mm^2/pass; R260/R350HT %.3f "
        "(H ratio %.3f), R200/R260 %.3f (H ratio %.3f)\n",
        std::string(ToString(law)).c_str(), a200 * 1e6, a260 * 1e6, a350 * 1e6, a260 / a350,
        h350 / h260, a200 / a260, h260 / h200);
    EXPECT_GT(a350, 0.0);
    if (law == WearLawKind::kArchard) {
      // One k, same contact (same elastic constants): depth ~ 1/H exactly.
      EXPECT_NEAR(a260 / a350, h350 / h260, 1e-9);
      EXPECT_NEAR(a200 / a260, h260 / h200, 1e-9);
    } else {
      // The map's coefficients do not change with the grade; only 1/H and the seizure
      // boundary 0.8 H do, and a harder rail enters seizure less.
      EXPECT_GE(a260 / a350, h350 / h260 * (1.0 - 1e-9));
      EXPECT_GE(a200 / a260, h260 / h200 * (1.0 - 1e-9));
    }
  }
}

}  // namespace
}  // namespace railwear
