// Conformal contact reference cases as quarter FEM models: geometry, deck, solves per mesh
// level, and the patch measures from the nodal contact pressure. See fem_contact.h.
#include "calibration/fem/fem_contact.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "calibration/fem/ccx_deck.h"
#include "calibration/fem/fem_mesh.h"
#include "calibration/fem/frd_file.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear {
namespace {

constexpr double kMPa = 1e6;  // MPa -> Pa
// Half-angle of the circular profiles (railwear's built-in circles and grooves: 80 degrees).
constexpr double kProfileHalfAngle_rad = 80.0 * std::numbers::pi / 180.0;
// The edge fit uses the nodes with kFitLow < p/p_max < kFitHigh: below, the penalty's pressure
// tail past the edge; above, the flat top where p^2 is not yet linear in r^2 for a
// non-Hertzian patch.
constexpr double kFitLow = 0.1;
constexpr double kFitHigh = 0.8;
// A node is on a symmetry plane when its coordinate is this close to 0 [m] (gmsh writes 16
// digits, ccx 5 significant digits in E12.5: 1e-9 m is far below any element).
constexpr double kOnPlane_m = 1e-9;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The groove body's profile circle in the cross-section x = 0 (zc, R) [mm]; the size field
// measures arc length and depth about it.
struct Circle2 {
  double zc_mm = 0.0;
  double r_mm = 0.0;
};
Circle2 GrooveCircle(const FemContactOptions& o) {
  const double rg = o.groove_radius_m / kMm;
  return o.contact_case == FemContactCase::kWheelInGroove ? Circle2{rg, rg} : Circle2{-rg, rg};
}
// The slave (rail) profile: groove (case A) or convex head (case B).
FemContactFrame SlaveFrame(const FemContactOptions& o) {
  if (o.contact_case == FemContactCase::kWheelInGroove) {
    return {o.groove_radius_m, o.groove_radius_m};
  }
  return {-o.convex_radius_m, o.convex_radius_m};
}

double ArcLength(const FemContactFrame& f, const Eigen::Vector3d& p) {
  if (f.radius_m <= 0.0) return p.y();
  return f.radius_m * std::atan2(p.y(), std::abs(p.z() - f.centre_z_m));
}

// p^2 = A + B r^2 fitted on kFitLow < p/p_max < kFitHigh; the r where it reaches 0, or nullopt.
std::optional<double> FitEdge(const std::vector<std::pair<double, double>>& r_p, double p_max) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [r, p] : r_p) {
    if (!(p > kFitLow * p_max && p < kFitHigh * p_max)) continue;
    const double x = r * r, y = p * p;
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  if (n < 2) return std::nullopt;
  const double det = n * sxx - sx * sx;
  if (!(det > 0.0)) return std::nullopt;
  const double slope = (n * sxy - sx * sy) / det;
  const double intercept = (sy - slope * sx) / n;
  if (!(slope < 0.0) || !(intercept > 0.0)) return std::nullopt;
  return std::sqrt(-intercept / slope);
}

// The outermost r of the nodes in contact (the fall-back when a fit fails).
double OutermostContact(const std::vector<std::pair<double, double>>& r_p) {
  double r_max = 0.0;
  for (const auto& [r, p] : r_p) {
    if (p > 0.0) r_max = std::max(r_max, r);
  }
  return r_max;
}

// Quadratic triangle shape functions at (r, s).
std::array<double, 6> Shape6(double r, double s) {
  const double t = 1.0 - r - s;
  return {t * (2 * t - 1), r * (2 * r - 1), s * (2 * s - 1), 4 * t * r, 4 * r * s, 4 * s * t};
}
// Their derivatives d/dr and d/ds.
void Shape6Derivatives(double r, double s, std::array<double, 6>* dr, std::array<double, 6>* ds) {
  const double t = 1.0 - r - s;
  *dr = {-(4 * t - 1), 4 * r - 1, 0.0, 4 * (t - r), 4 * s, -4 * s};
  *ds = {-(4 * t - 1), 0.0, 4 * s - 1, -4 * r, 4 * r, 4 * (t - s)};
}

// 6-point Gauss rule on the reference triangle (degree 4; weights sum to 1/2).
struct TriPoint {
  double r, s, w;
};
constexpr TriPoint kTriRule[] = {
    {0.445948490915965, 0.445948490915965, 0.111690794839005},
    {0.108103018168070, 0.445948490915965, 0.111690794839005},
    {0.445948490915965, 0.108103018168070, 0.111690794839005},
    {0.091576213509771, 0.091576213509771, 0.054975871827661},
    {0.816847572980459, 0.091576213509771, 0.054975871827661},
    {0.091576213509771, 0.816847572980459, 0.054975871827661},
};

