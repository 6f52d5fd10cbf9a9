// `railwear profile show FILE [--json]`, `railwear profile convert IN OUT` and
// `railwear profile fit FILE [--smoothing AUTO|LENGTH_MM] [--out FILE] [--json]`.
#pragma once

#include <optional>
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

struct ProfileFitCommandOptions {
  std::string path;
  // "auto" (any case): smoothing length by GCV; otherwise the smoothing length in mm (> 0),
  // lambda = length^4. Parsed by ParseSmoothingLength.
  std::string smoothing = "auto";
  std::string output;  // empty: no file; else .csv or .ban by extension
  bool json = false;   // one JSON object on stdout instead of the text report
};

// Adds `profile` with its subcommands `show`, `convert` and `fit`.
void SetupProfile(CLI::App& app);

// All throw InputError for unreadable or invalid files and options (exit 2); fit throws
// std::runtime_error when the fit fails numerically (exit 1).
void RunProfileShow(const ProfileShowOptions& options);
void RunProfileConvert(const ProfileConvertOptions& options);
void RunProfileFit(const ProfileFitCommandOptions& options);

// --smoothing: "auto" (any case) -> empty; a number > 0 in mm -> smoothing length [m].
// Throws InputError naming the option, the value and what was expected.
std::optional<double> ParseSmoothingLength(const std::string& text);

}  // namespace railwear::app
