// CalculiX .frd reader. See frd_file.h for the format.
#include "calibration/fem/frd_file.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/numerics/input_error.h"
#include "core/numerics/text.h"

namespace railwear {
namespace {

constexpr size_t kValueWidth = 12;  // E12.5

// Columns [begin, begin + width) of a line, empty past its end.
std::string_view Columns(std::string_view line, size_t begin, size_t width) {
  if (begin >= line.size()) return {};
  return line.substr(begin, width);
}

std::optional<int> ParseInt(std::string_view field) {
  const std::string t = Trim(field);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (end != t.c_str() + t.size()) return std::nullopt;
  return static_cast<int>(v);
}

std::vector<std::string> Tokens(std::string_view line) {
  std::istringstream is{std::string(line)};
  std::vector<std::string> out;
  std::string t;
  while (is >> t) out.push_back(t);
  return out;
}

class FrdParser {
 public:
  explicit FrdParser(const std::string& path) : path_(path) { file_.path = path; }

  FrdFile Parse() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot open the CalculiX result file", path_));
    std::string line;
    while (std::getline(in, line)) {
      ++number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (!Line(line)) break;
    }
    if (state_ != State::kTop) Fail("the file ends inside a block; expected ' -3'");
    return std::move(file_);
  }

 private:
  enum class State { kTop, kNodes, kElements, kResult };

  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(fmt::format("{}:{}: {}", path_, number_, message));
  }

  // The FORMAT flag (last token of a block header): 0 short, 1 long; 2 (binary) is refused.
  void ReadFormat(std::string_view line) {
    const auto tokens = Tokens(line);
    const auto f = tokens.empty() ? std::nullopt : ParseInt(tokens.back());
    if (!f || (*f != 0 && *f != 1)) {
      Fail(
          fmt::format("block header '{}': expected the ASCII format flag 0 or 1 at its end "
                      "(binary .frd files are not supported)",
                      Trim(line)));
    }
    id_width_ = *f == 0 ? 5 : 10;
  }

  // Values of a " -1" or " -2" row from column 3 + id_width_.
  void ReadValues(std::string_view line, std::vector<double>* values) {
    for (size_t c = 3 + id_width_; c < line.size(); c += kValueWidth) {
      const std::string_view field = Columns(line, c, kValueWidth);
      if (Trim(field).empty()) break;
      const auto v = ParseFiniteDouble(field);
      if (!v) Fail(fmt::format("'{}' is not a finite number (in '{}')", Trim(field), Trim(line)));
      values->push_back(*v);
    }
  }

  int ReadId(std::string_view line) {
    const auto id = ParseInt(Columns(line, 3, id_width_));
    if (!id)
      Fail(fmt::format("'{}': expected a node id in columns 4-{}", Trim(line), 3 + id_width_));
    return *id;
  }

  void FinishRow() {
    if (block_.node_ids.empty()) return;
    const size_t expected = block_.node_ids.size() * block_.components.size();
    if (block_.values.size() != expected) {
      Fail(fmt::format(
          "node {} of block {} has {} value(s); expected {}", block_.node_ids.back(), block_.name,
          block_.values.size() - (block_.node_ids.size() - 1) * block_.components.size(),
          block_.components.size()));
    }
  }

