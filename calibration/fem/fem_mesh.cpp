// gmsh MSH 2.2 reader and the mesh queries the ccx deck needs. See fem_mesh.h.
#include "calibration/fem/fem_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/numerics/check.h"
#include "core/numerics/input_error.h"

namespace railwear {
namespace {

struct GmshType {
  int gmsh;
  MeshElementType type;
};
constexpr GmshType kGmshTypes[] = {
    {15, MeshElementType::kPoint},    {1, MeshElementType::kLine2},
    {8, MeshElementType::kLine3},     {2, MeshElementType::kTriangle3},
    {9, MeshElementType::kTriangle6}, {4, MeshElementType::kTet4},
    {11, MeshElementType::kTet10},
};

// Reads the file line by line, counting lines for messages.
class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {}
  bool ok() const { return static_cast<bool>(in_); }
  bool Next(std::string* line) {
    if (!std::getline(in_, *line)) return false;
    ++number_;
    if (!line->empty() && line->back() == '\r') line->pop_back();
    return true;
  }
  // The next line, which must exist.
  std::string Required(std::string_view what) {
    std::string line;
    if (!Next(&line)) Fail(fmt::format("the file ends early; expected {}", what));
    return line;
  }
  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(fmt::format("{}:{}: {}", path_, number_, message));
  }
  int number() const { return number_; }

 private:
  std::string path_;
  std::ifstream in_;
  int number_ = 0;
};

size_t ReadCount(LineReader& r, std::string_view section) {
  const std::string line = r.Required(fmt::format("the number of entries of {}", section));
  std::istringstream is(line);
  long long n = -1;
  if (!(is >> n) || n < 0) {
    r.Fail(fmt::format("'{}': expected the number of entries of {}", line, section));
  }
  return static_cast<size_t>(n);
}

void ExpectEnd(LineReader& r, std::string_view section) {
  const std::string end = fmt::format("$End{}", section);
  const std::string line = r.Required(end);
  if (line != end) r.Fail(fmt::format("'{}': expected {}", line, end));
}

}  // namespace

std::string_view ToString(MeshElementType type) {
  switch (type) {
    case MeshElementType::kPoint:
      return "point";
    case MeshElementType::kLine2:
      return "line2";
    case MeshElementType::kLine3:
      return "line3";
    case MeshElementType::kTriangle3:
      return "triangle3";
    case MeshElementType::kTriangle6:
      return "triangle6";
    case MeshElementType::kTet4:
      return "C3D4";
    case MeshElementType::kTet10:
      return "C3D10";
  }
  return "?";
}

int Dimension(MeshElementType type) {
  switch (type) {
    case MeshElementType::kPoint:
      return 0;
    case MeshElementType::kLine2:
    case MeshElementType::kLine3:
      return 1;
    case MeshElementType::kTriangle3:
    case MeshElementType::kTriangle6:
      return 2;
    case MeshElementType::kTet4:
    case MeshElementType::kTet10:
      return 3;
  }
  return -1;
}

int NodeCount(MeshElementType type) {
  switch (type) {
    case MeshElementType::kPoint:
      return 1;
    case MeshElementType::kLine2:
      return 2;
    case MeshElementType::kLine3:
      return 3;
    case MeshElementType::kTriangle3:
      return 3;
    case MeshElementType::kTriangle6:
      return 6;
    case MeshElementType::kTet4:
      return 4;
    case MeshElementType::kTet10:
      return 10;
  }
  return 0;
}

std::array<int, 3> TetFaceCorners(int face) {
  switch (face) {
    case 1:
      return {0, 1, 2};
    case 2:
      return {0, 3, 1};
    case 3:
      return {1, 3, 2};
    case 4:
      return {2, 3, 0};
  }
  RAILWEAR_CHECK(false && "tetrahedron faces are 1..4");
  return {0, 0, 0};
}

void FemMesh::AddNode(int id, const Eigen::Vector3d& position_mm) {
  RAILWEAR_CHECK(id > 0);
  const bool inserted = index_.emplace(id, node_ids_.size()).second;
  RAILWEAR_CHECK(inserted);
  node_ids_.push_back(id);
  positions_.push_back(position_mm);
}

void FemMesh::AddElement(MeshElement element) {
  RAILWEAR_CHECK(static_cast<int>(element.nodes.size()) == NodeCount(element.type));
  elements_.push_back(std::move(element));
}

void FemMesh::AddGroup(MeshGroup group) {
  std::string name = group.name;
  groups_[name] = std::move(group);
}

