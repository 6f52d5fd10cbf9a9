// The displacement experiment as a quarter FEM model: geometry, mesh, one ccx solve per load,
// curve extraction. See fem_displacement.h.
#include "calibration/fem/fem_displacement.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "calibration/fem/ccx_deck.h"
#include "calibration/fem/fem_mesh.h"
#include "calibration/fem/frd_file.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear {
namespace {

constexpr double kMPa = 1e6;  // MPa -> Pa
// The full load [N] of every case. The model is linear; w is divided by it. The quarter model
// carries a quarter of it.
constexpr double kFullLoad_N = 1000.0;
// Mesh files name their groups; these are the names the .geo gives them.
constexpr const char* kLoad = "LOAD";
constexpr const char* kTop = "TOP";
constexpr const char* kSymX = "SYMX";
constexpr const char* kSymY = "SYMY";
constexpr const char* kBottom = "BOTTOM";
constexpr const char* kEnd = "END";
constexpr const char* kSide = "SIDE";

// A file that gmsh or ccx wrote and that cannot be read is their failure (exit code 1), not bad
// input: the readers' InputError becomes a runtime error.
template <class Read>
auto ReadProgramOutput(Read read) {
  try {
    return read();
  } catch (const InputError& e) {
    throw std::runtime_error(e.what());
  }
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Geometry of the quarter model in mm, for the checks and the path extraction.
struct Quarter {
  CurveBody body;
  double r = 0.0;    // R [mm]
  double l2 = 0.0;   // half length
  double w2 = 0.0;   // half width
  double d = 0.0;    // depth below O
  double tol = 0.0;  // a coordinate this close to a plane or surface is on it [mm]
};

Quarter MakeQuarter(const FemDisplacementOptions& o, const FemBodySize& s) {
  Quarter q;
  q.body = o.body;
  q.r = o.radius_m / kMm;
  q.l2 = 0.5 * s.length_m / kMm;
  q.w2 = 0.5 * s.width_m / kMm;
  q.d = s.depth_m / kMm;
  // gmsh writes coordinates to 16 digits; nodes off a surface are at least a fraction of the
  // smallest element away from it.
  q.tol = std::min(1e-3 * o.mesh_size_at_load_m / kMm, 1e-7 * std::max({q.l2, q.w2, q.d}) + 1e-9);
  return q;
}

// The surface of the curved body: its centre (0, 0, zc) in the cross-section.
double CentreZ(const Quarter& q) { return q.body == CurveBody::kConvex ? -q.r : q.r; }

// Distance from O along the arc path [mm] of a node in the plane x = 0 on the top surface.
double ArcDistance(const Quarter& q, const Eigen::Vector3d& p) {
  switch (q.body) {
    case CurveBody::kFlat:
      return p.y();
    case CurveBody::kConvex:
      return q.r * std::atan2(p.y(), p.z() + q.r);
    case CurveBody::kConcave:
      return q.r * std::atan2(p.y(), q.r - p.z());
  }
  return 0.0;
}

// The inward unit normal at a top-surface node.
Eigen::Vector3d InwardNormal(const Quarter& q, const Eigen::Vector3d& p) {
  if (q.body == CurveBody::kFlat) return {0.0, 0.0, -1.0};
  const Eigen::Vector3d from_centre(0.0, p.y(), p.z() - CentreZ(q));  // in the cross-section
  // Convex: the body is inside the circle; concave: outside.
  return q.body == CurveBody::kConvex ? Eigen::Vector3d(-from_centre.normalized())
                                      : Eigen::Vector3d(from_centre.normalized());
}

bool OnTopSurface(const Quarter& q, const Eigen::Vector3d& p) {
  if (q.body == CurveBody::kFlat) return std::abs(p.z()) <= q.tol;
  const double rho = std::hypot(p.y(), p.z() - CentreZ(q));
  return std::abs(rho - q.r) <= std::max(q.tol, 1e-9 * q.r);
}

// Throws std::runtime_error when a group is missing or has a node off its plane or surface:
// the .geo's physical groups did not land on the faces they name.
void CheckGroups(const FemMesh& mesh, const Quarter& q) {
  auto check = [&](const char* name, auto on) {
    const std::vector<int> ids = mesh.NodeSet(name);
    if (ids.empty()) {
      throw std::runtime_error(fmt::format("the mesh has no nodes in group {}", name));
    }
    for (int id : ids) {
      const Eigen::Vector3d& p = mesh.Position_mm(id);
      if (!on(p)) {
        throw std::runtime_error(
            fmt::format("mesh group {}: node {} at ({}, {}, {}) mm is off "
                        "its face",
                        name, id, p.x(), p.y(), p.z()));
      }
    }
  };
  const double tol = 1e-6 * std::max({q.l2, q.w2, q.d, q.r});
  check(kLoad, [&](const Eigen::Vector3d& p) { return p.norm() <= tol; });
  if (mesh.NodeSet(kLoad).size() != 1) throw std::runtime_error("mesh group LOAD is not one node");
  check(kSymX, [&](const Eigen::Vector3d& p) { return std::abs(p.x()) <= tol; });
  check(kSymY, [&](const Eigen::Vector3d& p) { return std::abs(p.y()) <= tol; });
  check(kBottom, [&](const Eigen::Vector3d& p) { return std::abs(p.z() + q.d) <= tol; });
  check(kEnd, [&](const Eigen::Vector3d& p) { return std::abs(p.x() - q.l2) <= tol; });
  const double side_y = q.body == CurveBody::kConvex ? q.r : q.w2;
  check(kSide, [&](const Eigen::Vector3d& p) { return std::abs(p.y() - side_y) <= tol; });
  Quarter loose = q;
  loose.tol = tol;
  check(kTop, [&](const Eigen::Vector3d& p) { return OnTopSurface(loose, p); });
}

// The mesh's symmetry boundary conditions and the nodal force of one load on the quarter model.
void AddLoadCase(CurveLoad load, CcxDeck* deck) {
  const double quarter = 0.25 * kFullLoad_N;
  switch (load) {
    case CurveLoad::kNormal:  // symmetric about x = 0 and y = 0; presses along -z
      deck->Boundary(kSymX, 1, 1).Boundary(kSymY, 2, 2);
      deck->BeginStaticStep().Cload(kLoad, 3, -quarter);
      break;
    case CurveLoad::kAxial:  // antisymmetric about x = 0, symmetric about y = 0; along +x
      deck->Boundary(kSymX, 2, 3).Boundary(kSymY, 2, 2);
      deck->BeginStaticStep().Cload(kLoad, 1, quarter);
      break;
    case CurveLoad::kCircumferential:  // symmetric about x = 0, antisymmetric about y = 0; +y
      deck->Boundary(kSymX, 1, 1).Boundary(kSymY, 1, 1).Boundary(kSymY, 3, 3);
      deck->BeginStaticStep().Cload(kLoad, 2, quarter);
      break;
  }
}

std::vector<const char*> ClampedGroups(const FemDisplacementOptions& o) {
  if (o.supports == FemSupports::kBottom) return {kBottom};
  return {kBottom, kEnd, kSide};
}

std::string SupportsText(const FemDisplacementOptions& o, const Quarter& q) {
  const std::string bottom = fmt::format("bottom face z = -{:g} mm clamped (u = 0)", q.d);
  if (o.supports == FemSupports::kBottom) return bottom + "; every other face free";
  const double side_y = q.body == CurveBody::kConvex ? q.r : q.w2;
  return fmt::format("{}, ends x = +-{:g} mm and sides y = +-{:g} mm clamped; the top free", bottom,
                     q.l2, side_y);
}

std::string GeometryText(const Quarter& q) {
  switch (q.body) {
    case CurveBody::kFlat:
      return fmt::format(
          "flat block {:g} x {:g} mm (x by y), {:g} mm deep; load at the top "
          "centre",
          2 * q.l2, 2 * q.w2, q.d);
    case CurveBody::kConvex:
      return fmt::format(
          "convex: half-cylinder R = {:g} mm (axis x) on a block {:g} mm wide, "
          "{:g} mm long, bottom {:g} mm below the load point at the top",
          q.r, 2 * q.r, 2 * q.l2, q.d);
    case CurveBody::kConcave:
      return fmt::format(
          "concave: block {:g} x {:g} mm (x by y) with a semicircular groove "
          "R = {:g} mm (axis x) in its top face; load at the groove bottom, "
          "bottom face {:g} mm below it",
          2 * q.l2, 2 * q.w2, q.r, q.d);
  }
  return "";
}

}  // namespace

std::string_view ToString(FemSupports v) {
  switch (v) {
    case FemSupports::kBottom:
      return "bottom";
    case FemSupports::kFarFaces:
      return "far_faces";
  }
  return "?";
}

std::optional<FemSupports> FemSupportsFromString(std::string_view s) {
  for (FemSupports v : {FemSupports::kBottom, FemSupports::kFarFaces}) {
    if (ToString(v) == s) return v;
  }
  return std::nullopt;
}

FemBodySize DefaultFemBodySize(CurveBody body, double radius_m) {
  // 200 mm along the axis and 100 mm below the load point: 8 and 4 times the sampled 25 mm,
  // so the supports act as a nearly constant offset on the normal load over the sampled
  // distances. A convex body is 2R wide (the rail head) and 2R deep: the half-cylinder on a
  // block R tall. Under a tangential load a convex body sways as a whole (its curves are not a
  // local response plus an offset, and the sway grows with the height: README), so it is kept
  // short. A concave body is at least 200 mm wide and 100 mm wider than its groove.
  FemBodySize s;
  s.length_m = 200.0 * kMm;
  switch (body) {
    case CurveBody::kFlat:
      s.width_m = 200.0 * kMm;
      s.depth_m = 100.0 * kMm;
      break;
    case CurveBody::kConvex:
      s.width_m = 2.0 * radius_m;
      s.depth_m = 2.0 * radius_m;
      break;
    case CurveBody::kConcave:
      s.width_m = std::max(200.0 * kMm, 2.0 * radius_m + 100.0 * kMm);
      s.depth_m = 100.0 * kMm;
      break;
  }
  return s;
}

bool FemDisplacementOptions::IsValid(std::string* error) const {
  auto fail = [error](std::string message) {
    if (error != nullptr) *error = std::move(message);
    return false;
  };
  if (body != CurveBody::kFlat && !(radius_m > 0.0 && std::isfinite(radius_m))) {
    return fail(fmt::format("radius {} mm: expected a radius > 0 for a {} body", radius_m / kMm,
                            ToString(body)));
  }
  if (!(material.youngs_modulus_Pa > 0.0 && std::isfinite(material.youngs_modulus_Pa))) {
    return fail(fmt::format("E {} MPa: expected > 0", material.youngs_modulus_Pa / kMPa));
  }
  if (!(material.poisson_ratio >= 0.0 && material.poisson_ratio < 0.5)) {
    return fail(fmt::format("nu {}: expected a number in [0, 0.5)", material.poisson_ratio));
  }
  if (loads.empty()) return fail("loads: expected at least one of normal, axial, circumferential");
  for (size_t i = 0; i < loads.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (loads[i] == loads[j]) {
        return fail(
            fmt::format("loads: '{}' given twice; expected each load once", ToString(loads[i])));
      }
    }
  }
  for (double v : {length_m, width_m, depth_m}) {
    if (!(v >= 0.0 && std::isfinite(v))) {
      return fail(
          fmt::format("body size {} mm: expected a length > 0 (or 0 for the default)", v / kMm));
    }
  }
  if (!(mesh_size_at_load_m > 0.0 && std::isfinite(mesh_size_at_load_m))) {
    return fail(
        fmt::format("mesh size at the load {} mm: expected > 0", mesh_size_at_load_m / kMm));
  }
  if (!(mesh_growth > 0.0 && mesh_growth <= 2.0)) {
    return fail(
        fmt::format("mesh growth {}: expected a number in (0, 2] (element size grows by "
                    "that many mm per mm from the load)",
                    mesh_growth));
  }
  if (!(max_element_m >= mesh_size_at_load_m && std::isfinite(max_element_m))) {
    return fail(
        fmt::format("largest element {} mm: expected at least the mesh size at the load "
                    "({} mm)",
                    max_element_m / kMm, mesh_size_at_load_m / kMm));
  }
  if (!(min_distance_m > 0.0 && max_distance_m > min_distance_m && std::isfinite(max_distance_m))) {
    return fail(fmt::format("distances {} to {} mm: expected 0 < min_distance < max_distance",
                            min_distance_m / kMm, max_distance_m / kMm));
  }
  const FemBodySize s = FemBodySizeUsed(*this);
  if (s.length_m < 4.0 * max_distance_m) {
    return fail(
        fmt::format("body length {} mm: expected at least 4 max_distance = {} mm, so the "
                    "axis path stays well inside the body",
                    s.length_m / kMm, 4.0 * max_distance_m / kMm));
  }
  if (body == CurveBody::kFlat && s.width_m < 4.0 * max_distance_m) {
    return fail(
        fmt::format("body width {} mm: expected at least 4 max_distance = {} mm, so the "
                    "arc path stays well inside the body",
                    s.width_m / kMm, 4.0 * max_distance_m / kMm));
  }
  if (body == CurveBody::kConcave && !(s.width_m > 2.0 * radius_m)) {
    return fail(fmt::format("body width {} mm: expected more than the groove's width 2R = {} mm",
                            s.width_m / kMm, 2.0 * radius_m / kMm));
  }
  if (body == CurveBody::kConvex && !(s.depth_m > radius_m)) {
    return fail(
        fmt::format("body depth {} mm: expected more than R = {} mm (the half-cylinder "
                    "stands on a block)",
                    s.depth_m / kMm, radius_m / kMm));
  }
  if (jobs < 1 || threads_per_job < 1) {
    return fail(fmt::format("jobs {}, threads per job {}: expected at least 1 each", jobs,
                            threads_per_job));
  }
  if (!(timeout_s >= 0.0)) return fail(fmt::format("timeout {} s: expected >= 0", timeout_s));
  std::error_code ec;
  if (work_dir.empty() || !std::filesystem::is_directory(work_dir, ec)) {
    return fail(fmt::format("work directory '{}': expected an existing folder", work_dir));
  }
  return true;
}

