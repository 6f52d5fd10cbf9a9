// `railwear profile show FILE [--json]` and `railwear profile convert IN OUT`.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace railwear::app {

struct ProfileShowOptions {
  std::string path;
  bool json = false;  // one JSON object on stdout instead of the text report
};

struct ProfileConvertOptions {
  std::string input;
  std::string output;  // format by extension: .csv or .ban
};

// Adds `profile` with its subcommands `show` and `convert`.
void SetupProfile(CLI::App& app);

// Both throw InputError for unreadable or invalid files (exit 2).
void RunProfileShow(const ProfileShowOptions& options);
void RunProfileConvert(const ProfileConvertOptions& options);

}  // namespace railwear::app