// Corner and mid-side positions (0-based, ccx C3D10 order) of the 6-node triangle of face 1..4:
// corners as TetFaceCorners, then the mid-side nodes of edges 0-1, 1-2, 2-0 of the face.
std::array<int, 6> TetFaceNodes(int face) {
  switch (face) {
    case 1:
      return {0, 1, 2, 4, 5, 6};
    case 2:
      return {0, 3, 1, 7, 8, 4};
    case 3:
      return {1, 3, 2, 8, 9, 5};
    case 4:
      return {2, 3, 0, 9, 7, 6};
  }
  throw std::logic_error("tetrahedron faces are 1..4");
}

// Names of the geometry's physical groups.
constexpr const char* kWheel = "WHEEL";
constexpr const char* kRail = "RAIL";
constexpr const char* kWheelContact = "WCONT";
constexpr const char* kRailContact = "RCONT";
constexpr const char* kWheelTop = "WTOP";
constexpr const char* kRailBottom = "RBOT";
constexpr const char* kSymmetry[] = {"WSYMX", "RSYMX", "WSYMY", "RSYMY"};

}  // namespace

std::string_view ToString(FemContactCase v) {
  return v == FemContactCase::kWheelInGroove ? "wheel_in_groove" : "rail_in_wheel_groove";
}

std::optional<FemContactCase> FemContactCaseFromString(std::string_view s) {
  if (s == "wheel_in_groove") return FemContactCase::kWheelInGroove;
  if (s == "rail_in_wheel_groove") return FemContactCase::kRailInWheelGroove;
  return std::nullopt;
}

std::string_view ToString(FemContactStatus v) {
  switch (v) {
    case FemContactStatus::kOk:
      return "ok";
    case FemContactStatus::kNoContact:
      return "no_contact";
    case FemContactStatus::kPatchAtZoneEdge:
      return "patch_at_zone_edge";
    case FemContactStatus::kFitFailed:
      return "fit_failed";
  }
  return "?";
}

FemContactOptions DefaultFemContactOptions(FemContactCase contact_case) {
  FemContactOptions o;
  o.contact_case = contact_case;
  if (contact_case == FemContactCase::kWheelInGroove) {
    // Patch about 2.8 x 4.4 mm (half axes): the zone is ~1.25 times that.
    o.convex_radius_m = 10e-3;
    o.groove_radius_m = 10.1e-3;
    o.load_N = 10e3;
    o.zone_x_m = 3.6e-3;
    o.zone_s_m = 5.4e-3;
    o.mesh_sizes_m = {0.7e-3, 0.5e-3, 0.35e-3};
  } else {
    // Patch about 4.3 x 10 mm.
    o.convex_radius_m = 15e-3;
    o.groove_radius_m = 15.1e-3;
    o.load_N = 50e3;
    o.zone_x_m = 5.4e-3;
    o.zone_s_m = 12e-3;
    o.mesh_sizes_m = {0.9e-3, 0.6e-3, 0.45e-3};
  }
  return o;
}

FemContactOptions ResolvedFemContactOptions(const FemContactOptions& options) {
  FemContactOptions o = options;
  const FemContactOptions d = DefaultFemContactOptions(o.contact_case);
  if (o.zone_x_m == 0.0) o.zone_x_m = d.zone_x_m;
  if (o.zone_s_m == 0.0) o.zone_s_m = d.zone_s_m;
  if (o.zone_depth_m == 0.0) o.zone_depth_m = 0.25 * o.zone_x_m;
  if (o.mesh_sizes_m.empty()) o.mesh_sizes_m = d.mesh_sizes_m;
  return o;
}

