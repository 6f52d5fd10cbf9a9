// Tests of hertz_estimate.h: the common approach of a wheel's candidates with each candidate's
// Hertz shape kept through the bisection (issue 18) gives the loads and the approach of a solve
// per call bit for bit.
#include "core/contact/hertz_estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace railwear::internal {
namespace {

// Two candidates as on a wheel at the gauge corner: a tread contact at first contact and a flange
// one 30 um away, on a rolled wheel.
std::vector<ContactCandidate> TwoCandidates() {
  ContactCandidate tread;
  tread.normal = Eigen::Vector2d(0.05, -1.0).normalized();
  tread.rail_lateral_curvature = 1.0 / 0.3;
  tread.wheel_lateral_curvature = -1.0 / 1.2;
  tread.wheel_radius_m = 0.46;
  tread.gap_m = 0.0;
  ContactCandidate flange;
  flange.normal = Eigen::Vector2d(-0.8, -0.6);
  flange.rail_lateral_curvature = 1.0 / 0.013;
  flange.wheel_lateral_curvature = -1.0 / 0.0155;
  flange.wheel_radius_m = 0.475;
  flange.gap_m = 3e-5;
  return {tread, flange};
}

// HertzVerticalLoad as it was before the shapes were kept: a full solve per candidate and call.
double LoadSolvedPerCall(const std::vector<ContactCandidate>& cands, double roll, double estar,
                         double delta, std::vector<HertzSolution>* out) {
  double total = 0.0;
  out->clear();
  for (const auto& c : cands) {
    const Curvatures k = CandidateCurvatures(c, roll);
    const double dn = std::max(0.0, (delta - c.gap_m) * k.w0);
    out->push_back(SolveHertzForApproach(k.A, k.B, estar, dn));
    total += out->back().force_N * k.w0;
  }
  return total;
}

TEST(HertzEstimate, KeptShapesGiveTheLoadsAndApproachOfASolvePerCall) {
  const std::vector<ContactCandidate> cands = TwoCandidates();
  const double roll = 2e-3, estar = 1.15e11;
  for (double delta : {0.0, 1e-5, 3e-5, 7.5e-5, 2e-4}) {
    std::vector<HertzSolution> kept, per_call;
    EXPECT_EQ(HertzVerticalLoad(cands, roll, estar, delta, &kept),
              LoadSolvedPerCall(cands, roll, estar, delta, &per_call));
    ASSERT_EQ(kept.size(), per_call.size());
    for (size_t i = 0; i < kept.size(); ++i) {
      EXPECT_EQ(kept[i].force_N, per_call[i].force_N);
      EXPECT_EQ(kept[i].p0_Pa, per_call[i].p0_Pa);
      EXPECT_EQ(kept[i].semi_axis_x_m, per_call[i].semi_axis_x_m);
      EXPECT_EQ(kept[i].semi_axis_y_m, per_call[i].semi_axis_y_m);
    }
  }
  // The bisection as it was, on loads solved per call.
  const double force = 60e3;
  double hi = 1e-6;
  std::vector<HertzSolution> scratch;
  while (LoadSolvedPerCall(cands, roll, estar, hi, &scratch) < force && hi < 1.0) hi *= 2.0;
  double lo = 0.0;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (LoadSolvedPerCall(cands, roll, estar, mid, &scratch) < force ? lo : hi) = mid;
  }
  const double approach = HertzApproachForLoad(cands, roll, estar, force);
  EXPECT_EQ(approach, 0.5 * (lo + hi));
  // And it carries the load (the bisection's 1e-15 m on a ~1e-4 m approach).
  EXPECT_NEAR(HertzVerticalLoad(cands, roll, estar, approach, nullptr), force, 1e-6 * force);
}

}  // namespace
}  // namespace railwear::internal
