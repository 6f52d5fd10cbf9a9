// `railwear init [FILE]`: write the commented scene template to FILE or stdout.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace railwear::app {

struct InitOptions {
  std::optional<std::string> path;  // stdout when absent
};

void SetupInit(CLI::App& app);

// Throws InputError when FILE exists (never overwrites) or cannot be written.
void RunInit(const InitOptions& options);

}  // namespace railwear::app
