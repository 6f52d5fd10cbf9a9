// The CLI's end on a broken internal invariant (a failed RAILWEAR_CHECK, core/numerics/check.h):
// the libraries throw railwear::InternalError instead of ending the process, so a host of the C
// API survives; the CLI prints the check's message as the check printed it before it threw
// ("railwear: internal check failed: EXPR (FILE:LINE)") and aborts, a bug's SIGABRT as before,
// not the exit code of a failed run.
#pragma once

#include <cstdlib>
#include <iostream>

#include "core/numerics/check.h"

namespace railwear::app {

[[noreturn]] inline void AbortOnInternalError(const InternalError& e) {
  std::cerr << "railwear: " << e.what() << std::endl;
  std::abort();
}

}  // namespace railwear::app
