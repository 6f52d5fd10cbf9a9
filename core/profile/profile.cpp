// Profile validation and its C2 arc-length spline.
#include "core/profile/profile.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/numerics/input_error.h"
#include "core/profile/profile_defects.h"

namespace railwear {

namespace {

// Arc length of the spline pieces between consecutive knots, by 5-point Gauss-Legendre.
std::vector<double> SplineArcLengths(const CubicSplineCurve& curve) {
  static constexpr double kX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                   0.5384693101056831, 0.9061798459386640};
  static constexpr double kW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                   0.4786286704993665, 0.2369268850561891};
  const std::vector<double>& t = curve.knots();
  std::vector<double> s(t.size(), 0.0);
  for (size_t i = 0; i + 1 < t.size(); ++i) {
    const double mid = 0.5 * (t[i] + t[i + 1]);
    const double half = 0.5 * (t[i + 1] - t[i]);
    double len = 0.0;
    for (int k = 0; k < 5; ++k) {
      Eigen::Vector2d d1;
      curve.Evaluate(mid + half * kX[k], nullptr, &d1, nullptr);
      len += kW[k] * std::hypot(d1.x(), d1.y());
    }
    s[i + 1] = s[i] + half * len;
  }
  return s;
}

}  // namespace

std::shared_ptr<const Profile::Data> Profile::Empty() {
  static const std::shared_ptr<const Data> empty = std::make_shared<const Data>();
  return empty;
}

void Profile::set_source(std::string source) {
  auto d = std::make_shared<Data>(*d_);
  d->source = std::move(source);
  d_ = std::move(d);
}

Profile::Profile(std::vector<Eigen::Vector2d> points_m, std::string source) {
  auto d = std::make_shared<Data>();
  d->points = std::move(points_m);
  d->source = std::move(source);
  const std::vector<Eigen::Vector2d>& points = d->points;
  const std::string& name = d->source;
  const std::string where = name.empty() ? std::string("profile") : name;
  if (points.size() < 4) {
    throw InputError(fmt::format("{}: {} point(s) read; a profile needs at least 4 points", where,
                                 points.size()));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x()) || !std::isfinite(points[i].y())) {
      throw InputError(fmt::format("{}: point {} has a non-finite coordinate (y = {}, z = {} mm)",
                                   where, i + 1, points[i].x() * 1e3, points[i].y() * 1e3));
    }
    if (std::abs(points[i].x()) > kMaxCoordinate_m || std::abs(points[i].y()) > kMaxCoordinate_m) {
      throw InputError(
          fmt::format("{}: point {} (y = {}, z = {} mm) lies beyond {} mm of the origin; expected "
                      "coordinates within +-{} mm",
                      where, i + 1, points[i].x() * 1e3, points[i].y() * 1e3,
                      kMaxCoordinate_m * 1e3, kMaxCoordinate_m * 1e3));
    }
  }
  if (const auto defect = FindProfileDefect(points)) {
    const auto mm = [&](int i) {
      return fmt::format("(y = {:.6f}, z = {:.6f} mm)", points[i].x() * 1e3, points[i].y() * 1e3);
    };
    const int a = defect->a, b = defect->b;
    switch (defect->kind) {
      case ProfileDefect::Kind::kDuplicate:
        throw InputError(
            fmt::format("{}: point {} {} duplicates point {}; expected distinct consecutive points",
                        where, b + 1, mm(b), a + 1));
      case ProfileDefect::Kind::kTurnBack:
        throw InputError(fmt::format(
            "{}: point {} {} makes the profile turn back on itself (more than 150 degrees); "
            "expected points ordered along the profile",
            where, b + 1, mm(b)));
      case ProfileDefect::Kind::kCrossing:
        throw InputError(fmt::format(
            "{}: the profile crosses itself: the segment from point {} {} to point {} {} "
            "crosses the segment from point {} {} to point {} {} at (y = {:.6f}, z = {:.6f} mm); "
            "expected a profile that does not cross itself",
            where, a + 1, mm(a), a + 2, mm(a + 1), b + 1, mm(b), b + 2, mm(b + 1),
            defect->crossing.x() * 1e3, defect->crossing.y() * 1e3));
    }
  }
  Build(d.get());
  d_ = std::move(d);
}

