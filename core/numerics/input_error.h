// The exception type for bad user input (files, scenes, options). Its message names the file,
// the key or line, the value and what was expected; app/main.cpp maps it to exit code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace railwear {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace railwear
