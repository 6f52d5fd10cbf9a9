// Issue 17, point 7: a wear study stores each step's warnings (p_max beyond the hardness, L/V
// beyond Nadal's limit) in its database (schema 8, table step_warnings) and `history steps`
// shows them (table and --json); a database of schema 7 is read as it is (no warnings) and
// migrated by the next write.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"
#include "tests/sqlite_test_support.h"

namespace railwear::test {
namespace {

// The small study with a rail hardness of 500 MPa: every gauge-corner case is beyond it.
std::string OverloadedStudy() {
  std::string text = kSmallWearStudy;
  const std::string from = "hardness_MPa = 2600";
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos);
  return text.replace(at, from.size(), "hardness_MPa = 500");
}

TEST_F(CliFixture, AnOverloadedStudyStoresAndShowsItsWarnings) {
  Write("study.toml", OverloadedStudy());
  const Outcome o = Run("wear study.toml --db s.sqlite --steps 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.err, "warning: step 1: p_max beyond the hardness in 3 of 3 load cases"))
      << o.err;
  EXPECT_TRUE(Contains(o.err, "warning: step 1: flange climb possible in 1 of 3")) << o.err;

  const Outcome table = Run("history --db s.sqlite steps 'small study'");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  // On stderr, so that stdout stays the table.
  for (const char* step : {"railwear: step 1 warning hardness: p_max beyond the hardness in 3 of 3",
                           "railwear: step 2 warning hardness: p_max beyond the hardness in 3 of 3",
                           "railwear: step 1 warning flange_climb: flange climb possible in 1 of 3"}) {
    EXPECT_TRUE(Contains(table.err, step)) << table.err;
  }
  EXPECT_TRUE(Contains(table.err, "exceeds the rail's hardness 500 MPa")) << table.err;
  EXPECT_FALSE(Contains(table.err, "step 0 warning")) << table.err;
  EXPECT_FALSE(Contains(table.out, "warning")) << table.out;

  const Outcome js = Run("history --db s.sqlite steps 'small study' --json");
  ASSERT_EQ(js.exit_code, 0) << js.err;
  const nlohmann::json j = nlohmann::json::parse(js.out);
  EXPECT_EQ(j["schema_version"], ProfileStore::kSchemaVersion);
  ASSERT_EQ(j["steps"].size(), 3u);
  EXPECT_TRUE(j["steps"][0]["warnings"].empty());
  for (int k : {1, 2}) {
    // The study's flange case also climbs (L/V 1.6 against Nadal's 1.1): both kinds, in order.
    const nlohmann::json& w = j["steps"][k]["warnings"];
    ASSERT_EQ(w.size(), 2u) << w;
    EXPECT_EQ(w[0]["kind"], "flange_climb");
    EXPECT_TRUE(Contains(w[0]["message"].get<std::string>(), "exceeds Nadal's limit"));
    EXPECT_EQ(w[1]["kind"], "hardness");
    EXPECT_TRUE(Contains(w[1]["message"].get<std::string>(), "hardness 500 MPa"));
    EXPECT_GT(j["steps"][k]["max_depth_mm"].get<double>(), 0.0);
  }
  EXPECT_TRUE(j["steps"][0]["w2_mm_per_mgt"].is_null());

  // A pressure limit at the hardness holds p_max there: no hardness warning, the climb stays.
  std::string limited = OverloadedStudy();
  limited.replace(limited.find("[model]\n"), 8, "[model]\npressure_limit = \"hardness\"\n");
  Write("limited.toml", limited);
  ASSERT_EQ(Run("wear limited.toml --db l.sqlite --steps 1").exit_code, 0);
  const Outcome l = Run("history --db l.sqlite steps 'small study' --json");
  const nlohmann::json lw = nlohmann::json::parse(l.out)["steps"][1]["warnings"];
  ASSERT_EQ(lw.size(), 1u) << lw;
  EXPECT_EQ(lw[0]["kind"], "flange_climb");

  EXPECT_EQ(Run("history --db s.sqlite steps 'small study' --json --wheel 0").exit_code, 2);
}

TEST_F(CliFixture, ASchema7StudyReadsAsItIsAndMigratesOnWrite) {
  Write("study.toml", OverloadedStudy());
  ASSERT_EQ(Run("wear study.toml --db s.sqlite --steps 1").exit_code, 0);
  // Schema 7: no step_warnings table (what railwear before this change wrote).
  RawExec((dir_ / "s.sqlite").string(),
          "DROP TABLE step_warnings; DROP TABLE run_failures; PRAGMA user_version = 7;");
  const Outcome table = Run("history --db s.sqlite steps 'small study'");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_FALSE(Contains(table.err, "warning")) << table.err;
  const Outcome js = Run("history --db s.sqlite steps 'small study' --json");
  ASSERT_EQ(js.exit_code, 0) << js.err;
  EXPECT_EQ(nlohmann::json::parse(js.out)["schema_version"], 7);  // read, not migrated
  // The next write migrates; the resumed step stores its warning.
  const Outcome resumed = Run("wear study.toml --db s.sqlite --resume --steps 1");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const nlohmann::json after =
      nlohmann::json::parse(Run("history --db s.sqlite steps 'small study' --json").out);
  EXPECT_EQ(after["schema_version"], ProfileStore::kSchemaVersion);
  EXPECT_TRUE(after["steps"][1]["warnings"].empty());  // stored under schema 7
  ASSERT_EQ(after["steps"][2]["warnings"].size(), 2u);
  EXPECT_EQ(after["steps"][2]["warnings"][1]["kind"], "hardness");
}

}  // namespace
}  // namespace railwear::test
