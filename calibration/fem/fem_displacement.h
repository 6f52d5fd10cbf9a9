// The seed paper's displacement experiment as a 3-D solid FEM model (gmsh + CalculiX): a body
// with a flat, convex (rail-head-like) or concave (groove) top surface carries a unit point
// load at a surface point O; the normal displacement of surface points along the arc and the
// axis (displacement_curves.h) becomes the reference data of influence-function calibration.
//
// Frame: x along the cylinder's axis, y across it, z the outward normal at O = (0, 0, 0); the
// body lies below (z < 0 near O). Bodies (cross-section in the plane x = const, extruded over
// the length L along x):
//   flat     a block W wide (y) and D deep (z from 0 to -D).
//   convex   a half-cylinder of radius R (centre at z = -R, the top half of the circle) on a
//            block 2R wide whose bottom is D below O: a rail head of gauge-corner radius R.
//   concave  a block W wide whose top face is at z = R, with a semicircular groove of radius R
//            (centre at z = R) in it: O is the groove's bottom; the bottom face is D below O.
// Supports: the bottom face z = -D clamped (u = 0), the rest free (FemSupports::kBottom, the
// default); or every face but the top and the symmetry planes clamped (kFarFaces: the bottom,
// the ends x = +-L/2 and the sides y = +-W/2, for a convex body y = +-R below its
// half-cylinder). A clamped support makes the body's displacement under a normal load differ
// from an unbounded body's by a nearly constant offset (about 1.8e-11 m/N with a 200 x 200 x
// 100 mm block, shrinking as 1/size), which calibration fits per curve. Under a tangential load
// a convex body also sways as a whole (a rigid-like motion of the head that grows with its
// height): its circumferential curve is not a local response plus an offset.
//
// Symmetry: only the quarter x >= 0, y >= 0 is meshed. The normal load (-z) is symmetric about
// both planes (u_x = 0 on x = 0, u_y = 0 on y = 0); the axial load (+x) is antisymmetric about
// x = 0 (u_y = u_z = 0 there) and symmetric about y = 0 (u_y = 0); the circumferential load (+y)
// is symmetric about x = 0 (u_x = 0) and antisymmetric about y = 0 (u_x = u_z = 0). The load is
// a nodal force at O, a quarter of the full load on the quarter model (each symmetry or
// antisymmetry plane through O halves what the model carries).
//
// Mesh: 10-node tetrahedra (C3D10) graded from h0 at O by h = h0 + growth * r (r the distance
// from O) up to max_element, at least 12 elements per circle on curved faces; gmsh places
// mid-side nodes on the curved surfaces. Curves: every
// surface node on a path (the arc in the plane x = 0, the axis y = 0 on the top) between
// min_distance and max_distance; w = u . n_in per newton, n_in the inward normal at the node.
// An approximation of the continuum: its error near the load is set by h0 (a point load is
// singular, so points closer than a few h0 are not written), further out by growth; the README
// shows the convergence.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/displacement_curves.h"
#include "calibration/fem/fem_programs.h"
#include "core/contact/contact_types.h"

