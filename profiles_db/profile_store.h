// ProfileStore: the profile history of one study, kept in one SQLite database file (DESIGN.md §5).
//
// A study database holds wear runs; each run holds numbered steps; each step holds the summary
// numbers of the rail profile after that step, the profile itself (float64 points), the per-load-
// case results as JSON text and per-position distributions (wear depth, damage). Every run keeps
// its full scene text, the program version and the wear-law parameters, so any step can be re-run.
// The wear loop (wear/) knows nothing of this; app/ hands its finished steps to AppendStep.
//
// A study database may also hold influence-constant calibrations (`railwear calibrate`), each
// with the text of every input it was made from. MergeRunsFrom copies the runs of another study
// database into this one (`railwear merge`, issue 19), idempotently.
//
// Schema version 7 (PRAGMA user_version = 7, PRAGMA application_id = kApplicationId), also
// documented for users of the sqlite3 shell in profiles_db/SCHEMA.md:
//
//   meta(key TEXT PRIMARY KEY, value TEXT)          -- ('format', 'railwear-profile-history'), ...
//   runs(id INTEGER PRIMARY KEY, name TEXT UNIQUE, created_utc TEXT, program_version TEXT,
//        scene_text TEXT, wear_law_json TEXT, state TEXT)   -- running|complete|aborted|interrupted
//        (v5)
//   steps(run_id, step, passes, mgt, worn_area_mm2, max_depth_mm, max_depth_y_mm,
//         w1_mm, w2_mm, w3_mm, smoothing_area_error, created_utc, PRIMARY KEY(run_id, step))
//   profiles(run_id, step, n_points, yz BLOB, PRIMARY KEY(run_id, step))
//         -- yz: n_points pairs (y, z) as little-endian IEEE-754 float64, metres, 16 bytes a point
//   load_cases(run_id, step, case_index, json TEXT, PRIMARY KEY(run_id, step, case_index))
//   distributions(run_id, step, kind TEXT, y BLOB, value BLOB, s BLOB NULL,
//                 PRIMARY KEY(run_id, step, kind))
//         -- y: rail-profile lateral positions [m], value: same count, little-endian float64;
//         -- s: arc length along the run's step-0 profile [m], same count, or NULL (since v2)
//   calibrations(id INTEGER PRIMARY KEY, name, created_utc, program_version, config_path,
//                config_text, status, well_conditioned, constants_json, correlation_json,
//                residuals_json, ceres_report, constants_toml)             -- since v3
//   calibration_inputs(calibration_id, input_index, kind, path, text,
//                      PRIMARY KEY(calibration_id, input_index))           -- since v3
//   low_rail_steps(run_id, step, worn_area_mm2, max_depth_mm, max_depth_y_mm, w1_mm, w2_mm,
//                  w3_mm, smoothing_area_error, n_points, yz BLOB,
//                  PRIMARY KEY(run_id, step))                              -- since v4
//   low_rail_distributions(run_id, step, kind, y, value, s,
//                          PRIMARY KEY(run_id, step, kind))                -- since v4
//         -- the low rail of a two-rail study, as steps/profiles/distributions hold the high
//         -- (or only) rail; no rows for single-rail runs
//   curving_starts(run_id, step, traffic_index, state BLOB, jacobian BLOB,
//                  PRIMARY KEY(run_id, step, traffic_index))               -- since v6
//         -- each vehicle traffic entry's curving solution at the step (float64; the Jacobian
//         -- n x n in column order, or empty): the next step's start
//   wheel_steps(run_id, step, traffic_index, wheel, name TEXT, worn_area_mm2, max_depth_mm,
//               max_depth_y_mm, smoothing_area_error, sh_mm NULL, sd_mm NULL, qr_mm NULL,
//               n_points, yz BLOB,
//               PRIMARY KEY(run_id, step, traffic_index, wheel))          -- since v7 (wheel v9)
//         -- the wheel of each traffic entry that wears its own (co-evolution, issue 16) after
//         -- the step, in the wheel profile frame, coded as profiles.yz; no rows otherwise
//
// Migrations (applied on open, all of them in one transaction): 0 -> 1 creates the schema;
// 1 -> 2 adds the nullable column distributions.s (rows written by version 1 keep s NULL);
// 2 -> 3 adds the calibrations and calibration_inputs tables; 3 -> 4 adds low_rail_steps and
// low_rail_distributions (older runs have no rows there: they are single-rail runs); 4 -> 5
// rebuilds runs to allow state 'interrupted' (foreign keys off meanwhile, checked before commit);
// 5 -> 6 adds curving_starts (older runs have no rows there: their steps start from the unworn
// solution); 6 -> 7 adds wheel_steps (older runs have no rows there: no wheel of theirs wore);
// 7 -> 8 adds step_warnings; 8 -> 9 rebuilds wheel_steps with the column wheel in its primary
// key (a vehicle entry's wheels, issue 16; older rows get wheel 0, an entry's one wheel).
//
// The database runs in WAL mode with foreign keys on. Each AppendStep is one transaction: a crash
// loses at most the step in flight; CreateRun(run, first_step) stores a run with its step 0 in
// one. Opening never modifies a file it refuses.
//
// Errors: bad input (a file that is not a railwear database, a duplicate run name, a step out of
// order, a write statement given to Query) throws InputError naming the file and what was
// expected; any other SQLite failure throws std::runtime_error with SQLite's message.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/profile/profile.h"

