// MBS time-history CSV reader and its binning into a load collective (load_collective.h).
#include "wear/load_collective.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "core/numerics/input_error.h"
#include "core/numerics/text.h"
#include "core/numerics/text_file.h"
#include "core/numerics/units.h"

namespace railwear {
namespace {

constexpr double kMrad = 1e-3;          // mrad -> rad
constexpr double kMaxYaw_mrad = 100.0;  // as the scenes: the yawed outline needs |yaw| << 1 rad
constexpr double kMaxBinIndex = 1e15;   // |value / width| beyond this cannot be a bin index
constexpr std::string_view kMbsPrefix = "mbs_";

// The columns other than mbs_*, in the order the docs list them.
enum class Column {
  kWeightPasses,
  kWeightDistance,
  kSide,
  kSpeed,
  kY,
  kYaw,
  kQ,
  kRoll,
  kXi,
  kMu,
  kAxleLoad,
  kMbs,
};

struct ColumnName {
  Column column;
  std::string_view name;
};
constexpr std::array<ColumnName, 11> kColumns = {{
    {Column::kWeightPasses, "weight_passes"},
    {Column::kWeightDistance, "weight_m"},
    {Column::kSide, "side"},
    {Column::kSpeed, "V_m_s"},
    {Column::kY, "y_mm"},
    {Column::kYaw, "yaw_mrad"},
    {Column::kQ, "Q_N"},
    {Column::kRoll, "roll_mrad"},
    {Column::kXi, "xi"},
    {Column::kMu, "mu"},
    {Column::kAxleLoad, "axle_load_t"},
}};
constexpr std::string_view kRequiredNames = "side, V_m_s, y_mm, yaw_mrad, Q_N";
constexpr std::string_view kAllNames =
    "weight_passes or weight_m, side, V_m_s, y_mm, yaw_mrad, Q_N, roll_mrad, xi, mu, "
    "axle_load_t, mbs_<name>";

std::vector<std::string_view> SplitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    std::string_view line =
        text.substr(start, end == std::string_view::npos ? text.npos : end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return lines;
}

std::vector<std::string> SplitFields(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(Trim(line.substr(start, comma == line.npos ? line.npos : comma - start)));
    if (comma == line.npos) break;
    start = comma + 1;
  }
  return fields;
}

bool IsBareKey(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::string Shorten(std::string_view s) {
  constexpr std::size_t kMax = 60;
  return s.size() <= kMax ? std::string(s) : std::string(s.substr(0, kMax)) + "...";
}

// Where a value came from, for messages.
struct Cell {
  const std::string& source;
  int line;
  const std::string& column;
  const std::string& value;
};

[[noreturn]] void FailValue(const Cell& c, std::string_view expected) {
  throw InputError(fmt::format("{}:{}: column '{}' = '{}': expected {}", c.source, c.line, c.column,
                               Shorten(c.value), expected));
}

// A finite number satisfying `ok`; the message says `expected`.
double Number(const Cell& c, const std::function<bool(double)>& ok, std::string_view expected) {
  const std::optional<double> v = ParseFiniteDouble(c.value);
  if (!v || !ok(*v)) FailValue(c, expected);
  return *v;
}

struct Header {
  int line = 0;
  std::vector<std::string> names;
  std::vector<Column> columns;  // per field
  std::vector<int> mbs_index;   // per field: index into mbs_names, -1 for other columns
};

Header ParseHeader(const std::string& source, int line, std::string_view text, MbsTimeHistory* h) {
  Header header;
  header.line = line;
  header.names = SplitFields(text);
  const auto fail = [&](const std::string& message) {
    throw InputError(fmt::format("{}:{}: {}", source, line, message));
  };
  std::map<std::string, int> seen;
  for (int i = 0; i < static_cast<int>(header.names.size()); ++i) {
    const std::string& name = header.names[i];
    if (name.empty()) {
      fail(fmt::format("header field {} is empty: expected a column name ({})", i + 1, kAllNames));
    }
    if (const auto it = seen.find(name); it != seen.end()) {
      fail(
          fmt::format("column '{}' appears twice (header fields {} and {}): expected each "
                      "column once",
                      name, it->second + 1, i + 1));
    }
    seen.emplace(name, i);
    const auto known = std::find_if(kColumns.begin(), kColumns.end(),
                                    [&](const ColumnName& c) { return c.name == name; });
    if (known != kColumns.end()) {
      header.columns.push_back(known->column);
      header.mbs_index.push_back(-1);
      continue;
    }
    if (name.rfind(kMbsPrefix, 0) == 0 && IsBareKey(name.substr(kMbsPrefix.size()))) {
      header.columns.push_back(Column::kMbs);
      header.mbs_index.push_back(static_cast<int>(h->mbs_names.size()));
      h->mbs_names.push_back(name.substr(kMbsPrefix.size()));
      continue;
    }
    if (name == "weight") {
      fail(
          fmt::format("column 'weight': expected 'weight_passes' (wheel passes) or 'weight_m' "
                      "(metres run, dt * V): the name says what the weight counts"));
    }
    fail(
        fmt::format("column '{}' is unknown: expected one of {} (names are case-sensitive; "
                    "mbs_ columns: letters, digits and '_')",
                    Shorten(name), kAllNames));
  }
  const auto has = [&](Column c) {
    return std::find(header.columns.begin(), header.columns.end(), c) != header.columns.end();
  };
  const bool passes = has(Column::kWeightPasses);
  const bool distance = has(Column::kWeightDistance);
  if (passes && distance) {
    fail("columns 'weight_passes' and 'weight_m' both present: expected one weight column");
  }
  if (!passes && !distance) {
    fail(
        "missing required column 'weight_passes' or 'weight_m' (the row's weight in wheel "
        "passes, or in metres run)");
  }
  for (const ColumnName& c : kColumns) {
    const bool required = c.column == Column::kSide || c.column == Column::kSpeed ||
                          c.column == Column::kY || c.column == Column::kYaw ||
                          c.column == Column::kQ;
    if (required && !has(c.column)) {
      fail(fmt::format("missing required column '{}' (required: weight_passes or weight_m, {})",
                       c.name, kRequiredNames));
    }
  }
  h->weight_unit = passes ? WeightUnit::kPasses : WeightUnit::kDistance;
  h->has_roll = has(Column::kRoll);
  h->has_creepage_x = has(Column::kXi);
  h->has_friction = has(Column::kMu);
  h->has_axle_load = has(Column::kAxleLoad);
  return header;
}

MbsRow ParseRow(const std::string& source, int line, std::string_view text, const Header& header,
                int mbs_count) {
  std::vector<std::string> fields = SplitFields(text);
  const std::size_t n = header.names.size();
  if (fields.size() > n) {
    throw InputError(fmt::format(
        "{}:{}: {} fields, expected {} as in the header (line {}); fields are separated by ',' "
        "and never quoted",
        source, line, fields.size(), n, header.line));
  }
  MbsRow row;
  row.line = line;
  row.mbs.assign(mbs_count, 0.0);
  const auto finite = [](double) { return true; };
  for (std::size_t i = 0; i < n; ++i) {
    static const std::string kEmpty;
    const std::string& value = i < fields.size() ? fields[i] : kEmpty;
    const Cell c{source, line, header.names[i], value};
    if (i >= fields.size()) {
      FailValue(c, fmt::format("a value (the row has {} fields, the header of line {} has {})",
                               fields.size(), header.line, n));
    }
    switch (header.columns[i]) {
      case Column::kWeightPasses:
      case Column::kWeightDistance:
        row.weight = Number(
            c, [](double v) { return v >= 0.0 && v <= 1e15; }, "a number in [0, 1e15] (the weight)");
        break;
      case Column::kSide:
        if (value == "high" || value == "right") {
          row.rail = RailSide::kHigh;
        } else if (value == "low" || value == "left") {
          row.rail = RailSide::kLow;
        } else {
          FailValue(c, "'high' or 'low' (or 'right' / 'left': right is the high rail)");
        }
        break;
      case Column::kSpeed:
        row.speed_m_s = Number(
            c, [](double v) { return v > 0.0 && v <= 150.0; }, "a number in (0, 150] (speed in m/s)");
        break;
      case Column::kY:
        row.wheelset_y_m = Number(
                               c, [](double v) { return std::abs(v) <= 100.0; },
                               "a number in [-100, 100] (mm)") *
                           kMm;
        break;
      case Column::kYaw:
        row.yaw_rad = Number(
                          c, [](double v) { return std::abs(v) < kMaxYaw_mrad; },
                          "a number in (-100, 100) (mrad)") *
                      kMrad;
        break;
      case Column::kQ:
        row.vertical_force_N = Number(
            c, [](double v) { return v >= 0.0 && v <= 1e6; },
            "a number in [0, 1e6] (a wheel load in N)");
        break;
      case Column::kRoll:
        row.roll_rad = Number(
                           c, [](double v) { return std::abs(v) <= 500.0; },
                           "a number in [-500, 500] (mrad)") *
                       kMrad;
        break;
      case Column::kXi:
        row.creepage_x = Number(
            c, [](double v) { return std::abs(v) <= 1.0; },
            "a number in [-1, 1] (longitudinal creepage)");
        break;
      case Column::kMu:
        row.friction = Number(
            c, [](double v) { return v > 0.0 && v <= 2.0; }, "a number in (0, 2] (friction)");
        break;
      case Column::kAxleLoad:
        row.axle_load_t = Number(
            c, [](double v) { return v >= 0.1 && v <= 40.0; }, "a number in [0.1, 40] (tonnes)");
        break;
      case Column::kMbs:
        row.mbs[header.mbs_index[i]] = Number(c, finite, "a finite number");
        break;
    }
  }
  return row;
}

// Bin of a value: floor(value / width), checked to fit an integer.
std::int64_t BinIndex(const MbsRow& row, const std::string& source, std::string_view column,
                      double value, double width) {
  const double q = std::floor(value / width);
  if (!(std::abs(q) < kMaxBinIndex)) {
    throw InputError(
        fmt::format("{}:{}: column '{}' = {}: expected a value within 1e15 bin "
                    "widths of 0",
                    source, row.line, column, value));
  }
  return static_cast<std::int64_t>(q);
}

// Weighted sums of one bin.
struct Sums {
  double weight = 0.0;
  double y = 0.0, yaw = 0.0, roll = 0.0, q = 0.0, v = 0.0, mu = 0.0, xi = 0.0, axle = 0.0;
  std::vector<double> mbs;
  int rows = 0;
};

}  // namespace

MbsTimeHistory ParseMbsTimeHistory(std::string_view text, const std::string& source) {
  MbsTimeHistory h;
  h.source = source;
  std::optional<Header> header;
  const std::vector<std::string_view> lines = SplitLines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    const std::string trimmed = Trim(lines[i]);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    if (!header) {
      header = ParseHeader(source, line, lines[i], &h);
      continue;
    }
    h.rows.push_back(
        ParseRow(source, line, lines[i], *header, static_cast<int>(h.mbs_names.size())));
  }
  if (!header) {
    throw InputError(
        fmt::format("{}: no header row: expected a line of column names ({})", source, kAllNames));
  }
  if (h.rows.empty()) {
    throw InputError(
        fmt::format("{}: no data rows after the header (line {}): expected one row "
                    "per wheel per time step or case",
                    source, header->line));
  }
  return h;
}