namespace railwear {

enum class FemSupports { kBottom, kFarFaces };
std::string_view ToString(FemSupports v);  // "bottom", "far_faces"
std::optional<FemSupports> FemSupportsFromString(std::string_view s);

// The body size [m] a body gets when its options leave it at 0: 200 mm long (8 times the
// sampled 25 mm) and, below O, flat 200 x 100 mm (width x depth), convex 2R x 2R (the
// half-cylinder on a block R tall: short, as a convex head sways under tangential loads more the
// taller it is), concave max(200 mm, 2R + 100 mm) x 100 mm.
struct FemBodySize {
  double length_m = 0.0;  // along x, the whole body (the quarter model is half as long)
  double width_m = 0.0;   // along y, the whole body (convex: 2R)
  double depth_m = 0.0;   // from O down to the bottom face
};
FemBodySize DefaultFemBodySize(CurveBody body, double radius_m);

struct FemDisplacementOptions {
  CurveBody body = CurveBody::kFlat;
  double radius_m = 0.0;  // R of the convex or concave surface [m], > 0 unless flat
  Material material;      // E > 0, nu in [0, 0.5)
  // The loads to run, each once (one ccx solve each), any order, not empty.
  std::vector<CurveLoad> loads = {CurveLoad::kNormal, CurveLoad::kAxial,
                                  CurveLoad::kCircumferential};
  // Body size [m]; 0 takes DefaultFemBodySize. Width is ignored for convex bodies (2R).
  // Checked: the length (and a flat body's width) at least 4 max_distance, so the sampled paths
  // stay well inside the body; depth > R for convex bodies, width > 2R for concave ones.
  double length_m = 0.0;
  double width_m = 0.0;
  double depth_m = 0.0;
  FemSupports supports = FemSupports::kBottom;
  double mesh_size_at_load_m = 0.1e-3;  // h0 > 0 [m]
  double mesh_growth = 0.12;            // element size grows by this many m per m from O, > 0
  double max_element_m = 20e-3;         // largest element [m], >= h0
  double min_distance_m = 0.5e-3;       // first distance written [m], > 0
  double max_distance_m = 25e-3;        // last distance written [m], > min (arcs stop at pi R/2)
  int jobs = 2;                         // ccx solves at once (each with threads_per_job threads)
  int threads_per_job = 1;              // >= 1
  double timeout_s = 3600.0;            // per gmsh or ccx run; 0: none
  std::string work_dir;                 // existing folder for .geo, .msh, .inp, .frd and logs
  // Progress messages ("meshing", "solving normal (23502 nodes)", ...); may be empty. Called
  // from the worker threads too (one call at a time).
  std::function<void(std::string_view)> progress;

  // False with a message naming the option, its value and what was expected.
  bool IsValid(std::string* error) const;
};

struct FemDisplacementSummary {
  FemBodySize body_size;                                   // as used (defaults filled in)
  size_t nodes = 0;                                        // of the quarter model
  size_t elements = 0;                                     // solid elements of the quarter model
  double mesh_time_s = 0.0;                                // gmsh wall time
  std::vector<std::pair<CurveLoad, double>> solve_time_s;  // ccx wall time per load
  double wall_time_s = 0.0;                                // the whole experiment
  size_t points = 0;                                       // rows of the curves
};

struct FemDisplacementResult {
  DisplacementCurves curves;  // body, radius, material, metadata and points (path empty)
  FemDisplacementSummary summary;
};

// Builds, meshes and solves the experiment and extracts the curves. Throws InputError when the
// options are not valid; std::runtime_error when gmsh or ccx fail (quoting the log), or when
// the mesh does not have the expected groups.
FemDisplacementResult RunFemDisplacement(const FemDisplacementOptions& options,
                                         const FemPrograms& programs);

// The gmsh .geo text of the quarter model (mm), with physical groups BODY, LOAD (the point O),
// TOP (the loaded surface), SYMX (x = 0), SYMY (y = 0), BOTTOM, END (x = L/2), SIDE (y = W/2;
// convex: y = R) and, for a concave body, TOPFLAT (its flat top beside the groove).
// The body size a run uses: the options' sizes, DefaultFemBodySize's for zeros (convex: 2R wide).
FemBodySize FemBodySizeUsed(const FemDisplacementOptions& options);

// The quarter model's node count gmsh will make, estimated before meshing (issue 17: a mesh too
// large for the machine is refused before a long run): 8.28 x GradedMeshIntegral over the
// quarter box (L/2 x W/2 x D, graded from the load point). The constant is fitted (geometric
// mean) to the 7 meshes of docs/fem_reference.md (2,591 to 96,209 nodes); each is within a
// factor 0.68-1.33 of its estimate (the box ignores the curved faces and their 12 elements per
// circle). An order of magnitude, not a count.
double EstimateFemDisplacementNodes(const FemDisplacementOptions& options);

std::string FemDisplacementGeo(const FemDisplacementOptions& options, const FemBodySize& size);

}  // namespace railwear
