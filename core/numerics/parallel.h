// A parallel loop over independent tasks on plain std::threads: the wear step's load cases and the
// curving solver's wheelset contact solves. Each task writes only its own slot, so results do not
// depend on the number of threads or on the order in which the tasks finish.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace railwear {

// The number of workers for a request: `requested` when > 0, else the machine's hardware
// threads; never more than `tasks` nor fewer than 1.
inline int WorkerCount(int requested, int tasks) {
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, std::min(requested > 0 ? requested : hardware, tasks));
}

// Calls task(i) for i in [0, n) on WorkerCount(threads, n) workers (the calling thread alone when
// that is 1). An exception of a task is rethrown after all workers have stopped; with several,
// the one of the lowest index.
template <typename Task>
void ParallelFor(int n, int threads, Task&& task) {
  std::vector<std::exception_ptr> errors(std::max(n, 0));
  std::atomic<int> next{0};
  auto worker = [&]() {
    for (int i = next++; i < n; i = next++) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const int workers = WorkerCount(threads, n);
  if (workers <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int t = 1; t < workers; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace railwear
