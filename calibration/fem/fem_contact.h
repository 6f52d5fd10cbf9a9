// Conformal wheel-rail contact as a 3-D FEM reference (gmsh + CalculiX): two steel bodies, one
// with a convex circular profile and one with a slightly larger circular groove, pressed
// together by a vertical load, frictionless, with ccx's penalty surface-to-surface contact. The
// contact area, the peak pressure and the patch size become calibration targets for the
// railwear contact models (README, "FEM contact cases").
//
// Cases (frame: x rolling direction, y lateral, z up; the first contact point at the origin):
//   wheel_in_groove       the wheel is a body of revolution about the axle y through
//                         (0, 0, r0), its profile a convex circle of radius Rc (a torus
//                         section: railwear's wheel "circle:Rc"); the rail is prismatic along x
//                         with a groove of radius Rg > Rc (rail "groove:Rg").
//   rail_in_wheel_groove  the rail is prismatic with a convex head of radius Rc (a
//                         half-cylinder on a block, rail "circle:Rc"); the wheel is a body of
//                         revolution with a groove of radius Rg > Rc (wheel "groove:Rg"), its
//                         radius r0 at the groove bottom.
// Both profiles are circular arcs up to 80 degrees from the bottom, like railwear's built-in
// circles and grooves. The wheel body reaches depth D above the contact (a segment of +-L/2
// along x, i.e. +-L/(2 r0) rad of the wheel), the rail block depth D below it; both are W wide.
//
// Model: the quarter x >= 0, y >= 0 (symmetric about x = 0 and y = 0: u_x = 0 and u_y = 0 on
// those planes). The rail's bottom face is clamped; a uniform pressure on the wheel's far face
// (a cylinder of radius r0 - D) whose vertical resultant is a quarter of the load pushes the
// wheel down. The wheel starts `initial_overlap` lower than first contact so that contact exists
// from the first iteration (linear kinematics: the final state does not depend on it), and weak
// springs to the ground on its far face (total `spring` N/m) remove its free vertical motion;
// the force they take is reported. Contact: slave = the rail's contact face, master = the
// wheel's, both restricted to the contact zone (|x| <= zone_x, arc length from the bottom
// <= zone_s: a tight search zone keeps ccx fast), *SURFACE BEHAVIOR PRESSURE-OVERCLOSURE=LINEAR
// with slope `penalty`. Mesh: 10-node tetrahedra (C3D10), size h in the zone (x <= zone_x,
// s <= zone_s, depth below the surface <= zone_depth), growing by `mesh_growth` per mm outside
// it up to max_element; one model per mesh level.
//
// Measures (CalcFemContactPatch, on the slave face's nodal CPRESS):
//   p_max       the largest nodal pressure.
//   half_length_x, half_width_s   the patch edge on the symmetry lines (x on y = 0; the arc
//               length s on x = 0), from a least-squares fit of p^2 = A + B r^2 to the nodes
//               with 0.1 < p/p_max < 0.8 extrapolated to p = 0 (exact for Hertz's
//               p = p0 sqrt(1 - r^2/a^2); the outer nodes of a penalty model carry a small
//               pressure tail that would otherwise inflate the patch by about one element).
//   area        in normalised coordinates (x/a, s/b) the patch edge is fitted the same way in
//               each of `sectors` angular sectors of the quarter, area = 4 a b sum(rho^2/2 dphi)
//               (an ellipse gives pi a b whatever the sectors).
//   area_nodes  the lumped area of the slave nodes with p > 0 (with ccx's pressure tail past
//               the edge it is 10-25 % larger than area; without a tail, about equal).
//   force       the vertical and normal resultants of the nodal pressure field integrated over
//               the slave faces with the 6-node triangle's shape functions (x 4), which the
//               report compares with the load.
// Approximate: the measures converge with the mesh and the penalty (README: convergence).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "calibration/fem/fem_mesh.h"
#include "calibration/fem/fem_programs.h"
#include "calibration/fem/frd_file.h"
#include "core/contact/contact_types.h"

