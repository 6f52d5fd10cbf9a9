// Warm start of one wheel's contact across the calls of one caller (issue 20): an MBS calls the
// contact every time step at a position close to the previous one, and CONTACT's library
// starts each call from the previous solution. A cold call measures the patch before it grids
// it at the preset's cells: on the gauge corner at standard accuracy its first two attempts
// (the Hertz estimate's cells, then the grown threshold) only measure the patch, three
// quarters of the operators' and solves' work (docs/library.md "Where a gauge-corner call's
// time goes"). With a ContactWarmStart, SolveContactCase keeps what the last call measured
// (the potential area's threshold, each patch's cell size and crop, the approach, and under a
// prescribed load the vertical balance's pressure target) and the next call's first attempt
// is the last call's final one on the grids of the new position: the preset's cells on the
// measured patch, solved at the last balanced target (scaled by the new load over the old),
// and the balance starts from there. Two more things carry over (potential_area.h):
//  - the pressures: under a prescribed load the attempt's normal solve starts from the last
//    call's final pressures, interpolated onto the new grids (WarmPressureStart), instead of
//    the solver's initial guess;
//  - the grids and their influence operators: while the wheel stays within kMaxKeptGridMove of
//    a cell (0.1) of where a grid was built, a later call keeps that grid's cells (its gaps
//    projected anew on the moved wheel, UpdateConformalGaps) and its operator, instead of
//    walking the cross-section and integrating the operator again (conformal grids).
//
// Fallback: when that attempt does not fit (pressure at a grid's edge, another cell size by
// more than the review's 30 %, a candidate more or fewer or not found where the last call had
// one, an approach past the crop or the candidates' threshold, a solve or the balance that does
// not converge), the call is solved cold, exactly as without a warm start (the same result bit
// for bit), and its state is kept instead.
//
// Accuracy: a warm call's grids are the preset's cells per semi-axis on the patch within the
// review's tolerance, as a cold call's final grid is, but placed from another measurement of
// the patch, so its results differ from a cold call's at the same position by an amount of the
// preset's discretization error (measured over an MBS-like sequence in docs/library.md,
// "Warm start"), not bit for bit. The first call on an empty warm start is the cold call.
//
// Contract: a warm start serves the calls of one problem set-up on one wheel (the same
// profiles, materials, model, solver options, friction and pressure limit) between which only
// the wheel's pose and motion and the load change; the caller clears it when anything else
// changes (the C API's handle does on every set-up call). A wheelset keeps one per wheel
// (SolveWheelset's right_warm and left_warm; with an axle force target the first solve of each
// wheel starts warm and its balance rounds continue from that solve's normal part, their
// NormalPartMemo, the pitch velocity being part of the motion). It is used by one thread.
#pragma once

#include <memory>

namespace railwear {

namespace internal {
struct WarmStartState;  // potential_area.h
}

class ContactWarmStart {
 public:
  ContactWarmStart();
  ~ContactWarmStart();
  ContactWarmStart(ContactWarmStart&&) noexcept;
  ContactWarmStart& operator=(ContactWarmStart&&) noexcept;

  // Forget the last call: the next one is cold.
  void Clear();
  bool empty() const { return state_ == nullptr; }

  int warm_calls() const { return warm_; }      // calls whose warm first attempt fitted
  int cold_calls() const { return cold_; }      // calls solved cold (the first, and every fallback)
  int fallbacks() const { return fallbacks_; }  // warm attempts that did not fit (solved cold)

  // SolveContact's (internal): the kept state (null when empty), and a call's new one.
  const internal::WarmStartState* state() const { return state_.get(); }
  void Keep(std::unique_ptr<internal::WarmStartState> state);
  void CountWarm() { ++warm_; }
  void CountCold() { ++cold_; }
  void CountFallback() { ++fallbacks_; }

 private:
  std::unique_ptr<internal::WarmStartState> state_;
  int warm_ = 0, cold_ = 0, fallbacks_ = 0;
};

}  // namespace railwear
