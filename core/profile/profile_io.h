// Reading and writing profile files: CSV, MiniProf .ban/.whl, SIMPACK .prr/.prw.
//
// Every reader returns the profile in railwear's profile frame (core/notation.md): millimetres
// in the file, metres inside; y lateral positive toward the field side; z positive downward
// (into the rail / toward the rail for a wheel). Conversions a format needs are applied and
// listed in ProfileFile::notes (e.g. SIMPACK mirror.y, MiniProf vertical axis pointing up).
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

// Writers (millimetres, 6 decimals). CSV: header "y_mm,z_mm". BAN: MiniProf Key=Value header and
// X, Y columns in MiniProf's convention (the inverse of what the reader applies).
// Throw InputError when the file cannot be written.
void WriteProfileCsv(const Profile& profile, const std::string& path);
void WriteProfileBan(const Profile& profile, const std::string& path);
// Chooses the writer by extension (.csv or .ban); InputError otherwise.
void WriteProfileFile(const Profile& profile, const std::string& path);

}  // namespace railwear
