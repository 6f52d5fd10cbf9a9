// MBS time-history CSV parsing and its binning into a load collective (wear/load_collective.h):
// what a CSV may hold, conservation of weight and first moments, the bins' widths, and that a
// CSV made from known wheelset states gives those states back. The CSV's error messages, with
// their line numbers and exit code, are tested through the CLI (tests/app/traffic_command_test).
#include "wear/load_collective.h"

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

// Sums of ~1e3 doubles of order 1: rounding far below this.
constexpr double kSumTolerance = 1e-12;

constexpr const char* kHeader = "weight_passes,side,V_m_s,y_mm,yaw_mrad,Q_N";

TEST(LoadCollectiveTest, ParsesColumnsInAnyOrderWithCommentsBlankLinesAndCrlf) {
  const std::string csv =
      "# a comment\r\n"
      "\r\n"
      "Q_N , side,y_mm,weight_m,yaw_mrad,V_m_s,mbs_Fy_N,roll_mrad,xi,mu,axle_load_t\r\n"
      "  # indented comment\r\n"
      "80000,right,5.5,0.2,2.5,20,30000,-1.5,-0.002,0.35,16.5\r\n"
      "\r\n"
      "75000,left,5.5,0.2,2.5,20,9000,-1.5,0.002,0.35,16.5\r\n";
  const MbsTimeHistory h = ParseMbsTimeHistory(csv, "t.csv");
  EXPECT_EQ(h.weight_unit, WeightUnit::kDistance);
  EXPECT_TRUE(h.has_roll && h.has_creepage_x && h.has_friction && h.has_axle_load);
  ASSERT_EQ(h.mbs_names, std::vector<std::string>{"Fy_N"});
  ASSERT_EQ(h.rows.size(), 2u);
  const MbsRow& r = h.rows[0];
  EXPECT_EQ(r.line, 5);
  EXPECT_EQ(h.rows[1].line, 7);
  EXPECT_EQ(r.rail, RailSide::kHigh);  // right = high
  EXPECT_EQ(h.rows[1].rail, RailSide::kLow);
  EXPECT_DOUBLE_EQ(r.vertical_force_N, 80000.0);
  EXPECT_DOUBLE_EQ(r.wheelset_y_m, 5.5e-3);  // SI inside
  EXPECT_DOUBLE_EQ(r.yaw_rad, 2.5e-3);
  EXPECT_DOUBLE_EQ(r.roll_rad, -1.5e-3);
  EXPECT_DOUBLE_EQ(r.weight, 0.2);
  EXPECT_DOUBLE_EQ(r.speed_m_s, 20.0);
  EXPECT_DOUBLE_EQ(*r.creepage_x, -0.002);
  EXPECT_DOUBLE_EQ(*r.friction, 0.35);
  EXPECT_DOUBLE_EQ(*r.axle_load_t, 16.5);
  EXPECT_DOUBLE_EQ(r.mbs[0], 30000.0);
}

TEST(LoadCollectiveTest, OptionalColumnsStayAbsent) {
  const MbsTimeHistory h =
      ParseMbsTimeHistory(std::string(kHeader) + "\n1,high,20,0,0,80000", "t.csv");  // no final \n
  EXPECT_EQ(h.weight_unit, WeightUnit::kPasses);
  EXPECT_FALSE(h.has_roll || h.has_creepage_x || h.has_friction || h.has_axle_load);
  ASSERT_EQ(h.rows.size(), 1u);
  EXPECT_FALSE(h.rows[0].friction || h.rows[0].creepage_x || h.rows[0].axle_load_t);
  const LoadCollective c = BinLoadCollective(h, {});
  ASSERT_EQ(c.entries.size(), 1u);
  EXPECT_FALSE(c.entries[0].friction || c.entries[0].creepage_x);
  // 2 Q / g / 1000 when the CSV has no axle_load_t column.
  EXPECT_DOUBLE_EQ(c.entries[0].axle_load_t, 2.0 * 80000.0 / kGravity_m_s2 / 1000.0);
  EXPECT_FALSE(c.axle_load_from_column);
}

