// railwear command-line entry point. Exit codes: 0 ok, 1 runtime or numerical failure,
// 2 bad input or usage, 3 a sweep or merge whose every line ended but some runs failed (named;
// app/sweep_command.h), 130 / 143 a `wear` run stopped by SIGINT / SIGTERM (its run marked
// interrupted, resumable). Errors go to stderr as "railwear: error: MESSAGE". A failed internal
// check (a bug) prints "railwear: internal check failed: ..." and aborts
// (app/internal_error_exit.h).
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/accuracy_command.h"
#include "app/calibrate_command.h"
#include "app/contact_command.h"
#include "app/curving_command.h"
#include "app/fem_reference_command.h"
#include "app/history_command.h"
#include "app/init_command.h"
#include "app/internal_error_exit.h"
#include "app/interrupt_signals.h"
#include "app/merge_command.h"
#include "app/profile_command.h"
#include "app/sweep_command.h"
#include "app/sweep_mpi.h"
#include "app/traffic_command.h"
#include "app/wear_command.h"
#include "core/numerics/input_error.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

int Fail(const char* message, int code) {
  std::cerr << "railwear: error: " << message << "\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"railwear: wheel-rail contact mechanics at the rail gauge corner"};
  app.name("railwear");
  app.set_version_flag("--version", std::string("railwear ") + RAILWEAR_VERSION);
  app.require_subcommand(1);
  railwear::app::SetupContact(app);
  railwear::app::SetupProfile(app);
  railwear::app::SetupWear(app);
  railwear::app::SetupHistory(app);
  railwear::app::SetupInit(app);
  railwear::app::SetupAccuracy(app);
  railwear::app::SetupCalibrate(app);
  railwear::app::SetupFemReference(app);
  railwear::app::SetupTraffic(app);
  railwear::app::SetupCurving(app);
  railwear::app::SetupSweep(app, &railwear::app::RunSweepMpi);
  railwear::app::SetupMerge(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    Fail(e.what(), kExitBadInput);
    std::cerr << "Run with --help for more information.\n";
    return kExitBadInput;
  } catch (const railwear::app::Interrupted& e) {
    // SIGINT / SIGTERM: the stored data is in order (app/interrupt_signals.h); 130 / 143.
    std::cerr << "railwear: " << e.what() << "\n";
    return e.exit_code();
  } catch (const railwear::app::SomeRunsFailed& e) {
    // Every line ended; the complete runs are usable, the failed ones named (issue 19).
    std::cerr << "railwear: warning: " << e.what() << "\n";
    return railwear::app::kExitSomeRunsFailed;
  } catch (const railwear::InputError& e) {
    return Fail(e.what(), kExitBadInput);
  } catch (const railwear::InternalError& e) {
    railwear::app::AbortOnInternalError(e);
  } catch (const std::exception& e) {
    return Fail(e.what(), kExitFailure);
  }
  return kExitOk;
}
