// Profile file readers (CSV, MiniProf .ban/.whl, SIMPACK .prr/.prw) and writers (CSV, .ban).
//
// Each reader collects raw points with the 1-based file line they came from, applies the format's
// conversions into railwear's profile frame (mm, y toward the field side, z downward), validates
// the points itself so that errors can name the file line, and orders them so that y increases
// from the first to the last point (the convention of the built-in profiles).
#include "core/profile/profile_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "core/numerics/input_error.h"
#include "core/numerics/text.h"
#include "core/profile/profile_defects.h"

namespace railwear {

namespace {

constexpr double kPi = 3.14159265358979323846;

// MiniProf wheel profiles: lateral X from the flange back; the taping line is 70 mm from it
// (EN 13715).
constexpr double kMiniProfTapingLineX_mm = 70.0;
// Lateral window (MiniProf X, mm) that holds the flange of a wheel profile.
constexpr double kFlangeWindowMin_mm = 5.0;
constexpr double kFlangeWindowMax_mm = 35.0;
// Written into .ban files by WriteProfileBan; the reader then trusts MiniProf's native Y-up.
constexpr const char* kRailwearProgramName = "railwear";

struct RawPoint {
  double y = 0.0, z = 0.0;  // millimetres until the final conversion
  int line = 0;             // 1-based line in the file
};

// What a reader collected: points in the profile frame (mm) with their lines, before the
// final ordering and checks.
struct RawRead {
  std::vector<RawPoint> pts;
  ProfileFormat format = ProfileFormat::kCsv;
  std::vector<std::string> notes;
  int last_line = 1;
};

// kProfile: a profile for use (MiniProf scan glitches dropped, every check applied).
// kPoints: the points as measured, for `profile fit`, which rejects glitches itself.
enum class ReadMode { kProfile, kPoints };

struct Line {
  int number = 0;
  std::string text;
};

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool StartsWith(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

// Splits on any of `separators`, dropping empty tokens.
std::vector<std::string> Split(std::string_view s, std::string_view separators) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < s.size()) {
    const size_t j = s.find_first_of(separators, i);
    const size_t end = j == std::string_view::npos ? s.size() : j;
    if (end > i) out.emplace_back(s.substr(i, end - i));
    if (j == std::string_view::npos) break;
    i = j + 1;
  }
  return out;
}

// Parses a whole token as a double (NaN and inf are parsed; callers check finiteness).
std::optional<double> ParseNumber(std::string_view token) {
  const std::string t = Trim(token);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size()) return std::nullopt;
  return v;
}

bool IsNumber(std::string_view token) { return ParseNumber(token).has_value(); }

std::vector<Line> ReadLines(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError(fmt::format("{}: cannot read profile file: no such file", path));
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(fmt::format("{}: cannot read profile file: it is a directory", path));
  }
  std::ifstream in(path);
  if (!in) {
    throw InputError(fmt::format("{}: cannot read profile file: {}", path, std::strerror(errno)));
  }
  std::vector<Line> lines;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    lines.push_back({number, std::move(text)});
  }
  if (in.bad()) {
    throw InputError(fmt::format("{}: error while reading the profile file", path));
  }
  return lines;
}

// Parses the first two tokens of a data line as y and z; throws naming the line otherwise.
RawPoint ParsePointTokens(const std::vector<std::string>& tokens, const std::string& path,
                          const Line& line, std::string_view expected) {
  if (tokens.size() < 2) {
    throw InputError(fmt::format("{}:{}: '{}' has {} column(s); expected {}", path, line.number,
                                 Trim(line.text), tokens.size(), expected));
  }
  RawPoint p;
  p.line = line.number;
  for (int k = 0; k < 2; ++k) {
    const auto v = ParseNumber(tokens[k]);
    if (!v) {
      throw InputError(fmt::format("{}:{}: column {} is '{}', not a number; expected {}", path,
                                   line.number, k + 1, Trim(tokens[k]), expected));
    }
    if (!std::isfinite(*v)) {
      throw InputError(fmt::format("{}:{}: column {} is '{}'; expected a finite number ({})", path,
                                   line.number, k + 1, Trim(tokens[k]), expected));
    }
    (k == 0 ? p.y : p.z) = *v;
  }
  return p;
}

// Every coordinate within Profile::kMaxCoordinate_m, naming the first line beyond it (before any
// arithmetic on the points: products of 1e300 mm coordinates overflow).
void CheckCoordinateRange(const std::vector<RawPoint>& pts, const std::string& path) {
  const double max_mm = Profile::kMaxCoordinate_m * 1e3;
  for (const RawPoint& p : pts) {
    if (std::abs(p.y) > max_mm || std::abs(p.z) > max_mm) {
      throw InputError(
          fmt::format("{}:{}: point (y = {}, z = {} mm) lies beyond {} mm of the origin; expected "
                      "coordinates within +-{} mm (after units.len.f and transformations)",
                      path, p.line, p.y, p.z, max_mm, max_mm));
    }
  }
}

