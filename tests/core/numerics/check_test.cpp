// RAILWEAR_CHECK (core/numerics/check.h): a broken invariant throws InternalError, a
// std::logic_error naming the condition, the file and the line; never an InputError (bad input),
// nor a std::runtime_error that code catching runtime failures (the wear step's failed load
// cases) would swallow. The CLI aborts on it (app/internal_error_exit.h), the C API returns
// RW_ERROR_INTERNAL (tests/api/bad_calls_test.cpp, ApiInternal.*).
#include "core/numerics/check.h"

#include <stdexcept>
#include <string>
#include <type_traits>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace {

static_assert(std::is_base_of_v<std::logic_error, InternalError>);
static_assert(!std::is_base_of_v<std::runtime_error, InternalError>);
static_assert(!std::is_base_of_v<InputError, InternalError>);

constexpr int kCheckLine = __LINE__ + 3;  // the RAILWEAR_CHECK's in CheckedHalf

int CheckedHalf(int n) {
  RAILWEAR_CHECK(n % 2 == 0);
  return n / 2;
}

TEST(Check, HoldingConditionPassesThrough) { EXPECT_EQ(CheckedHalf(8), 4); }

TEST(Check, BrokenConditionThrowsInternalErrorNamingItsPlace) {
  const int line = kCheckLine;
  try {
    CheckedHalf(7);
    FAIL() << "no exception";
  } catch (const InternalError& e) {
    EXPECT_STREQ(e.expression(), "n % 2 == 0");
    EXPECT_NE(std::string(e.file()).find("check_test.cpp"), std::string::npos) << e.file();
    EXPECT_EQ(e.line(), line);
    // The text the check printed before it threw, which the CLI still prints.
    EXPECT_EQ(std::string(e.what()), std::string("internal check failed: n % 2 == 0 (") + e.file() +
                                         ":" + std::to_string(line) + ")");
  }
}

TEST(Check, ConditionIsEvaluatedOnce) {
  int evaluations = 0;
  RAILWEAR_CHECK(++evaluations == 1);
  EXPECT_EQ(evaluations, 1);
}

}  // namespace
}  // namespace railwear
