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
// Warm balance (opt-in, NormalPartMemo(kWarmBalance); SolveWheelset's axle-force rounds): under
// a prescribed load the vertical balance with the creep forces (normal_tangential_stage.h) ran
// again from the kept normal part's target (the load) at every new pitch velocity, 2-5 normal
// solves each time, although the last solve's balanced target differs from the new one only by
// the change of the creep forces' vertical part. A warm memo also keeps the last balanced state
// (its patches, load target and pressures) and the next solve's balance starts from there: one
// or two normal solves, often none (a warm balance that fails is run again from the load). The
// result is then not the full solve's bit for bit but the same balance to its tolerance
// (|V_p + V_c - Q| <= kBalanceTolerance Q) from another start, so it differs within that
// tolerance and the normal solver's (normal_part_memo_test.cpp measures it). Not with coupling
// (the balance's gap changes there).
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
#include "core/contact/contact_warm_start.h"
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

// The state a balanced solve left (warm balance): the patches as its last normal solve gave them,
// that solve's load target for the pressure and its pressures [Pa] (np's cell order).
struct BalancedPart {
  std::vector<PatchResult> patches;
  double approach_m = 0.0;
  double target_N = 0.0;
  Eigen::VectorXd pressure;
};

class NormalPartMemo {
 public:
  enum Balance { kExact, kWarmBalance };
  NormalPartMemo() = default;
  explicit NormalPartMemo(Balance balance) : warm_(balance == kWarmBalance) {}

  // The part kept by a solve on `geom` (compared by address), or nullptr.
  const NormalPart* Find(const WheelRailGeometry& geom) const {
    return part_ && geom_ == &geom ? part_.get() : nullptr;
  }
  void Keep(const WheelRailGeometry& geom, std::unique_ptr<const NormalPart> part) {
    geom_ = &geom;
    part_ = std::move(part);
    balanced_.reset();
  }
  bool warm_balance() const { return warm_; }
  // The balanced state of the last solve on the kept part (warm balance only), or nullptr.
  const BalancedPart* Balanced(const WheelRailGeometry& geom) const {
    return warm_ && Find(geom) ? balanced_.get() : nullptr;
  }
  void KeepBalanced(BalancedPart balanced) {
    if (warm_ && part_) balanced_ = std::make_unique<BalancedPart>(std::move(balanced));
  }
  int warm_balances() const { return warm_balances_; }  // solves whose balance started warm
  void CountWarmBalance() { ++warm_balances_; }
  int reuses() const { return reuses_; }  // solves that continued from the kept part
  void CountReuse() { ++reuses_; }

 private:
  const WheelRailGeometry* geom_ = nullptr;
  std::unique_ptr<const NormalPart> part_;
  std::unique_ptr<const BalancedPart> balanced_;
  bool warm_ = false;
  int reuses_ = 0, warm_balances_ = 0;
};

// SolveContact(problem, placed, placement_s) with a memo (nullptr: none): continues from the
// memo's part when it holds one for `placed`, else solves in full and, when the problem is
// rolling and the normal solve converged, keeps its normal part there. The result is the same
// bit for bit either way; only its stages differ (a continued solve reports "normal reused"
// instead of the stages of the normal part). A warm memo (kWarmBalance) also keeps each
// balanced solve's state and starts the next one's balance from it (above): the same result to
// the balance's and the normal solver's tolerances.
// warm (optional, in/out; contact_warm_start.h): the last call's measured patch and balance to
// start from (when it holds one and the attempt fits; else solved as without it), updated with
// this call's. Not with a memo.
ContactResult SolveContact(const ContactProblem& problem, const WheelRailGeometry& placed,
                           double placement_s, NormalPartMemo* memo,
                           ContactWarmStart* warm = nullptr);

}  // namespace railwear::internal
