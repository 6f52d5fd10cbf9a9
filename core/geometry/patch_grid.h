// PatchGrid: the (x, s) grid of one contact patch on its reference surface.
//
// The reference surface (tangent plane for the planar model, intermediate surface of seed eq. 1
// for the conformal model) is extruded along x, the rolling direction: its cross-section is the
// same at every x. Cells are dx by ds; s is the arc length along the cross-section. Because of
// the extrusion, influence coefficients depend on x_i - x_j only (Toeplitz in x), and for a
// planar cross-section on s_i - s_j as well. So they do on a uniform arc (IsUniformArc below):
// the distance and the relative orientation of two points of a circle depend only on their
// separation in arc length.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace railwear {

struct PatchGrid {
  int nx = 0;           // cells along x (rolling direction)
  int ns = 0;           // cells along s (lateral arc of the cross-section)
  double dx_m = 0.0;    // cell length along x [m]
  double ds_m = 0.0;    // cell length along s [m]
  double x0_m = 0.0;    // x of the centres of cells (0, j) [m]
  double s0_m = 0.0;    // s of the centres of cells (i, 0) [m]
  bool planar = false;  // the cross-section is a straight line (all normals equal)

  // Per s index j (size ns), in the rail frame (y lateral toward the field side, z downward):
  std::vector<Eigen::Vector2d> point_yz_m;  // cell-centre point on the reference surface [m]
  std::vector<Eigen::Vector2d> tangent_yz;  // unit tangent along increasing s
  std::vector<Eigen::Vector2d> normal_yz;   // unit normal pointing out of the rail, into the wheel

  // Per cell k = Index(i, j) (size nx*ns): initial separation d [m], positive open, negative
  // overlap (seed eq. 2 for the conformal model; along the plane normal for the planar model).
  Eigen::VectorXd gap_m;

  int cells() const { return nx * ns; }
  int Index(int i, int j) const { return j * nx + i; }
  double CellArea() const { return dx_m * ds_m; }
  double X(int i) const { return x0_m + i * dx_m; }
  // x of the centre column: the contact point's (grids are centred on it in x; 0 without yaw).
  double XCentre() const { return x0_m + 0.5 * (nx - 1) * dx_m; }
  double S(int j) const { return s0_m + j * ds_m; }
  // Cell-centre point in 3-D (x, y, z) [m].
  Eigen::Vector3d Point(int i, int j) const { return {X(i), point_yz_m[j].x(), point_yz_m[j].y()}; }
};

// Tolerance of IsUniformArc: positions relative to ds_m, unit vectors absolute. About 100 units
// in the last place of coordinates of 3 cm over cells of 10 um (what an arc computed as
// centre + R (sin, -cos) carries), and far below anything visible in a coefficient: a
// cross-section within it gives the influence coefficients of the exact arc to ~1e-10 relative.
inline constexpr double kUniformArcTolerance = 1e-10;

// True when the grid's cross-section is a circular arc of constant curvature kappa (a straight
// line when kappa = 0) sampled every ds_m in arc length, with the arc's own tangents and a
// normal perpendicular to them: for every j, with phi_j = kappa j ds_m and R(phi) the rotation
// by phi,
//   point_yz_m[j] = point_yz_m[0] + R-integral of the arc  (within kUniformArcTolerance * ds_m),
//   tangent_yz[j] = R(phi_j) tangent_yz[0],  normal_yz[j] = R(phi_j) normal_yz[0]  (within
//   kUniformArcTolerance), tangent_yz[0] and normal_yz[0] unit and perpendicular.
// kappa is taken from the end tangents, so arcs turning by pi or more are not recognised.
// Such a grid is symmetric under a shift along s (a rotation about the centre) and under the
// reflection s -> -s about any cell, so its influence coefficients depend on |i_s - j_s|.
// Grids of one row are uniform arcs. O(ns). Only geometry built as an arc passes: the patch
// builder's reference curves are polylines of samples of the intermediate curve (tangents
// constant per sample interval), and the intermediate curve of two arcs of different radii is no
// arc (docs/speed.md, "Constant-curvature arcs").
bool IsUniformArc(const PatchGrid& grid, double tolerance = kUniformArcTolerance);

}  // namespace railwear
