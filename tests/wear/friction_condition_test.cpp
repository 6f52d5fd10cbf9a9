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
#include "core/profile/builtin_profiles.h"
#include "wear/wear_simulation.h"

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

// The default study (examples/wear_high_rail.toml) at draft accuracy with 3 nodes per entry.
WearStudy DefaultStudy(WearLawKind law) {
  WearStudy study;
  study.rail_profile = MakeUic60();
  study.cant_ratio = 0.025;
  study.rail_material.hardness_Pa = 2.6e9;
  study.rail_material.shear_yield_Pa = 350e6;
  study.model = MakeModelOptions(ModelKind::kConformal);
  study.model.kernel = KernelModel::kBoussinesq;
  study.model.kind = ModelKind::kCustom;
  study.model.accuracy = AccuracyPreset::kDraft;
  TrafficCase freight;
  freight.name = "freight";
  freight.wheel_profile = MakeS1002();
  freight.rolling_radius_m = 0.46;
  freight.vertical_force_N = 110e3;
  freight.axle_load_t = 22.5;
  freight.lateral_shift_mean_m = -4.5e-3;
  freight.lateral_shift_std_m = 1.0e-3;
  freight.yaw_rad = 4e-3;
  freight.speed_m_s = 22.0;
  freight.share = 0.4;
  TrafficCase passenger = freight;
  passenger.name = "passenger";
  passenger.vertical_force_N = 80e3;
  passenger.axle_load_t = 16.0;
  passenger.lateral_shift_mean_m = -5.0e-3;
  passenger.yaw_rad = 3e-3;
  passenger.speed_m_s = 33.0;
  passenger.share = 0.6;
  study.traffic = {freight, passenger};
  study.options.law.kind = law;
  study.options.total_mgt = 10.0;
  study.options.quadrature_points = 3;
  study.options.threads = 0;
  return study;
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

// Worn area per axle pass [m^2] of the high rail in the first step.
double WornAreaPerPass(const WearStudy& study) {
  const WearState start = MakeInitialState(study);
  const StepResult step = RunWearStep(study, UnwornRails::Of(start), start, 1e12);
  double area = 0.0;
  for (double d : step.depth_per_pass_m) area += d * step.grid.h_m;
  return area;
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
