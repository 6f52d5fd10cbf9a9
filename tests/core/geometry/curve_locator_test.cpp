#include "core/geometry/curve_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/profile/builtin_profiles.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

// Spline of 801 points on a 10 mm arc: position error of the C2 spline ~1e-12 m; projections
// converge to the spline, so distances agree with the exact circle to this level.
constexpr double kSplineTolerance_m = 1e-10;

TEST(CurveLocator, ProjectsOntoCircleWithSignedDistance) {
  const double R = 0.01;
  const Profile crown = testing::ArcProfile(R, +1.0);  // rail crown, centre at (0, R)
  const CurveLocator rail(crown, /*material_toward_plus_z=*/true);
  const Eigen::Vector2d centre(0.0, R);
  for (double angle : {-0.9, -0.3, 0.0, 0.4, 1.0}) {
    const Eigen::Vector2d dir(std::sin(angle), -std::cos(angle));
    for (double d : {-2e-3, -1e-5, 1e-6, 3e-3}) {
      const Eigen::Vector2d q = centre + (R + d) * dir;
      const auto p = rail.Project(q);
      EXPECT_NEAR(p.signed_distance, d, kSplineTolerance_m) << angle << " " << d;
      EXPECT_NEAR((p.point - (centre + R * dir)).norm(), 0.0, 1e-9);
      // Outward normal points away from the material (up, along dir).
      EXPECT_GT(rail.OutwardNormal(p.s).dot(dir), 0.999);
    }
  }
}

TEST(CurveLocator, WheelOrientationAndMirroredOrder) {
  // A convex wheel (material above) gives positive distance below its surface, whatever the
  // order of its points.
  const double R = 0.01;
  const Profile wheel = testing::ArcProfile(R, -1.0);
  const Profile reversed = wheel.Mirrored();  // same circle, points in the other order
  for (const Profile* p : {&wheel, &reversed}) {
    const CurveLocator loc(*p, /*material_toward_plus_z=*/false);
    EXPECT_NEAR(loc.Project({0.0, 1e-4}).signed_distance, 1e-4, kSplineTolerance_m);
    EXPECT_NEAR(loc.Project({0.0, -1e-4}).signed_distance, -1e-4, kSplineTolerance_m);
    EXPECT_GT(loc.OutwardNormal(loc.Project({0.0, 0.0}).s).y(), 0.999);
  }
}

TEST(CurveLocator, IntersectsLine) {
  const double R = 0.3;
  const Profile crown = testing::ArcProfile(R, +1.0, 0.2);
  const CurveLocator rail(crown, true);
  for (double y : {-0.02, 0.0, 0.013}) {
    const auto c = rail.IntersectLine({y, -0.001}, {0.0, 1.0}, 0.0, 1.0);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(-0.001 + c->lambda, R - std::sqrt(R * R - y * y), kSplineTolerance_m);
  }
  EXPECT_FALSE(rail.IntersectLine({1.0, 0.0}, {0.0, 1.0}, 0.0, 1.0).has_value());
}