// Random rows of every column, printed with 17 digits so that the parsed values are the drawn
// ones.
std::string RandomCsv(int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::string csv = "weight_passes,side,V_m_s,y_mm,yaw_mrad,roll_mrad,Q_N,xi,mu,mbs_Fy_N\n";
  for (int i = 0; i < rows; ++i) {
    const bool zero = i % 17 == 0;  // some rows of weight 0: read, not binned
    csv +=
        fmt::format("{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n",
                    zero ? 0.0 : 0.1 + u(rng), u(rng) < 0.5 ? "high" : "low", 18 + 6 * u(rng),
                    -3 + 10 * u(rng), -3 + 6 * u(rng), -2 + 2 * u(rng), 60e3 + 40e3 * u(rng),
                    -0.004 + 0.008 * u(rng), 0.2 + 0.2 * u(rng), 40e3 * u(rng));
  }
  return csv;
}

// Weighted sums of the rows of each rail, straight from the rows (the naive reference).
struct RailSums {
  double weight = 0, y = 0, yaw = 0, roll = 0, q = 0, v = 0, xi = 0, mu = 0, fy = 0;
  int rows = 0;
};

std::map<RailSide, RailSums> RowSums(const MbsTimeHistory& h) {
  std::map<RailSide, RailSums> s;
  for (const MbsRow& r : h.rows) {
    RailSums& a = s[r.rail];
    const double w = r.weight;
    a.weight += w;
    a.y += w * r.wheelset_y_m;
    a.yaw += w * r.yaw_rad;
    a.roll += w * r.roll_rad;
    a.q += w * r.vertical_force_N;
    a.v += w * r.speed_m_s;
    a.xi += w * *r.creepage_x;
    a.mu += w * *r.friction;
    a.fy += w * r.mbs[0];
    a.rows += w > 0 ? 1 : 0;
  }
  return s;
}

std::map<RailSide, RailSums> EntrySums(const LoadCollective& c) {
  std::map<RailSide, RailSums> s;
  for (const LoadCollectiveEntry& e : c.entries) {
    RailSums& a = s[e.rail];
    const double w = e.weight;
    a.weight += w;
    a.y += w * e.wheelset_y_m;
    a.yaw += w * e.yaw_rad;
    a.roll += w * e.roll_rad;
    a.q += w * e.vertical_force_N;
    a.v += w * e.speed_m_s;
    a.xi += w * *e.creepage_x;
    a.mu += w * *e.friction;
    a.fy += w * e.mbs[0];
    a.rows += e.rows;
  }
  return s;
}

void ExpectSameSums(const RailSums& a, const RailSums& b) {
  const auto near = [](double x, double y) {
    return std::abs(x - y) <= kSumTolerance * std::max(1.0, std::abs(y));
  };
  EXPECT_TRUE(near(a.weight, b.weight)) << a.weight << " " << b.weight;
  EXPECT_TRUE(near(a.y, b.y)) << a.y << " " << b.y;
  EXPECT_TRUE(near(a.yaw, b.yaw));
  EXPECT_TRUE(near(a.roll, b.roll));
  EXPECT_TRUE(near(a.q, b.q)) << a.q << " " << b.q;
  EXPECT_TRUE(near(a.v, b.v));
  EXPECT_TRUE(near(a.xi, b.xi));
  EXPECT_TRUE(near(a.mu, b.mu));
  EXPECT_TRUE(near(a.fy, b.fy));
  EXPECT_EQ(a.rows, b.rows);
}

