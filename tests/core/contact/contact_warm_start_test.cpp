#include "core/contact/contact_warm_start.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_case.h"
#include "core/contact/contact_forces.h"
#include "core/contact/hertz_tread.h"
#include "core/contact/influence_constant_sets.h"
#include "core/contact/normal_tangential_stage.h"
#include "core/contact/placement_cache.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/contact/same_result.h"

namespace railwear {
namespace {

// The C API benchmark's wheel (tests/api/rolling_wheel.h): S1002 on UIC60 at 1:40, conformal,
// standard, FASTSIM, mu 0.3, 100 kN at 20 m/s, the FEM-calibrated influence constants (the C
// API's default), at a lateral shift.
ContactCase GaugeCorner(double lateral_m, double load_N = 100e3) {
  ContactCase c;
  ContactProblem& p = c.problem;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.load.vertical_force_N = load_N;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.accuracy = AccuracyPreset::kStandard;
  p.model.constants = NamedInfluenceConstants(InfluenceConstantsName::kFem);
  p.placement.lateral_shift_m = lateral_m;
  RollingOptions r;
  r.friction = 0.3;
  r.motion.speed_m_s = 20.0;
  p.rolling = r;
  return c;
}

ContactResult Solve(const ContactCase& c, PlacementCache* cache, ContactWarmStart* warm) {
  return SolveContactCase(c, cache, nullptr, warm).wheel;
}

using testing::ExpectSameResult;

// Each patch's area, p_max, cells and contact y of a warm and a cold result, for a failure.
std::string Describe(const ContactResult& warm, const ContactResult& cold) {
  std::string out;
  for (const ContactResult* r : {&warm, &cold}) {
    out += r == &warm ? "\n  warm:" : "\n  cold:";
    for (const PatchResult& p : r->patches) {
      out += " " + std::to_string(p.area_m2 * 1e6) + " mm2, " + std::to_string(p.p_max_Pa / 1e6) +
             " MPa, " + std::to_string(p.grid.nx) + " x " + std::to_string(p.grid.ns) + " cells (" +
             std::to_string(p.cells_in_contact) + " in contact);";
    }
  }
  return out;
}

TEST(ContactWarmStart, FirstCallIsTheColdCallBitForBit) {
  const ContactCase c = GaugeCorner(-5.6e-3);
  PlacementCache cache;
  ContactWarmStart warm;
  ExpectSameResult(Solve(c, &cache, &warm), SolveContactCase(c).wheel);
  EXPECT_EQ(warm.cold_calls(), 1);
  EXPECT_EQ(warm.warm_calls(), 0);
  EXPECT_FALSE(warm.empty());
}

// Largest differences of a warm call from the cold call at the same position that this test
// accepts: the standard preset's own discretization error on this wheel, measured against the
// reference preset at 17 positions -3 .. -7 mm (docs/library.md, "Where a gauge-corner call's
// time goes": largest errors 7.3 % of the area, 3.1 % of p_max, 1.2 and 2.4 % of the load in
// F_x and F_y). Both calls carry that error; a warm call places its cells from another
// measurement of the patch, so the two may differ by up to about the error itself.
constexpr double kAreaTolerance = 0.073;
constexpr double kPeakTolerance = 0.062;  // twice p_max's 3.1 %: it depends on where cells fall
constexpr double kFxTolerance = 0.012;    // of the load
constexpr double kFyTolerance = 0.024;    // of the load

TEST(ContactWarmStart, NearbyPositionsStartWarmWithinTheDiscretizationError) {
  // A time loop's lateral positions, steps of 0.05 to 0.25 mm.
  const double steps_mm[] = {0.05, 0.10, 0.15, 0.20, 0.25, 0.05, 0.10, 0.15};
  const double load_N = 100e3;
  PlacementCache cache;
  ContactWarmStart warm;
  double y_mm = -5.0;
  Solve(GaugeCorner(y_mm * 1e-3), &cache, &warm);  // cold: the sequence's start
  for (const double step : steps_mm) {
    y_mm -= step;
    const ContactCase c = GaugeCorner(y_mm * 1e-3);
    const ContactResult w = Solve(c, &cache, &warm);
    const ContactResult cold = SolveContactCase(c).wheel;
    ASSERT_EQ(w.status, SolverStatus::kConverged) << y_mm << " mm: " << w.message;
    ASSERT_EQ(w.patches.size(), cold.patches.size()) << y_mm << " mm";
    double area_w = 0, area_c = 0, peak_w = 0, peak_c = 0;
    for (size_t k = 0; k < w.patches.size(); ++k) {
      area_w += w.patches[k].area_m2;
      area_c += cold.patches[k].area_m2;
      peak_w = std::max(peak_w, w.patches[k].p_max_Pa);
      peak_c = std::max(peak_c, cold.patches[k].p_max_Pa);
    }
    const Eigen::Vector3d fw = TotalForcesOnRail(w).Net(), fc = TotalForcesOnRail(cold).Net();
    EXPECT_NEAR(area_w / area_c, 1.0, kAreaTolerance) << y_mm << " mm";
    EXPECT_NEAR(peak_w / peak_c, 1.0, kPeakTolerance) << y_mm << " mm" << Describe(w, cold);
    EXPECT_NEAR(fw.x(), fc.x(), kFxTolerance * load_N) << y_mm << " mm";
    EXPECT_NEAR(fw.y(), fc.y(), kFyTolerance * load_N) << y_mm << " mm";
    // The vertical balance holds to its own tolerance, warm or cold.
    EXPECT_LE(w.balance_residual, internal::kBalanceTolerance) << y_mm << " mm";
  }
  // Most of the steps started warm (the rest fell back, solved cold).
  EXPECT_GE(warm.warm_calls(), 6);
  EXPECT_EQ(warm.cold_calls(), 1 + warm.fallbacks());
}

TEST(ContactWarmStart, AJumpFallsBackToTheColdCallBitForBit) {
  // From the gauge corner to the tread (another candidate, another patch), and a load twice the
  // last (pressure at the edge of the last patch): each solved cold, as without a warm start.
  PlacementCache cache;
  ContactWarmStart warm;
  Solve(GaugeCorner(-5.6e-3), &cache, &warm);
  const ContactCase jump = GaugeCorner(-10.4e-3);
  ExpectSameResult(Solve(jump, &cache, &warm), SolveContactCase(jump).wheel);
  EXPECT_EQ(warm.fallbacks(), 1);
  const ContactCase heavier = GaugeCorner(-10.4e-3, 200e3);
  ExpectSameResult(Solve(heavier, &cache, &warm), SolveContactCase(heavier).wheel);
  EXPECT_EQ(warm.fallbacks(), 2);
  EXPECT_EQ(warm.warm_calls(), 0);
  EXPECT_EQ(warm.cold_calls(), 3);
}

TEST(ContactWarmStart, APlanarPatchsPlaneFollowsTheContact) {
  // The half-space model's planar grid on the tread (-10.4 mm, 5 mrad, draft): its tangent plane
  // is re-centred on the solved pressure centre (potential_area.h); a warm call starts from the
  // last call's plane and the review checks it again, so over steps of 0.05 mm the pressure
  // centre stays within a cell of the cold call's and the contact angle with it.
  PlacementCache cache;
  ContactWarmStart warm;
  auto tread = [](double lateral_m) {
    ContactCase c = GaugeCorner(lateral_m);
    c.problem.model = MakeModelOptions(ModelKind::kHalfspace);
    c.problem.model.accuracy = AccuracyPreset::kDraft;
    c.problem.placement.yaw_rad = 5e-3;
    return c;
  };
  for (int k = 0; k < 6; ++k) {
    const ContactCase c = tread(-10.4e-3 + 0.05e-3 * k);
    const ContactResult w = Solve(c, &cache, &warm);
    const ContactResult cold = SolveContactCase(c).wheel;
    ASSERT_EQ(w.patches.size(), 1u) << k;
    ASSERT_EQ(cold.patches.size(), 1u) << k;
    const PatchResult& pw = w.patches[0];
    const PatchResult& pc = cold.patches[0];
    // Each pressure centre within half a cell of its own plane's point: one cell apart at most.
    EXPECT_NEAR(pw.contact_point_yz_m.x(), pc.contact_point_yz_m.x(), pc.grid.ds_m) << k;
    // The rail's profile turns by at most a cell over its smallest radius on the tread (80 mm).
    EXPECT_NEAR(pw.contact_angle_rad, pc.contact_angle_rad, pc.grid.ds_m / 0.08) << k;
  }
  EXPECT_GE(warm.warm_calls(), 1);
}

TEST(ContactWarmStart, ClearedItIsColdAgain) {
  PlacementCache cache;
  ContactWarmStart warm;
  Solve(GaugeCorner(-5.6e-3), &cache, &warm);
  warm.Clear();
  EXPECT_TRUE(warm.empty());
  const ContactCase next = GaugeCorner(-5.65e-3);
  ExpectSameResult(Solve(next, &cache, &warm), SolveContactCase(next).wheel);
  EXPECT_EQ(warm.cold_calls(), 2);
  EXPECT_EQ(warm.fallbacks(), 0);
}

}  // namespace
}  // namespace railwear
