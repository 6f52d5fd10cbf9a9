// Test support for suites that build databases by hand (foreign, future-version or damaged
// files) with the raw SQLite C API: profiles_db_tests and app_tests link SQLite for this.
#pragma once

#include <sqlite3.h>

#include <string>

#include <gtest/gtest.h>

namespace railwear::test {

// Runs `sql` (one or more statements) on the database file `path`, creating it when missing.
inline void RawExec(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err);
  const std::string msg = err ? err : "";
  sqlite3_free(err);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << msg;
}

}  // namespace railwear::test
