// A finite-element mesh as gmsh writes it (MSH 2.2 ASCII, `gmsh -3 x.geo -format msh22`):
// nodes, elements with their physical group, and the physical groups' names, plus what the
// CalculiX deck needs from them (node sets, element-face surfaces).
//
// Units: coordinates are kept in the unit of the mesh file (the FEM decks of railwear use
// mm, N and MPa throughout), hence `_mm` in the names.
//
// Element node order is CalculiX's (= Abaqus's): gmsh's 10-node tetrahedron lists its edge nodes
// (0-1, 1-2, 2-0, 0-3, 2-3, 1-3) and ccx's C3D10 (0-1, 1-2, 2-0, 0-3, 1-3, 2-3), so the reader
// swaps gmsh's last two nodes; every other supported type has the same order in both.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace railwear {

// The element types the reader accepts (gmsh type number in brackets) and their ccx names.
enum class MeshElementType {
  kPoint,      // [15] a node of a physical point
  kLine2,      // [1]
  kLine3,      // [8]
  kTriangle3,  // [2]
  kTriangle6,  // [9]
  kTet4,       // [4]  ccx C3D4
  kTet10,      // [11] ccx C3D10
};
std::string_view ToString(MeshElementType type);
int Dimension(MeshElementType type);
int NodeCount(MeshElementType type);

struct MeshElement {
  int id = 0;
  MeshElementType type = MeshElementType::kTet10;
  int physical = 0;        // physical group tag (0: none)
  std::vector<int> nodes;  // node ids in ccx order
};

struct MeshGroup {
  std::string name;
  int dimension = 0;  // 0 point, 1 curve, 2 surface, 3 volume
  int tag = 0;        // gmsh physical tag
};

// One face of a solid element: ccx numbers the faces of a tetrahedron 1: (1,2,3), 2: (1,4,2),
// 3: (2,4,3), 4: (3,4,1) (corner nodes, 1-based). A surface "E, S2" in *SURFACE.
struct ElementFace {
  int element = 0;
  int face = 0;  // 1..4
};

class FemMesh {
 public:
  // Adds a node; ids are positive and unique (checked).
  void AddNode(int id, const Eigen::Vector3d& position_mm);
  void AddElement(MeshElement element);
  void AddGroup(MeshGroup group);

  size_t NumNodes() const { return node_ids_.size(); }
  const std::vector<int>& node_ids() const { return node_ids_; }
  bool HasNode(int id) const { return index_.count(id) != 0; }
  // The node's position; the id must exist (checked).
  const Eigen::Vector3d& Position_mm(int id) const;
  const std::vector<MeshElement>& elements() const { return elements_; }
  const std::map<std::string, MeshGroup>& groups() const { return groups_; }

  // The group of that name, or nullptr.
  const MeshGroup* FindGroup(std::string_view name) const;
  // The elements of a physical group (empty for an unknown name).
  std::vector<const MeshElement*> GroupElements(std::string_view name) const;
  // The sorted, unique node ids of a group's elements (all nodes, mid-side ones included).
  std::vector<int> NodeSet(std::string_view name) const;
  // Solid (3-D) elements of any group.
  std::vector<const MeshElement*> SolidElements() const;
  // The element faces of solid elements that coincide with the triangles of a surface group
  // (matched by corner nodes). Throws std::runtime_error when a triangle matches no face.
  std::vector<ElementFace> FaceSurface(std::string_view surface_group) const;

 private:
  std::vector<int> node_ids_;
  std::vector<Eigen::Vector3d> positions_;
  std::unordered_map<int, size_t> index_;
  std::vector<MeshElement> elements_;
  std::map<std::string, MeshGroup> groups_;
};

// The corner nodes (0-based positions in MeshElement::nodes) of face 1..4 of a tetrahedron, in
// ccx's numbering.
std::array<int, 3> TetFaceCorners(int face);

// The integral of 1 / h^3 over a quarter model's box [0, body[0]] x [0, body[1]] x [0, body[2]]
// (m) whose element size grows from `h0_m` by `growth` per metre of distance d from the refined
// zone [0, zone[0]] x [0, zone[1]] x [0, zone[2]] (zeros: a point, the load point) up to
// `h_max_m`: h = min(h0 + growth d, h_max). The number of elements of a graded tetrahedral mesh
// is proportional to it (a regular tetrahedron of edge h fills h^3 / (6 sqrt 2)); the callers'
// estimates (EstimateFemDisplacementNodes, EstimateFemContactNodes) scale it by a constant fitted
// to gmsh's node counts. A midpoint rule on 40 log-spaced cells per axis from 1 um (the grading
// is steep at the zone), a fraction of a millisecond.
double GradedMeshIntegral(const std::array<double, 3>& body_m, const std::array<double, 3>& zone_m,
                          double h0_m, double growth, double h_max_m);

// Reads an MSH 2.2 ASCII file. Elements of types other than those above are refused; elements
// that belong to several physical groups appear once per group (as gmsh writes them). Throws
// InputError naming the file and line on a malformed file.
FemMesh ReadGmshMesh(const std::string& path);

}  // namespace railwear
