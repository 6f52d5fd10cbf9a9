// ProfileStore on the SQLite C API: thin RAII wrappers (connection, statement, a transaction that
// rolls back unless committed), the schema migrations keyed by version, the float64 BLOB codec,
// and the store's operations. The only place, with the rest of profiles_db/*.cpp, that sees SQLite.
#include "profiles_db/profile_store.h"

#include <sqlite3.h>
#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {
namespace internal {
namespace {

// How long a connection waits for another one's lock [ms].
constexpr int kBusyTimeoutMs = 5000;

// ---------------------------------------------------------------------------------------------
// Float64 BLOB codec: little-endian IEEE-754 doubles whatever the host byte order.

static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559);

void AppendDouble(double v, std::string* out) {
  auto bits = std::bit_cast<uint64_t>(v);
  for (int i = 0; i < 8; ++i) out->push_back(static_cast<char>((bits >> (8 * i)) & 0xffu));
}

double ReadDouble(const unsigned char* p) {
  uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) bits |= static_cast<uint64_t>(p[i]) << (8 * i);
  return std::bit_cast<double>(bits);
}

// No NaN or infinity is ever stored (issue 6): every double that goes into the database passes
// here, as a bound parameter or as an element of a BLOB, and the statement's transaction rolls
// back when one fails.
void RequireFiniteToStore(double v, const std::string& what) {
  if (!std::isfinite(v)) {
    throw std::runtime_error(
        fmt::format("refusing to store a non-finite value ({}) {}; nothing "
                    "of this write was stored",
                    v, what));
  }
}

std::string EncodeDoubles(const std::vector<double>& v) {
  std::string out;
  out.reserve(8 * v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    RequireFiniteToStore(v[i], fmt::format("at element {} of an array", i));
    AppendDouble(v[i], &out);
  }
  return out;
}

