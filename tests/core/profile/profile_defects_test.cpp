// Profile defects (core/profile/profile_defects.h): a self-crossing profile is refused with both
// segments named (by point and coordinates in Profile, by file line in the readers), touches
// count, and the y-sweep finds the same first crossing as the naive all-pairs test.
#include "core/profile/profile_defects.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "tests/test_support.h"

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "core/profile/profile.h"
#include "core/profile/profile_io.h"

namespace railwear {
namespace {

// A rail-like polyline (mm) with a loop: points 5-8 (1-based) go right, up, back left and down
// again, so the segment from point 6 to 7 crosses the one from point 4 to 5 at y = 1.887 mm,
// with every turn below 150 degrees (123, 128 and 105 degrees at the loop).
std::vector<Eigen::Vector2d> LoopMm() {
  return {{-30, 5}, {-20, 2}, {-10, 0.5}, {0, 0},  {10, 0.5},
          {5, -8},  {0, 5},   {10, 6},    {20, 2}, {30, 5}};
}

std::vector<Eigen::Vector2d> Scaled(std::vector<Eigen::Vector2d> p, double factor) {
  for (auto& q : p) q *= factor;
  return p;
}

// The naive reference: every pair of non-adjacent segments, lowest first segment first.
std::optional<std::pair<int, int>> NaiveFirstCrossing(const std::vector<Eigen::Vector2d>& p) {
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  const int m = static_cast<int>(p.size()) - 1;
  for (int a = 0; a < m; ++a) {
    for (int b = a + 2; b < m; ++b) {
      const Eigen::Vector2d d = p[a + 1] - p[a], e = p[b + 1] - p[b];
      const double den = cross(d, e);
      if (den == 0.0) continue;  // parallel: random points never are
      const double t = cross(p[b] - p[a], e) / den, u = cross(p[b] - p[a], d) / den;
      if (t >= 0 && t <= 1 && u >= 0 && u <= 1) return std::make_pair(a, b);
    }
  }
  return std::nullopt;
}

TEST(ProfileDefects, FindsTheLoopsCrossing) {
  const auto defect = FindProfileDefect(Scaled(LoopMm(), 1e-3));
  ASSERT_TRUE(defect.has_value());
  EXPECT_EQ(defect->kind, ProfileDefect::Kind::kCrossing);
  EXPECT_EQ(defect->a, 3);
  EXPECT_EQ(defect->b, 5);
  // Segment (5, -8) -> (0, 5) meets z = 0.05 y at t = 8.25 / 13.25.
  const double t = 8.25 / 13.25;
  EXPECT_NEAR(defect->crossing.x(), (5 - 5 * t) * 1e-3, 1e-12);
  EXPECT_NEAR(defect->crossing.y(), (-8 + 13 * t) * 1e-3, 1e-12);
}

TEST(ProfileDefects, ProfileNamesBothSegmentsWithCoordinates) {
  const std::string m =
      test::InputErrorMessage([] { Profile(Scaled(LoopMm(), 1e-3), "loop.csv"); });
  EXPECT_NE(m.find("loop.csv: the profile crosses itself"), std::string::npos) << m;
  EXPECT_NE(m.find("from point 4 (y = 0.000000, z = 0.000000 mm) to point 5 (y = 10.000000, "
                   "z = 0.500000 mm)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("from point 6 (y = 5.000000, z = -8.000000 mm) to point 7 (y = 0.000000, "
                   "z = 5.000000 mm)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("at (y = 1.886792, z = 0.094340 mm)"), std::string::npos) << m;
}

TEST(ProfileDefects, ReaderNamesTheFileLines) {
  const auto path = std::filesystem::temp_directory_path() / "railwear_loop_test.csv";
  {
    std::ofstream out(path);
    out << "y_mm,z_mm\n";
    for (const auto& p : LoopMm()) out << p.x() << "," << p.y() << "\n";
  }
  const std::string m = test::InputErrorMessage([&] { ReadProfileFile(path.string()); });
  std::filesystem::remove(path);
  EXPECT_NE(m.find("railwear_loop_test.csv:7: the profile crosses itself: the segment from line "
                   "5 (y = 0.000000, z = 0.000000 mm) to line 6"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("crosses the segment from line 7 (y = 5.000000, z = -8.000000 mm) to line 8"),
            std::string::npos)
      << m;
}

TEST(ProfileDefects, ATouchCountsAsACrossing) {
  // Point 7 lands exactly on the segment from point 4 to point 5 (z = 0.05 y at y = 4).
  std::vector<Eigen::Vector2d> p = LoopMm();
  p[6] = {4, 0.2};
  const auto defect = FindProfileDefect(p, 1e3);
  ASSERT_TRUE(defect.has_value());
  EXPECT_EQ(defect->kind, ProfileDefect::Kind::kCrossing);
  EXPECT_EQ(defect->a, 3);
  EXPECT_EQ(defect->b, 5);
  EXPECT_NEAR(defect->crossing.x(), 4.0, 1e-12);
}

TEST(ProfileDefects, DuplicatesAndTurnBacksComeFirst) {
  std::vector<Eigen::Vector2d> p = LoopMm();
  p[8] = p[7];  // a duplicate after the loop
  auto defect = FindProfileDefect(p, 1e3);
  ASSERT_TRUE(defect.has_value());
  EXPECT_EQ(defect->kind, ProfileDefect::Kind::kDuplicate);
  EXPECT_EQ(defect->b, 8);
  p = LoopMm();
  p[8] = {0, 6.2};  // back along the previous segment: a 170-degree turn at point 8 (0-based 7)
  defect = FindProfileDefect(p, 1e3);
  ASSERT_TRUE(defect.has_value());
  EXPECT_EQ(defect->kind, ProfileDefect::Kind::kTurnBack);
  EXPECT_EQ(defect->a, 7);
  EXPECT_GT(defect->turn_rad, Profile::kMaxTurnAngle_rad);
}

TEST(ProfileDefects, BuiltinProfilesAndTheirTransformsAreClean) {
  for (const Profile& p : {MakeS1002(), MakeUic60()}) {
    EXPECT_FALSE(FindProfileDefect(p.points()).has_value()) << p.source();
    const Profile moved = p.Mirrored().Transformed(0.025, {1e-3, -2e-3});  // no throw
    EXPECT_FALSE(FindProfileDefect(moved.points()).has_value()) << p.source();
  }
}

TEST(ProfileDefects, SweepAgreesWithTheNaiveTestOnRandomWalks) {
  // Random walks of 60 steps, mostly forward in y with vertical swings: some cross themselves,
  // some do not (both kinds are asserted to occur).
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> dy(-0.3, 1.0), dz(-0.6, 0.6);
  int crossing = 0, clean = 0;
  for (int walk = 0; walk < 300; ++walk) {
    std::vector<Eigen::Vector2d> p{{0.0, 0.0}};
    for (int i = 0; i < 60; ++i) p.push_back(p.back() + Eigen::Vector2d(dy(rng), dz(rng)));
    const auto naive = NaiveFirstCrossing(p);
    const auto sweep = FindSelfIntersection(p);
    ASSERT_EQ(naive.has_value(), sweep.has_value()) << "walk " << walk;
    if (naive) {
      EXPECT_EQ(sweep->a, naive->first) << "walk " << walk;
      EXPECT_EQ(sweep->b, naive->second) << "walk " << walk;
      ++crossing;
    } else {
      ++clean;
    }
  }
  EXPECT_GT(crossing, 10);
  EXPECT_GT(clean, 10);
}

}  // namespace
}  // namespace railwear
