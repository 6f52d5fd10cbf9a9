// Displacement curves against a reference, with the support offset fitted. See
// curve_comparison.h.
#include "calibration/curve_comparison.h"

#include <algorithm>
#include <cmath>

namespace railwear {

CurveReference HalfSpaceReference(const Material& material) {
  return [material](CurveLoad load, CurvePath, double distance_m) -> std::optional<double> {
    return HalfSpaceDisplacement(material, load, distance_m);
  };
}

CurveReference CurvesReference(const DisplacementCurves& reference) {
  return [&reference](CurveLoad load, CurvePath path, double d) -> std::optional<double> {
    const DisplacementPoint* below = nullptr;
    const DisplacementPoint* above = nullptr;
    for (const DisplacementPoint& p : reference.points) {
      if (p.load != load || p.path != path) continue;
      if (p.distance_m <= d && (below == nullptr || p.distance_m > below->distance_m)) below = &p;
      if (p.distance_m >= d && (above == nullptr || p.distance_m < above->distance_m)) above = &p;
    }
    if (below == nullptr || above == nullptr) return std::nullopt;
    if (below->distance_m == above->distance_m) return below->w_m_per_N;
    const double t =
        std::log(d / below->distance_m) / std::log(above->distance_m / below->distance_m);
    const double wd =
        (1.0 - t) * below->w_m_per_N * below->distance_m + t * above->w_m_per_N * above->distance_m;
    return wd / d;
  };
}

std::vector<CurveComparison> CompareCurves(const DisplacementCurves& curves,
                                           const CurveReference& reference, double from_m,
                                           double to_m) {
  std::vector<CurveComparison> out;
  for (const DisplacementPoint& p : curves.points) {
    if (p.distance_m < from_m || p.distance_m > to_m) continue;
    const std::optional<double> ref = reference(p.load, p.path, p.distance_m);
    if (!ref || *ref == 0.0) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const CurveComparison& c) {
      return c.load == p.load && c.path == p.path;
    });
    if (it == out.end()) {
      out.push_back({});
      it = out.end() - 1;
      it->load = p.load;
      it->path = p.path;
    }
    it->points.push_back({p.distance_m, p.w_m_per_N, *ref});
  }
  for (CurveComparison& c : out) {
    std::sort(c.points.begin(), c.points.end(),
              [](const auto& a, const auto& b) { return a.distance_m < b.distance_m; });
    double sum = 0.0;
    for (const ComparedPoint& p : c.points) sum += p.w_m_per_N - p.reference_m_per_N;
    c.offset_m_per_N = sum / static_cast<double>(c.points.size());
    double largest = 0.0;
    for (const ComparedPoint& p : c.points)
      largest = std::max(largest, std::abs(p.reference_m_per_N));
    for (const ComparedPoint& p : c.points) {
      if (std::abs(p.reference_m_per_N) < kSmallReferenceFraction * largest) {
        ++c.num_skipped;
        continue;
      }
      c.max_raw_error = std::max(c.max_raw_error, std::abs(c.RawRatio(p) - 1.0));
      c.max_corrected_error = std::max(c.max_corrected_error, std::abs(c.CorrectedRatio(p) - 1.0));
    }
  }
  return out;
}

}  // namespace railwear
