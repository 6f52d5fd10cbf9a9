// PooledBuffer: a buffer of doubles whose memory is recycled on its thread (issue 20, the cold
// gauge-corner call). A curved influence operator (core/contact/influence_operator.cpp) holds
// three matrices of some 0.7 MB each at the standard preset's gauge-corner grids, and a cold
// call builds four operators: freshly allocated, every page of them was first touched (a page
// fault and the kernel's zeroing) on every call, which `perf` put at a fifth of the call's CPU
// time on the benchmark machine (docs/library.md, "The cold call's fresh memory"). A buffer
// released here keeps its memory in a small per-thread pool instead, and the next buffer of at
// most its size on that thread takes it over: the memory stays mapped.
//
// The pool is memory only: a buffer's contents are unspecified when it is handed out (as
// new double[n]'s are), so nothing computed depends on the pool. Each thread has its own pool
// (thread_local: no locking, no sharing between threads); a buffer released on another thread
// than the one it was taken on goes to the releasing thread's pool. A pool keeps at most
// kMaxPooledBuffers buffers and kMaxPooledBytes bytes; larger buffers and the excess are freed
// as usual. The memory a thread's pool keeps is freed when the thread ends.
#pragma once

#include <cstddef>
#include <memory>

namespace railwear {

class PooledBuffer {
 public:
  // Buffers a thread's pool keeps at most, and their bytes in all (a buffer larger than this is
  // never pooled): the four operators of a cold standard gauge-corner call take some 9 MB.
  static constexpr size_t kMaxPooledBuffers = 16;
  static constexpr size_t kMaxPooledBytes = size_t{64} << 20;

  PooledBuffer() = default;
  // n doubles (contents unspecified), from this thread's pool when it holds a buffer of at
  // least n doubles (the smallest such), else newly allocated.
  explicit PooledBuffer(size_t n);
  ~PooledBuffer() { Release(); }
  PooledBuffer(PooledBuffer&& other) noexcept;
  PooledBuffer& operator=(PooledBuffer&& other) noexcept;
  PooledBuffer(const PooledBuffer&) = delete;
  PooledBuffer& operator=(const PooledBuffer&) = delete;

  double* data() { return data_.get(); }
  const double* data() const { return data_.get(); }
  size_t size() const { return size_; }
  // The doubles the memory holds (>= size(), from a larger pooled buffer).
  size_t capacity() const { return capacity_; }

  // Buffers and bytes in this thread's pool now (for tests).
  static size_t PooledCount();
  static size_t PooledBytes();

 private:
  // Gives the memory back to this thread's pool (or frees it); the buffer is then empty.
  void Release() noexcept;

  std::unique_ptr<double[]> data_;
  size_t size_ = 0, capacity_ = 0;
};

}  // namespace railwear
