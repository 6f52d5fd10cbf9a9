// Rolling contact on a patch grid: inputs and results of the tangential solvers.
//
// The rigid slip of every cell is given (it varies cell by cell on a curved gauge-corner patch;
// core/contact/kinematics.h computes it from the wheelset's motion), as creepage: rigid slip
// velocity of the wheel relative to the rail at the cell, divided by the rolling speed V,
// resolved along the cell's tangents: x (rolling direction) and s (the lateral arc of the patch
// cross-section, PatchGrid::tangent_yz). For a constant creepage (xi, eta, phi) on a planar
// patch this is Kalker's  w_x = xi - phi * s,  w_s = eta + phi * x.
//
// Tractions are those the rail exerts on the wheel (Kalker's convention: body 1 = wheel), so
// in full slip q = -mu p w/|w| and the creep force opposes the creepage: F_x = -G c^2 C11 xi in
// linear theory. The wheel rolls toward +x: material enters the patch at its leading edge
// (largest x) and leaves at the trailing edge.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/contact/normal_solver.h"

namespace railwear {

struct RollingInput {
  Eigen::VectorXd creep_x;  // per cell [-], size grid.cells()
  Eigen::VectorXd creep_s;  // per cell [-]
  double speed_m_s = 1.0;   // rolling speed V > 0
  double friction = 0.3;    // Coulomb coefficient mu > 0
};

struct TangentialSolution {
  SolverStatus status = SolverStatus::kNotConverged;
  std::string message;
  int iterations = 0;
  Eigen::VectorXd traction_x_Pa, traction_s_Pa;  // per cell, on the wheel
  Eigen::VectorXd slip_x_m_s, slip_s_m_s;        // local slip velocity per cell (0 in stick)
  Eigen::VectorXi stick;                         // 1 stick, 0 slip, -1 outside the contact
  double force_x_N = 0.0;                        // sum of q_x dA
  double force_s_N = 0.0;                        // sum of q_s dA (along each cell's s tangent)
  // The tangential force as a vector in the rail frame's (y, z) plane: sum of q_s dA t_j; on a
  // planar patch it is force_s_N along the one tangent.
  Eigen::Vector2d force_s_yz_N = Eigen::Vector2d::Zero();
  // Sum of ((x - x_c) q_s - s q_x) dA about the patch origin: the contact point, at s = 0 and
  // the grid's centre column x_c (PatchGrid::XCentre; ahead of the axle for a yawed wheel).
  double spin_moment_Nm = 0.0;
  double stick_area_m2 = 0.0;
  double slip_area_m2 = 0.0;
  double frictional_power_W = 0.0;  // sum of |q . v_slip| dA
};

// A solution with zero traction and slip on `cells` cells, all marked outside the contact (-1):
// where the solvers start.
inline TangentialSolution EmptyTangentialSolution(int cells) {
  TangentialSolution sol;
  sol.traction_x_Pa = Eigen::VectorXd::Zero(cells);
  sol.traction_s_Pa = Eigen::VectorXd::Zero(cells);
  sol.slip_x_m_s = Eigen::VectorXd::Zero(cells);
  sol.slip_s_m_s = Eigen::VectorXd::Zero(cells);
  sol.stick = Eigen::VectorXi::Constant(cells, -1);
  return sol;
}

}  // namespace railwear