// Fast path against the naive reference: the block-skipping scan and the sample-by-sample one
// give the same projections and crossings bit for bit (the skipped blocks only hold samples that
// lose their comparisons), on real profiles, near and far from them, over whole profiles and
// windows, on lines in every direction and through the profile's own samples, and for NaN.
TEST(CurveLocator, BlockScanEqualsSampleScanBitForBit) {
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  const Profile rail_profile = MakeUic60();
  const Profile wheel_profile = MakeS1002();
  const Profile arc = testing::ArcProfile(0.01, +1.0);
  struct Case {
    const Profile* profile;
    bool rail;
  };
  std::mt19937 rng(18);
  for (const Case& c : {Case{&rail_profile, true}, Case{&wheel_profile, false}, Case{&arc, true}}) {
    const CurveLocator fast(*c.profile, c.rail);
    const CurveLocator naive(*c.profile, c.rail, 2e-5, CurveLocator::Scan::kEverySample);
    const double length = fast.length();
    std::uniform_real_distribution<double> along(-0.1 * length, 1.1 * length);
    std::uniform_real_distribution<double> offset(-3e-3, 3e-3);
    std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
    std::uniform_real_distribution<double> window(0.0, 0.3 * length);
    int crossings = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      // A point near the profile (at a sample exactly every tenth trial), then far away.
      const double s = std::clamp(along(rng), 0.0, length);
      Eigen::Vector2d q = c.profile->Position(s);
      if (trial % 10 != 0) q += Eigen::Vector2d(offset(rng), offset(rng));
      if (trial % 97 == 0) q *= 20.0;
      const double lo = along(rng), hi = lo + window(rng);
      const bool whole = trial % 3 == 0;
      const auto pf = whole ? fast.Project(q) : fast.Project(q, lo, hi);
      const auto pn = whole ? naive.Project(q) : naive.Project(q, lo, hi);
      ASSERT_EQ(pf.s, pn.s) << trial;
      ASSERT_EQ(pf.signed_distance, pn.signed_distance) << trial;
      const double phi =
          trial % 7 == 0 ? 0.5 * std::numbers::pi : angle(rng);  // vertical lines too
      const Eigen::Vector2d n(std::cos(phi), std::sin(phi));
      const auto xf = fast.IntersectLine(q, n, whole ? 0.0 : lo, whole ? 1.0 : hi);
      const auto xn = naive.IntersectLine(q, n, whole ? 0.0 : lo, whole ? 1.0 : hi);
      ASSERT_EQ(xf.has_value(), xn.has_value()) << trial;
      if (xf) {
        ++crossings;
        ASSERT_EQ(xf->s, xn->s) << trial;
        ASSERT_EQ(xf->lambda, xn->lambda) << trial;
      }
    }
    EXPECT_GT(crossings, 1000);  // the lines do meet the profile
    const Eigen::Vector2d nan_point(kNaN, 0.0);
    EXPECT_EQ(fast.Project(nan_point).s, naive.Project(nan_point).s);
    EXPECT_EQ(fast.IntersectLine(nan_point, {0.0, 1.0}, 0.0, 1.0).has_value(),
              naive.IntersectLine(nan_point, {0.0, 1.0}, 0.0, 1.0).has_value());
  }
}

// Project and IntersectLine end on the refinement's last evaluation where it was at the answer's
// parameter (issue 20's grids): their point, signed distance and lambda are those of the profile
// evaluated afresh there, Position(s) and OutwardNormal(s), bit for bit.
TEST(CurveLocator, AnswersAreTheProfileAtTheirParameterBitForBit) {
  const Profile rail_profile = MakeUic60();
  const Profile wheel_profile = MakeS1002();
  std::mt19937 rng(20);
  for (const bool rail : {true, false}) {
    const Profile& profile = rail ? rail_profile : wheel_profile;
    const CurveLocator loc(profile, rail);
    const double length = loc.length();
    std::uniform_real_distribution<double> along(0.0, length);
    std::uniform_real_distribution<double> offset(-2e-3, 2e-3);
    std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
    int crossings = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      const double s = along(rng);
      Eigen::Vector2d q = profile.Position(s);
      if (trial % 10 != 0) q += Eigen::Vector2d(offset(rng), offset(rng));
      const auto p = trial % 2 ? loc.Project(q) : loc.Project(q, s - 1e-3, s + 1e-3);
      const Eigen::Vector2d point = profile.Position(p.s);
      ASSERT_EQ(p.point.x(), point.x()) << trial;
      ASSERT_EQ(p.point.y(), point.y()) << trial;
      const double dist = (q - point).norm();
      ASSERT_EQ(p.signed_distance, (q - point).dot(loc.OutwardNormal(p.s)) >= 0 ? dist : -dist)
          << trial;
      const double phi = angle(rng);
      const Eigen::Vector2d n(std::cos(phi), std::sin(phi));
      const auto x = loc.IntersectLine(q, n, s - 2e-3, s + 2e-3);
      if (x) {
        ++crossings;
        ASSERT_EQ(x->lambda, (profile.Position(x->s) - q).dot(n)) << trial;
      }
    }
    EXPECT_GT(crossings, 1000);  // the lines do meet the profile
  }
}

