// The default wear study (examples/wear_high_rail.toml: S1002 freight and passenger traffic on
// the gauge corner of a UIC60 1:40 high rail) at draft accuracy with 3 nodes per entry, for the
// one-step tests of friction conditions and rail grades; and the worn area of its first step. Also
// the vehicle wear tests' set-up (VehicleCurveStudy).
#pragma once

#include "core/profile/builtin_profiles.h"
#include "wear/wear_simulation.h"

namespace railwear {

// The set-up the wear tests share: UIC60 at 1:40, conformal geometry with the Boussinesq kernel
// at draft accuracy; materials and traffic are each test's.
inline WearStudy DraftConformalStudyOnUic60() {
  WearStudy study;
  study.rail_profile = MakeUic60();
  study.cant_ratio = 0.025;
  study.model = MakeModelOptions(ModelKind::kConformal);
  study.model.kernel = KernelModel::kBoussinesq;
  study.model.kind = ModelKind::kCustom;
  study.model.accuracy = AccuracyPreset::kDraft;
  return study;
}

// The default study (examples/wear_high_rail.toml) at draft accuracy with 3 nodes per entry.
inline WearStudy DefaultStudy(WearLawKind law) {
  WearStudy study = DraftConformalStudyOnUic60();
  study.rail_material.hardness_Pa = 2.6e9;
  study.rail_material.shear_yield_Pa = 350e6;
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

// One vehicle entry (S1002 wheels, 16 t axles) on UIC60 1:40 rails (hardness 2.6 GPa) in a curve
// of `radius_m` without cant, auto model at draft accuracy, Archard k = 1e-4, one thread: the
// set-up of the vehicle wear tests (a single wheelset, or a bogie vehicle of four).
inline WearStudy VehicleCurveStudy(double radius_m, VehicleKind kind, double friction,
                                   double speed_m_s) {
  WearStudy study;
  study.rail_profile = MakeUic60();
  study.low_rail_profile = MakeUic60();
  study.cant_ratio = 0.025;
  study.rail_material.hardness_Pa = 2.6e9;
  study.model = MakeModelOptions(ModelKind::kAuto);
  study.model.accuracy = AccuracyPreset::kDraft;
  study.curve.radius_m = radius_m;
  VehicleSpec v;
  v.name = kind == VehicleKind::kBogie ? "wagon" : "wheelset";
  v.kind = kind;
  v.axle_load_N = 16e3 * kGravity_m_s2;
  v.wheel_profile = MakeS1002();
  study.vehicles = {v};
  TrafficCase c;
  c.vehicle = 0;
  c.wheel_profile = v.wheel_profile;
  c.axle_load_t = 16.0;
  c.vertical_force_N = 0.5 * v.axle_load_N;
  c.friction = friction;
  c.speed_m_s = speed_m_s;
  study.traffic = {c};
  study.options.law.archard_k = 1e-4;
  study.options.total_passes = 1e6;
  study.options.threads = 1;
  return study;
}

// Worn area per axle pass [m^2] of the high rail in the first step.
inline double WornAreaPerPass(const WearStudy& study) {
  const WearState start = MakeInitialState(study);
  const StepResult step = RunWearStep(study, UnwornRails::Of(start), start, 1e12);
  double area = 0.0;
  for (double d : step.depth_per_pass_m) area += d * step.grid.h_m;
  return area;
}

}  // namespace railwear
