// InterruptSignals: sigaction handlers for SIGINT and SIGTERM that record the signal in an atomic.
#include "app/interrupt_signals.h"

#include <signal.h>

#include <atomic>
#include <cstring>

#include <fmt/format.h>

namespace railwear::app {
namespace {

// Lock-free, so storing to it is async-signal-safe.
std::atomic<int> g_received{0};
static_assert(std::atomic<int>::is_always_lock_free);

struct sigaction g_previous_int, g_previous_term;

// The first signal is recorded; a second one (Ctrl-C pressed again while a long solve finishes)
// ends the process at once by the default action, like a kill: every committed step stays stored
// and --resume continues from it. signal() and raise() are async-signal-safe.
extern "C" void RecordSignal(int number) {
  int none = 0;
  if (g_received.compare_exchange_strong(none, number)) return;
  signal(number, SIG_DFL);
  raise(number);
}

}  // namespace

InterruptSignals::InterruptSignals() {
  g_received = 0;
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = &RecordSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // system calls in flight (SQLite's I/O) go on
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptSignals::~InterruptSignals() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

int InterruptSignals::Received() { return g_received.load(); }

std::string SignalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return fmt::format("signal {}", signal);
  }
}

}  // namespace railwear::app