MbsTimeHistory ReadMbsTimeHistory(const std::string& path) {
  const std::optional<std::string> text = ReadTextFile(path);
  if (!text) {
    throw InputError(fmt::format("{}: cannot open the MBS time-history CSV", path));
  }
  return ParseMbsTimeHistory(*text, path);
}

void ValidateBinWidths(const LoadCollectiveBinWidths& w) {
  const auto check = [](double value, double to_option_unit, std::string_view option) {
    if (!(std::isfinite(value) && value > 0.0)) {
      throw InputError(
          fmt::format("{} = {}: expected a bin width > 0", option, value * to_option_unit));
    }
  };
  check(w.wheelset_y_m, kToMm, "--bin-y-mm");
  check(w.yaw_rad, 1.0 / kMrad, "--bin-yaw-mrad");
  check(w.vertical_force_N, 1e-3, "--bin-q-kN");
  check(w.speed_m_s, 1.0, "--bin-v-m-s");
  check(w.friction, 1.0, "--bin-mu");
  check(w.creepage_x, 1.0, "--bin-xi");
}

LoadCollective BinLoadCollective(const MbsTimeHistory& h, const LoadCollectiveBinWidths& widths) {
  ValidateBinWidths(widths);
  LoadCollective out;
  out.source = h.source;
  out.rows_read = static_cast<int>(h.rows.size());
  out.weight_unit = h.weight_unit;
  out.widths = widths;
  out.axle_load_from_column = h.has_axle_load;
  out.mbs_names = h.mbs_names;

  // Key: rail first (high before low), then the bin indices of y, yaw, Q, V, mu, xi (0 for an
  // absent column): std::map's lexicographic order is the output order.
  using Key = std::pair<int, std::array<std::int64_t, 6>>;
  std::map<Key, Sums> bins;
  for (const MbsRow& r : h.rows) {
    if (r.weight == 0.0) {
      ++out.rows_zero_weight;
      continue;
    }
    Key key{r.rail == RailSide::kHigh ? 0 : 1,
            {BinIndex(r, h.source, "y_mm", r.wheelset_y_m, widths.wheelset_y_m),
             BinIndex(r, h.source, "yaw_mrad", r.yaw_rad, widths.yaw_rad),
             BinIndex(r, h.source, "Q_N", r.vertical_force_N, widths.vertical_force_N),
             BinIndex(r, h.source, "V_m_s", r.speed_m_s, widths.speed_m_s),
             r.friction ? BinIndex(r, h.source, "mu", *r.friction, widths.friction) : 0,
             r.creepage_x ? BinIndex(r, h.source, "xi", *r.creepage_x, widths.creepage_x) : 0}};
    Sums& s = bins[key];
    const double w = r.weight;
    s.weight += w;
    s.y += w * r.wheelset_y_m;
    s.yaw += w * r.yaw_rad;
    s.roll += w * r.roll_rad;
    s.q += w * r.vertical_force_N;
    s.v += w * r.speed_m_s;
    if (r.friction) s.mu += w * *r.friction;
    if (r.creepage_x) s.xi += w * *r.creepage_x;
    if (r.axle_load_t) s.axle += w * *r.axle_load_t;
    s.mbs.resize(r.mbs.size(), 0.0);
    for (std::size_t k = 0; k < r.mbs.size(); ++k) s.mbs[k] += w * r.mbs[k];
    ++s.rows;
    (r.rail == RailSide::kHigh ? out.total_weight_high : out.total_weight_low) += w;
  }
  if (bins.empty()) {
    throw InputError(
        fmt::format("{}: all {} rows have weight 0: expected at least one row of "
                    "weight > 0",
                    h.source, out.rows_read));
  }

  int index_on_rail = 0;
  int previous_rail = -1;
  for (const auto& [key, s] : bins) {
    if (key.first != previous_rail) index_on_rail = 0;
    previous_rail = key.first;
    LoadCollectiveEntry e;
    e.rail = key.first == 0 ? RailSide::kHigh : RailSide::kLow;
    e.weight = s.weight;
    e.rows = s.rows;
    e.wheelset_y_m = s.y / s.weight;
    e.yaw_rad = s.yaw / s.weight;
    e.roll_rad = s.roll / s.weight;
    e.vertical_force_N = s.q / s.weight;
    e.speed_m_s = s.v / s.weight;
    if (h.has_friction) e.friction = s.mu / s.weight;
    if (h.has_creepage_x) e.creepage_x = s.xi / s.weight;
    e.axle_load_t = h.has_axle_load ? s.axle / s.weight
                                    : 2.0 * e.vertical_force_N / kAxleLoadGravity_m_s2 / 1000.0;
    e.mbs.resize(s.mbs.size());
    for (std::size_t k = 0; k < s.mbs.size(); ++k) e.mbs[k] = s.mbs[k] / s.weight;
    const double total = e.rail == RailSide::kHigh ? out.total_weight_high : out.total_weight_low;
    e.share = s.weight / total;
    e.name = fmt::format("{} {}: y {:.2f} mm, yaw {:.2f} mrad, Q {:.1f} kN", ToString(e.rail),
                         index_on_rail, e.wheelset_y_m * kToMm, e.yaw_rad / kMrad,
                         e.vertical_force_N * 1e-3);
    ++index_on_rail;
    out.entries.push_back(std::move(e));
  }
  return out;
}

int EntryCount(const LoadCollective& collective, RailSide rail) {
  return static_cast<int>(
      std::count_if(collective.entries.begin(), collective.entries.end(),
                    [&](const LoadCollectiveEntry& e) { return e.rail == rail; }));
}

}  // namespace railwear
