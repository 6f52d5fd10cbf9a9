// Duplicate points, turn-backs and self-crossings of a profile polyline (see profile_defects.h).
#include "core/profile/profile_defects.h"

#include <algorithm>
#include <cmath>

#include "core/profile/profile.h"

namespace railwear {

namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Sign of the turn from p->q to p->r: > 0 left, < 0 right, 0 collinear.
double Orientation(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return Cross(q - p, r - p);
}

// r, collinear with [p, q], lies within the segment's bounding box (so on the segment).
bool OnSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
         std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
}

// Where closed segments [p1, p2] and [q1, q2] meet, if they do (a touch counts).
std::optional<Eigen::Vector2d> SegmentsMeet(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                                            const Eigen::Vector2d& q1, const Eigen::Vector2d& q2) {
  const double o1 = Orientation(p1, p2, q1), o2 = Orientation(p1, p2, q2);
  const double o3 = Orientation(q1, q2, p1), o4 = Orientation(q1, q2, p2);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    const Eigen::Vector2d d = p2 - p1, e = q2 - q1;
    return p1 + d * (Cross(q1 - p1, e) / Cross(d, e));
  }
  if (o1 == 0 && OnSegment(p1, p2, q1)) return q1;
  if (o2 == 0 && OnSegment(p1, p2, q2)) return q2;
  if (o3 == 0 && OnSegment(q1, q2, p1)) return p1;
  if (o4 == 0 && OnSegment(q1, q2, p2)) return p2;
  return std::nullopt;
}

}  // namespace

std::optional<ProfileDefect> FindSelfIntersection(const std::vector<Eigen::Vector2d>& points) {
  const int segments = static_cast<int>(points.size()) - 1;
  if (segments < 3) return std::nullopt;
  struct Extent {
    double y_min, y_max, z_min, z_max;
  };
  std::vector<Extent> extent(segments);
  std::vector<int> order(segments);
  for (int i = 0; i < segments; ++i) {
    const Eigen::Vector2d& p = points[i];
    const Eigen::Vector2d& q = points[i + 1];
    extent[i] = {std::min(p.x(), q.x()), std::max(p.x(), q.x()), std::min(p.y(), q.y()),
                 std::max(p.y(), q.y())};
    order[i] = i;
  }
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return extent[i].y_min < extent[j].y_min || (extent[i].y_min == extent[j].y_min && i < j);
  });
  // Sweep in y: `active` holds the segments whose y-extent reaches the current one's start.
  std::optional<ProfileDefect> best;
  std::vector<int> active;
  for (const int i : order) {
    const Extent& ei = extent[i];
    std::erase_if(active, [&](int j) { return extent[j].y_max < ei.y_min; });
    for (const int j : active) {
      if (std::abs(i - j) < 2) continue;  // neighbours share a point (turn-backs checked apart)
      const Extent& ej = extent[j];
      if (ej.z_max < ei.z_min || ei.z_max < ej.z_min) continue;
      const int a = std::min(i, j), b = std::max(i, j);
      if (best && (best->a < a || (best->a == a && best->b < b))) continue;
      if (const auto at = SegmentsMeet(points[a], points[a + 1], points[b], points[b + 1])) {
        best = ProfileDefect{ProfileDefect::Kind::kCrossing, a, b, 0.0, *at};
      }
    }
    active.push_back(i);
  }
  return best;
}

std::optional<ProfileDefect> FindProfileDefect(const std::vector<Eigen::Vector2d>& points,
                                               double length_scale) {
  const int n = static_cast<int>(points.size());
  const double duplicate = Profile::kDuplicateDistance_m * length_scale;
  for (int i = 1; i < n; ++i) {
    if ((points[i] - points[i - 1]).norm() < duplicate) {
      return ProfileDefect{ProfileDefect::Kind::kDuplicate, i - 1, i, 0.0, Eigen::Vector2d::Zero()};
    }
  }
  const double cos_max_turn = std::cos(Profile::kMaxTurnAngle_rad);
  for (int i = 1; i + 1 < n; ++i) {
    const Eigen::Vector2d u = points[i] - points[i - 1];
    const Eigen::Vector2d v = points[i + 1] - points[i];
    const double nn = u.norm() * v.norm();
    if (u.dot(v) < cos_max_turn * nn) {
      const double turn = std::acos(std::clamp(u.dot(v) / nn, -1.0, 1.0));
      return ProfileDefect{ProfileDefect::Kind::kTurnBack, i, i + 1, turn, Eigen::Vector2d::Zero()};
    }
  }
  return FindSelfIntersection(points);
}

}  // namespace railwear