bool FemContactOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error != nullptr) *error = message;
    return false;
  };
  auto mm = [](double v) { return v / kMm; };
  if (!(convex_radius_m > 0.0)) {
    return fail(fmt::format("convex radius {:g} mm: expected > 0", mm(convex_radius_m)));
  }
  if (!(groove_radius_m > convex_radius_m)) {
    return fail(fmt::format("groove radius {:g} mm: expected > the convex radius {:g} mm",
                            mm(groove_radius_m), mm(convex_radius_m)));
  }
  if (!(depth_m > 0.0)) return fail(fmt::format("depth {:g} mm: expected > 0", mm(depth_m)));
  if (!(rolling_radius_m > 2.0 * depth_m)) {
    return fail(fmt::format("rolling radius {:g} mm: expected > 2 x depth ({:g} mm)",
                            mm(rolling_radius_m), mm(2.0 * depth_m)));
  }
  if (!(load_N > 0.0)) return fail(fmt::format("load {:g} N: expected > 0", load_N));
  if (!(material.youngs_modulus_Pa > 0.0) ||
      !(material.poisson_ratio >= 0.0 && material.poisson_ratio < 0.5)) {
    return fail(fmt::format("material E = {:g} MPa, nu = {:g}: expected E > 0, 0 <= nu < 0.5",
                            material.youngs_modulus_Pa / kMPa, material.poisson_ratio));
  }
  // The wheel's shoulder (case A) sits 1.2 Rc above the contact; the rail head's side goes
  // down to 1.5 Rc (case B): the bodies must be deeper than that.
  const double shoulder = (contact_case == FemContactCase::kWheelInGroove ? 1.2 : 1.5) *
                          std::max(convex_radius_m, groove_radius_m);
  if (!(depth_m > shoulder + 1e-3)) {
    return fail(fmt::format("depth {:g} mm: expected > {:g} mm (the profile's height + 1 mm)",
                            mm(depth_m), mm(shoulder + 1e-3)));
  }
  if (!(width_m > 2.0 * groove_radius_m + 2e-3)) {
    return fail(fmt::format("width {:g} mm: expected > 2 x groove radius + 2 mm ({:g} mm)",
                            mm(width_m), mm(2.0 * groove_radius_m + 2e-3)));
  }
  if (!(zone_x_m >= 0.0) || !(zone_s_m >= 0.0) || !(zone_depth_m >= 0.0)) {
    return fail("contact zone sizes: expected >= 0 (0 takes the case default)");
  }
  const double zx = zone_x_m > 0 ? zone_x_m : DefaultFemContactOptions(contact_case).zone_x_m;
  const double zs = zone_s_m > 0 ? zone_s_m : DefaultFemContactOptions(contact_case).zone_s_m;
  if (!(length_m > 4.0 * zx)) {
    return fail(
        fmt::format("length {:g} mm: expected > 4 x zone_x ({:g} mm)", mm(length_m), mm(4.0 * zx)));
  }
  if (!(zs < 0.9 * kProfileHalfAngle_rad * convex_radius_m)) {
    return fail(fmt::format("zone_s {:g} mm: expected < {:g} mm (inside the profile arcs)", mm(zs),
                            mm(0.9 * kProfileHalfAngle_rad * convex_radius_m)));
  }
  for (double h : mesh_sizes_m) {
    if (!(h > 0.0) || !(h <= max_element_m)) {
      return fail(fmt::format("mesh size {:g} mm: expected > 0 and <= the largest element {:g} mm",
                              mm(h), mm(max_element_m)));
    }
  }
  if (!(mesh_growth > 0.0 && mesh_growth <= 2.0)) {
    return fail(fmt::format("mesh growth {:g}: expected in (0, 2]", mesh_growth));
  }
  if (!(penalty_Pa_per_m > 0.0)) {
    return fail(fmt::format("penalty {:g} MPa/mm: expected > 0", penalty_Pa_per_m / kMPa * kMm));
  }
  if (!(initial_overlap_m >= 0.0)) {
    return fail(fmt::format("initial overlap {:g} mm: expected >= 0", mm(initial_overlap_m)));
  }
  if (!(spring_N_per_m > 0.0)) {
    return fail(fmt::format("spring {:g} N/mm: expected > 0", spring_N_per_m * kMm));
  }
  if (sectors < 2) return fail(fmt::format("sectors {}: expected >= 2", sectors));
  if (threads_per_job < 1) {
    return fail(fmt::format("threads_per_job {}: expected >= 1", threads_per_job));
  }
  if (!(timeout_s >= 0.0)) return fail(fmt::format("timeout {:g} s: expected >= 0", timeout_s));
  std::error_code ec;
  if (work_dir.empty() || !std::filesystem::is_directory(work_dir, ec)) {
    return fail(fmt::format("work directory '{}': expected an existing folder", work_dir));
  }
  return true;
}