std::string EncodePoints(const std::vector<Eigen::Vector2d>& points) {
  std::string out;
  out.reserve(16 * points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    RequireFiniteToStore(points[i].x(), fmt::format("at point {} of a profile", i));
    RequireFiniteToStore(points[i].y(), fmt::format("at point {} of a profile", i));
    AppendDouble(points[i].x(), &out);
    AppendDouble(points[i].y(), &out);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// RAII wrappers.

[[noreturn]] void ThrowSqlite(sqlite3* db, const std::string& path, const std::string& what) {
  throw std::runtime_error(fmt::format("database '{}': {} failed: {}", path, what,
                                       db ? sqlite3_errmsg(db) : "out of memory"));
}

class Connection {
 public:
  Connection() = default;
  Connection(const std::string& path, int flags) : Connection(path, flags, path) {}
  // Opens `name` (a file name, or a "file:" URI with SQLITE_OPEN_URI) and names it `path` in
  // messages.
  Connection(const std::string& name, int flags, const std::string& path) : path_(path) {
    const int rc = sqlite3_open_v2(name.c_str(), &db_, flags, nullptr);
    if (rc != SQLITE_OK) {
      const std::string msg = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
      sqlite3_close_v2(db_);
      db_ = nullptr;
      throw InputError(
          fmt::format("database '{}': cannot open it ({}); expected a railwear "
                      "profile-history database or a new file in an existing folder",
                      path, msg));
    }
    sqlite3_extended_result_codes(db_, 1);
    sqlite3_busy_timeout(db_, kBusyTimeoutMs);
  }
  Connection(Connection&& o) noexcept
      : db_(std::exchange(o.db_, nullptr)), path_(std::move(o.path_)) {}
  Connection& operator=(Connection&& o) noexcept {
    if (this != &o) {
      Close();
      db_ = std::exchange(o.db_, nullptr);
      path_ = std::move(o.path_);
    }
    return *this;
  }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  ~Connection() { Close(); }

  sqlite3* get() const { return db_; }
  const std::string& path() const { return path_; }

  // Runs SQL without results (may be several statements).
  void Exec(const std::string& sql) const {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string msg = err ? err : sqlite3_errmsg(db_);
      sqlite3_free(err);
      throw std::runtime_error(
          fmt::format("database '{}': '{}' failed: {}", path_, sql.substr(0, 60), msg));
    }
  }

 private:
  void Close() {
    if (db_) sqlite3_close_v2(db_);
    db_ = nullptr;
  }
  sqlite3* db_ = nullptr;
  std::string path_;
};

class Statement {
 public:
  Statement(const Connection& c, const std::string& sql) : c_(&c), sql_(sql) {
    if (sqlite3_prepare_v2(c.get(), sql.c_str(), static_cast<int>(sql.size()), &stmt_, nullptr) !=
        SQLITE_OK) {
      ThrowSqlite(c.get(), c.path(), fmt::format("preparing '{}'", sql));
    }
  }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement() { sqlite3_finalize(stmt_); }

  Statement& Bind(int i, int64_t v) { return Check(sqlite3_bind_int64(stmt_, i, v)); }
  Statement& Bind(int i, int v) { return Check(sqlite3_bind_int(stmt_, i, v)); }
  Statement& Bind(int i, double v) {
    internal::RequireFiniteToStore(v, fmt::format("in database '{}' as parameter {} of '{}'",
                                                  c_->path(), i, sql_.substr(0, 60)));
    return Check(sqlite3_bind_double(stmt_, i, v));
  }
  Statement& Bind(int i, const std::string& v) {
    return Check(sqlite3_bind_text64(stmt_, i, v.data(), v.size(), SQLITE_TRANSIENT, SQLITE_UTF8));
  }
  Statement& BindBlob(int i, const std::string& bytes) {
    return Check(sqlite3_bind_blob64(stmt_, i, bytes.data(), bytes.size(), SQLITE_TRANSIENT));
  }
  // A nullable REAL: NULL when absent.
  Statement& Bind(int i, const std::optional<double>& v) {
    return v ? Bind(i, *v) : Check(sqlite3_bind_null(stmt_, i));
  }

  // True while there is a row; throws on error. A constraint failure is returned to the caller
  // through *constraint (when given) instead of throwing.
  bool Step(int* constraint = nullptr) {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    if (constraint && (rc & 0xff) == SQLITE_CONSTRAINT) {
      *constraint = rc;
      return false;
    }
    ThrowSqlite(c_->get(), c_->path(), fmt::format("'{}'", sqlite3_sql(stmt_)));
  }
  void Run() {
    while (Step()) {
    }
  }

  int64_t Int64(int col) const { return sqlite3_column_int64(stmt_, col); }
  // Every double read back is checked (issue 17): railwear never stores a NaN or an infinity,
  // so one is a damaged row, reported with its table, row and column, never printed or resumed.
  double Double(int col) const {
    const double v = sqlite3_column_double(stmt_, col);
    if (!std::isfinite(v)) ThrowDamaged(col, fmt::format("{}", v));
    return v;
  }
  // A nullable REAL column: nullopt for NULL.
  std::optional<double> OptionalDouble(int col) const {
    if (sqlite3_column_type(stmt_, col) == SQLITE_NULL) return std::nullopt;
    return Double(col);
  }
  std::string Text(int col) const {
    const auto* p = sqlite3_column_text(stmt_, col);
    return p ? std::string(reinterpret_cast<const char*>(p),
                           static_cast<size_t>(sqlite3_column_bytes(stmt_, col)))
             : std::string();
  }
  std::vector<double> Doubles(int col) const {
    const auto* p = static_cast<const unsigned char*>(sqlite3_column_blob(stmt_, col));
    const int n = sqlite3_column_bytes(stmt_, col);
    std::vector<double> v(static_cast<size_t>(n) / 8);
    for (size_t i = 0; i < v.size(); ++i) {
      v[i] = ReadDouble(p + 8 * i);
      if (!std::isfinite(v[i])) ThrowDamaged(col, fmt::format("{} at element {}", v[i], i));
    }
    return v;
  }
  // InputError (exit 2: the file's contents are bad input, changed outside railwear) naming the
  // database, the table, the row (its step when the statement selects one, and the statement's
  // WHERE clause with its values) and the column.
  [[noreturn]] void ThrowDamaged(int col, const std::string& value) const {
    const char* column = sqlite3_column_name(stmt_, col);
    std::string table = "?";
    const std::string sql = sql_;
    if (const size_t from = sql.find(" FROM "); from != std::string::npos) {
      table = sql.substr(from + 6);
      table = table.substr(0, table.find_first_of(" ,;"));
    }
    std::string row;
    if (const char* c0 = sqlite3_column_name(stmt_, 0); c0 && std::string(c0) == "step") {
      row = fmt::format("step {}", sqlite3_column_int64(stmt_, 0));
    }
    char* expanded = sqlite3_expanded_sql(stmt_);
    if (expanded) {
      const std::string e = expanded;
      sqlite3_free(expanded);
      if (const size_t where = e.find(" WHERE "); where != std::string::npos) {
        std::string cond = e.substr(where + 7);
        cond = cond.substr(0, cond.find(" ORDER BY"));
        row += (row.empty() ? "" : ", ") + std::string("where ") + cond;
      }
    }
    throw InputError(fmt::format(
        "database '{}': damaged row in table '{}' ({}): column '{}' = {}; expected a finite "
        "number (railwear never stores one: the file was changed outside railwear)",
        c_->path(), table, row.empty() ? "row unknown" : row, column ? column : "?", value));
  }
  sqlite3_stmt* get() const { return stmt_; }

 private:
  Statement& Check(int rc) {
    if (rc != SQLITE_OK) ThrowSqlite(c_->get(), c_->path(), "binding a parameter");
    return *this;
  }
  const Connection* c_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string sql_;  // for messages
};

// A write transaction (BEGIN IMMEDIATE) that rolls back on destruction unless committed.
class Transaction {
 public:
  // BEGIN IMMEDIATE (the write lock at once) by default; "BEGIN" for a read snapshot.
  explicit Transaction(const Connection& c, const char* begin = "BEGIN IMMEDIATE") : c_(c) {
    c_.Exec(begin);
  }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction() {
    if (!committed_) sqlite3_exec(c_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void Commit() {
    c_.Exec("COMMIT");
    committed_ = true;
  }

 private:
  const Connection& c_;
  bool committed_ = false;
};

// PRAGMA journal_mode = WAL. Switching needs an exclusive lock, for which SQLite does not call
// the busy handler: while another connection (a run starting on the same new file) holds a
// transaction it fails at once with "database is locked", so it is retried for as long as the
// busy timeout would have waited.
void SwitchToWal(const Connection& c) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(kBusyTimeoutMs);
  while (true) {
    sqlite3_stmt* raw = nullptr;
    int rc = sqlite3_prepare_v2(c.get(), "PRAGMA journal_mode = WAL", -1, &raw, nullptr);
    std::string mode;
    if (rc == SQLITE_OK) {
      rc = sqlite3_step(raw);
      if (rc == SQLITE_ROW) {
        mode = reinterpret_cast<const char*>(sqlite3_column_text(raw, 0));
      }
    }
    sqlite3_finalize(raw);
    if (rc == SQLITE_ROW && mode == "wal") return;
    const int primary = rc & 0xff;
    if ((primary == SQLITE_BUSY || primary == SQLITE_LOCKED) &&
        std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    throw std::runtime_error(fmt::format("database '{}': cannot switch to WAL mode ({})", c.path(),
                                         sqlite3_errmsg(c.get())));
  }
}

int PragmaInt(const Connection& c, const char* pragma) {
  Statement s(c, fmt::format("PRAGMA {}", pragma));
  return s.Step() ? static_cast<int>(s.Int64(0)) : 0;
}

// ---------------------------------------------------------------------------------------------
// Schema migrations. kMigrations[v] takes a database from user_version v to v + 1; each runs in
// the transaction that also sets user_version.

void MigrateTo1(const Connection& c) {
  c.Exec(fmt::format("PRAGMA application_id = {}", ProfileStore::kApplicationId));
  c.Exec(R"sql(
CREATE TABLE meta(
  key   TEXT PRIMARY KEY,
  value TEXT NOT NULL);
CREATE TABLE runs(
  id              INTEGER PRIMARY KEY,
  name            TEXT NOT NULL UNIQUE,
  created_utc     TEXT NOT NULL,
  program_version TEXT NOT NULL,
  scene_text      TEXT NOT NULL,
  wear_law_json   TEXT NOT NULL,
  state           TEXT NOT NULL CHECK (state IN ('running', 'complete', 'aborted')));
CREATE TABLE steps(
  run_id               INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  step                 INTEGER NOT NULL CHECK (step >= 0),
  passes               REAL NOT NULL,
  mgt                  REAL NOT NULL,
  worn_area_mm2        REAL NOT NULL,
  max_depth_mm         REAL NOT NULL,
  max_depth_y_mm       REAL NOT NULL,
  w1_mm                REAL NOT NULL,
  w2_mm                REAL NOT NULL,
  w3_mm                REAL NOT NULL,
  smoothing_area_error REAL NOT NULL,
  created_utc          TEXT NOT NULL,
  PRIMARY KEY (run_id, step));
CREATE TABLE profiles(
  run_id   INTEGER NOT NULL,
  step     INTEGER NOT NULL,
  n_points INTEGER NOT NULL,
  yz       BLOB NOT NULL CHECK (length(yz) = 16 * n_points),
  PRIMARY KEY (run_id, step),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
CREATE TABLE load_cases(
  run_id     INTEGER NOT NULL,
  step       INTEGER NOT NULL,
  case_index INTEGER NOT NULL,
  json       TEXT NOT NULL,
  PRIMARY KEY (run_id, step, case_index),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
CREATE TABLE distributions(
  run_id INTEGER NOT NULL,
  step   INTEGER NOT NULL,
  kind   TEXT NOT NULL,
  y      BLOB NOT NULL,
  value  BLOB NOT NULL CHECK (length(value) = length(y)),
  PRIMARY KEY (run_id, step, kind),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
)sql");
  Statement ins(c, "INSERT INTO meta(key, value) VALUES ('format', ?1), ('schema_doc', ?2)");
  ins.Bind(1, std::string(ProfileStore::kFormatName))
      .Bind(2, std::string("profiles_db/SCHEMA.md in the railwear sources"));
  ins.Run();
}

// Version 2: wear distributions are functions of the arc length along the unworn profile.
// Rows written by version 1 keep s NULL; the CHECK holds for them.
void MigrateTo2(const Connection& c) {
  c.Exec(
      "ALTER TABLE distributions ADD COLUMN s BLOB "
      "CHECK (s IS NULL OR length(s) = length(value))");
}

// Version 3: influence-constant calibrations (`railwear calibrate`) with the text of every input
// they were made from, so that each can be redone.
void MigrateTo3(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE calibrations(
  id               INTEGER PRIMARY KEY,
  name             TEXT NOT NULL,
  created_utc      TEXT NOT NULL,
  program_version  TEXT NOT NULL,
  config_path      TEXT NOT NULL,
  config_text      TEXT NOT NULL,
  status           TEXT NOT NULL,
  well_conditioned INTEGER NOT NULL CHECK (well_conditioned IN (0, 1)),
  constants_json   TEXT NOT NULL,
  correlation_json TEXT NOT NULL,
  residuals_json   TEXT NOT NULL,
  ceres_report     TEXT NOT NULL,
  constants_toml   TEXT NOT NULL);
CREATE TABLE calibration_inputs(
  calibration_id INTEGER NOT NULL REFERENCES calibrations(id) ON DELETE CASCADE,
  input_index    INTEGER NOT NULL,
  kind           TEXT NOT NULL,
  path           TEXT NOT NULL,
  text           TEXT NOT NULL,
  PRIMARY KEY (calibration_id, input_index));
)sql");
}

// Version 4: the low rail of a two-rail wear study (issue 15): its per-step measures and
// profile, and its distributions, next to the high rail's in steps/profiles/distributions (which
// keep their meaning, so older readers still see the high rail). Older runs have no rows here.
void MigrateTo4(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE low_rail_steps(
  run_id               INTEGER NOT NULL,
  step                 INTEGER NOT NULL,
  worn_area_mm2        REAL NOT NULL,
  max_depth_mm         REAL NOT NULL,
  max_depth_y_mm       REAL NOT NULL,
  w1_mm                REAL NOT NULL,
  w2_mm                REAL NOT NULL,
  w3_mm                REAL NOT NULL,
  smoothing_area_error REAL NOT NULL,
  n_points             INTEGER NOT NULL,
  yz                   BLOB NOT NULL CHECK (length(yz) = 16 * n_points),
  PRIMARY KEY (run_id, step),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
CREATE TABLE low_rail_distributions(
  run_id INTEGER NOT NULL,
  step   INTEGER NOT NULL,
  kind   TEXT NOT NULL,
  y      BLOB NOT NULL,
  value  BLOB NOT NULL CHECK (length(value) = length(y)),
  s      BLOB CHECK (s IS NULL OR length(s) = length(value)),
  PRIMARY KEY (run_id, step, kind),
  FOREIGN KEY (run_id, step) REFERENCES low_rail_steps(run_id, step) ON DELETE CASCADE);
)sql");
}

// Version 5: runs.state may be 'interrupted' (issue 17: a run stopped by SIGINT or SIGTERM,
// its step in flight finished or rolled back). SQLite cannot change a CHECK constraint in place,
// so the runs table is rebuilt by SQLite's documented procedure for other schema changes
// (sqlite.org/lang_altertable.html: new table, copy, drop, rename): the caller has switched
// foreign keys off, so dropping the old table cascades to nothing, and checks the foreign keys
// before committing. The SQL repeats version 1's runs table on purpose: a migration is history.
void MigrateTo5(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE runs_v5(
  id              INTEGER PRIMARY KEY,
  name            TEXT NOT NULL UNIQUE,
  created_utc     TEXT NOT NULL,
  program_version TEXT NOT NULL,
  scene_text      TEXT NOT NULL,
  wear_law_json   TEXT NOT NULL,
  state           TEXT NOT NULL
                  CHECK (state IN ('running', 'complete', 'aborted', 'interrupted')));
INSERT INTO runs_v5(id, name, created_utc, program_version, scene_text, wear_law_json, state)
  SELECT id, name, created_utc, program_version, scene_text, wear_law_json, state FROM runs;
DROP TABLE runs;
ALTER TABLE runs_v5 RENAME TO runs;
)sql");
}

// Version 6: each vehicle traffic entry's curving solution of a step (issue 15): the next step
// starts from it, so a resumed run continues exactly where it stopped. Older runs have no rows
// here (their steps start from the unworn rails' solution). state: n float64; jacobian: n x n
// float64 in column order, or empty.
void MigrateTo6(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE curving_starts(
  run_id        INTEGER NOT NULL,
  step          INTEGER NOT NULL,
  traffic_index INTEGER NOT NULL CHECK (traffic_index >= 0),
  state         BLOB NOT NULL CHECK (length(state) > 0 AND length(state) % 8 = 0),
  jacobian      BLOB NOT NULL
                CHECK (length(jacobian) = 0 OR length(jacobian) * 8 = length(state) * length(state)),
  PRIMARY KEY (run_id, step, traffic_index),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
)sql");
}

// Version 7: the wheel of each traffic entry that wears its own (co-evolution, issue 16 point 6),
// per step: its measures against its unworn profile, its flange measures Sh, Sd, qR (NULL where
// the profile has no flange to measure) and its profile after the step (wheel profile frame,
// coded as profiles.yz). Older runs have no rows here (no wheel of theirs wore).
void MigrateTo7(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE wheel_steps(
  run_id               INTEGER NOT NULL,
  step                 INTEGER NOT NULL,
  traffic_index        INTEGER NOT NULL CHECK (traffic_index >= 0),
  name                 TEXT NOT NULL,
  worn_area_mm2        REAL NOT NULL,
  max_depth_mm         REAL NOT NULL,
  max_depth_y_mm       REAL NOT NULL,
  smoothing_area_error REAL NOT NULL,
  sh_mm                REAL,
  sd_mm                REAL,
  qr_mm                REAL,
  n_points             INTEGER NOT NULL,
  yz                   BLOB NOT NULL CHECK (length(yz) = 16 * n_points),
  PRIMARY KEY (run_id, step, traffic_index),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
)sql");
}

// Version 8: the warnings of each step (issue 17: p_max beyond the hardness, L/V beyond Nadal's
// limit), in order. Older runs have no rows here (their warnings went to stderr only).
void MigrateTo8(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE step_warnings(
  run_id        INTEGER NOT NULL,
  step          INTEGER NOT NULL,
  warning_index INTEGER NOT NULL CHECK (warning_index >= 0),
  kind          TEXT NOT NULL CHECK (kind IN ('flange_climb', 'hardness')),
  message       TEXT NOT NULL,
  PRIMARY KEY (run_id, step, warning_index),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
)sql");
}

// Version 9: why a run failed (issue 19: a sweep or an ensemble merges and names its failed runs
// beside the complete ones): the error message of the run's failure and its last stored step,
// one row per run in state 'aborted' (none for a run aborted by an older railwear).
void MigrateTo9(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE run_failures(
  run_id  INTEGER PRIMARY KEY REFERENCES runs(id) ON DELETE CASCADE,
  step    INTEGER NOT NULL,
  message TEXT NOT NULL);
)sql");
}

// Version 10: a vehicle entry's wheels wear too (co-evolution, issue 16), each wheel of each
// wheelset its own: wheel_steps gains `wheel` (0: a prescribed or collective entry's one wheel;
// a vehicle entry's 1 + 2 x wheelset + 0 for the high rail's wheel, 1 for the low rail's) in its
// primary key. SQLite cannot change a primary key in place, so the table is rebuilt as
// MigrateTo5 rebuilt runs (foreign keys off meanwhile, checked before the commit); every row is
// kept, with wheel 0.
void MigrateTo10(const Connection& c) {
  c.Exec(R"sql(
CREATE TABLE wheel_steps_v10(
  run_id               INTEGER NOT NULL,
  step                 INTEGER NOT NULL,
  traffic_index        INTEGER NOT NULL CHECK (traffic_index >= 0),
  wheel                INTEGER NOT NULL DEFAULT 0 CHECK (wheel >= 0),
  name                 TEXT NOT NULL,
  worn_area_mm2        REAL NOT NULL,
  max_depth_mm         REAL NOT NULL,
  max_depth_y_mm       REAL NOT NULL,
  smoothing_area_error REAL NOT NULL,
  sh_mm                REAL,
  sd_mm                REAL,
  qr_mm                REAL,
  n_points             INTEGER NOT NULL,
  yz                   BLOB NOT NULL CHECK (length(yz) = 16 * n_points),
  PRIMARY KEY (run_id, step, traffic_index, wheel),
  FOREIGN KEY (run_id, step) REFERENCES steps(run_id, step) ON DELETE CASCADE);
INSERT INTO wheel_steps_v10(run_id, step, traffic_index, wheel, name, worn_area_mm2, max_depth_mm,
                           max_depth_y_mm, smoothing_area_error, sh_mm, sd_mm, qr_mm, n_points, yz)
  SELECT run_id, step, traffic_index, 0, name, worn_area_mm2, max_depth_mm, max_depth_y_mm,
         smoothing_area_error, sh_mm, sd_mm, qr_mm, n_points, yz FROM wheel_steps;
DROP TABLE wheel_steps;
ALTER TABLE wheel_steps_v10 RENAME TO wheel_steps;
)sql");
}

using Migration = void (*)(const Connection&);
constexpr Migration kMigrations[] = {&MigrateTo1, &MigrateTo2, &MigrateTo3,
                                     &MigrateTo4, &MigrateTo5, &MigrateTo6,
                                     &MigrateTo7, &MigrateTo8, &MigrateTo9,
                                     &MigrateTo10};
static_assert(std::size(kMigrations) == ProfileStore::kSchemaVersion);

const char* kNowUtc = "strftime('%Y-%m-%dT%H:%M:%fZ', 'now')";

bool TableExists(const Connection& c, const std::string& name) {
  Statement s(c, "SELECT 1 FROM sqlite_schema WHERE type = 'table' AND name = ?1");
  s.Bind(1, name);
  return s.Step();
}

// "wheel of traffic entry T" for an entry's one wheel (wheel 0), "wheel W of traffic entry T"
// for a vehicle entry's.
std::string WheelText(int traffic_index, int wheel) {
  return wheel == 0 ? fmt::format("wheel of traffic entry {}", traffic_index)
                    : fmt::format("wheel {} of traffic entry {}", wheel, traffic_index);
}

// The SQL of wheel_steps' wheel column: `wheel`, or 0 in a file opened read-only that predates
// version 10 (every wheel of it is an entry's one wheel), usable in SELECT, WHERE and ORDER BY.
std::string WheelColumn(const Connection& c) {
  Statement s(c, "SELECT 1 FROM pragma_table_info('wheel_steps') WHERE name = 'wheel'");
  // Not the literal 0: SQLite reads an integer literal in ORDER BY as a column number.
  return s.Step() ? "wheel" : "CAST(0 AS INTEGER)";
}

// Checks that `c` holds a railwear database this program can use, or an empty database, without
// writing anything. Returns the user_version (0 for an empty database).
int InspectDatabase(const Connection& c) {
  const std::string& path = c.path();
  sqlite3_stmt* raw = nullptr;
  const int rc =
      sqlite3_prepare_v2(c.get(), "SELECT count(*) FROM sqlite_schema", -1, &raw, nullptr);
  int objects = 0;
  int step_rc = rc;
  if (rc == SQLITE_OK) {
    step_rc = sqlite3_step(raw);
    if (step_rc == SQLITE_ROW) objects = sqlite3_column_int(raw, 0);
  }
  sqlite3_finalize(raw);
  if (rc != SQLITE_OK || step_rc != SQLITE_ROW) {
    if ((step_rc & 0xff) == SQLITE_NOTADB || (rc & 0xff) == SQLITE_NOTADB ||
        (step_rc & 0xff) == SQLITE_CORRUPT || (rc & 0xff) == SQLITE_CORRUPT) {
      throw InputError(fmt::format(
          "database '{}': not an SQLite database ({}); expected a railwear profile-history "
          "database (SQLite, application_id 0x{:08x}) or a new file",
          path, sqlite3_errmsg(c.get()), ProfileStore::kApplicationId));
    }
    ThrowSqlite(c.get(), path, "reading the schema");
  }
  const int app_id = PragmaInt(c, "application_id");
  const int version = PragmaInt(c, "user_version");
  if (app_id == 0 && version == 0 && objects == 0) return 0;  // empty: a new database
  if (app_id != ProfileStore::kApplicationId) {
    throw InputError(fmt::format(
        "database '{}': an SQLite database of another application (application_id 0x{:08x}, "
        "{} schema objects); expected a railwear profile-history database (application_id "
        "0x{:08x}, table meta)",
        path, static_cast<uint32_t>(app_id), objects, ProfileStore::kApplicationId));
  }
  if (version > ProfileStore::kSchemaVersion) {
    throw InputError(fmt::format(
        "database '{}': written by a newer railwear (schema version {}); this program knows "
        "schema versions up to {}, upgrade railwear to open it",
        path, version, ProfileStore::kSchemaVersion));
  }
  bool format_ok = false;
  if (TableExists(c, "meta")) {
    Statement s(c, "SELECT value FROM meta WHERE key = 'format'");
    format_ok = s.Step() && s.Text(0) == ProfileStore::kFormatName;
  }
  if (!format_ok) {
    throw InputError(fmt::format(
        "database '{}': has the railwear application_id but no meta table with format '{}'; "
        "expected a railwear profile-history database (damaged or written by another program?)",
        path, ProfileStore::kFormatName));
  }
  return version;
}

int QueryAuthorizer(void*, int action, const char*, const char*, const char*, const char*) {
  switch (action) {
    case SQLITE_ATTACH:
    case SQLITE_DETACH:
    case SQLITE_TRANSACTION:
    case SQLITE_SAVEPOINT:
      return SQLITE_DENY;
    default:
      return SQLITE_OK;
  }
}

RunInfo ReadRun(const Statement& s) {
  RunInfo r;
  r.id = s.Int64(0);
  r.name = s.Text(1);
  r.created_utc = s.Text(2);
  r.program_version = s.Text(3);
  r.scene_text = s.Text(4);
  r.wear_law_json = s.Text(5);
  r.state = RunStateFromString(s.Text(6));
  return r;
}

constexpr const char* kRunColumns =
    "id, name, created_utc, program_version, scene_text, wear_law_json, state";
constexpr const char* kStepColumns =
    "step, passes, mgt, worn_area_mm2, max_depth_mm, max_depth_y_mm, w1_mm, w2_mm, w3_mm, "
    "smoothing_area_error, created_utc";

constexpr const char* kLowRailColumns =
    "worn_area_mm2, max_depth_mm, max_depth_y_mm, w1_mm, w2_mm, w3_mm, smoothing_area_error";

// The low rail's summary from columns kLowRailColumns starting at `first`.
RailStepRecord ReadLowRail(const Statement& s, int first) {
  RailStepRecord r;
  r.worn_area_mm2 = s.Double(first);
  r.max_depth_mm = s.Double(first + 1);
  r.max_depth_y_mm = s.Double(first + 2);
  r.w1_mm = s.Double(first + 3);
  r.w2_mm = s.Double(first + 4);
  r.w3_mm = s.Double(first + 5);
  r.smoothing_area_error = s.Double(first + 6);
  return r;
}

// A wheel's summary from the columns traffic_index, name, worn_area_mm2, max_depth_mm,
// max_depth_y_mm, smoothing_area_error, sh_mm, sd_mm, qr_mm (0 to 8) and wheel (`wheel_col`).
WheelStepRecord ReadWheelStep(const Statement& s, int wheel_col) {
  WheelStepRecord w;
  w.wheel = static_cast<int>(s.Int64(wheel_col));
  w.traffic_index = static_cast<int>(s.Int64(0));
  w.name = s.Text(1);
  w.worn_area_mm2 = s.Double(2);
  w.max_depth_mm = s.Double(3);
  w.max_depth_y_mm = s.Double(4);
  w.smoothing_area_error = s.Double(5);
  w.flange_height_mm = s.OptionalDouble(6);
  w.flange_thickness_mm = s.OptionalDouble(7);
  w.flange_slope_mm = s.OptionalDouble(8);
  return w;
}

// A profile from its point count and (y, z) BLOB; InputError naming `what` when they disagree.
Profile DecodeProfile(const Statement& s, int n_col, int yz_col, const std::string& path,
                      const std::string& what) {
  const std::vector<double> yz = s.Doubles(yz_col);
  if (yz.size() != 2 * static_cast<size_t>(s.Int64(n_col))) {
    throw InputError(fmt::format(
        "database '{}': {}: profile BLOB of {} values for {} points; expected 2 per point", path,
        what, yz.size(), s.Int64(n_col)));
  }
  std::vector<Eigen::Vector2d> points(yz.size() / 2);
  for (size_t i = 0; i < points.size(); ++i) points[i] = {yz[2 * i], yz[2 * i + 1]};
  return Profile(std::move(points), fmt::format("{}:{}", path, what));
}

constexpr const char* kCalibrationColumns =
    "id, name, created_utc, program_version, config_path, config_text, status, "
    "well_conditioned, constants_json, correlation_json, residuals_json, ceres_report, "
    "constants_toml";

CalibrationRecord ReadCalibration(const Statement& s) {
  CalibrationRecord r;
  r.id = s.Int64(0);
  r.name = s.Text(1);
  r.created_utc = s.Text(2);
  r.program_version = s.Text(3);
  r.config_path = s.Text(4);
  r.config_text = s.Text(5);
  r.status = s.Text(6);
  r.well_conditioned = s.Int64(7) != 0;
  r.constants_json = s.Text(8);
  r.correlation_json = s.Text(9);
  r.residuals_json = s.Text(10);
  r.ceres_report = s.Text(11);
  r.constants_toml = s.Text(12);
  return r;
}

StepRecord ReadStep(const Statement& s) {
  StepRecord r;
  r.step = static_cast<int>(s.Int64(0));
  r.passes = s.Double(1);
  r.mgt = s.Double(2);
  r.worn_area_mm2 = s.Double(3);
  r.max_depth_mm = s.Double(4);
  r.max_depth_y_mm = s.Double(5);
  r.w1_mm = s.Double(6);
  r.w2_mm = s.Double(7);
  r.w3_mm = s.Double(8);
  r.smoothing_area_error = s.Double(9);
  r.created_utc = s.Text(10);
  return r;
}

}  // namespace
}  // namespace internal

using internal::Connection;
using internal::Statement;
using internal::Transaction;

std::string ToString(RunState state) {
  switch (state) {
    case RunState::kRunning:
      return "running";
    case RunState::kComplete:
      return "complete";
    case RunState::kAborted:
      return "aborted";
    case RunState::kInterrupted:
      return "interrupted";
  }
  return "running";
}

RunState RunStateFromString(const std::string& text) {
  if (text == "running") return RunState::kRunning;
  if (text == "complete") return RunState::kComplete;
  if (text == "aborted") return RunState::kAborted;
  if (text == "interrupted") return RunState::kInterrupted;
  throw InputError(
      fmt::format("run state '{}': expected running, complete, aborted or interrupted", text));
}

struct ProfileStore::Impl {
  Connection db;
  bool in_memory = false;
  bool read_only = false;  // OpenReadOnly: db is a read-only (or immutable) connection
  // The file's identity (st_dev, st_ino) when Open accepted it, for RequireSameFile.
  dev_t device = 0;
  ino_t inode = 0;

  // Throws std::runtime_error (a failure: exit 1) when the path no longer names the file this
  // connection writes: the file was deleted, or another file was renamed over it (or it was
  // moved away). Writes would then go to a file nobody can open by its name: every step stored
  // from then on would be lost when the program ends. Called before each commit.
  void RequireSameFile() const {
    if (in_memory) return;
    int moved = 0;  // SQLite's own check of its open file against the path (inode or gone)
    sqlite3_file_control(db.get(), "main", SQLITE_FCNTL_HAS_MOVED, &moved);
    struct stat now {};
    const bool exists = ::stat(db.path().c_str(), &now) == 0;
    if (moved == 0 && exists && now.st_dev == device && now.st_ino == inode) return;
    throw std::runtime_error(fmt::format(
        "database '{}': the file was {} while railwear was writing to it (the path no longer "
        "names the file railwear opened); nothing more is written to it: the write in flight "
        "was rolled back, and what was stored before is {}",
        db.path(), exists ? "replaced by another file (or moved away)" : "deleted",
        exists ? "in the file wherever it went" : "lost with the deleted file"));
  }
};

namespace internal {

// A "file:" URI for `path` with `query` ("immutable=1"): '%', '?' and '#' percent-encoded; an
// absolute path gets an empty authority ("file:///abs").
std::string FileUri(const std::string& path, const std::string& query) {
  std::string out = path.rfind('/', 0) == 0 ? "file://" : "file:";
  for (char ch : path) {
    if (ch == '%' || ch == '?' || ch == '#') {
      out += fmt::format("%{:02X}", static_cast<unsigned char>(ch));
    } else {
      out += ch;
    }
  }
  return out + "?" + query;
}

// The file as it is on disk, without SQLite's locking, journal recovery or checkpoints (URI
// immutable=1, read-only): nothing is written and no -wal, -shm or -journal file is created or
// changed. Throws InputError (leaving every file untouched) for a file that is not a railwear
// database; returns the user_version its main file holds (0 for an empty database, which may
// still have its schema in a pending -wal).
int InspectImmutable(const std::string& path) {
  Connection probe(FileUri(path, "immutable=1"), SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, path);
  Transaction snapshot(probe, "BEGIN");
  return InspectDatabase(probe);
}

bool NonEmptyFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) > 0;
}

}  // namespace internal

