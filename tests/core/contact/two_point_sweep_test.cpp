// Hard case of issue 6: S1002 on UIC60 1:40 swept laterally from -6 to -2 mm at 100 kN. The
// contact runs from the tread (-22 mm on the rail) over two-point contact with the gauge corner
// (tread and gauge-corner patches that appear, merge into one grid and change their first
// contact point) up the flange (70 degrees): the lateral force must be continuous across the
// sweep, i.e. free of jumps beyond a stated bound.
//
// A jump is told from a steep but continuous change by refinement: every 0.1 mm step whose
// change, or change of slope, exceeds 1 % of the load is re-sampled in 5 sub-steps; a continuous
// curve spreads its change over them, a jump puts it into one. The jump estimate is the largest
// sub-step change less the median one (the local trend); where that exceeds the bound (a steep
// stretch whose slope grows within the step, or a jump), the largest sub-step is re-sampled in
// 5 again (4 um) and the estimate taken there, where the slope no longer changes. Bound: the
// preset's tolerance on the load (draft: 5 % of 100 kN): a re-grid or a new grid frame when the
// first contact point moves changes the discretisation by up to that; a larger jump means a
// patch lost or invented. Measured at draft: 1.7 % (auto) and 2.8 % (seed model), both near
// -3.7 mm where the flange takes over (--gtest_filter=TwoPoint* prints them).
//
// Known and reported, not hidden by the bound: patches on separate grids do not interact
// elastically (normal_solver.h), while one grid holding both regions does; where the seed's
// kernel keeps the tread and gauge-corner patches apart until -5.55 mm and then merges them, the
// lateral force drops by about 1 % of the load (0.1 mm either side: 15.6 kN, 14.9 kN at
// reference). With the Boussinesq kernel the two regions share one grid throughout this sweep.
//
// Not swept: the half-space model (Model A) is discontinuous here by construction. Its patch
// lies in the tangent plane of the first contact point, which jumps from the gauge corner (33
// degrees) to the flange (70 degrees) between -3.95 and -3.9 mm; the lateral force jumps from
// 65 kN to 275 kN with it (draft), where the conformal geometry passes through 44 and 62
// degrees. That is the seed paper's case against Model A at the gauge corner, and why auto
// puts conformal geometry there.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/contact/contact_solver.h"
#include "core/contact/model_selection.h"
#include "core/profile/builtin_profiles.h"

namespace railwear {
namespace {

constexpr double kLoad_N = 100e3;
constexpr double kStep_mm = 0.1;
constexpr int kSubSteps = 5;            // 0.02 mm, then 4 um
constexpr double kFlagFraction = 0.01;  // of the load: steps worth refining
// The load balance the normal solver guarantees (1e-10 relative) with room for the patch sum.
constexpr double kLoadTolerance = 1e-8;

struct SweepOutcome {
  double worst_jump_N = 0.0;
  double worst_at_mm = 0.0;
  int solves = 0;
};

SweepOutcome Sweep(ModelOptions model) {
  static const Profile wheel = MakeS1002();
  static const Profile rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  ContactProblem p;
  p.wheel_profile = wheel;
  p.rail_profile = rail;
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = kLoad_N;
  p.model = model;
  SweepOutcome out;
  auto lateral = [&](double shift_mm) {
    p.placement.lateral_shift_m = shift_mm * 1e-3;
    const ContactResult r = SolveContact(p);
    ++out.solves;
    EXPECT_EQ(r.status, SolverStatus::kConverged) << shift_mm << " mm: " << r.message;
    EXPECT_NEAR(r.vertical_force_N, kLoad_N, kLoadTolerance * kLoad_N) << shift_mm << " mm";
    return r.lateral_force_N;
  };
  const int steps = static_cast<int>(std::lround(4.0 / kStep_mm));
  std::vector<double> fy(steps + 1);
  for (int k = 0; k <= steps; ++k) fy[k] = lateral(-6.0 + k * kStep_mm);
  const double flag = kFlagFraction * kLoad_N;
  const double bound = PresetTolerance(model.accuracy) * kLoad_N;
  // Largest sub-step change less the median one over [a, a + h] in kSubSteps sub-steps, from
  // the values at its ends; *widest the start of the largest sub-step.
  auto jump_in = [&](double a, double h, double fa, double fb, double* widest) {
    std::vector<double> sub;
    double last = fa;
    for (int m = 1; m <= kSubSteps; ++m) {
      const double v = m == kSubSteps ? fb : lateral(a + m * h / kSubSteps);
      sub.push_back(std::abs(v - last));
      last = v;
    }
    const int top = static_cast<int>(std::max_element(sub.begin(), sub.end()) - sub.begin());
    *widest = a + top * h / kSubSteps;
    std::vector<double> sorted = sub;
    std::sort(sorted.begin(), sorted.end());
    return sorted.back() - sorted[kSubSteps / 2];
  };
  for (int k = 1; k <= steps; ++k) {
    const double d = fy[k] - fy[k - 1];
    const double before = k > 1 ? fy[k - 1] - fy[k - 2] : d;
    const double after = k < steps ? fy[k + 1] - fy[k] : d;
    if (std::abs(d) <= flag && std::abs(d - before) <= flag && std::abs(after - d) <= flag) {
      continue;
    }
    const double a = -6.0 + (k - 1) * kStep_mm;
    double widest = a;
    double jump = jump_in(a, kStep_mm, fy[k - 1], fy[k], &widest);
    if (jump > bound) {
      const double h = kStep_mm / kSubSteps;
      jump = jump_in(widest, h, lateral(widest), lateral(widest + h), &widest);
    }
    if (jump > out.worst_jump_N) {
      out.worst_jump_N = jump;
      out.worst_at_mm = a;
    }
  }
  return out;
}

void ExpectContinuous(const ModelOptions& model, const std::string& name) {
  const SweepOutcome o = Sweep(model);
  const double bound = PresetTolerance(model.accuracy) * kLoad_N;
  std::printf(
      "[ measured ] %s %s: largest jump of the lateral force %.0f N (%.2f %% of the load) "
      "in the step from %.2f mm; %d solves\n",
      name.c_str(), std::string(ToString(model.accuracy)).c_str(), o.worst_jump_N,
      100.0 * o.worst_jump_N / kLoad_N, o.worst_at_mm, o.solves);
  EXPECT_LE(o.worst_jump_N, bound) << name << " from " << o.worst_at_mm << " mm";
}

TEST(TwoPointSweep, LateralForceIsContinuousWithTheAutoModel) {
  ModelOptions m = MakeModelOptions(ModelKind::kAuto);
  m.accuracy = AccuracyPreset::kDraft;
  ExpectContinuous(m, "auto");
}

TEST(TwoPointSweep, LateralForceIsContinuousWithTheSeedModel) {
  ModelOptions m = MakeModelOptions(ModelKind::kConformal);
  m.accuracy = AccuracyPreset::kDraft;
  ExpectContinuous(m, "conformal+golubenko");
}

}  // namespace
}  // namespace railwear
