#include "wear/traffic.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "wear/spread_integration.h"

namespace railwear {
namespace {

TEST(TrafficTest, GaussHermiteIntegratesNormalMoments) {
  // E[X^2k] of N(0,1) = (2k-1)!!; an n-point rule is exact up to degree 2n-1. Up to the most
  // fixed nodes a scene takes (kMaxQuadraturePoints, 81: Golub-Welsch stays accurate there).
  std::vector<int> counts = {15, 20, 30, 41, 61, kMaxQuadraturePoints};
  for (int n = 1; n <= 9; ++n) counts.push_back(n);
  for (const int n : counts) {
    std::vector<double> x, w;
    GaussHermiteProbabilists(n, &x, &w);
    double moment[10] = {};
    for (int k = 0; k < n; ++k) {
      double p = 1.0;
      for (int d = 0; d < 10; ++d, p *= x[k]) moment[d] += w[k] * p;
    }
    const double exact[10] = {1, 0, 1, 0, 3, 0, 15, 0, 105, 0};
    for (int d = 0; d < std::min(10, 2 * n); ++d) {
      EXPECT_NEAR(moment[d], exact[d], 1e-12 * std::max(1.0, exact[d])) << "n " << n << " d " << d;
    }
    for (int k = 0; k < n; ++k) {  // symmetric rule
      EXPECT_EQ(x[k], -x[n - 1 - k]);
      EXPECT_EQ(w[k], w[n - 1 - k]);
    }
  }
}

TrafficCase MakeCase(double share, double std_mm) {
  TrafficCase c;
  c.name = "test";
  c.wheel_profile = MakeS1002();
  c.vertical_force_N = 100e3;
  c.axle_load_t = 20.0;
  c.lateral_shift_mean_m = -4e-3;
  c.lateral_shift_std_m = std_mm * 1e-3;
  c.share = share;
  return c;
}

TEST(TrafficTest, ExpandWeightsSumToOneAndMeanIsKept) {
  const std::vector<TrafficCase> traffic = {MakeCase(0.7, 1.5), MakeCase(0.3, 0.0)};
  const std::vector<LoadCase> cases = ExpandTraffic(traffic, 5);
  ASSERT_EQ(cases.size(), 6u);  // 5 nodes + 1 (std = 0)
  double sum = 0.0, mean0 = 0.0, var0 = 0.0;
  for (const LoadCase& c : cases) {
    sum += c.weight;
    if (c.traffic_index == 0) {
      mean0 += c.weight / 0.7 * c.placement.lateral_shift_m;
      var0 += c.weight / 0.7 * std::pow(c.placement.lateral_shift_m + 4e-3, 2);
    }
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
  EXPECT_NEAR(mean0, -4e-3, 1e-15);
  EXPECT_NEAR(var0, 1.5e-3 * 1.5e-3, 1e-18);
  EXPECT_NEAR(cases.back().weight, 0.3, 1e-15);
}

// The piecewise-linear rule (spread_rule = "piecewise_linear") on a prescribed entry: a case per
// node at mean + std x with the entry's share times the node's LinearGaussianWeights weight; the
// entry without spread keeps its one case.
TEST(TrafficTest, LinearNodesExpandPrescribedSpreads) {
  const std::vector<TrafficCase> traffic = {MakeCase(0.7, 1.5), MakeCase(0.3, 0.0)};
  const std::vector<double> x = LinearSpreadNodes(8);
  const std::vector<double> w = LinearGaussianWeights(x);
  const std::vector<LoadCase> cases = internal::ExpandValidTraffic(traffic, 5, x);
  ASSERT_EQ(cases.size(), x.size() + 1);
  double sum = 0.0;
  for (size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(cases[k].node, static_cast<int>(k));
    EXPECT_EQ(cases[k].spread_x, x[k]);
    EXPECT_NEAR(cases[k].placement.lateral_shift_m, -4e-3 + 1.5e-3 * x[k], 1e-18);
    EXPECT_NEAR(cases[k].weight, 0.7 * w[k], 1e-16);
    sum += cases[k].weight;
  }
  EXPECT_NEAR(sum, 0.7, 1e-14);
  EXPECT_NEAR(cases.back().weight, 0.3, 1e-15);
}

TEST(TrafficTest, MgtPerPassIsShareWeightedAxleLoad) {
  std::vector<TrafficCase> traffic = {MakeCase(3.0, 0.0), MakeCase(1.0, 0.0)};
  traffic[1].axle_load_t = 10.0;
  EXPECT_NEAR(MgtPerPass(traffic), (3 * 20.0 + 10.0) / 4.0 / 1e6, 1e-20);
}

TEST(TrafficTest, SharesAreNormalisedPerRailAndCasesCarryTheEntry) {
  std::vector<TrafficCase> traffic = {MakeCase(3.0, 1.0), MakeCase(1.0, 0.0), MakeCase(0.5, 0.0)};
  traffic[1].rail = RailSide::kLow;
  traffic[1].yaw_rad = -2e-3;
  traffic[1].roll_rad = 1e-3;
  traffic[1].rolling_radius_m = 0.45;
  traffic[1].friction = 0.25;
  traffic[1].speed_m_s = 30.0;
  traffic[1].vertical_force_N = 70e3;
  const std::vector<LoadCase> cases = ExpandTraffic(traffic, 3);
  ASSERT_EQ(cases.size(), 5u);  // 3 nodes + 1 + 1
  double high = 0.0, low = 0.0;
  for (const LoadCase& c : cases) (c.rail == RailSide::kHigh ? high : low) += c.weight;
  EXPECT_NEAR(high, 1.0, 1e-14);
  EXPECT_NEAR(low, 1.0, 1e-14);
  const LoadCase& l = cases[3];
  EXPECT_EQ(l.traffic_index, 1);
  EXPECT_EQ(l.rail, RailSide::kLow);
  EXPECT_EQ(l.weight, 1.0);
  EXPECT_EQ(l.placement.lateral_shift_m, -4e-3);
  EXPECT_EQ(l.placement.yaw_rad, -2e-3);
  EXPECT_EQ(l.placement.roll_rad, 1e-3);
  EXPECT_EQ(l.placement.rolling_radius_m, 0.45);
  EXPECT_EQ(l.friction, 0.25);
  EXPECT_EQ(l.motion.speed_m_s, 30.0);
  EXPECT_FALSE(l.motion.pitch_velocity_rad_s.has_value());  // pure rolling at r0
  EXPECT_EQ(l.vertical_force_N, 70e3);
  EXPECT_NEAR(cases[4].weight, 0.5 / 3.5, 1e-15);
}

TEST(TrafficTest, MgtPerPassCountsTheHighRailOrElseTheLowRail) {
  std::vector<TrafficCase> traffic = {MakeCase(1.0, 0.0), MakeCase(1.0, 0.0)};
  traffic[1].rail = RailSide::kLow;
  traffic[1].axle_load_t = 10.0;
  EXPECT_NEAR(MgtPerPass(traffic), 20.0 / 1e6, 1e-20);  // an axle is counted once
  traffic[0].rail = RailSide::kLow;
  EXPECT_NEAR(MgtPerPass(traffic), 15.0 / 1e6, 1e-20);
  EXPECT_FALSE(HasTrafficOn(traffic, RailSide::kHigh));
  EXPECT_TRUE(HasTrafficOn(traffic, RailSide::kLow));
}

TEST(TrafficTest, RailSideNames) {
  EXPECT_EQ(ToString(RailSide::kHigh), "high");
  EXPECT_EQ(ToString(RailSide::kLow), "low");
  EXPECT_EQ(RailSideFromString("low"), RailSide::kLow);
  EXPECT_FALSE(RailSideFromString("left").has_value());
}

TEST(TrafficTest, BadEntriesNameTheKey) {
  std::vector<TrafficCase> traffic = {MakeCase(1.0, -1.0)};
  traffic[0].name = "freight";
  try {
    ExpandTraffic(traffic, 5);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("freight: lateral_shift_mm.std = -1"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ExpandTraffic({}, 5), InputError);
  EXPECT_THROW(ExpandTraffic({MakeCase(1.0, 1.0)}, 0), InputError);
  EXPECT_THROW(ValidateQuadraturePoints(kMaxQuadraturePoints + 1), InputError);
  EXPECT_NO_THROW(ValidateQuadraturePoints(kMaxQuadraturePoints));
}

}  // namespace
}  // namespace railwear