// ProjectFrom and IntersectLineFrom (issue 20's grids) against the scans they skip: queries
// marching along the profiles as a grid's cells do (each started from its neighbour's answer,
// extrapolated) end on the same closest point and crossing as Project and IntersectLine, within
// kParameterTolerance_m of the same root each: s within twice it, lambda likewise (|C'| ~ 1),
// and the signed distance within kDistanceRounding (the distance is stationary at the closest
// point: a parameter 2e-12 m off moves it by some 1e-24 m; what is left is the rounding of a
// distance of millimetres, some 1e-19 m). Then points about the centre of a 10 mm arc, where the
// distance has other critical points within the window: the profile's bounds refuse Newton's
// answer there, and the scan's is returned, bit for bit.
TEST(CurveLocator, WarmStartedAnswersAreTheScansWithinTheParameterTolerance) {
  constexpr double kSameS = 2 * CurveLocator::kParameterTolerance_m;
  constexpr double kDistanceRounding = 1e-16;
  const Profile rail_profile = MakeUic60();
  const Profile wheel_profile = MakeS1002();
  std::mt19937 rng(2121);
  int projections = 0, crossings = 0;
  for (const bool rail : {true, false}) {
    const Profile& profile = rail ? rail_profile : wheel_profile;
    const CurveLocator loc(profile, rail);
    const double length = loc.length();
    std::uniform_real_distribution<double> along(0.0, length), offset(-2e-3, 2e-3);
    std::uniform_real_distribution<double> angle(0.0, std::numbers::pi);
    for (int run = 0; run < 60; ++run) {
      // A row of 40 points 0.1 mm apart along a random direction, near the profile.
      const Eigen::Vector2d q0 =
          profile.Position(along(rng)) + Eigen::Vector2d(offset(rng), offset(rng));
      const double heading = angle(rng);
      const Eigen::Vector2d step = 1e-4 * Eigen::Vector2d(std::cos(heading), std::sin(heading));
      const double phi = angle(rng);
      const Eigen::Vector2d n(std::cos(phi), std::sin(phi));
      const double window = 2e-4;
      double s_p = loc.Project(q0).s, s_p_before = s_p;
      auto x0 = loc.IntersectLine(q0, n, 0.0, length);
      if (!x0) continue;
      double s_x = x0->s, s_x_before = s_x;
      for (int i = 1; i < 40; ++i) {
        const Eigen::Vector2d q = q0 + i * step;
        const auto warm = loc.ProjectFrom(q, 2 * s_p - s_p_before, s_p - window, s_p + window);
        const auto scan = loc.Project(q, s_p - window, s_p + window);
        ASSERT_NEAR(warm.s, scan.s, kSameS) << run << " " << i;
        ASSERT_NEAR(warm.signed_distance, scan.signed_distance, kDistanceRounding)
            << run << " " << i;
        s_p_before = s_p;
        s_p = scan.s;
        ++projections;
        const auto xw =
            loc.IntersectLineFrom(q, n, 2 * s_x - s_x_before, s_x - window, s_x + window);
        const auto xs = loc.IntersectLine(q, n, s_x - window, s_x + window);
        ASSERT_EQ(xw.has_value(), xs.has_value()) << run << " " << i;
        if (!xs) break;
        ASSERT_NEAR(xw->s, xs->s, kSameS) << run << " " << i;
        ASSERT_NEAR(xw->lambda, xs->lambda, kSameS) << run << " " << i;
        s_x_before = s_x;
        s_x = xs->s;
        ++crossings;
      }
    }
  }
  EXPECT_GT(projections, 3000);
  EXPECT_GT(crossings, 1000);
  // About the centre of a 10 mm arc (the crown's centre of curvature), started anywhere.
  const double R = 0.01;
  const Profile crown = testing::ArcProfile(R, +1.0);
  const CurveLocator arc(crown, true);
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_real_distribution<double> near_centre(-1e-3, 1e-3), start(0.0, arc.length());
    const Eigen::Vector2d q(near_centre(rng), R + near_centre(rng));
    const double s0 = start(rng);
    const auto warm = arc.ProjectFrom(q, s0, 0.0, arc.length());
    const auto scan = arc.Project(q, 0.0, arc.length());
    ASSERT_EQ(warm.s, scan.s) << trial;
    ASSERT_EQ(warm.signed_distance, scan.signed_distance) << trial;
  }
}

// Answers of a locator to a fixed set of queries near and across the profile, for comparing
// locators bit for bit: projections (s, signed distance) and crossings (s, lambda, or NaN).
std::vector<double> Answers(const CurveLocator& loc, const Profile& profile, int seed) {
  std::mt19937 rng(seed);
  const double length = loc.length();
  std::uniform_real_distribution<double> along(0.0, length);
  std::uniform_real_distribution<double> offset(-2e-3, 2e-3);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::vector<double> out;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector2d q = profile.Position(along(rng)) + Eigen::Vector2d(offset(rng), offset(rng));
    const auto p = loc.Project(q);
    out.push_back(p.s);
    out.push_back(p.signed_distance);
    const double phi = angle(rng);
    const auto x = loc.IntersectLine(q, {std::cos(phi), std::sin(phi)}, 0.0, length);
    out.push_back(x ? x->s : std::numeric_limits<double>::quiet_NaN());
    out.push_back(x ? x->lambda : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

// Bit for bit, NaN equal to NaN.
void ExpectSameAnswers(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i]) && std::isnan(b[i])) continue;
    ASSERT_EQ(a[i], b[i]) << i;
  }
}

