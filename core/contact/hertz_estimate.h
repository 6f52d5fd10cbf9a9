// Hertz estimates for SolveContact: the Hertz model itself (candidates, common approach, one
// ellipse per patch), and the first estimate of the approach and patch size at first contact
// that seeds the grid models' potential area. Internal to SolveContact.
#pragma once

#include <vector>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/hertz.h"
#include "core/contact/stage_timer.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// Hertz's relative curvatures at a candidate [1/m]: A along x (the wheel's parallel circle,
// normal curvature cos(gamma)/r by Meusnier), B laterally (sum of the convex-positive profile
// curvatures); w0 the normal's cosine against the vertical. See the .cpp.
struct Curvatures {
  double A = 0.0, B = 0.0, w0 = 1.0;
};
Curvatures CandidateCurvatures(const ContactCandidate& c, double roll_rad);

// Total vertical load [N] of Hertz contacts at all candidates for the common vertical approach
// delta [m] (estar: the contact modulus E* [Pa]); each candidate's ellipse into *out when given.
double HertzVerticalLoad(const std::vector<ContactCandidate>& cands, double roll_rad, double estar,
                         double delta, std::vector<HertzSolution>* out);

// The vertical approach [m] for which the Hertz contacts at all candidates carry `force` [N]
// (bisection).
double HertzApproachForLoad(const std::vector<ContactCandidate>& cands, double roll_rad,
                            double estar, double force);

// The Hertz model's candidates and common approach: candidates within a generous threshold,
// widened while the approach passes it; hs[k] is candidate k's ellipse (force 0: no contact).
struct HertzSearch {
  std::vector<ContactCandidate> cands;
  std::vector<HertzSolution> hs;
  double delta = 0.0;
};
HertzSearch SearchHertz(const WheelRailGeometry& geom, const ContactProblem& problem, double estar);

// The Hertz model's result from a search: one patch per loaded candidate (stage "hertz", timed
// from t0).
ContactResult SolveHertzModel(const HertzSearch& search, ContactResult result,
                              Clock::time_point t0);

// Lateral semi-axis (arc length) [m] of a candidate's patch at the vertical approach delta, for
// the auto model's criterion (see the .cpp): `lo` the smaller of the Hertz and reach estimates
// (the first grid estimate), `hi` the larger. at_delta: geom.FindCandidates(delta).
struct SemiAxisEstimate {
  double lo = 0.0, hi = 0.0;
};
SemiAxisEstimate EstimateSemiAxisS(const WheelRailGeometry& geom, const ContactCandidate& c,
                                   double estar, double delta,
                                   const std::vector<ContactCandidate>& at_delta);

// The largest lateral semi-axis (EstimateSemiAxisS's lo) of the candidates at delta
// (at_delta: geom.FindCandidates(delta)) that hold no point of `first` (the candidates at first
// contact): second points of contact that the approach delta reaches; 0 when there is none.
double ReachedSemiAxisS(const WheelRailGeometry& geom, const std::vector<ContactCandidate>& first,
                        double estar, double delta, const std::vector<ContactCandidate>& at_delta);

// Hertz estimate of the approach and of the patch size at the first contact point, which seeds
// the grid models' potential area.
struct FirstContactEstimate {
  std::vector<ContactCandidate> first;  // candidates at first contact
  std::vector<HertzSolution> hs;        // their Hertz ellipses at delta
  double delta = 0.0;                   // estimated vertical approach [m]
  double semi_axis_x_m = 0.0;           // largest Hertz semi-axis along x
  // Largest Hertz lateral semi-axis, bounded by the lateral reach of the interpenetration at
  // delta (in nearly conformal contact Hertz's is far too large), and above the draft preset at
  // least the estimate of a candidate that delta reaches beside those at first contact
  // (ReachedSemiAxisS) [m].
  double semi_axis_s_m = 0.0;
  std::vector<ContactCandidate> at_delta;  // geom.FindCandidates(delta)
};
FirstContactEstimate EstimateFirstContact(const WheelRailGeometry& geom,
                                          const ContactProblem& problem, double estar);

}  // namespace railwear::internal
