// Displacement curves: CSV reading and writing, eq. 4's prediction. See displacement_curves.h.
#include "calibration/displacement_curves.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/contact/seed_kernel.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "core/numerics/text.h"
#include "core/numerics/units.h"

namespace railwear {
namespace {

constexpr std::string_view kMarker = "railwear displacement curves v1";
constexpr double kNmPerN = 1e-9;  // nm/N -> m/N
constexpr const char* kColumns = "load,path,distance_mm,w_nm_per_N";

std::vector<std::string> SplitCommas(std::string_view s) {
  std::vector<std::string> out;
  size_t i = 0;
  while (true) {
    const size_t j = s.find(',', i);
    out.push_back(Trim(s.substr(i, j == std::string_view::npos ? std::string_view::npos : j - i)));
    if (j == std::string_view::npos) return out;
    i = j + 1;
  }
}

bool Vanishes(CurveLoad load, CurvePath path) {
  return (load == CurveLoad::kAxial && path == CurvePath::kArc) ||
         (load == CurveLoad::kCircumferential && path == CurvePath::kAxis);
}

// Metadata values: the number after "key =", checked.
double MetadataNumber(const std::string& file, int line, const std::string& key,
                      const std::string& value, bool (*ok)(double), const char* expected) {
  const auto v = ParseFiniteDouble(value);
  if (!v || !ok(*v)) {
    throw InputError(
        fmt::format("{}:{}: metadata '{}' = '{}': expected {}", file, line, key, value, expected));
  }
  return *v;
}

}  // namespace

std::string_view ToString(CurveBody v) {
  switch (v) {
    case CurveBody::kFlat:
      return "flat";
    case CurveBody::kConvex:
      return "convex";
    case CurveBody::kConcave:
      return "concave";
  }
  return "?";
}
std::string_view ToString(CurveLoad v) {
  switch (v) {
    case CurveLoad::kNormal:
      return "normal";
    case CurveLoad::kAxial:
      return "axial";
    case CurveLoad::kCircumferential:
      return "circumferential";
  }
  return "?";
}
std::string_view ToString(CurvePath v) {
  switch (v) {
    case CurvePath::kArc:
      return "arc";
    case CurvePath::kAxis:
      return "axis";
  }
  return "?";
}
std::optional<CurveBody> CurveBodyFromString(std::string_view s) {
  for (CurveBody v : {CurveBody::kFlat, CurveBody::kConvex, CurveBody::kConcave}) {
    if (ToString(v) == s) return v;
  }
  return std::nullopt;
}
std::optional<CurveLoad> CurveLoadFromString(std::string_view s) {
  for (CurveLoad v : {CurveLoad::kNormal, CurveLoad::kAxial, CurveLoad::kCircumferential}) {
    if (ToString(v) == s) return v;
  }
  return std::nullopt;
}
std::optional<CurvePath> CurvePathFromString(std::string_view s) {
  for (CurvePath v : {CurvePath::kArc, CurvePath::kAxis}) {
    if (ToString(v) == s) return v;
  }
  return std::nullopt;
}

int CurvatureSign(CurveBody body) {
  switch (body) {
    case CurveBody::kConcave:
      return +1;
    case CurveBody::kConvex:
      return -1;
    case CurveBody::kFlat:
      return 0;
  }
  return 0;
}

DisplacementCurves ReadDisplacementCurves(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw InputError(fmt::format("{}: cannot read displacement curves: no such file", path));
  }
  if (fs::is_directory(path, ec)) {
    throw InputError(fmt::format("{}: cannot read displacement curves: it is a directory", path));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the displacement curves file", path));

  DisplacementCurves out;
  out.path = path;
  std::optional<CurveBody> body;
  std::optional<double> radius_mm, e_mpa, nu;
  bool marker = false, header = false;
  int col_load = -1, col_path = -1, col_distance = -1, col_w = -1;
  size_t num_columns = 0;
  std::set<std::string> keys;
  int last_meta_line = 1;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    const std::string t = Trim(text);
    if (t.empty()) continue;
    if (t[0] == '#') {
      const std::string body_text = Trim(std::string_view(t).substr(1));
      if (!marker) {
        if (body_text != kMarker) {
          throw InputError(
              fmt::format("{}:{}: first line is '{}'; expected '# {}'", path, number, t, kMarker));
        }
        marker = true;
        continue;
      }
      if (header) continue;  // comments among the data rows
      const size_t eq = body_text.find('=');
      if (eq == std::string::npos) continue;  // a plain comment
      const std::string key = Trim(std::string_view(body_text).substr(0, eq));
      const std::string value = Trim(std::string_view(body_text).substr(eq + 1));
      last_meta_line = number;
      if (!keys.insert(key).second) {
        throw InputError(
            fmt::format("{}:{}: metadata '{}' given twice; expected it once", path, number, key));
      }
      if (key == "body") {
        body = CurveBodyFromString(value);
        if (!body) {
          throw InputError(
              fmt::format("{}:{}: metadata 'body' = '{}': expected flat, convex or "
                          "concave",
                          path, number, value));
        }
      } else if (key == "radius_mm") {
        radius_mm = MetadataNumber(
            path, number, key, value, [](double v) { return v >= 1e-3 && v <= 1e6; },
            "a radius > 0 in mm, in [0.001, 1e6]");
      } else if (key == "E_MPa") {
        // The range the fit bears (1e308 gave an infinite residual): as in scenes.
        e_mpa = MetadataNumber(
            path, number, key, value, [](double v) { return v >= 1.0 && v <= 1e7; },
            "Young's modulus > 0 in MPa, in [1, 1e7]");
      } else if (key == "nu") {
        nu = MetadataNumber(
            path, number, key, value, [](double v) { return v >= 0.0 && v < 0.5; },
            "Poisson's ratio in [0, 0.5)");
      } else {
        out.metadata.emplace_back(key, value);
      }
      continue;
    }
    if (!marker) {
      throw InputError(
          fmt::format("{}:{}: first line is '{}'; expected '# {}'", path, number, t, kMarker));
    }
    const std::vector<std::string> cols = SplitCommas(t);
    if (!header) {
      for (size_t i = 0; i < cols.size(); ++i) {
        if (cols[i] == "load") col_load = static_cast<int>(i);
        if (cols[i] == "path") col_path = static_cast<int>(i);
        if (cols[i] == "distance_mm") col_distance = static_cast<int>(i);
        if (cols[i] == "w_nm_per_N") col_w = static_cast<int>(i);
      }
      for (const auto& [name, col] : {std::pair<const char*, int>{"load", col_load},
                                      {"path", col_path},
                                      {"distance_mm", col_distance},
                                      {"w_nm_per_N", col_w}}) {
        if (col < 0) {
          throw InputError(
              fmt::format("{}:{}: header '{}' has no column '{}'; expected the "
                          "columns {} (any order, extra columns allowed)",
                          path, number, t, name, kColumns));
        }
      }
      num_columns = cols.size();
      header = true;
      // The metadata is complete once the header is reached.
      if (!body) {
        throw InputError(
            fmt::format("{}:{}: metadata 'body' is missing: expected a line "
                        "'# body = flat|convex|concave' before the header",
                        path, number));
      }
      if (*body != CurveBody::kFlat && !radius_mm) {
        throw InputError(
            fmt::format("{}:{}: metadata 'radius_mm' is missing: expected "
                        "'# radius_mm = R' for a {} body",
                        path, number, ToString(*body)));
      }
      if (!e_mpa || !nu) {
        throw InputError(
            fmt::format("{}:{}: metadata '{}' is missing: expected '# E_MPa = ...' "
                        "and '# nu = ...' before the header",
                        path, number, !e_mpa ? "E_MPa" : "nu"));
      }
      continue;
    }
    if (cols.size() != num_columns) {
      throw InputError(fmt::format("{}:{}: '{}' has {} column(s); expected {} as in the header",
                                   path, number, t, cols.size(), num_columns));
    }
    DisplacementPoint p;
    p.line = number;
    const auto load = CurveLoadFromString(cols[col_load]);
    if (!load) {
      throw InputError(
          fmt::format("{}:{}: column 'load' is '{}': expected normal, axial or "
                      "circumferential",
                      path, number, cols[col_load]));
    }
    const auto curve_path = CurvePathFromString(cols[col_path]);
    if (!curve_path) {
      throw InputError(fmt::format("{}:{}: column 'path' is '{}': expected arc or axis", path,
                                   number, cols[col_path]));
    }
    if (Vanishes(*load, *curve_path)) {
      throw InputError(fmt::format(
          "{}:{}: load {} seen on path {}: eq. 4 predicts no displacement there, so it cannot "
          "be fitted; expected normal loads on either path, axial loads on the axis, "
          "circumferential loads on the arc",
          path, number, ToString(*load), ToString(*curve_path)));
    }
    const auto d = ParseFiniteDouble(cols[col_distance]);
    if (!d) {
      throw InputError(
          fmt::format("{}:{}: column 'distance_mm' is '{}': expected a finite "
                      "number in mm",
                      path, number, cols[col_distance]));
    }
    if (!(*d > 0.0)) {
      throw InputError(
          fmt::format("{}:{}: column 'distance_mm' is {}: expected a positive "
                      "distance from the load point",
                      path, number, cols[col_distance]));
    }
    if (*curve_path == CurvePath::kArc && *body != CurveBody::kFlat &&
        *d > std::numbers::pi * *radius_mm) {
      throw InputError(
          fmt::format("{}:{}: column 'distance_mm' is {}: expected an arc length of "
                      "at most half the circumference, pi R = {:.6g} mm",
                      path, number, cols[col_distance], std::numbers::pi * *radius_mm));
    }
    const auto w = ParseFiniteDouble(cols[col_w]);
    if (!w) {
      throw InputError(
          fmt::format("{}:{}: column 'w_nm_per_N' is '{}': expected a finite "
                      "number in nm/N",
                      path, number, cols[col_w]));
    }
    p.load = *load;
    p.path = *curve_path;
    p.distance_m = *d * kMm;
    p.w_m_per_N = *w * kNmPerN;
    out.points.push_back(p);
  }
  if (in.bad()) throw InputError(fmt::format("{}: error while reading the file", path));
  if (!marker) {
    throw InputError(fmt::format("{}:1: the file is empty; expected '# {}'", path, kMarker));
  }
  if (!header) {
    throw InputError(
        fmt::format("{}:{}: no header line; expected the columns {} after the "
                    "metadata",
                    path, last_meta_line, kColumns));
  }
  if (out.points.empty()) {
    throw InputError(
        fmt::format("{}:{}: no data rows after the header; expected at least one "
                    "'{}' row",
                    path, number, kColumns));
  }
  out.body = *body;
  out.radius_m = out.body == CurveBody::kFlat ? 0.0 : *radius_mm * kMm;
  out.material.youngs_modulus_Pa = *e_mpa * 1e6;
  out.material.poisson_ratio = *nu;
  return out;
}

