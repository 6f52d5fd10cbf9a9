// Fixed-point numbers for tables: a value that rounds to zero prints as 0, never as -0.000
// (a wear measure of -1e-9 mm is no wear, not negative wear).
#pragma once

#include <string>

#include <fmt/format.h>

namespace railwear::app {

// `value` with `decimals` digits after the point; "-0.000" becomes "0.000".
inline std::string FixedNoNegativeZero(double value, int decimals) {
  std::string s = fmt::format("{:.{}f}", value, decimals);
  if (!s.empty() && s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace railwear::app