namespace railwear {

enum class FemContactCase { kWheelInGroove, kRailInWheelGroove };
std::string_view ToString(FemContactCase v);  // "wheel_in_groove", "rail_in_wheel_groove"
std::optional<FemContactCase> FemContactCaseFromString(std::string_view s);

struct FemContactOptions {
  FemContactCase contact_case = FemContactCase::kWheelInGroove;
  double convex_radius_m = 10e-3;    // Rc, profile radius of the convex body, > 0
  double groove_radius_m = 10.1e-3;  // Rg, > Rc
  double rolling_radius_m = 0.46;    // r0 of the wheel at the contact, > 2 D
  double load_N = 10e3;              // vertical load on the whole wheel, > 0
  Material material;                 // both bodies; E > 0, nu in [0, 0.5)
  // Body size [m]: whole length along x, whole width along y (> 2 Rg), depth of each body.
  double length_m = 80e-3;
  double width_m = 60e-3;
  double depth_m = 40e-3;
  // Refined zone and contact search zone [m] (quarter: x in [0, zone_x], arc length
  // s in [0, zone_s] from the bottom; zone_depth below the surface). 0 takes the case default
  // (DefaultFemContactOptions); zone_depth 0 takes 0.25 zone_x. The patch must stay inside.
  double zone_x_m = 0.0;
  double zone_s_m = 0.0;
  double zone_depth_m = 0.0;
  // Element sizes in the zone [m], one model per level, coarse to fine; the last one is the
  // result. Not empty; each > 0.
  std::vector<double> mesh_sizes_m;
  double mesh_growth = 0.4;            // element size growth outside the zone [m/m], (0, 2]
  double max_element_m = 8e-3;         // largest element [m]
  double penalty_Pa_per_m = 5e15;      // contact slope K (5e6 MPa/mm), > 0
  double initial_overlap_m = 0.01e-3;  // >= 0
  double spring_N_per_m = 1e4;         // total stiffness of the far-face springs (10 N/mm), > 0
  int sectors = 9;                     // angular sectors of the area fit, >= 2
  int threads_per_job = 1;             // ccx threads, >= 1
  double timeout_s = 3600.0;           // per gmsh or ccx run; 0: none
  std::string work_dir;                // existing folder for .geo, .msh, .inp, .frd and logs
  // Progress messages; may be empty.
  std::function<void(std::string_view)> progress;