namespace railwear {

// running: started (or stopped by --steps, or killed: resumable); complete: the total reached;
// aborted: stopped by a failure; interrupted: stopped by SIGINT or SIGTERM after its last
// complete step (resumable; since schema version 5).
enum class RunState { kRunning, kComplete, kAborted, kInterrupted };
// "running", "complete", "aborted", "interrupted"; FromString throws InputError for anything else.
std::string ToString(RunState state);
RunState RunStateFromString(const std::string& text);

// Why a run failed (schema 9): the error message of the failure that stopped it, and its last
// stored step then (-1 for none).
struct RunFailure {
  int step = 0;
  std::string message;
};

// One wear run: what it was started from. Everything needed to re-run any of its steps.
struct RunInfo {
  int64_t id = 0;               // assigned by CreateRun; ignored on input
  std::string name;             // unique within the database, not empty
  std::string created_utc;      // ISO 8601 "YYYY-MM-DDTHH:MM:SS.sssZ"; set by CreateRun if empty
  std::string program_version;  // e.g. "0.1.0"
  std::string scene_text;       // the full scene file (TOML), verbatim
  std::string wear_law_json;    // the wear-law parameters as JSON text
  RunState state = RunState::kRunning;
};

// A quantity sampled along the rail profile, e.g. kind "wear_depth_mm" or "damage".
// Wear is naturally a function of the arc length s along the unworn profile (y is not single-
// valued on the gauge face), so a distribution may carry s next to y.
struct Distribution {
  std::string kind;           // unique within a step, not empty
  std::vector<double> y_m;    // lateral positions on the rail profile [m], shape [n]
  std::vector<double> value;  // the quantity at each y (units in `kind`), shape [n]
  // Arc length of each sample along the run's step-0 (unworn) profile, measured from its first
  // point [m], shape [n]; empty when the distribution has none (always so for schema-1 rows).
  // (The "= {}" keeps three-member brace initialisation free of -Wmissing-field-initializers.)
  std::vector<double> s_m = {};
};

// The low rail's part of a step of a two-rail study (schema 4): its measures, profile and
// distributions, as the StepRecord fields of the same names hold the high rail's.
struct RailStepRecord {
  double worn_area_mm2 = 0.0;
  double max_depth_mm = 0.0;
  double max_depth_y_mm = 0.0;  // in the low rail's own frame (y toward its field side)
  double w1_mm = 0.0;
  double w2_mm = 0.0;
  double w3_mm = 0.0;
  double smoothing_area_error = 0.0;
  Profile profile;                          // own frame (not filled by Steps())
  std::vector<Distribution> distributions;  // not filled by Steps()
};

// A vehicle traffic entry's curving solution at a step (wear/: WearState::curving): the unknowns
// and the equilibrium Jacobian there, n x n in column order (empty when none was evaluated).
struct CurvingStartRecord {
  int traffic_index = 0;
  std::vector<double> state;
  std::vector<double> jacobian;
};

// The wheel of a traffic entry that wears its own (co-evolution, schema 7) at a step: its measures
// against its unworn profile (step 0) and its profile after the step, wheel profile frame.
struct WheelStepRecord {
  int traffic_index = 0;  // the study's traffic entry (0-based)
  // Which wheel of the entry (schema 10): 0 for a prescribed or collective entry's one wheel; a
  // vehicle entry's 1 + 2 x wheelset + (0 high rail's wheel, 1 low rail's).
  int wheel = 0;
  std::string name;  // the entry's name; a vehicle wheel's "ENTRY / wheelset W high" (or low)
  int step = 0;           // filled by WheelSteps(); AppendStep takes the StepRecord's
  double worn_area_mm2 = 0.0;
  double max_depth_mm = 0.0;
  double max_depth_y_mm = 0.0;  // wheel profile frame
  double smoothing_area_error = 0.0;
  // The flange measures of the profile after the step (EN 15313 Sh, Sd, qR; wear/wear_measures.h
  // MeasureWheelFlange) [mm]; absent (NULL) where the profile has no flange to measure.
  std::optional<double> flange_height_mm, flange_thickness_mm, flange_slope_mm;
  Profile profile;  // not filled by WheelSteps()
};

// One wear step. Step 0 is conventionally the unworn profile (passes = 0). The summary, profile
// and distributions are the high (or only) rail's; `low_rail` the low rail's in a two-rail study.
// A warning of a wear step (schema 8, issue 17): `kind` "flange_climb" (L/V beyond Nadal's limit
// in some load case) or "hardness" (p_max beyond the hardness of the softer body), and the
// message the wear command printed for it.
struct StepWarningRecord {
  std::string kind;
  std::string message;
  bool operator==(const StepWarningRecord&) const = default;
};

struct StepRecord {
  int step = 0;
  double passes = 0.0;          // cumulative wheel passes up to the end of this step
  double mgt = 0.0;             // cumulative traffic [million gross tonnes]
  double worn_area_mm2 = 0.0;   // cumulative worn cross-section area [mm^2]
  double max_depth_mm = 0.0;    // largest cumulative wear depth [mm]
  double max_depth_y_mm = 0.0;  // lateral position of that depth [mm]
  double w1_mm = 0.0;           // W1/W2/W3 wear measures [mm] (wear/wear_measures.h)
  double w2_mm = 0.0;
  double w3_mm = 0.0;
  double smoothing_area_error = 0.0;  // relative area change caused by profile smoothing [-]
  std::string created_utc;            // set by AppendStep; filled in by Steps()
  Profile profile;                    // the rail profile after this step (not filled by Steps())
  std::vector<std::string> load_cases_json;  // per load case (index = case_index): JSON text
  std::vector<Distribution> distributions;   // wear and damage per rail-profile position
  // The low rail (two-rail studies); its profile and distributions are not filled by Steps().
  std::optional<RailStepRecord> low_rail = std::nullopt;
  // The vehicle entries' curving solutions of the step (not filled by Steps()).
  std::vector<CurvingStartRecord> curving_starts;
  // The wearing wheels (co-evolution), by traffic entry (not filled by Steps(); WheelSteps()).
  std::vector<WheelStepRecord> wheels = {};
  // The step's warnings, in order (filled by Steps() and LoadStep(); none in a file of schema 7
  // or older, which had no place for them).
  std::vector<StepWarningRecord> warnings = {};
};

// One input of a calibration, verbatim: kind "config", "displacement_curves", "scene" or
// "profile" (a profile file a scene names), the path as resolved when it was read, its text.
struct CalibrationInput {
  std::string kind;
  std::string path;
  std::string text;
};

// An influence-constant calibration (`railwear calibrate`): what it was made from and what it
// found. The JSON texts are as the calibrate command writes them (SCHEMA.md).
struct CalibrationRecord {
  int64_t id = 0;           // assigned by AddCalibration; ignored on input
  std::string name;         // not empty (need not be unique: the id identifies)
  std::string created_utc;  // set by AddCalibration if empty
  std::string program_version;
  std::string config_path;  // the calibration config as given
  std::string config_text;  // its full text
  std::string status;       // "converged", "no-convergence", "failure"
  bool well_conditioned = true;
  std::string constants_json;            // fitted constants: start, value, standard error, flags
  std::string correlation_json;          // correlation matrix of the fitted constants
  std::string residuals_json;            // per curve and per contact result, before and after
  std::string ceres_report;              // Ceres's full report
  std::string constants_toml;            // the [influence_constants] file written for scenes
  std::vector<CalibrationInput> inputs;  // filled by LoadCalibration, not by Calibrations()
};

// What `ProfileStore::MergeRunsFrom` did with one input (issue 19, `railwear merge`).
struct MergeSummary {
  int runs_copied = 0;      // runs new to the output, copied with all their rows
  int runs_identical = 0;   // runs the output already held with the same content (left as they are)
  int64_t rows_copied = 0;  // rows written, the runs' own included
  int calibrations_left = 0;  // calibrations of the input (not runs: never merged)
};

// How merge treats a table of a study database: the runs themselves; rows that belong to a run
// (every table with a run_id column: copied with the run, run_id remapped); tables that hold no
// run data (meta, calibrations, calibration_inputs: left out). A table in none of these is
// refused, so a table added to the schema later can never be skipped silently.
enum class MergeTableRole { kRuns, kRunRows, kNotRunData };

// Result of Query: column names and rows, every value as text (NULL -> "NULL",
// a BLOB -> "<blob N bytes>", numbers as SQLite prints them).
struct QueryResult {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

class ProfileStore {
 public:
  // Schema version written by this program (PRAGMA user_version).
  static constexpr int kSchemaVersion = 10;
  // The oldest schema OpenReadOnly reads as it is: version 5 only widened runs.state's CHECK
  // (adding 'interrupted'), version 6 only added curving_starts, 7 wheel_steps, 8 step_warnings
  // (each read when present) and 9 wheel_steps.wheel (read as 0 when absent), so a version-4 to
  // -8 file reads the same; older ones need migrating.
  static constexpr int kOldestReadOnlyVersion = 4;
  // PRAGMA application_id of railwear databases: "RWDB" in ASCII.
  static constexpr int32_t kApplicationId = 0x52574442;
  // Value of meta.format in railwear databases.
  static constexpr const char* kFormatName = "railwear-profile-history";