ProfileStore ProfileStore::OpenReadOnly(const std::string& path) {
  auto impl = std::make_unique<Impl>();
  impl->read_only = true;
  std::error_code ec;
  if (path.empty() || path == ":memory:" || !std::filesystem::exists(path, ec)) {
    throw InputError(fmt::format(
        "database '{}': no such file; expected an existing railwear profile-history database "
        "(read-only commands never create one)",
        path));
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(fmt::format(
        "database '{}': is a directory; expected a railwear profile-history database file", path));
  }
  // 1. The main file as it is: a foreign file is refused before SQLite could recover its
  // journal or checkpoint its WAL.
  int version = internal::InspectImmutable(path);
  // 2. A rollback journal left by an interrupted write would have to be rolled back (a write):
  // refused, the file and its journal untouched.
  if (internal::NonEmptyFile(path + "-journal")) {
    throw InputError(fmt::format(
        "database '{}': has a rollback journal '{}-journal' left by an interrupted write; a "
        "read-only command does not roll it back (that changes the file): run a command that "
        "writes to the database (railwear wear SCENE --db {} --resume) to recover it",
        path, path, path));
  }
  const int ro = SQLITE_OPEN_READONLY | SQLITE_OPEN_URI;
  if (!std::filesystem::exists(path + "-wal", ec)) {
    // 3a. No WAL: the main file is the whole database. Immutable: no lock, no -shm or -wal is
    // created (so it also reads a database on read-only media or in a read-only folder).
    impl->db = Connection(internal::FileUri(path, "immutable=1"), ro, path);
  } else {
    // 3b. A -wal (a run writing now, or one killed before its checkpoint): read through it
    // read-only. SQLite may build its wal-index in -shm; the database and its -wal are never
    // written (read-only file handles, no checkpoint on close).
    impl->db = Connection(internal::FileUri(path, "mode=ro"), ro, path);
    sqlite3_db_config(impl->db.get(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
    Transaction snapshot(impl->db, "BEGIN");
    version = internal::InspectDatabase(impl->db);
  }
  if (version == 0) {
    throw InputError(fmt::format(
        "database '{}': an empty SQLite database; expected a railwear profile-history database",
        path));
  }
  if (version < kOldestReadOnlyVersion) {
    throw InputError(fmt::format(
        "database '{}': schema version {} (written by an older railwear); read-only commands "
        "read versions {} to {} and never migrate a file: run a command that writes to it once "
        "(railwear wear SCENE --db {} --resume, or railwear calibrate CONFIG --db {}) to "
        "migrate it",
        path, version, kOldestReadOnlyVersion, kSchemaVersion, path, path));
  }
  impl->db.Exec("PRAGMA query_only = ON");
  return ProfileStore(std::move(impl));
}

ProfileStore::ProfileStore(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ProfileStore::ProfileStore(ProfileStore&&) noexcept = default;
ProfileStore& ProfileStore::operator=(ProfileStore&&) noexcept = default;
ProfileStore::~ProfileStore() = default;

ProfileStore ProfileStore::Open(const std::string& path) {
  auto impl = std::make_unique<Impl>();
  impl->in_memory = path == ":memory:" || path.empty();
  std::error_code ec;
  if (!impl->in_memory && std::filesystem::is_directory(path, ec)) {
    throw InputError(
        fmt::format("database '{}': is a directory; expected a railwear "
                    "profile-history database file",
                    path));
  }
  // An existing file is inspected as it is first (immutable): a foreign file with a pending WAL
  // or a hot journal is refused before a read-write connection could recover it.
  if (!impl->in_memory && internal::NonEmptyFile(path)) internal::InspectImmutable(path);
  impl->db = Connection(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  const Connection& c = impl->db;
  // Until the file is accepted, closing must not checkpoint a pending WAL into it (a file
  // whose main part is still empty is only known after reading through its WAL).
  sqlite3_db_config(c.get(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
  // Nothing is written before InspectDatabase has accepted the file. Its reads share one
  // snapshot: another process may create the schema between two of them.
  int version = 0;
  {
    Transaction snapshot(c, "BEGIN");
    version = internal::InspectDatabase(c);
  }  // rolled back: it only read
  sqlite3_db_config(c.get(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 0, nullptr);
  if (!impl->in_memory) internal::SwitchToWal(c);
  // All migrations in one transaction: a failure leaves the database at its old version.
  // Foreign keys are off while they run (MigrateTo5 drops and rebuilds runs) and on afterwards.
  c.Exec("PRAGMA foreign_keys = OFF");
  if (version < kSchemaVersion) {
    Transaction t(c);
    // Another process may have created or migrated the file between the inspection and this
    // write lock (a `wear` run and a `history` query started together on a new file): migrate
    // from the version found under the lock, not the one inspected.
    version = internal::PragmaInt(c, "user_version");
    for (int v = version; v < kSchemaVersion; ++v) internal::kMigrations[v](c);
    c.Exec(fmt::format("PRAGMA user_version = {}", kSchemaVersion));
    // MigrateTo5 rebuilt runs with foreign keys off: every reference must still resolve.
    if (Statement check(c, "PRAGMA foreign_key_check"); check.Step()) {
      throw std::runtime_error(fmt::format(
          "database '{}': migrating to schema version {} left a dangling reference in table "
          "'{}'; the file stays at version {}",
          path, kSchemaVersion, check.Text(0), version));
    }
    t.Commit();
  }
  c.Exec("PRAGMA foreign_keys = ON");  // after the migrations (a no-op inside a transaction)
  if (!impl->in_memory) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
      throw std::runtime_error(
          fmt::format("database '{}': the file disappeared while it was being opened", path));
    }
    impl->device = st.st_dev;
    impl->inode = st.st_ino;
  }
  return ProfileStore(std::move(impl));
}

const std::string& ProfileStore::path() const { return impl_->db.path(); }

int ProfileStore::SchemaVersion() const { return internal::PragmaInt(impl_->db, "user_version"); }

namespace {

// Inserts the run row inside the caller's transaction and returns its id; InputError for an
// empty or used name (the caller's transaction then rolls back).
int64_t InsertRun(const internal::Connection& c, const RunInfo& run) {
  if (run.name.empty()) {
    throw InputError(fmt::format("database '{}': run name is empty; expected a name", c.path()));
  }
  internal::Statement s(c, fmt::format("INSERT INTO runs(name, created_utc, program_version, "
                                       "scene_text, wear_law_json, state) VALUES (?1, coalesce(?2, "
                                       "{}), ?3, ?4, ?5, ?6)",
                                       internal::kNowUtc));
  s.Bind(1, run.name);
  if (!run.created_utc.empty()) s.Bind(2, run.created_utc);
  s.Bind(3, run.program_version).Bind(4, run.scene_text).Bind(5, run.wear_law_json);
  s.Bind(6, ToString(run.state));
  int constraint = 0;
  s.Step(&constraint);
  if (constraint != 0) {
    throw InputError(
        fmt::format("database '{}': a run named '{}' already exists; expected a new "
                    "run name (or resume that run)",
                    c.path(), run.name));
  }
  return sqlite3_last_insert_rowid(c.get());
}

}  // namespace

int64_t ProfileStore::CreateRun(const RunInfo& run) {
  Transaction t(impl_->db);
  const int64_t id = InsertRun(impl_->db, run);
  impl_->RequireSameFile();
  t.Commit();
  return id;
}

int64_t ProfileStore::CreateRun(const RunInfo& run, const StepRecord& first_step) {
  Transaction t(impl_->db);
  const int64_t id = InsertRun(impl_->db, run);
  WriteStep(id, first_step);
  impl_->RequireSameFile();
  t.Commit();
  return id;
}

std::optional<RunInfo> ProfileStore::FindRun(const std::string& name) const {
  Statement s(impl_->db, fmt::format("SELECT {} FROM runs WHERE name = ?1", internal::kRunColumns));
  s.Bind(1, name);
  if (!s.Step()) return std::nullopt;
  return internal::ReadRun(s);
}

std::vector<RunInfo> ProfileStore::Runs() const {
  Statement s(impl_->db, fmt::format("SELECT {} FROM runs ORDER BY id", internal::kRunColumns));
  std::vector<RunInfo> runs;
  while (s.Step()) runs.push_back(internal::ReadRun(s));
  return runs;
}

void ProfileStore::SetRunState(int64_t run, RunState state) {
  impl_->RequireSameFile();
  Transaction t(impl_->db);
  Statement s(impl_->db, "UPDATE runs SET state = ?1 WHERE id = ?2");
  s.Bind(1, ToString(state)).Bind(2, run);
  s.Run();
  if (sqlite3_changes(impl_->db.get()) == 0) {
    throw InputError(fmt::format("database '{}': no run with id {}", path(), run));
  }
  // A new state ends the failure that was recorded (a resumed run starts afresh).
  Statement clear(impl_->db, "DELETE FROM run_failures WHERE run_id = ?1");
  clear.Bind(1, run);
  clear.Run();
  t.Commit();
}

void ProfileStore::SetRunFailed(int64_t run, const std::string& message) {
  impl_->RequireSameFile();
  const std::optional<int> last = LastStep(run);
  Transaction t(impl_->db);
  Statement s(impl_->db, "UPDATE runs SET state = ?1 WHERE id = ?2");
  s.Bind(1, ToString(RunState::kAborted)).Bind(2, run);
  s.Run();
  if (sqlite3_changes(impl_->db.get()) == 0) {
    throw InputError(fmt::format("database '{}': no run with id {}", path(), run));
  }
  Statement f(impl_->db,
              "INSERT OR REPLACE INTO run_failures(run_id, step, message) VALUES (?1, ?2, ?3)");
  f.Bind(1, run).Bind(2, last.value_or(-1)).Bind(3, message);
  f.Run();
  t.Commit();
}

std::optional<RunFailure> ProfileStore::FindRunFailure(int64_t run) const {
  if (!internal::TableExists(impl_->db, "run_failures")) return std::nullopt;  // schema <= 8
  Statement s(impl_->db, "SELECT step, message FROM run_failures WHERE run_id = ?1");
  s.Bind(1, run);
  if (!s.Step()) return std::nullopt;
  return RunFailure{static_cast<int>(s.Int64(0)), s.Text(1)};
}

namespace {

// Inserts `distributions` into `table` (distributions or low_rail_distributions) inside the
// caller's transaction; a kind given twice is InputError (the transaction then rolls back).
void WriteDistributions(const internal::Connection& c, const char* table, int64_t run, int step,
                        const std::vector<Distribution>& distributions) {
  internal::Statement s(c, fmt::format("INSERT INTO {}(run_id, step, kind, y, value, s) "
                                       "VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
                                       table));
  for (const auto& d : distributions) {
    sqlite3_reset(s.get());
    sqlite3_clear_bindings(s.get());  // ?6 stays NULL for a distribution without s
    s.Bind(1, run).Bind(2, step).Bind(3, d.kind);
    s.BindBlob(4, internal::EncodeDoubles(d.y_m)).BindBlob(5, internal::EncodeDoubles(d.value));
    if (!d.s_m.empty()) s.BindBlob(6, internal::EncodeDoubles(d.s_m));
    int constraint = 0;
    s.Step(&constraint);
    if (constraint != 0) {
      throw InputError(fmt::format(
          "database '{}': run {} step {}: {} kind '{}' given twice; expected each kind once",
          c.path(), run, step,
          std::string(table) == "distributions" ? "distribution" : "low-rail distribution",
          d.kind));
    }
  }
}

std::vector<Distribution> ReadDistributions(const internal::Connection& c, const char* table,
                                            int64_t run, int step) {
  internal::Statement s(c, fmt::format("SELECT kind, y, value, s FROM {} WHERE run_id = ?1 AND "
                                       "step = ?2 ORDER BY kind",
                                       table));
  s.Bind(1, run).Bind(2, step);
  std::vector<Distribution> out;
  while (s.Step()) out.push_back({s.Text(0), s.Doubles(1), s.Doubles(2), s.Doubles(3)});
  return out;
}

}  // namespace

void ProfileStore::AppendStep(int64_t run, const StepRecord& step) {
  Transaction t(impl_->db);
  WriteStep(run, step);
  impl_->RequireSameFile();
  t.Commit();
}

void ProfileStore::WriteStep(int64_t run, const StepRecord& step) {
  const Connection& c = impl_->db;
  if (step.profile.size() == 0) {
    throw InputError(
        fmt::format("database '{}': run {} step {}: the profile is empty; expected "
                    "the rail profile after the step",
                    path(), run, step.step));
  }
  for (const WheelStepRecord& w : step.wheels) {
    if (w.profile.size() == 0 || w.traffic_index < 0 || w.wheel < 0) {
      throw InputError(fmt::format(
          "database '{}': run {} step {}: the {} ('{}') has {} profile points; expected an "
          "entry index >= 0, a wheel >= 0 and the wheel's profile after the step",
          path(), run, step.step, internal::WheelText(w.traffic_index, w.wheel), w.name,
          w.profile.size()));
    }
  }
  if (step.low_rail && step.low_rail->profile.size() == 0) {
    throw InputError(
        fmt::format("database '{}': run {} step {}: the low rail's profile is empty; expected "
                    "the low rail's profile after the step",
                    path(), run, step.step));
  }
  std::vector<const Distribution*> all;
  for (const auto& d : step.distributions) all.push_back(&d);
  if (step.low_rail) {
    for (const auto& d : step.low_rail->distributions) all.push_back(&d);
  }
  for (const Distribution* dp : all) {
    const Distribution& d = *dp;
    if (d.kind.empty() || d.y_m.size() != d.value.size()) {
      throw InputError(fmt::format(
          "database '{}': run {} step {}: distribution '{}' ({} positions, {} values); expected a "
          "unique non-empty kind and as many values as positions",
          path(), run, step.step, d.kind, d.y_m.size(), d.value.size()));
    }
    if (!d.s_m.empty() && d.s_m.size() != d.value.size()) {
      throw InputError(fmt::format(
          "database '{}': run {} step {}: distribution '{}' ({} arc lengths s, {} values); "
          "expected no s or one s per value",
          path(), run, step.step, d.kind, d.s_m.size(), d.value.size()));
    }
  }
  {
    Statement s(c, "SELECT 1 FROM runs WHERE id = ?1");
    s.Bind(1, run);
    if (!s.Step()) throw InputError(fmt::format("database '{}': no run with id {}", path(), run));
  }
  const std::optional<int> last = LastStep(run);
  const int expected = last ? *last + 1 : 0;
  if (step.step != expected) {
    throw InputError(
        fmt::format("database '{}': run {} step {}: steps are appended in order; "
                    "expected step {}",
                    path(), run, step.step, expected));
  }
  {
    Statement s(c, fmt::format("INSERT INTO steps(run_id, {}) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, "
                               "?8, ?9, ?10, ?11, {})",
                               internal::kStepColumns, internal::kNowUtc));
    s.Bind(1, run).Bind(2, step.step).Bind(3, step.passes).Bind(4, step.mgt);
    s.Bind(5, step.worn_area_mm2).Bind(6, step.max_depth_mm).Bind(7, step.max_depth_y_mm);
    s.Bind(8, step.w1_mm).Bind(9, step.w2_mm).Bind(10, step.w3_mm);
    s.Bind(11, step.smoothing_area_error);
    s.Run();
  }
  {
    Statement s(c, "INSERT INTO profiles(run_id, step, n_points, yz) VALUES (?1, ?2, ?3, ?4)");
    s.Bind(1, run).Bind(2, step.step).Bind(3, step.profile.size());
    s.BindBlob(4, internal::EncodePoints(step.profile.points()));
    s.Run();
  }
  {
    Statement s(c,
                "INSERT INTO load_cases(run_id, step, case_index, json) VALUES (?1, ?2, ?3, ?4)");
    for (size_t i = 0; i < step.load_cases_json.size(); ++i) {
      sqlite3_reset(s.get());
      s.Bind(1, run)
          .Bind(2, step.step)
          .Bind(3, static_cast<int>(i))
          .Bind(4, step.load_cases_json[i]);
      s.Run();
    }
  }
  WriteDistributions(c, "distributions", run, step.step, step.distributions);
  if (step.low_rail) {
    const RailStepRecord& low = *step.low_rail;
    Statement s(c, fmt::format("INSERT INTO low_rail_steps(run_id, step, {}, n_points, yz) "
                               "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
                               internal::kLowRailColumns));
    s.Bind(1, run).Bind(2, step.step);
    s.Bind(3, low.worn_area_mm2).Bind(4, low.max_depth_mm).Bind(5, low.max_depth_y_mm);
    s.Bind(6, low.w1_mm).Bind(7, low.w2_mm).Bind(8, low.w3_mm);
    s.Bind(9, low.smoothing_area_error).Bind(10, low.profile.size());
    s.BindBlob(11, internal::EncodePoints(low.profile.points()));
    s.Run();
    WriteDistributions(c, "low_rail_distributions", run, step.step, low.distributions);
  }
  if (!step.wheels.empty()) {
    Statement s(c,
                "INSERT INTO wheel_steps(run_id, step, traffic_index, name, worn_area_mm2, "
                "max_depth_mm, max_depth_y_mm, smoothing_area_error, sh_mm, sd_mm, qr_mm, "
                "n_points, yz, wheel) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, "
                "?13, ?14)");
    for (const WheelStepRecord& w : step.wheels) {
      sqlite3_reset(s.get());
      s.Bind(1, run).Bind(2, step.step).Bind(3, w.traffic_index).Bind(4, w.name);
      s.Bind(5, w.worn_area_mm2).Bind(6, w.max_depth_mm).Bind(7, w.max_depth_y_mm);
      s.Bind(8, w.smoothing_area_error);
      s.Bind(9, w.flange_height_mm).Bind(10, w.flange_thickness_mm).Bind(11, w.flange_slope_mm);
      s.Bind(12, w.profile.size());
      s.BindBlob(13, internal::EncodePoints(w.profile.points()));
      s.Bind(14, w.wheel);
      int constraint = 0;
      s.Step(&constraint);
      if (constraint != 0) {
        throw InputError(fmt::format(
            "database '{}': run {} step {}: the {} given twice; expected each wheel once",
            path(), run, step.step, internal::WheelText(w.traffic_index, w.wheel)));
      }
    }
  }
  if (!step.warnings.empty()) {
    Statement s(c,
                "INSERT INTO step_warnings(run_id, step, warning_index, kind, message) "
                "VALUES (?1, ?2, ?3, ?4, ?5)");
    for (size_t i = 0; i < step.warnings.size(); ++i) {
      const StepWarningRecord& w = step.warnings[i];
      if (w.kind != "flange_climb" && w.kind != "hardness") {
        throw InputError(fmt::format(
            "database '{}': run {} step {}: warning kind '{}'; expected 'flange_climb' or "
            "'hardness'",
            path(), run, step.step, w.kind));
      }
      sqlite3_reset(s.get());
      s.Bind(1, run).Bind(2, step.step).Bind(3, static_cast<int>(i)).Bind(4, w.kind);
      s.Bind(5, w.message);
      s.Run();
    }
  }
  if (!step.curving_starts.empty()) {
    Statement s(c,
                "INSERT INTO curving_starts(run_id, step, traffic_index, state, jacobian) "
                "VALUES (?1, ?2, ?3, ?4, ?5)");
    for (const CurvingStartRecord& cs : step.curving_starts) {
      const size_t n = cs.state.size();
      if (n == 0 || cs.traffic_index < 0 || !(cs.jacobian.empty() || cs.jacobian.size() == n * n)) {
        throw InputError(fmt::format(
            "database '{}': run {} step {}: curving start of traffic entry {}: {} state values "
            "and {} Jacobian values; expected n > 0 and 0 or n^2",
            path(), run, step.step, cs.traffic_index, n, cs.jacobian.size()));
      }
      sqlite3_reset(s.get());
      s.Bind(1, run).Bind(2, step.step).Bind(3, cs.traffic_index);
      s.BindBlob(4, internal::EncodeDoubles(cs.state));
      s.BindBlob(5, internal::EncodeDoubles(cs.jacobian));
      int constraint = 0;
      s.Step(&constraint);
      if (constraint != 0) {
        throw InputError(fmt::format(
            "database '{}': run {} step {}: curving start of traffic entry {} given twice; "
            "expected each entry once",
            path(), run, step.step, cs.traffic_index));
      }
    }
  }
}

std::vector<StepRecord> ProfileStore::Steps(int64_t run) const {
  Statement s(impl_->db, fmt::format("SELECT {} FROM steps WHERE run_id = ?1 ORDER BY step",
                                     internal::kStepColumns));
  s.Bind(1, run);
  std::vector<StepRecord> steps;
  while (s.Step()) steps.push_back(internal::ReadStep(s));
  Statement low(impl_->db,
                fmt::format("SELECT step, {} FROM low_rail_steps WHERE run_id = ?1 ORDER BY step",
                            internal::kLowRailColumns));
  low.Bind(1, run);
  size_t i = 0;  // both in step order
  while (low.Step()) {
    const int step = static_cast<int>(low.Int64(0));
    while (i < steps.size() && steps[i].step < step) ++i;
    if (i < steps.size() && steps[i].step == step)
      steps[i].low_rail = internal::ReadLowRail(low, 1);
  }
  // A file opened read-only may predate the table (schema 7 or older): no warnings stored.
  if (internal::TableExists(impl_->db, "step_warnings")) {
    Statement w(impl_->db,
                "SELECT step, kind, message FROM step_warnings WHERE run_id = ?1 "
                "ORDER BY step, warning_index");
    w.Bind(1, run);
    i = 0;
    while (w.Step()) {
      const int step = static_cast<int>(w.Int64(0));
      while (i < steps.size() && steps[i].step < step) ++i;
      if (i < steps.size() && steps[i].step == step)
        steps[i].warnings.push_back({w.Text(1), w.Text(2)});
    }
  }
  return steps;
}

Profile ProfileStore::LoadProfile(int64_t run, int step) const {
  Statement s(impl_->db, "SELECT n_points, yz FROM profiles WHERE run_id = ?1 AND step = ?2");
  s.Bind(1, run).Bind(2, step);
  if (!s.Step()) {
    throw InputError(fmt::format("database '{}': run {} has no step {}", path(), run, step));
  }
  return internal::DecodeProfile(s, 0, 1, path(), fmt::format("run {} step {}", run, step));
}

Profile ProfileStore::LoadLowRailProfile(int64_t run, int step) const {
  Statement s(impl_->db, "SELECT n_points, yz FROM low_rail_steps WHERE run_id = ?1 AND step = ?2");
  s.Bind(1, run).Bind(2, step);
  if (!s.Step()) {
    throw InputError(fmt::format(
        "database '{}': run {} has no low rail at step {}; expected a step of a two-rail run",
        path(), run, step));
  }
  return internal::DecodeProfile(s, 0, 1, path(),
                                 fmt::format("run {} step {} low rail", run, step));
}

StepRecord ProfileStore::LoadStep(int64_t run, int step) const {
  const Connection& c = impl_->db;
  StepRecord r;
  {
    Statement s(c, fmt::format("SELECT {} FROM steps WHERE run_id = ?1 AND step = ?2",
                               internal::kStepColumns));
    s.Bind(1, run).Bind(2, step);
    if (!s.Step()) {
      throw InputError(fmt::format("database '{}': run {} has no step {}", path(), run, step));
    }
    r = internal::ReadStep(s);
  }
  r.profile = LoadProfile(run, step);
  {
    Statement s(c,
                "SELECT json FROM load_cases WHERE run_id = ?1 AND step = ?2 "
                "ORDER BY case_index");
    s.Bind(1, run).Bind(2, step);
    while (s.Step()) r.load_cases_json.push_back(s.Text(0));
  }
  r.distributions = ReadDistributions(c, "distributions", run, step);
  {
    Statement s(c, fmt::format("SELECT {}, n_points, yz FROM low_rail_steps WHERE run_id = ?1 "
                               "AND step = ?2",
                               internal::kLowRailColumns));
    s.Bind(1, run).Bind(2, step);
    if (s.Step()) {
      RailStepRecord low = internal::ReadLowRail(s, 0);
      low.profile = internal::DecodeProfile(s, 7, 8, path(),
                                            fmt::format("run {} step {} low rail", run, step));
      low.distributions = ReadDistributions(c, "low_rail_distributions", run, step);
      r.low_rail = std::move(low);
    }
  }
  // A file opened read-only may predate the table (OpenReadOnly reads older schemas as they are).
  if (internal::TableExists(c, "curving_starts")) {
    Statement s(c,
                "SELECT traffic_index, state, jacobian FROM curving_starts WHERE run_id = ?1 AND "
                "step = ?2 ORDER BY traffic_index");
    s.Bind(1, run).Bind(2, step);
    while (s.Step()) {
      r.curving_starts.push_back({static_cast<int>(s.Int64(0)), s.Doubles(1), s.Doubles(2)});
    }
  }
  if (internal::TableExists(c, "step_warnings")) {
    Statement s(c,
                "SELECT kind, message FROM step_warnings WHERE run_id = ?1 AND step = ?2 "
                "ORDER BY warning_index");
    s.Bind(1, run).Bind(2, step);
    while (s.Step()) r.warnings.push_back({s.Text(0), s.Text(1)});
  }
  if (internal::TableExists(c, "wheel_steps")) {
    const std::string wheel = internal::WheelColumn(c);
    Statement s(c, fmt::format("SELECT traffic_index, name, worn_area_mm2, max_depth_mm, "
                               "max_depth_y_mm, smoothing_area_error, sh_mm, sd_mm, qr_mm, "
                               "n_points, yz, {0} FROM wheel_steps WHERE run_id = ?1 AND step = ?2 "
                               "ORDER BY traffic_index, {0}",
                               wheel));
    s.Bind(1, run).Bind(2, step);
    while (s.Step()) {
      WheelStepRecord w = internal::ReadWheelStep(s, 11);
      w.step = step;
      w.profile = internal::DecodeProfile(
          s, 9, 10, path(),
          fmt::format("run {} step {} {}", run, step, internal::WheelText(w.traffic_index, w.wheel)));
      r.wheels.push_back(std::move(w));
    }
  }
  return r;
}

std::vector<WheelStepRecord> ProfileStore::WheelSteps(int64_t run) const {
  std::vector<WheelStepRecord> out;
  if (!internal::TableExists(impl_->db, "wheel_steps")) return out;
  const std::string wheel = internal::WheelColumn(impl_->db);
  Statement s(impl_->db, fmt::format("SELECT traffic_index, name, worn_area_mm2, max_depth_mm, "
                                     "max_depth_y_mm, smoothing_area_error, sh_mm, sd_mm, qr_mm, "
                                     "step, {0} FROM wheel_steps WHERE run_id = ?1 "
                                     "ORDER BY traffic_index, {0}, step",
                                     wheel));
  s.Bind(1, run);
  while (s.Step()) {
    WheelStepRecord w = internal::ReadWheelStep(s, 10);
    w.step = static_cast<int>(s.Int64(9));
    out.push_back(std::move(w));
  }
  return out;
}

Profile ProfileStore::LoadWheelProfile(int64_t run, int step, int traffic_index,
                                       int wheel) const {
  const std::string what =
      fmt::format("run {} step {} {}", run, step, internal::WheelText(traffic_index, wheel));
  if (internal::TableExists(impl_->db, "wheel_steps")) {
    Statement s(impl_->db, fmt::format("SELECT n_points, yz FROM wheel_steps WHERE run_id = ?1 "
                                       "AND step = ?2 AND traffic_index = ?3 AND {} = ?4",
                                       internal::WheelColumn(impl_->db)));
    s.Bind(1, run).Bind(2, step).Bind(3, traffic_index).Bind(4, wheel);
    if (s.Step()) return internal::DecodeProfile(s, 0, 1, path(), what);
  }
  throw InputError(fmt::format(
      "database '{}': {}: not stored; expected a step of a run whose entry's wheel wears "
      "(wheel_wear)",
      path(), what));
}

std::optional<int> ProfileStore::LastStep(int64_t run) const {
  Statement s(impl_->db, "SELECT max(step) FROM steps WHERE run_id = ?1");
  s.Bind(1, run);
  if (!s.Step() || sqlite3_column_type(s.get(), 0) == SQLITE_NULL) return std::nullopt;
  return static_cast<int>(s.Int64(0));
}

int64_t ProfileStore::AddCalibration(const CalibrationRecord& calibration) {
  const Connection& c = impl_->db;
  if (calibration.name.empty()) {
    throw InputError(
        fmt::format("database '{}': calibration name is empty; expected a name", path()));
  }
  for (const auto& input : calibration.inputs) {
    if (input.kind.empty() || input.path.empty()) {
      throw InputError(
          fmt::format("database '{}': calibration '{}': an input without kind or "
                      "path; expected both",
                      path(), calibration.name));
    }
  }
  Transaction t(c);
  int64_t id = 0;
  {
    Statement s(c, fmt::format("INSERT INTO calibrations(name, created_utc, program_version, "
                               "config_path, config_text, status, well_conditioned, "
                               "constants_json, correlation_json, residuals_json, ceres_report, "
                               "constants_toml) VALUES (?1, coalesce(?2, {}), ?3, ?4, ?5, ?6, "
                               "?7, ?8, ?9, ?10, ?11, ?12)",
                               internal::kNowUtc));
    s.Bind(1, calibration.name);
    if (!calibration.created_utc.empty()) s.Bind(2, calibration.created_utc);
    s.Bind(3, calibration.program_version).Bind(4, calibration.config_path);
    s.Bind(5, calibration.config_text).Bind(6, calibration.status);
    s.Bind(7, calibration.well_conditioned ? 1 : 0).Bind(8, calibration.constants_json);
    s.Bind(9, calibration.correlation_json).Bind(10, calibration.residuals_json);
    s.Bind(11, calibration.ceres_report).Bind(12, calibration.constants_toml);
    s.Run();
    id = sqlite3_last_insert_rowid(c.get());
  }
  {
    Statement s(c,
                "INSERT INTO calibration_inputs(calibration_id, input_index, kind, path, text) "
                "VALUES (?1, ?2, ?3, ?4, ?5)");
    for (size_t i = 0; i < calibration.inputs.size(); ++i) {
      const CalibrationInput& input = calibration.inputs[i];
      sqlite3_reset(s.get());
      s.Bind(1, id).Bind(2, static_cast<int>(i)).Bind(3, input.kind).Bind(4, input.path);
      s.Bind(5, input.text);
      s.Run();
    }
  }
  t.Commit();
  return id;
}

std::vector<CalibrationRecord> ProfileStore::Calibrations() const {
  Statement s(impl_->db, fmt::format("SELECT {} FROM calibrations ORDER BY id",
                                     internal::kCalibrationColumns));
  std::vector<CalibrationRecord> out;
  while (s.Step()) out.push_back(internal::ReadCalibration(s));
  return out;
}

CalibrationRecord ProfileStore::LoadCalibration(int64_t id) const {
  CalibrationRecord r;
  {
    Statement s(impl_->db, fmt::format("SELECT {} FROM calibrations WHERE id = ?1",
                                       internal::kCalibrationColumns));
    s.Bind(1, id);
    if (!s.Step()) {
      throw InputError(fmt::format("database '{}': no calibration with id {}", path(), id));
    }
    r = internal::ReadCalibration(s);
  }
  Statement s(impl_->db,
              "SELECT kind, path, text FROM calibration_inputs WHERE "
              "calibration_id = ?1 ORDER BY input_index");
  s.Bind(1, id);
  while (s.Step()) r.inputs.push_back({s.Text(0), s.Text(1), s.Text(2)});
  return r;
}

// ---------------------------------------------------------------------------------------------
// Merging study databases (issue 19, `railwear merge`): runs copied between two connections
// value by value (sqlite3_value: every type and every bit kept), run ids remapped.

namespace {

// The tables that hold no run data: never merged.
constexpr const char* kNotRunDataTables[] = {"meta", "calibrations", "calibration_inputs"};

// Columns ignored when two runs are compared: ids (renumbered by every merge) and the times a
// row was written (a run recomputed bit for bit is the same run).
bool IgnoredInComparison(const std::string& column) {
  return column == "id" || column == "run_id" || column == "created_utc";
}

struct TableColumns {
  std::vector<std::string> all;          // in table order
  std::vector<std::string> primary_key;  // in key order
  bool Has(const std::string& c) const { return std::find(all.begin(), all.end(), c) != all.end(); }
};

TableColumns ColumnsOf(const Connection& c, const std::string& table) {
  Statement s(c, "SELECT name, pk FROM pragma_table_info(?1) ORDER BY cid");
  s.Bind(1, table);
  TableColumns t;
  std::vector<std::pair<int64_t, std::string>> pk;
  while (s.Step()) {
    t.all.push_back(s.Text(0));
    if (s.Int64(1) > 0) pk.emplace_back(s.Int64(1), s.Text(0));
  }
  std::sort(pk.begin(), pk.end());
  for (auto& [order, name] : pk) t.primary_key.push_back(name);
  return t;
}

std::vector<std::string> UserTables(const Connection& c) {
  Statement s(c,
              "SELECT name FROM sqlite_schema WHERE type = 'table' AND name NOT LIKE 'sqlite_%' "
              "ORDER BY name");
  std::vector<std::string> out;
  while (s.Step()) out.push_back(s.Text(0));
  return out;
}

std::vector<std::pair<std::string, MergeTableRole>> TableRoles(const Connection& c) {
  std::vector<std::pair<std::string, MergeTableRole>> out;
  for (const std::string& table : UserTables(c)) {
    MergeTableRole role;
    if (table == "runs") {
      role = MergeTableRole::kRuns;
    } else if (ColumnsOf(c, table).Has("run_id")) {
      role = MergeTableRole::kRunRows;
    } else if (std::find(std::begin(kNotRunDataTables), std::end(kNotRunDataTables), table) !=
               std::end(kNotRunDataTables)) {
      role = MergeTableRole::kNotRunData;
    } else {
      throw InputError(fmt::format(
          "database '{}': table '{}' is unknown to merge (it has no run_id column and is not one "
          "of runs, {}); expected the tables of profiles_db/SCHEMA.md (written by a newer "
          "railwear, or changed outside railwear?); nothing of it was merged",
          c.path(), table, "meta, calibrations, calibration_inputs"));
    }
    out.emplace_back(table, role);
  }
  return out;
}

std::string Join(const std::vector<std::string>& names, const std::string& prefix = "") {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + prefix + n;
  return out;
}

// True when the two column values are the same type and the same bits.
bool SameValue(sqlite3_stmt* a, sqlite3_stmt* b, int ca, int cb) {
  const int type = sqlite3_column_type(a, ca);
  if (type != sqlite3_column_type(b, cb)) return false;
  switch (type) {
    case SQLITE_NULL:
      return true;
    case SQLITE_INTEGER:
      return sqlite3_column_int64(a, ca) == sqlite3_column_int64(b, cb);
    case SQLITE_FLOAT:
      return std::bit_cast<uint64_t>(sqlite3_column_double(a, ca)) ==
             std::bit_cast<uint64_t>(sqlite3_column_double(b, cb));
    default: {
      const void* pa = type == SQLITE_TEXT ? static_cast<const void*>(sqlite3_column_text(a, ca))
                                           : sqlite3_column_blob(a, ca);
      const void* pb = type == SQLITE_TEXT ? static_cast<const void*>(sqlite3_column_text(b, cb))
                                           : sqlite3_column_blob(b, cb);
      const int na = sqlite3_column_bytes(a, ca);
      return na == sqlite3_column_bytes(b, cb) && (na == 0 || std::memcmp(pa, pb, na) == 0);
    }
  }
}

// The rows of `table` that belong to run `id` (`key` the run's key column), the compared
// columns only, in primary-key order.
std::string RunRowsSql(const std::string& table, const TableColumns& columns,
                       const std::vector<std::string>& compared, const char* key) {
  std::vector<std::string> order;
  for (const std::string& c : columns.primary_key) {
    if (!IgnoredInComparison(c)) order.push_back(c);
  }
  return fmt::format("SELECT {} FROM {} WHERE {} = ?1{}", compared.empty() ? "1" : Join(compared),
                     table, key, order.empty() ? "" : " ORDER BY " + Join(order));
}

// Why run `in_id` of `in` differs from run `out_id` of `out` (the first difference), or "" when
// they hold the same content in every table of `tables`.
std::string RunDifference(const Connection& in, int64_t in_id, const Connection& out,
                          int64_t out_id, const std::vector<std::string>& tables) {
  for (const std::string& table : tables) {
    const bool in_has = internal::TableExists(in, table);
    const TableColumns columns = ColumnsOf(out, table);
    std::vector<std::string> compared;
    const TableColumns in_columns = in_has ? ColumnsOf(in, table) : TableColumns{};
    for (const std::string& c : columns.all) {
      if (!IgnoredInComparison(c) && (!in_has || in_columns.Has(c))) compared.push_back(c);
    }
    const char* key = table == "runs" ? "id" : "run_id";
    Statement b(out, RunRowsSql(table, columns, compared, key));
    b.Bind(1, out_id);
    if (!in_has) {
      if (b.Step()) return fmt::format("table '{}' holds rows of it only in the output", table);
      continue;
    }
    Statement a(in, RunRowsSql(table, columns, compared, key));
    a.Bind(1, in_id);
    for (int64_t row = 0;; ++row) {
      const bool more_a = a.Step(), more_b = b.Step();
      if (!more_a && !more_b) break;
      if (more_a != more_b) {
        return fmt::format("table '{}' holds more rows of it in the {} (the {} has {})", table,
                           more_a ? "input" : "output", more_a ? "output" : "input", row);
      }
      for (size_t i = 0; i < compared.size(); ++i) {
        if (!SameValue(a.get(), b.get(), static_cast<int>(i), static_cast<int>(i))) {
          return fmt::format("table '{}', row {} (in primary-key order), column '{}' differs",
                             table, row, compared[i]);
        }
      }
    }
  }
  return "";
}

// Copies the rows of `table` of run `in_id` in `in` into `out` as rows of run `out_id`; every
// REAL is checked finite (a damaged input row is refused, not copied). Returns the rows copied.
int64_t CopyRunRows(const Connection& in, int64_t in_id, const Connection& out, int64_t out_id,
                    const std::string& table) {
  const TableColumns columns = ColumnsOf(in, table);
  const TableColumns out_columns = ColumnsOf(out, table);
  std::vector<std::string> placeholders;
  for (size_t i = 0; i < columns.all.size(); ++i) {
    if (!out_columns.Has(columns.all[i])) {
      throw InputError(fmt::format(
          "database '{}': table '{}' has a column '{}' that the output '{}' lacks; expected the "
          "columns of profiles_db/SCHEMA.md",
          in.path(), table, columns.all[i], out.path()));
    }
    placeholders.push_back(fmt::format("?{}", i + 1));
  }
  Statement read(in, fmt::format("SELECT {} FROM {} WHERE run_id = ?1", Join(columns.all), table));
  read.Bind(1, in_id);
  Statement write(out, fmt::format("INSERT INTO {}({}) VALUES ({})", table, Join(columns.all),
                                   Join(placeholders)));
  int64_t rows = 0;
  while (read.Step()) {
    sqlite3_reset(write.get());
    for (size_t i = 0; i < columns.all.size(); ++i) {
      const int col = static_cast<int>(i);
      if (columns.all[i] == "run_id") {
        write.Bind(col + 1, out_id);
        continue;
      }
      if (sqlite3_column_type(read.get(), col) == SQLITE_FLOAT) read.Double(col);  // finite?
      if (sqlite3_bind_value(write.get(), col + 1, sqlite3_column_value(read.get(), col)) !=
          SQLITE_OK) {
        internal::ThrowSqlite(out.get(), out.path(), "binding a merged value");
      }
    }
    write.Run();
    ++rows;
  }
  return rows;
}

}  // namespace

std::vector<std::pair<std::string, MergeTableRole>> ProfileStore::MergeTableRoles() const {
  return TableRoles(impl_->db);
}

MergeSummary ProfileStore::MergeRunsFrom(const ProfileStore& input) {
  const Connection& in = input.impl_->db;
  const Connection& out = impl_->db;
  std::vector<std::string> run_tables;  // the output's: a superset of an older input's
  for (const auto& [table, role] : TableRoles(out)) {
    if (role == MergeTableRole::kRunRows) run_tables.push_back(table);
  }
  Transaction snapshot(in, "BEGIN");  // one consistent view of the input
  MergeSummary summary;
  for (const auto& [table, role] : TableRoles(in)) {
    if (role == MergeTableRole::kRunRows &&
        std::find(run_tables.begin(), run_tables.end(), table) == run_tables.end()) {
      throw InputError(fmt::format(
          "database '{}': table '{}' holds run rows but the output '{}' has no such table; "
          "expected the tables of profiles_db/SCHEMA.md",
          in.path(), table, out.path()));
    }
    if (table == "calibrations") {
      Statement s(in, "SELECT count(*) FROM calibrations");
      if (s.Step()) summary.calibrations_left = static_cast<int>(s.Int64(0));
    }
  }
  std::vector<std::string> compared_tables = {"runs"};
  compared_tables.insert(compared_tables.end(), run_tables.begin(), run_tables.end());

  Transaction t(out);
  // Rows are inserted table by table; the references between them are checked at the commit.
  out.Exec("PRAGMA defer_foreign_keys = ON");
  Statement runs(in, fmt::format("SELECT {} FROM runs ORDER BY id", internal::kRunColumns));
  while (runs.Step()) {
    const RunInfo run = internal::ReadRun(runs);
    if (const std::optional<RunInfo> there = FindRun(run.name)) {
      const std::string why = RunDifference(in, run.id, out, there->id, compared_tables);
      if (!why.empty()) {
        throw InputError(fmt::format(
            "database '{}': run '{}' conflicts with the run of that name in '{}' ({}); expected "
            "the same content (a run is identified by its name: merge runs of different "
            "studies under different names); nothing of '{}' was merged",
            in.path(), run.name, path(), why, in.path()));
      }
      ++summary.runs_identical;
      continue;
    }
    Statement insert(out, fmt::format("INSERT INTO runs(name, created_utc, program_version, "
                                      "scene_text, wear_law_json, state) VALUES (?1, ?2, ?3, ?4, "
                                      "?5, ?6)"));
    insert.Bind(1, run.name).Bind(2, run.created_utc).Bind(3, run.program_version);
    insert.Bind(4, run.scene_text).Bind(5, run.wear_law_json).Bind(6, ToString(run.state));
    insert.Run();
    const int64_t id = sqlite3_last_insert_rowid(out.get());
    ++summary.rows_copied;
    for (const std::string& table : run_tables) {
      if (internal::TableExists(in, table))
        summary.rows_copied += CopyRunRows(in, run.id, out, id, table);
    }
    ++summary.runs_copied;
  }
  if (Statement check(out, "PRAGMA foreign_key_check"); check.Step()) {
    throw InputError(fmt::format(
        "database '{}': its rows in table '{}' reference rows it does not have; expected a "
        "consistent railwear database (changed outside railwear?); nothing of it was merged",
        in.path(), check.Text(0)));
  }
  impl_->RequireSameFile();
  t.Commit();
  return summary;
}

QueryResult ProfileStore::Query(const std::string& sql) const {
  // A file database gets its own read-only connection: SQLite itself refuses any write there.
  // ":memory:" cannot be shared with a second connection, so it is queried here, query_only.
  std::optional<Connection> own;
  if (!impl_->in_memory && !impl_->read_only) own.emplace(path(), SQLITE_OPEN_READONLY);
  const Connection& c = own ? *own : impl_->db;
  c.Exec("PRAGMA query_only = ON");
  // sqlite3_stmt_readonly() accepts ATTACH, DETACH and transaction control, which would change
  // the connection (or create an attached file): the authorizer refuses them at prepare time.
  sqlite3_set_authorizer(c.get(), &internal::QueryAuthorizer, nullptr);
  struct Restore {
    const Connection& c;
    bool read_only;
    ~Restore() {
      sqlite3_set_authorizer(c.get(), nullptr, nullptr);
      if (!read_only) sqlite3_exec(c.get(), "PRAGMA query_only = OFF", nullptr, nullptr, nullptr);
    }
  } restore{c, impl_->read_only};

  sqlite3_stmt* raw = nullptr;
  const char* tail = nullptr;
  if (sqlite3_prepare_v2(c.get(), sql.c_str(), static_cast<int>(sql.size()), &raw, &tail) !=
      SQLITE_OK) {
    const std::string msg = sqlite3_errmsg(c.get());
    sqlite3_finalize(raw);
    throw InputError(
        fmt::format("query on '{}': {}; expected one read-only SQL statement "
                    "(see profiles_db/SCHEMA.md)",
                    path(), msg));
  }
  std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> stmt(raw, &sqlite3_finalize);
  if (!stmt) throw InputError(fmt::format("query on '{}': empty; expected a SELECT", path()));
  for (const char* p = tail; p && *p; ++p) {
    if (!std::isspace(static_cast<unsigned char>(*p)) && *p != ';') {
      throw InputError(
          fmt::format("query on '{}': more than one statement ('{}'); expected one", path(), p));
    }
  }
  if (!sqlite3_stmt_readonly(stmt.get())) {
    throw InputError(
        fmt::format("query on '{}': '{}' would modify the database; expected a "
                    "read-only statement such as SELECT",
                    path(), sql));
  }
  QueryResult result;
  const int n = sqlite3_column_count(stmt.get());
  for (int i = 0; i < n; ++i) result.columns.emplace_back(sqlite3_column_name(stmt.get(), i));
  int rc;
  while ((rc = sqlite3_step(stmt.get())) == SQLITE_ROW) {
    std::vector<std::string> row;
    row.reserve(n);
    for (int i = 0; i < n; ++i) {
      switch (sqlite3_column_type(stmt.get(), i)) {
        case SQLITE_NULL:
          row.emplace_back("NULL");
          break;
        case SQLITE_BLOB:
          row.push_back(fmt::format("<blob {} bytes>", sqlite3_column_bytes(stmt.get(), i)));
          break;
        default:
          row.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(stmt.get(), i)),
                           static_cast<size_t>(sqlite3_column_bytes(stmt.get(), i)));
      }
    }
    result.rows.push_back(std::move(row));
  }
  if (rc != SQLITE_DONE) {
    const int code = rc & 0xff;
    const std::string msg = sqlite3_errmsg(c.get());
    if (code == SQLITE_READONLY || code == SQLITE_ERROR || code == SQLITE_CONSTRAINT) {
      throw InputError(
          fmt::format("query on '{}': {}; expected one read-only SQL statement", path(), msg));
    }
    throw std::runtime_error(fmt::format("query on '{}' failed: {}", path(), msg));
  }
  return result;
}

}  // namespace railwear
