// SIGINT and SIGTERM during a long command (`railwear wear`): a handler installed with sigaction
// that only records the signal (an async-signal-safe store to a lock-free atomic), checked by the
// command between steps and load cases (WearOptions::cancel), so the step in flight finishes
// and is committed, or is dropped and never stored. The command then marks its run
// "interrupted" and throws Interrupted, which main() turns into exit 128 + signal (130 for
// SIGINT, 143 for SIGTERM). Only app/ installs handlers; the libraries never do.
#pragma once

#include <stdexcept>
#include <string>

namespace railwear::app {

// While alive: SIGINT and SIGTERM set a flag instead of ending the process; a second signal
// ends it at once (the default action: as safe as a kill, since every step is one transaction).
// The previous dispositions come back on destruction. One at a time (the flag is process-wide).
class InterruptSignals {
 public:
  InterruptSignals();
  ~InterruptSignals();
  InterruptSignals(const InterruptSignals&) = delete;
  InterruptSignals& operator=(const InterruptSignals&) = delete;

  // The first signal received since construction (SIGINT or SIGTERM), 0 for none. Thread-safe
  // and cheap: the wear loop's workers ask it before every load case.
  static int Received();
};

// "SIGINT", "SIGTERM" (or "signal N").
std::string SignalName(int signal);

// A command stopped by a signal after putting its stored data in order; main() prints the
// message and exits with exit_code() = 128 + signal.
class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal, const std::string& message)
      : std::runtime_error(message), signal_(signal) {}
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

}  // namespace railwear::app
