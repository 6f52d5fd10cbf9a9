// CalculiX (ccx) input decks: the mesh part written from a FemMesh (*NODE, *ELEMENT, *NSET,
// *SURFACE) and a small builder for the model and step keywords. Units are the caller's; the
// FEM decks of railwear use mm, N and MPa (displacements come back in mm).
//
// Only solid elements are written: gmsh's lower-dimensional elements of physical surfaces and
// curves (triangles, lines) would become elements of the model in ccx; their node sets and
// element faces are written as *NSET and *SURFACE instead.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "calibration/fem/fem_mesh.h"

namespace railwear {

// Named node sets, element sets and element-face surfaces to write with the mesh.
struct CcxMeshSets {
  std::vector<std::pair<std::string, std::vector<int>>> node_sets;
  std::vector<std::pair<std::string, std::vector<int>>> element_sets;  // solid element ids
  std::vector<std::pair<std::string, std::vector<ElementFace>>> surfaces;
};

// The element ids of a physical volume group (for CcxMeshSets::element_sets).
std::vector<int> ElementIds(const FemMesh& mesh, std::string_view volume_group);

// The mesh part of a deck: *NODE (all nodes), *ELEMENT blocks of the solid elements (one per
// type, all in element set `solid_elset`), then *NSET, *ELSET and *SURFACE (TYPE=ELEMENT)
// blocks.
// Numbers with 12 significant digits (ccx reads
// at most 20 characters per number).
std::string CcxMeshText(const FemMesh& mesh, const CcxMeshSets& sets,
                        std::string_view solid_elset = "EALL");

// Builds the keyword part of a deck line by line. Each call appends complete keyword lines;
// Raw appends anything else (contact pairs, other outputs).
class CcxDeck {
 public:
  CcxDeck& Comment(std::string_view text);  // "** text"
  CcxDeck& Include(std::string_view file);  // *INCLUDE, INPUT=file
  CcxDeck& ElasticMaterial(std::string_view name, double youngs_modulus, double poisson_ratio);
  CcxDeck& SolidSection(std::string_view elset, std::string_view material);
  // *BOUNDARY: degrees of freedom first..last (1 x, 2 y, 3 z) of a node set (or node id) held
  // at `value` (a prescribed displacement; 0 fixes them).
  CcxDeck& Boundary(std::string_view nodes, int first_dof, int last_dof, double value = 0.0);
  // *STEP[, step_parameters] and *STATIC with an optional data line, e.g. ("NLGEOM, INC=100",
  // "0.1, 1."); the defaults give a linear static step of one increment.
  CcxDeck& BeginStaticStep(std::string_view step_parameters = "",
                           std::string_view static_data = "");
  CcxDeck& Cload(std::string_view nodes, int dof, double force);  // *CLOAD
  CcxDeck& NodeFile(std::string_view outputs = "U");              // *NODE FILE: results to the .frd
  CcxDeck& EndStep();                                             // *END STEP
  CcxDeck& Raw(std::string_view lines);  // appended as given (newline added)

  const std::string& Text() const { return text_; }

 private:
  std::string text_;
};

// Writes text to a file; throws std::runtime_error when it cannot be written.
void WriteWorkFile(const std::string& path, std::string_view text);

}  // namespace railwear
