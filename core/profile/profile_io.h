// Reading and writing profile files: CSV, MiniProf .ban/.whl, SIMPACK .prr/.prw.
//
// Every reader returns the profile in railwear's profile frame (core/notation.md): millimetres
// in the file, metres inside; y lateral positive toward the field side; z positive downward
// (into the rail / toward the rail for a wheel). Conversions a format needs are applied and
// listed in ProfileFile::notes (e.g. SIMPACK mirror.y, MiniProf vertical axis pointing up).
//
// Point order: every reader returns the points ordered so that y increases from the first to the
// last point (flange / gauge side first), like the built-in profiles; for a rail LeftNormal() then
// points into the rail (+z), for a wheel out of the wheel toward the rail.
//
// Format conventions applied:
//   CSV         header "y_mm,z_mm" (extra columns, spaces, '#' comment lines allowed); frame as is.
//   SIMPACK     header keys applied in SIMPACK's order: shift, rotate (turns +y toward +z), bound,
//               mirror, inversion, units.len.f (mm when absent); header type must match the
//               extension (0 = .prr rail, 1 = .prw wheel).
//   MiniProf    .ban: y = -X; Y upward (z = -Y) unless the content shows it stored downward (the
//               crown is then the interior minimum); files written by WriteProfileBan are taken
//               as Y upward. .whl: y = X - 70 (taping line), z = Y (negated if the flange points
//               to negative Y). Measured scan glitches (a point repeating or stepping back against
//               the scan) are dropped with a note, up to max(3, 1% of the points).
#pragma once

#include <string>
#include <vector>

#include "core/profile/profile.h"

namespace railwear {

enum class ProfileFormat { kCsv, kMiniProfBan, kMiniProfWhl, kSimpackPrr, kSimpackPrw, kBuiltin };
std::string_view ToString(ProfileFormat f);  // "csv", "miniprof-ban", ...

struct ProfileFile {
  Profile profile;
  ProfileFormat format = ProfileFormat::kCsv;
  std::vector<std::string> notes;  // conversions applied, header facts (one line each)
};

// Format chosen by extension (case-insensitive: .csv, .ban, .whl, .prr, .prw) and checked by
// content. Throws InputError naming the file and line for: unknown extension, content that does
// not match the format, missing or non-numeric columns, NaN, fewer than 4 points, duplicate or
// backtracking points, unreadable file.
ProfileFile ReadProfileFile(const std::string& path);

// The points of a profile file as measured, for fitting (`railwear profile fit`): the format's
// conversions and point order (y increasing) applied, and the checks that make numbers of them
// (finite, within Profile::kMaxCoordinate_m, at least 4 points), but no duplicate, turn-back or
// crossing checks and no MiniProf scan-glitch dropping: the fit treats glitches as outliers.
// Throws InputError as ReadProfileFile for everything else.
struct ProfilePoints {
  std::vector<Eigen::Vector2d> points_m;  // shape [n][2], metres, profile frame
  std::vector<int> lines;                 // shape [n], 1-based file line of each point
  ProfileFormat format = ProfileFormat::kCsv;
  std::vector<std::string> notes;
};
ProfilePoints ReadProfilePoints(const std::string& path);

// Writers (millimetres, 6 decimals). CSV: header "y_mm,z_mm". BAN: MiniProf Key=Value header and
// X, Y columns in MiniProf's convention (the inverse of what the reader applies).
// Throw InputError when the file cannot be written.
void WriteProfileCsv(const Profile& profile, const std::string& path);
void WriteProfileBan(const Profile& profile, const std::string& path);
// Chooses the writer by extension (.csv or .ban); InputError otherwise.
void WriteProfileFile(const Profile& profile, const std::string& path);

}  // namespace railwear