FemContactPatch CalcFemContactPatch(const FemContactSurface& surface, const FemContactFrame& frame,
                                    int sectors) {
  RAILWEAR_CHECK(surface.positions_m.size() == surface.pressure_Pa.size());
  FemContactPatch patch;
  const size_t n = surface.positions_m.size();
  for (size_t i = 0; i < n; ++i) {
    patch.p_max_Pa = std::max(patch.p_max_Pa, surface.pressure_Pa[i]);
    if (surface.pressure_Pa[i] > 0.0) ++patch.contact_nodes;
  }
  if (!(patch.p_max_Pa > 0.0)) {
    patch.status = FemContactStatus::kNoContact;
    patch.message = "no slave node carries a positive contact pressure";
    return patch;
  }
  // Resultants and lumped nodal areas.
  std::vector<double> lumped(n, 0.0);
  for (const auto& t : surface.triangles) {
    for (const TriPoint& q : kTriRule) {
      std::array<double, 6> dr, ds;
      Shape6Derivatives(q.r, q.s, &dr, &ds);
      const std::array<double, 6> sh = Shape6(q.r, q.s);
      Eigen::Vector3d tr = Eigen::Vector3d::Zero(), ts = Eigen::Vector3d::Zero();
      double p = 0.0;
      for (int k = 0; k < 6; ++k) {
        tr += dr[k] * surface.positions_m[t[k]];
        ts += ds[k] * surface.positions_m[t[k]];
        p += sh[k] * surface.pressure_Pa[t[k]];
      }
      const Eigen::Vector3d area_vector = tr.cross(ts) * q.w;
      patch.normal_force_N += 4.0 * p * area_vector.norm();
      patch.vertical_force_N += 4.0 * p * std::abs(area_vector.z());
    }
    // Lumped areas: the four flat sub-triangles, a third of each to its nodes.
    static constexpr int kSub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
    for (const auto& sub : kSub) {
      const Eigen::Vector3d& a = surface.positions_m[t[sub[0]]];
      const double area =
          0.5 *
          (surface.positions_m[t[sub[1]]] - a).cross(surface.positions_m[t[sub[2]]] - a).norm();
      for (int k : sub) lumped[t[k]] += area / 3.0;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (surface.pressure_Pa[i] > 0.0) patch.area_nodes_m2 += 4.0 * lumped[i];
  }
  // Patch coordinates (x, s) of the nodes that carry pressure or lie next to the patch.
  std::vector<std::pair<double, double>> axis_x, axis_s;
  std::vector<Eigen::Vector2d> xs(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = surface.positions_m[i];
    xs[i] = {p.x(), ArcLength(frame, p)};
    if (std::abs(p.y()) < kOnPlane_m) axis_x.emplace_back(xs[i].x(), surface.pressure_Pa[i]);
    if (std::abs(p.x()) < kOnPlane_m) axis_s.emplace_back(xs[i].y(), surface.pressure_Pa[i]);
  }
  const auto a = FitEdge(axis_x, patch.p_max_Pa);
  const auto b = FitEdge(axis_s, patch.p_max_Pa);
  patch.half_length_x_m = a.value_or(OutermostContact(axis_x));
  patch.half_width_s_m = b.value_or(OutermostContact(axis_s));
  if (!a || !b || !(patch.half_length_x_m > 0.0) || !(patch.half_width_s_m > 0.0)) {
    patch.status = FemContactStatus::kFitFailed;
    patch.message = fmt::format("too few nodes on the {} symmetry line for the edge fit",
                                !a ? "y = 0" : "x = 0");
    patch.area_m2 = patch.area_nodes_m2;
    return patch;
  }
  const double ax = patch.half_length_x_m, bs = patch.half_width_s_m;
  const double dphi = 0.5 * std::numbers::pi / sectors;
  std::vector<std::vector<std::pair<double, double>>> in_sector(static_cast<size_t>(sectors));
  for (size_t i = 0; i < n; ++i) {
    const double u = xs[i].x() / ax, v = xs[i].y() / bs;
    const double phi = std::atan2(v, u);
    const int k = std::clamp(static_cast<int>(phi / dphi), 0, sectors - 1);
    in_sector[static_cast<size_t>(k)].emplace_back(std::hypot(u, v), surface.pressure_Pa[i]);
  }
  std::vector<std::optional<double>> edges;
  double sum = 0.0;
  int fitted = 0;
  for (const auto& nodes : in_sector) {
    edges.push_back(FitEdge(nodes, patch.p_max_Pa));
    if (edges.back()) {
      sum += *edges.back();
      ++fitted;
    }
  }
  // A sector with too few nodes for a fit takes the mean edge of the others.
  const double mean_edge = fitted > 0 ? sum / fitted : 1.0;
  double area_quarter = 0.0;
  for (const auto& e : edges) {
    const double rho = e.value_or(mean_edge);
    patch.sector_edges.push_back(rho);
    area_quarter += 0.5 * rho * rho * dphi;
  }
  patch.area_m2 = 4.0 * ax * bs * area_quarter;
  return patch;
}

std::string FemContactGeo(const FemContactOptions& o, double mesh_size_m) {
  const bool a = o.contact_case == FemContactCase::kWheelInGroove;
  const double rc = o.convex_radius_m / kMm, rg = o.groove_radius_m / kMm;
  const double w2 = 0.5 * o.width_m / kMm, d = o.depth_m / kMm, r0 = o.rolling_radius_m / kMm;
  const double phi = 0.5 * o.length_m / o.rolling_radius_m;  // the wheel segment's half angle
  const double sa = std::sin(kProfileHalfAngle_rad), ca = std::cos(kProfileHalfAngle_rad);
  std::string geo = fmt::format(
      "// railwear fem-reference contact case {} (quarter x >= 0, y >= 0; mm).\n"
      "// Cross-sections in the plane x = 0: the wheel (points 1xx) is revolved about the axle\n"
      "// (y axis through z = r0), the rail (points 2xx) extruded along x. Curve 100/200 (the\n"
      "// profile arcs) become the contact faces ww[2]/rr[2]; the other lateral faces follow the\n"
      "// loops' curves.\n"
      "SetFactory(\"OpenCASCADE\");\n",
      ToString(o.contact_case));
  // Section polygons: the first two points bound the profile arc about `centre`.
  struct Section {
    std::vector<std::pair<double, double>> points;  // (y, z)
    std::pair<double, double> centre;
  };
  Section wheel, rail;
  if (a) {
    wheel.points = {{0, 0}, {rc * sa, rc * (1 - ca)}, {rc * sa, 1.2 * rc}, {w2, 1.2 * rc}, {w2, d},
                    {0, d}};
    wheel.centre = {0, rc};
    rail.points = {{0, 0}, {rg * sa, rg * (1 - ca)}, {w2, rg * (1 - ca)}, {w2, -d}, {0, -d}};
    rail.centre = {0, rg};
  } else {
    wheel.points = {{0, 0}, {rg * sa, -rg * (1 - ca)}, {w2, -rg * (1 - ca)}, {w2, d}, {0, d}};
    wheel.centre = {0, -rg};
    rail.points = {{0, 0}, {rc, -rc}, {rc, -1.5 * rc}, {w2, -1.5 * rc}, {w2, -d}, {0, -d}};
    rail.centre = {0, -rc};
  }
  auto section = [&geo](const Section& s, int base) {
    const int np = static_cast<int>(s.points.size());
    for (int i = 0; i < np; ++i) {
      geo += fmt::format("Point({}) = {{0, {:.12g}, {:.12g}}};\n", base + i, s.points[i].first,
                         s.points[i].second);
    }
    geo += fmt::format("Point({}) = {{0, {:.12g}, {:.12g}}};\n", base + 50, s.centre.first,
                       s.centre.second);
    geo += fmt::format("Circle({}) = {{{}, {}, {}}};\n", base, base, base + 50, base + 1);
    std::string loop = std::to_string(base);
    for (int i = 1; i < np; ++i) {
      geo += fmt::format("Line({}) = {{{}, {}}};\n", base + i, base + i, base + (i + 1) % np);
      loop += fmt::format(", {}", base + i);
    }
    geo += fmt::format("Curve Loop({}) = {{{}}};\nPlane Surface({}) = {{{}}};\n", base, loop, base,
                       base);
    return np;
  };
  const int nw = section(wheel, 100);
  const int nr = section(rail, 200);
  geo += fmt::format(
      "ww[] = Extrude {{ {{0, 1, 0}}, {{0, 0, {:.12g}}}, {:.12g} }} {{ Surface{{100}}; }};\n"
      "rr[] = Extrude {{ {:.12g}, 0, 0 }} {{ Surface{{200}}; }};\n",
      r0, -phi, 0.5 * o.length_m / kMm);
  // The wheel's far face comes from the section's second-to-last line (to (0, d)), its y = 0
  // face from the last one; likewise for the rail.
  geo += fmt::format(
      "Physical Volume(\"{}\") = {{ww[1]}};\nPhysical Volume(\"{}\") = {{rr[1]}};\n"
      "Physical Surface(\"{}\") = {{ww[2]}};\nPhysical Surface(\"{}\") = {{rr[2]}};\n"
      "Physical Surface(\"{}\") = {{ww[{}]}};\nPhysical Surface(\"WSYMY\") = {{ww[{}]}};\n"
      "Physical Surface(\"{}\") = {{rr[{}]}};\nPhysical Surface(\"RSYMY\") = {{rr[{}]}};\n"
      "Physical Surface(\"WSYMX\") = {{100}};\nPhysical Surface(\"RSYMX\") = {{200}};\n",
      kWheel, kRail, kWheelContact, kRailContact, kWheelTop, nw, nw + 1, kRailBottom, nr, nr + 1);
  // Size field: h in the zone, growing with the distance outside it. Zone coordinates about
  // the groove's circle: x, arc length s, depth |r - R|; max(0, u) = (u + |u|)/2.
  const Circle2 g = GrooveCircle(o);
  const std::string dz = fmt::format("(z - ({:.12g}))", g.zc_mm);
  const std::string radius = fmt::format("Sqrt(y * y + {} * {})", dz, dz);
  const std::string arc = fmt::format("{:.12g} * Atan(y / (Fabs{} + 1e-9))", g.r_mm, dz);
  const std::string depth = fmt::format("Fabs({} - {:.12g})", radius, g.r_mm);
  auto outside = [](const std::string& u, double limit) {
    const std::string v = fmt::format("({} - {:.12g})", u, limit);
    return fmt::format("(({} + Fabs{}) / 2)", v, v);
  };
  const std::string ox = outside("x", o.zone_x_m / kMm);
  const std::string os = outside(arc, o.zone_s_m / kMm);
  const std::string od = outside(depth, o.zone_depth_m / kMm);
  geo += fmt::format(
      "// Element size: h in the zone (x <= {:g}, s <= {:g}, depth <= {:g} mm), + growth x the\n"
      "// distance outside it, up to the largest element.\n"
      "Field[1] = MathEval;\n"
      "Field[1].F = \"{:.12g} + {:.12g} * Sqrt({} * {} + {} * {} + {} * {})\";\n"
      "Background Field = 1;\n"
      "Mesh.MeshSizeExtendFromBoundary = 0;\n"
      "Mesh.MeshSizeFromPoints = 0;\n"
      "Mesh.MeshSizeMax = {:.12g};\n"
      "Mesh.ElementOrder = 2;\n"
      "Mesh.SaveAll = 0;\n",
      o.zone_x_m / kMm, o.zone_s_m / kMm, o.zone_depth_m / kMm, mesh_size_m / kMm, o.mesh_growth,
      ox, ox, os, os, od, od, o.max_element_m / kMm);
  return geo;
}

std::string FemContactDeck(const FemContactOptions& o, const std::string& mesh_file,
                           const std::vector<int>& top_nodes, int first_spring_id) {
  RAILWEAR_CHECK(!top_nodes.empty());
  // Far-face pressure whose vertical resultant on the quarter is load/4: the face is a cylinder
  // of radius r0 - D over the half angle phi and half width W/2.
  const double phi = 0.5 * o.length_m / o.rolling_radius_m;
  const double r_top_mm = (o.rolling_radius_m - o.depth_m) / kMm;
  const double pressure_MPa = 0.25 * o.load_N / (0.5 * o.width_m / kMm * r_top_mm * std::sin(phi));
  CcxDeck deck;
  deck.Comment(fmt::format("railwear fem-reference contact case {}: quarter model, mm N MPa",
                           ToString(o.contact_case)))
      .Include(mesh_file)
      .ElasticMaterial("STEEL", o.material.youngs_modulus_Pa / kMPa, o.material.poisson_ratio)
      .SolidSection("EALL", "STEEL");
  std::string springs = "*ELEMENT, TYPE=SPRING1, ELSET=ESPRING\n";
  for (size_t i = 0; i < top_nodes.size(); ++i) {
    springs += fmt::format("{}, {}\n", first_spring_id + static_cast<int>(i), top_nodes[i]);
  }
  springs += fmt::format("*SPRING, ELSET=ESPRING\n3\n{:.12g}",
                         o.spring_N_per_m * kMm / static_cast<double>(top_nodes.size()));
  deck.Comment("weak springs to the ground on the wheel's far face (its free vertical motion)")
      .Raw(springs)
      .Comment("frictionless penalty contact, slope K in MPa/mm; slave: the rail's face")
      .Raw(fmt::format("*SURFACE INTERACTION, NAME=SI\n"
                       "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{:.12g}\n"
                       "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSR, SW",
                       o.penalty_Pa_per_m / kMPa * kMm))
      .Comment("symmetry planes x = 0 and y = 0; the rail's bottom clamped")
      .Boundary("WSYMX", 1, 1)
      .Boundary("RSYMX", 1, 1)
      .Boundary("WSYMY", 2, 2)
      .Boundary("RSYMY", 2, 2)
      .Boundary(kRailBottom, 1, 3)
      .BeginStaticStep("INC=200", "1., 1.")
      .Comment(fmt::format("far-face pressure: vertical resultant {:g} N on the quarter",
                           0.25 * o.load_N))
      .Raw(fmt::format("*DLOAD\nSTOP, P, {:.12g}", pressure_MPa))
      .NodeFile("U")
      .Raw("*CONTACT FILE\nCDIS, CSTR")
      .EndStep();
  return deck.Text();
}

namespace {

// A copy of the mesh with the wheel's nodes moved down by `shift_mm`.
FemMesh ShiftWheel(const FemMesh& mesh, double shift_mm) {
  const std::vector<int> wheel_nodes = mesh.NodeSet(kWheel);
  const std::set<int> wheel(wheel_nodes.begin(), wheel_nodes.end());
  FemMesh out;
  for (int id : mesh.node_ids()) {
    Eigen::Vector3d p = mesh.Position_mm(id);
    if (wheel.count(id) != 0) p.z() -= shift_mm;
    out.AddNode(id, p);
  }
  for (const MeshElement& e : mesh.elements()) out.AddElement(e);
  for (const auto& [name, group] : mesh.groups()) out.AddGroup(group);
  return out;
}

// The faces of a contact surface group with a corner node inside the contact zone.
std::vector<ElementFace> ZoneFaces(const FemMesh& mesh, const char* group,
                                   const FemContactOptions& o) {
  const Circle2 g = GrooveCircle(o);
  const FemContactFrame frame{g.zc_mm, g.r_mm};
  std::map<int, const MeshElement*> by_id;
  for (const MeshElement* e : mesh.SolidElements()) by_id[e->id] = e;
  std::vector<ElementFace> out;
  for (const ElementFace& f : mesh.FaceSurface(group)) {
    const MeshElement& e = *by_id.at(f.element);
    for (int c : TetFaceCorners(f.face)) {
      const Eigen::Vector3d& p = mesh.Position_mm(e.nodes[static_cast<size_t>(c)]);
      if (p.x() <= o.zone_x_m / kMm && ArcLength(frame, p) <= o.zone_s_m / kMm) {
        out.push_back(f);
        break;
      }
    }
  }
  return out;
}

}  // namespace

FemContactSurface FemContactSlaveSurface(const FemMesh& mesh, const std::vector<ElementFace>& faces,
                                         const FrdFile& frd) {
  const FrdResultBlock* contact = frd.Find("CONTACT");
  if (contact == nullptr) {
    throw std::runtime_error(frd.path + ": no CONTACT block (ccx wrote no contact results)");
  }
  const int cpress = contact->ComponentIndex("CPRESS");
  if (cpress < 0) throw std::runtime_error(frd.path + ": CONTACT block without CPRESS");
  std::map<int, const MeshElement*> by_id;
  for (const MeshElement* e : mesh.SolidElements()) by_id[e->id] = e;
  FemContactSurface s;
  std::map<int, int> index;  // node id -> surface index
  for (const ElementFace& f : faces) {
    const MeshElement& e = *by_id.at(f.element);
    std::array<int, 6> t;
    const std::array<int, 6> local = TetFaceNodes(f.face);
    for (int k = 0; k < 6; ++k) {
      const int id = e.nodes[static_cast<size_t>(local[static_cast<size_t>(k)])];
      auto [it, inserted] = index.emplace(id, static_cast<int>(s.positions_m.size()));
      if (inserted) {
        s.positions_m.push_back(mesh.Position_mm(id) * kMm);
        const int row = contact->Row(id);
        s.pressure_Pa.push_back(row < 0 ? 0.0 : std::max(0.0, contact->Value(row, cpress)) * kMPa);
      }
      t[static_cast<size_t>(k)] = it->second;
    }
    s.triangles.push_back(t);
  }
  return s;
}

namespace {

int CountIterations(const std::string& log_path) {
  std::ifstream in(log_path);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    if (line.rfind(" iteration ", 0) == 0) ++n;
  }
  return n;
}

}  // namespace

