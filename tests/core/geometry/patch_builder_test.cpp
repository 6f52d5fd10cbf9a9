#include "core/geometry/patch_builder.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"

#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// Projections are refined on C2 splines of 801-point arcs (position error ~1e-12 m) to a
// parameter tolerance of 1e-12 m; the reference curve is linear between samples 20 um apart,
// which moves a cell centre off the exact intermediate curve by at most h^2 kappa / 8 ~ 5e-9 m —
// the gap itself is exact for the point used, so compare gaps to 1e-10 m.
constexpr double kGapTolerance_m = 1e-10;

// A 10 mm convex wheel in a 10.25 mm groove, both touching at the origin, and a conformal grid
// of 0.2 mm cells on it. At x = 0 the gap of seed eq. 2 is exact:
// d = (R2 - |P - C2|) + (|P - C1| - R1), C1 = (0, -R1), C2 = (0, -R2).
struct Groove {
  static constexpr double R1 = 0.010, R2 = 0.01025;
  const Profile wheel = testing::ArcProfile(R1, -1.0);
  const Profile rail = testing::ArcProfile(R2, -1.0);
  static WheelPose Pose() {
    WheelPose pose;
    pose.rolling_radius_m = 0.46;
    return pose;
  }
  static PatchGridOptions Options() {
    PatchGridOptions o;
    o.geometry = GeometryModel::kConformal;
    o.cell_dx_m = 2e-4;
    o.cell_ds_m = 2e-4;
    o.threshold_m = 2e-5;
    return o;
  }
};

TEST(PatchBuilder, ConformalGapIsTheSumOfOrthogonalDistances) {
  const Groove groove;
  const double R1 = Groove::R1, R2 = Groove::R2;
  const WheelPose pose = Groove::Pose();
  const WheelRailGeometry g(groove.wheel, groove.rail, pose);
  const auto cands = g.FindCandidates(2e-5);
  ASSERT_EQ(cands.size(), 1u);
  const PatchBuild b = BuildPatchGrid(g, cands[0], Groove::Options());
  ASSERT_TRUE(b.valid);
  const PatchGrid& grid = b.grid;
  EXPECT_FALSE(grid.planar);
  EXPECT_GT(grid.ns, 20);  // the conformal patch wraps far around the groove
  const Eigen::Vector2d c1(0.0, -R1), c2(0.0, -R2);
  const int ic = (grid.nx - 1) / 2;
  EXPECT_NEAR(grid.X(ic), 0.0, 1e-15);
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d p = grid.point_yz_m[j];
    const double exact = (R2 - (p - c2).norm()) + ((p - c1).norm() - R1);
    EXPECT_NEAR(grid.gap_m[grid.Index(ic, j)], exact, kGapTolerance_m) << j;
    // Identical materials: the cell centre lies midway between the two circles along the
    // common radial direction (to the curvature of the offset between them).
    const double mid = 0.5 * ((p - c1).norm() - R1 - (R2 - (p - c2).norm()));
    EXPECT_NEAR(mid, 0.0, 1e-7) << j;
    // Normals point out of the rail, into the wheel: toward the circle centres.
    EXPECT_GT(grid.normal_yz[j].dot((c1 - p).normalized()), 0.999);
  }
  // The gap grows away from x = 0 as the wheel lifts: x^2/(2 r0) w, w = -n_z.
  const int j0 = static_cast<int>(std::lround(-grid.s0_m / grid.ds_m));
  const double x = grid.X(grid.nx - 1);
  EXPECT_NEAR(grid.gap_m[grid.Index(grid.nx - 1, j0)] - grid.gap_m[grid.Index(ic, j0)],
              x * x / (2 * pose.rolling_radius_m), 1e-3 * x * x / (2 * pose.rolling_radius_m));
}

