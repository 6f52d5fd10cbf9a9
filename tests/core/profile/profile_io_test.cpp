// Profile readers and writers: every shared file loads into the railwear frame, formats agree with
// each other, bad input names the file and line, and write -> read round-trips.
#include "core/profile/profile_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/profile/profile_test_util.h"

namespace railwear {
namespace {

using railwear::testing::SharedProfilesDir;

// Files and writers use 6 decimals in mm: round-off 5e-7 mm.
constexpr double kSixDecimals_mm = 1e-6;

#define SKIP_WITHOUT_SHARED(dir)               \
  const std::string dir = SharedProfilesDir(); \
  if (!std::filesystem::is_directory(dir))     \
  GTEST_SKIP() << "../shared/data/profiles not found: " << dir

std::string TempPath(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/railwear_profile_io_test";
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

bool HasNote(const ProfileFile& f, const std::string& part) {
  return std::any_of(f.notes.begin(), f.notes.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

// Expects ReadProfileFile(path) to throw an InputError whose message contains every one of
// `parts` (the path is always required).
void ExpectReadError(const std::string& path, std::initializer_list<std::string> parts) {
  try {
    ReadProfileFile(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

double MaxPointDifference_mm(const Profile& a, const Profile& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (int i = 0; i < std::min(a.size(), b.size()); ++i) {
    worst = std::max(worst, (a.points()[i] - b.points()[i]).norm() * 1e3);
  }
  return worst;
}

TEST(ProfileFormat, ToString) {
  EXPECT_EQ(ToString(ProfileFormat::kCsv), "csv");
  EXPECT_EQ(ToString(ProfileFormat::kMiniProfBan), "miniprof-ban");
  EXPECT_EQ(ToString(ProfileFormat::kMiniProfWhl), "miniprof-whl");
  EXPECT_EQ(ToString(ProfileFormat::kSimpackPrr), "simpack-prr");
  EXPECT_EQ(ToString(ProfileFormat::kSimpackPrw), "simpack-prw");
  EXPECT_EQ(ToString(ProfileFormat::kBuiltin), "builtin");
}

// ---------------------------------------------------------------------------- shared files

TEST(SharedProfiles, EveryFileLoads) {
  SKIP_WITHOUT_SHARED(dir);
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string path = entry.path().string();
    if (entry.path().filename() == "NOTICE.md") continue;
    SCOPED_TRACE(path);
    ProfileFile f;
    ASSERT_NO_THROW(f = ReadProfileFile(path));
    ++count;
    EXPECT_GE(f.profile.size(), 4);
    EXPECT_EQ(f.profile.source(), path);
    // Convention: y increases from the first to the last point.
    EXPECT_LT(f.profile.points().front().x(), f.profile.points().back().x());
    EXPECT_GT(f.profile.Length(), 0.0);
  }
  EXPECT_EQ(count, 17);
}

TEST(SharedProfiles, SimpackWheelIsMirroredToFlangeAtNegativeY) {
  SKIP_WITHOUT_SHARED(dir);
  const ProfileFile f = ReadProfileFile(dir + "/MBench_S1002_v3.prw");
  EXPECT_EQ(f.format, ProfileFormat::kSimpackPrw);
  EXPECT_TRUE(HasNote(f, "mirror.y = 1"));
  EXPECT_TRUE(HasNote(f, "inversion = 1"));
  // The raw file starts (after its commented-out first point) at y = +69.612628 = -S.
  const auto& p = f.profile.points();
  EXPECT_NEAR(p.front().x() * 1e3, -69.612628, kSixDecimals_mm);
  EXPECT_NEAR(p.front().y() * 1e3, 13.485642, kSixDecimals_mm);
  EXPECT_NEAR(p.back().x() * 1e3, 60.0, kSixDecimals_mm);
}

TEST(SharedProfiles, SimpackRailHasGaugeSideAtNegativeY) {
  SKIP_WITHOUT_SHARED(dir);
  const ProfileFile f = ReadProfileFile(dir + "/MBench_UIC60_v3.prr");
  EXPECT_EQ(f.format, ProfileFormat::kSimpackPrr);
  EXPECT_FALSE(HasNote(f, "mirror"));
  const auto& p = f.profile.points();
  EXPECT_NEAR(p.front().x() * 1e3, -43.704898, kSixDecimals_mm);
  EXPECT_NEAR(p.front().y() * 1e3, 38.510726, kSixDecimals_mm);
  // Canted 1:40 toward the gauge side: the gauge-side end is deeper than the field-side end.
  EXPECT_GT(p.front().y(), p.back().y() + 1e-3);
}

TEST(SharedProfiles, PercentCommentsInsideThePointBlockAreSkipped) {
  SKIP_WITHOUT_SHARED(dir);
  // circ_r300.prr: 584 commented-out points with "%" inside the point block.
  const ProfileFile f = ReadProfileFile(dir + "/circ_r300.prr");
  const auto b = f.profile.bounds();
  EXPECT_NEAR(b.y_min * 1e3, -212.1, kSixDecimals_mm);
  EXPECT_NEAR(b.y_max * 1e3, 212.1, kSixDecimals_mm);
  EXPECT_EQ(f.profile.size(), 1415);  // 2011 lines - 584 % lines - 12 others
}

TEST(SharedProfiles, BanEqualsPrrForTheManchesterRail) {
  SKIP_WITHOUT_SHARED(dir);
  const ProfileFile ban = ReadProfileFile(dir + "/MBench_UIC60_v3.ban");
  const ProfileFile prr = ReadProfileFile(dir + "/MBench_UIC60_v3.prr");
  EXPECT_EQ(ban.format, ProfileFormat::kMiniProfBan);
  EXPECT_TRUE(HasNote(ban, "already downward"));
  const double d = MaxPointDifference_mm(ban.profile, prr.profile);
  std::cout << "[ measured ] MBench_UIC60_v3.ban vs .prr: max point difference " << d << " mm over "
            << ban.profile.size() << " points\n";
  EXPECT_LT(d, kSixDecimals_mm);
}

TEST(SharedProfiles, MeasuredBanRailsAreTurnedYUp) {
  SKIP_WITHOUT_SHARED(dir);
  for (const char* name : {"avg_HR.BAN", "avg_low2.ban"}) {
    SCOPED_TRACE(name);
    const ProfileFile f = ReadProfileFile(dir + "/" + name);
    EXPECT_TRUE(HasNote(f, "Y upward (crown is the interior maximum)"));
    // Crown (min z) in the interior, both ends below it; the gauge face (X up to ~46 mm for the
    // high rail) is at negative y.
    const auto& p = f.profile.points();
    const auto top = std::min_element(p.begin(), p.end(),
                                      [](const auto& a, const auto& b) { return a.y() < b.y(); });
    EXPECT_NE(top, p.begin());
    EXPECT_NE(top + 1, p.end());
    EXPECT_GT(p.front().y(), top->y() + 5e-3);
    EXPECT_LT(f.profile.bounds().y_min, -20e-3);
  }
  // avg_low2.ban ends with "add point to extend gauge face" after the numbers.
  const ProfileFile low = ReadProfileFile(dir + "/avg_low2.ban");
  EXPECT_NEAR(low.profile.points().front().x() * 1e3, -25.591, kSixDecimals_mm);
  EXPECT_NEAR(low.profile.points().front().y() * 1e3, 33.80, kSixDecimals_mm);
}

TEST(SharedProfiles, MiniProfWheelsInTheWheelFrame) {
  SKIP_WITHOUT_SHARED(dir);
  for (const char* name : {"avg_wheel.whl", "Car7216_0001r.whl"}) {
    SCOPED_TRACE(name);
    const ProfileFile f = ReadProfileFile(dir + "/" + name);
    EXPECT_EQ(f.format, ProfileFormat::kMiniProfWhl);
    EXPECT_TRUE(HasNote(f, "old MINIPROF header"));
    EXPECT_TRUE(HasNote(f, "z = Y"));
    const auto& p = f.profile.points();
    // The "32.58 37.11 14.71 (Sd/Sh/qR)" line is not a point: the first point is at the flange
    // back (X near 0 -> y near -70).
    EXPECT_LT(p.front().x() * 1e3, -68.0);
    // Flange tip: largest z, at X = 15..16 (y = -55..-54), 27.5..28.1 mm toward the rail.
    const auto tip = std::max_element(p.begin(), p.end(),
                                      [](const auto& a, const auto& b) { return a.y() < b.y(); });
    EXPECT_GT(tip->x() * 1e3, -56.0);
    EXPECT_LT(tip->x() * 1e3, -54.0);
    EXPECT_GT(tip->y() * 1e3, 27.5);
    EXPECT_LT(tip->y() * 1e3, 28.1);
    // Taping line at y = 0 with z near 0 (measured worn wheels: within 0.2 mm).
    for (size_t i = 0; i + 1 < p.size(); ++i) {
      if (p[i].x() <= 0.0 && p[i + 1].x() > 0.0) {
        EXPECT_NEAR(p[i].y() * 1e3, 0.0, 0.2);
      }
    }
  }
}

TEST(SharedProfiles, MeasuredScanGlitchesAreDroppedWithANote) {
  SKIP_WITHOUT_SHARED(dir);
  EXPECT_TRUE(HasNote(ReadProfileFile(dir + "/avg_HR.BAN"), "scan glitch dropped: line 136"));
  EXPECT_TRUE(
      HasNote(ReadProfileFile(dir + "/Car7216_0001r.whl"), "scan glitch dropped: line 223"));
  EXPECT_TRUE(HasNote(ReadProfileFile(dir + "/avg_low2.ban"), "scan glitch dropped: line 74"));
}

// ---------------------------------------------------------------------------- CSV

TEST(CsvReader, AcceptsCommentsSpacesExtraColumnsAndCrlf) {
  const std::string path = WriteFile("ok.csv",
                                     "# a test profile\r\n"
                                     " y_mm , z_mm , note\r\n"
                                     "-1.5, 0.5, a\r\n"
                                     "# comment between points\r\n"
                                     "-0.5 ,0.1,b\r\n"
                                     "\r\n"
                                     "0.5, 0.1\r\n"
                                     "1.5,0.5\r\n");
  const ProfileFile f = ReadProfileFile(path);
  EXPECT_EQ(f.format, ProfileFormat::kCsv);
  ASSERT_EQ(f.profile.size(), 4);
  EXPECT_DOUBLE_EQ(f.profile.points()[0].x(), -1.5e-3);
  EXPECT_DOUBLE_EQ(f.profile.points()[3].y(), 0.5e-3);
  EXPECT_TRUE(f.notes.empty());
  // Reversed input comes back with y increasing, and says so.
  const ProfileFile r =
      ReadProfileFile(WriteFile("rev.CSV", "y_mm,z_mm\n1.5,0.5\n0.5,0.1\n-0.5,0.1\n-1.5,0.5\n"));
  EXPECT_DOUBLE_EQ(r.profile.points()[0].x(), -1.5e-3);
  EXPECT_TRUE(HasNote(r, "reversed"));
}

TEST(CsvReader, BadInputNamesFileLineAndValue) {
  ExpectReadError(WriteFile("noheader.csv", "1,2\n2,3\n3,4\n4,5\n"), {":1:", "'1,2'", "y_mm,z_mm"});
  ExpectReadError(WriteFile("empty.csv", "# only a comment\n"), {"no CSV header", "y_mm,z_mm"});
  ExpectReadError(WriteFile("text.csv", "y_mm,z_mm\n0,0\n1,abc\n2,0\n3,0\n"),
                  {":3:", "'abc'", "column 2", "not a number"});
  ExpectReadError(WriteFile("onecol.csv", "y_mm,z_mm\n0,0\n1\n2,0\n3,0\n"),
                  {":3:", "1 column(s)", "y_mm,z_mm"});
  ExpectReadError(WriteFile("emptycol.csv", "y_mm,z_mm\n0,0\n,1\n2,0\n3,0\n"),
                  {":3:", "empty column 1"});
  ExpectReadError(WriteFile("nan.csv", "y_mm,z_mm\n0,0\n1,0\nnan,0\n3,0\n"),
                  {":4:", "'nan'", "finite"});
  ExpectReadError(WriteFile("inf.csv", "y_mm,z_mm\n0,0\n1,0\n2,-inf\n3,0\n"),
                  {":4:", "'-inf'", "finite"});
  ExpectReadError(WriteFile("three.csv", "y_mm,z_mm\n0,0\n1,0\n2,0\n"),
                  {":4:", "3 profile point(s)", "at least 4"});
  ExpectReadError(WriteFile("dup.csv", "y_mm,z_mm\n0,0\n1,0\n# c\n1,0\n2,0\n3,0\n"),
                  {":5:", "duplicates the point on line 3", "y = 1.000000"});
  ExpectReadError(WriteFile("back.csv", "y_mm,z_mm\n0,0\n1,0\n2,0\n1.5,0.01\n3,0\n"),
                  {":5:", "turns the profile back", "after line 4"});
}

// ---------------------------------------------------------------------------- SIMPACK

const char* kSimpackHead =
    "! test\n"
    "header.begin\n  version = 1\n  type = 0   ! rail\nheader.end\n"
    "spline.begin\n";

TEST(SimpackReader, AppliesHeaderTransformsInSimpackOrder) {
  // Points in metres (units.len.f = 1), shifted, mirrored in z, bounded in y, inverted.
  const std::string path = WriteFile(
      "t.prr", std::string(kSimpackHead) +
                   "  shift.y = 0.001\n  shift.z = 0.0\n  bound.y.min = -0.5\n"
                   "  bound.y.max = 0.0035\n  mirror.z = 1\n  inversion = 1\n"
                   "  units.len.f = 1.   ! metres\n"
                   "  point.begin\n"
                   "   % commented point\n"
                   "   -0.002  0.001  1.0 ! weight and comment\n"
                   "   ! another comment\n"
                   "   -0.001  0.0002\n    0.000  0.0\n    0.001  0.0002\n    0.002  0.001\n"
                   "    0.003  0.002\n"
                   "  point.end\nspline.end\n");
  const ProfileFile f = ReadProfileFile(path);
  // Shift +1 mm in y, then bound y <= 3.5 mm drops the last point; z mirrored.
  ASSERT_EQ(f.profile.size(), 5);
  const auto& p = f.profile.points();
  EXPECT_NEAR(p[0].x(), -0.001, 1e-15);
  EXPECT_NEAR(p[0].y(), -0.001, 1e-15);
  EXPECT_NEAR(p[4].x(), 0.003, 1e-15);
  EXPECT_NEAR(p[4].y(), -0.001, 1e-15);
  EXPECT_TRUE(HasNote(f, "bound"));
  EXPECT_TRUE(HasNote(f, "mirror.z"));
  EXPECT_TRUE(HasNote(f, "units.len.f = 1"));
}

TEST(SimpackReader, RotateTurnsYTowardZ) {
  const std::string path = WriteFile(
      "rot.prr", std::string(kSimpackHead) +
                     "  rotate = 90\n  units.ang.f = 57.29577951308232\n  units.len.f = 1000\n"
                     "  point.begin\n 0 0\n 1 0\n 2 0\n 3 0\n point.end\nspline.end\n");
  const ProfileFile f = ReadProfileFile(path);
  EXPECT_NEAR(f.profile.points()[3].x(), 0.0, 1e-15);
  EXPECT_NEAR(f.profile.points()[3].y(), 3e-3, 1e-15);
}

TEST(SimpackReader, BadInputNamesFileLineAndValue) {
  ExpectReadError(WriteFile("nopoints.prr", std::string(kSimpackHead) + "  units.len.f = 1000\n"
                                                                        "spline.end\n"),
                  {":8:", "'point.begin'"});
  ExpectReadError(WriteFile("csvlike.prr", "y_mm,z_mm\n0,0\n"), {":1:", "not a SIMPACK"});
  ExpectReadError(WriteFile("wheel.prr",
                            "header.begin\n type = 1\nheader.end\nspline.begin\n"
                            "point.begin\n0 0\n1 0\n2 0\n3 0\npoint.end\nspline.end\n"),
                  {":2:", "type = 1", "expected type = 0"});
  ExpectReadError(WriteFile("bad.prw",
                            "header.begin\n type = 1\nheader.end\nspline.begin\n"
                            "point.begin\n0 0\n1 x\n2 0\n3 0\npoint.end\nspline.end\n"),
                  {":7:", "'x'", "y z [weight]"});
  ExpectReadError(WriteFile("open.prw",
                            "header.begin\n type = 1\nheader.end\nspline.begin\n"
                            "point.begin\n0 0\n1 0\n2 0\n3 0\n"),
                  {":9:", "line 5", "'point.end'"});
  ExpectReadError(WriteFile("units.prw", "spline.begin\n units.len.f = mm\n point.begin\n"),
                  {":2:", "'mm'", "finite number"});
}

// ---------------------------------------------------------------------------- MiniProf

TEST(MiniProfReader, BanBadInput) {
  ExpectReadError(WriteFile("simpack.ban", "header.begin\n type = 0\nheader.end\n"),
                  {":1:", "SIMPACK"});
  ExpectReadError(WriteFile("nohead.ban", "1 2\n2 3\n3 4\n4 5\n"), {"Key=Value"});
  ExpectReadError(WriteFile("junk.ban", "XYPoints=4\nColumnDef=X,Y\n\n1 2\nhello\n3 4\n4 5\n"),
                  {":5:", "'hello'", "Key=Value"});
  ExpectReadError(WriteFile("col2.ban", "XYPoints=4\nColumnDef=X,Y\n\n1 2\n2 z\n3 4\n4 5\n"),
                  {":5:", "'z'", "X Y"});
  ExpectReadError(WriteFile("coldef.ban", "XYPoints=4\nColumnDef=A,X,Y\n\n1 2\n2 2\n3 4\n4 5\n"),
                  {":2:", "ColumnDef=A,X,Y", "X,Y"});
}

TEST(MiniProfReader, BanVerticalSenseDetection) {
  // A crown as the interior maximum of Y with its ends lowest: native Y up -> z = -Y.
  const ProfileFile up =
      ReadProfileFile(WriteFile("up.ban", "XYPoints=5\n\n-2 -1\n-1 -0.2\n0 0\n1 -0.2\n2 -1\n"));
  EXPECT_TRUE(HasNote(up, "Y upward"));
  EXPECT_NEAR(up.profile.points()[0].y(), 1e-3, 1e-15);
  // The same stored downward: z = Y.
  const ProfileFile down =
      ReadProfileFile(WriteFile("down.ban", "XYPoints=5\n\n-2 1\n-1 0.2\n0 0\n1 0.2\n2 1\n"));
  EXPECT_TRUE(HasNote(down, "already downward"));
  EXPECT_NEAR(down.profile.points()[0].y(), 1e-3, 1e-15);
  // Monotone: ambiguous, MiniProf's native Y up assumed.
  const ProfileFile amb =
      ReadProfileFile(WriteFile("amb.ban", "XYPoints=4\n\n0 0\n1 1\n2 2\n3 3\n"));
  EXPECT_TRUE(HasNote(amb, "ambiguous"));
  // X toward the gauge side: y = -X.
  EXPECT_NEAR(amb.profile.points()[0].x(), -3e-3, 1e-15);
  EXPECT_NEAR(amb.profile.points()[0].y(), -3e-3, 1e-15);
}

TEST(MiniProfReader, ManyBacktrackingPointsAreAnError) {
  // One glitch is dropped with a note; a file that keeps turning back is an error naming the
  // first offending line (more than max(3, 1%) glitches).
  const ProfileFile one = ReadProfileFile(
      WriteFile("one.ban", "XYPoints=6\n\n-2 -1\n-1 -0.2\n0 0\n-0.5 0\n1 -0.2\n2 -1\n"));
  EXPECT_TRUE(HasNote(one, "scan glitch dropped: line 6"));
  EXPECT_EQ(one.profile.size(), 5);
  ExpectReadError(WriteFile("many.ban",
                            "XYPoints=9\n\n0 0\n1 0\n0.5 0\n2 0\n1.5 0\n3 0\n"
                            "2.5 0\n4 0\n3.5 0\n5 0\n"),
                  {":5:", "turns the profile back"});
}

TEST(MiniProfReader, WhlLayoutsAndFlangeSense) {
  // Key=Value layout, flange stored toward negative Y: negated with a note.
  std::string text = "ColumnDef=X,Y\n\n";
  for (int x = 0; x <= 100; x += 5) {
    const double flange = x < 30 ? -(30 - x) : 0.0;
    std::ostringstream row;
    row << x << " " << flange - 0.01 * (x - 70) << "\n";
    text += row.str();
  }
  const ProfileFile f = ReadProfileFile(WriteFile("kv.whl", text));
  EXPECT_TRUE(HasNote(f, "Key=Value"));
  EXPECT_TRUE(HasNote(f, "z = -Y"));
  EXPECT_NEAR(f.profile.points()[0].x(), -70e-3, 1e-15);
  EXPECT_NEAR(f.profile.points()[0].y(), 29.3e-3, 1e-15);

  ExpectReadError(WriteFile("nosd.whl", "MINIPROF 101\nx.prd\nStock..:\n1 2\n2 3\n3 4\n4 5\n"),
                  {":7:", "(Sd/Sh/qR)"});
  ExpectReadError(WriteFile("short.whl",
                            "MINIPROF 1\nname\n32.58 37.11 14.71 (Sd/Sh/qR)\n0 20\n10 25\n20 "
                            "10\n30 1\n"),
                  {":7:", "taping line"});
  ExpectReadError(
      WriteFile("bad.whl", "MINIPROF 1\nname\n32.58 37.11 14.71 (Sd/Sh/qR)\n0 20\n10 25\nabc\n"),
      {":6:", "'abc'"});
}

// ---------------------------------------------------------------------------- extension, files

TEST(ProfileFiles, UnknownExtensionAndMissingFile) {
  ExpectReadError(WriteFile("p.txt", "y_mm,z_mm\n"), {"'.txt'", ".csv, .ban, .whl, .prr or .prw"});
  ExpectReadError(WriteFile("noext", "y_mm,z_mm\n"), {"extension"});
  ExpectReadError(TempPath("missing.csv"), {"no such file"});
  ExpectReadError(::testing::TempDir(), {"extension"});
  std::filesystem::create_directories(TempPath("dir.csv"));
  ExpectReadError(TempPath("dir.csv"), {"directory"});
}

// ---------------------------------------------------------------------------- writers

TEST(ProfileWriters, CsvAndBanRoundTrip) {
  const Profile profiles[] = {ApplyCant(MakeUic60(), 0.025), MakeUic60(0.5e-3),
                              MakeGroove(10e-3, BodyRole::kRail),
                              MakeCircle(50e-3, BodyRole::kRail), MakeS1002(1e-3)};
  for (const Profile& p : profiles) {
    SCOPED_TRACE(p.source());
    for (const char* ext : {".csv", ".ban"}) {
      const std::string path = TempPath("round_trip" + std::string(ext));
      WriteProfileFile(p, path);
      const ProfileFile back = ReadProfileFile(path);
      EXPECT_LT(MaxPointDifference_mm(p, back.profile), kSixDecimals_mm) << ext;
    }
  }
  // The .ban file is in MiniProf's convention: X = -y, Y = -z.
  const std::string path = TempPath("conv.ban");
  WriteProfileBan(MakeCircle(10e-3, BodyRole::kWheel), path);
  std::ifstream in(path);
  std::string line, last;
  bool header = true;
  int data = 0;
  while (std::getline(in, line)) {
    if (line.empty()) header = false;
    if (!header && !line.empty()) ++data, last = line;
  }
  EXPECT_EQ(data, MakeCircle(10e-3, BodyRole::kWheel).size());
  // Last point: y = +9.848 mm, z = -(10 - 10 cos 80deg) = -8.264 mm -> X = -9.848, Y = 8.264.
  EXPECT_EQ(last, "-9.848078\t8.263518");
}

TEST(ProfileWriters, Errors) {
  const Profile p = MakeCircle(10e-3, BodyRole::kRail);
  const std::string bad = TempPath("no_such_dir/p.csv");
  try {
    WriteProfileCsv(p, bad);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
  }
  EXPECT_THROW(WriteProfileBan(p, TempPath("no_such_dir/p.ban")), InputError);
  try {
    WriteProfileFile(p, TempPath("p.prr"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'.prr'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace railwear
