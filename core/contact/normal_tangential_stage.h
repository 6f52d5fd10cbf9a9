// The normal-tangential stage of SolveContact: one loop that repeats the normal and rolling
// stages for two effects, alone or together:
//   coupling  the tangential tractions add CouplingDisplacement (coupling.h, seed eq. 4 cross
//             terms) to each patch's gap, until the pressure settles;
//   balance   with a prescribed vertical load Q, the net vertical force on the rail, pressure
//             V_p and creep forces V_c (contact_forces.h), must equal Q: the normal problem's
//             target for the pressure alone is set to T with T + V_c(T) = Q (balance_target.h:
//             secant steps, then regula falsi; a step of V_c is recognised), until
//             |V_p + V_c - Q| <= kBalanceTolerance Q (dV_c/dV_p is about mu tan(gamma) in full
//             slip, where V_c is linear in T and one secant step ends it).
// With both, the balance runs alone first (so that the coupling's reported area and peak changes
// are against the balanced uncoupled solution), then the one loop iterates both; the secant
// steps go on in that loop. With a prescribed approach only coupling iterates. Internal to
// SolveContact.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/normal_solver.h"
#include "core/contact/rolling_stage.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

inline constexpr double kBalanceTolerance = 1e-9;  // relative to the load
inline constexpr int kBalanceMaxIterations = 50;   // without coupling

// The balance's normal solves (without the coupling) are only as accurate as its next step
// needs: the gap residual at kBalanceSolveFraction |f| / Q, f = V_p + V_c - Q before the solve,
// between the strict setting (`strict_tolerance`, 1e-10 or the caller's tighter gap residual) and
// kLoosestBalanceSolveTolerance. A solve to tolerance tau moves f by about tau Q, so each step
// still takes |f| down by three decades or more (a secant step alone: 1e-2 -> 2.6e-5 -> 8e-9 of
// the load at the C API benchmark's position), and the first solve after the default-criterion
// start stops some five decades early. Only a strict solve settles the balance: one that lands
// within kBalanceTolerance at a looser tolerance is repeated strictly at the same target
// (docs/library.md, "The balance's solves as accurate as its next step needs").
inline constexpr double kBalanceSolveFraction = 1e-3;
inline constexpr double kLoosestBalanceSolveTolerance = 1e-5;
double BalanceSolveTolerance(double f_N, double load_N, double strict_tolerance);

// |V_p + V_c - Q| / Q of a rolling result under the load Q [N] > 0.
double BalanceResidual(const ContactResult& result, double load_N);

// cands[kept_build[k]] is the candidate of result->patches[k], whose cells start at
// kept_offset[k] in np's vectors; np is the normal problem of the rolling result (its gap and
// load target are changed) and pressure its solution [Pa], shape [np->gap_m.size()]. Runs when
// problem.rolling asks for coupling or the load is prescribed; the iterations, the coupling's
// relative area and peak changes, the balance residual, or kNotConverged go into *result.
// memory (optional, in/out): what the rolling stage keeps (RunRollingStage), across the loop's
// repeats of it.
// Returns the pressure [Pa] of *result's patches as the stage leaves them (the last normal
// solve's, or `pressure` when none ran), with np->force_N that solve's load target.
Eigen::VectorXd IterateNormalTangential(const ContactProblem& problem,
                                        const WheelRailGeometry& geom,
                                        const std::vector<ContactCandidate>& cands,
                                        const std::vector<int>& kept_build,
                                        const std::vector<int>& kept_offset, NormalProblem* np,
                                        Eigen::VectorXd pressure, ContactResult* result,
                                        RollingStageMemory* memory = nullptr);

}  // namespace railwear::internal
