// Always-on invariant checks. A broken internal invariant (a bug, not bad input) throws
// railwear::InternalError naming the expression, file and line (STYLE.md "Errors"); bad user
// input throws InputError instead (core/numerics/input_error.h). The libraries never print and
// never end the process: the CLI (app/main.cpp) prints "railwear: internal check failed: ..." and
// aborts, as the check itself did before; the C API (api/railwear_c.cpp) returns
// RW_ERROR_INTERNAL with the same text, so a host process is never killed by a check.
#pragma once

#include <stdexcept>
#include <string>

namespace railwear {

// A failed RAILWEAR_CHECK. A std::logic_error (a bug), never an InputError: code that catches
// bad input or runtime failures (InputError, std::runtime_error) does not swallow it.
class InternalError : public std::logic_error {
 public:
  InternalError(const char* expression, const char* file, int line)
      : std::logic_error(std::string("internal check failed: ") + expression + " (" + file + ":" +
                         std::to_string(line) + ")"),
        expression_(expression),
        file_(file),
        line_(line) {}
  const char* expression() const { return expression_; }  // the check's condition, as written
  const char* file() const { return file_; }              // __FILE__ of the check
  int line() const { return line_; }

 private:
  const char* expression_;  // string literals: valid for the program's lifetime
  const char* file_;
  int line_;
};

namespace internal {

// The failing branch of RAILWEAR_CHECK, out of line so the checks cost a compare and a branch.
[[noreturn, gnu::cold, gnu::noinline]] inline void CheckFailed(const char* expression,
                                                               const char* file, int line) {
  throw InternalError(expression, file, line);
}

}  // namespace internal
}  // namespace railwear

#define RAILWEAR_CHECK(cond)                                        \
  do {                                                              \
    if (!(cond)) [[unlikely]] {                                     \
      ::railwear::internal::CheckFailed(#cond, __FILE__, __LINE__); \
    }                                                               \
  } while (false)
