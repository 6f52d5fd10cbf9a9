// Whole-file text input and output: the one place that opens a file to read or write it at once
// (scenes, configs, constants files, gnuplot data, logs). Callers turn a failure into their own
// message (InputError with the file and what was expected).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace railwear {

// The file's bytes, unchanged (binary mode); nullopt when it cannot be opened.
std::optional<std::string> ReadTextFile(const std::string& path);

// Replaces the file's contents with `text` (binary mode); false when it cannot be written.
bool WriteTextFile(const std::string& path, std::string_view text);

}  // namespace railwear