TEST(PatchBuilder, UpdatedConformalGapsAreTheMovedWheelsOnTheSameCells) {
  // The groove; the grid's gaps computed again (UpdateConformalGaps) on the
  // same placed geometry are BuildPatchGrid's bit for bit, and on a geometry whose wheel moved
  // 5 um across (and was lowered to first contact again) they are seed eq. 2's exact gaps of the
  // moved wheel circle at the same cells.
  const Groove groove;
  const double R1 = Groove::R1, R2 = Groove::R2;
  const WheelPose pose = Groove::Pose();
  const WheelRailGeometry g(groove.wheel, groove.rail, pose);
  const auto cands = g.FindCandidates(2e-5);
  ASSERT_EQ(cands.size(), 1u);
  PatchGridOptions o = Groove::Options();
  const PatchBuild b = BuildPatchGrid(g, cands[0], o);
  ASSERT_TRUE(b.valid);
  PatchBuild again = b;
  ASSERT_TRUE(UpdateConformalGaps(g, &again));
  for (int k = 0; k < b.grid.cells(); ++k) EXPECT_EQ(again.grid.gap_m[k], b.grid.gap_m[k]) << k;

  WheelPose moved_pose = pose;
  moved_pose.lateral_shift_m = 5e-6;
  const WheelRailGeometry moved(groove.wheel, groove.rail, moved_pose);
  PatchBuild updated = b;
  ASSERT_TRUE(UpdateConformalGaps(moved, &updated));
  const Eigen::Vector2d c1 = moved.WheelToRail(g.RailToWheel({0.0, -R1})), c2(0.0, -R2);
  EXPECT_NEAR(std::abs(c1.x()), 5e-6, 1e-12);  // (the wheel did move)
  const PatchGrid& grid = updated.grid;
  const int ic = (grid.nx - 1) / 2;
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d p = grid.point_yz_m[j];
    const double exact = (R2 - (p - c2).norm()) + ((p - c1).norm() - R1);
    EXPECT_NEAR(grid.gap_m[grid.Index(ic, j)], exact, kGapTolerance_m) << j;
  }
  // A planar build has nothing to update.
  o.geometry = GeometryModel::kPlanar;
  PatchBuild planar = BuildPatchGrid(g, cands[0], o);
  EXPECT_FALSE(UpdateConformalGaps(g, &planar));
}

// Everything a build reports, compared with ==.
void ExpectSameBuild(const PatchBuild& a, const PatchBuild& b) {
  EXPECT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.lateral_limited, b.lateral_limited);
  EXPECT_EQ(a.trimmed, b.trimmed);
  EXPECT_EQ(a.too_large, b.too_large);
  EXPECT_EQ(a.grid.nx, b.grid.nx);
  EXPECT_EQ(a.grid.ns, b.grid.ns);
  EXPECT_EQ(a.grid.x0_m, b.grid.x0_m);
  EXPECT_EQ(a.grid.s0_m, b.grid.s0_m);
  EXPECT_EQ(a.grid.point_yz_m, b.grid.point_yz_m);
  EXPECT_EQ(a.grid.tangent_yz, b.grid.tangent_yz);
  EXPECT_EQ(a.grid.normal_yz, b.grid.normal_yz);
  EXPECT_TRUE(a.grid.gap_m.size() == b.grid.gap_m.size() && a.grid.gap_m == b.grid.gap_m);
  EXPECT_EQ(a.rail_s_m, b.rail_s_m);
  EXPECT_EQ(a.wheel_s_m, b.wheel_s_m);
  EXPECT_EQ(a.x_contact_m, b.x_contact_m);
}

TEST(PatchBuilder, AKeptLateralWalkGivesTheSameGridsBitForBit) {
  // The groove's candidate gridded in turn at other cells, thresholds (lower: a prefix of the
  // kept walk; higher: the walk goes on from its last section; far higher: up to the profile's
  // end), models and a size limit, all on one LateralWalkCache: each grid equals the one built
  // without a cache, ==. The walk is kept per step (an eighth of a cell up to 20 um): the
  // 0.1 mm cells walk anew.
  const Groove groove;
  const WheelRailGeometry g(groove.wheel, groove.rail, Groove::Pose());
  const auto cands = g.FindCandidates(2e-5);
  ASSERT_EQ(cands.size(), 1u);
  LateralWalkCache cache;
  struct Case {
    double cell_m, threshold_m;
    GeometryModel geometry;
    bool size_limited;
  };
  const Case cases[] = {{2e-4, 2e-5, GeometryModel::kConformal, false},
                        {4e-4, 1e-5, GeometryModel::kConformal, false},
                        {3e-4, 8e-5, GeometryModel::kConformal, false},
                        {2e-4, 8e-5, GeometryModel::kPlanar, false},
                        {5e-4, 2e-3, GeometryModel::kConformal, false},
                        {2e-4, 4e-5, GeometryModel::kConformal, true},
                        {1e-4, 2e-5, GeometryModel::kConformal, false},
                        {1e-4, 2e-5, GeometryModel::kConformal, false}};
  for (const Case& k : cases) {
    SCOPED_TRACE(::testing::Message() << k.cell_m << " m cells, threshold " << k.threshold_m);
    PatchGridOptions o = Groove::Options();
    o.cell_dx_m = o.cell_ds_m = k.cell_m;
    o.threshold_m = k.threshold_m;
    o.geometry = k.geometry;
    if (k.size_limited) o.size_accepted = [](const PatchGrid& sized) { return sized.ns <= 12; };
    const PatchBuild fresh = BuildPatchGrid(g, cands[0], o);
    o.walks = &cache;
    const PatchBuild kept = BuildPatchGrid(g, cands[0], o);
    ExpectSameBuild(kept, fresh);
  }
  // Two walks (the 20 um step and the 0.1 mm cells' 12.5 um), the others reused.
  EXPECT_EQ(cache.walks.size(), 2u);
  EXPECT_EQ(cache.reused, 6);
  // The far threshold walked up to the profile's end.
  EXPECT_TRUE(cache.walks[0].lo.ended || cache.walks[0].hi.ended);
  // Another geometry object empties the cache first.
  const WheelRailGeometry other(groove.wheel, groove.rail, Groove::Pose());
  PatchGridOptions o = Groove::Options();
  o.walks = &cache;
  ExpectSameBuild(BuildPatchGrid(other, cands[0], o),
                  BuildPatchGrid(g, cands[0], Groove::Options()));
  EXPECT_EQ(cache.walks.size(), 1u);
  EXPECT_EQ(cache.geometry, &other);
}

