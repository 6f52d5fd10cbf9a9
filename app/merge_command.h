// `railwear merge OUT.sqlite IN.sqlite...`: copies the runs of study databases (e.g. the per-run
// databases of a sweep, app/sweep_command.h) into one study database (issue 19).
//
// OUT is created when missing (the normal schema) and migrated when older, as by `wear`. Every
// input is first opened read-only (ProfileStore::OpenReadOnly: never written, its -wal and
// -journal neither) and checked, all of them before OUT is written: a file that is not SQLite,
// a database of another application, a newer (or pre-4) schema, or a table merge does not know
// is refused with exit 2 and nothing merged. Then each input is merged in one transaction
// (ProfileStore::MergeRunsFrom): runs are identified by name; a run OUT already holds with the
// same content is left alone (merging again changes nothing), one with different content is a
// conflict (exit 2; the inputs before it stay merged, nothing of that input or those after it
// is). Calibrations are not runs and are not merged (a note on stderr says so).
//
// stdout: one line per input (runs copied, runs already there, rows); stderr: the total time.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace railwear::app {

struct MergeCommandOptions {
  std::string out;                  // the study database to merge into
  std::vector<std::string> inputs;  // the study databases to merge from, in order
};

void SetupMerge(CLI::App& app);

// Throws InputError (exit 2) for a refused input or output, an input given as the output, or a
// conflicting run; std::runtime_error (exit 1) for an SQLite failure.
void RunMergeCommand(const MergeCommandOptions& options);

}  // namespace railwear::app