// Sets the shared samples of kSharedSampleSets other profiles, so that the next locator on any
// earlier profile samples it anew.
void EvictSharedSamples() {
  for (size_t k = 0; k <= CurveLocator::kSharedSampleSets; ++k) {
    const Profile other = testing::ArcProfile(0.02 + 1e-4 * k, +1.0, 0.5, 101);
    const CurveLocator loc(other, true);
  }
}

// Issue 18: locators on the same points share their samples, and a locator on shared samples
// answers as one that sampled its profile itself.
TEST(CurveLocatorSharedSamples, SameProfilePointsShareAndAnswerBitForBit) {
  const Profile rail = MakeUic60();
  EvictSharedSamples();
  const CurveLocator fresh(rail, true);  // samples the profile itself
  const std::vector<double> reference = Answers(fresh, rail, 3);
  EvictSharedSamples();
  const Profile copy(rail.points(), "another source");  // equal points, another object
  const CurveLocator resampled(copy, true);
  EXPECT_FALSE(resampled.SharesSamplesWith(fresh));  // evicted: sampled again
  const CurveLocator shared(rail, true);
  EXPECT_TRUE(shared.SharesSamplesWith(resampled));  // the source does not matter
  ExpectSameAnswers(Answers(shared, rail, 3), reference);
  ExpectSameAnswers(Answers(resampled, copy, 3), reference);
  // The reference scan shares the samples too, and still answers the same.
  const CurveLocator naive(rail, true, 2e-5, CurveLocator::Scan::kEverySample);
  EXPECT_TRUE(naive.SharesSamplesWith(shared));
  ExpectSameAnswers(Answers(naive, rail, 3), reference);
}

TEST(CurveLocatorSharedSamples, OtherPointsOrientationOrStepDoNotShare) {
  const Profile rail = MakeUic60();
  const CurveLocator base(rail, true);
  // One coordinate of one point moved by one ulp.
  std::vector<Eigen::Vector2d> moved = rail.points();
  moved[moved.size() / 2].y() = std::nextafter(moved[moved.size() / 2].y(), 1.0);
  const Profile nudged(moved, rail.source());
  EXPECT_FALSE(CurveLocator(nudged, true).SharesSamplesWith(base));
  EXPECT_FALSE(CurveLocator(rail, false).SharesSamplesWith(base));  // the wheel's orientation
  EXPECT_FALSE(CurveLocator(rail, true, std::nextafter(2e-5, 1.0)).SharesSamplesWith(base));
  EXPECT_FALSE(CurveLocator(rail, true, 4e-5).SharesSamplesWith(base));
  EXPECT_TRUE(CurveLocator(rail, true).SharesSamplesWith(base));
}

// Locators built and queried in several threads at once (as a wear step's load cases do) on
// profiles shared between the threads and on profiles the others evict: every answer is the
// single-threaded one.
TEST(CurveLocatorSharedSamples, ConcurrentLocatorsAnswerAsSingleThreaded) {
  std::vector<Profile> profiles = {MakeUic60(), MakeS1002(), testing::ArcProfile(0.01, +1.0)};
  for (int k = 0; k < 6; ++k) profiles.push_back(testing::ArcProfile(0.03 + 1e-3 * k, -1.0));
  std::vector<std::vector<double>> reference;
  for (const Profile& p : profiles) reference.push_back(Answers(CurveLocator(p, true), p, 7));
  constexpr int kThreads = 4;
  std::vector<std::vector<std::vector<double>>> got(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 3; ++round) {
        for (size_t k = 0; k < profiles.size(); ++k) {
          const size_t i = (k + t) % profiles.size();
          if (t == kThreads - 1 && round == 1) EvictSharedSamples();
          got[t].push_back(Answers(CurveLocator(profiles[i], true), profiles[i], 7));
        }
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) {
    ASSERT_EQ(got[t].size(), 3 * profiles.size());
    for (size_t j = 0; j < got[t].size(); ++j) {
      ExpectSameAnswers(got[t][j], reference[(j % profiles.size() + t) % profiles.size()]);
    }
  }
}

}  // namespace
}  // namespace railwear
