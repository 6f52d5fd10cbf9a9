// Unit conversions between the SI values inside the code and the units of files, scenes and
// printed output (core/notation.md): one home for the factors, so that no file spells its own.
//
//   double y_m = y_mm * kMm;          // millimetres in, metres inside
//   double a_mm2 = area_m2 * kToMm2;  // metres inside, square millimetres out
#pragma once

namespace railwear {

inline constexpr double kMm = 1e-3;     // one millimetre in metres: mm -> m
inline constexpr double kToMm = 1e3;    // m -> mm
inline constexpr double kToMm2 = 1e6;   // m^2 -> mm^2
inline constexpr double kToMPa = 1e-6;  // Pa -> MPa
inline constexpr double kToMs = 1e3;    // s -> ms
// Standard gravity [m/s^2]: axle loads in tonnes to newtons, and the curve's accelerations.
inline constexpr double kGravity_m_s2 = 9.80665;

}  // namespace railwear
