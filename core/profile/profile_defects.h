// Geometric defects of a profile polyline that no profile may have: two consecutive points at
// the same place, a turn back on itself, and segments that cross (a self-intersecting curve).
//
// One finder serves the Profile constructor (messages by point number), the file readers
// (messages by file line) and the profile fit's scan cleaning (wear/profile_fit.h), which drops
// the glitches that cause them.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

namespace railwear {

struct ProfileDefect {
  enum class Kind {
    kDuplicate,  // point `b` lies within kDuplicateDistance of point a = b - 1
    kTurnBack,   // at point a the polyline turns by turn_rad > kMaxTurnAngle; b = a + 1
    kCrossing,   // segment [a, a+1] crosses (or touches) segment [b, b+1], a + 1 < b
  };
  Kind kind = Kind::kDuplicate;
  int a = 0;  // 0-based point / segment indices, see kind
  int b = 0;
  double turn_rad = 0.0;                               // kTurnBack: the turn at point a
  Eigen::Vector2d crossing = Eigen::Vector2d::Zero();  // kCrossing: where (same units as points)
};

// The first defect of the polyline `points` (shape [n][2], any length unit; thresholds are in
// metres for metre points, `length_scale` converts: 1 for metres, 1e3 for millimetres):
// duplicates first (lowest index), then turn-backs (lowest index), then the crossing with the
// lowest first segment. Non-adjacent segments are tested by a sweep over their y-extents
// (sorted once, O(n log n) plus the pairs that overlap in y), so a few thousand points cost
// well under a millisecond (see tests/benchmarks). Empty when the polyline has none.
std::optional<ProfileDefect> FindProfileDefect(const std::vector<Eigen::Vector2d>& points,
                                               double length_scale = 1.0);

// Only the crossing test of FindProfileDefect: the crossing with the lowest first segment.
std::optional<ProfileDefect> FindSelfIntersection(const std::vector<Eigen::Vector2d>& points);

}  // namespace railwear
