// `railwear traffic import` end to end: the shipped example imports and reads back; a CSV, its
// collective, the collective file and ReadLoadCollective agree to print precision; every kind of
// bad row or header is refused with its file:line message and exit code 2, writing nothing; an
// existing output is replaced only with --force.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app/load_collective_file.h"
#include "core/numerics/input_error.h"
#include "tests/app/cli_runner.h"
#include "wear/load_collective.h"

namespace railwear::test {
namespace {

using TrafficCommandTest = CliFixture;

const std::string kExample = RAILWEAR_SOURCE_DIR "/examples/mbs/curve_r600_mbs.csv";
// The file prints 9 significant digits ({:.9g}): values read back agree to half a unit there.
constexpr double kPrintTolerance = 1e-8;

void ExpectNear(double back, double original, const std::string& what) {
  EXPECT_LE(std::abs(back - original), kPrintTolerance * std::max(std::abs(original), 1e-300))
      << what << ": " << back << " vs " << original;
}

// Every field of the collective read back equals the original within print precision.
void ExpectSameCollective(const LoadCollective& back, const LoadCollective& c) {
  EXPECT_EQ(back.source, c.source);
  EXPECT_EQ(back.rows_read, c.rows_read);
  EXPECT_EQ(back.rows_zero_weight, c.rows_zero_weight);
  EXPECT_EQ(back.weight_unit, c.weight_unit);
  EXPECT_EQ(back.axle_load_from_column, c.axle_load_from_column);
  EXPECT_EQ(back.mbs_names, c.mbs_names);
  ExpectNear(back.total_weight_high, c.total_weight_high, "total_weight_high");
  ExpectNear(back.total_weight_low, c.total_weight_low, "total_weight_low");
  ExpectNear(back.widths.wheelset_y_m, c.widths.wheelset_y_m, "bin y");
  ExpectNear(back.widths.yaw_rad, c.widths.yaw_rad, "bin yaw");
  ExpectNear(back.widths.vertical_force_N, c.widths.vertical_force_N, "bin Q");
  ExpectNear(back.widths.speed_m_s, c.widths.speed_m_s, "bin V");
  ExpectNear(back.widths.friction, c.widths.friction, "bin mu");
  ExpectNear(back.widths.creepage_x, c.widths.creepage_x, "bin xi");
  ASSERT_EQ(back.entries.size(), c.entries.size());
  for (std::size_t i = 0; i < c.entries.size(); ++i) {
    const LoadCollectiveEntry& b = back.entries[i];
    const LoadCollectiveEntry& e = c.entries[i];
    SCOPED_TRACE(e.name);
    EXPECT_EQ(b.name, e.name);
    EXPECT_EQ(b.rail, e.rail);
    ExpectNear(b.wheelset_y_m, e.wheelset_y_m, "y");
    ExpectNear(b.yaw_rad, e.yaw_rad, "yaw");
    ExpectNear(b.roll_rad, e.roll_rad, "roll");
    ExpectNear(b.vertical_force_N, e.vertical_force_N, "Q");
    ExpectNear(b.speed_m_s, e.speed_m_s, "V");
    ASSERT_EQ(b.friction.has_value(), e.friction.has_value());
    if (e.friction) ExpectNear(*b.friction, *e.friction, "mu");
    ASSERT_EQ(b.creepage_x.has_value(), e.creepage_x.has_value());
    if (e.creepage_x) ExpectNear(*b.creepage_x, *e.creepage_x, "xi");
    ExpectNear(b.share, e.share, "share");
    ExpectNear(b.weight, e.weight, "weight");
    ExpectNear(b.axle_load_t, e.axle_load_t, "axle load");
    EXPECT_EQ(b.rows, e.rows);
    ASSERT_EQ(b.mbs.size(), e.mbs.size());
    for (std::size_t k = 0; k < e.mbs.size(); ++k) ExpectNear(b.mbs[k], e.mbs[k], "mbs");
  }
}

TEST_F(TrafficCommandTest, ExampleImportsWithItsSummaryAndReadsBack) {
  const Outcome o = Run("traffic import '" + kExample + "' --out collective.toml");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const LoadCollective expected = BinLoadCollective(ReadMbsTimeHistory(kExample), {});
  EXPECT_TRUE(Contains(o.out, "read 320 rows from " + kExample));
  EXPECT_TRUE(Contains(o.out, fmt::format("high rail: {:>4} bins, weight 33.6144 m run",
                                          EntryCount(expected, RailSide::kHigh))));
  EXPECT_TRUE(Contains(o.out, fmt::format("low  rail: {:>4} bins, weight 33.6144 m run",
                                          EntryCount(expected, RailSide::kLow))));
  const LoadCollective back = app::ReadLoadCollective((dir_ / "collective.toml").string());
  ExpectSameCollective(back, expected);
  // The example: 4 wheelsets x 2 wheels x 40 steps of 0.01 s at about 21 m/s, with mu, xi and
  // two mbs_ columns.
  EXPECT_EQ(back.rows_read, 320);
  EXPECT_EQ(back.weight_unit, WeightUnit::kDistance);
  EXPECT_EQ(back.mbs_names, (std::vector<std::string>{"Fy_N", "Fx_N"}));
  EXPECT_TRUE(back.entries.front().friction && back.entries.front().creepage_x);
}

// CSV -> collective -> file -> ReadLoadCollective, for a passes-weighted CSV with an axle-load
// column and without mu or xi (the example covers the other columns).
TEST_F(TrafficCommandTest, CollectiveRoundTripsThroughItsFile) {
  const std::string csv =
      "weight_passes,side,V_m_s,y_mm,yaw_mrad,Q_N,axle_load_t,mbs_L_over_V\n"
      "3,high,22.5,6.123456789,2.987654321,81234.5678,16.75,0.41\n"
      "1,high,22.7,6.2,2.9,81500,16.75,0.43\n"
      "0,high,22.7,6.2,2.9,81500,16.75,0.43\n"
      "2.5,low,22.5,6.123456789,2.987654321,76543.21,16.75,0.12\n"
      "1e-3,low,22.5,-0.3333333333,-1e-4,77000,16.75,-0.05\n";
  const std::string path = Write("passes.csv", csv);
  const LoadCollective c = BinLoadCollective(ReadMbsTimeHistory(path), {});
  ASSERT_EQ(c.entries.size(), 3u);
  EXPECT_TRUE(c.axle_load_from_column);
  const std::string out = (dir_ / "passes.toml").string();
  std::ofstream(out) << app::LoadCollectiveFileText(c, "test");
  const LoadCollective back = app::ReadLoadCollective(out);
  ExpectSameCollective(back, c);
  EXPECT_FALSE(back.entries[0].friction || back.entries[0].creepage_x);
  ExpectNear(back.entries[0].axle_load_t, 16.75, "axle_load_t from the column");
}

struct BadCsv {
  const char* what;
  std::string csv;
  std::string message;  // the whole first line of stderr after "railwear: error: "
};

// Line 1 is a comment, line 2 the header, so the first data row is line 3; CRLF in one case.
const char* const kHead = "# bad file\nweight_passes,side,V_m_s,y_mm,yaw_mrad,Q_N\n";

std::vector<BadCsv> BadCsvs() {
  const std::string h = kHead;
  return {
      {"missing field", h + "1,high,20,0,0\n",
       "bad.csv:3: column 'Q_N' = '': expected a value (the row has 5 fields, the header of line 2 "
       "has 6)"},
      {"extra field", h + "1,high,20,0,0,8e4\n1,low,20,0,0,8e4,5\n",
       "bad.csv:4: 7 fields, expected 6 as in the header (line 2); fields are separated by ',' and "
       "never quoted"},
      {"not a number", h + "1,high,fast,0,0,8e4\n",
       "bad.csv:3: column 'V_m_s' = 'fast': expected a number in (0, 150] (speed in m/s)"},
      {"trailing characters", h + "1,high,20,3.5mm,0,8e4\n",
       "bad.csv:3: column 'y_mm' = '3.5mm': expected a number in [-100, 100] (mm)"},
      {"NaN", h + "1,high,20,nan,0,8e4\n",
       "bad.csv:3: column 'y_mm' = 'nan': expected a number in [-100, 100] (mm)"},
      {"infinity", h + "1,high,20,0,0,inf\n",
       "bad.csv:3: column 'Q_N' = 'inf': expected a number in [0, 1e6] (a wheel load in N)"},
      {"negative weight", h + "1,high,20,0,0,8e4\n\n-1,low,20,0,0,8e4\n",
       "bad.csv:5: column 'weight_passes' = '-1': expected a number in [0, 1e15] (the weight)"},
      {"negative load", h + "1,high,20,0,0,-8e4\n",
       "bad.csv:3: column 'Q_N' = '-8e4': expected a number in [0, 1e6] (a wheel load in N)"},
      {"zero speed", h + "1,high,0,0,0,8e4\n",
       "bad.csv:3: column 'V_m_s' = '0': expected a number in (0, 150] (speed in m/s)"},
      {"yaw out of range", h + "1,high,20,0,-150,8e4\n",
       "bad.csv:3: column 'yaw_mrad' = '-150': expected a number in (-100, 100) (mrad)"},
      {"bad side", h + "1,outer,20,0,0,8e4\n",
       "bad.csv:3: column 'side' = 'outer': expected 'high' or 'low' (or 'right' / 'left': right "
       "is the high rail)"},
      {"side is case-sensitive", h + "1,High,20,0,0,8e4\n",
       "bad.csv:3: column 'side' = 'High': expected 'high' or 'low' (or 'right' / 'left': right "
       "is the high rail)"},
      {"zero friction", "weight_m,side,V_m_s,y_mm,yaw_mrad,Q_N,mu\n0.2,low,20,0,0,8e4,0\n",
       "bad.csv:2: column 'mu' = '0': expected a number in (0, 2] (friction)"},
      {"CRLF line numbers",
       "# bad\r\nweight_m,side,V_m_s,y_mm,yaw_mrad,Q_N\r\n\r\n"
       "0.2,low,20,0,0,8e4\r\n0.2,low,20,x,0,8e4\r\n",
       "bad.csv:5: column 'y_mm' = 'x': expected a number in [-100, 100] (mm)"},
      {"duplicate column", "# bad file\nweight_m,side,V_m_s,y_mm,yaw_mrad,Q_N,y_mm\n",
       "bad.csv:2: column 'y_mm' appears twice (header fields 4 and 7): expected each column once"},
      {"missing required column", "# bad file\nweight_m,side,V_m_s,y_mm,Q_N\n0.2,low,20,0,8e4\n",
       "bad.csv:2: missing required column 'yaw_mrad' (required: weight_passes or weight_m, side, "
       "V_m_s, y_mm, yaw_mrad, Q_N)"},
      {"missing weight column", "side,V_m_s,y_mm,yaw_mrad,Q_N\n",
       "bad.csv:1: missing required column 'weight_passes' or 'weight_m' (the row's weight in "
       "wheel passes, or in metres run)"},
      {"bare weight column", "weight,side,V_m_s,y_mm,yaw_mrad,Q_N\n",
       "bad.csv:1: column 'weight': expected 'weight_passes' (wheel passes) or 'weight_m' (metres "
       "run, dt * V): the name says what the weight counts"},
      {"two weight columns", "weight_m,weight_passes,side,V_m_s,y_mm,yaw_mrad,Q_N\n",
       "bad.csv:1: columns 'weight_passes' and 'weight_m' both present: expected one weight "
       "column"},
      {"unknown column", "# bad file\nweight_m,side,V_m_s,y_mm,yaw_mrad,Q_N,Fy_N\n",
       "bad.csv:2: column 'Fy_N' is unknown: expected one of weight_passes or weight_m, side, "
       "V_m_s, y_mm, yaw_mrad, Q_N, roll_mrad, xi, mu, axle_load_t, mbs_<name> (names are "
       "case-sensitive; mbs_ columns: letters, digits and '_')"},
      {"wrong case", "weight_m,side,v_m_s,y_mm,yaw_mrad,Q_N\n",
       "bad.csv:1: column 'v_m_s' is unknown: expected one of weight_passes or weight_m, side, "
       "V_m_s, y_mm, yaw_mrad, Q_N, roll_mrad, xi, mu, axle_load_t, mbs_<name> (names are "
       "case-sensitive; mbs_ columns: letters, digits and '_')"},
      {"empty column name", "weight_m,side,,V_m_s,y_mm,yaw_mrad,Q_N\n",
       "bad.csv:1: header field 3 is empty: expected a column name (weight_passes or weight_m, "
       "side, V_m_s, y_mm, yaw_mrad, Q_N, roll_mrad, xi, mu, axle_load_t, mbs_<name>)"},
      {"no data rows", h + "\n# nothing\n",
       "bad.csv: no data rows after the header (line 2): expected one row per wheel per time step "
       "or case"},
      {"empty file", "# only a comment\n",
       "bad.csv: no header row: expected a line of column names (weight_passes or weight_m, side, "
       "V_m_s, y_mm, yaw_mrad, Q_N, roll_mrad, xi, mu, axle_load_t, mbs_<name>)"},
      {"all weights zero", h + "0,high,20,0,0,8e4\n",
       "bad.csv: all 1 rows have weight 0: expected at least one row of weight > 0"},
  };
}

TEST_F(TrafficCommandTest, EveryBadRowOrHeaderIsAFileLineErrorWithExitTwo) {
  for (const BadCsv& bad : BadCsvs()) {
    SCOPED_TRACE(bad.what);
    Write("bad.csv", bad.csv);
    const Outcome o = Run("traffic import bad.csv --out out.toml");
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(o.err, "railwear: error: " + bad.message + "\n");
    EXPECT_FALSE(fs::exists(dir_ / "out.toml")) << "an output was written";
  }
}

TEST_F(TrafficCommandTest, BadOptionsAndMissingFilesExitTwo) {
  Write("ok.csv", std::string(kHead) + "1,high,20,0,0,8e4\n");
  const Outcome width = Run("traffic import ok.csv --out out.toml --bin-q-kN -5");
  EXPECT_EQ(width.exit_code, 2);
  EXPECT_TRUE(Contains(width.err, "--bin-q-kN = -5: expected a bin width > 0"));
  const Outcome missing = Run("traffic import absent.csv --out out.toml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(Contains(missing.err, "absent.csv: cannot open the MBS time-history CSV"));
  const Outcome no_out = Run("traffic import ok.csv");
  EXPECT_EQ(no_out.exit_code, 2);
  EXPECT_TRUE(Contains(no_out.err, "--out is required"));
  EXPECT_FALSE(fs::exists(dir_ / "out.toml"));
}

TEST_F(TrafficCommandTest, ExistingOutputIsReplacedOnlyWithForce) {
  Write("ok.csv", std::string(kHead) + "1,high,20,0,0,8e4\n1,low,20,0,0,7e4\n");
  Write("out.toml", "keep me\n");
  const Outcome refused = Run("traffic import ok.csv --out out.toml");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err,
            "railwear: error: out.toml: file exists; traffic import overwrites it only with "
            "--force\n");
  EXPECT_EQ(ReadFile(dir_ / "out.toml"), "keep me\n");
  const Outcome forced = Run("traffic import ok.csv --out out.toml --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  const LoadCollective back = app::ReadLoadCollective((dir_ / "out.toml").string());
  ASSERT_EQ(back.entries.size(), 2u);
  EXPECT_EQ(back.entries[0].rail, RailSide::kHigh);
  EXPECT_EQ(back.entries[1].rail, RailSide::kLow);
  EXPECT_DOUBLE_EQ(back.entries[1].vertical_force_N, 7e4);
}

TEST_F(TrafficCommandTest, BinWidthOptionsChangeTheCollective) {
  const Outcome fine = Run("traffic import '" + kExample + "' --out fine.toml");
  const Outcome coarse = Run("traffic import '" + kExample +
                             "' --out coarse.toml --bin-y-mm 2 --bin-yaw-mrad 2 --bin-q-kN 20 "
                             "--bin-xi 0.01");
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  const LoadCollective f = app::ReadLoadCollective((dir_ / "fine.toml").string());
  const LoadCollective c = app::ReadLoadCollective((dir_ / "coarse.toml").string());
  EXPECT_LT(c.entries.size(), f.entries.size());
  ExpectNear(c.widths.wheelset_y_m, 2e-3, "--bin-y-mm");
  ExpectNear(c.widths.vertical_force_N, 20e3, "--bin-q-kN");
  ExpectNear(c.total_weight_high, f.total_weight_high, "weight kept");
}

// ReadLoadCollective names the file, line and key of what it refuses.
TEST_F(TrafficCommandTest, CollectiveReaderRefusesBadFilesWithFileLineKey) {
  Write("ok.csv", std::string(kHead) + "1,high,20,0,0,8e4\n3,high,20,4,0,8e4\n1,low,20,0,0,7e4\n");
  ASSERT_EQ(Run("traffic import ok.csv --out good.toml").exit_code, 0);
  const std::string good = ReadFile(dir_ / "good.toml");
  const auto read_error = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    const std::string path = Write("bad.toml", text);
    try {
      app::ReadLoadCollective(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_TRUE(Contains(read_error("rail = \"low\"", "rail = \"middle\""),
                       "key 'traffic[2].rail' = \"middle\": expected one of 'high', 'low'"));
  EXPECT_TRUE(Contains(read_error("share = 0.25", "share = 0.5"),
                       "the shares of the high rail's entries sum to 1.25: expected 1"));
  EXPECT_TRUE(Contains(read_error("share = 0.75", "share = 0.75\nspeed_kmh = 72"),
                       "key 'traffic[1].speed_kmh' = 72: expected one of the keys allowed in "
                       "[traffic[1]]"));
  const std::string negative = read_error("vertical_N = 80000", "vertical_N = -80000");
  EXPECT_TRUE(Contains(negative, (dir_ / "bad.toml").string() + ":28: key"));  // FILE:LINE
  EXPECT_TRUE(Contains(negative, "key 'traffic[0].vertical_N' = -80000: expected a number >= 0"));
}

}  // namespace
}  // namespace railwear::test
