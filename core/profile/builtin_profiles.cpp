// Built-in profiles (S1002 wheel, UIC60 rail head, circles and grooves), rail cant and profile
// specs. Definitions and check values: ../shared/reference/README.md §5.
//
// Point order convention (shared with the file readers in profile_io.cpp): points run so that y
// increases from the first to the last point (flange / gauge side first).
#include "core/profile/builtin_profiles.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "core/numerics/text.h"
#include "core/profile/profile_io.h"

namespace railwear {

namespace {

constexpr double kPi = std::numbers::pi;

// S1002 section boundaries (mm), README §5.
constexpr double kS1002End_mm = 60.0;
constexpr double kS1002AB_mm = 32.15796;
constexpr double kS1002BC_mm = -26.0;
constexpr double kS1002CD_mm = -35.0;
constexpr double kS1002DE_mm = -38.426669071;
constexpr double kS1002EF_mm = -39.764473993;
constexpr double kS1002FG_mm = -49.662510381;
constexpr double kS1002GH_mm = -62.764705882;
constexpr double kS1002Start_mm = -70.0;
// Section H circle: F = AH + sqrt(BH^2 - (S + CH)^2); its end S = -70 = -CH - BH has a vertical
// tangent, so MakeS1002 samples it by angle.
constexpr double kAH = 9.519259302, kBH = 20.5, kCH = 49.5;

// Appends points (mm) to `pts`, skipping a point that repeats the previous one.
void Append(std::vector<Eigen::Vector2d>* pts, double y_mm, double z_mm) {
  const Eigen::Vector2d p(y_mm * 1e-3, z_mm * 1e-3);
  if (!pts->empty() && (p - pts->back()).norm() < 1e-9) return;
  pts->push_back(p);
}

// Number of equal intervals of at most `step` covering `length` (at least 1).
int Intervals(double length, double step) {
  return std::max(1, static_cast<int>(std::ceil(length / step - 1e-9)));
}

// Builds a profile symmetric about y = 0 from its half for y >= 0, given with y increasing from
// y = 0 (first point on the axis).
std::vector<Eigen::Vector2d> MirrorHalf(const std::vector<Eigen::Vector2d>& half) {
  RAILWEAR_CHECK(!half.empty() && half.front().x() == 0.0);
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(2 * half.size());
  for (auto it = half.rbegin(); it + 1 != half.rend(); ++it) pts.emplace_back(-it->x(), it->y());
  pts.insert(pts.end(), half.begin(), half.end());
  return pts;
}

void CheckStep(double step_m, const char* what) {
  if (!(step_m > 0.0) || !std::isfinite(step_m)) {
    throw InputError(
        fmt::format("{}: step = {} m; expected a finite positive point spacing", what, step_m));
  }
}

// Arc of a circle of radius R (mm) with its lowest/highest point at the origin, sampled by angle,
// as a symmetric profile in mm: z = sign * (R - sqrt(R^2 - y^2)).
Profile MakeArc(double radius_m, double sign, const std::string& source) {
  if (!(radius_m > 0.0) || !std::isfinite(radius_m)) {
    throw InputError(
        fmt::format("{}: radius = {} m; expected a finite positive radius", source, radius_m));
  }
  const double r_mm = radius_m * 1e3;
  // Extent: half-angle 80 degrees for R <= 50 mm, otherwise half-width 50 mm.
  constexpr double kMaxHalfAngle_rad = 80.0 * kPi / 180.0;
  constexpr double kHalfWidthLarge_mm = 50.0;
  const double half_angle = r_mm <= 50.0 ? kMaxHalfAngle_rad : std::asin(kHalfWidthLarge_mm / r_mm);
  // Spacing about min(0.05 mm, R * 0.5 deg).
  const double spacing_mm = std::min(0.05, r_mm * 0.5 * kPi / 180.0);
  const int n = Intervals(r_mm * half_angle, spacing_mm);
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(2 * n + 1);
  for (int i = -n; i <= n; ++i) {
    const double phi = half_angle * i / n;
    Append(&pts, r_mm * std::sin(phi), sign * r_mm * (1.0 - std::cos(phi)));
  }
  return Profile(std::move(pts), source);
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Parses a whole string as a finite double; false otherwise.
bool ParseDouble(const std::string& text, double* value) {
  const std::string t = Trim(text);
  if (t.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

}  // namespace

double S1002RadiusIncrease_mm(double S) {
  if (S >= kS1002AB_mm) {  // A
    return 1.364323640 - 0.066666667 * S;
  }
  if (S >= kS1002BC_mm) {  // B
    constexpr double c[9] = {0.0,
                             -3.358537058e-02,
                             1.565681624e-03,
                             -2.810427944e-05,
                             5.844240864e-08,
                             -1.562379023e-08,
                             5.309217349e-15,
                             -5.957839843e-12,
                             2.646656573e-13};
    double f = 0.0;
    for (int k = 8; k >= 0; --k) f = f * S + c[k];
    return f;
  }
  if (S >= kS1002CD_mm) {  // C
    constexpr double c[8] = {-4.320221063e+03, -1.038384026e+03, -1.065501873e+02,
                             -6.051367875,     -2.054332446e-01, -4.169739389e-03,
                             -4.687195829e-05, -2.252755540e-07};
    double f = 0.0;
    for (int k = 7; k >= 0; --k) f = f * S + c[k];
    return f;
  }
  if (S >= kS1002DE_mm) {  // D
    const double u = S + 26.210665;
    return 16.446 - std::sqrt(std::max(0.0, 13.0 * 13.0 - u * u));
  }
  if (S >= kS1002EF_mm) {  // E
    return -93.576667419 - 2.747477419 * S;
  }
  if (S >= kS1002FG_mm) {  // F
    const double u = S + 58.558326413;
    return 8.834924130 + std::sqrt(std::max(0.0, 20.0 * 20.0 - u * u));
  }
  if (S >= kS1002GH_mm) {  // G
    const double u = S + 55.0;
    return 16.0 + std::sqrt(std::max(0.0, 12.0 * 12.0 - u * u));
  }
  // H (S down to -70; clamped to the circle beyond)
  const double u = S + kCH;
  return kAH + std::sqrt(std::max(0.0, kBH * kBH - u * u));
}

Profile MakeS1002(double step_m) {
  CheckStep(step_m, "builtin:S1002");
  const double step_mm = step_m * 1e3;
  std::vector<Eigen::Vector2d> pts;
  // Section H by angle: S = -CH - BH cos(phi), F = AH + BH sin(phi), phi from 0 (S = -70, vertical
  // tangent) to the G/H breakpoint.
  const double phi_end = std::acos(-(kS1002GH_mm + kCH) / kBH);
  const int nh = Intervals(kBH * phi_end, step_mm);
  for (int i = 0; i < nh; ++i) {
    const double phi = phi_end * i / nh;
    Append(&pts, -kCH - kBH * std::cos(phi), kAH + kBH * std::sin(phi));
  }
  // Sections G..A: march in S with an S-step that keeps the arc-length step near step_mm
  // (|dF/dS| <= 2.75 there), landing exactly on every breakpoint.
  const double breaks[] = {kS1002GH_mm, kS1002FG_mm, kS1002EF_mm, kS1002DE_mm,
                           kS1002CD_mm, kS1002BC_mm, kS1002AB_mm, kS1002End_mm};
  for (size_t b = 0; b + 1 < std::size(breaks); ++b) {
    const double s0 = breaks[b], s1 = breaks[b + 1];
    double s = s0;
    Append(&pts, s, S1002RadiusIncrease_mm(s));
    while (s < s1) {
      const double h = 1e-4;
      const double slope =
          (S1002RadiusIncrease_mm(std::min(s + h, s1)) - S1002RadiusIncrease_mm(s)) /
          (std::min(s + h, s1) - s);
      double ds = step_mm / std::sqrt(1.0 + slope * slope);
      // Avoid a sliver interval before the breakpoint.
      if (s + 1.5 * ds >= s1) ds = (s + ds >= s1) ? s1 - s : 0.5 * (s1 - s);
      s = (s1 - s - ds < 1e-9) ? s1 : s + ds;
      Append(&pts, s, S1002RadiusIncrease_mm(s));
    }
  }
  return Profile(std::move(pts), "builtin:S1002");
}

Profile MakeUic60(double step_m) {
  CheckStep(step_m, "builtin:UIC60");
  const double step_mm = step_m * 1e3;
  // Half profile y >= 0 (field side), mm, README §5. Each arc: centre (yc, zc), radius r, z = zc -
  // sqrt(r^2 - (y - yc)^2); sampled by angle between the breakpoints.
  struct Arc {
    double yc, zc, r, y0, y1;
  };
  constexpr double kY1 = 10.228, kY2 = 26.0265, kY3 = 36.000;
  const Arc arcs[] = {{0.0, 300.0, 300.0, 0.0, kY1},
                      {7.500533, 80.127896, 80.0, kY1, kY2},
                      {23.016030, 14.949147, 13.0, kY2, kY3}};
  std::vector<Eigen::Vector2d> half;
  for (const Arc& a : arcs) {
    const double phi0 = std::asin((a.y0 - a.yc) / a.r), phi1 = std::asin((a.y1 - a.yc) / a.r);
    const int n = Intervals(a.r * (phi1 - phi0), step_mm);
    for (int i = 0; i <= n; ++i) {
      const double phi = phi0 + (phi1 - phi0) * i / n;
      // Breakpoints use the nominal y so both arcs meet at the same point.
      const double y = i == 0 ? a.y0 : (i == n ? a.y1 : a.yc + a.r * std::sin(phi));
      const double dy = y - a.yc;
      Append(&half, y, a.zc - std::sqrt(a.r * a.r - dy * dy));
    }
  }
  // 1:20 flank from the end of R13 down to the bottom of the head (kHeadDepth_mm below the crown,
  // as in the Manchester benchmark file).
  constexpr double kHeadDepth_mm = 37.5;
  const Eigen::Vector2d start = half.back() * 1e3;
  const double length = (kHeadDepth_mm - start.y()) * std::sqrt(1.0 + 1.0 / 400.0);
  const int nf = Intervals(length, step_mm);
  for (int i = 1; i <= nf; ++i) {
    const double z = start.y() + (kHeadDepth_mm - start.y()) * i / nf;
    Append(&half, start.x() + (z - start.y()) / 20.0, z);
  }
  half.front().x() = 0.0;
  return Profile(MirrorHalf(half), "builtin:UIC60");
}

Profile MakeCircle(double radius_m, BodyRole role) {
  const std::string source = fmt::format("circle:{:g}", radius_m * 1e3);
  return MakeArc(radius_m, role == BodyRole::kWheel ? -1.0 : 1.0, source);
}

Profile MakeGroove(double radius_m, BodyRole role) {
  const std::string source = fmt::format("groove:{:g}", radius_m * 1e3);
  return MakeArc(radius_m, role == BodyRole::kRail ? -1.0 : 1.0, source);
}

CantTransform CalcCantTransform(const Profile& rail, double ratio) {
  if (!std::isfinite(ratio)) {
    throw InputError(
        fmt::format("{}: cant ratio = {}; expected a finite number", rail.source(), ratio));
  }
  // Transformed() turns +y toward +z for a positive angle; the gauge side (-y) must go down
  // (+z), so the angle is negative.
  const double angle = -std::atan(ratio);
  const Profile turned = rail.Transformed(angle, Eigen::Vector2d::Zero());
  // New highest point: minimum z of the spline, found on the points then refined by a parabola
  // through the neighbouring knots' spline values.
  const auto& p = turned.points();
  int imin = 0;
  for (int i = 1; i < turned.size(); ++i) {
    if (p[i].y() < p[imin].y()) imin = i;
  }
  Eigen::Vector2d top = p[imin];
  if (imin > 0 && imin + 1 < turned.size()) {
    // Golden-section search for min z(s) on [s_{i-1}, s_{i+1}].
    double a = turned.KnotS(imin - 1), b = turned.KnotS(imin + 1);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 80; ++it) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      if (turned.Position(c).y() < turned.Position(d).y()) {
        b = d;
      } else {
        a = c;
      }
    }
    top = turned.Position(0.5 * (a + b));
  }
  return CantTransform{angle, -top};
}

Profile ApplyCant(const Profile& rail, double ratio) {
  const CantTransform cant = CalcCantTransform(rail, ratio);
  return rail.Transformed(cant.angle_rad, cant.shift_m);
}

double ParseCant(const std::string& text) {
  const std::string t = Trim(text);
  const auto bad = [&]() {
    return InputError(fmt::format(
        "cant '{}': expected \"0\" or a ratio \"1:N\" with N > 0 (e.g. \"1:40\")", text));
  };
  const auto colon = t.find(':');
  if (colon == std::string::npos) {
    double v;
    if (ParseDouble(t, &v) && v == 0.0) return 0.0;
    throw bad();
  }
  double num, den;
  if (!ParseDouble(t.substr(0, colon), &num) || !ParseDouble(t.substr(colon + 1), &den) ||
      !(den > 0.0) || num < 0.0) {
    throw bad();
  }
  return num / den;
}

Profile LoadProfileSpec(const std::string& spec, BodyRole role, const std::string& base_dir) {
  const std::string t = Trim(spec);
  const auto colon = t.find(':');
  const std::string kind = colon == std::string::npos ? std::string() : Lower(t.substr(0, colon));
  if (kind == "builtin") {
    const std::string name = Lower(Trim(t.substr(colon + 1)));
    Profile p;
    if (name == "s1002") {
      p = MakeS1002();
    } else if (name == "uic60") {
      p = MakeUic60();
    } else {
      throw InputError(fmt::format(
          "profile spec '{}': unknown built-in '{}'; expected builtin:S1002 or builtin:UIC60", spec,
          name));
    }
    p.set_source(spec);
    return p;
  }
  if (kind == "circle" || kind == "groove") {
    double r_mm;
    if (!ParseDouble(t.substr(colon + 1), &r_mm) || !(r_mm > 0.0)) {
      throw InputError(fmt::format(
          "profile spec '{}': radius '{}' is not valid; expected a finite positive radius in mm "
          "(e.g. {}:10)",
          spec, Trim(t.substr(colon + 1)), kind));
    }
    Profile p = kind == "circle" ? MakeCircle(r_mm * 1e-3, role) : MakeGroove(r_mm * 1e-3, role);
    p.set_source(spec);
    return p;
  }
  if (t.empty()) {
    throw InputError(
        "profile spec is empty; expected builtin:S1002, builtin:UIC60, circle:R, "
        "groove:R or a profile file path");
  }
  std::filesystem::path path(t);
  if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
  return ReadProfileFile(path.string()).profile;
}

}  // namespace railwear