std::vector<Eigen::Vector2d> MillimetrePoints(const std::vector<RawPoint>& pts) {
  std::vector<Eigen::Vector2d> mm;
  mm.reserve(pts.size());
  for (const RawPoint& p : pts) mm.emplace_back(p.y, p.z);
  return mm;
}

// The checks of the Profile constructor, on millimetre points, naming file lines.
void ValidatePoints(const std::vector<RawPoint>& pts, const std::string& path, int last_line) {
  CheckCoordinateRange(pts, path);
  if (pts.size() < 4) {
    throw InputError(
        fmt::format("{}:{}: {} profile point(s) read by the end of the file; expected at least 4",
                    path, last_line, pts.size()));
  }
  const auto defect = FindProfileDefect(MillimetrePoints(pts), 1e3);
  if (!defect) return;
  const RawPoint& pa = pts[defect->a];
  const RawPoint& pb = pts[defect->b];
  switch (defect->kind) {
    case ProfileDefect::Kind::kDuplicate:
      throw InputError(fmt::format(
          "{}:{}: point (y = {:.6f}, z = {:.6f} mm) duplicates the point on line {}; expected "
          "distinct consecutive points",
          path, pb.line, pb.y, pb.z, pa.line));
    case ProfileDefect::Kind::kTurnBack:
      throw InputError(fmt::format(
          "{}:{}: point (y = {:.6f}, z = {:.6f} mm) turns the profile back by {:.1f} degrees "
          "after line {}; expected points ordered along the profile (turns up to 150 degrees)",
          path, pb.line, pb.y, pb.z, defect->turn_rad * 180.0 / kPi, pa.line));
    case ProfileDefect::Kind::kCrossing: {
      const RawPoint& pa1 = pts[defect->a + 1];
      const RawPoint& pb1 = pts[defect->b + 1];
      throw InputError(fmt::format(
          "{}:{}: the profile crosses itself: the segment from line {} (y = {:.6f}, z = {:.6f} "
          "mm) to line {} (y = {:.6f}, z = {:.6f} mm) crosses the segment from line {} "
          "(y = {:.6f}, z = {:.6f} mm) to line {} (y = {:.6f}, z = {:.6f} mm) at (y = {:.6f}, "
          "z = {:.6f} mm); expected a profile that does not cross itself",
          path, pb.line, pa.line, pa.y, pa.z, pa1.line, pa1.y, pa1.z, pb.line, pb.y, pb.z, pb1.line,
          pb1.y, pb1.z, defect->crossing.x(), defect->crossing.y()));
    }
  }
}

// Measured MiniProf profiles carry scan glitches: a point that repeats its predecessor or steps
// back against the scan direction (avg_HR.BAN line 136 steps back 0.01 mm; Car7216_0001r.whl line
// 223 jumps back 0.6 mm at the flange tip). Such points are dropped, each with a note naming its
// line, up to max(3, 1% of the points); more than that is a badly ordered file and is an error
// (ValidatePoints reports the first offending line).
void DropScanGlitches(std::vector<RawPoint>* pts, const std::string& path, int last_line,
                      std::vector<std::string>* notes) {
  CheckCoordinateRange(*pts, path);
  const size_t max_drops = std::max<size_t>(3, pts->size() / 100);
  const double dup_mm = Profile::kDuplicateDistance_m * 1e3;
  const double cos_max_turn = std::cos(Profile::kMaxTurnAngle_rad);
  std::vector<RawPoint> kept;
  std::vector<std::string> dropped;
  kept.reserve(pts->size());
  for (const RawPoint& p : *pts) {
    const size_t k = kept.size();
    bool glitch = false;
    if (k >= 1 && std::hypot(p.y - kept[k - 1].y, p.z - kept[k - 1].z) < dup_mm) {
      glitch = true;
      dropped.push_back(fmt::format("line {} (repeats line {})", p.line, kept[k - 1].line));
    } else if (k >= 2) {
      const double ay = kept[k - 1].y - kept[k - 2].y, az = kept[k - 1].z - kept[k - 2].z;
      const double by = p.y - kept[k - 1].y, bz = p.z - kept[k - 1].z;
      if (ay * by + az * bz < cos_max_turn * std::hypot(ay, az) * std::hypot(by, bz)) {
        glitch = true;
        dropped.push_back(
            fmt::format("line {} (steps back {:.3f} mm)", p.line, std::hypot(by, bz)));
      }
    }
    if (!glitch) kept.push_back(p);
  }
  if (dropped.empty()) return;
  if (dropped.size() > max_drops) {
    ValidatePoints(*pts, path, last_line);  // throws, naming the first offending line
  }
  for (const auto& d : dropped) notes->push_back("scan glitch dropped: " + d);
  *pts = std::move(kept);
}

