// Wear measures by line crossings on the profile splines (CurveLocator): the normal-depth scan,
// the curvature-corrected worn-area integral, and the W1/W2/W3 measuring lines.
#include "wear/wear_measures.h"

#include <cmath>
#include <optional>
#include <limits>

#include <fmt/format.h>

#include "core/geometry/curve_locator.h"
#include "core/numerics/input_error.h"

namespace railwear {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// How far outside the profile's bounding box the W1/W2 search lines start [m]: any margin > 0
// works, the crossing nearest to the start is the surface facing it.
constexpr double kLineMargin_m = 1e-3;
// Coarse scan step of the locators [m]. The crossings are refined on the spline to
// CurveLocator::kParameterTolerance_m; the scan only has to separate distinct crossings, and rail
// profiles have no features narrower than 0.02 mm.
constexpr double kScanStep_m = 2e-5;
// Bisection iterations for the 45-degree point: the bracket of one scan step (0.02 mm) halves
// 40 times to below 1e-17 m.
constexpr int kBisections = 40;

// The crossing of the line p + lambda u with the profile nearest to p, within max_distance.
std::optional<double> CrossingNear(const CurveLocator& locator, const Eigen::Vector2d& p,
                                   const Eigen::Vector2d& u, double max_distance) {
  const auto c = locator.IntersectLine(p, u, 0.0, locator.length());
  if (!c || std::abs(c->lambda) > max_distance) return std::nullopt;
  return c->lambda;
}

// Position of the surface along a measuring line: lambda of its nearest crossing, or NaN.
double AlongLine(const CurveLocator& locator, const MeasuringLine& line, double max_distance) {
  const auto lambda = CrossingNear(locator, line.point_m, line.direction, max_distance);
  return lambda ? *lambda : kNaN;
}

[[noreturn]] void NotARailHead(const Profile& p, const std::string& what) {
  throw InputError(fmt::format(
      "profile '{}': {}; expected a rail head in its own uncanted frame (y toward the field side, "
      "gauge face at negative y, z down, the centre line at y = 0), like builtin:UIC60",
      p.source(), what));
}

}  // namespace

bool WearMeasureOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& msg) {
    if (error) *error = msg;
    return false;
  };
  if (!(step_m >= 1e-6 && step_m <= 1e-3)) {
    return fail(fmt::format("wear measures: step_m = {}; expected 1e-6 to 1e-3 m", step_m));
  }
  if (!(side_wear_depth_m > 0.0 && std::isfinite(side_wear_depth_m))) {
    return fail(fmt::format("wear measures: side_wear_depth_m = {}; expected a finite depth > 0 m",
                            side_wear_depth_m));
  }
  if (!(max_normal_distance_m > 0.0 && std::isfinite(max_normal_distance_m))) {
    return fail(
        fmt::format("wear measures: max_normal_distance_m = {}; expected a finite "
                    "distance > 0 m",
                    max_normal_distance_m));
  }
  return true;
}

