// The spin-dominated flange case of issue 16 (tests/core/contact/tangential_method_test.cpp,
// tests/benchmarks/tangential_bench.cpp, examples/rolling_flange.toml): the S1002 flange on UIC60
// 1:40 with the wheel at -3 mm (flange contact at 69 degrees, a patch of about 44 x 2.5 mm,
// a/b 18), 80 kN, mu 0.35, 20 m/s, yaw -5 mrad, pure rolling at the nominal radius; conformal
// geometry with the Boussinesq kernel (the wear study's model) at standard.
#pragma once

#include "core/contact/contact_problem.h"
#include "core/profile/builtin_profiles.h"

namespace railwear::testing {

inline ContactProblem SpinDominatedFlangeProblem(TangentialMethod method) {
  ContactProblem p;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.placement.lateral_shift_m = -3e-3;
  p.placement.rolling_radius_m = 0.46;
  p.placement.yaw_rad = -5e-3;
  p.load.vertical_force_N = 80e3;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.kind = ModelKind::kCustom;
  p.model.kernel = KernelModel::kBoussinesq;
  p.model.accuracy = AccuracyPreset::kStandard;
  RollingOptions r;
  r.friction = 0.35;
  r.motion.speed_m_s = 20.0;
  p.rolling = r;
  p.tangential = method;
  return p;
}

}  // namespace railwear::testing