// Orders the points so that y increases from first to last, validates and builds the Profile.
Profile Finish(std::vector<RawPoint> pts, const std::string& path, int last_line,
               std::vector<std::string>* notes) {
  ValidatePoints(pts, path, last_line);
  if (pts.front().y > pts.back().y) {
    std::reverse(pts.begin(), pts.end());
    notes->push_back("point order reversed so that y increases along the profile");
  }
  std::vector<Eigen::Vector2d> m;
  m.reserve(pts.size());
  for (const auto& p : pts) m.emplace_back(p.y * 1e-3, p.z * 1e-3);
  return Profile(std::move(m), path);
}

int LastLine(const std::vector<Line>& lines) { return lines.empty() ? 1 : lines.back().number; }

// ------------------------------------------------------------------------------------ CSV

RawRead ReadCsv(const std::string& path) {
  const auto lines = ReadLines(path);
  RawRead out;
  out.format = ProfileFormat::kCsv;
  bool header_seen = false;
  std::vector<RawPoint> pts;
  constexpr std::string_view kExpected = "y_mm,z_mm numbers";
  for (const Line& line : lines) {
    const std::string t = Trim(line.text);
    if (t.empty() || t[0] == '#') continue;
    const auto fields = Split(t, ",");
    if (!header_seen) {
      if (fields.size() < 2 || Lower(Trim(fields[0])) != "y_mm" ||
          Lower(Trim(fields[1])) != "z_mm") {
        throw InputError(fmt::format(
            "{}:{}: first line is '{}'; expected the CSV header 'y_mm,z_mm' (extra columns "
            "allowed after it)",
            path, line.number, t));
      }
      header_seen = true;
      continue;
    }
    // Keep empty fields so that "1.0,,2" reports a missing column 2.
    std::vector<std::string> cols;
    size_t i = 0;
    while (true) {
      const size_t j = t.find(',', i);
      cols.push_back(Trim(t.substr(i, j == std::string::npos ? std::string::npos : j - i)));
      if (j == std::string::npos) break;
      i = j + 1;
    }
    if (cols.size() >= 2 && (cols[0].empty() || cols[1].empty())) {
      throw InputError(fmt::format("{}:{}: '{}' has an empty column {}; expected {}", path,
                                   line.number, t, cols[0].empty() ? 1 : 2, kExpected));
    }
    pts.push_back(ParsePointTokens(cols, path, line, kExpected));
  }
  if (!header_seen) {
    throw InputError(fmt::format("{}:{}: no CSV header found; expected a first line 'y_mm,z_mm'",
                                 path, LastLine(lines)));
  }
  out.pts = std::move(pts);
  out.last_line = LastLine(lines);
  return out;
}

// ------------------------------------------------------------------------------------ SIMPACK

// Removes a trailing "! comment" outside single-quoted strings.
std::string StripBangComment(const std::string& s) {
  bool quoted = false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\'') quoted = !quoted;
    if (s[i] == '!' && !quoted) return s.substr(0, i);
  }
  return s;
}

