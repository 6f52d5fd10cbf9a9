// CLI11 checks for the numeric options (cli_checks.h).
#include "app/cli_checks.h"

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace railwear::app {

namespace {

// The value of `text` when all of it is a number (strtod's syntax), else NaN.
double Parse(const std::string& text) {
  if (text.empty()) return std::nan("");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() ? v : std::nan("");
}

}  // namespace

CLI::Validator NumberIn(double lo, double hi) {
  const std::string expected = fmt::format("a number in [{}, {}]", lo, hi);
  return CLI::Validator(
      [lo, hi, expected](std::string& text) {
        const double v = Parse(text);
        if (std::isfinite(v) && v >= lo && v <= hi) return std::string();
        return fmt::format("{}: expected {} (the range the numerics bear)", text, expected);
      },
      "NUMBER in [" + fmt::format("{}, {}", lo, hi) + "]");
}

CLI::Validator IntegerIn(long long lo, long long hi) {
  const std::string expected = fmt::format("an integer in [{}, {}]", lo, hi);
  return CLI::Validator(
      [lo, hi, expected](std::string& text) {
        const double v = Parse(text);
        if (std::isfinite(v) && v == std::floor(v) && v >= static_cast<double>(lo) &&
            v <= static_cast<double>(hi)) {
          return std::string();
        }
        return fmt::format("{}: expected {} (the range the numerics bear)", text, expected);
      },
      "INT in [" + fmt::format("{}, {}", lo, hi) + "]");
}

}  // namespace railwear::app