FemContactResult RunFemContact(const FemContactOptions& options, const FemPrograms& programs) {
  namespace fs = std::filesystem;
  std::string error;
  if (!options.IsValid(&error)) throw InputError("FEM contact case: " + error);
  const auto start = std::chrono::steady_clock::now();
  FemContactResult result;
  result.options = ResolvedFemContactOptions(options);
  result.options.progress = nullptr;
  const FemContactOptions& o = result.options;
  auto progress = [&options](const std::string& message) {
    if (options.progress) options.progress(message);
  };
  const fs::path dir(o.work_dir);
  for (size_t level = 0; level < o.mesh_sizes_m.size(); ++level) {
    FemContactLevel L;
    L.mesh_size_m = o.mesh_sizes_m[level];
    const std::string name = fmt::format("level{}", level + 1);
    WriteWorkFile((dir / (name + ".geo")).string(), FemContactGeo(o, L.mesh_size_m));
    progress(fmt::format("{}: meshing (gmsh, h = {:g} mm)", name, L.mesh_size_m / kMm));
    L.mesh_time_s = RunGmsh(programs.gmsh, o.work_dir, name + ".geo", name + ".msh", 1, o.timeout_s)
                        .wall_time_s;
    const FemMesh mesh =
        ShiftWheel(ReadGmshMesh((dir / (name + ".msh")).string()), o.initial_overlap_m / kMm);
    for (const char* group : {kWheel, kRail, kWheelContact, kRailContact, kWheelTop, kRailBottom,
                              kSymmetry[0], kSymmetry[1], kSymmetry[2], kSymmetry[3]}) {
      if (mesh.FindGroup(group) == nullptr) {
        throw std::runtime_error(fmt::format("{}.msh: no physical group {}", name, group));
      }
    }
    CcxMeshSets sets;
    for (const char* group : kSymmetry) sets.node_sets.emplace_back(group, mesh.NodeSet(group));
    sets.node_sets.emplace_back(kRailBottom, mesh.NodeSet(kRailBottom));
    const std::vector<ElementFace> slave = ZoneFaces(mesh, kRailContact, o);
    const std::vector<ElementFace> master = ZoneFaces(mesh, kWheelContact, o);
    sets.surfaces = {{"SR", slave}, {"SW", master}, {"STOP", mesh.FaceSurface(kWheelTop)}};
    L.slave_faces = slave.size();
    L.master_faces = master.size();
    L.nodes = mesh.NumNodes();
    L.elements = mesh.SolidElements().size();
    int max_id = 0;
    for (const MeshElement& e : mesh.elements()) max_id = std::max(max_id, e.id);
    const std::vector<int> top = mesh.NodeSet(kWheelTop);
    WriteWorkFile((dir / (name + "_mesh.inp")).string(), CcxMeshText(mesh, sets));
    WriteWorkFile((dir / (name + ".inp")).string(),
                  FemContactDeck(o, name + "_mesh.inp", top, max_id + 1));
    progress(
        fmt::format("{}: solving (ccx, {} nodes, {} slave faces)", name, L.nodes, L.slave_faces));
    const ProgramResult solved =
        RunCcx(programs.ccx, o.work_dir, name, o.threads_per_job, o.timeout_s);
    L.solve_time_s = solved.wall_time_s;
    L.iterations = CountIterations(solved.log_path);
    const FrdFile frd = ReadFrd((dir / (name + ".frd")).string());
    // Spring force: k_node * sum of the far-face nodes' vertical displacement (x 4).
    if (const FrdResultBlock* disp = frd.Find("DISP")) {
      double sum_uz = 0.0;
      for (int id : top) sum_uz += FrdDisplacement(*disp, id).z();
      L.spring_force_N = 4.0 * o.spring_N_per_m * kMm / static_cast<double>(top.size()) * sum_uz;
    }
    L.patch =
        CalcFemContactPatch(FemContactSlaveSurface(mesh, slave, frd), SlaveFrame(o), o.sectors);
    if (L.patch.status == FemContactStatus::kOk &&
        (L.patch.half_length_x_m > o.zone_x_m || L.patch.half_width_s_m > o.zone_s_m)) {
      L.patch.status = FemContactStatus::kPatchAtZoneEdge;
      L.patch.message = fmt::format(
          "the patch ({:.3f} x {:.3f} mm) reaches past the contact zone ({:g} x {:g} mm): enlarge "
          "zone_x_mm / zone_s_mm",
          L.patch.half_length_x_m / kMm, L.patch.half_width_s_m / kMm, o.zone_x_m / kMm,
          o.zone_s_m / kMm);
    }
    progress(fmt::format(
        "{}: solved in {:.1f} s ({} iterations): area {:.2f} mm2, p_max {:.1f} MPa", name,
        L.solve_time_s, L.iterations, L.patch.area_m2 / (kMm * kMm), L.patch.p_max_Pa / kMPa));
    result.levels.push_back(std::move(L));
  }
  result.wall_time_s = Seconds(start);
  return result;
}

double EstimateFemContactNodes(const FemContactOptions& o, double mesh_size_m) {
  // Nodes per unit of the integral and body, fitted to docs/fem_contact_cases.md (the header).
  constexpr double kNodesPerUnit = 15.47;
  return 2.0 * kNodesPerUnit *
         GradedMeshIntegral({0.5 * o.length_m, 0.5 * o.width_m, o.depth_m},
                            {o.zone_x_m, o.zone_s_m, o.zone_depth_m}, mesh_size_m, o.mesh_growth,
                            o.max_element_m);
}

}  // namespace railwear