RawRead ReadSimpack(const std::string& path, bool wheel) {
  const auto lines = ReadLines(path);
  RawRead out;
  out.format = wheel ? ProfileFormat::kSimpackPrw : ProfileFormat::kSimpackPrr;
  enum class Block { kNone, kHeader, kSpline, kPoints, kDone };
  Block block = Block::kNone;
  bool spline_seen = false, points_seen = false, header_type_seen = false;
  std::vector<RawPoint> pts;
  // Header keys with their SIMPACK defaults; "shift.y" etc. in user length units.
  double shift_y = 0, shift_z = 0, rotate = 0, bound_y_min = 1, bound_y_max = 0, bound_z_min = 1,
         bound_z_max = 0, mirror_y = 0, mirror_z = 0, inversion = 0, units_len = 1000,
         units_ang = 1, point_dist_min = 0;
  bool units_len_seen = false;
  int point_begin_line = 0;
  constexpr std::string_view kExpectedPoint = "'y z [weight]' numbers";

  for (const Line& line : lines) {
    const std::string raw = Trim(line.text);
    if (raw.empty() || raw[0] == '!' || raw[0] == '%') continue;
    const std::string t = Trim(StripBangComment(raw));
    if (t.empty()) continue;
    const std::string key_lc = Lower(t);
    if (block == Block::kPoints) {
      if (key_lc == "point.end") {
        block = Block::kSpline;
        continue;
      }
      pts.push_back(ParsePointTokens(Split(t, " \t,"), path, line, kExpectedPoint));
      continue;
    }
    if (key_lc == "header.begin") {
      block = Block::kHeader;
      continue;
    }
    if (key_lc == "header.end") {
      block = Block::kNone;
      continue;
    }
    if (key_lc == "spline.begin") {
      block = Block::kSpline;
      spline_seen = true;
      continue;
    }
    if (key_lc == "spline.end") {
      block = Block::kDone;
      continue;
    }
    if (key_lc == "point.begin") {
      if (block != Block::kSpline) {
        throw InputError(fmt::format(
            "{}:{}: 'point.begin' outside a spline.begin ... spline.end block; expected the "
            "SIMPACK layout spline.begin, point.begin, points, point.end, spline.end",
            path, line.number));
      }
      if (points_seen) {
        throw InputError(fmt::format("{}:{}: a second 'point.begin'; expected one point block",
                                     path, line.number));
      }
      block = Block::kPoints;
      points_seen = true;
      point_begin_line = line.number;
      continue;
    }
    const auto eq = t.find('=');
    if (eq == std::string::npos) {
      throw InputError(fmt::format(
          "{}:{}: '{}' is not a SIMPACK profile line; expected 'key = value', a block keyword "
          "(header.begin, spline.begin, point.begin, ...) or a comment",
          path, line.number, t));
    }
    const std::string key = Lower(Trim(t.substr(0, eq)));
    const std::string value = Trim(t.substr(eq + 1));
    const auto number = [&]() {
      const auto v = ParseNumber(value);
      if (!v || !std::isfinite(*v)) {
        throw InputError(fmt::format("{}:{}: {} = '{}'; expected a finite number", path,
                                     line.number, key, value));
      }
      return *v;
    };
    if (block == Block::kHeader) {
      if (key == "type") {
        const double type = number();
        header_type_seen = true;
        if (type != 0.0 && type != 1.0) {
          throw InputError(
              fmt::format("{}:{}: type = {}; expected 0 (rail profile) or 1 (wheel profile)", path,
                          line.number, value));
        }
        if ((type == 1.0) != wheel) {
          throw InputError(fmt::format(
              "{}:{}: type = {} ({} profile) but the extension says {} profile; expected type "
              "= {}",
              path, line.number, value, type == 1.0 ? "wheel" : "rail",
              wheel ? "a wheel" : "a rail", wheel ? 1 : 0));
        }
      }
      continue;
    }
    if (block != Block::kSpline) continue;  // keys outside blocks are ignored
    if (key == "shift.y")
      shift_y = number();
    else if (key == "shift.z")
      shift_z = number();
    else if (key == "rotate")
      rotate = number();
    else if (key == "bound.y.min")
      bound_y_min = number();
    else if (key == "bound.y.max")
      bound_y_max = number();
    else if (key == "bound.z.min")
      bound_z_min = number();
    else if (key == "bound.z.max")
      bound_z_max = number();
    else if (key == "mirror.y")
      mirror_y = number();
    else if (key == "mirror.z")
      mirror_z = number();
    else if (key == "inversion")
      inversion = number();
    else if (key == "point.dist.min")
      point_dist_min = number();
    else if (key == "units.ang.f")
      units_ang = number();
    else if (key == "units.len.f") {
      units_len = number();
      units_len_seen = true;
      // Between a kilometre and a micrometre as the file's unit: 1e-300 made every point
      // overflow to 1e303 mm.
      if (!(units_len >= 1e-3 && units_len <= 1e6)) {
        throw InputError(
            fmt::format("{}:{}: units.len.f = '{}'; expected a factor in [0.001, 1e6] "
                        "(user length per metre, 1000 for mm)",
                        path, line.number, value));
      }
    }
  }
  if (!spline_seen || !points_seen) {
    throw InputError(
        fmt::format("{}:{}: no {} found; expected a SIMPACK profile (spline.begin, point.begin ... "
                    "point.end, spline.end)",
                    path, LastLine(lines), spline_seen ? "'point.begin'" : "'spline.begin'"));
  }
  if (block == Block::kPoints) {
    throw InputError(fmt::format(
        "{}:{}: the point block opened on line {} has no 'point.end'; expected 'point.end'", path,
        LastLine(lines), point_begin_line));
  }
  auto& notes = out.notes;
  if (!header_type_seen) {
    notes.push_back(fmt::format("no header type; taken as a {} profile from the extension",
                                wheel ? "wheel" : "rail"));
  }
  // SIMPACK's processing order: 1 point.dist.min, 2 shift, 3 rotate, 4 bounds, 5 mirror,
  // 6 inversion, 7 units.
  if (point_dist_min > 0.0) {
    std::vector<RawPoint> kept;
    for (const auto& p : pts) {
      if (kept.empty() || std::hypot(p.y - kept.back().y, p.z - kept.back().z) >= point_dist_min) {
        kept.push_back(p);
      }
    }
    notes.push_back(fmt::format("point.dist.min = {}: {} point(s) dropped", point_dist_min,
                                pts.size() - kept.size()));
    pts = std::move(kept);
  }
  if (shift_y != 0.0 || shift_z != 0.0) {
    for (auto& p : pts) {
      p.y += shift_y;
      p.z += shift_z;
    }
    notes.push_back(fmt::format("shift.y = {}, shift.z = {} applied", shift_y, shift_z));
  }
  if (rotate != 0.0) {
    const double a = rotate / units_ang, c = std::cos(a), s = std::sin(a);
    for (auto& p : pts) {
      const double y = c * p.y - s * p.z, z = s * p.y + c * p.z;
      p.y = y;
      p.z = z;
    }
    notes.push_back(
        fmt::format("rotate = {} (units.ang.f = {}) applied about x", rotate, units_ang));
  }
  const size_t before_bounds = pts.size();
  if (bound_y_min <= bound_y_max) {
    std::erase_if(pts, [&](const RawPoint& p) { return p.y < bound_y_min || p.y > bound_y_max; });
  }
  if (bound_z_min <= bound_z_max) {
    std::erase_if(pts, [&](const RawPoint& p) { return p.z < bound_z_min || p.z > bound_z_max; });
  }
  if (pts.size() != before_bounds) {
    notes.push_back(fmt::format("bound.* applied: {} point(s) outside the bounds dropped",
                                before_bounds - pts.size()));
  }
  if (mirror_y != 0.0) {
    for (auto& p : pts) p.y = -p.y;
    notes.push_back("SIMPACK mirror.y = 1: y -> -y");
  }
  if (mirror_z != 0.0) {
    for (auto& p : pts) p.z = -p.z;
    notes.push_back("SIMPACK mirror.z = 1: z -> -z");
  }
  if (inversion != 0.0) {
    std::reverse(pts.begin(), pts.end());
    notes.push_back("SIMPACK inversion = 1: point order reversed");
  }
  const double to_mm = 1000.0 / units_len;
  if (to_mm != 1.0) {
    for (auto& p : pts) {
      p.y *= to_mm;
      p.z *= to_mm;
    }
  }
  notes.push_back(units_len_seen
                      ? fmt::format("units.len.f = {}: file lengths divided by {} to metres",
                                    units_len, units_len)
                      : std::string("no units.len.f; lengths taken as millimetres"));
  out.pts = std::move(pts);
  out.last_line = LastLine(lines);
  return out;
}

