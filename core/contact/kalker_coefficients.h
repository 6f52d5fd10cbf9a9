// Kalker's creep coefficients C11, C22, C23 (Kalker 1990, Table E.3; reference README §4) and
// the creep forces of Kalker's linear theory (vanishing creepage, full adhesion).
//
// Conventions (core/notation.md, core/contact/tangential_types.h): a is the semi-axis along the
// rolling direction x, b the lateral one, c = sqrt(a b). Forces are those the rail exerts on the
// wheel, so they oppose the creepage:
//   F_x = -G c^2 C11 xi,   F_y = -G c^2 C22 eta - G c^3 C23 phi.
#pragma once

namespace railwear {

// Dimensionless creep coefficients.
struct CreepCoefficients {
  double c11 = 0.0;
  double c22 = 0.0;
  double c23 = 0.0;
};

// Interpolates Kalker's table at the axis ratio a/b (a along x, b lateral) and Poisson's ratio
// nu (the combined nu of the two bodies).
//   a_over_b_along_x > 0, finite. Kalker's table covers a/b in [0.1, 10] (its second half is
//     tabulated against b/a = 0.9 ... 0.1). Beyond it (issue 16: flange patches reach a/b ~ 20
//     and below 0.1) the coefficients are EXTENDED, not clamped: rows down to min(a/b, b/a) =
//     0.02 computed with railwear's exact solver in linear theory, scaled to meet Kalker's end
//     rows (kalker_coefficients.cpp says how), ln C linear in ln(a/b) between them; below 0.02
//     C23 follows Kalker's asymptotic expression scaled to the last row, C11 and C22 the line
//     through the last two rows. Checked against Kalker's asymptotic
//     expressions for slender ellipses (C23 on both sides, C11 and C22 for a/b -> 0) in
//     kalker_coefficients_test.cpp.
//   nu in [0, 0.5]; throws std::invalid_argument otherwise (and for a/b <= 0 or non-finite).
// Interpolation inside the table: the abscissa u = a/b - 1 for a/b <= 1 and u = 1 - b/a for
// a/b > 1 puts the 19 table rows at equal steps of 0.1 in u in [-0.9, 0.9]; each column is
// interpolated by a monotone piecewise cubic (Fritsch-Carlson) in u, and the three nu columns by
// the quadratic through nu = 0, 0.25, 0.5 (all columns are smooth and convex in nu). Table nodes
// are exact.
CreepCoefficients KalkerCoefficients(double a_over_b_along_x, double nu);

struct LinearCreepForces {
  double force_x_N = 0.0;  // F_x on the wheel [N]
  double force_y_N = 0.0;  // F_y on the wheel [N] (lateral, along the patch's s tangent)
};

// Kalker's linear theory. a, b > 0 semi-axes along x and lateral [m]; G > 0 combined shear
// modulus [Pa]; nu in [0, 0.5]; xi, eta creepages [-]; phi spin creepage [1/m]. Throws
// std::invalid_argument on a bad a, b, G or nu. (The spin moment needs C32, C33, which the
// reference table does not carry; it is left out.)
LinearCreepForces CalcLinearCreepForces(double a_m, double b_m, double shear_modulus_Pa, double nu,
                                        double xi, double eta, double phi_per_m);

}  // namespace railwear
