// The normal part of one wheel's SolveContact kept for the next solve of the same problem on
// the same placed geometry that differs only in the wheel's pitch velocity (issue 18, set-up
// reuse). Internal to the contact module.
//
// SolveWheelset's axle-force search solves each wheel again at the pitch velocity it found
// (wheelset_contact.h): the contact search, the Hertz estimates, the patch grids, the influence
// operators and the normal solves before the rolling stage (SolveContact's steps 2-4) depend on
// the placed geometry and the problem's load, model, materials and solver options, never on the
// pitch velocity, so the second solve recomputed the first one's normal part exactly (about a
// third of the main job's CPU time). With a memo, SolveContact keeps that part after its normal
// solve and the next call on the same geometry continues from a copy of it with the rolling
// stage, so its result is the one a full solve gives, bit for bit (contact_solver_test.cpp).
//
// Contract: a memo serves the solves of one ContactProblem (the same profiles, placement, load,
// model, materials, solver options and pressure limit; rolling present) on one WheelRailGeometry
// object, in which only rolling->motion.pitch_velocity_rad_s changes between calls. A memo is
// used by one thread; it holds the grids' operators (megabytes) until it is destroyed.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/normal_stage.h"
#include "core/contact/operator_stage.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// SolveContact's state after its normal solve and patch results (step 4), before rolling.
struct NormalPart {
  ContactResult result;                 // status, patches, iterations, message; stages so far
  std::vector<ContactCandidate> cands;  // of the attempt's grids
  KeptPatches kept;
  NormalAssembly assembly;   // the operators and the normal problem as the solve left them
  Eigen::VectorXd pressure;  // the normal solution [Pa]
};

class NormalPartMemo {
 public:
  // The part kept by a solve on `geom` (compared by address), or nullptr.
  const NormalPart* Find(const WheelRailGeometry& geom) const {
    return part_ && geom_ == &geom ? part_.get() : nullptr;
  }
  void Keep(const WheelRailGeometry& geom, std::unique_ptr<const NormalPart> part) {
    geom_ = &geom;
    part_ = std::move(part);
  }
  int reuses() const { return reuses_; }  // solves that continued from the kept part
  void CountReuse() { ++reuses_; }

 private:
  const WheelRailGeometry* geom_ = nullptr;
  std::unique_ptr<const NormalPart> part_;
  int reuses_ = 0;
};

// SolveContact(problem, placed, placement_s) with a memo (nullptr: none): continues from the
// memo's part when it holds one for `placed`, else solves in full and, when the problem is
// rolling and the normal solve converged, keeps its normal part there. The result is the same
// bit for bit either way; only its stages differ (a continued solve reports "normal reused"
// instead of the stages of the normal part).
ContactResult SolveContact(const ContactProblem& problem, const WheelRailGeometry& placed,
                           double placement_s, NormalPartMemo* memo);

}  // namespace railwear::internal