// ------------------------------------------------------------------------------------ MiniProf

// "Key=Value" header line (possibly wrapped in double quotes): returns the key and value.
bool ParseKeyValue(const std::string& t, std::string* key, std::string* value) {
  std::string s = t;
  if (!s.empty() && s.front() == '"') s.erase(0, 1);
  if (!s.empty() && s.back() == '"') s.pop_back();
  const auto eq = s.find('=');
  if (eq == std::string::npos || eq == 0) return false;
  const std::string k = Trim(s.substr(0, eq));
  if (k.empty() || !std::isalpha(static_cast<unsigned char>(k[0]))) return false;
  for (char c : k) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != ' ') {
      return false;
    }
  }
  *key = k;
  *value = Trim(s.substr(eq + 1));
  return true;
}

// A MiniProf data line: optional leading '"', then X Y [more columns] [trailing text].
// Returns nullopt when the line does not start with a number.
std::optional<RawPoint> ParseMiniProfData(const std::string& t, const std::string& path,
                                          const Line& line) {
  std::string s = t;
  if (!s.empty() && s.front() == '"') s.erase(0, 1);
  const auto tokens = Split(s, " \t,");
  if (tokens.empty() || !IsNumber(tokens[0])) return std::nullopt;
  // Only the leading numeric columns are data; text after them is tolerated.
  std::vector<std::string> numeric;
  for (const auto& tok : tokens) {
    if (!IsNumber(tok)) break;
    numeric.push_back(tok);
  }
  if (numeric.size() < 2) {
    throw InputError(fmt::format("{}:{}: '{}' has column 2 = '{}'; expected two numbers X Y (mm)",
                                 path, line.number, Trim(t),
                                 tokens.size() > 1 ? tokens[1] : std::string("(missing)")));
  }
  return ParsePointTokens(numeric, path, line, "two numbers X Y (mm)");
}