void WriteDisplacementCurves(const DisplacementCurves& curves, const std::string& path) {
  std::ostringstream os;
  os << "# " << kMarker << "\n";
  os << "# body = " << ToString(curves.body) << "\n";
  if (curves.body != CurveBody::kFlat) {
    os << fmt::format("# radius_mm = {:.10g}\n", curves.radius_m / kMm);
  }
  os << fmt::format("# E_MPa = {:.10g}\n", curves.material.youngs_modulus_Pa / 1e6);
  os << fmt::format("# nu = {:.10g}\n", curves.material.poisson_ratio);
  for (const auto& [key, value] : curves.metadata) os << "# " << key << " = " << value << "\n";
  os << kColumns << "\n";
  for (const DisplacementPoint& p : curves.points) {
    os << fmt::format("{},{},{:.10g},{:.10g}\n", ToString(p.load), ToString(p.path),
                      p.distance_m / kMm, p.w_m_per_N / kNmPerN);
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << os.str();
  out.flush();
  if (!out) throw InputError(fmt::format("{}: cannot write the displacement curves file", path));
}

double SeedKernelDisplacement(const InfluenceConstants& c, CurveBody body, double radius_m,
                              const Material& material, CurveLoad load, CurvePath path,
                              double distance_m) {
  RAILWEAR_CHECK(distance_m > 0.0);
  RAILWEAR_CHECK(!Vanishes(load, path));
  double rho = distance_m, dn2 = 0.0, d_t = distance_m;
  if (path == CurvePath::kArc && body != CurveBody::kFlat) {
    RAILWEAR_CHECK(radius_m > 0.0);
    const double theta = distance_m / radius_m;
    const double half_sin = std::sin(0.5 * theta);
    rho = 2.0 * radius_m * half_sin;
    dn2 = rho * rho * half_sin * half_sin;
    d_t = radius_m * std::sin(theta);
  }
  const double k_d = SeedKernelKd(material);
  const InfluenceConstantSet set = c.ForBody(CurvatureSign(body));
  if (load == CurveLoad::kNormal) {
    const double k_f = SeedKernelKf(material, k_d);
    return (set.c_f * k_f + set.c_z * k_d * dn2 / (rho * rho)) / rho;
  }
  const double c_t = SeedKernelCt(set, CurvatureSign(body));
  return c_t * k_d * d_t / (rho * rho);
}

double HalfSpaceDisplacement(const Material& material, CurveLoad load, double distance_m) {
  const double g = material.ShearModulus();
  const double nu = material.poisson_ratio;
  if (load == CurveLoad::kNormal) return (1.0 - nu) / (2.0 * std::numbers::pi * g * distance_m);
  return (1.0 - 2.0 * nu) / (4.0 * std::numbers::pi * g * distance_m);
}

double HalfSpaceEquivalentCf(double nu) { return 4.0 * (1.0 - nu) * (1.0 - nu) / (3.0 - 4.0 * nu); }

double HalfSpaceEquivalentCt(double nu) { return 2.0 * (1.0 - 2.0 * nu) * (1.0 - nu); }

}  // namespace railwear
