// The seed's eq. 4 constants in one place: the compliances k_d and k_f of one body and the
// tangential factor c_t. The normal kernel (influence_kernels.cpp), the normal-tangential coupling
// (coupling.cpp) and the calibration's point-load curves (calibration/displacement_curves.cpp)
// all take them from here, so that the three evaluate the same numbers in the same order.
//
//   k_d = 1 / (8 pi (1 - nu) G)        [1/Pa]   G = E / (2 (1 + nu)), the body's shear modulus
//   k_f = (3 - 4 nu) k_d               [1/Pa]
//   c_t = 1 + c_s sign                 [-]      sign +1 concave body, -1 convex (DESIGN.md §1)
//
// Eq. 4 on body b: w_z = (1/rho) [c_f k_f + c_z k_d dn^2/rho^2], w_t = c_t(b) k_d d_t/rho^2.
#pragma once

#include <numbers>

#include "core/contact/contact_types.h"

namespace railwear {

// k_d [1/Pa] of a body of material m (E > 0, 0 <= nu < 0.5; not checked here).
inline double SeedKernelKd(const Material& m) {
  return 1.0 / (8.0 * std::numbers::pi * (1.0 - m.poisson_ratio) * m.ShearModulus());
}

// k_f [1/Pa] = (3 - 4 nu) k_d, given that body's k_d [1/Pa] (SeedKernelKd).
inline double SeedKernelKf(const Material& m, double k_d) {
  return (3.0 - 4.0 * m.poisson_ratio) * k_d;
}

// c_t [-] = 1 + c_s sign of a body with constants `set` and curvature sign `sign` (+1 concave,
// -1 convex, 0 flat: BodyCurvatureSign).
inline double SeedKernelCt(const InfluenceConstantSet& set, int sign) {
  return 1.0 + set.c_s * sign;
}

}  // namespace railwear