void Profile::Build(Data* d) {
  const std::vector<Eigen::Vector2d>& points = d->points;
  // Spline knots: the points, plus chord points on any segment much longer than a neighbour.
  // A steep wall sampled at a fixed lateral step gives such segments (0.1 mm next to 1.27 mm in
  // the shared groove files), and a natural spline through them swings out by a sizeable part of
  // the long segment (0.22 mm there) instead of following the wall.
  const size_t n = points.size();
  std::vector<double> seg(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) seg[i] = (points[i + 1] - points[i]).norm();
  std::vector<Eigen::Vector2d> knots;
  std::vector<int> point_knot(n);
  for (size_t i = 0; i + 1 < n; ++i) {
    point_knot[i] = static_cast<int>(knots.size());
    knots.push_back(points[i]);
    double neighbour = std::numeric_limits<double>::infinity();
    if (i > 0) neighbour = std::min(neighbour, seg[i - 1]);
    if (i + 2 < n) neighbour = std::min(neighbour, seg[i + 1]);
    if (seg[i] > kMaxSegmentRatio * neighbour) {
      const int pieces =
          std::min(kMaxSubdivision, static_cast<int>(std::ceil(seg[i] / (2.0 * neighbour))));
      for (int k = 1; k < pieces; ++k) {
        knots.push_back(points[i] + (points[i + 1] - points[i]) * (double(k) / pieces));
      }
    }
  }
  point_knot[n - 1] = static_cast<int>(knots.size());
  knots.push_back(points[n - 1]);

  const size_t m = knots.size();
  std::vector<double> t(m, 0.0), y(m), z(m);
  for (size_t i = 0; i < m; ++i) {
    y[i] = knots[i].x();
    z[i] = knots[i].y();
    if (i > 0) t[i] = t[i - 1] + (knots[i] - knots[i - 1]).norm();
  }
  // Chord-length spline first, then re-parametrise by its own arc length (one pass makes the
  // parameter an arc length to far below the point spacing's second order).
  const std::vector<double> knot_s = SplineArcLengths(CubicSplineCurve(t, y, z));
  d->curve = CubicSplineCurve(knot_s, y, z);
  d->knot_s.resize(n);
  for (size_t i = 0; i < n; ++i) d->knot_s[i] = knot_s[point_knot[i]];
  d->length = knot_s.back();
}

void Profile::Evaluate(double s, Eigen::Vector2d* position, Eigen::Vector2d* d1,
                       Eigen::Vector2d* d2) const {
  d_->curve.Evaluate(s, position, d1, d2);
}

Eigen::Vector2d Profile::Position(double s) const {
  Eigen::Vector2d p;
  Evaluate(s, &p, nullptr, nullptr);
  return p;
}

Eigen::Vector2d Profile::Derivative(double s) const {
  Eigen::Vector2d d;
  Evaluate(s, nullptr, &d, nullptr);
  return d;
}

Eigen::Vector2d Profile::Tangent(double s) const { return Derivative(s).normalized(); }

Eigen::Vector2d Profile::LeftNormal(double s) const {
  const Eigen::Vector2d t = Tangent(s);
  return {-t.y(), t.x()};
}

double Profile::Curvature(double s) const {
  Eigen::Vector2d d1, d2;
  Evaluate(s, nullptr, &d1, &d2);
  const double speed = d1.norm();
  return (d1.x() * d2.y() - d1.y() * d2.x()) / (speed * speed * speed);
}

Profile::Bounds Profile::bounds() const {
  const std::vector<Eigen::Vector2d>& points = d_->points;
  Bounds b{points[0].x(), points[0].x(), points[0].y(), points[0].y()};
  for (const auto& p : points) {
    b.y_min = std::min(b.y_min, p.x());
    b.y_max = std::max(b.y_max, p.x());
    b.z_min = std::min(b.z_min, p.y());
    b.z_max = std::max(b.z_max, p.y());
  }
  return b;
}

Profile Profile::Mirrored() const {
  std::vector<Eigen::Vector2d> pts(d_->points.rbegin(), d_->points.rend());
  for (auto& p : pts) p.x() = -p.x();
  return Profile(std::move(pts), d_->source);
}

Profile Profile::Transformed(double angle_rad, const Eigen::Vector2d& shift_m) const {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  std::vector<Eigen::Vector2d> pts(d_->points);
  for (auto& p : pts) {
    const Eigen::Vector2d q(c * p.x() - s * p.y(), s * p.x() + c * p.y());
    p = q + shift_m;
  }
  return Profile(std::move(pts), d_->source);
}

}  // namespace railwear
