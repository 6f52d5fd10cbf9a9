// Co-evolution and wheel populations (issue 16 point 6): the wheel of a traffic entry wearing
// with the rail from the same contact solutions (wear/wheel_wear.h), the step control over rails
// and wheels, the opt-in leaving the rail as it was, resumption with the wheels, wheel grades and
// the expansion of a wheel population into weighted entries.
#include "wear/wheel_wear.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/geometry/curve_locator.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/test_support.h"
#include "tests/wear/default_study.h"
#include "wear/rail_grade.h"
#include "wear/wear_simulation.h"

namespace railwear {
namespace {

// The InputError `f` throws names every part.
void ExpectInputError(const std::function<void()>& f, const std::vector<std::string>& parts) {
  const std::string message = test::InputErrorMessage(f);
  for (const std::string& part : parts) EXPECT_TRUE(test::Contains(message, part));
}

constexpr double kRailHardness_Pa = 2.6e9;
constexpr double kRollingRadius_m = 0.46;
// "No wear": below 1 nm, a sixtieth of the 6.4e-8 m the resampling left at the flange back.
// Measured with CompareWheelWithUnworn: 3e-17 m for the resampled unworn wheel, 8e-16 m off the
// band of a 0.1 mm deep step 1.
constexpr double kNoWear_m = 1e-9;
// Off the band after more steps, relative to the wheel's deepest wear (measured 5e-5: see below).
constexpr double kResampling = 1e-3;
// The band beyond the worn bins where the worn profile may still differ: a changed point moves a
// natural cubic spline by a factor 0.27 less per knot (0.2 mm) away, so 2 mm is 1e-6 of the
// change; step 2's worn bins lie on step 1's profile, whose arc length moved by under 0.1 mm.
constexpr double kBand_m = 2e-3;

// S1002 on UIC60 1:40 at draft accuracy, one load case at the gauge corner (no spread), the
// entry's wheel wearing over `distance_m` per pass with hardness `wheel_hardness_Pa`.
WearStudy MakeStudy(WearLawKind law, double wheel_hardness_Pa, double distance_m = 200.0) {
  WearStudy study = DraftConformalStudyOnUic60();
  study.rail_material.hardness_Pa = kRailHardness_Pa;
  TrafficCase c;
  c.name = "S1002";
  c.wheel_profile = MakeS1002();
  c.rolling_radius_m = kRollingRadius_m;
  c.vertical_force_N = 80e3;
  c.axle_load_t = 16.0;
  c.lateral_shift_mean_m = -4.5e-3;
  c.yaw_rad = 4e-3;
  c.friction = 0.4;
  c.speed_m_s = 20.0;
  c.wheel_wear = WheelWear{distance_m, wheel_hardness_Pa};
  study.traffic = {c};
  study.options.law.kind = law;
  study.options.law.archard_k = 1e-4;
  study.options.total_passes = 2e5;
  study.options.quadrature_points = 1;
  study.options.threads = 1;
  return study;
}

StepResult FirstStep(const WearStudy& study) {
  const WearState start = MakeInitialState(study);
  return RunWearStep(study, UnwornRails::Of(start), start, TotalPasses(study));
}

// The worn volume of one pass of the rail over the wheel's rolled distance L, and of the wheel.
struct Volumes {
  double rail_m3 = 0.0, wheel_m3 = 0.0;
};
Volumes VolumesPerPass(const WearStudy& study, const StepResult& step) {
  EXPECT_EQ(step.wheels.size(), 1u);
  const WheelStepResult& w = step.wheels.at(0);
  const TrafficCase& c = study.traffic[w.traffic_index];
  Volumes v;
  v.rail_m3 = WornArea(step.depth_per_pass_m, step.grid) * c.wheel_wear->distance_per_pass_m;
  v.wheel_m3 = WheelWornVolume(w.depth_per_pass_m, w.grid, c.wheel_profile, c.rolling_radius_m);
  return v;
}

// The wheel's volume over the rail's is the law's ratio: H_rail / H_wheel for Archard (both bodies
// slide the same distance under the same load), 1 for USFD (no hardness, equal densities).
// Tolerance: the wheel's volume here sums depth x 2 pi r at the bin centres, while each column's
// depth went round its circle with the column's own radius. Along a column's arc r is nearly
// linear and the depth is spread uniformly, so the two agree to second order; what is left is
// the end bins' centres against their overlaps' centres, of order h |dr/ds| / r ~ 2e-4 times the
// end bins' share of the column. Measured 9.1e-7 for all three cases (the same geometry): 1e-5
// keeps a margin of 10. (A bound that ignores the cancellation, column width over r, is 2e-3.)
TEST(WheelWearTest, WornVolumesPerPassFollowTheLawsHardnessRatio) {
  constexpr double kTolerance = 1e-5;
  struct Case {
    WearLawKind law;
    double wheel_hardness_Pa;
    double expected_ratio;
  };
  for (const Case& k : {Case{WearLawKind::kArchard, 2.0e9, kRailHardness_Pa / 2.0e9},
                        Case{WearLawKind::kArchard, 3.4e9, kRailHardness_Pa / 3.4e9},
                        Case{WearLawKind::kUsfd, 3.4e9, 1.0}}) {
    SCOPED_TRACE(std::string(ToString(k.law)) + " wheel H " + std::to_string(k.wheel_hardness_Pa));
    const WearStudy study = MakeStudy(k.law, k.wheel_hardness_Pa);
    const StepResult step = FirstStep(study);
    const Volumes v = VolumesPerPass(study, step);
    ASSERT_GT(v.rail_m3, 0.0);
    ASSERT_GT(v.wheel_m3, 0.0);
    EXPECT_NEAR(v.wheel_m3 / v.rail_m3 / k.expected_ratio, 1.0, kTolerance);
    // The circumference factor: the wheel's worn AREA per pass is the rail's times the law's
    // ratio times L / (2 pi r) (r within the wheel's radii at the patch).
    const double wheel_area = WornArea(step.wheels[0].depth_per_pass_m, step.wheels[0].grid);
    const double rail_area = WornArea(step.depth_per_pass_m, step.grid);
    const double factor = wheel_area / (rail_area * k.expected_ratio);
    EXPECT_GT(factor, 200.0 / (2.0 * std::numbers::pi * 0.50));
    EXPECT_LT(factor, 200.0 / (2.0 * std::numbers::pi * 0.44));
    std::cerr << "[figure] " << ToString(k.law) << ": wheel/rail volume per pass "
              << v.wheel_m3 / v.rail_m3 << " (law's ratio " << k.expected_ratio << ", relative "
              << v.wheel_m3 / v.rail_m3 / k.expected_ratio - 1.0
              << "), area factor " << factor << " (L/(2 pi r0) = "
              << 200.0 / (2.0 * std::numbers::pi * kRollingRadius_m) << ")\n";
  }
}

// Twice the distance per pass: twice the wheel's wear, the rail's unchanged bit for bit.
TEST(WheelWearTest, WheelWearScalesWithTheDistancePerPass) {
  const StepResult one = FirstStep(MakeStudy(WearLawKind::kArchard, 2.4e9, 100.0));
  const StepResult two = FirstStep(MakeStudy(WearLawKind::kArchard, 2.4e9, 200.0));
  EXPECT_EQ(one.depth_per_pass_m, two.depth_per_pass_m);
  const double a1 = WornArea(one.wheels[0].depth_per_pass_m, one.wheels[0].grid);
  const double a2 = WornArea(two.wheels[0].depth_per_pass_m, two.wheels[0].grid);
  EXPECT_NEAR(a2 / a1, 2.0, 1e-12);
}

// Co-evolution is opt-in and changes nothing of the rail's first step but its passes: the same
// contacts (the wheel is not resampled at step 0) give the rail the same depth per pass, bit for
// bit; the step's passes then take the deepest of rail and wheel.
TEST(WheelWearTest, OptInLeavesTheRailsDepthPerPassAsItWas) {
  WearStudy without = MakeStudy(WearLawKind::kArchard, 2.4e9);
  without.traffic[0].wheel_wear.reset();
  const StepResult plain = FirstStep(without);
  const StepResult coevolving = FirstStep(MakeStudy(WearLawKind::kArchard, 2.4e9));
  EXPECT_TRUE(plain.wheels.empty());
  EXPECT_TRUE(plain.state.wheels.empty());
  EXPECT_EQ(plain.depth_per_pass_m, coevolving.depth_per_pass_m);
  ASSERT_EQ(plain.cases.size(), 1u);
  EXPECT_EQ(plain.cases[0].worn_area_per_pass_m2, coevolving.cases[0].worn_area_per_pass_m2);
  EXPECT_EQ(plain.cases[0].wheel_worn_area_per_pass_m2, 0.0);
  EXPECT_GT(coevolving.cases[0].wheel_worn_area_per_pass_m2, 0.0);
  // The wheel wears faster here (L / (2 pi r) ~ 69 revolutions a pass): it sets the step.
  EXPECT_LT(coevolving.step_passes, plain.step_passes);
}

// Step control over rails and wheels: the deepest smoothed step depth of every worn body is at
// most max_depth_per_step, and the deepest of them is at it (to rounding).
TEST(WheelWearTest, StepControlTakesTheDeepestOfRailsAndWheels) {
  for (const double distance_m : {0.5, 200.0}) {  // the rail sets the step, then the wheel
    SCOPED_TRACE(distance_m);
    const StepResult s = FirstStep(MakeStudy(WearLawKind::kArchard, 2.4e9, distance_m));
    const double rail = *std::max_element(s.step_depth_m.begin(), s.step_depth_m.end());
    const double wheel =
        *std::max_element(s.wheels[0].step_depth_m.begin(), s.wheels[0].step_depth_m.end());
    EXPECT_LE(rail, 1e-4 * (1.0 + 1e-12));
    EXPECT_LE(wheel, 1e-4 * (1.0 + 1e-12));
    EXPECT_NEAR(std::max(rail, wheel), 1e-4, 1e-15);
    EXPECT_EQ(wheel > rail, distance_m > 1.0);
    // The wheel moved by that depth: its measures against the unworn wheel.
    EXPECT_NEAR(s.wheels[0].measures.max_depth_m, wheel, 0.05 * wheel);
    EXPECT_GT(s.wheels[0].measures.worn_area_m2, 0.0);
  }
}

// Two steps at once, and one step then a second from the first's state (as --resume reads it
// back): the same rail and wheel profiles, bit for bit; the wheel profile changes every step.
TEST(WheelWearTest, WheelsAreStateAndAResumedRunIsBitIdentical) {
  const WearStudy study = MakeStudy(WearLawKind::kArchard, 2.4e9);
  const WearState start = MakeInitialState(study);
  ASSERT_EQ(start.wheels.size(), 1u);
  EXPECT_EQ(start.wheels[0].points(), study.traffic[0].wheel_profile.points());
  std::vector<StepResult> whole;
  RunWear(study, UnwornRails::Of(start), start, [&](const StepResult& s) {
    whole.push_back(s);
    return true;
  }, 2);
  ASSERT_EQ(whole.size(), 2u);
  EXPECT_NE(whole[0].state.wheels[0].points(), start.wheels[0].points());
  EXPECT_NE(whole[1].state.wheels[0].points(), whole[0].state.wheels[0].points());
  std::vector<StepResult> resumed;
  RunWear(study, UnwornRails::Of(start), whole[0].state, [&](const StepResult& s) {
    resumed.push_back(s);
    return true;
  }, 1);
  ASSERT_EQ(resumed.size(), 1u);
  EXPECT_EQ(resumed[0].state.rail.points(), whole[1].state.rail.points());
  EXPECT_EQ(resumed[0].state.wheels[0].points(), whole[1].state.wheels[0].points());
  EXPECT_EQ(resumed[0].state.passes, whole[1].state.passes);
}

// The wheel's measures report wear, not the loop's resampling (issue 16: four nearly unworn wheels
// of examples/curve_r600_wheel_wear.toml reported their deepest point, 0.1 um, at the flange back
// y = -70 mm where no contact is). The cause: the loop resamples a worn wheel every 0.2 mm
// (ResampleProfile) while step 0 keeps S1002 as given (0.1 mm points); natural cubic splines at
// the two spacings part where the curve bends near an end. Measured against the given wheel that
// difference is the deepest "wear" of a wheel that barely wore; CompareWheelWithUnworn measures
// against the given wheel resampled as the worn one was.
TEST(WheelWearTest, ResamplingTheUnwornWheelIsNoWear) {
  const Profile s1002 = MakeS1002();
  const Profile resampled = ResampleProfile(s1002, 2e-4);
  const WearMeasures raw = CompareWheelProfiles(s1002, resampled);
  // The representation error itself: 6.4e-8 m at the flange back's end (and up to 7e-8 m of
  // either sign at the arcs' junctions inside).
  EXPECT_GT(raw.max_depth_m, 1e-8);
  EXPECT_NEAR(raw.max_depth_y_m, -0.070, 1e-3);
  const WearMeasures m = CompareWheelWithUnworn(s1002, resampled);
  double largest = 0.0;
  for (double d : m.depth_m) largest = std::max(largest, std::abs(d));
  std::cerr << "[figure] S1002 against itself resampled at 0.2 mm: max depth " << raw.max_depth_m
            << " m at y = " << raw.max_depth_y_m * 1e3
            << " mm; CompareWheelWithUnworn: largest |depth| " << largest << " m\n";
  // Both sides are the same resampling of the same curve: rounding only.
  EXPECT_LT(largest, kNoWear_m);
  EXPECT_LT(std::abs(m.worn_area_m2), kNoWear_m * 1e-3);
  // A wheel that never wore (the given profile itself) is measured as it is: zero.
  const WearMeasures same = CompareWheelWithUnworn(s1002, s1002);
  EXPECT_LT(std::abs(same.max_depth_m), kNoWear_m);
  EXPECT_LT(std::abs(same.worn_area_m2), kNoWear_m * 1e-3);
}

// CompareWheelWithUnworn's fallback (issue 16): when the feet of the worn profile's points on
// the unworn curve do not advance (wear deeper than the curve's radius of curvature bunches
// them; a spline through them could not even be built, Profile refuses duplicate points), it
// measures the worn profile against the unworn one resampled at the worn profile's number of
// intervals. The smallest case: a conical tread (1:20, straight, so that its resampling is
// exact) with a groove of depth kGrooveDepth_m and width kGrooveWidth_m worn into it, whose walls
// lie along the tread's normal (a step in depth: zero radius). Every point of a wall has the
// same foot, so the loop over the feet stops at the first wall point and the fallback measures.
TEST(WheelWearTest, AGrooveWhoseFeetBunchIsMeasuredAgainstTheResampledUnwornWheel) {
  constexpr double kSpacing_m = 1e-4;      // the points' spacing, on tread, walls and floor
  constexpr double kHalfLength_m = 20e-3;  // the tread runs from -20 to 20 mm along itself
  constexpr double kGrooveWidth_m = 4e-3;  // from -2 to 2 mm
  constexpr double kGrooveDepth_m = 1e-3;
  // The tread's unit tangent (1:20 cone) and its normal into the wheel's material (-z side).
  const double alpha = std::atan(1.0 / 20.0);
  const Eigen::Vector2d t(std::cos(alpha), std::sin(alpha));
  const Eigen::Vector2d n(std::sin(alpha), -std::cos(alpha));
  const auto at = [&](double u, double v) -> Eigen::Vector2d { return u * t + v * n; };
  const int half = static_cast<int>(std::lround(kHalfLength_m / kSpacing_m));         // 200
  const int groove = static_cast<int>(std::lround(kGrooveWidth_m / 2 / kSpacing_m));  // 20
  const int wall = static_cast<int>(std::lround(kGrooveDepth_m / kSpacing_m));        // 10
  std::vector<Eigen::Vector2d> unworn_points, worn_points;
  for (int i = -half; i <= half; ++i) unworn_points.push_back(at(i * kSpacing_m, 0.0));
  for (int i = -half; i <= -groove; ++i) worn_points.push_back(at(i * kSpacing_m, 0.0));
  for (int j = 1; j <= wall; ++j) worn_points.push_back(at(-groove * kSpacing_m, j * kSpacing_m));
  for (int i = -groove + 1; i <= groove; ++i)
    worn_points.push_back(at(i * kSpacing_m, kGrooveDepth_m));
  for (int j = wall - 1; j >= 0; --j)
    worn_points.push_back(at(groove * kSpacing_m, j * kSpacing_m));
  for (int i = groove + 1; i <= half; ++i) worn_points.push_back(at(i * kSpacing_m, 0.0));
  const Profile unworn(unworn_points, "1:20 tread");
  const Profile worn(worn_points, "1:20 tread with a groove");
  const int m = worn.size() - 1;  // 420 intervals: 400 along the tread, 2 x 10 down the walls

  // The trigger: the groove's corner and the foot of its left wall's deepest point coincide.
  const CurveLocator locator(unworn, /*material_toward_plus_z=*/false);
  const double corner_s = locator.Project(at(-groove * kSpacing_m, 0.0)).s;
  const double bottom_s = locator.Project(at(-groove * kSpacing_m, kGrooveDepth_m)).s;
  EXPECT_LE(std::abs(bottom_s - corner_s), Profile::kDuplicateDistance_m);

  const WearMeasures fallback = CompareWheelWithUnworn(unworn, worn);
  // It is the comparison with the unworn wheel at m uniform intervals (ResampleProfile rounds
  // length / spacing up, so a spacing of length / (m - 0.5) gives m intervals), bit for bit.
  const Profile resampled = ResampleProfile(unworn, unworn.Length() / (m - 0.5));
  ASSERT_EQ(resampled.size(), m + 1);
  const WearMeasures expected = CompareWheelProfiles(resampled, worn);
  EXPECT_EQ(fallback.worn_area_m2, expected.worn_area_m2);
  EXPECT_EQ(fallback.max_depth_m, expected.max_depth_m);
  EXPECT_EQ(fallback.depth_m.size(), expected.depth_m.size());

  // And it measures the groove: its depth across it, none on the tread beyond the splines'
  // reach, its area. The natural cubic spline through the worn points rounds the groove's four
  // corners, and the original's cells (0.1 mm) need not end at the walls: kCornerDepth_m bounds
  // the spline's bulge at a right-angle corner (measured: see the figure line), kCellArea_m2 the
  // midpoint rule's error at the two walls plus the bulges (a cell of the groove's depth each).
  constexpr double kCornerDepth_m = 0.1 * kSpacing_m;
  constexpr double kCellArea_m2 = 2.0 * kSpacing_m * kGrooveDepth_m;
  // Beyond 1 mm (10 knots) of a wall a natural spline's disturbance has decayed by 0.27^10.
  constexpr double kReach_m = 1e-3;
  double largest_outside = 0.0, smallest_inside = 1.0;
  int inside = 0;
  for (size_t i = 0; i < fallback.s_m.size(); ++i) {
    const double u = fallback.s_m[i] - 0.5 * unworn.Length();  // along the straight tread
    ASSERT_FALSE(std::isnan(fallback.depth_m[i])) << "u = " << u;
    if (std::abs(u) < kGrooveWidth_m / 2 - kReach_m) {
      smallest_inside = std::min(smallest_inside, fallback.depth_m[i]);
      EXPECT_NEAR(fallback.depth_m[i], kGrooveDepth_m, kCornerDepth_m) << "u = " << u;
      ++inside;
    } else if (std::abs(u) > kGrooveWidth_m / 2 + kReach_m) {
      largest_outside = std::max(largest_outside, std::abs(fallback.depth_m[i]));
    }
  }
  EXPECT_GT(inside, 10);
  EXPECT_LT(largest_outside, kNoWear_m);
  EXPECT_NEAR(fallback.max_depth_m, kGrooveDepth_m, kCornerDepth_m);
  EXPECT_LT(std::abs(fallback.max_depth_y_m - at(0.0, 0.0).x()), kGrooveWidth_m / 2);
  EXPECT_NEAR(fallback.worn_area_m2, kGrooveWidth_m * kGrooveDepth_m, kCellArea_m2);
  std::cerr << std::setprecision(9) << "[figure] groove 4 x 1 mm in a 1:20 tread, fallback: area "
            << fallback.worn_area_m2 * 1e6 << " mm^2 (4 exact), max depth "
            << fallback.max_depth_m * 1e3
            << " mm, depth in the groove's middle >= " << smallest_inside * 1e3
            << " mm, largest |depth| on the tread beyond 1 mm of it " << largest_outside << " m\n";
}

// A wheel worn only at its flange root reports its deepest point there and no depth where no
// contact is, whether it wore 0.1 mm (it sets the step) or about a nanometre (the rail sets the
// step: a trailing wheelset's wheel), at step 1 (against the given wheel) and step 2.
TEST(WheelWearTest, AWheelWornInTheMiddleReportsItsDepthThereAndNoneAtItsEnds) {
  for (const double distance_m : {200.0, 2e-3}) {
    SCOPED_TRACE(distance_m);
    const WearStudy study = MakeStudy(WearLawKind::kArchard, 2.4e9, distance_m);
    const WearState start = MakeInitialState(study);
    std::vector<StepResult> steps;
    RunWear(study, UnwornRails::Of(start), start, [&](const StepResult& s) {
      steps.push_back(s);
      return true;
    }, 2);
    ASSERT_EQ(steps.size(), 2u);
    for (const StepResult& step : steps) {
      const WheelStepResult& w = step.wheels.at(0);
      // Where this step wore the wheel: its bins with step depth, on the profile it started from.
      int first = -1, last = -1;
      for (int b = 0; b < w.grid.n; ++b) {
        if (w.step_depth_m[b] > 0.0) {
          if (first < 0) first = b;
          last = b;
        }
      }
      ASSERT_GE(first, 0);
      const double worn_from = first * w.grid.h_m, worn_to = (last + 1) * w.grid.h_m;
      const WearMeasures& m = w.measures;
      ASSERT_GT(m.max_depth_m, 0.0);
      EXPECT_GT(m.max_depth_s_m, worn_from);
      EXPECT_LT(m.max_depth_s_m, worn_to);
      // Off the worn band (beyond kBand of it: the spline's reach and step 2's arc-length shift)
      // nothing, and never at the profile's ends.
      double off_band = 0.0;
      for (size_t i = 0; i < m.s_m.size(); ++i) {
        if (m.s_m[i] < worn_from - kBand_m || m.s_m[i] > worn_to + kBand_m) {
          off_band = std::max(off_band, std::abs(m.depth_m[i]));
        }
      }
      std::cerr << "[figure] L " << distance_m << " m, step " << step.state.step << ": max depth "
                << m.max_depth_m << " m at y = " << m.max_depth_y_m * 1e3
                << " mm, worn band s " << worn_from * 1e3 << "-" << worn_to * 1e3
                << " mm, largest |depth| off it " << off_band << " m\n";
      // Step 1 moved only the worn band's points: nothing off it. Step 2 resampled a worn,
      // resampled profile, which moves the curve by the splines' representation error where its
      // samples shifted along it (measured: 9e-9 m at 0.18 mm of wear, 4e-12 at 1.3e-7 m): the
      // profile's own change, a rail's too, and far below its wear.
      if (step.state.step == 1) {
        EXPECT_LT(off_band, kNoWear_m);
      }
      EXPECT_LT(off_band, kResampling * m.max_depth_m);
    }
  }
}

// (A vehicle entry's wheels wear too since issue 16's vehicle co-evolution:
// tests/wear/vehicle_wheel_wear_test.cpp; a population stays refused there.)
TEST(WheelWearTest, WheelWearNeedsAHardnessAndAPositiveDistance) {
  WearStudy study = MakeStudy(WearLawKind::kArchard, 2.4e9);
  study.traffic[0].wheel_wear->hardness_Pa.reset();
  ExpectInputError([&] { MakeInitialState(study); },
                         {"S1002", "wheel_wear", "hardness", "archard"});
  study.wheel_material.hardness_Pa = 2.4e9;  // the study's wheel material gives it
  EXPECT_NO_THROW(MakeInitialState(study));
  study.traffic[0].wheel_wear->distance_per_pass_m = -1.0;
  ExpectInputError([&] { MakeInitialState(study); },
                         {"S1002", "wheel_wear.distance_per_pass_m = -1"});
  study.traffic[0].wheel_wear->distance_per_pass_m = 10.0;
  study.traffic[0].vehicle = 0;
  EXPECT_NO_THROW(ValidateTraffic(study.traffic));
  ExpectInputError([&] { ExpandWheelPopulation(study.traffic[0], {{"a", MakeS1002(), 0.46, 1.0}}); },
                   {"S1002", "population on a vehicle entry"});
}

// EN 13262 as quoted in wear/rail_grade.h: the rim's minimum hardness in HB times 9.80665 MPa.
TEST(WheelWearTest, WheelGradePresets) {
  EXPECT_DOUBLE_EQ(WheelGradeOf(WheelGrade::kR7).hardness_Pa, 235.0 * 9.80665e6);
  EXPECT_DOUBLE_EQ(WheelGradeOf(WheelGrade::kR8).hardness_Pa, 245.0 * 9.80665e6);
  EXPECT_DOUBLE_EQ(WheelGradeOf(WheelGrade::kR8).yield_strength_min_Pa, 540e6);
  EXPECT_NEAR(WheelGradeOf(WheelGrade::kR7).shear_yield_Pa, 520e6 / std::sqrt(3.0), 1e-3);
  EXPECT_EQ(WheelGradeFromString("R8"), WheelGrade::kR8);
  EXPECT_FALSE(WheelGradeFromString("ER9").has_value());
  // A rail grade is harder than either wheel grade: the wheel wears more per volume (Archard).
  EXPECT_GT(RailGradeOf(RailGrade::kR260).hardness_Pa, WheelGradeOf(WheelGrade::kR8).hardness_Pa);
}

// EN 15313 flange measures on the new S1002 (EN 13715's design values: flange height 28 mm,
// thickness 32.5 mm, qR 10.8 mm). Tolerance 0.05 mm: the quoted values are rounded to 0.1 mm
// (qR) and the profile is sampled every 0.1 mm of S.
TEST(WheelWearTest, FlangeMeasuresOfTheNewS1002) {
  const WheelFlangeMeasures m = MeasureWheelFlange(MakeS1002());
  EXPECT_NEAR(m.flange_height_m * 1e3, 28.0, 0.05);
  EXPECT_NEAR(m.flange_thickness_m * 1e3, 32.5, 0.05);
  EXPECT_NEAR(m.flange_slope_m * 1e3, 10.8, 0.05);
  std::cerr << "[figure] S1002: Sh " << m.flange_height_m * 1e3 << " Sd "
            << m.flange_thickness_m * 1e3 << " qR " << m.flange_slope_m * 1e3 << " mm\n";
  // Flange-root wear thins the flange: Sd falls, Sh stays (the tread is untouched).
  std::vector<Eigen::Vector2d> worn = MakeS1002().points();
  for (Eigen::Vector2d& p : worn) {
    if (p.x() > -0.045 && p.x() < -0.030) p.x() -= 0.5e-3 * std::sin((p.x() + 0.045) / 0.015 * std::numbers::pi);
  }
  const WheelFlangeMeasures w = MeasureWheelFlange(Profile(worn, "worn"));
  EXPECT_LT(w.flange_thickness_m, m.flange_thickness_m - 0.2e-3);
  EXPECT_NEAR(w.flange_height_m, m.flange_height_m, 1e-6);
}

// A population: one entry per wheel, shares share x weight / sum, total and MGT per pass kept.
TEST(WheelPopulationTest, EachWheelIsAnEntryWeightedByItsShare) {
  TrafficCase entry = MakeStudy(WearLawKind::kArchard, 2.4e9).traffic[0];
  entry.wheel_wear.reset();
  entry.name = "fleet";
  entry.share = 0.6;
  const std::vector<PopulationWheel> wheels = {{"new", MakeS1002(), 0.46, 3.0},
                                               {"worn", MakeS1002().Mirrored().Mirrored(), 0.44,
                                                1.0}};
  const std::vector<TrafficCase> expanded = ExpandWheelPopulation(entry, wheels);
  ASSERT_EQ(expanded.size(), 2u);
  EXPECT_EQ(expanded[0].name, "fleet / new");
  EXPECT_EQ(expanded[1].name, "fleet / worn");
  EXPECT_DOUBLE_EQ(expanded[0].share, 0.6 * 0.75);
  EXPECT_DOUBLE_EQ(expanded[1].share, 0.6 * 0.25);
  EXPECT_DOUBLE_EQ(expanded[1].rolling_radius_m, 0.44);
  EXPECT_DOUBLE_EQ(MgtPerPass(expanded), MgtPerPass({entry}));
  // Each wheel's load cases carry its share of the rail's passes.
  const std::vector<LoadCase> cases = ExpandTraffic(expanded, 1);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_DOUBLE_EQ(cases[0].weight, 0.75);
  EXPECT_DOUBLE_EQ(cases[1].weight, 0.25);
  EXPECT_DOUBLE_EQ(cases[1].placement.rolling_radius_m, 0.44);

  ExpectInputError([&] { ExpandWheelPopulation(entry, {}); }, {"fleet", "no wheels"});
  std::vector<PopulationWheel> bad = wheels;
  bad[1].weight = 0.0;
  ExpectInputError([&] { ExpandWheelPopulation(entry, bad); },
                         {"fleet", "wheel 1 ('worn')", "weight = 0", "> 0"});
  bad = wheels;
  bad[1].name = "new";
  ExpectInputError([&] { ExpandWheelPopulation(entry, bad); }, {"fleet", "unique names"});
  entry.vehicle = 0;
  ExpectInputError([&] { ExpandWheelPopulation(entry, wheels); },
                         {"fleet", "vehicle entry"});
}

}  // namespace
}  // namespace railwear
