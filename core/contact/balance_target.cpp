// The vertical balance's iteration on the load target (balance_target.h).
#include "core/contact/balance_target.h"

#include <cmath>

namespace railwear::internal {
namespace {

// A bracket narrower than this (relative to the load) that has not met the tolerance holds a
// step of f, whatever its height.
constexpr double kClosedBracket = 1e-10;
// Inside a bracket, the secant of the last two points is taken only after a step that reduced
// |f| to below this fraction of the one before.
constexpr double kSecantProgress = 0.5;

}  // namespace

BalanceTarget::BalanceTarget(double load_N, double target_N, double tolerance)
    : load_(load_N), target_(target_N), tolerance_(tolerance) {}

bool BalanceTarget::Settled(double f_N) const { return std::abs(f_N) <= tolerance_ * load_; }

bool BalanceTarget::Stalled() const {
  if (!lo_ || !hi_) return false;
  const double width = hi_->target_N - lo_->target_N;
  if (width <= kClosedBracket * load_) return true;
  return Jump() > kJumpSlope * width;
}

double BalanceTarget::Jump() const { return lo_ && hi_ ? hi_->f_N - lo_->f_N : 0.0; }

std::pair<double, double> BalanceTarget::Best() const {
  const Point& p = std::abs(lo_->f_N) <= std::abs(hi_->f_N) ? *lo_ : *hi_;
  return {p.target_N, p.f_N};
}

std::optional<double> BalanceTarget::Next(double f, double initial_slope) {
  // f grows with T (the pressure's part does, and dV_c/dT > -1): f < 0 below the root.
  if (f < 0) {
    if (lo_ && side_ == -1 && hi_) hi_->weight_N *= 0.5;  // Illinois
    lo_ = Point{target_, f, f};
    side_ = -1;
  } else {
    if (hi_ && side_ == +1 && lo_) lo_->weight_N *= 0.5;
    hi_ = Point{target_, f, f};
    side_ = +1;
  }
  const std::optional<std::pair<double, double>> previous = last_;
  last_ = std::pair{target_, f};
  if (lo_ && hi_) {
    double t = (lo_->target_N * hi_->weight_N - hi_->target_N * lo_->weight_N) /
               (hi_->weight_N - lo_->weight_N);
    // The secant through the last two points where it lands inside the bracket and the last
    // step at least halved |f|: near the root those are the two latest strict solves, while the
    // bracket's far end can be the first point, whose f comes from the default criterion's
    // solve and lies off the line through the strict ones (on the benchmark's wheel at -4 mm by
    // 37 N of 100 kN), and whose weight Illinois halves, which doubled a step past the root
    // (docs/library.md, "The balance's secant inside its bracket"). Elsewhere, and across a
    // step of f (where |f| does not halve), regula falsi as before.
    if (previous && std::abs(f) < kSecantProgress * std::abs(previous->second)) {
      const double secant = target_ - f * (target_ - previous->first) / (f - previous->second);
      if (secant > lo_->target_N && secant < hi_->target_N) t = secant;
    }
    if (!(t > lo_->target_N && t < hi_->target_N)) t = 0.5 * (lo_->target_N + hi_->target_N);
    target_ = t;
  } else {
    double slope = previous ? (f - previous->second) / (target_ - previous->first) : initial_slope;
    if (!std::isfinite(slope) || slope < kMinBalanceSlope) slope = kMinBalanceSlope;
    target_ -= f / slope;
  }
  if (!(target_ > 0.0)) return std::nullopt;
  return target_;
}

void BalanceTarget::Reset() {
  last_.reset();
  lo_.reset();
  hi_.reset();
  side_ = 0;
}

}  // namespace railwear::internal