WearGauge MakeWearGauge(const Profile& unworn, double side_wear_depth_m) {
  if (!(side_wear_depth_m > 0.0 && std::isfinite(side_wear_depth_m))) {
    throw InputError(fmt::format("wear gauge: side wear depth = {} m; expected a finite depth > 0",
                                 side_wear_depth_m));
  }
  if (unworn.size() < 4) NotARailHead(unworn, "empty profile");
  const CurveLocator locator(unworn, /*material_toward_plus_z=*/true, kScanStep_m);
  const Profile::Bounds b = unworn.bounds();
  WearGauge g;

  // W1: the top of rail on the centre line, seen from above.
  const Eigen::Vector2d down(0.0, 1.0);
  const auto top =
      locator.IntersectLine({0.0, b.z_min - kLineMargin_m}, down, 0.0, locator.length());
  if (!top) NotARailHead(unworn, "no surface on the centre line y = 0");
  g.vertical.point_m = unworn.Position(top->s);
  g.vertical.direction = down;

  // W2: the gauge face at side_wear_depth_m below the top, seen from the gauge side.
  const Eigen::Vector2d toward_field(1.0, 0.0);
  const double z_side = g.vertical.point_m.y() + side_wear_depth_m;
  const auto face =
      locator.IntersectLine({b.y_min - kLineMargin_m, z_side}, toward_field, 0.0, locator.length());
  if (!face || unworn.Position(face->s).x() >= g.vertical.point_m.x()) {
    NotARailHead(unworn, fmt::format("no gauge face {:g} mm below the top of rail (z = {:g} mm)",
                                     side_wear_depth_m * 1e3, z_side * 1e3));
  }
  g.side.point_m = unworn.Position(face->s);
  g.side.direction = toward_field;

  // W3: from the gauge-side end toward the crown, the first point where the outward normal n
  // turns past 45 degrees, i.e. f = n_y - n_z changes sign from - (facing the gauge side) to +.
  const double length = unworn.Length();
  const bool gauge_end_first = unworn.Position(0.0).x() <= unworn.Position(length).x();
  const int n = static_cast<int>(std::ceil(length / kScanStep_m));
  auto s_at = [&](int k) { return gauge_end_first ? length * k / n : length * (n - k) / n; };
  auto f = [&](double s) {
    const Eigen::Vector2d normal = locator.OutwardNormal(s);
    return normal.x() - normal.y();
  };
  std::optional<double> s45;
  double f_prev = f(s_at(0));
  for (int k = 1; k <= n && !s45; ++k) {
    const double f_k = f(s_at(k));
    if (f_prev < 0.0 && f_k >= 0.0 && locator.OutwardNormal(s_at(k)).x() < 0.0) {
      double lo = s_at(k - 1), hi = s_at(k);  // f(lo) < 0 <= f(hi)
      for (int it = 0; it < kBisections; ++it) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) < 0.0 ? lo : hi) = mid;
      }
      s45 = 0.5 * (lo + hi);
    }
    f_prev = f_k;
  }
  if (!s45) NotARailHead(unworn, "no gauge-corner point whose normal points 45 degrees up");
  g.corner45.point_m = unworn.Position(*s45);
  g.corner45.direction = Eigen::Vector2d(1.0, 1.0) / std::sqrt(2.0);
  return g;
}

namespace {

// The normal-depth scan, the worn area and the largest depth of `worn` against `original`
// (WearMeasures' fields but W1/W2/W3), material on the side `orig_locator` and `worn_locator`
// were built with.
WearMeasures NormalDepthScan(const Profile& original, const CurveLocator& orig_locator,
                             const CurveLocator& worn_locator, const WearMeasureOptions& options) {
  const double max_distance = options.max_normal_distance_m;
  WearMeasures m;
  // Normal depth at the centres of n equal cells of the original's arc length.
  const double length = original.Length();
  const int n = std::max(1, static_cast<int>(std::ceil(length / options.step_m)));
  const double h = length / n;
  m.s_m.resize(n);
  m.depth_m.resize(n);
  bool any = false;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * h;
    const Eigen::Vector2d c = original.Position(s);
    const Eigen::Vector2d inward = -orig_locator.OutwardNormal(s);
    m.s_m[i] = s;
    const auto d = CrossingNear(worn_locator, c, inward, max_distance);
    if (!d) {
      m.depth_m[i] = kNaN;
      ++m.unmatched_samples;
      continue;
    }
    m.depth_m[i] = *d;
    // Curvature toward the material: positive where the original is convex (rail crown).
    const double kappa = original.Curvature(s) * original.LeftNormal(s).dot(inward);
    m.worn_area_m2 += h * (*d - 0.5 * kappa * *d * *d);
    if (!any || *d > m.max_depth_m) {
      any = true;
      m.max_depth_m = *d;
      m.max_depth_s_m = s;
      m.max_depth_y_m = c.x();
      m.max_depth_z_m = c.y();
    }
  }
  if (!any) m.max_depth_m = m.max_depth_s_m = m.max_depth_y_m = m.max_depth_z_m = kNaN;
  return m;
}

}  // namespace

