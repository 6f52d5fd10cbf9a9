// Tests of profile_keyed_cache.h: exact keys (points byte for byte, extra bits, text), the
// most-recently-used bound, and concurrent lookups.
#include "core/profile/profile_keyed_cache.h"

#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace railwear {
namespace {

Profile Line(double slope, int n = 8) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(1e-3 * i, slope * 1e-3 * i);
  return Profile(std::move(pts), "line");
}

TEST(ProfileKeyedCache, HitsOnlyForTheSamePointsExtraAndText) {
  ProfileKeyedCache<int> cache(8);
  int built = 0;
  auto make = [&] { return std::make_shared<const int>(++built); };
  const Profile a = Line(0.1);
  const auto first = cache.Get(a, {DoubleBits(2e-5)}, "", make);
  EXPECT_EQ(*first, 1);
  // The same points in another object (another source name): a hit, the same value.
  EXPECT_EQ(cache.Get(Profile(a.points(), "copy"), {DoubleBits(2e-5)}, "", make), first);
  EXPECT_EQ(cache.hits(), 1);
  // One ulp in one coordinate, in the extra key, another text, another extra count: misses.
  std::vector<Eigen::Vector2d> moved = a.points();
  moved[3].x() = std::nextafter(moved[3].x(), 1.0);
  EXPECT_NE(cache.Get(Profile(moved), {DoubleBits(2e-5)}, "", make), first);
  EXPECT_NE(cache.Get(a, {DoubleBits(std::nextafter(2e-5, 1.0))}, "", make), first);
  EXPECT_NE(cache.Get(a, {DoubleBits(2e-5)}, "other", make), first);
  EXPECT_NE(cache.Get(a, {DoubleBits(2e-5), 0u}, "", make), first);
  EXPECT_EQ(cache.Get(a, {DoubleBits(-0.0)}, "", make), cache.Get(a, {DoubleBits(-0.0)}, "", make));
  EXPECT_NE(cache.Get(a, {DoubleBits(0.0)}, "", make), cache.Get(a, {DoubleBits(-0.0)}, "", make));
  EXPECT_EQ(cache.misses(), 7);
  EXPECT_EQ(built, 7);
}

TEST(ProfileKeyedCache, KeepsTheMostRecentlyUsedWithinItsCapacity) {
  ProfileKeyedCache<double> cache(3);
  auto value = [](double v) { return [v] { return std::make_shared<const double>(v); }; };
  std::vector<Profile> p;
  for (int k = 0; k < 5; ++k) p.push_back(Line(0.1 * (k + 1)));
  const auto v0 = cache.Get(p[0], {}, "", value(0));
  cache.Get(p[1], {}, "", value(1));
  cache.Get(p[2], {}, "", value(2));
  EXPECT_EQ(cache.Get(p[0], {}, "", value(-1)), v0);  // p[0] used again: most recent
  cache.Get(p[3], {}, "", value(3));                  // evicts p[1], the least recent
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(*cache.Get(p[0], {}, "", value(-1)), 0.0);
  EXPECT_EQ(*cache.Get(p[1], {}, "", value(11)), 11.0);  // built again
  EXPECT_EQ(cache.size(), 3u);
  // An evicted value lives on with its user.
  EXPECT_EQ(*v0, 0.0);
}

TEST(ProfileKeyedCache, ConcurrentLookupsShareOneValuePerKey) {
  ProfileKeyedCache<int> cache(4);
  std::vector<Profile> p;
  for (int k = 0; k < 6; ++k) p.push_back(Line(0.2 * (k + 1), 50));
  std::atomic<int> built{0};
  constexpr int kThreads = 4, kRounds = 300;
  std::vector<std::vector<int>> got(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int r = 0; r < kRounds; ++r) {
        const int k = (r * 7 + t) % 6;
        const auto v = cache.Get(p[k], {static_cast<std::uint64_t>(k)}, "", [&] {
          ++built;
          return std::make_shared<const int>(100 + k);
        });
        got[t].push_back(*v - 100 - k);  // the value of its own key
      }
    });
  }
  for (auto& th : threads) th.join();
  for (const auto& g : got) {
    for (int d : g) ASSERT_EQ(d, 0);
  }
  EXPECT_LE(cache.size(), 4u);
  EXPECT_EQ(cache.hits() + cache.misses(), kThreads * kRounds);
  EXPECT_EQ(cache.misses(), built.load());
}

}  // namespace
}  // namespace railwear
