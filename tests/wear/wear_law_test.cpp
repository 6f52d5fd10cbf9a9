#include "wear/wear_law.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

constexpr double kH = 2.6e9;  // rail hardness [Pa]

TEST(WearLawTest, NamesRoundTrip) {
  for (WearLawKind k : {WearLawKind::kArchard, WearLawKind::kKth, WearLawKind::kKthContinuous,
                        WearLawKind::kUsfd}) {
    EXPECT_EQ(WearLawKindFromString(ToString(k)), k);
  }
  EXPECT_FALSE(WearLawKindFromString("archard2").has_value());
}

TEST(WearLawTest, ArchardDepthRateIsKPVOverHV) {
  WearLaw law;
  law.archard_k = 2e-4;
  const WearCellState cell{1.0e9, 0.05, 0.0};
  // dz/dL = k p v / (H V)
  EXPECT_DOUBLE_EQ(WearDepthPerRolledMetre(law, cell, kH, 20.0), 2e-4 * 1e9 * 0.05 / (kH * 20.0));
  EXPECT_EQ(WearDepthPerRolledMetre(law, {0.0, 0.05, 0.0}, kH, 20.0), 0.0);
  EXPECT_EQ(WearDepthPerRolledMetre(law, {1e9, 0.0, 0.0}, kH, 20.0), 0.0);
}

TEST(WearLawTest, KthPublishedRegions) {
  WearLaw law;
  law.kind = WearLawKind::kKth;
  EXPECT_EQ(WearCoefficient(law, 0.5 * kH, 0.1, kH), law.kth_k_mild_low);   // B
  EXPECT_EQ(WearCoefficient(law, 0.5 * kH, 0.3, kH), law.kth_k_severe);     // C
  EXPECT_EQ(WearCoefficient(law, 0.5 * kH, 1.0, kH), law.kth_k_mild_high);  // D
  EXPECT_EQ(WearCoefficient(law, 0.9 * kH, 0.1, kH), law.kth_k_seizure);    // A
  // Discontinuous at v1 as published.
  EXPECT_EQ(WearCoefficient(law, 0.5 * kH, 0.2 - 1e-9, kH), law.kth_k_mild_low);
  EXPECT_EQ(WearCoefficient(law, 0.5 * kH, 0.2, kH), law.kth_k_severe);
}

TEST(WearLawTest, KthContinuousMatchesMapAwayFromBoundariesAndIsContinuous) {
  WearLaw pub;
  pub.kind = WearLawKind::kKth;
  WearLaw cont = pub;
  cont.kind = WearLawKind::kKthContinuous;
  // Outside the blend bands the two agree.
  for (double v : {0.01, 0.1, 0.35, 2.0}) {
    for (double ph : {0.3, 0.95}) {
      EXPECT_NEAR(WearCoefficient(cont, ph * kH, v, kH), WearCoefficient(pub, ph * kH, v, kH),
                  1e-12 * WearCoefficient(pub, ph * kH, v, kH))
          << "v = " << v << " p/H = " << ph;
    }
  }
  // Continuous: no jump larger than the blend slope allows across a fine sweep in v and p/H.
  double prev = WearCoefficient(cont, 0.5 * kH, 0.05, kH);
  for (double v = 0.05; v < 2.0; v *= 1.001) {
    const double k = WearCoefficient(cont, 0.5 * kH, v, kH);
    EXPECT_LT(std::abs(std::log(k / prev)), 0.02) << "v = " << v;
    prev = k;
  }
  prev = WearCoefficient(cont, 0.5 * kH, 0.1, kH);
  for (double ph = 0.5; ph < 1.2; ph += 0.0005) {
    const double k = WearCoefficient(cont, ph * kH, 0.1, kH);
    EXPECT_LT(std::abs(std::log(k / prev)), 0.05) << "p/H = " << ph;
    prev = k;
  }
}

TEST(WearLawTest, UsfdContinuousFormAndKnees) {
  EXPECT_DOUBLE_EQ(UsfdWearRate(5.0), 26.5);       // 5.3 x
  EXPECT_DOUBLE_EQ(UsfdWearRate(40.0), 55.0);      // plateau
  EXPECT_NEAR(UsfdWearRate(100.0), 1411.3, 1e-9);  // 61.9 x - 4778.7
  // Knees of the continuous form: 55/5.3 and (55 + 4778.7)/61.9, within 1 % of the published.
  const double knee1 = 55.0 / 5.3, knee2 = (55.0 + 4778.7) / 61.9;
  EXPECT_NEAR(knee1, 10.4, 0.01 * 10.4);
  EXPECT_NEAR(knee2, 77.2, 0.015 * 77.2);
  for (double x = 0.0; x < 200.0; x += 0.01) {
    EXPECT_LE(UsfdWearRate(x), UsfdWearRate(x + 0.01) + 1e-12);  // monotone, no jumps
    EXPECT_LT(UsfdWearRate(x + 0.01) - UsfdWearRate(x), 61.9 * 0.01 + 1e-9);
  }
}

TEST(WearLawTest, UsfdDepthRateFromEnergyIndex) {
  WearLaw law;
  law.kind = WearLawKind::kUsfd;
  // q.v / V = 40 N/mm^2 = 40e6 Pa: plateau 55 ug/(m mm^2) = 0.055 kg/(m m^2).
  const WearCellState cell{1e9, 0.1, 40e6 * 20.0};
  EXPECT_NEAR(WearDepthPerRolledMetre(law, cell, kH, 20.0), 0.055 / 7850.0, 1e-18);
}

TEST(WearLawTest, ValidateNamesTheParameter) {
  WearLaw law;
  law.archard_k = -1.0;
  try {
    ValidateWearLaw(law);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("k = -1"), std::string::npos) << e.what();
  }
  law = WearLaw{};
  law.kth_v1_m_s = 0.8;
  EXPECT_THROW(ValidateWearLaw(law), InputError);
  EXPECT_NO_THROW(ValidateWearLaw(WearLaw{}));
}

}  // namespace
}  // namespace railwear
