// The load-collective TOML file that `railwear traffic import` writes and a wear scene will read
// as traffic: writer and reader live together so that they cannot drift (docs/mbs_import.md).
//
// The file (units in the key names; wheelset quantities in the track frame, signs toward the
// high rail as in the CSV):
//   # comment header: source, rows, total weight per rail, bin widths, railwear version
//   [collective]
//   source = "curve_r600_mbs.csv"         # the CSV as given on the command line
//   rows_read = 320                        # data rows in the CSV
//   rows_zero_weight = 0                   # of those, rows of weight 0 (not binned)
//   weight_unit = "distance_m"             # or "passes"
//   total_weight_high = 70.4               # per rail, in weight_unit
//   total_weight_low = 70.4
//   axle_load = "2Q/g"                     # or "column": where axle_load_t comes from
//   mbs = ["Fy_N", "Fx_N"]                 # the averaged mbs_* columns, CSV order
//   bin_widths = { y_mm = 0.5, yaw_mrad = 0.5, Q_N = 5000, V_m_s = 2, mu = 0.05, xi = 0.001 }
//   [[traffic]]                            # one per bin, high rail first, then low
//   name = "high 0: y 5.96 mm, yaw 2.04 mrad, Q 88.2 kN"
//   rail = "high"
//   wheelset_y_mm = 5.96   yaw_mrad = 2.04   roll_mrad = 0.1   vertical_N = 88200
//   speed_m_s = 22   friction = 0.35 (when mu given)   creepage_x = -0.001 (when xi given)
//   share = 0.12   weight = 8.4   axle_load_t = 17.98   rows = 36
//   mbs = { Fy_N = 35000, Fx_N = -800 }    # when the CSV has mbs_* columns
#pragma once

#include <string>

#include "wear/load_collective.h"

namespace railwear::app {

// The file's text. Numbers are printed with 9 significant digits ({:.9g}), so a collective read
// back equals `c` to a relative 1e-8. `version` goes into the comment header ("" leaves it out).
std::string LoadCollectiveFileText(const LoadCollective& c, const std::string& version);

// Reads a collective file. Throws InputError "FILE:LINE: key 'traffic[3].share' = ...: expected
// ..." for a missing, unknown or malformed key, an entry whose mbs table does not hold exactly
// the [collective] mbs names, or shares that do not sum to 1 (within 1e-6) on a rail. The
// entries' optional friction / creepage_x stay absent when the file has none.
LoadCollective ReadLoadCollective(const std::string& path);

}  // namespace railwear::app