struct MiniProfData {
  std::vector<RawPoint> pts;  // y = MiniProf X, z = MiniProf Y (raw, mm)
  std::vector<std::pair<std::string, std::string>> keys;
};

// Key=Value layout (.ban and newer .whl).
MiniProfData ReadKeyValueLayout(const std::vector<Line>& lines, const std::string& path,
                                std::string_view what) {
  MiniProfData d;
  for (const Line& line : lines) {
    const std::string t = Trim(line.text);
    if (t.empty()) continue;
    std::string key, value;
    if (ParseKeyValue(t, &key, &value)) {
      d.keys.emplace_back(key, value);
      if (Lower(key) == "columndef") {
        const auto cols = Split(value, ", \t");
        if (cols.size() < 2 || Lower(cols[0]) != "x" || Lower(cols[1]) != "y") {
          throw InputError(
              fmt::format("{}:{}: ColumnDef={}; expected the first two columns to be X,Y", path,
                          line.number, value));
        }
      }
      continue;
    }
    auto p = ParseMiniProfData(t, path, line);
    if (!p) {
      throw InputError(fmt::format(
          "{}:{}: '{}' is neither a 'Key=Value' header line nor a data line; expected a {} "
          "file (Key=Value header, then X Y columns)",
          path, line.number, t, what));
    }
    d.pts.push_back(*p);
  }
  if (d.keys.empty()) {
    throw InputError(fmt::format(
        "{}:{}: no 'Key=Value' header lines found; expected a {} file (e.g. 'XYPoints=...', "
        "'ColumnDef=X,Y')",
        path, lines.empty() ? 1 : lines.front().number, what));
  }
  return d;
}

std::string FindKey(const MiniProfData& d, std::string_view key) {
  for (const auto& [k, v] : d.keys) {
    if (Lower(k) == key) return v;
  }
  return {};
}

void NoteXYPoints(const MiniProfData& d, std::vector<std::string>* notes) {
  const std::string xy = FindKey(d, "xypoints");
  const auto n = ParseNumber(xy);
  if (n && *n != static_cast<double>(d.pts.size())) {
    notes->push_back(fmt::format("header XYPoints={} but {} data points read", xy, d.pts.size()));
  }
  for (const char* k : {"xoffset", "yoffset"}) {
    const auto v = ParseNumber(FindKey(d, k));
    if (v && *v != 0.0) notes->push_back(fmt::format("header {}={} not applied", k, *v));
  }
}

RawRead ReadBan(const std::string& path, ReadMode mode) {
  const auto lines = ReadLines(path);
  for (const Line& line : lines) {
    const std::string t = Lower(Trim(line.text));
    if (t == "point.begin" || t == "header.begin" || StartsWith(t, "miniprof") ||
        StartsWith(t, "#miniwheelprof")) {
      throw InputError(fmt::format(
          "{}:{}: '{}' belongs to a {} file; expected a MiniProf .ban rail profile (Key=Value "
          "header, then X Y columns)",
          path, line.number, Trim(line.text),
          t[0] == 'p' || t[0] == 'h' ? "SIMPACK profile" : "MiniProf wheel (.whl)"));
    }
  }
  RawRead out;
  out.format = ProfileFormat::kMiniProfBan;
  MiniProfData d = ReadKeyValueLayout(lines, path, "MiniProf .ban");
  auto& notes = out.notes;
  NoteXYPoints(d, &notes);
  // Lateral: MiniProf X is positive toward the gauge side -> y = -X.
  for (auto& p : d.pts) p.y = -p.y;
  notes.push_back("MiniProf X toward the gauge side: y = -X");
  // Vertical sense. A rail's crown is an interior extreme of the vertical coordinate and its
  // lowest points are at an end of the profile.
  bool y_up = true;
  if (FindKey(d, "programname") == kRailwearProgramName) {
    notes.push_back("written by railwear: MiniProf Y upward, z = -Y");
  } else if (d.pts.size() >= 3) {
    const auto [mn, mx] = std::minmax_element(
        d.pts.begin(), d.pts.end(), [](const RawPoint& a, const RawPoint& b) { return a.z < b.z; });
    const auto at_end = [&](auto it) { return it == d.pts.begin() || it + 1 == d.pts.end(); };
    if (!at_end(mx) && at_end(mn)) {
      notes.push_back("MiniProf Y upward (crown is the interior maximum): z = -Y");
    } else if (!at_end(mn) && at_end(mx)) {
      y_up = false;
      notes.push_back("MiniProf Y already downward (crown is the interior minimum): z = Y");
    } else {
      notes.push_back("vertical sense ambiguous; assumed MiniProf's native Y upward: z = -Y");
    }
  }
  if (y_up) {
    for (auto& p : d.pts) p.z = -p.z;
  }
  if (mode == ReadMode::kProfile) DropScanGlitches(&d.pts, path, LastLine(lines), &notes);
  out.pts = std::move(d.pts);
  out.last_line = LastLine(lines);
  return out;
}

