// Profile: an ordered cross-section curve of a wheel or rail, with a smooth C2 representation.
//
// Frame (see core/notation.md): y lateral, positive toward the field side; z vertical, positive
// downward (into the rail, toward the rail for a wheel). A rail profile's origin is its reference
// point (the crown for built-ins); a wheel profile's origin is the taping line at z = 0, where the
// wheel radius equals the nominal rolling radius. SI inside (metres); files use millimetres.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/numerics/cubic_spline.h"

namespace railwear {

class Profile {
 public:
  Profile() = default;
  // points_m: ordered (y, z) points in metres, shape [n][2], n >= 4. `source` names where they
  // came from (a file, "builtin:S1002") and is used in error messages.
  // Throws InputError for fewer than 4 points, a non-finite coordinate or one beyond
  // kMaxCoordinate_m, a duplicate point
  // (closer than kDuplicateDistance_m to its predecessor) or a backtracking point (the curve
  // turns back by more than kMaxTurnAngle_rad between consecutive segments) or a profile that
  // crosses itself (two segments meet, core/profile/profile_defects.h). Messages name the
  // source, the 1-based point numbers and their coordinates.
  explicit Profile(std::vector<Eigen::Vector2d> points_m, std::string source = {});

  static constexpr double kDuplicateDistance_m = 1e-9;
  // No coordinate may lie farther than this from the profile's origin: a wheel or rail section
  // spans some 0.2 m, and the spline, arc-length and contact numerics overflow long before
  // 1e300 (a point at 1e308 mm aborted an internal check). Larger is refused as InputError.
  static constexpr double kMaxCoordinate_m = 10.0;
  static constexpr double kMaxTurnAngle_rad = 2.6179938779914944;  // 150 degrees
  // A segment longer than kMaxSegmentRatio times a neighbouring one is subdivided along its
  // chord (into pieces of about twice the neighbour, at most kMaxSubdivision) before the spline
  // is built, so that the spline follows coarsely sampled steep walls without overshoot.
  static constexpr double kMaxSegmentRatio = 4.0;
  static constexpr int kMaxSubdivision = 64;

  int size() const { return static_cast<int>(d_->points.size()); }
  const std::vector<Eigen::Vector2d>& points() const { return d_->points; }
  const std::string& source() const { return d_->source; }
  void set_source(std::string source);

  // Arc-length parameter s in [0, Length()] (metres). The knots carry the arc length of the
  // interpolating spline itself (Gauss-Legendre per interval), so s is a true arc length.
  double Length() const { return d_->length; }
  // Arc length of point i.
  double KnotS(int i) const { return d_->knot_s[i]; }

  // Position (y, z) [m], first and second derivative with respect to s, at parameter s.
  // s outside [0, Length()] extrapolates the end cubic (callers should stay inside).
  Eigen::Vector2d Position(double s) const;
  Eigen::Vector2d Derivative(double s) const;
  void Evaluate(double s, Eigen::Vector2d* position, Eigen::Vector2d* d1,
                Eigen::Vector2d* d2) const;
  // Unit tangent in the direction of increasing s.
  Eigen::Vector2d Tangent(double s) const;
  // Unit tangent rotated by +90 degrees in the (y, z) plane: (-t_z, t_y).
  Eigen::Vector2d LeftNormal(double s) const;
  // Signed curvature [1/m]: positive when the curve turns toward LeftNormal().
  double Curvature(double s) const;

  struct Bounds {
    double y_min, y_max, z_min, z_max;  // metres
  };
  Bounds bounds() const;

  // y -> -y (point order reversed so that s still runs the same way round the body).
  Profile Mirrored() const;
  // Rotate about the origin by angle_rad (positive turns +y toward +z), then translate by shift_m.
  Profile Transformed(double angle_rad, const Eigen::Vector2d& shift_m) const;

 private:
  // A profile's data, immutable once built and shared by its copies: a Profile is a value, and
  // copying one is O(1) (a wheelset call copied the wheel and rail profiles six times, each a
  // block of some 100 kB that glibc mapped afresh on every call: docs/library.md, "Wheelsets on
  // the fast tread path"). set_source copies the data first.
  struct Data {
    std::vector<Eigen::Vector2d> points;
    std::string source;
    std::vector<double> knot_s;  // arc length of each point
    double length = 0.0;
    CubicSplineCurve curve;  // (y, z) of s
  };
  static std::shared_ptr<const Data> Empty();
  static void Build(Data* d);
  std::shared_ptr<const Data> d_ = Empty();
};

}  // namespace railwear
