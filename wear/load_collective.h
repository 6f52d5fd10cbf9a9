// Load collectives from a multibody (MBS) time history: the rows of a vehicle-dynamics code's
// output (one row per wheel per time step or load case) read from CSV and binned into a weighted
// set of wheelset states per rail, which a wear scene can use as traffic (docs/mbs_import.md).
//
// The CSV (docs/mbs_import.md has the full contract): a header row of column names (any order,
// case-sensitive, units in the names), then one row per wheel. Required columns: exactly one of
// weight_passes / weight_m (the row's weight in wheel passes, or in metres run, dt * V), side,
// V_m_s, y_mm, yaw_mrad, Q_N. Optional: roll_mrad, xi, mu, axle_load_t. Columns named mbs_*
// hold the MBS's own results (forces...) and are averaged per bin for comparison only.
//
// Signs (core/notation.md, track frame T: x forward, Y right, z down; the high rail is the right
// rail): y_mm is the wheelset's lateral displacement toward the high rail, yaw_mrad turns the
// wheelset's nose toward the high rail, roll_mrad lowers the high-rail wheel. These are wheelset
// quantities: both wheels' rows of one wheelset carry the same y, yaw and roll.
//
// Binning: each row falls in the cell floor(value / width) of every binned quantity (y, yaw, Q,
// V and, when present, mu and xi), per rail. A bin's values are the weight-weighted means of its
// rows, so the collective keeps each rail's total weight and the weighted mean of every column
// exactly; the spread inside a bin is lost. Bins narrower than the wear's sensitivity (about
// 0.5 mm lateral) lose nothing that matters.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/numerics/enum_names.h"
#include "core/numerics/units.h"
#include "wear/traffic.h"

namespace railwear {

// What a row's weight counts: wheel passes (column weight_passes), or metres run (weight_m, the
// time step times the speed of a time history). Shares do not depend on it.
enum class WeightUnit { kPasses, kDistance };
inline constexpr std::array<EnumName<WeightUnit>, 2> kWeightUnitNames = {
    {{WeightUnit::kPasses, "passes"}, {WeightUnit::kDistance, "distance_m"}}};
inline std::string_view ToString(WeightUnit u) { return EnumToString(kWeightUnitNames, u); }

// One wheel at one time step or case, in SI.
struct MbsRow {
  int line = 0;  // line in the file (1-based), for messages
  RailSide rail = RailSide::kHigh;
  double weight = 0.0;                // >= 0, in the file's WeightUnit
  double speed_m_s = 0.0;             // > 0
  double wheelset_y_m = 0.0;          // toward the high rail
  double yaw_rad = 0.0;               // nose toward the high rail, |yaw| < 0.1 rad
  double vertical_force_N = 0.0;      // >= 0
  double roll_rad = 0.0;              // lowers the high-rail wheel; 0 when the column is absent
  std::optional<double> creepage_x;   // longitudinal creepage xi (column xi)
  std::optional<double> friction;     // mu (column mu), > 0
  std::optional<double> axle_load_t;  // column axle_load_t, > 0
  std::vector<double> mbs;            // the mbs_* columns, in MbsTimeHistory::mbs_names order
};

// A parsed CSV: which optional columns it has and its rows in file order.
struct MbsTimeHistory {
  std::string source;  // the file name as given, for messages and the collective's header
  WeightUnit weight_unit = WeightUnit::kPasses;
  bool has_roll = false;
  bool has_creepage_x = false;
  bool has_friction = false;
  bool has_axle_load = false;
  std::vector<std::string> mbs_names;  // the mbs_* column names without the prefix, file order
  std::vector<MbsRow> rows;
};

// Parses the CSV text. `source` names the file in messages ("FILE:LINE: column 'Q_N' = '-5':
// expected a number >= 0 (a wheel load in N)"). Throws InputError for a missing, unknown or
// repeated column, a row with too few or too many fields, a value that is not a finite number or
// out of the range the numerics bear (the scene's for the same quantities, issue 17: weight in
// [0, 1e15], Q in [0, 1e6] N, V in (0, 150] m/s, mu in (0, 2], axle_load_t in [0.1, 40] t,
// |y| <= 100 mm, |yaw| < 100 mrad, |roll| <= 500 mrad, |xi| <= 1), a bad
// side, and a file without data rows. '#' comment lines and blank lines are skipped; CRLF line
// ends are accepted.
MbsTimeHistory ParseMbsTimeHistory(std::string_view text, const std::string& source);

// Reads and parses the file at `path` (InputError "PATH: cannot open ..." when it cannot).
MbsTimeHistory ReadMbsTimeHistory(const std::string& path);

// Bin widths, SI. Defaults: 0.5 mm, 0.5 mrad, 5 kN, 2 m/s, 0.05, 0.001.
struct LoadCollectiveBinWidths {
  double wheelset_y_m = 0.5e-3;
  double yaw_rad = 0.5e-3;
  double vertical_force_N = 5000.0;
  double speed_m_s = 2.0;
  double friction = 0.05;
  double creepage_x = 0.001;
};

// Throws InputError naming the width (in the CLI's units, e.g. "--bin-y-mm") unless every width
// is finite and > 0.
void ValidateBinWidths(const LoadCollectiveBinWidths& widths);

// One bin: the weighted means of its rows (SI), its total weight and its share of its rail.
struct LoadCollectiveEntry {
  std::string name;  // "high 3: y 6.02 mm, yaw 2.11 mrad, Q 88.1 kN"
  RailSide rail = RailSide::kHigh;
  double wheelset_y_m = 0.0;
  double yaw_rad = 0.0;
  double roll_rad = 0.0;
  double vertical_force_N = 0.0;
  double speed_m_s = 0.0;
  std::optional<double> friction;    // when the CSV has mu
  std::optional<double> creepage_x;  // when the CSV has xi
  double share = 0.0;                // weight / the rail's total weight; sums to 1 per rail
  double weight = 0.0;               // the bin's total weight, in the collective's WeightUnit
  double axle_load_t = 0.0;          // mean of axle_load_t, else 2 Q / g / 1000 (standard g)
  std::vector<double> mbs;           // means of the mbs_* columns, LoadCollective::mbs_names
  int rows = 0;                      // rows of weight > 0 in the bin
};

struct LoadCollective {
  std::string source;        // the CSV it came from
  int rows_read = 0;         // data rows in the file
  int rows_zero_weight = 0;  // of those, rows of weight 0 (read, checked, not binned)
  WeightUnit weight_unit = WeightUnit::kPasses;
  LoadCollectiveBinWidths widths;
  bool axle_load_from_column = false;  // axle_load_t from the CSV, not from 2 Q / g
  std::vector<std::string> mbs_names;  // without the mbs_ prefix
  double total_weight_high = 0.0;
  double total_weight_low = 0.0;
  std::vector<LoadCollectiveEntry> entries;  // high rail first, then low; each by bin keys
};

// g for the axle load estimate 2 Q / g when the CSV has no axle_load_t column [m/s^2].
inline constexpr double kAxleLoadGravity_m_s2 = kGravity_m_s2;

// Bins the rows (see the file comment). Rows of weight 0 are left out; a rail without rows has
// no entries. Throws InputError when no row has a weight > 0, or for invalid widths.
LoadCollective BinLoadCollective(const MbsTimeHistory& history,
                                 const LoadCollectiveBinWidths& widths);

// Number of entries on `rail`.
int EntryCount(const LoadCollective& collective, RailSide rail);

}  // namespace railwear
