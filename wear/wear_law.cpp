#include "wear/wear_law.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {

std::string_view ToString(WearLawKind v) { return EnumToString(kWearLawKindNames, v); }

std::optional<WearLawKind> WearLawKindFromString(std::string_view s) {
  return EnumFromString(kWearLawKindNames, s);
}

namespace {

void RequirePositive(const char* name, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("wear law: {} = {}: expected a finite number > 0", name, value));
  }
}

// C1 step: 0 below -1, 1 above 1, 0.5 + 0.75 t - 0.25 t^3 between.
double SmoothStep(double t) {
  if (t <= -1.0) return 0.0;
  if (t >= 1.0) return 1.0;
  return 0.5 + 0.75 * t - 0.25 * t * t * t;
}

double KthPublished(const WearLaw& law, double p_over_h, double v) {
  if (p_over_h > law.kth_pressure_ratio) return law.kth_k_seizure;
  if (v < law.kth_v1_m_s) return law.kth_k_mild_low;
  if (v < law.kth_v2_m_s) return law.kth_k_severe;
  return law.kth_k_mild_high;
}

double KthContinuous(const WearLaw& law, double p_over_h, double v) {
  // log k blended across each boundary; v = 0 lies deep in region B.
  const double lv = std::log(std::max(v, 1e-300));
  const double w = law.kth_velocity_band;
  double log_k = std::log(law.kth_k_mild_low);
  log_k += (std::log(law.kth_k_severe) - std::log(law.kth_k_mild_low)) *
           SmoothStep((lv - std::log(law.kth_v1_m_s)) / w);
  log_k += (std::log(law.kth_k_mild_high) - std::log(law.kth_k_severe)) *
           SmoothStep((lv - std::log(law.kth_v2_m_s)) / w);
  const double seizure = SmoothStep((p_over_h - law.kth_pressure_ratio) / law.kth_pressure_band);
  log_k += (std::log(law.kth_k_seizure) - log_k) * seizure;
  return std::exp(log_k);
}

}  // namespace

void ValidateWearLaw(const WearLaw& law) {
  RequirePositive("k", law.archard_k);
  RequirePositive("kth_k_seizure", law.kth_k_seizure);
  RequirePositive("kth_k_mild_low", law.kth_k_mild_low);
  RequirePositive("kth_k_severe", law.kth_k_severe);
  RequirePositive("kth_k_mild_high", law.kth_k_mild_high);
  RequirePositive("kth_v1_m_s", law.kth_v1_m_s);
  RequirePositive("kth_v2_m_s", law.kth_v2_m_s);
  RequirePositive("kth_pressure_ratio", law.kth_pressure_ratio);
  RequirePositive("kth_velocity_band", law.kth_velocity_band);
  RequirePositive("kth_pressure_band", law.kth_pressure_band);
  RequirePositive("density_kg_m3", law.density_kg_m3);
  if (!(law.kth_v1_m_s < law.kth_v2_m_s)) {
    throw InputError(fmt::format("wear law: kth_v1_m_s = {} and kth_v2_m_s = {}: expected v1 < v2",
                                 law.kth_v1_m_s, law.kth_v2_m_s));
  }
}

double WearCoefficient(const WearLaw& law, double pressure_Pa, double slip_speed_m_s,
                       double hardness_Pa) {
  switch (law.kind) {
    case WearLawKind::kArchard:
      return law.archard_k;
    case WearLawKind::kKth:
      return KthPublished(law, pressure_Pa / hardness_Pa, slip_speed_m_s);
    case WearLawKind::kKthContinuous:
      return KthContinuous(law, pressure_Pa / hardness_Pa, slip_speed_m_s);
    case WearLawKind::kUsfd:
      break;
  }
  throw std::logic_error("WearCoefficient: the USFD law has no Archard coefficient");
}

double UsfdWearRate(double x) { return std::max(std::min(5.3 * x, 55.0), 61.9 * x - 4778.7); }

double WearDepthPerRolledMetre(const WearLaw& law, const WearCellState& cell, double hardness_Pa,
                               double speed_m_s) {
  if (!(cell.pressure_Pa > 0.0) || !(cell.slip_speed_m_s > 0.0)) return 0.0;
  if (law.kind == WearLawKind::kUsfd) {
    const double t_gamma_per_area_N_mm2 = cell.frictional_power_Pa_m_s / speed_m_s * 1e-6;
    // W [ug/(m mm^2)] = W * 1e-9 kg / (m * 1e-6 m^2) = W * 1e-3 kg/(m m^2).
    return UsfdWearRate(t_gamma_per_area_N_mm2) * 1e-3 / law.density_kg_m3;
  }
  const double k = WearCoefficient(law, cell.pressure_Pa, cell.slip_speed_m_s, hardness_Pa);
  return k * cell.pressure_Pa * cell.slip_speed_m_s / (hardness_Pa * speed_m_s);
}

}  // namespace railwear
