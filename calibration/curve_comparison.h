// Comparing displacement curves with a reference: the half-space (Boussinesq, Cerruti) for a
// flat FEM body, or another set of curves (a finer mesh, a bigger body). A finite body with
// supports deflects by a nearly constant offset that a half-space does not (only differences of
// w across a contact patch matter for contact), so every comparison also fits that offset: the
// least-squares constant c = mean(w - w_ref) over the compared range, and reports both the raw
// and the offset-removed relative errors. Where a curve crosses zero (a convex body under a
// tangential load) a relative error means nothing: points whose reference is below
// kSmallReferenceFraction of the curve's largest |reference| in the range are left out of the
// largest errors (not out of the offset).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "calibration/displacement_curves.h"

namespace railwear {

constexpr double kSmallReferenceFraction = 0.05;

// w_ref(load, path, distance) [m/N], or nullopt where the reference has no value.
using CurveReference = std::function<std::optional<double>(CurveLoad, CurvePath, double)>;

// The half-space values of HalfSpaceDisplacement for a body of this material.
CurveReference HalfSpaceReference(const Material& material);

// The curves of `reference` (same load and path), interpolated linearly in log(distance) of
// w * distance (which a 1/d decay keeps nearly constant); nullopt outside their distance range
// or for a curve they lack. The object must outlive the returned function.
CurveReference CurvesReference(const DisplacementCurves& reference);

struct ComparedPoint {
  double distance_m = 0.0;
  double w_m_per_N = 0.0;          // the curve's value
  double reference_m_per_N = 0.0;  // the reference's value
};

struct CurveComparison {
  CurveLoad load = CurveLoad::kNormal;
  CurvePath path = CurvePath::kArc;
  std::vector<ComparedPoint> points;  // in the range, where the reference has a value
  double offset_m_per_N = 0.0;        // mean(w - w_ref) over `points`
  double max_raw_error = 0.0;         // max |w / w_ref - 1|
  double max_corrected_error = 0.0;   // max |(w - offset) / w_ref - 1|
  size_t num_skipped = 0;  // points left out of the two maxima (|w_ref| small, see above)

  double RawRatio(const ComparedPoint& p) const { return p.w_m_per_N / p.reference_m_per_N; }
  double CorrectedRatio(const ComparedPoint& p) const {
    return (p.w_m_per_N - offset_m_per_N) / p.reference_m_per_N;
  }
};

// One comparison per curve (load, path) of `curves` that has points in [from_m, to_m] where the
// reference has a non-zero value, in the order the curves first appear.
std::vector<CurveComparison> CompareCurves(const DisplacementCurves& curves,
                                           const CurveReference& reference, double from_m,
                                           double to_m);

}  // namespace railwear
