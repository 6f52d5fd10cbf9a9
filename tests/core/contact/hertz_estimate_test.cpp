// Tests of hertz_estimate.h: the common approach of a wheel's candidates with each candidate's
// Hertz shape kept through the bisection (issue 18) gives the loads and the approach of a solve
// per call bit for bit.
#include "core/contact/hertz_estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/contact/contact_forces.h"
#include "core/contact/patch_model_memory.h"
#include "core/contact/placement_stage.h"
#include "core/contact/potential_area.h"
#include "tests/core/contact/gauge_corner_scene.h"

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

// The first estimate on the C API benchmark's gauge-corner wheel (gauge_corner_scene.h) at a
// lateral shift, and the first attempt's grids from it: their cells and the curved operator's
// cell integrals, nx ns^2 summed over the grids (the first attempt's cost; docs/library.md,
// "The cold call").
struct FirstAttempt {
  FirstContactEstimate estimate;
  // The largest Hertz b at first contact, the interpenetration's reach / sqrt(2), and the
  // reached candidates' estimate (ReachedSemiAxisS).
  double hertz_b_m = 0.0, reach_b_m = 0.0, reached_b_m = 0.0;
  double ds_m = 0.0;
  double integrals = 0.0;
};

FirstAttempt FirstAttemptAt(double lateral_m) {
  const ContactProblem problem = testing::GaugeCorner(lateral_m).problem;
  const WheelRailGeometry geom = PlaceWheel(problem);
  const double estar = ContactModulus(problem.wheel_material, problem.rail_material);
  const double k_w = problem.wheel_material.Compliance(), k_r = problem.rail_material.Compliance();
  FirstAttempt out;
  out.estimate = EstimateFirstContact(geom, problem, estar);
  const FirstContactEstimate& e = out.estimate;
  for (const HertzSolution& h : e.hs) out.hertz_b_m = std::max(out.hertz_b_m, h.semi_axis_y_m);
  for (const ContactCandidate& c : e.at_delta) {
    out.reach_b_m = std::max(
        out.reach_b_m, 0.5 * (c.y_hi_m - c.y_lo_m) / std::max(-c.normal.y(), 0.1) / std::sqrt(2.0));
  }
  out.reached_b_m = ReachedSemiAxisS(geom, e.first, estar, e.delta, e.at_delta);
  PatchModelMemory models(geom, problem, estar, k_r / (k_w + k_r), e);
  PotentialArea area(problem, e, k_r / (k_w + k_r));
  PatchBuilds builds;
  ContactResult scratch;
  EXPECT_TRUE(area.Build(geom, &models, e.delta, &builds, &scratch)) << scratch.message;
  for (const PatchBuild& b : builds.builds) {
    out.ds_m = b.grid.ds_m;
    out.integrals += static_cast<double>(b.grid.nx) * b.grid.ns * b.grid.ns;
  }
  return out;
}

// From -5.35 mm the tread's point lies more than 1 um from first contact: the flange root alone
// is at first contact, and its Hertz b (1.35 mm) sized the cells of the tread's patch, which the
// estimated approach reaches (the tread's own estimate 5.7 mm): 0.137 mm cells and a first
// attempt of 35 x 60 and 35 x 175 cells, 1.2 million cell integrals against 0.08 million at
// -5.36 mm, where both points are at first contact. The reached candidate's estimate now bounds
// the first cells from below (at the standard preset and finer); where both are at first
// contact nothing changes, nor at the draft preset.
TEST(HertzEstimate, ASecondPointTheApproachReachesSizesTheFirstCells) {
  const FirstAttempt before = FirstAttemptAt(-5.36e-3);
  ASSERT_EQ(before.estimate.first.size(), 2u);
  // (both points at first contact: the rule before, min(Hertz b, reach), unchanged)
  EXPECT_EQ(before.estimate.semi_axis_s_m, std::min(before.hertz_b_m, before.reach_b_m));
  for (const double y : {-5.35e-3, -5.30e-3, -5.21e-3}) {
    SCOPED_TRACE(y);
    const FirstAttempt cliff = FirstAttemptAt(y);
    const FirstContactEstimate& e = cliff.estimate;
    ASSERT_EQ(e.first.size(), 1u);
    ASSERT_EQ(e.at_delta.size(), 2u);
    EXPECT_LT(cliff.hertz_b_m, 0.3 * cliff.reach_b_m);  // (the flange root's Hertz b)
    EXPECT_GT(e.semi_axis_s_m, 3.0 * cliff.hertz_b_m);
    EXPECT_EQ(e.semi_axis_s_m, cliff.reached_b_m);
    // The first attempt's lateral cells are its neighbour's (-5.36 mm) within 2x, and its
    // cell integrals within 3x (0.13 million at -5.21 mm: its patches are longer).
    EXPECT_GT(cliff.ds_m, 0.5 * before.ds_m);
    EXPECT_LT(cliff.ds_m, 2.0 * before.ds_m);
    EXPECT_LT(cliff.integrals, 3.0 * before.integrals);
  }
  // At draft the first cells stay the flange root's Hertz b bounded by the reach, as before.
  ContactProblem draft = testing::GaugeCorner(-5.35e-3).problem;
  draft.model.accuracy = AccuracyPreset::kDraft;
  const WheelRailGeometry geom = PlaceWheel(draft);
  const FirstContactEstimate e =
      EstimateFirstContact(geom, draft, ContactModulus(draft.wheel_material, draft.rail_material));
  ASSERT_EQ(e.hs.size(), 1u);
  EXPECT_EQ(e.semi_axis_s_m, e.hs[0].semi_axis_y_m);
}

// The cold call at -5.35 mm on the coarser first cells: within the standard preset's
// discretization error of the reference preset's call (gauge_corner_scene.h).
TEST(HertzEstimate, TheCallAtTheCliffIsWithinTheStandardPresetsErrorOfTheReference) {
  testing::ExpectStandardWithinTheReferencesError(-5.35e-3);
}

}  // namespace
}  // namespace railwear::internal
