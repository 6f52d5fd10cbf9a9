// CalculiX result files (.frd, ASCII): the node block and every nodal result block (DISP,
// STRESS, CONTACT, ...), kept generic so that any block ccx writes can be looked up by name
// and step. Interpreting a block (e.g. contact pressure and slip from CONTACT) belongs in the
// code that asked for it.
//
// The format (CalculiX CGX manual, "Result Format"), fixed columns:
//   "    2C" ... FORMAT           node block; rows " -1" + id + 3 x E12.5 coordinates, ends " -3"
//   "    3C"                      element block (skipped)
//   "    1PSTEP" set inc step     result set header: increment and step number
//   "  100C" setname VALUE ...    result block: VALUE (12 chars at column 13) is the step time
//   " -4  NAME    NCOMPS IRTYPE"  block name
//   " -5  COMP    MENU ICTYPE I1 I2 IEXIST"   components; IEXIST = 1 marks a component that is
//                                 not stored (e.g. DISP's "ALL")
//   " -1" + id + values           rows; " -2" + values continues a row with more than 6 values
//   " -3"                         end of block;  " 9999" end of file
// Ids take 10 columns in the long format (FORMAT 1, what ccx writes) and 5 in the short one
// (FORMAT 0); values take 12 columns (E12.5). Binary files (FORMAT 2) are refused.
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace railwear {

// One nodal result block of one step.
struct FrdResultBlock {
  std::string name;                          // "DISP", "STRESS", "CONTACT", "ERROR", ...
  int step = 0;                              // ccx step number (1-based, from the PSTEP line)
  int increment = 0;                         // increment within the step
  double time = 0.0;                         // the step time ccx writes with the block
  std::vector<std::string> components;       // stored components in row order ("D1", "D2", "D3")
  std::vector<int> node_ids;                 // rows in file order
  std::vector<double> values;                // node_ids.size() x components.size(), row-major
  std::unordered_map<int, int> row_of_node;  // node id -> row

  size_t NumComponents() const { return components.size(); }
  // Column of a component, or -1.
  int ComponentIndex(std::string_view component) const;
  // The row of a node, or -1 when the block has no value for it.
  int Row(int node_id) const;
  double Value(int row, int component) const {
    return values[static_cast<size_t>(row) * components.size() + static_cast<size_t>(component)];
  }
};

struct FrdFile {
  std::string path;
  std::vector<int> node_ids;               // in file order
  std::vector<Eigen::Vector3d> positions;  // the node coordinates as ccx wrote them
  std::vector<FrdResultBlock> blocks;      // in file order

  // The block of that name in that step (its last increment), or nullptr. step = -1: the last
  // step that has one.
  const FrdResultBlock* Find(std::string_view name, int step = -1) const;
};

// Reads an ASCII .frd file. Throws InputError naming the file and line when it cannot be read,
// is malformed, or holds a value that is not a finite number.
FrdFile ReadFrd(const std::string& path);

// The displacement of a node in a DISP block [unit of the model] (D1, D2, D3). Throws
// std::runtime_error when the block lacks the components or the node.
Eigen::Vector3d FrdDisplacement(const FrdResultBlock& disp, int node_id);

}  // namespace railwear