const Eigen::Vector3d& FemMesh::Position_mm(int id) const {
  const auto it = index_.find(id);
  RAILWEAR_CHECK(it != index_.end());
  return positions_[it->second];
}

const MeshGroup* FemMesh::FindGroup(std::string_view name) const {
  const auto it = groups_.find(std::string(name));
  return it == groups_.end() ? nullptr : &it->second;
}

std::vector<const MeshElement*> FemMesh::GroupElements(std::string_view name) const {
  std::vector<const MeshElement*> out;
  const MeshGroup* g = FindGroup(name);
  if (g == nullptr) return out;
  for (const MeshElement& e : elements_) {
    if (e.physical == g->tag && Dimension(e.type) == g->dimension) out.push_back(&e);
  }
  return out;
}

std::vector<int> FemMesh::NodeSet(std::string_view name) const {
  std::vector<int> ids;
  for (const MeshElement* e : GroupElements(name))
    ids.insert(ids.end(), e->nodes.begin(), e->nodes.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

std::vector<const MeshElement*> FemMesh::SolidElements() const {
  std::vector<const MeshElement*> out;
  for (const MeshElement& e : elements_) {
    if (Dimension(e.type) == 3) out.push_back(&e);
  }
  return out;
}

std::vector<ElementFace> FemMesh::FaceSurface(std::string_view surface_group) const {
  using Key = std::array<int, 3>;
  auto sorted = [](Key k) {
    std::sort(k.begin(), k.end());
    return k;
  };
  std::map<Key, ElementFace> faces;
  for (const MeshElement* e : SolidElements()) {
    for (int f = 1; f <= 4; ++f) {
      const auto c = TetFaceCorners(f);
      faces.emplace(sorted({e->nodes[c[0]], e->nodes[c[1]], e->nodes[c[2]]}),
                    ElementFace{e->id, f});
    }
  }
  std::vector<ElementFace> out;
  for (const MeshElement* t : GroupElements(surface_group)) {
    const auto it = faces.find(sorted({t->nodes[0], t->nodes[1], t->nodes[2]}));
    if (it == faces.end()) {
      throw std::runtime_error(
          fmt::format("surface group '{}': triangle {} is no face of a solid "
                      "element",
                      surface_group, t->id));
    }
    out.push_back(it->second);
  }
  return out;
}

FemMesh ReadGmshMesh(const std::string& path) {
  LineReader r(path);
  if (!r.ok()) throw InputError(fmt::format("{}: cannot open the mesh file", path));
  FemMesh mesh;
  bool format_seen = false, nodes_seen = false, elements_seen = false;
  std::string line;
  while (r.Next(&line)) {
    if (line.empty()) continue;
    if (line[0] != '$') r.Fail(fmt::format("'{}': expected a section such as $Nodes", line));
    const std::string section = line.substr(1);
    if (section == "MeshFormat") {
      const std::string f = r.Required("the format line '2.2 0 8'");
      std::istringstream is(f);
      std::string version;
      int file_type = -1;
      if (!(is >> version >> file_type) || version.rfind("2.", 0) != 0 || file_type != 0) {
        r.Fail(
            fmt::format("mesh format '{}': expected MSH version 2.2 ASCII ('2.2 0 8'; gmsh "
                        "-format msh22)",
                        f));
      }
      ExpectEnd(r, section);
      format_seen = true;
    } else if (section == "PhysicalNames") {
      const size_t n = ReadCount(r, section);
      for (size_t i = 0; i < n; ++i) {
        const std::string g = r.Required("a physical name 'dim tag \"name\"'");
        std::istringstream is(g);
        MeshGroup group;
        std::string rest;
        if (!(is >> group.dimension >> group.tag) || !std::getline(is, rest)) {
          r.Fail(fmt::format("'{}': expected 'dim tag \"name\"'", g));
        }
        const size_t a = rest.find('"'), b = rest.rfind('"');
        if (a == std::string::npos || b == a)
          r.Fail(fmt::format("'{}': expected a quoted name", g));
        group.name = rest.substr(a + 1, b - a - 1);
        mesh.AddGroup(std::move(group));
      }
      ExpectEnd(r, section);
    } else if (section == "Nodes") {
      if (!format_seen) r.Fail("$Nodes before $MeshFormat; expected an MSH 2.2 file");
      const size_t n = ReadCount(r, section);
      for (size_t i = 0; i < n; ++i) {
        const std::string t = r.Required("a node 'id x y z'");
        std::istringstream is(t);
        int id = 0;
        Eigen::Vector3d p;
        if (!(is >> id >> p.x() >> p.y() >> p.z()) || id <= 0 || !p.allFinite()) {
          r.Fail(fmt::format("'{}': expected a node 'id x y z' with id > 0", t));
        }
        if (mesh.HasNode(id)) r.Fail(fmt::format("node {} given twice", id));
        mesh.AddNode(id, p);
      }
      ExpectEnd(r, section);
      nodes_seen = true;
    } else if (section == "Elements") {
      if (!nodes_seen) r.Fail("$Elements before $Nodes");
      const size_t n = ReadCount(r, section);
      for (size_t i = 0; i < n; ++i) {
        const std::string t = r.Required("an element 'id type ntags tags... nodes...'");
        std::istringstream is(t);
        int id = 0, gmsh_type = 0, num_tags = 0;
        if (!(is >> id >> gmsh_type >> num_tags) || num_tags < 0) {
          r.Fail(fmt::format("'{}': expected 'id type ntags tags... nodes...'", t));
        }
        MeshElement e;
        e.id = id;
        bool known = false;
        for (const GmshType& g : kGmshTypes) {
          if (g.gmsh == gmsh_type) {
            e.type = g.type;
            known = true;
          }
        }
        if (!known) {
          r.Fail(
              fmt::format("element {} has gmsh type {}; expected 15 (point), 1/8 (line), 2/9 "
                          "(triangle) or 4/11 (tetrahedron)",
                          id, gmsh_type));
        }
        std::vector<int> tags(static_cast<size_t>(num_tags));
        for (int& tag : tags) {
          if (!(is >> tag)) r.Fail(fmt::format("'{}': element {} lacks its tags", t, id));
        }
        e.physical = tags.empty() ? 0 : tags[0];
        e.nodes.resize(static_cast<size_t>(NodeCount(e.type)));
        for (int& node : e.nodes) {
          if (!(is >> node) || !mesh.HasNode(node)) {
            r.Fail(fmt::format("'{}': element {} expects {} existing node ids", t, id,
                               NodeCount(e.type)));
          }
        }
        if (e.type == MeshElementType::kTet10) std::swap(e.nodes[8], e.nodes[9]);  // to ccx
        mesh.AddElement(std::move(e));
      }
      ExpectEnd(r, section);
      elements_seen = true;
    } else {  // a section this reader does not use ($Periodic, $NodeData, ...)
      const std::string end = "$End" + section;
      while (true) {
        const std::string skip = r.Required(end);
        if (skip == end) break;
      }
    }
  }
  if (!format_seen || !nodes_seen || !elements_seen) {
    r.Fail(fmt::format("the file lacks {}; expected an MSH 2.2 mesh", !format_seen  ? "$MeshFormat"
                                                                      : !nodes_seen ? "$Nodes"
                                                                                    : "$Elements"));
  }
  return mesh;
}

double GradedMeshIntegral(const std::array<double, 3>& body_m, const std::array<double, 3>& zone_m,
                          double h0_m, double growth, double h_max_m) {
  constexpr int kCells = 40;
  constexpr double kFirst = 1e-6;  // [m]: the first cell edge past 0
  // Midpoints and widths of [0, a] cut at 0 and log-spaced edges from kFirst to a.
  const auto cells = [](double a) {
    std::vector<std::pair<double, double>> out;
    double previous = 0.0;
    for (int k = 0; k < kCells; ++k) {
      const double edge =
          a <= kFirst ? a * (k + 1) / kCells : kFirst * std::pow(a / kFirst, k / (kCells - 1.0));
      out.emplace_back(0.5 * (previous + edge), edge - previous);
      previous = edge;
    }
    return out;
  };
  const auto xs = cells(body_m[0]), ys = cells(body_m[1]), zs = cells(body_m[2]);
  double sum = 0.0;
  for (const auto& [x, wx] : xs) {
    const double dx = std::max(0.0, x - zone_m[0]);
    for (const auto& [y, wy] : ys) {
      const double dy = std::max(0.0, y - zone_m[1]);
      for (const auto& [z, wz] : zs) {
        const double dz = std::max(0.0, z - zone_m[2]);
        const double h = std::min(h0_m + growth * std::sqrt(dx * dx + dy * dy + dz * dz), h_max_m);
        sum += wx * wy * wz / (h * h * h);
      }
    }
  }
  return sum;
}

}  // namespace railwear
