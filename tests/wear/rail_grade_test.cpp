// Rail grades (issue 16 point 3): the EN 13674-1 presets, and on the default study's set-up one
// wear step per grade showing that a harder grade wears less, by the factor the laws give
// (Archard: the hardness ratio exactly; KTH: at least that, as its seizure region p > 0.8 H
// shrinks), pinned and compared with the published track factor (Heyder & Girsch 2005), as
// docs/wear.md documents.
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

// The published factor railwear compares with (docs/wear.md "Rail grades"): in DB's track tests
// of voestalpine's head-special-hardened rail (350HT, today's R350HT) against grade 900A (R260),
// measured by transverse profile measurements over up to 90 MGT, "HSH rails showed the lowest
// wear rate (30 to 45 % less than 900A-grades)" (Heyder & Girsch, "Testing of HSH rails in
// high-speed tracks to minimise rail damage", Wear 258 (2005) 1014-1021, abstract). As a factor
// R260 / R350HT: 1 / 0.70 to 1 / 0.55.
constexpr double kPublishedFactorLow = 1.0 / 0.70;   // 1.43
constexpr double kPublishedFactorHigh = 1.0 / 0.55;  // 1.82

// railwear's R260 / R350HT factors on this traffic, pinned (measured on commit 192d1bf + this
// test: Archard 1.321, KTH 2.006, KTH continuous 2.097). Tolerance 3 %: the step is
// deterministic, so this only lets the contact numerics move a little (the KTH factors moved by
// about 1 % when FASTSIM's coefficients were extended beyond a/b = 10) while keeping each factor
// on its side of the published band, which is at least 7.5 % away from each.
constexpr double kPinnedFactorTolerance = 0.03;

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
    const double factor = a260 / a350;
    if (law == WearLawKind::kArchard) {
      // One k, same contact (same elastic constants): depth ~ 1/H exactly.
      EXPECT_NEAR(factor, h350 / h260, 1e-9);
      EXPECT_NEAR(a200 / a260, h260 / h200, 1e-9);
      // Below the published band: the hardness ratio alone understates the track's gain.
      EXPECT_LT(factor, kPublishedFactorLow);
    } else {
      // The map's coefficients do not change with the grade; only 1/H and the seizure
      // boundary 0.8 H do, and a harder rail enters seizure less.
      EXPECT_GE(factor, h350 / h260 * (1.0 - 1e-9));
      EXPECT_GE(a200 / a260, h260 / h200 * (1.0 - 1e-9));
      // Above the published band on this flange-dominated traffic (the seizure region's share).
      EXPECT_GT(factor, kPublishedFactorHigh);
    }
    const double pinned = law == WearLawKind::kArchard ? 1.321
                          : law == WearLawKind::kKth   ? 2.006
                                                       : 2.097;
    EXPECT_NEAR(factor / pinned, 1.0, kPinnedFactorTolerance);
    std::printf(
        "[figure] %-15s R260/R350HT %.3f against the published %.2f-%.2f (Heyder & Girsch "
        "2005): %+.1f %% from the band\n",
        std::string(ToString(law)).c_str(), factor, kPublishedFactorLow, kPublishedFactorHigh,
        100.0 * (factor < kPublishedFactorLow ? factor / kPublishedFactorLow - 1.0
                                              : factor / kPublishedFactorHigh - 1.0));
  }
}

}  // namespace
}  // namespace railwear
