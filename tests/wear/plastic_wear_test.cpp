// The wear maps on a pressure-limited contact (issue 16 point 2): with p_lim = H (the rail's
// hardness) no cell is above H, the KTH map's seizure region (p > 0.8 H) holds exactly the cells
// whose limited pressure passes 0.8 H, and the per-pass depth is computed from the limited
// pressure that the contact solution reports.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/contact/contact_solver.h"
#include "core/profile/builtin_profiles.h"
#include "wear/pass_depth.h"
#include "wear/wear_law.h"

namespace railwear {
namespace {

constexpr double kV = 20.0;  // rolling speed [m/s]
// A soft rail (hardness 1.2 GPa) under the 100 kN gauge-corner case of pass_depth_test.cpp,
// whose elastic peak is about 1.5 times that: the limit binds over a core of the patch.
constexpr double kSoftRailHardness_Pa = 1.2e9;

ContactProblem GaugeCornerProblem(bool limited) {
  ContactProblem p;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = {210e9, 0.28};
  p.rail_material = {210e9, 0.28};
  p.rail_material.hardness_Pa = kSoftRailHardness_Pa;
  p.placement.lateral_shift_m = -4e-3;
  p.placement.rolling_radius_m = 0.46;
  p.placement.yaw_rad = 5e-3;
  p.load.vertical_force_N = 100e3;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.accuracy = AccuracyPreset::kStandard;
  if (limited) p.pressure_limit.kind = PressureLimitKind::kHardness;
  RollingOptions ro;
  ro.friction = 0.3;
  ro.motion.speed_m_s = kV;
  p.rolling = ro;
  return p;
}

TEST(PlasticWear, KthSeizureOnlyWhereTheLimitedPressurePassesPointEightH) {
  const ContactResult elastic = SolveContact(GaugeCornerProblem(false));
  const ContactResult limited = SolveContact(GaugeCornerProblem(true));
  ASSERT_EQ(elastic.status, SolverStatus::kConverged) << elastic.message;
  ASSERT_EQ(limited.status, SolverStatus::kConverged) << limited.message;
  const double h = kSoftRailHardness_Pa;
  ASSERT_GT(elastic.p_max_Pa, 1.2 * h);  // the case is overloaded when elastic
  ASSERT_TRUE(limited.pressure_limit_Pa.has_value());
  EXPECT_EQ(*limited.pressure_limit_Pa, h);
  EXPECT_LE(limited.p_max_Pa, h);
  EXPECT_GT(limited.plastic_cells, 0);
  EXPECT_GT(limited.plastic_area_m2, 0.0);
  EXPECT_GT(limited.area_m2, elastic.area_m2);  // the patch grew to carry the load

  WearLaw kth;
  kth.kind = WearLawKind::kKth;
  int seizure = 0, below = 0, elastic_seizure = 0, elastic_above_h = 0;
  for (const PatchResult& patch : limited.patches) {
    for (int k = 0; k < patch.pressure_Pa.size(); ++k) {
      const double p = patch.pressure_Pa[k];
      if (!(p > 0.0)) continue;
      ASSERT_LE(p, h);  // no cell above p_lim = H
      const bool is_seizure = WearCoefficient(kth, p, 0.1, h) == kth.kth_k_seizure;
      EXPECT_EQ(is_seizure, p > kth.kth_pressure_ratio * h) << "cell " << k << " p " << p;
      (is_seizure ? seizure : below) += 1;
    }
  }
  for (const PatchResult& patch : elastic.patches) {
    for (int k = 0; k < patch.pressure_Pa.size(); ++k) {
      const double p = patch.pressure_Pa[k];
      elastic_seizure += p > kth.kth_pressure_ratio * h;
      elastic_above_h += p > h;
    }
  }
  EXPECT_GT(seizure, 0);          // the cells between 0.8 H and H are seizure ...
  EXPECT_GT(below, 0);            // ... the rest not
  EXPECT_GT(elastic_above_h, 0);  // elastic, the impossible pressures above H exist
  double normal_N = 0.0;
  for (const PatchResult& q : limited.patches) normal_N += q.normal_force_N;
  std::printf(
      "[ measured ] 100 kN gauge corner, H = %.0f MPa: elastic p_max %.0f MPa, %d cells above "
      "0.8 H (%d above H), area %.1f mm2; limited p_max %.0f MPa, %d seizure cells, %d plastic "
      "(%.1f %% of the load), area %.1f mm2\n",
      h * 1e-6, elastic.p_max_Pa * 1e-6, elastic_seizure, elastic_above_h, elastic.area_m2 * 1e6,
      limited.p_max_Pa * 1e-6, seizure, limited.plastic_cells,
      100.0 * limited.plastic_force_N / normal_N, limited.area_m2 * 1e6);
}

TEST(PlasticWear, PassDepthReadsTheLimitedPressure) {
  // The per-pass depth is the sum over each column of the law at the patch's own (limited)
  // pressure: recomputed here cell by cell from the reported fields, and no cell enters it with
  // a pressure above the limit.
  const ContactResult limited = SolveContact(GaugeCornerProblem(true));
  ASSERT_EQ(limited.status, SolverStatus::kConverged) << limited.message;
  WearLaw kth;
  kth.kind = WearLawKind::kKth;
  const double h = kSoftRailHardness_Pa;
  for (const PatchResult& patch : limited.patches) {
    const std::vector<double> dz = CalcColumnPassDepth(patch, kth, h, kV);
    const TangentialSolution& t = patch.rolling->tangential;
    for (int j = 0; j < patch.grid.ns; ++j) {
      double sum = 0.0;
      for (int i = 0; i < patch.grid.nx; ++i) {
        const int k = patch.grid.Index(i, j);
        const double p = patch.pressure_Pa[k];
        if (!(p > 0.0)) continue;
        ASSERT_LE(p, h);
        const double v = std::hypot(t.slip_x_m_s[k], t.slip_s_m_s[k]);
        if (!(v > 0.0)) continue;
        sum += WearCoefficient(kth, p, v, h) * p * v / (h * kV);
      }
      EXPECT_NEAR(dz[j], sum * patch.grid.dx_m, 1e-12 * std::max(dz[j], 1e-30)) << "column " << j;
    }
  }
}

}  // namespace
}  // namespace railwear
