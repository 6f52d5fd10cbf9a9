// Small text helpers shared by the file readers (profiles, displacement curves, CalculiX
// results): trimming and whole-token number parsing.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace railwear {

// `s` without leading and trailing spaces, tabs, CR and LF.
std::string Trim(std::string_view s);

// The whole token (after Trim) as a finite double; nullopt for an empty token, trailing
// characters, NaN, infinity or a value out of double's range.
std::optional<double> ParseFiniteDouble(std::string_view token);

}  // namespace railwear
