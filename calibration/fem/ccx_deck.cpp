// CalculiX input decks. See ccx_deck.h.
#include "calibration/fem/ccx_deck.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "core/numerics/check.h"
#include "core/numerics/text_file.h"

namespace railwear {
namespace {

constexpr int kIdsPerLine = 10;  // ccx: at most 16 entries and 132 characters per line

// A number for a ccx data line: 12 significant digits, at most 18 characters (ccx reads at most
// 20 characters per number and stops with "*ERROR reading *NODE" on longer ones).
std::string Num(double v) { return fmt::format("{:.12g}", v); }

void AppendIdList(const std::vector<int>& ids, std::string* out) {
  for (size_t i = 0; i < ids.size(); ++i) {
    *out += fmt::format("{}{}", ids[i],
                        (i + 1) % kIdsPerLine == 0 || i + 1 == ids.size() ? ",\n" : ", ");
  }
}

}  // namespace

std::vector<int> ElementIds(const FemMesh& mesh, std::string_view volume_group) {
  std::vector<int> ids;
  for (const MeshElement* e : mesh.GroupElements(volume_group)) {
    if (Dimension(e->type) == 3) ids.push_back(e->id);
  }
  return ids;
}

std::string CcxMeshText(const FemMesh& mesh, const CcxMeshSets& sets,
                        std::string_view solid_elset) {
  std::string out = "*NODE\n";
  for (int id : mesh.node_ids()) {
    const Eigen::Vector3d& p = mesh.Position_mm(id);
    out += fmt::format("{}, {}, {}, {}\n", id, Num(p.x()), Num(p.y()), Num(p.z()));
  }
  std::map<MeshElementType, std::vector<const MeshElement*>> by_type;
  for (const MeshElement* e : mesh.SolidElements()) by_type[e->type].push_back(e);
  for (const auto& [type, elements] : by_type) {
    out += fmt::format("*ELEMENT, TYPE={}, ELSET={}\n", ToString(type), solid_elset);
    for (const MeshElement* e : elements) {
      // C3D10 has 11 entries: ccx takes at most 16 per line, so one line per element.
      out += fmt::format("{}", e->id);
      for (int n : e->nodes) out += fmt::format(", {}", n);
      out += "\n";
    }
  }
  for (const auto& [name, ids] : sets.node_sets) {
    RAILWEAR_CHECK(!ids.empty());
    out += fmt::format("*NSET, NSET={}\n", name);
    AppendIdList(ids, &out);
  }
  for (const auto& [name, ids] : sets.element_sets) {
    RAILWEAR_CHECK(!ids.empty());
    out += fmt::format("*ELSET, ELSET={}\n", name);
    AppendIdList(ids, &out);
  }
  for (const auto& [name, faces] : sets.surfaces) {
    RAILWEAR_CHECK(!faces.empty());
    out += fmt::format("*SURFACE, NAME={}, TYPE=ELEMENT\n", name);
    for (const ElementFace& f : faces) out += fmt::format("{}, S{}\n", f.element, f.face);
  }
  return out;
}

CcxDeck& CcxDeck::Comment(std::string_view text) {
  text_ += fmt::format("** {}\n", text);
  return *this;
}

CcxDeck& CcxDeck::Include(std::string_view file) {
  text_ += fmt::format("*INCLUDE, INPUT={}\n", file);
  return *this;
}

CcxDeck& CcxDeck::ElasticMaterial(std::string_view name, double youngs_modulus,
                                  double poisson_ratio) {
  text_ += fmt::format("*MATERIAL, NAME={}\n*ELASTIC\n{}, {}\n", name, Num(youngs_modulus),
                       Num(poisson_ratio));
  return *this;
}

CcxDeck& CcxDeck::SolidSection(std::string_view elset, std::string_view material) {
  text_ += fmt::format("*SOLID SECTION, ELSET={}, MATERIAL={}\n", elset, material);
  return *this;
}

CcxDeck& CcxDeck::Boundary(std::string_view nodes, int first_dof, int last_dof, double value) {
  RAILWEAR_CHECK(1 <= first_dof && first_dof <= last_dof && last_dof <= 3);
  text_ += fmt::format("*BOUNDARY\n{}, {}, {}, {}\n", nodes, first_dof, last_dof, Num(value));
  return *this;
}

CcxDeck& CcxDeck::BeginStaticStep(std::string_view step_parameters, std::string_view static_data) {
  text_ += step_parameters.empty() ? "*STEP\n" : fmt::format("*STEP, {}\n", step_parameters);
  text_ += "*STATIC\n";
  if (!static_data.empty()) text_ += fmt::format("{}\n", static_data);
  return *this;
}

CcxDeck& CcxDeck::Cload(std::string_view nodes, int dof, double force) {
  RAILWEAR_CHECK(1 <= dof && dof <= 3);
  text_ += fmt::format("*CLOAD\n{}, {}, {}\n", nodes, dof, Num(force));
  return *this;
}

CcxDeck& CcxDeck::NodeFile(std::string_view outputs) {
  text_ += fmt::format("*NODE FILE\n{}\n", outputs);
  return *this;
}

CcxDeck& CcxDeck::EndStep() {
  text_ += "*END STEP\n";
  return *this;
}

CcxDeck& CcxDeck::Raw(std::string_view lines) {
  text_ += lines;
  if (lines.empty() || lines.back() != '\n') text_ += "\n";
  return *this;
}

void WriteWorkFile(const std::string& path, std::string_view text) {
  if (!WriteTextFile(path, text)) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path, std::strerror(errno)));
  }
}

}  // namespace railwear
