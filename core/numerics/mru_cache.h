// MruCache: a bounded, thread-safe, process-wide cache of immutable shared values, the most
// recently used first (issue 18, set-up reuse). Behind ProfileKeyedCache
// (core/profile/profile_keyed_cache.h) and the shared FFTW plans (core/numerics/fftw.h).
//
// Lookups and insertions run under the cache's mutex; values are built outside it (two threads
// missing the same key at once both build it, and the first one kept is shared from then on).
// Values are std::shared_ptr<const Value>, so an evicted value lives on with its last user; the
// cache's own reference to it is released after the mutex is let go (an FFTW plan's destructor
// takes the planner's mutex).
#pragma once

#include <deque>
#include <memory>
#include <mutex>
#include <utility>

namespace railwear {

template <class Key, class Value>
class MruCache {
 public:
  explicit MruCache(size_t capacity) : capacity_(capacity) {}

  // The kept value whose key satisfies same(key) (a hit makes it the most recently used); else
  // make()'s, kept under make_key() as the most recently used. make_key() is called only to
  // keep a new value, so a hit copies no key.
  template <class Same, class MakeKey, class Make>
  std::shared_ptr<const Value> Get(Same&& same, MakeKey&& make_key, Make&& make) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (!same(it->key)) continue;
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
    std::shared_ptr<const Value> evicted;  // released after the lock below
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_) {
      if (same(e.key)) return e.value;  // another thread kept the same value meanwhile
    }
    entries_.push_front(Entry{make_key(), value});
    if (entries_.size() > capacity_) {
      evicted = std::move(entries_.back().value);
      entries_.pop_back();
    }
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
    Key key;
    std::shared_ptr<const Value> value;
  };
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<Entry> entries_;  // most recently used first
  long hits_ = 0, misses_ = 0;
};

}  // namespace railwear
