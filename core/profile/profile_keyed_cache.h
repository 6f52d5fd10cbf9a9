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
// memory). Thread-safe: lookups and insertions run under the cache's mutex; values are built
// outside it (two threads missing the same key at once both build it, and the first one kept
// is shared from then on; both are the same bit for bit). Values are immutable and shared
// (std::shared_ptr<const Value>), so an evicted value lives on with its last user.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <deque>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/profile/profile.h"

namespace railwear {

// The bits of a double, for the exact extra keys of ProfileKeyedCache.
inline std::uint64_t DoubleBits(double v) { return std::bit_cast<std::uint64_t>(v); }

template <class Value>
class ProfileKeyedCache {
 public:
  explicit ProfileKeyedCache(size_t capacity) : capacity_(capacity) {}

  // The value for (profile's points, extra, text): the kept one on a hit, else make()'s
  // (a std::shared_ptr<const Value>), which is kept as the most recently used.
  template <class Make>
  std::shared_ptr<const Value> Get(const Profile& profile, std::initializer_list<std::uint64_t> extra,
                                   const std::string& text, Make&& make) {
    const std::vector<Eigen::Vector2d>& points = profile.points();
    auto same = [&](const Entry& e) {
      return e.points.size() == points.size() && e.extra.size() == extra.size() &&
             std::equal(extra.begin(), extra.end(), e.extra.begin()) && e.text == text &&
             (points.empty() ||
              std::memcmp(e.points.data(), points.data(), points.size() * sizeof(points[0])) == 0);
    };
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (!same(*it)) continue;
        ++hits_;
        if (it != entries_.begin()) {
          Entry hit = std::move(*it);
          entries_.erase(it);
          entries_.push_front(std::move(hit));
        }
        return entries_.front().value;
      }
      ++misses_;
    }
    std::shared_ptr<const Value> value = make();
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_) {
      if (same(e)) return e.value;  // another thread kept the same value meanwhile
    }
    entries_.push_front(Entry{points, std::vector<std::uint64_t>(extra), text, value});
    if (entries_.size() > capacity_) entries_.pop_back();
    return value;
  }

  // Calls that found a kept value / that built one (for tests).
  long hits() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return hits_;
  }
  long misses() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return misses_;
  }
  size_t size() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return entries_.size();
  }
  size_t capacity() const { return capacity_; }

 private:
  struct Entry {
    std::vector<Eigen::Vector2d> points;
    std::vector<std::uint64_t> extra;
    std::string text;
    std::shared_ptr<const Value> value;
  };
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<Entry> entries_;  // most recently used first
  long hits_ = 0, misses_ = 0;
};

}  // namespace railwear
