// Tests of PooledBuffer (core/numerics/pooled_buffer.h): a released buffer's memory is taken over
// by the next buffer of at most its size on the same thread, the smallest that fits; the pool
// keeps within its bounds; each thread has its own pool.
#include "core/numerics/pooled_buffer.h"

#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace railwear {
namespace {

// Each test starts from an empty pool: on a thread of its own (a new thread's pool is empty).
template <class Body>
void OnFreshThread(Body&& body) {
  std::thread thread(std::forward<Body>(body));
  thread.join();
}

TEST(PooledBuffer, ReleasedMemoryIsTakenOverByTheNextBufferThatFits) {
  OnFreshThread([] {
    ASSERT_EQ(PooledBuffer::PooledCount(), 0u);
    const double* small_memory = nullptr;
    const double* large_memory = nullptr;
    {
      PooledBuffer small(1000), large(5000);
      EXPECT_EQ(small.size(), 1000u);
      EXPECT_EQ(large.capacity(), 5000u);
      small.data()[999] = 1.0;  // (the whole size is writable)
      large.data()[4999] = 1.0;
      small_memory = small.data();
      large_memory = large.data();
    }
    EXPECT_EQ(PooledBuffer::PooledCount(), 2u);
    EXPECT_EQ(PooledBuffer::PooledBytes(), 6000u * sizeof(double));
    {
      // 800 doubles fit both: the smaller one is taken.
      PooledBuffer a(800);
      EXPECT_EQ(a.data(), small_memory);
      EXPECT_EQ(a.size(), 800u);
      EXPECT_EQ(a.capacity(), 1000u);
      // 2000 fit only the larger one.
      PooledBuffer b(2000);
      EXPECT_EQ(b.data(), large_memory);
      EXPECT_EQ(PooledBuffer::PooledCount(), 0u);
      // Nothing left that fits: new memory.
      PooledBuffer c(10);
      EXPECT_NE(c.data(), nullptr);
      EXPECT_NE(c.data(), small_memory);
      EXPECT_NE(c.data(), large_memory);
    }
    EXPECT_EQ(PooledBuffer::PooledCount(), 3u);
  });
}

TEST(PooledBuffer, MovedBuffersReleaseOnce) {
  OnFreshThread([] {
    {
      PooledBuffer a(100);
      const double* memory = a.data();
      PooledBuffer b(std::move(a));
      EXPECT_EQ(b.data(), memory);
      EXPECT_EQ(a.data(), nullptr);  // NOLINT(bugprone-use-after-move): the moved-from state
      EXPECT_EQ(a.size(), 0u);
      PooledBuffer c(50);
      c = std::move(b);  // c's own memory goes to the pool
      EXPECT_EQ(c.data(), memory);
      EXPECT_EQ(PooledBuffer::PooledCount(), 1u);
    }
    EXPECT_EQ(PooledBuffer::PooledCount(), 2u);
    PooledBuffer empty(0);
    EXPECT_EQ(empty.data(), nullptr);
  });
}

TEST(PooledBuffer, ThePoolKeepsWithinItsBounds) {
  OnFreshThread([] {
    {
      std::vector<PooledBuffer> many;
      for (size_t k = 0; k < 2 * PooledBuffer::kMaxPooledBuffers; ++k) many.emplace_back(100 + k);
    }
    EXPECT_EQ(PooledBuffer::PooledCount(), PooledBuffer::kMaxPooledBuffers);
    // The largest ones stay (the smallest go first).
    PooledBuffer largest(100 + 2 * PooledBuffer::kMaxPooledBuffers - 1);
    EXPECT_EQ(PooledBuffer::PooledCount(), PooledBuffer::kMaxPooledBuffers - 1);
  });
  OnFreshThread([] {
    const size_t over = PooledBuffer::kMaxPooledBytes / sizeof(double) + 1;
    { PooledBuffer too_large(over); }
    EXPECT_EQ(PooledBuffer::PooledCount(), 0u);  // freed, not pooled
    {
      // Two halves of the bound and a third: the bytes stay within it.
      const size_t half = PooledBuffer::kMaxPooledBytes / sizeof(double) / 2;
      PooledBuffer a(half), b(half), c(half / 2);
    }
    EXPECT_LE(PooledBuffer::PooledBytes(), PooledBuffer::kMaxPooledBytes);
    EXPECT_EQ(PooledBuffer::PooledCount(), 2u);
  });
}

TEST(PooledBuffer, EachThreadHasItsOwnPool) {
  OnFreshThread([] {
    PooledBuffer mine(100);
    // Released on another thread: that thread's pool takes it, not this one's.
    std::thread other([b = std::move(mine)]() mutable {
      { PooledBuffer released = std::move(b); }
      EXPECT_EQ(PooledBuffer::PooledCount(), 1u);
    });
    other.join();
    EXPECT_EQ(PooledBuffer::PooledCount(), 0u);
  });
}

}  // namespace
}  // namespace railwear