TEST(PatchBuilder, PlanarGapIsQuadraticNearFirstContact) {
  // Laterally flat wheel of radius r0 on a 300 mm crown: along the plane normal the gap is
  // x^2/(2 r0) + s^2/(2 R) + higher order terms (relative size ~ s^2/R^2 ~ 1e-4 here).
  const double R = 0.3, r0 = 0.46;
  const Profile rail = testing::ArcProfile(R, +1.0, 0.15);
  const Profile wheel = testing::FunctionProfile([](double) { return 0.0; }, -0.05, 0.05, 201);
  WheelPose pose;
  pose.rolling_radius_m = r0;
  const WheelRailGeometry g(wheel, rail, pose);
  const auto cands = g.FindCandidates(1e-4);
  ASSERT_EQ(cands.size(), 1u);
  PatchGridOptions o;
  o.geometry = GeometryModel::kPlanar;
  o.cell_dx_m = 5e-4;
  o.cell_ds_m = 5e-4;
  o.threshold_m = 1e-4;
  const PatchBuild b = BuildPatchGrid(g, cands[0], o);
  ASSERT_TRUE(b.valid);
  const PatchGrid& grid = b.grid;
  EXPECT_TRUE(grid.planar);
  for (int j = 0; j < grid.ns; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const double x = grid.X(i), s = grid.S(j);
      const double quad = x * x / (2 * r0) + s * s / (2 * R);
      EXPECT_NEAR(grid.gap_m[grid.Index(i, j)], quad, 2e-3 * quad + 1e-11) << i << " " << j;
    }
  }
  // Potential area: |s| up to sqrt(2 R T), |x| up to sqrt(2 r0 T).
  EXPECT_NEAR(grid.S(grid.ns - 1), std::sqrt(2 * R * 1e-4), 1.5 * o.cell_ds_m);
  EXPECT_NEAR(grid.X(grid.nx - 1), std::sqrt(2 * r0 * 1e-4), 1.0 * o.cell_dx_m);
}