  // False with a message naming the option, its value and what was expected.
  bool IsValid(std::string* error) const;
};

// The case's defaults: radii, load, zones and mesh levels of the README's reference runs
// (wheel_in_groove: Rc 10, Rg 10.1 mm, 10 kN, zone 3.6 x 5.4 mm, h = 0.7, 0.5, 0.35 mm;
// rail_in_wheel_groove: Rc 15, Rg 15.1 mm, 50 kN, zone 5.4 x 12 mm, h = 0.9, 0.6, 0.45 mm).
FemContactOptions DefaultFemContactOptions(FemContactCase contact_case);

// The slave (rail) profile's circle in the cross-section x = 0: s = R atan2(y, |z - zc|) is the
// arc length from the bottom. radius_m = 0: a flat surface, s = y.
struct FemContactFrame {
  double centre_z_m = 0.0;
  double radius_m = 0.0;
};

// A slave surface with its nodal contact pressures [SI]: node positions, pressures (>= 0 in
// contact, 0 elsewhere), and 6-node triangles (indices into positions: corners 0, 1, 2, then the
// mid-side nodes of edges 0-1, 1-2, 2-0) covering the quarter x >= 0, y >= 0.
struct FemContactSurface {
  std::vector<Eigen::Vector3d> positions_m;
  std::vector<double> pressure_Pa;
  std::vector<std::array<int, 6>> triangles;
};

enum class FemContactStatus { kOk, kNoContact, kPatchAtZoneEdge, kFitFailed };
std::string_view ToString(FemContactStatus v);

// The measures of one contact patch (full patch: the quarter's values x 4).
struct FemContactPatch {
  FemContactStatus status = FemContactStatus::kOk;
  std::string message;
  double area_m2 = 0.0;
  double area_nodes_m2 = 0.0;
  double p_max_Pa = 0.0;
  double half_length_x_m = 0.0;
  double half_width_s_m = 0.0;
  double vertical_force_N = 0.0;
  double normal_force_N = 0.0;
  size_t contact_nodes = 0;          // slave nodes with p > 0 (quarter)
  std::vector<double> sector_edges;  // fitted edge radius per sector in units of (a, b)
};

// The measures of a surface (see the file comment). Status kNoContact when no pressure is
// positive, kFitFailed when a symmetry line has too few nodes for the edge fit (the values then
// come from the outermost contact nodes).
FemContactPatch CalcFemContactPatch(const FemContactSurface& surface, const FemContactFrame& frame,
                                    int sectors = 9);

// The slave surface of `faces` (C3D10 faces of `mesh`, positions in mm) with the nodal
// pressures of the last CONTACT block of `frd` (CPRESS, MPa; negative values and nodes the block
// lacks count as 0), converted to SI. Throws std::runtime_error when the file has no CONTACT
// block with CPRESS.
FemContactSurface FemContactSlaveSurface(const FemMesh& mesh, const std::vector<ElementFace>& faces,
                                         const FrdFile& frd);

// One mesh level: the model and its result.
struct FemContactLevel {
  double mesh_size_m = 0.0;
  size_t nodes = 0;     // of the quarter model
  size_t elements = 0;  // C3D10
  size_t slave_faces = 0;
  size_t master_faces = 0;
  double mesh_time_s = 0.0;   // gmsh wall time
  double solve_time_s = 0.0;  // ccx wall time
  int iterations = 0;         // ccx's contact iterations (all increments)
  // Vertical force the wheel puts on its far-face springs, k * sum(u_z) x 4 [N] (z up:
  // negative when the wheel moved down, the springs then carry |spring_force_N| of the load).
  double spring_force_N = 0.0;
  FemContactPatch patch;
};

struct FemContactResult {
  FemContactOptions options;            // as used (defaults filled in; progress cleared)
  std::vector<FemContactLevel> levels;  // in mesh_sizes order; the last is the result
  double wall_time_s = 0.0;
};

// The options with the case defaults filled in for zeros (zones).
FemContactOptions ResolvedFemContactOptions(const FemContactOptions& options);

// One mesh level's node count (both bodies) gmsh will make at element size `mesh_size_m` in
// the zone, estimated before meshing: 2 x 15.47 x GradedMeshIntegral over a body's quarter box
// (L/2 x W/2 x depth) graded from the zone box (zone_x x zone_s x zone_depth). The constant is
// fitted to the six levels of docs/fem_contact_cases.md (9,652 to 53,132 nodes); each is within
// 0.91-1.14 of its estimate. `options` resolved.
double EstimateFemContactNodes(const FemContactOptions& options, double mesh_size_m);

// Builds, meshes and solves every mesh level. Throws InputError when the options are not valid;
// std::runtime_error when gmsh or ccx fail (quoting the log) or the mesh lacks a group.
FemContactResult RunFemContact(const FemContactOptions& options, const FemPrograms& programs);

// The gmsh .geo text (mm) of the quarter model at element size h [m] in the zone: volumes WHEEL
// and RAIL; surfaces WCONT, RCONT (contact faces), WTOP (wheel far face), RBOT (rail bottom),
// WSYMX, RSYMX (x = 0), WSYMY, RSYMY (y = 0). `options` resolved.
std::string FemContactGeo(const FemContactOptions& options, double mesh_size_m);

// The ccx keyword part of a level's deck (after *INCLUDE of `mesh_file`): material, springs on
// `top_nodes` (element ids from `first_spring_id`), contact pair SR (slave) / SW (master),
// symmetry and clamp boundaries, the load step with the far-face pressure on STOP, outputs.
std::string FemContactDeck(const FemContactOptions& options, const std::string& mesh_file,
                           const std::vector<int>& top_nodes, int first_spring_id);

}  // namespace railwear