  // Opens `path` (a file name, or ":memory:" for a private in-memory database). A missing or
  // empty file becomes a new database of schema kSchemaVersion; an older railwear database is
  // migrated in one transaction (its data kept; on failure it stays at its old version).
  // Throws InputError, leaving the file untouched, when the file is not an SQLite database, is
  // an SQLite database of another application, or was written by a newer railwear
  // (user_version > kSchemaVersion), or cannot be opened at all.
  static ProfileStore Open(const std::string& path);
  // Opens an existing file database for reading only (the `history` commands), never writing
  // to it, its -wal or its -journal: the main file is inspected as it is (URI immutable=1, so a
  // foreign file is refused before any journal recovery or checkpoint); a database without a
  // -wal is then read immutable (nothing created: works on read-only media and folders), one
  // with a -wal read-only through it (SQLite may create its -shm; no checkpoint on close).
  // Throws InputError for a missing file, a foreign or empty database, a non-empty -journal
  // (an interrupted write that would need rolling back), a newer schema, and an older one
  // (never migrated here; the message names the commands that do).
  static ProfileStore OpenReadOnly(const std::string& path);

  ProfileStore(ProfileStore&&) noexcept;
  ProfileStore& operator=(ProfileStore&&) noexcept;
  ~ProfileStore();

