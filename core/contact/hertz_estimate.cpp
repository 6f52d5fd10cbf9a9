// Hertz estimates for SolveContact (hertz_estimate.h).
#include "core/contact/hertz_estimate.h"

#include <algorithm>
#include <cmath>

#include "core/contact/patch_results.h"

namespace railwear::internal {

// Hertz's relative curvatures at a candidate: A along x (the wheel's parallel circle, normal
// curvature cos(gamma)/r by Meusnier, gamma the angle between the contact normal and the wheel's
// radial direction, which the wheel's roll turns away from the vertical), B laterally (sum of the
// convex-positive profile curvatures); w0 the normal's cosine against the vertical.
// B is bounded below to stay meaningful in nearly conformal contact, where it only seeds the
// estimate of the approach.
Curvatures CandidateCurvatures(const ContactCandidate& c, double roll_rad) {
  Curvatures k;
  k.w0 = std::max(-c.normal.y(), 1e-3);
  // The wheel's radial direction (toward the rail) in R: (-sin roll, cos roll).
  const double cos_gamma = c.normal.x() * std::sin(roll_rad) - c.normal.y() * std::cos(roll_rad);
  k.A = std::max(cos_gamma, 1e-3) / (2.0 * c.wheel_radius_m);
  k.B = std::max(0.5 * (c.rail_lateral_curvature + c.wheel_lateral_curvature), 1e-4 * k.A);
  return k;
}

namespace {

// A candidate's curvatures and Hertz shape (axis ratio, elliptic integrals), which do not depend
// on the approach: the bisection below solves every candidate at ~60 approaches, and the shape
// was 6 % of the main job's CPU time when each solve found it again (issue 18 point 3). The
// solves from a kept shape are bit for bit the ones SolveHertzForApproach returns.
struct CandidateShape {
  Curvatures k;
  double gap_m;
  HertzShape shape;
};

std::vector<CandidateShape> ShapesOf(const std::vector<ContactCandidate>& cands, double roll_rad) {
  std::vector<CandidateShape> shapes;
  shapes.reserve(cands.size());
  for (const auto& c : cands) {
    const Curvatures k = CandidateCurvatures(c, roll_rad);
    shapes.push_back({k, c.gap_m, HertzShape(k.A, k.B)});
  }
  return shapes;
}

double VerticalLoad(const std::vector<CandidateShape>& shapes, double estar, double delta,
                    std::vector<HertzSolution>* out) {
  double total = 0.0;
  if (out) out->clear();
  for (const auto& c : shapes) {
    const double dn = std::max(0.0, (delta - c.gap_m) * c.k.w0);
    const HertzSolution h = c.shape.SolveForApproach(estar, dn);
    total += h.force_N * c.k.w0;
    if (out) out->push_back(h);
  }
  return total;
}

}  // namespace

// Vertical approach for which Hertz contacts at all candidates carry the vertical load F
// (bisection on the common approach), or their loads for a given approach.
double HertzVerticalLoad(const std::vector<ContactCandidate>& cands, double roll_rad, double estar,
                         double delta, std::vector<HertzSolution>* out) {
  return VerticalLoad(ShapesOf(cands, roll_rad), estar, delta, out);
}

double HertzApproachForLoad(const std::vector<ContactCandidate>& cands, double roll_rad,
                            double estar, double force) {
  const std::vector<CandidateShape> shapes = ShapesOf(cands, roll_rad);
  double hi = 1e-6;
  while (VerticalLoad(shapes, estar, hi, nullptr) < force && hi < 1.0) hi *= 2.0;
  double lo = 0.0;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (VerticalLoad(shapes, estar, mid, nullptr) < force ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The Hertz model's candidates and common approach: candidates within a generous threshold,
// widened while the approach passes it; hs[k] is candidate k's ellipse (force 0: no contact).
HertzSearch SearchHertz(const WheelRailGeometry& geom, const ContactProblem& problem,
                        double estar) {
  HertzSearch out;
  double threshold = 1e-4;
  for (int attempt = 0; attempt < 20; ++attempt) {
    out.cands = geom.FindCandidates(threshold);
    out.delta = problem.load.approach_m
                    ? *problem.load.approach_m
                    : HertzApproachForLoad(out.cands, problem.placement.roll_rad, estar,
                                           *problem.load.vertical_force_N);
    if (out.delta < 0.8 * threshold) break;
    threshold = 2.0 * out.delta;
  }
  HertzVerticalLoad(out.cands, problem.placement.roll_rad, estar, out.delta, &out.hs);
  return out;
}

ContactResult SolveHertzModel(const HertzSearch& search, ContactResult result,
                              Clock::time_point t0) {
  result.approach_m = search.delta;
  for (size_t k = 0; k < search.cands.size(); ++k) {
    if (search.hs[k].force_N <= 0) continue;
    result.patches.push_back(HertzPatch(search.cands[k], search.hs[k]));
    result.patches.back().model = "hertz";
  }
  result.status = result.patches.empty() ? SolverStatus::kNoContact : SolverStatus::kConverged;
  if (result.patches.empty()) result.message = "no contact at this approach";
  AddStage(&result.stages, "hertz", SecondsSince(t0));
  return result;
}

// Lateral semi-axis (arc length) of a candidate's patch at the vertical approach delta, for the
// auto model's criterion: Hertz's b, and the lateral reach of the interpenetration at delta
// divided by sqrt(2) (equal to b for Hertz's quadratic gap; smaller in nearly conformal contact,
// where Hertz's b is far too large; larger where the gap flattens and the patch spreads). `lo`
// is the smaller of the two (the first grid estimate of SolveContact), `hi` the larger. A
// candidate that delta does not reach yet gets the reach of its potential area (its interval).
// at_delta: geom.FindCandidates(delta).
SemiAxisEstimate EstimateSemiAxisS(const WheelRailGeometry& geom, const ContactCandidate& c,
                                   double estar, double delta,
                                   const std::vector<ContactCandidate>& at_delta) {
  constexpr double kMinSemiAxis_m = 1e-5;
  static constexpr double kMinApproachWeight = 0.1;  // as the reach bound of SolveContact
  const Curvatures k = CandidateCurvatures(c, geom.pose().roll_rad);
  const double dn = (delta - c.gap_m) * k.w0;
  auto reach_of = [](const ContactCandidate& ci) {
    return 0.5 * (ci.y_hi_m - ci.y_lo_m) / std::max(-ci.normal.y(), kMinApproachWeight);
  };
  if (!(dn > 0)) {
    const double b = std::max(reach_of(c) / std::sqrt(2.0), kMinSemiAxis_m);
    return {b, b};
  }
  const double hertz_b = SolveHertzForApproach(k.A, k.B, estar, dn).semi_axis_y_m;
  SemiAxisEstimate e{hertz_b, hertz_b};
  for (const auto& ci : at_delta) {
    if (c.y_m >= ci.y_lo_m && c.y_m <= ci.y_hi_m) {
      const double reach_b = reach_of(ci) / std::sqrt(2.0);
      e = {std::min(hertz_b, reach_b), std::max(hertz_b, reach_b)};
    }
  }
  e.lo = std::max(e.lo, kMinSemiAxis_m);
  e.hi = std::max(e.hi, kMinSemiAxis_m);
  return e;
}

double ReachedSemiAxisS(const WheelRailGeometry& geom, const std::vector<ContactCandidate>& first,
                        double estar, double delta, const std::vector<ContactCandidate>& at_delta) {
  double b = 0.0;
  for (const auto& c : at_delta) {
    const bool holds_first = std::any_of(first.begin(), first.end(), [&](const auto& f) {
      return f.y_m >= c.y_lo_m && f.y_m <= c.y_hi_m;
    });
    if (!holds_first) b = std::max(b, EstimateSemiAxisS(geom, c, estar, delta, at_delta).lo);
  }
  return b;
}

FirstContactEstimate EstimateFirstContact(const WheelRailGeometry& geom,
                                          const ContactProblem& problem, double estar) {
  FirstContactEstimate e;
  const bool load_given = problem.load.vertical_force_N.has_value();
  // (Widen the search when no gap sample lies within 1 um of first contact, e.g. at a corner.)
  std::vector<ContactCandidate> first = geom.FindCandidates(1e-6);
  for (double t = 1e-5; first.empty() && t < 1e-2; t *= 10) first = geom.FindCandidates(t);
  double delta_est = load_given ? HertzApproachForLoad(first, problem.placement.roll_rad, estar,
                                                       *problem.load.vertical_force_N)
                                : *problem.load.approach_m;
  std::vector<HertzSolution> hs;
  HertzVerticalLoad(first, problem.placement.roll_rad, estar, delta_est, &hs);
  double ax = 0.0, bs = 0.0;
  for (const auto& h : hs) {
    ax = std::max(ax, h.semi_axis_x_m);
    bs = std::max(bs, h.semi_axis_y_m);
  }
  // In nearly conformal contact Hertz's lateral semi-axis is far too large; bound it by the
  // lateral reach of the interpenetration at the estimated approach.
  const std::vector<ContactCandidate> at_delta_est = geom.FindCandidates(delta_est);
  {
    double reach = 0.0;
    for (const auto& c : at_delta_est) {
      reach = std::max(reach, 0.5 * (c.y_hi_m - c.y_lo_m) / std::max(-c.normal.y(), 0.1));
    }
    if (reach > 0) bs = std::min(bs, reach / std::sqrt(2.0));
  }
  // A candidate that the estimated approach reaches but that holds no first-contact point (a
  // second point of contact more than the search's 1 um away at first contact) is a patch too:
  // its lateral semi-axis (EstimateSemiAxisS's lo, as the auto model estimates it) bounds bs
  // from below. Without it a flange root's Hertz b sized the cells of the tread's patch beside
  // it: on the gauge-corner scene from -5.35 mm (the tread's point 1 um away) b = 1.35 mm
  // against the tread's 5.7 mm, 0.137 mm cells where the patch needs 0.8, and a first attempt
  // of 35 x 175 cells costing ten times its neighbours' (docs/library.md, "The cold call").
  // Not at the draft preset: its 4 cells per semi-axis put some 17 on the tread's semi-axis
  // there, about a standard grid's cost, and the draft runs (the main job, README) keep their
  // results bit for bit (with it the main job's W3 at 1 MGT moved from 0.439 to 0.419 mm).
  if (problem.model.accuracy != AccuracyPreset::kDraft) {
    bs = std::max(bs, ReachedSemiAxisS(geom, first, estar, delta_est, at_delta_est));
  }
  e.first = std::move(first);
  e.hs = std::move(hs);
  e.delta = delta_est;
  e.semi_axis_x_m = ax;
  e.semi_axis_s_m = bs;
  e.at_delta = at_delta_est;
  return e;
}

}  // namespace railwear::internal