RawRead ReadWhl(const std::string& path, ReadMode mode) {
  const auto lines = ReadLines(path);
  RawRead out;
  out.format = ProfileFormat::kMiniProfWhl;
  auto& notes = out.notes;
  for (const Line& line : lines) {
    const std::string t = Lower(Trim(line.text));
    if (t == "point.begin" || t == "header.begin") {
      throw InputError(fmt::format(
          "{}:{}: '{}' belongs to a SIMPACK profile; expected a MiniProf .whl wheel profile", path,
          line.number, Trim(line.text)));
    }
  }
  // Layout: the older MINIPROF header ("MINIPROF ..." or "#MINIWHEELPROF" first) or Key=Value.
  size_t first = 0;
  while (first < lines.size() && Trim(lines[first].text).empty()) ++first;
  const std::string head = first < lines.size() ? Trim(lines[first].text) : std::string();
  MiniProfData d;
  if (StartsWith(head, "MINIPROF") || StartsWith(head, "#MINIWHEELPROF")) {
    // Header ends with the "(Sd/Sh/qR)" line (flange width, height, qR: not a data point).
    size_t data_start = lines.size();
    for (size_t i = first; i < lines.size(); ++i) {
      if (lines[i].text.find("(Sd/Sh/qR)") != std::string::npos) {
        data_start = i + 1;
        break;
      }
    }
    if (data_start == lines.size()) {
      throw InputError(fmt::format(
          "{}:{}: MINIPROF header without the '(Sd/Sh/qR)' line; expected the old MiniProf "
          "wheel header (MINIPROF, file name, Stock.../Wheel ID lines, 'Sd Sh qR (Sd/Sh/qR)')",
          path, LastLine(lines)));
    }
    notes.push_back("MiniProf wheel, old MINIPROF header layout");
    for (size_t i = data_start; i < lines.size(); ++i) {
      const std::string t = Trim(lines[i].text);
      if (t.empty()) continue;
      auto p = ParseMiniProfData(t, path, lines[i]);
      if (!p) {
        throw InputError(fmt::format("{}:{}: '{}' is not a data line; expected X Y numbers (mm)",
                                     path, lines[i].number, t));
      }
      d.pts.push_back(*p);
    }
  } else {
    d = ReadKeyValueLayout(lines, path, "MiniProf .whl");
    notes.push_back("MiniProf wheel, Key=Value header layout");
    NoteXYPoints(d, &notes);
  }
  const int last_line = LastLine(lines);
  if (d.pts.size() < 4) ValidatePoints(d.pts, path, last_line);
  if (mode == ReadMode::kProfile) DropScanGlitches(&d.pts, path, last_line, &notes);
  // Y at the taping line X = 70 (first crossing) and the flange (largest |Y - Y70| for X in the
  // flange window).
  std::optional<double> y70;
  for (size_t i = 0; i + 1 < d.pts.size() && !y70; ++i) {
    const double x0 = d.pts[i].y, x1 = d.pts[i + 1].y;
    if ((x0 - kMiniProfTapingLineX_mm) * (x1 - kMiniProfTapingLineX_mm) <= 0.0 && x0 != x1) {
      const double t = (kMiniProfTapingLineX_mm - x0) / (x1 - x0);
      y70 = d.pts[i].z + t * (d.pts[i + 1].z - d.pts[i].z);
    }
  }
  if (!y70) {
    throw InputError(fmt::format(
        "{}:{}: the wheel profile does not reach the taping line (X = {} mm); expected MiniProf "
        "X from the flange back past X = {} mm",
        path, last_line, kMiniProfTapingLineX_mm, kMiniProfTapingLineX_mm));
  }
  double flange = 0.0;
  for (const auto& p : d.pts) {
    if (p.y >= kFlangeWindowMin_mm && p.y <= kFlangeWindowMax_mm &&
        std::abs(p.z - *y70) > std::abs(flange)) {
      flange = p.z - *y70;
    }
  }
  const bool negate = flange < 0.0;
  for (auto& p : d.pts) {
    p.y -= kMiniProfTapingLineX_mm;
    if (negate) p.z = -p.z;
  }
  notes.push_back(
      fmt::format("y = X - {} (taping line 70 mm from the flange back)", kMiniProfTapingLineX_mm));
  notes.push_back(negate ? "flange pointed to negative Y: z = -Y"
                         : "flange toward positive Y: z = Y");
  notes.push_back(fmt::format("z at the taping line: {:.3f} mm", negate ? -*y70 : *y70));
  out.pts = std::move(d.pts);
  out.last_line = last_line;
  return out;
}

