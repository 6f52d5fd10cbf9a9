// Internal building blocks of the influence operators (influence_operator.h): the per-cell kernel
// shared by the dense reference and the FFT operators, so that both evaluate exactly the same
// function of the same inputs. Not part of the public interface.
#pragma once

#include "core/contact/influence_operator.h"

namespace railwear::internal {

// The cell kernel of either model is a C_ij = a * I_invR + b * I_n2R3 with the rectangle
// integrals of influence_operator.h; a [1/Pa] and b [1/Pa] sum both bodies:
//   boussinesq: a = sum_b (1 - nu_b) / (2 pi G_b),  b = 0
//   golubenko:  a = sum_b c_f(b) k_f,b,             b = sum_b c_z(b) k_d,b
// (c_f(b), c_z(b) of body b's set: InfluenceConstants::ForBody with the settings' curvature
// signs; one set for both bodies unless the constants are separate).
struct KernelCoefficients {
  double inv_r = 0.0;  // a [1/Pa]
  double n2_r3 = 0.0;  // b [1/Pa]
};
KernelCoefficients MakeKernelCoefficients(const InfluenceSettings& settings);

// Beyond this centre distance, in cell diagonals sqrt(hx^2 + hs^2), a cell is integrated by the
// midpoint rule with its second- and fourth-order Taylor terms (RectangleIntegralsFarField)
// instead of the closed forms. Its relative error there is below 1e-6 for 1/R, 2.5e-5 for
// n^2/R^3 (under 1 % of the seed kernel) and 1.5e-6 for the seed kernel's combination
// (influence_operator_test.cpp, FarFieldRule*): no more than the second-order rule's at the
// 8.5 diagonals used until 2026-11-30 (2e-6, 3e-5, 2.4e-6), while the disc of closed forms around
// a cell shrinks by (3.5/8.5)^2 in area (docs/library.md, "The cell integrals' far-field rule").
// The closed forms lose digits to cancellation at large distances, so the rule
// is also the more accurate one far away. A half-integer value keeps lattice distances of uniform
// grids away from the switch, so translated copies of a cell pair never fall on different sides of
// it.
inline constexpr double kFarFieldDiagonals = 3.5;

// Both rectangle integrals at once (they share the atan term); arguments as in
// RectangleIntegralInvR. Closed forms near, corrected midpoint rule beyond kFarFieldDiagonals.
void RectangleIntegrals(double x, double s, double n, double hx, double hs, double* inv_r,
                        double* n2_r3);
// The closed forms alone, at any distance (for tests of the far-field rule).
void RectangleIntegralsClosedForm(double x, double s, double n, double hx, double hs, double* inv_r,
                                  double* n2_r3);
// The corrected midpoint rule alone, at any distance (for tests of the far-field rule).
void RectangleIntegralsFarField(double x, double s, double n, double hx, double hs, double* inv_r,
                                double* n2_r3);

// C_ij [m/Pa] for field cell (field_ix, field_is) and source cell (source_ix, source_is).
// The x offset is (field_ix - source_ix) * dx_m (the exact value of (P_i - P_j) . e_x on the
// extruded grid), the s and n offsets come from point_yz_m, tangent_yz and normal_yz at the
// source's s index.
double CellInfluence(const PatchGrid& grid, const KernelCoefficients& coefficients, int field_ix,
                     int field_is, int source_ix, int source_is);

// CellInfluence(grid, coefficients, d, field_is, 0, source_is) for every x offset d = 0 .. nx - 1
// into out[d] (out holds grid.nx values), bit for bit: the row of x offsets the FFT operators
// need per pair of s indices. A near cell's closed forms take four corner terms, and the upper x
// corner of offset d, d dx + dx / 2, is the lower one of offset d + 1, (d + 1) dx - dx / 2, when
// both round to the same double (about half the offsets): the row computes such a corner once,
// the same function of the same arguments, and sums the terms in RectangleIntegralsClosedForm's
// order (influence_operator_test.cpp, CellInfluenceRow.*).
void CellInfluenceRow(const PatchGrid& grid, const KernelCoefficients& coefficients, int field_is,
                      int source_is, double* out);

// Aborts unless the grid is well formed (sizes, positive cell lengths).
void CheckGrid(const PatchGrid& grid);

}  // namespace railwear::internal
