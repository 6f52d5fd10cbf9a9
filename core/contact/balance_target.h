// The iteration on the pressure's load target T of the vertical balance
// (normal_tangential_stage.h): find T with f(T) = V_p(T) + V_c(T) - Q = 0, where V_p = T is the
// pressure's vertical part and V_c the creep forces' vertical part. Secant steps first; once f has
// changed sign, regula falsi (Illinois) inside the bracket, or the secant of the last two points
// where it lands inside the bracket after a step that halved |f| (balance_target.cpp).
//
// V_c(T) can jump where a cell enters or leaves the contact (the tangential solution changes with
// the contact set), and f then has no root: it steps across zero. Regula falsi closes on such a
// step only slowly, because nearly every new target lands on the same side (on the worn rails of
// the 10 MGT run's step 119 it took 50 iterations to narrow a 40.7 N step of a 61 kN load to
// 3e-4 N, and gave up). Stalled() recognises the step instead: the bracket's f rises across it
// far faster than f can rise anywhere else. Then Best() is the side nearer to the load.
// Internal to SolveContact.
#pragma once

#include <optional>
#include <utility>

namespace railwear::internal {

// f rises with T at slope 1 + dV_c/dT, and dV_c/dT lies between -1 + kMinBalanceSlope and about
// mu tan(gamma) <= 1 for the contact angles and friction of wheel and rail (contact_forces.h), so
// a continuous f rises by at most about 2 x the bracket's width across it. A rise of
// kJumpSlope x the width is a step of V_c. (Round-off cannot fake one: it would have to exceed
// 100 x a bracket whose ends both miss the tolerance, so it would be far above the tolerance.)
inline constexpr double kJumpSlope = 100.0;
// The smallest slope d(V_p + V_c)/dT a secant step divides by: creep forces that cancel the
// pressure's vertical part (dV_c/dV_p near -1) leave no load to balance.
inline constexpr double kMinBalanceSlope = 0.05;

class BalanceTarget {
 public:
  // load_N = Q > 0, target_N = the first T, tolerance: |f| <= tolerance Q settles.
  BalanceTarget(double load_N, double target_N, double tolerance);

  bool Settled(double f_N) const;
  // The next target after f(current target) = f_N; initial_slope is df/dT's estimate for the first
  // secant step (1 + V_c / V_p). nullopt when none is positive.
  std::optional<double> Next(double f_N, double initial_slope);

  // The bracket holds a step of f, not a root: f rises across it by more than kJumpSlope x its
  // width, or it has closed to 1e-10 of the load.
  bool Stalled() const;
  // The step of f across the bracket [N] (0 without one).
  double Jump() const;
  // (T, f) of the bracket's side nearer to the load (Stalled() only).
  std::pair<double, double> Best() const;

  // Forget the history (f has changed: the coupling moved the gap).
  void Reset();

 private:
  struct Point {
    double target_N, f_N;  // as solved
    double weight_N;       // f as regula falsi uses it (Illinois halves a side that stays)
  };
  double load_, target_, tolerance_;
  std::optional<std::pair<double, double>> last_;  // (T, f) of the previous point
  std::optional<Point> lo_, hi_;                   // f < 0 and f >= 0
  int side_ = 0;
};

}  // namespace railwear::internal