TEST(LoadCollectiveTest, BinningKeepsEachRailsWeightAndWeightedMeans) {
  const MbsTimeHistory h = ParseMbsTimeHistory(RandomCsv(400, 15), "random.csv");
  const LoadCollective c = BinLoadCollective(h, {});
  EXPECT_EQ(c.rows_read, 400);
  EXPECT_EQ(c.rows_zero_weight, 24);  // i % 17 == 0 for i < 400
  const auto rows = RowSums(h);
  const auto bins = EntrySums(c);
  for (const RailSide rail : {RailSide::kHigh, RailSide::kLow}) {
    SCOPED_TRACE(std::string(ToString(rail)));
    ExpectSameSums(bins.at(rail), rows.at(rail));
    EXPECT_NEAR(rail == RailSide::kHigh ? c.total_weight_high : c.total_weight_low,
                rows.at(rail).weight, kSumTolerance * rows.at(rail).weight);
    double share = 0.0;
    for (const LoadCollectiveEntry& e : c.entries) {
      if (e.rail == rail) share += e.share;
    }
    EXPECT_NEAR(share, 1.0, kSumTolerance);
  }
}

TEST(LoadCollectiveTest, EntriesAreOrderedByRailThenBinAndMeansLieInTheirBins) {
  const MbsTimeHistory h = ParseMbsTimeHistory(RandomCsv(300, 7), "random.csv");
  const LoadCollectiveBinWidths w;
  const LoadCollective c = BinLoadCollective(h, w);
  const auto cell = [](double v, double width) { return std::floor(v / width); };
  std::set<std::vector<double>> keys;
  std::vector<double> previous;
  bool low_seen = false;
  for (const LoadCollectiveEntry& e : c.entries) {
    if (e.rail == RailSide::kLow) low_seen = true;
    EXPECT_FALSE(low_seen && e.rail == RailSide::kHigh) << "high after low: " << e.name;
    // A weighted mean of values in [k w, (k+1) w) lies in that cell (up to rounding at an edge).
    const std::vector<double> key = {e.rail == RailSide::kHigh ? 0.0 : 1.0,
                                     cell(e.wheelset_y_m * (1 + 1e-12), w.wheelset_y_m),
                                     cell(e.yaw_rad * (1 + 1e-12), w.yaw_rad),
                                     cell(e.vertical_force_N, w.vertical_force_N),
                                     cell(e.speed_m_s, w.speed_m_s),
                                     cell(*e.friction, w.friction),
                                     cell(*e.creepage_x * (1 + 1e-12), w.creepage_x)};
    EXPECT_TRUE(keys.insert(key).second) << "two entries in one bin: " << e.name;
    if (!previous.empty() && previous[0] == key[0]) {
      EXPECT_LT(previous, key) << e.name;
    }
    previous = key;
  }
}

TEST(LoadCollectiveTest, BinWidthsSetHowManyEntries) {
  const MbsTimeHistory h = ParseMbsTimeHistory(RandomCsv(300, 3), "random.csv");
  LoadCollectiveBinWidths fine;
  fine.wheelset_y_m = fine.yaw_rad = fine.vertical_force_N = fine.speed_m_s = fine.friction =
      fine.creepage_x = 1e-9;
  LoadCollectiveBinWidths coarse;
  coarse.wheelset_y_m = 2e-3;
  coarse.yaw_rad = 2e-3;
  coarse.vertical_force_N = 20e3;
  LoadCollectiveBinWidths huge;
  huge.wheelset_y_m = huge.yaw_rad = huge.vertical_force_N = huge.speed_m_s = huge.friction =
      huge.creepage_x = 1e6;
  const LoadCollective c_fine = BinLoadCollective(h, fine);
  const LoadCollective c_default = BinLoadCollective(h, {});
  const LoadCollective c_coarse = BinLoadCollective(h, coarse);
  const LoadCollective c_huge = BinLoadCollective(h, huge);
  // Tiny bins: one entry per row of weight > 0 (random rows never share a cell).
  EXPECT_EQ(static_cast<int>(c_fine.entries.size()), c_fine.rows_read - c_fine.rows_zero_weight);
  EXPECT_LE(c_default.entries.size(), c_fine.entries.size());
  EXPECT_LT(c_coarse.entries.size(), c_default.entries.size());
  // Bins of 1e6 on a grid anchored at 0 split only by sign: y, yaw and xi take both signs here
  // (Q, V, mu are positive), so there is one entry per rail and sign triple that occurs.
  std::set<std::vector<int>> signs;
  for (const MbsRow& r : h.rows) {
    if (r.weight > 0) {
      signs.insert(
          {static_cast<int>(r.rail), r.wheelset_y_m < 0, r.yaw_rad < 0, *r.creepage_x < 0});
    }
  }
  EXPECT_EQ(c_huge.entries.size(), signs.size());
  const auto rows = RowSums(h);
  // Each collective keeps the weight, whatever its bins.
  for (const LoadCollective* c : {&c_fine, &c_default, &c_coarse, &c_huge}) {
    ExpectSameSums(EntrySums(*c).at(RailSide::kLow), rows.at(RailSide::kLow));
  }
}

