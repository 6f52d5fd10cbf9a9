// Tests of damage.h: WLRM damage function, FI_surf and the shakedown map against hand
// calculations on a Hertz patch.
#include "core/contact/damage.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace railwear {
namespace {

// Piecewise-linear formulas evaluated by hand: only round-off separates them.
constexpr double kExact = 1e-15;

TEST(Damage, TGammaIsEnergyPerMetre) {
  // |Fx xi| + |Fy eta|: 10 kN at 3e-3 plus 2 kN at -1e-3 = 30 + 2 = 32 J/m.
  EXPECT_NEAR(TGamma(-10e3, 2e3, 3e-3, -1e-3), 32.0, 1e-12);
  EXPECT_EQ(TGamma(0.0, 0.0, 1e-3, 1e-3), 0.0);
}

TEST(Damage, WlrmPeakThresholdAndWearRegion) {
  // "A T-gamma at the WLRM peak gives the peak damage per axle": 1e-5 at 65 J/m.
  EXPECT_NEAR(WlrmRcfDamage(65.0), 1e-5, kExact);
  EXPECT_EQ(WlrmRcfDamage(0.0), 0.0);
  EXPECT_EQ(WlrmRcfDamage(14.9), 0.0);
  EXPECT_EQ(WlrmRcfDamage(15.0), 0.0);
  EXPECT_EQ(WlrmRcfDamage(175.0), 0.0);
  EXPECT_EQ(WlrmRcfDamage(500.0), 0.0);
  // Halfway up the rise (40 J/m) and halfway down the fall (120 J/m): half the peak.
  EXPECT_NEAR(WlrmRcfDamage(40.0), 0.5e-5, kExact);
  EXPECT_NEAR(WlrmRcfDamage(120.0), 0.5e-5, kExact);
  try {
    WlrmRcfDamage(-1.0);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("T-gamma = -1"), std::string::npos) << e.what();
  }
}

// The README §4 Hertz patch: a = 8, b = 4 mm, Fn = 82 kN: p0 = 3 Fn/(2 pi a b) = 1223.5 MPa.
// Shear yield k = 350 MPa (a typical R260 value): p0/k = 3.4957.
constexpr double kA = 8e-3, kB = 4e-3, kFn = 82e3, kK = 350e6;

TEST(Damage, SurfaceFatigueIndexByHand) {
  const double p0 = HertzPeakPressure(kA, kB, kFn);
  EXPECT_NEAR(p0, 3.0 * kFn / (2.0 * std::numbers::pi * kA * kB), 1e-6);
  EXPECT_NEAR(p0, 1223.5e6, 0.05e6);
  // FI_surf = mu - k/p0 = 0.3 - 350/1223.5 = 0.3 - 0.28606 = 0.01394.
  const double fi = SurfaceFatigueIndex(0.3, p0, kK);
  EXPECT_NEAR(fi, 0.3 - kK / p0, 1e-14);
  EXPECT_NEAR(fi, 0.01394, 1e-5);
  EXPECT_THROW(SurfaceFatigueIndex(0.3, 0.0, kK), std::invalid_argument);
  EXPECT_THROW(HertzPeakPressure(kA, kB, 0.0), std::invalid_argument);
}

// Issue 16: FI_surf and the shakedown point read the patch's own peak pressure. A patch whose
// peak is 1.5x the Hertz p0 of its ellipse (a conformal or non-elliptic patch) is judged at that
// peak: FI_surf = mu - k/p_max, not mu - k/p0.
TEST(Damage, PatchDamageReadsThePatchsOwnPeak) {
  const double p0 = HertzPeakPressure(kA, kB, kFn);
  PatchDamageInput in;
  in.force_x_N = 0.25 * kFn;  // mu_eff = 0.25: surface shakedown limit 1/0.25 = 4
  in.normal_force_N = kFn;
  in.xi = 1e-3;
  in.shear_yield_Pa = kK;
  in.peak_pressure_Pa = 1.5 * p0;
  const PatchDamage d = CalcPatchDamage(in);
  EXPECT_NEAR(d.fi_surf, 0.25 - kK / (1.5 * p0), 1e-14);
  EXPECT_GT(d.fi_surf, 0.0);  // at the Hertz p0 it would be 0.25 - 0.286 < 0
  EXPECT_LT(SurfaceFatigueIndex(0.25, p0, kK), 0.0);
  EXPECT_NEAR(d.shakedown.load_factor, 1.5 * p0 / kK, 1e-12);
  EXPECT_EQ(d.shakedown.regime, ShakedownRegime::kRatchetting);  // 5.24 > 4
  EXPECT_EQ(CalcShakedownPoint(p0, kK, 0.25).regime, ShakedownRegime::kElasticShakedown);
  in.peak_pressure_Pa = 0.0;
  EXPECT_THROW(CalcPatchDamage(in), std::invalid_argument);
}

