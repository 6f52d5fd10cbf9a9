// Normal contact solver: pressures p >= 0 with complementarity against the deformed gap, for a
// prescribed load or a prescribed approach. Several patches share one rigid approach.
//
// Unknowns p_k >= 0 (cell pressures, Pa) and delta (rigid approach along the load direction e_F,
// m). Deformed gap g = d - delta * w + C p, with w_k = e_F . (-n_k) the share of the approach
// that closes cell k's normal gap. Conditions: g >= 0, p >= 0, p_k g_k = 0, and either
//   sum_k p_k A_k w_k = F   (prescribed load; A_k cell area)   or   delta = delta0 (prescribed).
// Method: projected conjugate gradients of Polonsky & Keer (1999) type, with the approach as the
// multiplier of the load condition. Numerical outcomes (no contact, no convergence) are reported
// in the status, never thrown.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/contact/influence_operator.h"

namespace railwear {

enum class SolverStatus { kConverged, kNotConverged, kNoContact };
std::string_view ToString(SolverStatus s);

struct NormalSolverOptions {
  // Stop when the complementarity residual max_k |g_k| over the contact set and the relative
  // load error are below tolerance (|g| relative to the largest |d| over the contact set).
  double tolerance = 1e-10;
  int max_iterations = 2000;
  // Returns "" when valid, otherwise what is wrong.
  std::string Validate() const;
};

struct NormalProblem {
  // One operator per patch; cells of patch b occupy the consecutive range [offset_b,
  // offset_b + blocks[b]->size()) of the vectors below. Patches do not interact elastically.
  std::vector<const InfluenceOperator*> blocks;
  Eigen::VectorXd gap_m;          // d, initial separation per cell [m]
  Eigen::VectorXd approach_weight;  // w, per cell, in (0, 1]
  Eigen::VectorXd cell_area_m2;   // A, per cell [m^2]
  std::optional<double> force_N;     // prescribed load F (> 0) ...
  std::optional<double> approach_m;  // ... or prescribed approach delta
};

struct NormalSolution {
  SolverStatus status = SolverStatus::kNotConverged;
  std::string message;
  Eigen::VectorXd pressure_Pa;  // per cell
  Eigen::VectorXd deformed_gap_m;  // g per cell
  double approach_m = 0.0;
  int iterations = 0;
  double complementarity_residual_m = 0.0;  // max over cells of |min(p, g)|-type measure, m
  double load_error_relative = 0.0;
};

NormalSolution SolveNormal(const NormalProblem& problem, const NormalSolverOptions& options = {});

}  // namespace railwear
