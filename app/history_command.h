// `railwear history [--db FILE] runs | calibrations | steps RUN | profile RUN | diff RUN A B |
// plot RUN | sql Q | bands | life`: reading a study's profile-history database
// (profiles_db/SCHEMA.md) — runs, influence-constant calibrations, the steps of a run,
// a step's profile as CSV/BAN/JSON, the wear between two steps, plots, read-only SQL, and an
// ensemble's percentile bands and traffic to wear limits (app/history_ensemble.h).
//
// Data goes to stdout, messages to stderr. The database must exist and be a railwear profile-
// history database: history never creates one (a missing or empty file is InputError, exit 2),
// and refuses other files untouched. An older-schema database is migrated on open, as by every
// railwear command (ProfileStore::Open). Unknown runs, steps out of range and SQL that would
// write throw InputError (exit 2) naming the file, the run and the step.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/numerics/enum_names.h"

namespace CLI {
class App;
}

namespace railwear::app {

// Shared by every history subcommand.
struct HistoryOptions {
  std::string db = "wear.sqlite";  // the study database (the scene template's [wear] db default)
};

// Co-evolution (issue 16): a wearing wheel of the run, by its traffic entry's index or name
// (`history steps/profile/diff --wheel`); empty: the rail.
struct HistoryWheelOption {
  std::string wheel;
};

struct HistoryStepsOptions : HistoryWheelOption {
  std::string run;
  bool json = false;  // --json: one JSON object on stdout (the rail's steps with their warnings)
};

enum class HistoryProfileFormat { kCsv, kBan, kJson };
inline constexpr std::array<EnumName<HistoryProfileFormat>, 3> kHistoryProfileFormatNames = {{
    {HistoryProfileFormat::kCsv, "csv"},
    {HistoryProfileFormat::kBan, "ban"},
    {HistoryProfileFormat::kJson, "json"},
}};
std::string ToString(HistoryProfileFormat format);
// Throws InputError naming the value and the choices.
HistoryProfileFormat HistoryProfileFormatFromString(const std::string& text);

// Which rail of a two-rail run `history profile` and `diff` read: "high" (default, also the only
// rail of a single-rail run) or "low" (wear/traffic.h RailSide names).
struct HistoryRailOption {
  std::string rail = "high";
};

struct HistoryProfileOptions : HistoryRailOption, HistoryWheelOption {
  std::string run;
  std::optional<int> step;  // default: the run's last step
  std::string format;       // "csv", "ban" or "json"; default: by --out's extension, else csv
  std::string out;          // file to write; empty: stdout
};

struct HistoryDiffOptions : HistoryRailOption, HistoryWheelOption {
  std::string run;
  int from_step = 0;  // A
  int to_step = 0;    // B
  bool json = false;  // one JSON object instead of the text report
};

struct HistoryPlotOptions {
  std::string run;
  std::string prefix;  // PNG files PREFIX_profiles.png, _depth.png, _measures.png; default: RUN
};

struct HistorySqlOptions {
  std::string sql;
  bool tsv = false;  // tab-separated instead of aligned columns
};

// Columns padded to their widest cell, two spaces apart; numbers right-aligned, text left-aligned;
// a rule of dashes under the header (every history table).
std::string AlignedTable(const std::vector<std::string>& columns,
                         const std::vector<std::vector<std::string>>& rows);

// Adds `history` with its subcommands runs, steps, profile, diff, plot, sql, bands and life
// (app/history_ensemble.h).
void SetupHistory(CLI::App& app);

// Each opens options.db (InputError when missing, empty or not a railwear database).
// runs: table name, state, created, steps, last MGT, program version.
void RunHistoryRuns(const HistoryOptions& options);
// calibrations: table id, name, created, status, well conditioned, fitted constants, version
// (the rows `railwear calibrate --db` stores; their inputs: `history sql`).
void RunHistoryCalibrations(const HistoryOptions& options);
// steps: table step, passes, MGT, worn area, max depth and its y, W1 W2 W3, smoothing error, the
// W2 and W3 rates [mm/MGT] since the previous stored step; for a two-rail run the same measures
// and rates of the low rail in columns low_*. --wheel ENTRY: that wearing wheel's table instead
// (step, passes, MGT, worn area, max depth and its y in the wheel frame, smoothing error).
void RunHistorySteps(const HistoryOptions& options, const HistoryStepsOptions& steps);
// profile: the step's rail profile (mm) as CSV or MiniProf BAN (core/profile/profile_io.h), or
// JSON {run, step, passes, mgt, points, y_mm[], z_mm[]}; --rail low: the low rail's (own frame);
// --wheel ENTRY: that wearing wheel's (wheel profile frame; CSV or JSON, not BAN).
void RunHistoryProfile(const HistoryOptions& options, const HistoryProfileOptions& profile);
// diff: CompareProfiles(step A, step B) with the wear gauge of the run's step 0, so W1/W2/W3
// between A and B are the differences of their values against step 0 (wear/wear_measures.h);
// --rail low: of the low rail; --wheel ENTRY: of that wearing wheel (CompareWheelProfiles: worn
// area and max depth, no W1/W2/W3; from step 0 CompareWheelWithUnworn, as the run measured it).
void RunHistoryDiff(const HistoryOptions& options, const HistoryDiffOptions& diff);
// plot: three PNGs via gnuplot (app/history_plot.h); std::runtime_error when gnuplot is missing.
void RunHistoryPlot(const HistoryOptions& options, const HistoryPlotOptions& plot);
// sql: ProfileStore::Query (read-only; a statement that would write is InputError).
void RunHistorySql(const HistoryOptions& options, const HistorySqlOptions& sql);

}  // namespace railwear::app
