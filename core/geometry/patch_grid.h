// PatchGrid: the (x, s) grid of one contact patch on its reference surface.
//
// The reference surface (tangent plane for the planar model, intermediate surface of seed eq. 1
// for the conformal model) is extruded along x, the rolling direction: its cross-section is the
// same at every x. Cells are dx by ds; s is the arc length along the cross-section. Because of
// the extrusion, influence coefficients depend on x_i - x_j only (Toeplitz in x), and for a
// planar cross-section on s_i - s_j as well.
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

}  // namespace railwear