TEST(PatchBuilder, TheWalksNarrowWindowFindsTheWideWindowsCrossings) {
  // S1002 on UIC60 canted 1:40 from the tread (-10.4 mm) over the flange root (api_bench's
  // -5.6 mm) to the gauge corner (-3 mm), conformal grids of 0.16 mm cells (20 um walk steps) at
  // a threshold of 0.1 mm: every section of every walk (LateralWalkCache keeps them) is the
  // crossing the former 1.5 mm window's scan found from the previous section's. Since the walk
  // starts Newton's iteration from the sections before without the scan
  // (CurveLocator::IntersectLineFrom), the same crossing within the refinements' tolerance: both
  // end within kParameterTolerance_m of the same root, so s and lambda (|C'| ~ 1) within twice
  // that; it was bit for bit with the scan.
  const Profile wheel = MakeS1002();
  const Profile rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  constexpr double kFormerWindow_m = 50 * 2e-5 + 5e-4;
  constexpr double kSame = 2 * CurveLocator::kParameterTolerance_m;
  int sections = 0;
  for (double shift_mm = -10.4; shift_mm <= -2.95; shift_mm += 0.2) {
    WheelPose pose;
    pose.lateral_shift_m = shift_mm * 1e-3;
    pose.roll_rad = 1e-3;
    const WheelRailGeometry g(wheel, rail, pose);
    SCOPED_TRACE(::testing::Message() << shift_mm << " mm");
    PatchGridOptions o;
    o.geometry = GeometryModel::kConformal;
    o.cell_dx_m = o.cell_ds_m = 1.6e-4;
    o.threshold_m = 1e-4;
    LateralWalkCache cache;
    o.walks = &cache;
    for (const ContactCandidate& c : g.FindCandidates(o.threshold_m)) {
      BuildPatchGrid(g, c, o);
    }
    for (const LateralWalkCache::Walked& walk : cache.walks) {
      ASSERT_TRUE(walk.centre_found);
      const Eigen::Vector2d n0 = walk.normal.normalized();
      const Eigen::Vector2d t0(-n0.y(), n0.x());
      for (const LateralWalkCache::Side* side : {&walk.lo, &walk.hi}) {
        LateralWalkCache::Section prev = walk.centre;
        for (const LateralWalkCache::Section& s : side->sections) {
          const Eigen::Vector2d b = walk.rail_point_m + s.tau * t0;
          auto r = g.rail().IntersectLine(b, n0, prev.rail_s - kFormerWindow_m,
                                          prev.rail_s + kFormerWindow_m);
          if (!r) r = g.rail().IntersectLine(b, n0, 0.0, 1.0);
          const Eigen::Vector2d b_w = g.RailToWheel(b), n_w = g.RailDirectionToWheel(n0);
          auto w = g.wheel().IntersectLine(b_w, n_w, prev.wheel_s - kFormerWindow_m,
                                           prev.wheel_s + kFormerWindow_m);
          if (!w) w = g.wheel().IntersectLine(b_w, n_w, 0.0, 1.0);
          ASSERT_TRUE(r && w) << s.tau;
          ASSERT_NEAR(r->s, s.rail_s, kSame) << s.tau;
          ASSERT_NEAR(r->lambda, s.lambda_r, kSame) << s.tau;
          ASSERT_NEAR(w->s, s.wheel_s, kSame) << s.tau;
          ASSERT_NEAR(w->lambda, s.lambda_w, kSame) << s.tau;
          prev = s;
          ++sections;
        }
      }
    }
  }
  EXPECT_GT(sections, 10000);
}

TEST(PatchBuilder, GapsMirroredWithoutYawAreEachCellsOwnProjections) {
  // Without yaw the wheel is a surface of revolution and FillConformalGaps gives the columns
  // left of the contact the gaps of their mirror images. Every cell's gap, mirrored or not, is
  // checked against its own projections onto the rail and the wheel searched over the whole
  // profiles: the same to far below a cell's gap change across a column (dx x / r0, some 1e-7 m
  // at 0.16 mm cells), within the projections' tolerance. With 5 mrad of yaw no column is
  // mirrored, and the same check holds.
  const Profile wheel = MakeS1002();
  const Profile rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  constexpr double kOwnProjection_m = 1e-12;
  int mirrored_grids = 0, cells = 0;
  for (const double yaw_rad : {0.0, 5e-3}) {
    for (const double shift_mm : {-10.4, -5.6, -4.0, -3.0}) {
      WheelPose pose;
      pose.lateral_shift_m = shift_mm * 1e-3;
      pose.roll_rad = 1e-3;
      pose.yaw_rad = yaw_rad;
      const WheelRailGeometry g(wheel, rail, pose);
      SCOPED_TRACE(::testing::Message() << shift_mm << " mm, yaw " << yaw_rad);
      PatchGridOptions o;
      o.geometry = GeometryModel::kConformal;
      o.cell_dx_m = o.cell_ds_m = 1.6e-4;
      o.threshold_m = 1e-4;
      for (const ContactCandidate& c : g.FindCandidates(o.threshold_m)) {
        const PatchBuild b = BuildPatchGrid(g, c, o);
        if (!b.valid || b.grid.planar) continue;
        const PatchGrid& grid = b.grid;
        const int ic = (grid.nx - 1) / 2;
        bool mirror_image = true;
        for (int j = 0; j < grid.ns; ++j) {
          const Eigen::Vector2d p = grid.point_yz_m[j];
          const double rail_d = g.ProjectOnRail(p, 0.0, 1.0).signed_distance;
          for (int i = 0; i < grid.nx; ++i) {
            const double own =
                rail_d + g.ProjectOnWheel({grid.X(i), p.x(), p.y()}, 0.0, 1.0).signed_distance;
            ASSERT_NEAR(grid.gap_m[grid.Index(i, j)], own, kOwnProjection_m) << i << ", " << j;
            mirror_image = mirror_image && (i >= ic || grid.gap_m[grid.Index(i, j)] ==
                                                           grid.gap_m[grid.Index(2 * ic - i, j)]);
            ++cells;
          }
        }
        if (yaw_rad == 0.0) {
          EXPECT_TRUE(mirror_image);
          ++mirrored_grids;
        } else {
          EXPECT_FALSE(mirror_image);
        }
      }
    }
  }
  EXPECT_GT(mirrored_grids, 3);
  EXPECT_GT(cells, 5000);
}

}  // namespace
}  // namespace railwear