// A CSV made from known wheelset states (rows spread symmetrically about each state, inside
// its bin, equal weights) gives those states back, each with its total weight.
TEST(LoadCollectiveTest, CsvFromKnownStatesGivesTheStatesBack) {
  struct State {
    const char* side;
    double y_mm, yaw_mrad, q_N, v_m_s, passes;
  };
  // Values at bin centres of the default widths (0.5 mm, 0.5 mrad, 5 kN, 2 m/s).
  const std::vector<State> states = {{"high", 6.25, 2.25, 82500, 21, 30},
                                     {"high", 2.25, -1.25, 77500, 21, 10},
                                     {"low", 6.25, 2.25, 72500, 21, 30},
                                     {"low", 2.25, -1.25, 77500, 21, 10}};
  std::string csv = std::string(kHeader) + "\n";
  for (const State& s : states) {
    for (const double d : {-1.0, 1.0}) {  // two rows of half the passes each, +-0.1 of a bin
      csv += fmt::format("{},{},{},{},{},{}\n", s.passes / 2, s.side, s.v_m_s + 0.2 * d,
                         s.y_mm + 0.05 * d, s.yaw_mrad - 0.05 * d, s.q_N + 500 * d);
    }
  }
  const LoadCollective c = BinLoadCollective(ParseMbsTimeHistory(csv, "states.csv"), {});
  ASSERT_EQ(c.entries.size(), states.size());
  // Entries come sorted by rail then bin: y ascending within a rail.
  const std::vector<int> order = {1, 0, 3, 2};
  for (std::size_t i = 0; i < order.size(); ++i) {
    const State& s = states[order[i]];
    const LoadCollectiveEntry& e = c.entries[i];
    SCOPED_TRACE(e.name);
    EXPECT_EQ(ToString(e.rail), s.side);
    EXPECT_NEAR(e.wheelset_y_m, s.y_mm * 1e-3, 1e-15);
    EXPECT_NEAR(e.yaw_rad, s.yaw_mrad * 1e-3, 1e-15);
    EXPECT_NEAR(e.vertical_force_N, s.q_N, 1e-9);
    EXPECT_NEAR(e.speed_m_s, s.v_m_s, 1e-12);
    EXPECT_DOUBLE_EQ(e.weight, s.passes);
    EXPECT_DOUBLE_EQ(e.share, s.passes / 40.0);
    EXPECT_EQ(e.rows, 2);
  }
  EXPECT_EQ(EntryCount(c, RailSide::kHigh), 2);
  EXPECT_EQ(EntryCount(c, RailSide::kLow), 2);
}

TEST(LoadCollectiveTest, BadWidthsAndWeightlessFilesAreRefused) {
  LoadCollectiveBinWidths w;
  w.wheelset_y_m = 0.0;
  const MbsTimeHistory h =
      ParseMbsTimeHistory(std::string(kHeader) + "\n1,high,20,0,0,8e4\n", "t.csv");
  try {
    BinLoadCollective(h, w);
    FAIL() << "a zero bin width was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--bin-y-mm = 0: expected a bin width > 0");
  }
  const MbsTimeHistory zero = ParseMbsTimeHistory(
      std::string(kHeader) + "\n0,high,20,0,0,8e4\n0,low,20,0,0,8e4\n", "z.csv");
  try {
    BinLoadCollective(zero, {});
    FAIL() << "a file of weight 0 was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "z.csv: all 2 rows have weight 0: expected at least one row of weight > 0");
  }
}

}  // namespace
}  // namespace railwear
