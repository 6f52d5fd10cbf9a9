// The influence constants of the seed's eq. 4 as the app reads and writes them: the TOML table a
// scene gives inline ([model] influence_constants = { ... }) or names as a file, the file that
// `railwear calibrate` writes and scenes load, and the JSON and one-line text forms of the
// outputs. Reading, writing and the text forms live here together so that they cannot drift.
//
// The file:
//   # provenance comments (calibrate's)
//   [influence_constants]            one set for both bodies
//   c_f = 0.75
//   c_z = 1.0
//   c_s = 0.25
// or separate sets per curvature sign, [influence_constants.convex] and
// [influence_constants.concave], each with c_f, c_z, c_s. The constants are dimensionless.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/contact/contact_types.h"

namespace railwear::app {

class Fields;  // app/toml_fields.h

// What a constants table may be, for messages: "{ c_f, c_z, c_s } (one set for both bodies) or
// { convex = {...}, concave = {...} } (a set for each curvature sign)".
extern const char* const kInfluenceConstantsExpected;

// An influence-constants table: one set { c_f, c_z, c_s } (each key optional, the seed's values
// by default), or separate sets { convex = {...}, concave = {...} } (both required), never a
// mixture. Throws InputError naming the file, line and key.
InfluenceConstants ReadInfluenceConstantsTable(const Fields& table);

// Reads a TOML file with an [influence_constants] table (what `railwear calibrate` writes and a
// scene names with influence_constants = "FILE"): { c_f, c_z, c_s } or { convex = {...},
// concave = {...} }. Throws InputError naming the file, line and key.
InfluenceConstants ReadInfluenceConstantsFile(const std::string& path);

// The file's text: `header` (comment lines, each ending in a newline; may be empty), a blank
// line, then the [influence_constants] table(s) of `c` with every digit fmt's shortest
// round-trip form gives.
std::string InfluenceConstantsFileText(const std::string& header, const InfluenceConstants& c);

// Writes `text` (InfluenceConstantsFileText) to `path` and reads it back as a scene would.
// Throws InputError when the file cannot be written, std::runtime_error when it does not read
// back as `expected`.
void WriteInfluenceConstantsFile(const std::string& path, const std::string& text,
                                 const InfluenceConstants& expected);

// The constants as JSON: {c_f, c_z, c_s}, or {convex: {...}, concave: {...}} for separate sets.
nlohmann::json InfluenceConstantsJson(const InfluenceConstants& c);
// ... and as text, "c_f 0.75 c_z 1 c_s 0.25" or "convex c_f ... c_s ..., concave c_f ...".
std::string InfluenceConstantsText(const InfluenceConstants& c);

// The name of a named set ("fem", "paper": core's kInfluenceConstantsNames) equal to `c`, else
// "custom" (a file or an inline table with other values).
std::string ConstantsSetName(const InfluenceConstants& c);
// "constants NAME (c_f .. c_z .. c_s .., 4 digits)": the summaries' account of the constants.
std::string InfluenceConstantsLine(const InfluenceConstants& c);

}  // namespace railwear::app
