// Tests of IsUniformArc (patch_grid.h): arcs and lines built as such are recognised, anything
// off an arc by more than the tolerance is not, and the patch builder's grids (even on two
// circular profiles) are not uniform arcs.
#include "core/geometry/patch_grid.h"

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "core/geometry/patch_builder.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// Arc of signed curvature 1 / radius_m (0: straight), ns cells of ds, turned by angle_rad and
// moved to origin_yz (rail-frame-sized coordinates), normals on the side `normal_sign` of the
// tangent (+1: to its left). Computed as centre + R (sin, -cos), as the tests and benchmarks do.
PatchGrid MakeArc(int ns, double ds, double radius_m, double angle_rad = 0.0,
                  Eigen::Vector2d origin_yz = {0.0, 0.0}, double normal_sign = -1.0) {
  PatchGrid g;
  g.nx = 3;
  g.ns = ns;
  g.dx_m = ds;
  g.ds_m = ds;
  g.x0_m = -ds;
  g.s0_m = -0.5 * (ns - 1) * ds;
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  auto turn = [&](const Eigen::Vector2d& v) {
    return Eigen::Vector2d(c * v.x() - s * v.y(), s * v.x() + c * v.y());
  };
  for (int j = 0; j < ns; ++j) {
    Eigen::Vector2d p, t;
    if (radius_m == 0.0) {
      p = {g.S(j), 0.0};
      t = {1.0, 0.0};
    } else {
      const double theta = g.S(j) / radius_m;
      p = Eigen::Vector2d(0.0, radius_m) +
          radius_m * Eigen::Vector2d(std::sin(theta), -std::cos(theta));
      t = {std::cos(theta), std::sin(theta)};
    }
    const Eigen::Vector2d left(-t.y(), t.x());
    g.point_yz_m.push_back(origin_yz + turn(p));
    g.tangent_yz.push_back(turn(t));
    g.normal_yz.push_back(turn(normal_sign * left));
  }
  g.gap_m = Eigen::VectorXd::Zero(g.cells());
  return g;
}

// The smallest tolerance at which the grid passes IsUniformArc (bisection on a log scale; it
// passes monotonically in the tolerance): how far the grid is from a uniform arc.
double ArcDeviation(const PatchGrid& g) {
  double lo = 1e-17, hi = 10.0;
  if (!IsUniformArc(g, hi)) return hi;
  for (int k = 0; k < 60; ++k) {
    const double mid = std::sqrt(lo * hi);
    (IsUniformArc(g, mid) ? hi : lo) = mid;
  }
  return hi;
}

TEST(UniformArc, ArcsAndLinesBuiltAsSuchAreRecognised) {
  for (double radius : {10e-3, -10e-3, 5e-3, 0.3, 0.0}) {
    for (double angle : {0.0, 0.4, -2.0}) {
      for (double normal_sign : {-1.0, 1.0}) {
        SCOPED_TRACE(::testing::Message()
                     << "R " << radius << " angle " << angle << " normal " << normal_sign);
        const PatchGrid g = MakeArc(90, 1e-4, radius, angle, {0.03, -0.01}, normal_sign);
        EXPECT_TRUE(IsUniformArc(g)) << "deviation " << ArcDeviation(g);
        // Rounding alone (measured 3.7e-13 at most: a few units in the last place of the
        // 3 cm coordinates over 0.1 mm cells): far inside the tolerance.
        EXPECT_LT(ArcDeviation(g), 1e-2 * kUniformArcTolerance);
      }
    }
  }
  // 10 um cells over 86 degrees of a 20 mm arc (ns = 3,000), and one row.
  const PatchGrid fine = MakeArc(3000, 1e-5, 20e-3, 0.3, {0.03, -0.01});
  EXPECT_TRUE(IsUniformArc(fine)) << "deviation " << ArcDeviation(fine);
  EXPECT_TRUE(IsUniformArc(MakeArc(1, 1e-4, 10e-3)));
}

