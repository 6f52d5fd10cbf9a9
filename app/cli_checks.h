// CLI11 checks for the numeric options (issue 17): a finite number or an integer within the range
// the numerics bear. CLI11's own Range lets "nan" through for doubles and its PositiveNumber and
// NonNegativeNumber print their bound as 1.8e308 in full.
#pragma once

#include <CLI/CLI.hpp>

namespace railwear::app {

// A finite number in [lo, hi]. Refused: "VALUE: expected a number in [lo, hi] (the range the
// numerics bear)", which CLI11 prefixes with the option's name (exit 2).
CLI::Validator NumberIn(double lo, double hi);
// A whole number in [lo, hi] (for int options: "1.5" and "1e9" are refused the same way).
CLI::Validator IntegerIn(long long lo, long long hi);

}  // namespace railwear::app
