// Friction conditions: names, defaults, the factor per wear law and the checks.
#include "wear/friction_condition.h"

#include <cmath>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {

std::string_view ToString(FrictionCondition v) { return EnumToString(kFrictionConditionNames, v); }

std::optional<FrictionCondition> FrictionConditionFromString(std::string_view s) {
  return EnumFromString(kFrictionConditionNames, s);
}

FrictionConditionParams DefaultFrictionConditionParams(FrictionCondition condition) {
  switch (condition) {
    case FrictionCondition::kDry:
      return {0.40, 1.0, 1.0, 1.0};
    case FrictionCondition::kWet:
      return {0.25, 0.2, 0.2, 0.2};
    case FrictionCondition::kLubricated:
      return {0.10, 0.1, 0.1, 0.1};
    case FrictionCondition::kFrictionModified:
      return {0.35, 0.5, 0.5, 0.5};
  }
  return {};
}

double WearFactor(const FrictionConditionParams& params, WearLawKind law) {
  switch (law) {
    case WearLawKind::kArchard:
      return params.archard_factor;
    case WearLawKind::kKth:
    case WearLawKind::kKthContinuous:
      return params.kth_factor;
    case WearLawKind::kUsfd:
      return params.usfd_factor;
  }
  return 1.0;
}

namespace {

void RequireIn(FrictionCondition c, const char* key, double value, double lo, double hi) {
  if (!(value > lo && value <= hi) || !std::isfinite(value)) {
    throw InputError(
        fmt::format("friction condition \"{}\": {} = {}: expected a number in ({}, {}]",
                    ToString(c), key, value, lo, hi));
  }
}

}  // namespace

void ValidateFrictionConditions(const FrictionConditions& conditions) {
  for (const auto& entry : kFrictionConditionNames) {
    const FrictionConditionParams& p = conditions[entry.value];
    RequireIn(entry.value, "friction", p.friction, 0.0, 2.0);
    RequireIn(entry.value, "archard_factor", p.archard_factor, 0.0, 10.0);
    RequireIn(entry.value, "kth_factor", p.kth_factor, 0.0, 10.0);
    RequireIn(entry.value, "usfd_factor", p.usfd_factor, 0.0, 10.0);
  }
  const double g = conditions.gauge_face_angle_rad;
  if (!(g > 0.0 && g < 0.5 * 3.14159265358979323846)) {
    throw InputError(fmt::format(
        "friction conditions: gauge-face angle = {} rad: expected an angle in (0, 90) degrees", g));
  }
}

}  // namespace railwear