  const std::string& path() const;
  // The database's PRAGMA user_version (kSchemaVersion once open).
  int SchemaVersion() const;

  // Stores a new run and returns its id. Throws InputError when the name is empty or already used.
  int64_t CreateRun(const RunInfo& run);
  // Stores a new run and its first step (step 0, the unworn rails) in one transaction: a run
  // exists with its step 0 or not at all, whenever the process is killed (issue 17). Throws as
  // CreateRun and AppendStep, storing nothing.
  int64_t CreateRun(const RunInfo& run, const StepRecord& first_step);
  std::optional<RunInfo> FindRun(const std::string& name) const;
  // All runs, in creation (id) order.
  std::vector<RunInfo> Runs() const;
  // Throws InputError for an unknown run id. Clears the run's recorded failure (SetRunFailed):
  // a run resumed after a failure is running again.
  void SetRunState(int64_t run, RunState state);
  // Marks the run aborted and records why, with its last stored step, in one transaction (issue
  // 19: a sweep merges and names its failed runs). Throws InputError for an unknown run id.
  void SetRunFailed(int64_t run, const std::string& message);
  // The run's recorded failure; nullopt when it has none (not aborted, aborted by a railwear
  // before schema 9, or a read-only file of schema 8 or older, which has no place for it).
  std::optional<RunFailure> FindRunFailure(int64_t run) const;
  // Every write (CreateRun, AppendStep, SetRunState) first checks that the database's path still
  // names the file this store opened (SQLite's SQLITE_FCNTL_HAS_MOVED and the file's st_dev and
  // st_ino recorded at Open): when the file was deleted, or replaced by or renamed over with
  // another one while the store was open, it rolls back and throws std::runtime_error saying so
  // (writing on would store steps that vanish with the deleted file). Not for ":memory:".