std::string Extension(const std::string& path) {
  return Lower(std::filesystem::path(path).extension().string());
}

std::ofstream OpenForWriting(const std::string& path) {
  std::ofstream out(path);
  if (!out) {
    throw InputError(fmt::format("{}: cannot write profile file: {}", path, std::strerror(errno)));
  }
  return out;
}

void CloseAfterWriting(std::ofstream& out, const std::string& path) {
  out.close();
  if (!out) throw InputError(fmt::format("{}: error while writing the profile file", path));
}

RawRead ReadRaw(const std::string& path, ReadMode mode) {
  const std::string ext = Extension(path);
  if (ext == ".csv") return ReadCsv(path);
  if (ext == ".ban") return ReadBan(path, mode);
  if (ext == ".whl") return ReadWhl(path, mode);
  if (ext == ".prr") return ReadSimpack(path, /*wheel=*/false);
  if (ext == ".prw") return ReadSimpack(path, /*wheel=*/true);
  throw InputError(fmt::format(
      "{}: unknown profile file extension '{}'; expected .csv, .ban, .whl, .prr or .prw", path,
      ext));
}

}  // namespace

std::string_view ToString(ProfileFormat f) {
  switch (f) {
    case ProfileFormat::kCsv:
      return "csv";
    case ProfileFormat::kMiniProfBan:
      return "miniprof-ban";
    case ProfileFormat::kMiniProfWhl:
      return "miniprof-whl";
    case ProfileFormat::kSimpackPrr:
      return "simpack-prr";
    case ProfileFormat::kSimpackPrw:
      return "simpack-prw";
    case ProfileFormat::kBuiltin:
      return "builtin";
  }
  return "unknown";
}

ProfileFile ReadProfileFile(const std::string& path) {
  RawRead raw = ReadRaw(path, ReadMode::kProfile);
  ProfileFile out;
  out.format = raw.format;
  out.notes = std::move(raw.notes);
  out.profile = Finish(std::move(raw.pts), path, raw.last_line, &out.notes);
  return out;
}

ProfilePoints ReadProfilePoints(const std::string& path) {
  RawRead raw = ReadRaw(path, ReadMode::kPoints);
  CheckCoordinateRange(raw.pts, path);
  if (raw.pts.size() < 4) ValidatePoints(raw.pts, path, raw.last_line);  // throws
  ProfilePoints out;
  out.format = raw.format;
  out.notes = std::move(raw.notes);
  if (raw.pts.front().y > raw.pts.back().y) {
    std::reverse(raw.pts.begin(), raw.pts.end());
    out.notes.push_back("point order reversed so that y increases along the profile");
  }
  for (const RawPoint& p : raw.pts) {
    out.points_m.emplace_back(p.y * 1e-3, p.z * 1e-3);
    out.lines.push_back(p.line);
  }
  return out;
}

void WriteProfileCsv(const Profile& profile, const std::string& path) {
  std::ofstream out = OpenForWriting(path);
  out << "y_mm,z_mm\n";
  for (const auto& p : profile.points()) {
    out << fmt::format("{:.6f},{:.6f}\n", p.x() * 1e3, p.y() * 1e3);
  }
  CloseAfterWriting(out, path);
}

void WriteProfileBan(const Profile& profile, const std::string& path) {
  std::ofstream out = OpenForWriting(path);
  // MiniProf convention: X toward the gauge side (X = -y), Y upward (Y = -z).
  out << "Filename=" << std::filesystem::path(path).filename().string() << "\n";
  out << "ProgramName=" << kRailwearProgramName << "\n";
  out << "XYPoints=" << profile.size() << "\n";
  out << "ColumnDef=X,Y\n\n";
  for (const auto& p : profile.points()) {
    out << fmt::format("{:.6f}\t{:.6f}\n", -p.x() * 1e3 + 0.0, -p.y() * 1e3 + 0.0);
  }
  CloseAfterWriting(out, path);
}

void WriteProfileFile(const Profile& profile, const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == ".csv") return WriteProfileCsv(profile, path);
  if (ext == ".ban") return WriteProfileBan(profile, path);
  throw InputError(fmt::format(
      "{}: cannot write profiles with extension '{}'; expected .csv or .ban", path, ext));
}

}  // namespace railwear
