// The vertical balance's iteration on the load target (balance_target.h).
#include "core/contact/balance_target.h"

#include <cmath>

namespace railwear::internal {
namespace {

// A bracket narrower than this (relative to the load) that has not met the tolerance holds a
// step of f, whatever its height.
constexpr double kClosedBracket = 1e-10;

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
  if (lo_ && hi_) {
    double t = (lo_->target_N * hi_->weight_N - hi_->target_N * lo_->weight_N) /
               (hi_->weight_N - lo_->weight_N);
    if (!(t > lo_->target_N && t < hi_->target_N)) t = 0.5 * (lo_->target_N + hi_->target_N);
    target_ = t;
  } else {
    double slope = last_ ? (f - last_->second) / (target_ - last_->first) : initial_slope;
    if (!std::isfinite(slope) || slope < kMinBalanceSlope) slope = kMinBalanceSlope;
    last_ = std::pair{target_, f};
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
