// PooledBuffer's per-thread pool (pooled_buffer.h).
#include "core/numerics/pooled_buffer.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace railwear {

namespace {

struct Pooled {
  std::unique_ptr<double[]> data;
  size_t capacity;
};

// This thread's free buffers and their bytes.
struct Pool {
  std::vector<Pooled> free;
  size_t bytes = 0;
};

// This thread's pool, or null once the thread's thread_local objects are being destroyed (a
// buffer released then, by another thread_local's destructor, is freed as usual).
thread_local Pool* t_pool = nullptr;  // (trivially destructible: valid to the thread's end)
thread_local bool t_pool_gone = false;

struct PoolOwner {
  ~PoolOwner() {
    delete t_pool;
    t_pool = nullptr;
    t_pool_gone = true;
  }
};

Pool* ThreadPool() {
  if (t_pool_gone) return nullptr;
  thread_local PoolOwner owner;  // (its destructor runs at the thread's end)
  if (!t_pool) t_pool = new Pool;
  return t_pool;
}

}  // namespace

PooledBuffer::PooledBuffer(size_t n) : size_(n) {
  if (n == 0) return;
  if (Pool* pool = ThreadPool()) {
    auto best = pool->free.end();
    for (auto it = pool->free.begin(); it != pool->free.end(); ++it) {
      if (it->capacity >= n && (best == pool->free.end() || it->capacity < best->capacity)) {
        best = it;
      }
    }
    if (best != pool->free.end()) {
      data_ = std::move(best->data);
      capacity_ = best->capacity;
      pool->bytes -= capacity_ * sizeof(double);
      pool->free.erase(best);
      return;
    }
  }
  data_.reset(new double[n]);  // (default-initialised: not zeroed)
  capacity_ = n;
}

PooledBuffer::PooledBuffer(PooledBuffer&& other) noexcept
    : data_(std::move(other.data_)),
      size_(std::exchange(other.size_, 0)),
      capacity_(std::exchange(other.capacity_, 0)) {}

PooledBuffer& PooledBuffer::operator=(PooledBuffer&& other) noexcept {
  if (this != &other) {
    Release();
    data_ = std::move(other.data_);
    size_ = std::exchange(other.size_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
  }
  return *this;
}

void PooledBuffer::Release() noexcept {
  if (!data_) return;
  const size_t bytes = capacity_ * sizeof(double);
  size_ = capacity_ = 0;
  Pool* pool_ptr = bytes <= kMaxPooledBytes ? ThreadPool() : nullptr;
  if (!pool_ptr) {
    data_.reset();
    return;
  }
  Pool& pool = *pool_ptr;
  try {
    // Make room: the smallest buffers go first (the large ones are those whose pages cost).
    while (!pool.free.empty() &&
           (pool.free.size() >= kMaxPooledBuffers || pool.bytes + bytes > kMaxPooledBytes)) {
      auto smallest = std::min_element(
          pool.free.begin(), pool.free.end(),
          [](const Pooled& a, const Pooled& b) { return a.capacity < b.capacity; });
      pool.bytes -= smallest->capacity * sizeof(double);
      pool.free.erase(smallest);
    }
    pool.free.push_back({std::move(data_), bytes / sizeof(double)});
    pool.bytes += bytes;
  } catch (...) {  // out of memory for the pool's list: free the buffer instead
    data_.reset();
  }
}

size_t PooledBuffer::PooledCount() {
  const Pool* pool = ThreadPool();
  return pool ? pool->free.size() : 0;
}

size_t PooledBuffer::PooledBytes() {
  const Pool* pool = ThreadPool();
  return pool ? pool->bytes : 0;
}

}  // namespace railwear