TEST(Damage, ShakedownMapRegions) {
  const double p0 = 3.0 * kFn / (2.0 * std::numbers::pi * kA * kB);  // p0/k = 3.4957
  // mu = 0.3: surface limit 1/0.3 = 3.333 < 4.7 binds; p0/k beyond it -> ratchetting, and
  // FI_surf > 0 agrees.
  const ShakedownPoint r = CalcShakedownPoint(p0, kK, 0.3);
  EXPECT_NEAR(r.load_factor, 3.4957, 1e-4);
  EXPECT_NEAR(r.shakedown_limit, 1.0 / 0.3, kExact);
  EXPECT_NEAR(r.margin, 1.0 / 0.3 - p0 / kK, 1e-12);
  EXPECT_LT(r.margin, 0.0);
  EXPECT_EQ(r.regime, ShakedownRegime::kRatchetting);
  EXPECT_EQ(ToString(r.regime), "ratchetting");
  // mu = 0.1: limits 3.2 (elastic) and 4.7 (shakedown); 3.4957 lies between.
  const ShakedownPoint e = CalcShakedownPoint(p0, kK, 0.1);
  EXPECT_EQ(e.regime, ShakedownRegime::kElasticShakedown);
  EXPECT_NEAR(e.margin, 4.7 - p0 / kK, 1e-12);
  // A softer rail (k = 200 MPa, p0/k = 6.12) at mu = 0.1: beyond the subsurface limit.
  EXPECT_EQ(CalcShakedownPoint(p0, 200e6, 0.1).regime, ShakedownRegime::kPlasticShakedown);
  // A light load (p0/k = 2) stays elastic.
  EXPECT_EQ(CalcShakedownPoint(2.0 * kK, kK, 0.2).regime, ShakedownRegime::kElastic);
}

TEST(Damage, PatchDamageCombinesIndices) {
  PatchDamageInput in;
  in.force_x_N = -6e3;
  in.force_y_N = 8e3;  // |F_t| = 10 kN, mu_eff = 10/82
  in.normal_force_N = kFn;
  in.xi = 5e-3;
  in.eta = -1e-3;  // T-gamma = 30 + 8 = 38 J/m
  in.spin_moment_Nm = -40.0;
  in.spin_per_m = 0.3;  // |M_z phi| = 12 J/m: spin's share 12 / (38 + 12) = 0.24
  in.peak_pressure_Pa = HertzPeakPressure(kA, kB, kFn);  // a Hertzian patch: p_max = p0
  in.shear_yield_Pa = kK;
  const PatchDamage d = CalcPatchDamage(in);
  EXPECT_NEAR(d.t_gamma_N, 38.0, 1e-12);
  EXPECT_NEAR(d.spin_work_N, 12.0, 1e-12);
  EXPECT_NEAR(d.spin_share, 0.24, 1e-15);
  EXPECT_NEAR(d.wlrm_damage, 1e-5 * (38.0 - 15.0) / 50.0, kExact);
  EXPECT_NEAR(d.traction_coefficient, 10.0 / 82.0, 1e-15);
  EXPECT_LT(d.fi_surf, 0.0);
  EXPECT_EQ(d.shakedown.regime, ShakedownRegime::kElasticShakedown);
}

}  // namespace
}  // namespace railwear
