// Curving problems shared by the curving tests and benchmarks: flangeless cones of a given
// conicity on UIC60 rails inclined 1:40, as a single wheelset or a bogie vehicle, without cant
// deficiency.
#pragma once

#include <vector>

#include "core/profile/builtin_profiles.h"
#include "core/vehicle/curving.h"

namespace railwear::test {

inline constexpr double kR0 = 0.46;
inline constexpr double kHalfSpan = 0.75;  // wheel origin (taping line) from the wheelset centre

// A flangeless cone of conicity lambda: r = r0 - lambda y (flange side at negative y).
inline Profile MakeCone(double lambda) {
  std::vector<Eigen::Vector2d> points;
  for (int k = -60; k <= 70; ++k) points.emplace_back(k * 1e-3, -lambda * k * 1e-3);
  return Profile(points, "cone");
}

inline CurvingProblem BaseProblem(const Profile& wheel, double radius_m) {
  CurvingProblem p;
  p.contact.model = CurvingOptions::PredictorModel();
  p.contact.tangential = TangentialMethod::kFastsim;
  p.high_rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.low_rail = p.high_rail;
  p.curve.radius_m = radius_m;
  p.vehicle.name = "test";
  p.vehicle.kind = VehicleKind::kWheelset;
  p.vehicle.axle_load_N = 100e3;
  p.vehicle.wheel_profile = wheel;
  p.vehicle.rolling_radius_m = kR0;
  p.vehicle.cg_height_m = 0.0;
  p.speed_m_s = 20.0;
  p.friction = 0.3;
  return p;
}

// A bogie vehicle of cone wheelsets with stiff or soft primary suspension, no cant deficiency.
inline CurvingProblem ConeBogie(double lambda, double radius, double primary_kx) {
  CurvingProblem p = BaseProblem(MakeCone(lambda), radius);
  p.vehicle.kind = VehicleKind::kBogie;
  p.vehicle.wheelbase_m = 2.5;
  p.vehicle.bogie_spacing_m = 19.0;
  p.vehicle.primary_kx_N_m = primary_kx;
  p.vehicle.primary_ky_N_m = 1e10;
  p.vehicle.primary_semi_spacing_m = 1.0;
  p.vehicle.secondary_ky_N_m = 1e5;
  p.vehicle.secondary_yaw_Nm_rad = 1.0;  // no yaw restraint from the car body
  p.friction = 1.0;  // creepages of 4e-4 stay in the linear range of the creep curves
  p.speed_m_s = 10.0;
  p.curve.cant_m = p.curve.cant_base_m * p.speed_m_s * p.speed_m_s / radius / kGravity_m_s2;
  return p;
}

}  // namespace railwear::test
