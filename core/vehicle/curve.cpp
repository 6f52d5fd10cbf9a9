// Unbalanced acceleration of a curve (see curve.h).
#include "core/vehicle/curve.h"

#include <cmath>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {

namespace {
double CantAngle(const CurveSpec& curve) { return std::asin(curve.cant_m / curve.cant_base_m); }
}  // namespace

double UnbalancedLateralAcceleration(const CurveSpec& curve, double speed_m_s) {
  const double phi = CantAngle(curve);
  return speed_m_s * speed_m_s * curve.curvature_per_m() * std::cos(phi) -
         kGravity_m_s2 * std::sin(phi);
}

double CantDeficiency(const CurveSpec& curve, double speed_m_s) {
  return curve.cant_base_m * UnbalancedLateralAcceleration(curve, speed_m_s) / kGravity_m_s2;
}

double TrackNormalAcceleration(const CurveSpec& curve, double speed_m_s) {
  const double phi = CantAngle(curve);
  return kGravity_m_s2 * std::cos(phi) +
         speed_m_s * speed_m_s * curve.curvature_per_m() * std::sin(phi);
}

void ValidateCurve(const CurveSpec& curve) {
  if (!(curve.radius_m >= 0.0) || !std::isfinite(curve.radius_m)) {
    throw InputError(fmt::format(
        "track.radius_m = {}: expected a finite radius > 0 (leave it out for tangent track)",
        curve.radius_m));
  }
  if (curve.radius_m > 0.0 && curve.radius_m < 50.0) {
    throw InputError(fmt::format(
        "track.radius_m = {}: expected at least 50 m (the tightest curves of tramways; the "
        "steady-curving model assumes the wheelbase is small against the radius)",
        curve.radius_m));
  }
  if (!(curve.cant_base_m > 0.0) || !std::isfinite(curve.cant_base_m)) {
    throw InputError(
        fmt::format("track.cant_base_mm = {}: expected a distance > 0", curve.cant_base_m * 1e3));
  }
  if (!(curve.cant_m >= 0.0) || !(curve.cant_m < 0.25 * curve.cant_base_m)) {
    throw InputError(fmt::format(
        "track.cant_mm = {}: expected 0 to {} mm (a quarter of the rail-centre distance; "
        "main lines allow at most about 180 mm)",
        curve.cant_m * 1e3, 0.25 * curve.cant_base_m * 1e3));
  }
}

}  // namespace railwear
