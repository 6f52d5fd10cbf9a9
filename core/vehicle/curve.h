// A curve of the track for steady-state curving: radius, cant and the unbalanced lateral
// acceleration a vehicle feels in the track plane.
//
// Convention (core/notation.md, track frame T): the curve turns left, toward -Y; the right rail
// (+Y) is the outer, high rail. The cant (superelevation) raises the high rail by `cant_m` over
// the distance between the rail centres `cant_base_m`, so the track plane is rolled by
// phi = asin(cant / base). Working in the track plane, the vehicle's weight has the lateral part
// -g sin(phi) (toward the low rail) and the centripetal acceleration V^2/R has V^2/R cos(phi):
// the unbalanced lateral acceleration toward the high rail is
//     a_u = V^2/R cos(phi) - g sin(phi),
// and the cant deficiency is base * a_u / g (positive: the vehicle runs faster than the
// equilibrium speed).
#pragma once

#include "core/numerics/units.h"

namespace railwear {

struct CurveSpec {
  double radius_m = 0.0;     // > 0 for a curve; 0 means tangent track
  double cant_m = 0.0;       // superelevation of the high rail, >= 0
  double cant_base_m = 1.5;  // distance between the rail centres (standard gauge) [m]

  double curvature_per_m() const { return radius_m > 0.0 ? 1.0 / radius_m : 0.0; }
};

// a_u [m/s^2], positive toward the high rail (+Y), at speed V [m/s].
double UnbalancedLateralAcceleration(const CurveSpec& curve, double speed_m_s);

// Cant deficiency [m] at speed V: base * a_u / g (negative: cant excess).
double CantDeficiency(const CurveSpec& curve, double speed_m_s);

// The vertical acceleration normal to the track plane [m/s^2]: g cos(phi) + V^2/R sin(phi).
double TrackNormalAcceleration(const CurveSpec& curve, double speed_m_s);

// Throws InputError (key names as in a scene's [track]) for a negative radius or cant, a cant of
// the base or more, or non-finite values.
void ValidateCurve(const CurveSpec& curve);

}  // namespace railwear
