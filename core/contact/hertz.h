// Hertz's analytic elliptical contact. Gap near the first contact point h = A x^2 + B y^2
// (A, B principal relative curvatures / 2, 1/m), contact modulus E* (Pa), normal force P (N).
// Formulas in ../shared/reference/README.md §1 (exact): a >= b semi-axes with
// e^2 = 1 - (b/a)^2, B/A = [(a/b)^2 E(e) - K(e)] / [K(e) - E(e)] along the smaller curvature,
// c^3 = 3 P E(e) / (2 pi E* (A + B) sqrt(g)), g = b/a, p0 = 3P/(2 pi a b),
// delta = p0 b K(e) / E*.
#pragma once

namespace railwear {

struct HertzSolution {
  double semi_axis_x_m = 0.0;  // semi-axis along x (the direction of curvature A)
  double semi_axis_y_m = 0.0;  // semi-axis along y (the direction of curvature B)
  double p0_Pa = 0.0;          // peak pressure
  double approach_m = 0.0;     // mutual approach delta
  double area_m2 = 0.0;        // pi a b
  double force_N = 0.0;
};

// A, B > 0 [1/m], E* > 0 [Pa], P >= 0 [N] (P = 0 gives a zero patch). Throws
// std::invalid_argument on A or B <= 0 (or E* <= 0, P < 0, non-finite input), and
// std::runtime_error if the axis ratio cannot be found (curvature ratio beyond ~1e12).
// Any ratio B/A is accepted: the major axis lies along the smaller curvature.
HertzSolution SolveHertz(double A_per_m, double B_per_m, double contact_modulus_Pa, double force_N);
// The same for a prescribed approach delta >= 0.
HertzSolution SolveHertzForApproach(double A_per_m, double B_per_m, double contact_modulus_Pa,
                                    double approach_m);

// The part of the Hertz solution that depends on the curvatures alone: the axis ratio g (a
// bracketed root of the elliptic-integral equation) and K(e), E(e). Callers that solve the same
// A and B for many forces or approaches (the bisection of the common approach over a wheel's
// candidates, SolveHertzForApproach's unit-force scaling) build it once: Solve and
// SolveForApproach then run exactly the arithmetic of SolveHertz and SolveHertzForApproach on the
// same values, so their results are bit for bit the same (issue 18, set-up reuse; hertz_test.cpp).
class HertzShape {
 public:
  // Throws as SolveHertz does for A or B.
  HertzShape(double A_per_m, double B_per_m);
  // = SolveHertz(A, B, contact_modulus_Pa, force_N), bit for bit (and the same exceptions).
  HertzSolution Solve(double contact_modulus_Pa, double force_N) const;
  // = SolveHertzForApproach(A, B, contact_modulus_Pa, approach_m), bit for bit.
  HertzSolution SolveForApproach(double contact_modulus_Pa, double approach_m) const;

 private:
  double A_per_m_, B_per_m_;
  double g_ = 1.0;           // axis ratio b/a
  double k_ = 0.0, e_ = 0.0;  // K(m), E(m), m = 1 - g^2
};

// 2-D line contact (exact): a = sqrt(4 P' R / (pi E*)), p0 = 2 P' / (pi a), 1/R = 1/R1 + 1/R2.
struct LineContactSolution {
  double half_width_m = 0.0;
  double p0_Pa = 0.0;
};
// P' >= 0 force per unit length [N/m], R > 0 [m], E* > 0 [Pa]; throws std::invalid_argument
// otherwise.
LineContactSolution SolveLineContact(double force_per_length_N_m, double relative_radius_m,
                                     double contact_modulus_Pa);

namespace internal {
// Complete elliptic integrals of the first and second kind as functions of the PARAMETER
// m = e^2 in [0, 1) (GSL takes the modulus e = sqrt(m)). Throw std::runtime_error on failure.
double CompleteEllipticK(double m);
double CompleteEllipticE(double m);
// Axis ratio g = b/a in (0, 1] of the Hertz ellipse for a curvature ratio
// r = (larger curvature)/(smaller curvature) >= 1 (reference README §1).
double HertzAxisRatio(double curvature_ratio);
}  // namespace internal

}  // namespace railwear
