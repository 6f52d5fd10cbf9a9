// Always-on invariant checks. A broken internal invariant aborts with the expression, file and
// line (STYLE.md "Errors"); bad user input throws instead (see core/numerics/input_error.h).
#pragma once

#include <cstdio>
#include <cstdlib>

#define RAILWEAR_CHECK(cond)                                                                 \
  do {                                                                                       \
    if (!(cond)) {                                                                           \
      std::fprintf(stderr, "railwear: internal check failed: %s (%s:%d)\n", #cond, __FILE__, \
                   __LINE__);                                                                \
      std::abort();                                                                          \
    }                                                                                        \
  } while (false)