TEST(UniformArc, AnythingOffTheArcIsNot) {
  const PatchGrid arc = MakeArc(40, 1e-4, 10e-3, 0.2, {0.03, -0.01});
  ASSERT_TRUE(IsUniformArc(arc));
  const double off = 10 * kUniformArcTolerance;
  {
    PatchGrid g = arc;  // one point moved along its normal
    g.point_yz_m[17] += off * g.ds_m * g.normal_yz[17];
    EXPECT_FALSE(IsUniformArc(g));
  }
  {
    PatchGrid g = arc;  // one tangent turned
    g.tangent_yz[5] = (g.tangent_yz[5] + off * g.normal_yz[5]).normalized();
    EXPECT_FALSE(IsUniformArc(g));
  }
  {
    PatchGrid g = arc;  // one normal flipped
    g.normal_yz[30] = -g.normal_yz[30];
    EXPECT_FALSE(IsUniformArc(g));
  }
  {
    PatchGrid g = arc;  // the cells' length is not the points' spacing
    g.ds_m *= 1.0 + off;
    EXPECT_FALSE(IsUniformArc(g));
  }
  {
    // Points on the circle but every tangent turned by the same angle: still symmetric under a
    // shift along s, but not under s -> -s, so not Toeplitz in |i_s - j_s|.
    PatchGrid g = arc;
    for (int j = 0; j < g.ns; ++j) {
      const Eigen::Vector2d t = g.tangent_yz[j], n = g.normal_yz[j];
      g.tangent_yz[j] = std::cos(0.01) * t + std::sin(0.01) * n;
      g.normal_yz[j] = std::cos(0.01) * n - std::sin(0.01) * t;
    }
    EXPECT_FALSE(IsUniformArc(g));
  }
  {
    // A parabola z = y^2 / (2 * 8 mm), tangents and normals its own: curvature varies.
    PatchGrid g = arc;
    for (int j = 0; j < g.ns; ++j) {
      const double y = g.S(j);
      g.point_yz_m[j] = {y, y * y / (2.0 * 8e-3)};
      g.tangent_yz[j] = Eigen::Vector2d(1.0, y / 8e-3).normalized();
      g.normal_yz[j] = {g.tangent_yz[j].y(), -g.tangent_yz[j].x()};
    }
    EXPECT_FALSE(IsUniformArc(g));
  }
}

// The patch builder's grids: a 10 mm wheel in a 10.25 mm groove (two circular profiles) and
// S1002 on UIC60 1:40 at the gauge corner. The reference curve is the intermediate curve of
// seed eq. 1, which for two arcs of different radii is no arc, sampled as a polyline (points
// linear between samples a cell / 8 or 20 um apart, tangents constant per sample interval).
TEST(UniformArc, PatchBuilderGridsAreNot) {
  PatchGridOptions o;
  o.geometry = GeometryModel::kConformal;
  o.cell_dx_m = 2e-4;
  o.cell_ds_m = 2e-4;
  o.threshold_m = 2e-5;
  {
    WheelPose pose;
    pose.rolling_radius_m = 0.46;
    const Profile wheel = testing::ArcProfile(0.010, -1.0),
                  rail = testing::ArcProfile(0.01025, -1.0);
    const WheelRailGeometry g(wheel, rail, pose);  // keeps references to the profiles
    const auto cands = g.FindCandidates(2e-5);
    ASSERT_EQ(cands.size(), 1u);
    const PatchBuild b = BuildPatchGrid(g, cands[0], o);
    ASSERT_TRUE(b.valid);
    ASSERT_GT(b.grid.ns, 20);
    const double deviation = ArcDeviation(b.grid);
    std::cout << "[ figures  ] 10 mm wheel in a 10.25 mm groove, " << b.grid.ns
              << " rows: off a uniform arc by " << deviation << "\n";
    EXPECT_FALSE(IsUniformArc(b.grid));
  }
  {
    WheelPose pose;
    pose.rolling_radius_m = 0.46;
    pose.lateral_shift_m = -0.004;
    const Profile wheel = MakeS1002(), rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
    const WheelRailGeometry g(wheel, rail, pose);
    const auto cands = g.FindCandidates(1e-4);
    ASSERT_FALSE(cands.empty());
    for (const ContactCandidate& c : cands) {
      const PatchBuild b = BuildPatchGrid(g, c, o);
      if (!b.valid || b.grid.ns < 3) continue;
      const double deviation = ArcDeviation(b.grid);
      std::cout << "[ figures  ] S1002 on UIC60 1:40, patch of " << b.grid.ns
                << " rows: off a uniform arc by " << deviation << "\n";
      EXPECT_FALSE(IsUniformArc(b.grid));
    }
  }
}

}  // namespace
}  // namespace railwear