std::string FemDisplacementGeo(const FemDisplacementOptions& o, const FemBodySize& size) {
  const Quarter q = MakeQuarter(o, size);
  std::string geo = fmt::format(
      "// railwear fem-reference: quarter model (x >= 0, y >= 0) of the {} body, in mm.\n"
      "// Cross-section in the plane x = 0, extruded along x; the load point O is point 1.\n"
      "SetFactory(\"OpenCASCADE\");\n"
      "R = {}; W2 = {}; D = {}; L2 = {};\n",
      ToString(o.body), q.r, q.w2, q.d, q.l2);
  // Curve 1 is the top surface's section (it becomes out[2]); the lateral surfaces come out of
  // Extrude in the order of the loop's curves.
  std::vector<std::string> lateral;
  switch (o.body) {
    case CurveBody::kFlat:
      geo +=
          "Point(1) = {0, 0, 0}; Point(2) = {0, W2, 0}; Point(3) = {0, W2, -D};\n"
          "Point(4) = {0, 0, -D};\n"
          "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
          "Curve Loop(1) = {1, 2, 3, 4};\n";
      lateral = {kTop, kSide, kBottom, kSymY};
      break;
    case CurveBody::kConvex:
      geo +=
          "Point(1) = {0, 0, 0}; Point(2) = {0, R, -R}; Point(3) = {0, R, -D};\n"
          "Point(4) = {0, 0, -D}; Point(5) = {0, 0, -R};\n"
          "Circle(1) = {1, 5, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
          "Curve Loop(1) = {1, 2, 3, 4};\n";
      lateral = {kTop, kSide, kBottom, kSymY};
      break;
    case CurveBody::kConcave:
      geo +=
          "Point(1) = {0, 0, 0}; Point(2) = {0, R, R}; Point(3) = {0, W2, R};\n"
          "Point(4) = {0, W2, -D}; Point(5) = {0, 0, -D}; Point(6) = {0, 0, R};\n"
          "Circle(1) = {1, 6, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};\n"
          "Line(5) = {5, 1};\n"
          "Curve Loop(1) = {1, 2, 3, 4, 5};\n";
      lateral = {kTop, "TOPFLAT", kSide, kBottom, kSymY};
      break;
  }
  geo +=
      "Plane Surface(1) = {1};\n"
      "out[] = Extrude {L2, 0, 0} { Surface{1}; };\n"
      "Physical Volume(\"BODY\") = {out[1]};\n"
      "Physical Point(\"LOAD\") = {1};\n"
      "Physical Surface(\"SYMX\") = {1};\n"
      "Physical Surface(\"END\") = {out[0]};\n";
  for (size_t i = 0; i < lateral.size(); ++i) {
    geo += fmt::format("Physical Surface(\"{}\") = {{out[{}]}};\n", lateral[i], i + 2);
  }
  geo += fmt::format(
      "// Element size h = h0 + growth * r, r the distance from O, up to the largest element.\n"
      "Field[1] = MathEval;\n"
      "Field[1].F = \"{} + {} * Sqrt(x * x + y * y + z * z)\";\n"
      "Background Field = 1;\n"
      "Mesh.MeshSizeExtendFromBoundary = 0;\n"
      "Mesh.MeshSizeFromPoints = 0;\n"
      "Mesh.MeshSizeFromCurvature = 12;  // at least 12 elements per full circle\n"
      "Mesh.MeshSizeMax = {};\n"
      "Mesh.ElementOrder = 2;\n"
      "Mesh.SaveAll = 0;\n",
      o.mesh_size_at_load_m / kMm, o.mesh_growth, o.max_element_m / kMm);
  return geo;
}

