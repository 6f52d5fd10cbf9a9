// Friction conditions (issue 16 point 1): the defaults and their checks, and on the default
// study's set-up (examples/wear_high_rail.toml at draft accuracy) one wear step per law that
// shows a lubricated gauge face wears at least 3x less than a dry one and that no condition's
// lower mu, with its factor, raises wear.
#include "wear/friction_condition.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "tests/wear/default_study.h"

namespace railwear {
namespace {

TEST(FrictionConditionTest, NamesRoundTripAndDefaultsFollowTheTable) {
  for (const auto& e : kFrictionConditionNames) {
    EXPECT_EQ(FrictionConditionFromString(ToString(e.value)), e.value);
  }
  EXPECT_FALSE(FrictionConditionFromString("greasy").has_value());
  const FrictionConditions c;
  EXPECT_DOUBLE_EQ(c[FrictionCondition::kDry].friction, 0.40);
  EXPECT_DOUBLE_EQ(c[FrictionCondition::kWet].kth_factor, 0.2);
  EXPECT_DOUBLE_EQ(c[FrictionCondition::kLubricated].archard_factor, 0.1);
  EXPECT_DOUBLE_EQ(c[FrictionCondition::kLubricated].friction, 0.10);
  EXPECT_DOUBLE_EQ(c[FrictionCondition::kFrictionModified].friction, 0.35);
  // Every law takes the same default factor; kth and kth-continuous share theirs.
  for (const auto& e : kFrictionConditionNames) {
    EXPECT_DOUBLE_EQ(WearFactor(c[e.value], WearLawKind::kUsfd),
                     WearFactor(c[e.value], WearLawKind::kArchard));
    EXPECT_DOUBLE_EQ(WearFactor(c[e.value], WearLawKind::kKth),
                     WearFactor(c[e.value], WearLawKind::kKthContinuous));
  }
  EXPECT_NEAR(c.gauge_face_angle_rad * 180.0 / M_PI, 15.0, 1e-12);
  EXPECT_NO_THROW(ValidateFrictionConditions(c));
}

TEST(FrictionConditionTest, BadValuesAreRefusedWithTheirName) {
  FrictionConditions c;
  c[FrictionCondition::kWet].kth_factor = -1.0;
  try {
    ValidateFrictionConditions(c);
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"wet\": kth_factor = -1"), std::string::npos)
        << e.what();
  }
  c = FrictionConditions{};
  c[FrictionCondition::kLubricated].friction = 0.0;
  EXPECT_THROW(ValidateFrictionConditions(c), InputError);
  c = FrictionConditions{};
  c.gauge_face_angle_rad = 2.0;
  EXPECT_THROW(ValidateFrictionConditions(c), InputError);
}

// Every entry at `top` on the top of rail (mu from the condition) and `gauge` on the gauge face.
WearStudy WithConditions(WearStudy study, FrictionCondition top,
                         std::optional<FrictionCondition> gauge) {
  for (TrafficCase& c : study.traffic) {
    c.condition = top;
    c.gauge_face_condition = gauge;
    c.friction = study.options.conditions[top].friction;
  }
  return study;
}

constexpr WearLawKind kLaws[] = {WearLawKind::kArchard, WearLawKind::kKth,
                                 WearLawKind::kKthContinuous, WearLawKind::kUsfd};

TEST(FrictionConditionTest, ALubricatedGaugeFaceWearsAtLeastThreeTimesLessWithEveryLaw) {
  for (const WearLawKind law : kLaws) {
    const WearStudy base = DefaultStudy(law);
    const double dry = WornAreaPerPass(WithConditions(base, FrictionCondition::kDry, std::nullopt));
    const double lubricated = WornAreaPerPass(
        WithConditions(base, FrictionCondition::kDry, FrictionCondition::kLubricated));
    std::printf("%-15s dry %.4e mm^2  lubricated gauge face %.4e mm^2  ratio %.2f\n",
                std::string(ToString(law)).c_str(), dry * 1e6, lubricated * 1e6, dry / lubricated);
    EXPECT_GT(dry, 0.0);
    EXPECT_GE(dry / lubricated, 3.0) << ToString(law);
  }
}

TEST(FrictionConditionTest, NoConditionsLowerMuWithItsFactorRaisesWear) {
  for (const WearLawKind law : kLaws) {
    const WearStudy base = DefaultStudy(law);
    const double dry = WornAreaPerPass(WithConditions(base, FrictionCondition::kDry, std::nullopt));
    for (const FrictionCondition c : {FrictionCondition::kFrictionModified, FrictionCondition::kWet,
                                      FrictionCondition::kLubricated}) {
      const double wear = WornAreaPerPass(WithConditions(base, c, std::nullopt));
      std::printf("%-15s %-18s %.4e mm^2 (dry %.4e)\n", std::string(ToString(law)).c_str(),
                  std::string(ToString(c)).c_str(), wear * 1e6, dry * 1e6);
      EXPECT_LE(wear, dry) << ToString(law) << " " << ToString(c);
    }
  }
}

}  // namespace
}  // namespace railwear