  // Writes the step row, its profile, load cases and distributions, the low rail's when present
  // the curving starts and the wheels, in one transaction (all or nothing). Throws InputError when
  // the run does not exist, step.step is not LastStep()+1 (0 for a run without steps), a profile
  // (a wheel's too) is empty, a distribution is malformed (empty or duplicate kind, y and value of
  // different lengths, s neither empty nor as long as value), a curving start is (an empty state,
  // a Jacobian neither empty nor n x n, a traffic entry given twice) or a wheel's traffic entry is
  // negative or given twice.
  void AppendStep(int64_t run, const StepRecord& step);
  // The steps of a run in order, summary columns only, with the low rail's summary when stored
  // (profiles, load cases and distributions are left empty; see LoadProfile / LoadStep).
  std::vector<StepRecord> Steps(int64_t run) const;
  // One step in full: summary, profile, load cases, distributions and curving starts. Throws
  // InputError when absent.
  StepRecord LoadStep(int64_t run, int step) const;
  // The profile stored for a step, points bit-for-bit as appended. Throws InputError when absent.
  Profile LoadProfile(int64_t run, int step) const;
  // The low rail's profile stored for a step; InputError when the step has no low rail.
  Profile LoadLowRailProfile(int64_t run, int step) const;
  // The wearing wheels' summaries of a run (co-evolution), by traffic entry, wheel, then step, profiles
  // left empty; none for a run without them or a file older than schema 7.
  std::vector<WheelStepRecord> WheelSteps(int64_t run) const;
  // The profile of traffic entry `traffic_index`'s wheel `wheel` (WheelStepRecord::wheel) stored
  // for a step; InputError when the step has none.
  Profile LoadWheelProfile(int64_t run, int step, int traffic_index, int wheel = 0) const;
  // The last stored step of a run, nullopt when it has none.
  std::optional<int> LastStep(int64_t run) const;

  // Stores a calibration and its inputs in one transaction; returns its id. Throws InputError
  // for an empty name or an input without kind or path.
  int64_t AddCalibration(const CalibrationRecord& calibration);
  // All calibrations in id order, without their inputs.
  std::vector<CalibrationRecord> Calibrations() const;
  // One calibration with its inputs. Throws InputError for an unknown id.
  CalibrationRecord LoadCalibration(int64_t id) const;

  // Copies every run of `input` (opened with OpenReadOnly) into this database, in one
  // transaction: the run row and its rows in every run-rows table (MergeTableRoles), with new
  // ids here. Runs are identified by name (unique in a study database, and the run id of a sweep
  // line): a run this database already holds with the same content — every column of the run and
  // of its rows except ids and the created_utc timestamps — is left as it is (merging twice
  // changes nothing); one with different content is a conflict. Throws InputError, having
  // written nothing of this input, for a conflict, a table merge does not know (input or output),
  // an input table with a column the output lacks, or a non-finite REAL in the input (a damaged
  // row). The input is only read.
  MergeSummary MergeRunsFrom(const ProfileStore& input);
  // The role of every table of this database (name, role) in name order; InputError naming the
  // table for one that fits no role.
  std::vector<std::pair<std::string, MergeTableRole>> MergeTableRoles() const;

  // Runs one read-only SQL statement (a SELECT, or a read-only PRAGMA) and returns all its rows.
  // File databases are queried through a separate read-only connection (SQLITE_OPEN_READONLY);
  // ":memory:" through this connection with PRAGMA query_only. Throws InputError for a syntax
  // error, more than one statement, or any statement that would write.
  QueryResult Query(const std::string& sql) const;

 private:
  struct Impl;
  explicit ProfileStore(std::unique_ptr<Impl> impl);
  // AppendStep's writes inside the caller's transaction (checks included).
  void WriteStep(int64_t run, const StepRecord& step);
  std::unique_ptr<Impl> impl_;
};

}  // namespace railwear
