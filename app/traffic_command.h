// `railwear traffic import FILE.csv --out COLLECTIVE.toml [--bin-... W] [--force]`: reads an MBS
// time history (one row per wheel per time step or case, docs/mbs_import.md), bins it into a
// weighted load collective per rail and writes the collective file (app/load_collective_file.h).
#pragma once

#include <string>

#include "wear/load_collective.h"

namespace CLI {
class App;
}

namespace railwear::app {

struct TrafficImportOptions {
  std::string input;               // the CSV
  std::string output;              // the collective TOML
  bool force = false;              // overwrite an existing output
  LoadCollectiveBinWidths widths;  // SI; the options are in mm, mrad, kN, m/s
};

// Adds `traffic` with its subcommand `import`.
void SetupTraffic(CLI::App& app);

// Prints a summary (rows, bins and weight per rail) on stdout. Throws InputError for a bad CSV
// (FILE:LINE), bad bin widths, or an existing output without --force (exit 2); writes nothing
// then.
void RunTrafficImport(const TrafficImportOptions& options);

}  // namespace railwear::app
