#include "core/contact/patch_results.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"
#include "tests/core/contact/hertz_grid.h"

namespace railwear::internal {
namespace {

// Every sample evaluated, as SubCellArea counted a square before SubSampledHits bisected its rows.
int EverySampleHits(double a, double b, double c, double d) {
  int hit = 0;
  for (int v = 0; v < kSubSamples; ++v) {
    const double t = (v + 0.5) / kSubSamples;
    for (int u = 0; u < kSubSamples; ++u) {
      const double r = (u + 0.5) / kSubSamples;
      hit += (1 - r) * (1 - t) * a + r * (1 - t) * b + (1 - r) * t * c + r * t * d > 0;
    }
  }
  return hit;
}

TEST(SubCellArea, BisectedRowsCountTheSameSamplesAsEverySample) {
  // Random corners of mixed signs and scales, and the degenerate ones: equal corners, a row's
  // ends that cancel (B = 0 or within rounding), zeros, a root on a sample.
  std::mt19937_64 rng(20);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<std::vector<double>> squares = {
      {1, -1, 1, -1},         {1, 1, -1, -1},         {0, 0, 0, 1},     {1e-300, -1e-300, 0, 0},
      {1, 1 + 1e-15, -1, -1}, {2.5, -0.5, 2.5, -0.5}, {-1, 23, -1, 23}, {1e24, -1e-3, 5e23, -2e-3}};
  for (int k = 0; k < 20000; ++k) {
    const double scale = std::pow(10.0, 30.0 * unit(rng));
    squares.push_back({scale * unit(rng), scale * unit(rng), scale * unit(rng), scale * unit(rng)});
    // nearly flat rows: b = a and d = c to a few roundings
    const double a = scale * unit(rng), c = scale * unit(rng);
    squares.push_back({a, a * (1 + 1e-15 * unit(rng)), c, c * (1 + 1e-14 * unit(rng))});
  }
  for (const auto& s : squares) {
    ASSERT_EQ(SubSampledHits(s[0], s[1], s[2], s[3]), EverySampleHits(s[0], s[1], s[2], s[3]))
        << s[0] << " " << s[1] << " " << s[2] << " " << s[3];
  }
}

TEST(SubCellArea, AHertzPatchsAreaWithinTheSecondOrderEstimatorsError) {
  // A Hertz pressure on the ellipse a = 6, b = 4 mm over a grid of 10 cells per semi-axis
  // (standard), the ellipse inside a grid 1.5 times wider: the level-set area is within 1 % of
  // pi a b (second order: whole cells would count some 3 % more, patch_results.cpp).
  const double a = 6e-3, b = 4e-3;
  const PatchGrid g = testing::MakeHertzGrid(1.5 * a, 1.5 * b, 30, 30);
  const Eigen::VectorXd p = testing::HertzPressure(g, a, b, 1e5);
  EXPECT_NEAR(SubCellArea(g, p) / (M_PI * a * b), 1.0, 0.01);
}

TEST(SubCellArea, ADeferredAreaIsFilledWithTheOneComputedAtOnce) {
  // NumericalPatch with PatchArea::kDeferred leaves the area NaN (and every other result as at
  // once); FillDeferredAreas computes it, the same bit for bit, and leaves computed ones alone.
  const double a = 6e-3, b = 4e-3;
  const PatchGrid g = testing::MakeHertzGrid(1.5 * a, 1.5 * b, 30, 30);
  const Eigen::VectorXd p = testing::HertzPressure(g, a, b, 1e5);
  const Profile rail = MakeUic60();
  const Profile wheel = MakeS1002();
  const WheelRailGeometry geom(wheel, rail, WheelPose{});
  std::vector<PatchResult> patches = {
      NumericalPatch(geom, g, p, std::nullopt, PatchArea::kDeferred), NumericalPatch(geom, g, p)};
  const PatchResult now = NumericalPatch(geom, g, p);
  EXPECT_TRUE(std::isnan(patches[0].area_m2));
  EXPECT_EQ(patches[0].normal_force_N, now.normal_force_N);
  EXPECT_EQ(patches[0].p_max_Pa, now.p_max_Pa);
  patches[1].area_m2 = 1.0;  // (computed: left as it is)
  FillDeferredAreas(&patches);
  EXPECT_EQ(patches[0].area_m2, now.area_m2);
  EXPECT_EQ(patches[1].area_m2, 1.0);
}

}  // namespace
}  // namespace railwear::internal