FemDisplacementResult RunFemDisplacement(const FemDisplacementOptions& o,
                                         const FemPrograms& programs) {
  namespace fs = std::filesystem;
  std::string error;
  if (!o.IsValid(&error)) throw InputError("FEM displacement experiment: " + error);
  const auto start = std::chrono::steady_clock::now();
  std::mutex progress_mutex;
  auto progress = [&](const std::string& message) {
    if (!o.progress) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    o.progress(message);
  };

  FemDisplacementResult result;
  FemDisplacementSummary& summary = result.summary;
  summary.body_size = FemBodySizeUsed(o);
  const Quarter q = MakeQuarter(o, summary.body_size);

  // 1. Geometry and mesh.
  const fs::path dir(o.work_dir);
  WriteWorkFile((dir / "body.geo").string(), FemDisplacementGeo(o, summary.body_size));
  progress("meshing (gmsh)");
  const ProgramResult meshed =
      RunGmsh(programs.gmsh, o.work_dir, "body.geo", "body.msh", 1, o.timeout_s);
  summary.mesh_time_s = meshed.wall_time_s;
  const FemMesh mesh = ReadProgramOutput([&] { return ReadGmshMesh((dir / "body.msh").string()); });
  CheckGroups(mesh, q);
  summary.nodes = mesh.NumNodes();
  summary.elements = mesh.SolidElements().size();

  CcxMeshSets sets;
  for (const char* name : {kLoad, kSymX, kSymY, kBottom, kEnd, kSide}) {
    sets.node_sets.push_back({name, mesh.NodeSet(name)});
  }
  WriteWorkFile((dir / "mesh.inp").string(), CcxMeshText(mesh, sets));

  // 2. One deck and one ccx run per load, `jobs` at a time.
  std::vector<std::string> jobs;
  for (CurveLoad load : o.loads) {
    CcxDeck deck;
    deck.Comment(fmt::format("railwear fem-reference: {} load on the quarter model, mm N MPa",
                             ToString(load)))
        .Include("mesh.inp")
        .ElasticMaterial("BODY", o.material.youngs_modulus_Pa / kMPa, o.material.poisson_ratio)
        .SolidSection("EALL", "BODY");
    for (const char* group : ClampedGroups(o)) deck.Boundary(group, 1, 3);
    AddLoadCase(load, &deck);
    deck.NodeFile("U").EndStep();
    const std::string job(ToString(load));
    WriteWorkFile((dir / (job + ".inp")).string(), deck.Text());
    jobs.push_back(job);
  }
  std::vector<double> solve_times(jobs.size(), 0.0);
  std::vector<std::exception_ptr> failures(jobs.size());
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  auto worker = [&]() {
    for (size_t i = next++; i < jobs.size() && !failed; i = next++) {
      try {
        progress(fmt::format("solving {} load (ccx, {} nodes)", jobs[i], summary.nodes));
        solve_times[i] =
            RunCcx(programs.ccx, o.work_dir, jobs[i], o.threads_per_job, o.timeout_s).wall_time_s;
        progress(fmt::format("{} load solved in {:.1f} s", jobs[i], solve_times[i]));
      } catch (...) {
        failures[i] = std::current_exception();
        failed = true;  // start no further solve
      }
    }
  };
  const size_t num_workers = std::min(jobs.size(), static_cast<size_t>(o.jobs));
  std::vector<std::thread> workers;
  for (size_t w = 1; w < num_workers; ++w) workers.emplace_back(worker);
  worker();
  for (std::thread& t : workers) t.join();
  for (const std::exception_ptr& f : failures) {
    if (f) std::rethrow_exception(f);
  }

  // 3. Curves: every top-surface node on a path within the distance range.
  const std::vector<int> top = mesh.NodeSet(kTop);
  const double arc_end_mm = o.body == CurveBody::kFlat ? q.w2 : 0.5 * std::numbers::pi * q.r;
  const double min_mm = o.min_distance_m / kMm, max_mm = o.max_distance_m / kMm;
  DisplacementCurves& curves = result.curves;
  curves.body = o.body;
  curves.radius_m = o.body == CurveBody::kFlat ? 0.0 : o.radius_m;
  curves.material = o.material;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const CurveLoad load = o.loads[i];
    const FrdFile frd =
        ReadProgramOutput([&] { return ReadFrd((dir / (jobs[i] + ".frd")).string()); });
    const FrdResultBlock* disp = frd.Find("DISP", 1);
    if (disp == nullptr) {
      throw std::runtime_error(
          fmt::format("{}: ccx wrote no DISP block", (dir / (jobs[i] + ".frd")).string()));
    }
    summary.solve_time_s.emplace_back(load, solve_times[i]);
    for (CurvePath path : {CurvePath::kArc, CurvePath::kAxis}) {
      if ((load == CurveLoad::kAxial && path == CurvePath::kArc) ||
          (load == CurveLoad::kCircumferential && path == CurvePath::kAxis)) {
        continue;  // zero by (anti)symmetry: no data for a fit
      }
      std::vector<DisplacementPoint> points;
      for (int id : top) {
        const Eigen::Vector3d& p = mesh.Position_mm(id);
        double distance_mm = 0.0;
        if (path == CurvePath::kArc) {
          if (std::abs(p.x()) > q.tol) continue;
          distance_mm = ArcDistance(q, p);
          if (distance_mm > arc_end_mm + q.tol) continue;
        } else {
          if (std::abs(p.y()) > q.tol || std::abs(p.z()) > q.tol) continue;
          distance_mm = p.x();
        }
        if (distance_mm < min_mm || distance_mm > max_mm) continue;
        const Eigen::Vector3d u_mm = FrdDisplacement(*disp, id);
        DisplacementPoint point;
        point.load = load;
        point.path = path;
        point.distance_m = distance_mm * kMm;
        point.w_m_per_N = u_mm.dot(InwardNormal(q, p)) * kMm / kFullLoad_N;
        points.push_back(point);
      }
      if (points.size() < 2) {
        throw std::runtime_error(fmt::format(
            "{} load, {} path: {} mesh node(s) between {} and {} mm; expected a curve (is the "
            "mesh too coarse for the range?)",
            ToString(load), ToString(path), points.size(), min_mm, max_mm));
      }
      std::sort(points.begin(), points.end(),
                [](const auto& a, const auto& b) { return a.distance_m < b.distance_m; });
      curves.points.insert(curves.points.end(), points.begin(), points.end());
    }
  }
  summary.points = curves.points.size();
  summary.wall_time_s = Seconds(start);

  // 4. What the data is: everything needed to rebuild it.
  std::string times;
  for (const auto& [load, t] : summary.solve_time_s) {
    times += fmt::format("{}{} {:.1f}", times.empty() ? "" : ", ", ToString(load), t);
  }
  curves.metadata = {
      {"source", fmt::format("railwear fem-reference: gmsh {}, CalculiX {} (ccx, SPOOLES)",
                             programs.gmsh_version, programs.ccx_version)},
      {"geometry", GeometryText(q)},
      {"body_length_mm", fmt::format("{:g}", 2 * q.l2)},
      {"body_width_mm", fmt::format("{:g}", o.body == CurveBody::kConvex ? 2 * q.r : 2 * q.w2)},
      {"body_depth_mm", fmt::format("{:g}", q.d)},
      {"supports", SupportsText(o, q)},
      {"model",
       "quarter model x >= 0, y >= 0; symmetry planes x = 0 and y = 0 through the load "
       "point (normal load symmetric about both; axial antisymmetric about x = 0; "
       "circumferential antisymmetric about y = 0)"},
      {"load",
       "nodal force at the load point, a quarter of the full load on the quarter model; "
       "w per newton of the full load"},
      {"element", "C3D10 (10-node tetrahedron), mid-side nodes on the curved surfaces"},
      {"mesh_size_at_load_mm", fmt::format("{:g}", o.mesh_size_at_load_m / kMm)},
      {"mesh_growth", fmt::format("{:g}", o.mesh_growth)},
      {"max_element_mm", fmt::format("{:g}", o.max_element_m / kMm)},
      {"nodes", fmt::format("{}", summary.nodes)},
      {"elements", fmt::format("{}", summary.elements)},
      {"points", "every surface node on the path from the load point between the distances"},
      {"distances_mm", fmt::format("{:g} to {:g}", min_mm, max_mm)},
      {"solve_time_s", times},
  };
  return result;
}

FemBodySize FemBodySizeUsed(const FemDisplacementOptions& o) {
  FemBodySize s = DefaultFemBodySize(o.body, o.radius_m);
  if (o.length_m > 0.0) s.length_m = o.length_m;
  if (o.width_m > 0.0 && o.body != CurveBody::kConvex) s.width_m = o.width_m;
  if (o.depth_m > 0.0) s.depth_m = o.depth_m;
  return s;
}

double EstimateFemDisplacementNodes(const FemDisplacementOptions& o) {
  // Nodes per unit of the integral, fitted to docs/fem_reference.md's meshes (see the header).
  constexpr double kNodesPerUnit = 8.28;
  const FemBodySize s = FemBodySizeUsed(o);
  return kNodesPerUnit * GradedMeshIntegral({0.5 * s.length_m, 0.5 * s.width_m, s.depth_m},
                                            {0.0, 0.0, 0.0}, o.mesh_size_at_load_m, o.mesh_growth,
                                            o.max_element_m);
}

}  // namespace railwear
