// Co-evolution of a vehicle entry's wheels (issue 16): every wheel of every wheelset wears with
// the rails from the same contact solutions (wear/wheel_wear.h), each on its own profile
// (WearState::vehicle_wheels), and the next step's curving and cases run the worn wheels.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"
#include "tests/wear/default_study.h"
#include "wear/vehicle_traffic.h"
#include "wear/wheel_wear.h"

namespace railwear {
namespace {

constexpr double kRailHardness_Pa = 2.6e9;
constexpr double kDistancePerPass_m = 300.0;

// S1002 wheels on UIC60 1:40 rails in a R 600 m curve at draft accuracy, one vehicle entry whose
// wheels wear over kDistancePerPass_m per pass with hardness `wheel_hardness_Pa`: a single
// wheelset (`bogie` false) or a bogie vehicle of four.
WearStudy VehicleWheelStudy(double wheel_hardness_Pa, bool bogie = false) {
  WearStudy study = VehicleCurveStudy(600.0, bogie ? VehicleKind::kBogie : VehicleKind::kWheelset,
                                      0.4, 20.0);
  study.rail_material.hardness_Pa = kRailHardness_Pa;
  study.traffic[0].name = "vehicle";
  study.traffic[0].wheel_wear = WheelWear{kDistancePerPass_m, wheel_hardness_Pa};
  study.options.quadrature_points = 1;
  return study;
}

double Area(const std::vector<double>& depth, const WearGrid& grid) {
  double a = 0.0;
  for (const double d : depth) a += d * grid.h_m;
  return a;
}

// A step of a bogie wagon wears both rails and both wheels of every wheelset (high and low, each
// its own profile); the wheelsets' wheels wear differently. A second step (on one wheelset, to
// keep the test short) runs the first step's worn wheels.
TEST(VehicleWheelWearTest, EveryWheelOfEveryWheelsetWearsEachStep) {
  const WearStudy study = VehicleWheelStudy(2.4e9, /*bogie=*/true);
  const WearState s0 = MakeInitialState(study);
  ASSERT_EQ(s0.vehicle_wheels.size(), 1u);
  ASSERT_EQ(s0.vehicle_wheels[0].size(), 4u);
  EXPECT_TRUE(s0.wheels.empty());
  const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  EXPECT_NE(step.state.rail.points(), s0.rail.points());
  EXPECT_NE(step.state.low_rail->points(), s0.low_rail->points());
  ASSERT_EQ(step.wheels.size(), 8u);  // 4 wheelsets x (high, low)
  std::printf("[ measured ] wagon, step 1 wheel worn area per pass [mm2]:");
  for (int k = 0; k < 8; ++k) {
    const WheelStepResult& w = step.wheels[k];
    EXPECT_EQ(w.traffic_index, 0);
    EXPECT_EQ(w.wheel, VehicleWheelIndex(k / 2, k % 2 == 0 ? RailSide::kHigh : RailSide::kLow));
    EXPECT_GT(Area(w.depth_per_pass_m, w.grid), 0.0) << "wheel " << w.wheel;
    EXPECT_GT(w.measures.worn_area_m2, 0.0) << "wheel " << w.wheel;
    EXPECT_NE(StateWheel(step.state, 0, w.wheel).points(), StateWheel(s0, 0, w.wheel).points())
        << "wheel " << w.wheel;
    std::printf(" %s %.3e", WheelName(study.traffic[0], w.wheel).c_str(),
                Area(w.depth_per_pass_m, w.grid) * 1e6);
  }
  std::printf("\n");
  // Each bogie's leading wheelset runs nearer its high flange than the trailing one: their high
  // wheels wear differently, which is why each wheel has its own profile.
  EXPECT_GT(step.wheels[0].measures.worn_area_m2, 2.0 * step.wheels[2].measures.worn_area_m2);

  const WearStudy one = VehicleWheelStudy(2.4e9);
  const WearState start = MakeInitialState(one);
  std::vector<StepResult> steps;
  RunWear(one, UnwornRails::Of(start), start,
          [&](const StepResult& s) {
            steps.push_back(s);
            return true;
          },
          2);
  ASSERT_EQ(steps.size(), 2u);
  for (const WheelStepResult& w : steps[1].wheels) {
    // Step 2's cases ran the worn wheels: their wheel grids are the worn profiles' bins, and
    // every wheel moved again.
    const Profile& worn = StateWheel(steps[0].state, 0, w.wheel);
    EXPECT_NE(worn.points(), StateWheel(start, 0, w.wheel).points());
    EXPECT_EQ(w.grid.n, WearGrid::ForProfile(worn, one.options.bin_m).n);
    EXPECT_NE(StateWheel(steps[1].state, 0, w.wheel).points(), worn.points());
  }
}

// Each wheel's worn volume per pass over its rail's (worn area per pass x L, the rail under the
// same cases) is the law's ratio H_rail / H_wheel, as for a prescribed entry's wheel
// (WheelWearTest.WornVolumesPerPassFollowTheLawsHardnessRatio, whose tolerance this keeps: the
// wheel's volume sums depth x 2 pi r at its bin centres, each column went round its own circle;
// second order in the bin width, measured ~1e-6). One wheelset: each rail's cases are its one
// wheel's, so the rail's depth per pass and the wheel's come from the same patches.
TEST(VehicleWheelWearTest, WornVolumesPerPassFollowTheLawsHardnessRatio) {
  constexpr double kTolerance = 1e-5;
  for (const double wheel_hardness_Pa : {2.0e9, 3.4e9}) {
    SCOPED_TRACE("wheel H " + std::to_string(wheel_hardness_Pa));
    const WearStudy study = VehicleWheelStudy(wheel_hardness_Pa);
    const WearState s0 = MakeInitialState(study);
    const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
    ASSERT_TRUE(step.low_rail);
    ASSERT_EQ(step.wheels.size(), 2u);
    const double expected = kRailHardness_Pa / wheel_hardness_Pa;
    const Profile& unworn = study.vehicles[0].wheel_profile;
    const double r0 = study.vehicles[0].rolling_radius_m;
    const double rail_high = Area(step.depth_per_pass_m, step.grid) * kDistancePerPass_m;
    const double rail_low =
        Area(step.low_rail->depth_per_pass_m, step.low_rail->grid) * kDistancePerPass_m;
    const double wheel_high = WheelWornVolume(step.wheels[0].depth_per_pass_m, step.wheels[0].grid,
                                              unworn, r0);
    const double wheel_low = WheelWornVolume(step.wheels[1].depth_per_pass_m, step.wheels[1].grid,
                                             unworn, r0);
    ASSERT_GT(rail_high, 0.0);
    ASSERT_GT(rail_low, 0.0);
    EXPECT_NEAR(wheel_high / rail_high / expected, 1.0, kTolerance);
    EXPECT_NEAR(wheel_low / rail_low / expected, 1.0, kTolerance);
    std::printf("[ measured ] wheelset, wheel/rail volume per pass over H_rail/H_wheel %.4f: high "
                "%.3e, low %.3e (relative)\n",
                expected, wheel_high / rail_high / expected - 1.0,
                wheel_low / rail_low / expected - 1.0);
  }
}

// A run stopped after one step and resumed from its state (the rails, the curving start and the
// vehicle's worn wheels) ends exactly where the uninterrupted run does, wheels included.
TEST(VehicleWheelWearTest, ResumedRunEqualsUninterrupted) {
  WearStudy study = VehicleWheelStudy(2.4e9);
  const WearState s0 = MakeInitialState(study);
  const UnwornRails unworn = UnwornRails::Of(s0);
  const WearRunSummary whole = RunWear(study, unworn, s0, nullptr, 2);
  const WearRunSummary first = RunWear(study, unworn, s0, nullptr, 1);
  // The resumed state as storage gives it back: every wheel through its slot.
  WearState resumed = first.state;
  resumed.vehicle_wheels.clear();
  for (const int wheel : {VehicleWheelIndex(0, RailSide::kHigh), VehicleWheelIndex(0, RailSide::kLow)}) {
    StateWheelSlot(&resumed, 0, wheel) = StateWheel(first.state, 0, wheel);
  }
  const WearRunSummary rest = RunWear(study, unworn, resumed, nullptr, 1);
  ASSERT_EQ(whole.state.step, 2);
  ASSERT_EQ(rest.state.step, 2);
  EXPECT_EQ(whole.state.passes, rest.state.passes);
  EXPECT_EQ(whole.state.rail.points(), rest.state.rail.points());
  EXPECT_EQ(whole.state.low_rail->points(), rest.state.low_rail->points());
  ASSERT_EQ(rest.state.vehicle_wheels.size(), 1u);
  ASSERT_EQ(rest.state.vehicle_wheels[0].size(), 1u);
  EXPECT_EQ(whole.state.vehicle_wheels[0][0].high.points(),
            rest.state.vehicle_wheels[0][0].high.points());
  EXPECT_EQ(whole.state.vehicle_wheels[0][0].low.points(),
            rest.state.vehicle_wheels[0][0].low.points());
}

// Without wheel_wear a vehicle entry runs as before: no wheels in the state or the step.
TEST(VehicleWheelWearTest, WithoutWheelWearNoWheelsAreCarried) {
  WearStudy study = VehicleWheelStudy(2.4e9);
  study.traffic[0].wheel_wear.reset();
  const WearState s0 = MakeInitialState(study);
  EXPECT_TRUE(s0.vehicle_wheels.empty());
  const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  EXPECT_TRUE(step.wheels.empty());
  EXPECT_TRUE(step.state.vehicle_wheels.empty());
}

}  // namespace
}  // namespace railwear