  // Returns false at the end-of-file marker.
  bool Line(const std::string& line) {
    const std::string_view key = Columns(line, 0, 3);
    switch (state_) {
      case State::kTop: {
        if (Trim(line) == "9999") return false;
        const std::string head = Trim(Columns(line, 0, 6));
        if (head == "2C") {
          ReadFormat(line);
          state_ = State::kNodes;
        } else if (head == "3C") {
          state_ = State::kElements;
        } else if (line.rfind("    1PSTEP", 0) == 0) {
          const auto tokens = Tokens(line);
          if (tokens.size() < 4)
            Fail(fmt::format("'{}': expected '1PSTEP set increment step'", Trim(line)));
          const auto inc = ParseInt(tokens[2]);
          const auto step = ParseInt(tokens[3]);
          if (!inc || !step)
            Fail(fmt::format("'{}': expected '1PSTEP set increment step'", Trim(line)));
          increment_ = *inc;
          step_ = *step;
        } else if (head.rfind("100C", 0) == 0) {
          ReadFormat(line);
          block_ = FrdResultBlock{};
          block_.step = step_;
          block_.increment = increment_;
          const auto time = ParseFiniteDouble(Columns(line, 12, kValueWidth));
          if (!time) Fail(fmt::format("'{}': expected the step time in columns 13-24", Trim(line)));
          block_.time = *time;
          state_ = State::kResult;
        }
        // "    1C" (model name), "    1U..." (user headers) and anything else: ignored.
        return true;
      }
      case State::kNodes: {
        if (key == " -3") {
          state_ = State::kTop;
        } else if (key == " -1") {
          const int id = ReadId(line);
          std::vector<double> xyz;
          ReadValues(line, &xyz);
          if (xyz.size() != 3)
            Fail(fmt::format("node {} has {} coordinate(s); expected 3", id, xyz.size()));
          file_.node_ids.push_back(id);
          file_.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
        } else {
          Fail(fmt::format("'{}' in the node block; expected ' -1' rows or ' -3'", Trim(line)));
        }
        return true;
      }
      case State::kElements: {
        if (key == " -3") state_ = State::kTop;
        return true;
      }
      case State::kResult: {
        if (key == " -4") {
          block_.name = Trim(Columns(line, 5, 8));
        } else if (key == " -5") {
          const auto exists = ParseInt(Columns(line, 33, 5));
          if (!exists || *exists != 1) block_.components.push_back(Trim(Columns(line, 5, 8)));
        } else if (key == " -1") {
          FinishRow();
          if (block_.components.empty())
            Fail("a data row before the block's ' -5' component lines");
          const int id = ReadId(line);
          if (!block_.row_of_node.emplace(id, static_cast<int>(block_.node_ids.size())).second) {
            Fail(fmt::format("node {} given twice in block {}", id, block_.name));
          }
          block_.node_ids.push_back(id);
          ReadValues(line, &block_.values);
        } else if (key == " -2") {
          if (block_.node_ids.empty()) Fail("a ' -2' continuation line without a ' -1' row");
          ReadValues(line, &block_.values);
        } else if (key == " -3") {
          FinishRow();
          if (block_.name.empty()) Fail("a result block without its ' -4' name line");
          file_.blocks.push_back(std::move(block_));
          block_ = FrdResultBlock{};
          state_ = State::kTop;
        } else {
          Fail(
              fmt::format("'{}' in result block {}; expected ' -4', ' -5', ' -1', ' -2' or ' -3' "
                          "lines",
                          Trim(line), block_.name));
        }
        return true;
      }
    }
    return true;
  }

  std::string path_;
  FrdFile file_;
  FrdResultBlock block_;
  State state_ = State::kTop;
  size_t id_width_ = 10;
  int step_ = 0, increment_ = 0;
  int number_ = 0;
};

}  // namespace

int FrdResultBlock::ComponentIndex(std::string_view component) const {
  for (size_t i = 0; i < components.size(); ++i) {
    if (components[i] == component) return static_cast<int>(i);
  }
  return -1;
}

int FrdResultBlock::Row(int node_id) const {
  const auto it = row_of_node.find(node_id);
  return it == row_of_node.end() ? -1 : it->second;
}

const FrdResultBlock* FrdFile::Find(std::string_view name, int step) const {
  const FrdResultBlock* found = nullptr;
  for (const FrdResultBlock& b : blocks) {
    if (b.name == name && (step < 0 || b.step == step)) found = &b;  // the last one wins
  }
  return found;
}

FrdFile ReadFrd(const std::string& path) { return FrdParser(path).Parse(); }

Eigen::Vector3d FrdDisplacement(const FrdResultBlock& disp, int node_id) {
  const int row = disp.Row(node_id);
  const int d1 = disp.ComponentIndex("D1"), d2 = disp.ComponentIndex("D2"),
            d3 = disp.ComponentIndex("D3");
  if (row < 0 || d1 < 0 || d2 < 0 || d3 < 0) {
    throw std::runtime_error(fmt::format("result block {} (step {}) has no displacement of node {}",
                                         disp.name, disp.step, node_id));
  }
  return {disp.Value(row, d1), disp.Value(row, d2), disp.Value(row, d3)};
}

}  // namespace railwear