WearMeasures CompareProfiles(const Profile& original, const Profile& worn,
                             const WearMeasureOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  const WearGauge gauge =
      options.gauge ? *options.gauge : MakeWearGauge(original, options.side_wear_depth_m);
  const CurveLocator orig_locator(original, /*material_toward_plus_z=*/true, kScanStep_m);
  const CurveLocator worn_locator(worn, /*material_toward_plus_z=*/true, kScanStep_m);
  const double max_distance = options.max_normal_distance_m;
  WearMeasures m = NormalDepthScan(original, orig_locator, worn_locator, options);

  // W1/W2/W3: worn minus original position along each fixed line.
  auto measure = [&](const MeasuringLine& line) {
    return AlongLine(worn_locator, line, max_distance) -
           AlongLine(orig_locator, line, max_distance);
  };
  m.vertical_wear_m = measure(gauge.vertical);
  m.side_wear_m = measure(gauge.side);
  m.wear_45_m = measure(gauge.corner45);
  return m;
}

WearMeasures CompareWheelProfiles(const Profile& original, const Profile& worn,
                                  const WearMeasureOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  const CurveLocator orig_locator(original, /*material_toward_plus_z=*/false, kScanStep_m);
  const CurveLocator worn_locator(worn, /*material_toward_plus_z=*/false, kScanStep_m);
  WearMeasures m = NormalDepthScan(original, orig_locator, worn_locator, options);
  m.vertical_wear_m = m.side_wear_m = m.wear_45_m = kNaN;
  return m;
}

namespace {

// The profile sampled every `step` of arc length (both ends included).
std::vector<Eigen::Vector2d> Sampled(const Profile& p, double step) {
  const int n = std::max(2, static_cast<int>(std::ceil(p.Length() / step)));
  std::vector<Eigen::Vector2d> out(n + 1);
  for (int k = 0; k <= n; ++k) out[k] = p.Position(p.Length() * k / n);
  return out;
}

}  // namespace

WheelFlangeMeasures MeasureWheelFlange(const Profile& wheel, double flange_back_y_m) {
  constexpr double kStep_m = 1e-5;      // sampling of the profile: 10 um
  constexpr double kSdHeight_m = 10e-3;  // Sd: 10 mm above the running circle
  constexpr double kQrDepth_m = 2e-3;    // qR: 2 mm below the flange tip
  const std::vector<Eigen::Vector2d> pts = Sampled(wheel, kStep_m);
  WheelFlangeMeasures m{kNaN, kNaN, kNaN};
  // The tread at the taping line y = 0, and the flange tip: the largest z at y < 0.
  std::optional<double> z0;
  double z_tip = -kInf, y_tip = 0.0;
  for (size_t k = 0; k + 1 < pts.size(); ++k) {
    const Eigen::Vector2d& a = pts[k];
    const Eigen::Vector2d& b = pts[k + 1];
    if (!z0 && (a.x() - 0.0) * (b.x() - 0.0) <= 0.0 && a.x() != b.x()) {
      z0 = a.y() + (b.y() - a.y()) * (0.0 - a.x()) / (b.x() - a.x());
    }
    if (a.x() < 0.0 && a.y() > z_tip) {
      z_tip = a.y();
      y_tip = a.x();
    }
  }
  if (!z0 || !(z_tip > -kInf)) return m;
  // The tread-side flank at height z: the first crossing from the tip toward the taping line.
  const auto flank_y = [&](double z) -> double {
    double best = kNaN;
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      const Eigen::Vector2d& a = pts[k];
      const Eigen::Vector2d& b = pts[k + 1];
      if ((a.y() - z) * (b.y() - z) > 0.0 || a.y() == b.y()) continue;
      const double y = a.x() + (b.x() - a.x()) * (z - a.y()) / (b.y() - a.y());
      if (y > y_tip && y <= 0.0 && !(y >= best)) best = y;
    }
    return best;
  };
  m.flange_height_m = z_tip - *z0;
  const double y_sd = flank_y(*z0 + kSdHeight_m);
  m.flange_thickness_m = y_sd - flange_back_y_m;
  m.flange_slope_m = y_sd - flank_y(z_tip - kQrDepth_m);
  return m;
}

}  // namespace railwear
