// `railwear sweep PLAN --mpi`: dynamic dispatch of a sweep's lines over MPI ranks
// (app/sweep_mpi.h). The only file that includes <mpi.h>; linked into the railwear executable.
#include "app/sweep_mpi.h"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <exception>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "app/internal_error_exit.h"
#include "app/interrupt_signals.h"
#include "app/sweep_plan.h"
#include "core/numerics/input_error.h"

namespace railwear::app {
namespace {

constexpr int kTagRequest = 1;  // rank -> 0: {the line it finished or -1, its outcome}
constexpr int kTagLine = 2;     // 0 -> rank: the next line, or -1: no more
// How often a waiting rank looks for its message: short against a run (seconds), long enough
// that a waiting rank uses no core (Open MPI's blocking calls poll without pause).
constexpr auto kPollInterval = std::chrono::milliseconds(5);

// MPI_Init_thread on construction, MPI_Finalize on destruction (or Finalize() before).
class MpiSession {
 public:
  MpiSession() {
    int provided = MPI_THREAD_SINGLE;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    if (provided < MPI_THREAD_FUNNELED) {
      MPI_Finalize();
      throw std::runtime_error(
          "--mpi: the MPI library gives no MPI_THREAD_FUNNELED support (rank 0 runs lines in a "
          "thread beside its dispatcher); expected Open MPI as Debian builds it");
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiSession() { Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  void Finalize() {
    if (!finalized_) MPI_Finalize();
    finalized_ = true;
  }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0;
  int size_ = 1;
  bool finalized_ = false;
};

// Completes `request`, looking every kPollInterval; `between` runs between the looks.
template <class Between>
MPI_Status WaitPolling(MPI_Request* request, Between between) {
  MPI_Status status;
  for (int done = 0;;) {
    MPI_Test(request, &done, &status);
    if (done) return status;
    between();
    std::this_thread::sleep_for(kPollInterval);
  }
}

// A line that did not end well, and where.
struct Failure {
  int line = 0;
  int rank = 0;
  int exit_code = 0;
};

// Runs a line; 0 when it is complete (run or skipped), else the exit code its error has in a
// serial sweep (2 bad input, 1 failure), the error printed with the rank. A signal (Interrupted,
// the run marked interrupted) is left in `interrupted` as its exit code.
int RunOne(const SweepPlan& plan, int index, const SweepCommandOptions& options, int rank,
           std::atomic<int>* interrupted) {
  const SweepLine& line = plan.lines[static_cast<size_t>(index)];
  try {
    RunSweepLine(plan, line, options);
    return 0;
  } catch (const Interrupted& e) {
    std::cerr << fmt::format("railwear: rank {}, sweep line {} ({}): {}\n", rank, index, line.id,
                             e.what());
    interrupted->store(e.exit_code());
    return e.exit_code();
  } catch (const InputError& e) {
    std::cerr << fmt::format("railwear: error: rank {}, sweep line {} ({}): {}\n", rank, index,
                             line.id, e.what());
    return 2;
  } catch (const InternalError& e) {  // a bug: the rank ends as the check ended it before
    AbortOnInternalError(e);
  } catch (const std::exception& e) {
    std::cerr << fmt::format("railwear: error: rank {}, sweep line {} ({}): {}\n", rank, index,
                             line.id, e.what());
    return 1;
  }
}

// Every rank but 0: asks rank 0 for a line, runs it, reports and asks again, until told none.
void Work(const SweepPlan& plan, const SweepCommandOptions& options, int rank) {
  std::atomic<int> interrupted{0};
  int report[2] = {-1, 0};
  while (true) {
    MPI_Send(report, 2, MPI_INT, 0, kTagRequest, MPI_COMM_WORLD);
    int line = -1;
    MPI_Request request;
    MPI_Irecv(&line, 1, MPI_INT, 0, kTagLine, MPI_COMM_WORLD, &request);
    WaitPolling(&request, [] {});
    if (line < 0) return;
    report[0] = line;
    report[1] = RunOne(plan, line, options, rank, &interrupted);
    if (interrupted.load() != 0) MPI_Abort(MPI_COMM_WORLD, interrupted.load());
  }
}

// Rank 0: serves the other ranks' requests and runs lines itself in a worker thread, all from
// one queue; returns the lines that failed.
std::vector<Failure> Dispatch(const SweepPlan& plan, const std::vector<int>& order,
                              const std::vector<double>& costs, const SweepCommandOptions& options,
                              int ranks) {
  std::mutex mutex;
  std::deque<int> queue(order.begin(), order.end());
  std::vector<Failure> failures;
  std::atomic<int> interrupted{0};
  std::atomic<bool> own_done{false};
  const auto next = [&](int rank) {
    std::lock_guard<std::mutex> lock(mutex);
    if (queue.empty() || interrupted.load() != 0) return -1;
    const int line = queue.front();
    queue.pop_front();
    std::cerr << fmt::format(
        "railwear: sweep --mpi: line {} ({}, expected cost {:.3g}) to rank {}\n", line,
        plan.lines[static_cast<size_t>(line)].id, costs[static_cast<size_t>(line)], rank);
    return line;
  };
  const auto fail = [&](int line, int rank, int code) {
    std::lock_guard<std::mutex> lock(mutex);
    failures.push_back({line, rank, code});
  };
  // Rank 0's own runs; no MPI calls from this thread (MPI_THREAD_FUNNELED).
  std::thread own([&] {
    for (int line; (line = next(0)) >= 0;) {
      const int code = RunOne(plan, line, options, 0, &interrupted);
      if (code != 0) fail(line, 0, code);
    }
    own_done.store(true);
  });
  const auto abort_if_interrupted = [&] {
    if (interrupted.load() != 0) MPI_Abort(MPI_COMM_WORLD, interrupted.load());
  };
  for (int active = ranks - 1; active > 0;) {
    int report[2] = {-1, 0};
    MPI_Request request;
    MPI_Irecv(report, 2, MPI_INT, MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &request);
    const MPI_Status status = WaitPolling(&request, abort_if_interrupted);
    if (report[0] >= 0 && report[1] != 0) fail(report[0], status.MPI_SOURCE, report[1]);
    int line = next(status.MPI_SOURCE);
    MPI_Send(&line, 1, MPI_INT, status.MPI_SOURCE, kTagLine, MPI_COMM_WORLD);
    if (line < 0) --active;
  }
  while (!own_done.load()) {
    abort_if_interrupted();
    std::this_thread::sleep_for(kPollInterval);
  }
  own.join();
  abort_if_interrupted();
  std::sort(failures.begin(), failures.end(),
            [](const Failure& a, const Failure& b) { return a.line < b.line; });
  return failures;
}

}  // namespace

void RunSweepMpi(const SweepPlan& plan, const std::vector<int>& order,
                 const std::vector<double>& costs, const std::string& study_db,
                 const SweepCommandOptions& options) {
  SweepCommandOptions run_options = options;
  if (!run_options.threads) run_options.threads = 1;  // the ranks are the parallelism
  MpiSession mpi;
  if (mpi.rank() != 0) {
    Work(plan, run_options, mpi.rank());
    return;
  }
  std::cerr << fmt::format(
      "railwear: sweep --mpi: {} line(s) of {} on {} rank(s), largest expected cost first\n",
      plan.lines.size(), plan.path, mpi.size());
  const std::vector<Failure> failures = Dispatch(plan, order, costs, run_options, mpi.size());
  mpi.Finalize();  // the other ranks end now; rank 0 merges alone
  // Lines whose run failed and says so in its database are results: merged with the complete
  // ones and named (MergeSweepRuns throws SomeRunsFailed, exit 3). Any other failure (bad input,
  // a run that did not record its failure) merges nothing.
  const bool all_recorded = std::all_of(failures.begin(), failures.end(), [&](const Failure& f) {
    return f.exit_code == 1 &&
           SweepLineFailure(plan, plan.lines[static_cast<size_t>(f.line)]).has_value();
  });
  if (!failures.empty() && !all_recorded) {
    std::string list;
    for (const Failure& f : failures) {
      list += fmt::format("{}{} (rank {}, exit {})", list.empty() ? "" : ", ", f.line, f.rank,
                          f.exit_code);
    }
    throw std::runtime_error(fmt::format(
        "sweep {}: {} of {} line(s) failed: {} (their errors above); the other lines are "
        "complete and nothing is merged: run mpirun again (complete lines are skipped, started "
        "ones continue) or `railwear sweep {} --index N`, then `railwear sweep {} --merge`",
        plan.path, failures.size(), plan.lines.size(), list, plan.path, plan.path));
  }
  MergeSweepRuns(plan, study_db);
}

}  // namespace railwear::app
