// Damage indices of a contact patch; see damage.h for the laws and their sources.
#include "core/contact/damage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace railwear {
namespace {

void RequirePositive(double v, const char* name) {
  if (!std::isfinite(v) || v <= 0.0) {
    throw std::invalid_argument(std::string(name) + " = " + std::to_string(v) +
                                ", expected finite > 0");
  }
}

}  // namespace

double TGamma(double force_x_N, double force_y_N, double xi, double eta) {
  return std::abs(force_x_N * xi) + std::abs(force_y_N * eta);
}

double SpinWork(double spin_moment_Nm, double spin_per_m) {
  return std::abs(spin_moment_Nm * spin_per_m);
}

double WlrmRcfDamage(double t_gamma_N) {
  if (!std::isfinite(t_gamma_N) || t_gamma_N < 0.0) {
    throw std::invalid_argument("WlrmRcfDamage: T-gamma = " + std::to_string(t_gamma_N) +
                                " N, expected finite >= 0");
  }
  if (t_gamma_N <= kWlrmThreshold_N || t_gamma_N >= kWlrmWearOnly_N) return 0.0;
  if (t_gamma_N <= kWlrmPeak_N) {
    return kWlrmPeakDamage * (t_gamma_N - kWlrmThreshold_N) / (kWlrmPeak_N - kWlrmThreshold_N);
  }
  return kWlrmPeakDamage * (kWlrmWearOnly_N - t_gamma_N) / (kWlrmWearOnly_N - kWlrmPeak_N);
}

double SurfaceFatigueIndex(double traction_coefficient, double peak_pressure_Pa,
                           double shear_yield_Pa) {
  RequirePositive(peak_pressure_Pa, "SurfaceFatigueIndex: peak_pressure_Pa");
  RequirePositive(shear_yield_Pa, "SurfaceFatigueIndex: shear_yield_Pa");
  return traction_coefficient - shear_yield_Pa / peak_pressure_Pa;
}

double HertzPeakPressure(double semi_axis_x_m, double semi_axis_y_m, double normal_force_N) {
  RequirePositive(semi_axis_x_m, "HertzPeakPressure: semi_axis_x_m");
  RequirePositive(semi_axis_y_m, "HertzPeakPressure: semi_axis_y_m");
  RequirePositive(normal_force_N, "HertzPeakPressure: normal_force_N");
  return 3.0 * normal_force_N / (2.0 * std::numbers::pi * semi_axis_x_m * semi_axis_y_m);
}

std::string_view ToString(ShakedownRegime v) {
  switch (v) {
    case ShakedownRegime::kElastic:
      return "elastic";
    case ShakedownRegime::kElasticShakedown:
      return "elastic shakedown";
    case ShakedownRegime::kPlasticShakedown:
      return "plastic shakedown";
    case ShakedownRegime::kRatchetting:
      return "ratchetting";
  }
  return "unknown";
}

ShakedownPoint CalcShakedownPoint(double p0_Pa, double shear_yield_Pa,
                                  double traction_coefficient) {
  RequirePositive(p0_Pa, "CalcShakedownPoint: p0_Pa");
  RequirePositive(shear_yield_Pa, "CalcShakedownPoint: shear_yield_Pa");
  if (!std::isfinite(traction_coefficient) || traction_coefficient < 0.0) {
    throw std::invalid_argument("CalcShakedownPoint: traction coefficient = " +
                                std::to_string(traction_coefficient) + ", expected finite >= 0");
  }
  ShakedownPoint s;
  s.load_factor = p0_Pa / shear_yield_Pa;
  s.traction_coefficient = traction_coefficient;
  const double surface = traction_coefficient > 0.0 ? 1.0 / traction_coefficient
                                                    : std::numeric_limits<double>::infinity();
  s.elastic_limit = std::min(kElasticLimitPointContact, surface);
  s.shakedown_limit = std::min(kShakedownLimitPointContact, surface);
  s.margin = s.shakedown_limit - s.load_factor;
  if (s.load_factor <= s.elastic_limit) {
    s.regime = ShakedownRegime::kElastic;
  } else if (s.load_factor <= s.shakedown_limit) {
    s.regime = ShakedownRegime::kElasticShakedown;
  } else if (surface <= kShakedownLimitPointContact) {
    s.regime = ShakedownRegime::kRatchetting;
  } else {
    s.regime = ShakedownRegime::kPlasticShakedown;
  }
  return s;
}

PatchDamage CalcPatchDamage(const PatchDamageInput& in) {
  RequirePositive(in.normal_force_N, "CalcPatchDamage: normal_force_N");
  RequirePositive(in.peak_pressure_Pa, "CalcPatchDamage: peak_pressure_Pa");
  PatchDamage d;
  d.t_gamma_N = TGamma(in.force_x_N, in.force_y_N, in.xi, in.eta);
  d.wlrm_damage = WlrmRcfDamage(d.t_gamma_N);
  d.spin_work_N = SpinWork(in.spin_moment_Nm, in.spin_per_m);
  const double work = d.t_gamma_N + d.spin_work_N;
  d.spin_share = work > 0.0 ? d.spin_work_N / work : 0.0;
  d.traction_coefficient = std::hypot(in.force_x_N, in.force_y_N) / in.normal_force_N;
  d.fi_surf = SurfaceFatigueIndex(d.traction_coefficient, in.peak_pressure_Pa, in.shear_yield_Pa);
  d.shakedown = CalcShakedownPoint(in.peak_pressure_Pa, in.shear_yield_Pa, d.traction_coefficient);
  return d;
}

}  // namespace railwear
