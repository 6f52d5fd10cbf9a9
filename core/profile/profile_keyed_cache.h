// ProfileKeyedCache: values that are pure functions of a profile's points (and a few exact
// numbers), shared process-wide by everything that would build them again (issue 18, set-up
// reuse): the samples of a CurveLocator (core/geometry/curve_locator.h) and the yawed wheel
// outlines (core/geometry/wheel_rail_geometry.cpp). A Profile is a function of its points, so
// a value built for a profile whose points are the same byte for byte, with the same extra key
// (the bits of the doubles that select it: a sampling step, a rolling radius, a yaw) and text
// (a source name the value carries), is the value a new build would make: a hit changes no
// result, not even in the last bit.
//
// Bounded: the `capacity` most recently used values are kept (callers size it by their values'
// memory). Thread-safe and shared as core/numerics/mru_cache.h says (two threads missing the
// same key at once both build it; both are the same bit for bit).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/numerics/mru_cache.h"
#include "core/profile/profile.h"

namespace railwear {

// The bits of a double, for the exact extra keys of ProfileKeyedCache.
inline std::uint64_t DoubleBits(double v) { return std::bit_cast<std::uint64_t>(v); }

template <class Value>
class ProfileKeyedCache {
 public:
  explicit ProfileKeyedCache(size_t capacity) : cache_(capacity) {}

  // The value for (profile's points, extra, text): the kept one on a hit, else make()'s
  // (a std::shared_ptr<const Value>), which is kept as the most recently used.
  template <class Make>
  std::shared_ptr<const Value> Get(const Profile& profile, std::initializer_list<std::uint64_t> extra,
                                   const std::string& text, Make&& make) {
    const std::vector<Eigen::Vector2d>& points = profile.points();
    auto same = [&](const Key& k) {
      return k.points.size() == points.size() && k.extra.size() == extra.size() &&
             std::equal(extra.begin(), extra.end(), k.extra.begin()) && k.text == text &&
             (points.empty() ||
              std::memcmp(k.points.data(), points.data(), points.size() * sizeof(points[0])) == 0);
    };
    return cache_.Get(same, [&] { return Key{points, std::vector<std::uint64_t>(extra), text}; },
                      std::forward<Make>(make));
  }

  // Calls that found a kept value / that built one (for tests).
  long hits() const { return cache_.hits(); }
  long misses() const { return cache_.misses(); }
  size_t size() const { return cache_.size(); }
  size_t capacity() const { return cache_.capacity(); }

 private:
  struct Key {
    std::vector<Eigen::Vector2d> points;
    std::vector<std::uint64_t> extra;
    std::string text;
  };
  MruCache<Key, Value> cache_;
};

}  // namespace railwear
