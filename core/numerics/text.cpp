// Text helpers for the file readers. See text.h.
#include "core/numerics/text.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace railwear {

std::string Trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

std::optional<double> ParseFiniteDouble(std::string_view token) {
  const std::string t = Trim(token);
  if (t.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace railwear
