// Uncertainty ensembles and rail-life answers end to end (issue 19 points 4 and 5): a plan with
// distribution axes gives the same samples bit for bit from its seed and records them in the
// manifest and the lines' scenes; bad plans and axes exit 2 naming the key; `history bands` on a
// study of stored runs equals hand-computed percentiles of the stored values; `history life` on
// constant wear rates equals limit / rate, per class and for the line; a small real ensemble
// swept, merged and banded.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/scene.h"
#include "app/sweep_plan.h"
#include "core/profile/builtin_profiles.h"
#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/sweep_test_support.h"
#include "wear/wear_simulation.h"

namespace railwear::test {
namespace {

// Two yaw angles (the curve classes) x 4 samples of the wear coefficient and friction.
const char* const kEnsemblePlan = R"([sweep]
scene = "base.toml"
out_dir = "runs"
samples = 4
seed = 7

[[axis]]
key = "traffic[0].yaw_mrad"
values = [4.0, 6.0]

[[axis]]
key = "wear.k"
distribution = { kind = "lognormal" }

[[axis]]
key = "traffic[0].friction"
distribution = { kind = "uniform", min = 0.3, max = 0.5 }

[life]
annual_mgt = 20
[[life.limit]]
name = "grinding"
measure = "w2_mm"
value = 0.6
[[life.class]]
match = "traffic[0].yaw_mrad=4.0"
length_km = 3
[[life.class]]
match = "traffic[0].yaw_mrad=6.0"
length_km = 1
)";

// R's / NumPy's default percentile ("type 7"), by hand: rank (n - 1) p between order statistics.
double HandPercentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double h = (v.size() - 1) * p / 100.0;
  const size_t lo = static_cast<size_t>(std::floor(h));
  if (lo + 1 >= v.size()) return v.back();
  return v[lo] + (h - lo) * (v[lo + 1] - v[lo]);
}

class SweepEnsembleTest : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    Write("base.toml", SmallStudyOfPasses("5e4"));
    Write("plan.toml", kEnsemblePlan);
  }
  app::SweepPlan Plan() const { return app::LoadSweepPlan((dir_ / "plan.toml").string()); }

  // study.sqlite: one complete run per line of the plan, named by its id, whose W2 at the stored
  // MGT is w2(line index, MGT).
  void BuildStudy(const std::vector<double>& mgt,
                  const std::function<double(int, double)>& w2) const {
    ProfileStore db = ProfileStore::Open((dir_ / "study.sqlite").string());
    const Profile rail = MakeUic60();
    for (const app::SweepLine& line : Plan().lines) {
      RunInfo info;
      info.name = line.id;
      info.program_version = "test";
      info.scene_text = line.scene_text;
      const int64_t run = db.CreateRun(info);
      for (size_t k = 0; k < mgt.size(); ++k) {
        StepRecord step;
        step.step = static_cast<int>(k);
        step.passes = mgt[k] * 62500.0;
        step.mgt = mgt[k];
        step.w2_mm = w2(line.index, mgt[k]);
        step.w3_mm = 2.0 * step.w2_mm;
        step.profile = rail;
        db.AppendStep(run, step);
      }
      db.SetRunState(run, RunState::kComplete);
    }
  }
};

TEST_F(SweepEnsembleTest, SeededPlanGivesTheSameSamplesBitForBitAndRecordsThem) {
  const app::SweepPlan a = Plan(), b = Plan();
  ASSERT_TRUE(a.ensemble.has_value());
  ASSERT_EQ(a.lines.size(), 8u);  // 2 classes x 4 samples
  for (size_t i = 0; i < a.lines.size(); ++i) {
    EXPECT_EQ(a.lines[i].id, b.lines[i].id);
    EXPECT_EQ(a.lines[i].scene_text, b.lines[i].scene_text);
  }
  const std::vector<std::vector<double>>& drawn = a.ensemble->values;
  for (const app::SweepLine& line : a.lines) {
    // The classes vary slowest (the yaw axis comes first); each class has every sample.
    EXPECT_EQ(line.sample, line.index % 4);
    EXPECT_EQ(line.group, line.index < 4 ? "traffic[0].yaw_mrad=4.0" : "traffic[0].yaw_mrad=6.0");
    EXPECT_TRUE(Contains(line.scene_text, "# railwear ensemble sample " +
                                              std::to_string(line.sample) +
                                              " of 4 (latin-hypercube, seed 7)"));
    // The value written is the drawn double, bit for bit, and the scene reads it back so.
    ASSERT_EQ(line.overrides.size(), 3u);
    const double k = std::stod(line.overrides[1].value);
    EXPECT_EQ(std::memcmp(&k, &drawn[line.sample][0], sizeof(double)), 0) << line.overrides[1].value;
    const app::Scene scene = app::SweepLineScene(a, line);
    const double read = scene.wear->options.law.archard_k;
    EXPECT_EQ(std::memcmp(&read, &drawn[line.sample][0], sizeof(double)), 0);
    const double mu = std::stod(line.overrides[2].value);
    EXPECT_GE(mu, 0.3);
    EXPECT_LT(mu, 0.5);
  }
  // The log-normal's default median is the base scene's k (1e-4): half the samples each side
  // (one per stratum of 4).
  EXPECT_EQ(std::count_if(drawn.begin(), drawn.end(),
                          [](const std::vector<double>& s) { return s[0] < 1e-4; }),
            2);

  // The manifest lists the sampled values; the same from a second call; another seed differs.
  const Outcome list = Run("sweep plan.toml --list");
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_EQ(Run("sweep plan.toml --list").out, list.out);
  EXPECT_TRUE(Contains(list.out, "traffic[0].yaw_mrad=4.0 wear.k=" + a.lines[0].overrides[1].value +
                                     " traffic[0].friction=" + a.lines[0].overrides[2].value));
  EXPECT_TRUE(Contains(list.err, "an ensemble of 4 sample(s) per curve class (latin-hypercube, "
                                 "seed 7) of wear.k, traffic[0].friction"));
  std::string reseeded = kEnsemblePlan;
  reseeded.replace(reseeded.find("seed = 7"), 8, "seed = 8");
  Write("plan8.toml", reseeded);
  const Outcome other = Run("sweep plan8.toml --list");
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(ManifestIds(other.out), ManifestIds(list.out));
  // Sobol: reproducible too.
  std::string sobol = kEnsemblePlan;
  sobol.replace(sobol.find("seed = 7"), 8, "seed = 7\nsampling = \"sobol\"");
  Write("sobol.toml", sobol);
  const Outcome s1 = Run("sweep sobol.toml --list"), s2 = Run("sweep sobol.toml --list");
  ASSERT_EQ(s1.exit_code, 0) << s1.err;
  EXPECT_EQ(s1.out, s2.out);
  EXPECT_NE(s1.out, list.out);
}

TEST_F(SweepEnsembleTest, BadPlansAndAxesExitTwoNamingTheKey) {
  struct Case {
    std::string from, to, expected;
  };
  const std::vector<Case> cases = {
      {"samples = 4\n", "", "key 'sweep.samples'"},
      {"kind = \"lognormal\"", "kind = \"gamma\"", "kind' = \"gamma\""},
      {"kind = \"lognormal\"", "kind = \"lognormal\", sigma_ln = -0.2", "sigma_ln"},
      {"min = 0.3, max = 0.5", "min = 0.5, max = 0.3", "min 0.5 and max 0.3: expected min < max"},
      {"min = 0.3, max = 0.5", "min = 0.3", "key 'axis[2].distribution.max'"},
      {"measure = \"w2_mm\"", "measure = \"w9_mm\"", "measure' = \"w9_mm\""},
      {"distribution = { kind = \"lognormal\" }",
       "distribution = { kind = \"lognormal\" }\nvalues = [1.0]",
       "key 'axis[1].values'"},
      {"key = \"wear.k\"", "key = \"wear.k_missing\"", "median"},
      {"samples = 4", "samples = 0", "samples"},
      {"seed = 7", "seed = -1", "seed"},
      {"length_km = 3", "length_km = -3", "length_km"},
  };
  for (const Case& c : cases) {
    std::string plan = kEnsemblePlan;
    ASSERT_NE(plan.find(c.from), std::string::npos) << c.from;
    plan.replace(plan.find(c.from), c.from.size(), c.to);
    Write("bad.toml", plan);
    const Outcome o = Run("sweep bad.toml --list");
    EXPECT_EQ(o.exit_code, 2) << c.to << "\n" << o.err;
    EXPECT_TRUE(Contains(o.err, "bad.toml:")) << o.err;
    EXPECT_TRUE(Contains(o.err, c.expected)) << o.err;
  }
  // samples without a distribution axis.
  Write("nodist.toml", "[sweep]\nscene = \"base.toml\"\nsamples = 4\n");
  const Outcome o = Run("sweep nodist.toml --list");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(Contains(o.err, "nodist.toml:3: key 'sweep.samples'")) << o.err;
}

TEST_F(SweepEnsembleTest, BandsAreHandComputedPercentilesOfTheStoredRuns) {
  // Stored at the grid's MGT (0 to 2 in 5 points), a different curve per line.
  const std::vector<double> mgt = {0.0, 0.5, 1.0, 1.5, 2.0};
  const auto w2 = [](int line, double m) {
    return (0.2 + 0.07 * ((line * 5) % 8)) * std::pow(m, 1.3);
  };
  BuildStudy(mgt, w2);
  const Outcome o = Run(
      "history --db study.sqlite bands --plan plan.toml --measures w2_mm,w3_mm --points 5 "
      "--format json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  ASSERT_EQ(j["classes"].size(), 2u);
  for (int c = 0; c < 2; ++c) {
    const nlohmann::json& cls = j["classes"][c];
    EXPECT_EQ(cls["runs"].size(), 4u);
    for (size_t k = 0; k < mgt.size(); ++k) {
      std::vector<double> stored;
      for (int s = 0; s < 4; ++s) stored.push_back(w2(4 * c + s, mgt[k]));
      EXPECT_EQ(cls["measures"]["w2_mm"]["mgt"][k].get<double>(), mgt[k]);
      for (const auto& [p, name] :
           std::vector<std::pair<double, std::string>>{{5.0, "p5"}, {50.0, "p50"}, {95.0, "p95"}}) {
        const double hand = HandPercentile(stored, p);
        // The same two order statistics combined; GSL writes (1 - d) a + d b, the hand a + d (b
        // - a): a few units in the last place of values below 2.
        EXPECT_NEAR(cls["measures"]["w2_mm"][name][k].get<double>(), hand, 1e-15) << name << k;
        EXPECT_NEAR(cls["measures"]["w3_mm"][name][k].get<double>(), 2.0 * hand, 2e-15);
      }
    }
  }
  // The table and the CSV carry the same numbers.
  const Outcome csv =
      Run("history --db study.sqlite bands --plan plan.toml --measures w2_mm --points 5 "
          "--format csv --percentiles 50");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_TRUE(Contains(csv.out, "class,measure,MGT,runs,p50\n"));
  std::vector<double> last;
  for (int s = 0; s < 4; ++s) last.push_back(w2(s, 2.0));
  const std::string row = "traffic[0].yaw_mrad=4.0,w2_mm,2,4,";
  ASSERT_TRUE(Contains(csv.out, row)) << csv.out;
  const size_t at = csv.out.find(row) + row.size();
  EXPECT_NEAR(std::stod(csv.out.substr(at, csv.out.find('\n', at) - at)),
              HandPercentile(last, 50.0), 1e-15);
  const Outcome table = Run("history --db study.sqlite bands --measures w2_mm --points 3");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_TRUE(Contains(table.out, "(all runs)  w2_mm")) << table.out;
  EXPECT_TRUE(Contains(table.err, "1 class(es), 8 run(s)")) << table.err;
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    const Outcome plot =
        Run("history --db study.sqlite bands --plan plan.toml --measures w2_mm --plot ens");
    ASSERT_EQ(plot.exit_code, 0) << plot.err;
    EXPECT_GT(fs::file_size(dir_ / "ens_bands.png"), 1000u);
  }
  // Bad options: exit 2 naming them.
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--measures w7_mm", "--measures 'w7_mm'"},
           {"--percentiles 50,5", "--percentiles 50,5"},
           {"--format xml", "--format 'xml'"},
           {"--points 1", "--points 1"}}) {
    const Outcome bad = Run("history --db study.sqlite bands " + args);
    EXPECT_EQ(bad.exit_code, 2) << args;
    EXPECT_TRUE(Contains(bad.err, expected)) << bad.err;
  }
}

TEST_F(SweepEnsembleTest, LifeOnConstantWearRatesIsLimitOverRate) {
  // W2 = r m at uneven steps up to 3 MGT; line 7's rate never reaches the 0.6 mm limit.
  const std::vector<double> mgt = {0.0, 0.33, 0.8, 1.45, 2.1, 3.0};
  const auto rate = [](int line) { return line == 7 ? 0.1 : 0.25 + 0.05 * line; };
  BuildStudy(mgt, [&](int line, double m) { return rate(line) * m; });
  const Outcome o = Run("history --db study.sqlite life --plan plan.toml --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  ASSERT_EQ(j["runs"].size(), 8u);
  std::vector<double> life;
  for (int line = 0; line < 8; ++line) {
    const nlohmann::json& run = j["runs"][line];
    if (line == 7) {
      EXPECT_TRUE(run["mgt"][0].is_null());
      life.push_back(INFINITY);
      continue;
    }
    const double expected = 0.6 / rate(line);
    // Linear between stored steps on a linear history: exact up to rounding.
    EXPECT_NEAR(run["mgt"][0].get<double>(), expected, 1e-12 * expected) << line;
    EXPECT_NEAR(run["years"][0].get<double>(), expected / 20.0, 1e-12 * expected);
    life.push_back(expected);
  }
  // Per class: the percentiles of its runs' lives.
  const std::vector<double> first(life.begin(), life.begin() + 4);
  EXPECT_NEAR(j["classes"][0]["mgt"][0]["p50"].get<double>(), HandPercentile(first, 50.0), 1e-12);
  EXPECT_NEAR(j["classes"][0]["mgt"][0]["p5"].get<double>(), HandPercentile(first, 5.0), 1e-12);
  // The second class's 95 % needs the run that never reached the limit: not reached (null).
  EXPECT_TRUE(j["classes"][1]["mgt"][0]["p95"].is_null());
  // The line: class 1 (3 km) weighs 3/4 km per run, class 2 (1 km) 1/4 km per run. Sorted
  // lives: class 2's three reached ones (shortest, lines 4-6 have the highest rates) first:
  // 3 x 0.25 = 0.75 km of 4 km = 18.75 %; so the 5 % of the line is the shortest of them.
  EXPECT_NEAR(j["line"]["mgt"][0]["p5"].get<double>(), 0.6 / rate(6), 1e-12);
  EXPECT_EQ(j["line"]["length_km"].get<double>(), 4.0);
  // The text tables say the same.
  const Outcome text = Run("history --db study.sqlite life --plan plan.toml");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_TRUE(Contains(text.out, "Per curve class")) << text.out;
  EXPECT_TRUE(Contains(text.out, "not_reached"));
  EXPECT_TRUE(Contains(text.out, "Line (runs weighted"));
  // --limit on the command line, without a plan: every complete run.
  const Outcome cli = Run("history --db study.sqlite life --limit w3_mm=1.2 --annual-mgt 10 --json");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const nlohmann::json k = nlohmann::json::parse(cli.out);
  EXPECT_NEAR(k["runs"][0]["mgt"][0].get<double>(), 1.2 / (2.0 * rate(0)), 1e-12);
  // Bad limits and a plan whose runs are missing: exit 2, named.
  const Outcome bad = Run("history --db study.sqlite life --limit w9_mm=3");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "--limit 'w9_mm=3': measure 'w9_mm'")) << bad.err;
  const Outcome none = Run("history --db study.sqlite life");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_TRUE(Contains(none.err, "no limits")) << none.err;
  std::string other = kEnsemblePlan;
  other.replace(other.find("seed = 7"), 8, "seed = 9");
  Write("other.toml", other);
  const Outcome missing = Run("history --db study.sqlite life --plan other.toml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(Contains(missing.err, "8 of 8 line(s) have no complete run")) << missing.err;
  std::string unknown = kEnsemblePlan;
  const std::string six = "match = \"traffic[0].yaw_mrad=6.0\"";
  unknown.replace(unknown.find(six), six.size(), "match = \"track.radius_m=600\"");
  Write("unknown.toml", unknown);
  const Outcome cls = Run("history --db study.sqlite life --plan unknown.toml");
  EXPECT_EQ(cls.exit_code, 2);
  EXPECT_TRUE(Contains(cls.err, "key 'match' = \"track.radius_m=600\"")) << cls.err;
}

// Both rails of a curve (issue 19): a run's life to a limit is the earlier of its high and low
// rail's, and the output names the rail that governs. Constant wear rates on both rails
// (W2 = r MGT, stored at uneven steps to 3 MGT), limit W2 = 0.6 mm, by hand:
//   run    high rate  low rate  high life  low life  life  governs
//   a      0.30       0.40      2.0        1.5       1.5   low
//   b      0.50       0.20      1.2        3.0       1.2   high
//   c      0.10       0.10      -          -         -     - (0.3 mm at 3 MGT: not reached)
//   d      0.25       0.25      2.4        2.4       2.4   both
// The class's median: sorted 1.2, 1.5, 2.4, inf; rank 1.5: (1.5 + 2.4) / 2 = 1.95 MGT.
TEST_F(SweepEnsembleTest, LifeOfBothRailsIsTheEarlierAndNamesTheGoverningRail) {
  const std::vector<double> mgt = {0.0, 0.5, 1.1, 1.7, 2.6, 3.0};
  const std::vector<std::tuple<std::string, double, double>> runs = {
      {"a", 0.30, 0.40}, {"b", 0.50, 0.20}, {"c", 0.10, 0.10}, {"d", 0.25, 0.25}};
  {
    ProfileStore db = ProfileStore::Open((dir_ / "rails.sqlite").string());
    const Profile rail = MakeUic60();
    for (const auto& [name, high, low] : runs) {
      RunInfo info;
      info.name = name;
      info.program_version = "test";
      info.scene_text = "two rails " + name;
      const int64_t run = db.CreateRun(info);
      for (size_t k = 0; k < mgt.size(); ++k) {
        StepRecord step;
        step.step = static_cast<int>(k);
        step.mgt = mgt[k];
        step.passes = mgt[k] * 62500.0;
        step.w2_mm = high * mgt[k];
        step.profile = rail;
        RailStepRecord l;
        l.w2_mm = low * mgt[k];
        l.profile = rail;
        step.low_rail = l;
        db.AppendStep(run, step);
      }
      db.SetRunState(run, RunState::kComplete);
    }
  }
  const Outcome o = Run("history --db rails.sqlite life --rail both --limit w2_mm=0.6 --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  ASSERT_EQ(j["runs"].size(), 4u);
  // Linear between stored steps on linear histories: exact up to rounding.
  constexpr double kRounding = 1e-12;
  const std::vector<double> hand = {1.5, 1.2, INFINITY, 2.4};
  const std::vector<std::string> governs = {"low", "high", "", "both"};
  for (size_t r = 0; r < 4; ++r) {
    const nlohmann::json& run = j["runs"][r];
    EXPECT_EQ(run["run"], std::get<0>(runs[r]));
    if (std::isfinite(hand[r])) {
      EXPECT_NEAR(run["mgt"][0].get<double>(), hand[r], kRounding) << r;
      EXPECT_EQ(run["governing_rail"][0], governs[r]) << r;
    } else {
      EXPECT_TRUE(run["mgt"][0].is_null());
      EXPECT_TRUE(run["governing_rail"][0].is_null());
    }
  }
  EXPECT_NEAR(j["classes"][0]["mgt"][0]["p50"].get<double>(), 1.95, kRounding);
  EXPECT_EQ(j["classes"][0]["governing_rail"][0], "high 1, low 1, both 1");
  // One rail at a time: run a's high rail alone lasts 2.0 MGT, its low rail 1.5.
  const Outcome high = Run("history --db rails.sqlite life --limit w2_mm=0.6 --json");
  ASSERT_EQ(high.exit_code, 0) << high.err;
  EXPECT_NEAR(nlohmann::json::parse(high.out)["runs"][0]["mgt"][0].get<double>(), 2.0, kRounding);
  EXPECT_FALSE(nlohmann::json::parse(high.out)["runs"][0].contains("governing_rail"));
  const Outcome low = Run("history --db rails.sqlite life --rail low --limit w2_mm=0.6 --json");
  ASSERT_EQ(low.exit_code, 0) << low.err;
  EXPECT_NEAR(nlohmann::json::parse(low.out)["runs"][0]["mgt"][0].get<double>(), 1.5, kRounding);
  // The table names the rail per run and counts it per class.
  const Outcome table = Run("history --db rails.sqlite life --rail both --limit w2_mm=0.6");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_TRUE(Contains(table.out, "governing_rail")) << table.out;
  EXPECT_TRUE(Contains(table.out, "high 1, low 1, both 1")) << table.out;
  // bands take one rail; a one-rail study cannot give both.
  const Outcome bands = Run("history --db rails.sqlite bands --rail both");
  EXPECT_EQ(bands.exit_code, 2);
  EXPECT_TRUE(Contains(bands.err, "--rail 'both'")) << bands.err;
  BuildStudy({0.0, 1.0}, [](int, double m) { return m; });
  const Outcome one = Run("history --db study.sqlite life --rail both --limit w2_mm=0.6");
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_TRUE(Contains(one.err, "has one rail only; expected two-rail runs")) << one.err;
}

// A real failing sample (issue 19; kFailingSamplePlan): the 0.0037 mm cell's run fails at once
// ("the contact solution did not converge ... choose ... a larger model.cell_mm"), the other
// two complete in about a second each. The sweep goes on past it and exits 3 naming it; --merge
// merges the two complete runs and the failed one with its error and exits 3; bands and life use
// the two and name the failed one.
TEST_F(SweepEnsembleTest, AFailedSampleIsRecordedMergedNamedAndLeftOutOfBandsAndLife) {
  Write("fbase.toml", FailingSampleBase());
  Write("fail.toml", kFailingSamplePlan);
  // The design: exactly one sample below 0.01 mm (fails), the others at 1 mm or more (fast).
  const app::SweepPlan plan = app::LoadSweepPlan((dir_ / "fail.toml").string());
  int failing = -1;
  for (const app::SweepLine& line : plan.lines) {
    const double cell = std::stod(line.overrides[1].value);
    if (cell < 0.01) {
      ASSERT_EQ(failing, -1);
      failing = line.index;
    } else {
      ASSERT_GE(cell, 1.0);
    }
  }
  ASSERT_GE(failing, 0);
  const app::SweepLine& bad = plan.lines[static_cast<size_t>(failing)];
  const std::string cell_value = "model.cell_mm[0]=" + bad.overrides[1].value;
  const std::string error = "the contact solution did not converge";

  // The sweep runs every line, names the failed one (id, values, error) and exits 3.
  const Outcome sweep = Run("sweep fail.toml");
  EXPECT_EQ(sweep.exit_code, 3) << sweep.err;
  EXPECT_TRUE(Contains(sweep.err, "railwear: warning: sweep fail.toml: 1 of 3 run(s) failed"))
      << sweep.err;
  EXPECT_TRUE(Contains(sweep.err, "line " + std::to_string(failing) + " (" + bad.id + "; "))
      << sweep.err;
  EXPECT_TRUE(Contains(sweep.err, cell_value)) << sweep.err;
  EXPECT_TRUE(Contains(sweep.err, error)) << sweep.err;
  EXPECT_TRUE(Contains(sweep.err, "choose a coarser model.accuracy or a larger model.cell_mm"));
  {
    const ProfileStore line_db =
        ProfileStore::OpenReadOnly((dir_ / "fail_runs" / (bad.id + ".sqlite")).string());
    const RunInfo run = *line_db.FindRun(bad.id);
    EXPECT_EQ(run.state, RunState::kAborted);
    ASSERT_TRUE(line_db.FindRunFailure(run.id).has_value());
    EXPECT_TRUE(Contains(line_db.FindRunFailure(run.id)->message, error));
  }
  // The failing line alone: exit 1, as `wear`.
  EXPECT_EQ(Run("sweep fail.toml --index " + std::to_string(failing)).exit_code, 1);

  // The merge takes the complete runs and the failed one (with its error), names it, exits 3;
  // merging again changes nothing and says the same.
  for (int pass = 0; pass < 2; ++pass) {
    const Outcome merge = Run("sweep fail.toml --merge");
    EXPECT_EQ(merge.exit_code, 3) << merge.err;
    EXPECT_TRUE(
        Contains(merge.out, "failed run: line " + std::to_string(failing) + " (" + bad.id + "; "))
        << merge.out;
    EXPECT_TRUE(Contains(merge.out, error)) << merge.out;
    EXPECT_TRUE(Contains(merge.err, "1 of 3 run(s) failed and are merged into")) << merge.err;
  }
  {
    const ProfileStore study = ProfileStore::OpenReadOnly((dir_ / "fail_runs.sqlite").string());
    ASSERT_EQ(study.Runs().size(), 3u);
    const RunInfo run = *study.FindRun(bad.id);
    EXPECT_EQ(run.state, RunState::kAborted);
    EXPECT_TRUE(Contains(study.FindRunFailure(run.id)->message, error));
  }

  // bands: the two complete runs; the failed one named in the JSON, the table and on stderr.
  const Outcome bands =
      Run("history --db fail_runs.sqlite bands --plan fail.toml --measures worn_area_mm2 --format "
          "json");
  ASSERT_EQ(bands.exit_code, 0) << bands.err;
  const nlohmann::json j = nlohmann::json::parse(bands.out);
  EXPECT_EQ(j["classes"][0]["runs"].size(), 2u);
  ASSERT_EQ(j["failed_runs"].size(), 1u);
  EXPECT_EQ(j["failed_runs"][0]["run"], bad.id);
  EXPECT_TRUE(Contains(j["failed_runs"][0]["values"].get<std::string>(), cell_value));
  EXPECT_TRUE(Contains(j["failed_runs"][0]["error"].get<std::string>(), error));
  EXPECT_TRUE(Contains(bands.err,
                       "railwear: warning: 1 run(s) failed and are left out of the "
                       "bands"))
      << bands.err;
  const Outcome table =
      Run("history --db fail_runs.sqlite bands --plan fail.toml --measures worn_area_mm2");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_TRUE(Contains(table.out, "Failed runs (left out of the bands)")) << table.out;
  EXPECT_TRUE(Contains(table.out, bad.id)) << table.out;
  // Without --plan: the complete runs, the failed one named by its run name.
  const Outcome all =
      Run("history --db fail_runs.sqlite bands --measures worn_area_mm2 --format csv");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_TRUE(Contains(all.err, "run '" + bad.id + "': ")) << all.err;
  EXPECT_FALSE(Contains(all.out, bad.id));  // the CSV stays a table of numbers

  // life: per run and per class over the two complete runs; the class says 1 failed.
  const Outcome life = Run("history --db fail_runs.sqlite life --plan fail.toml --json");
  ASSERT_EQ(life.exit_code, 0) << life.err;
  const nlohmann::json l = nlohmann::json::parse(life.out);
  EXPECT_EQ(l["runs"].size(), 2u);
  EXPECT_EQ(l["classes"][0]["runs"], 2);
  EXPECT_EQ(l["classes"][0]["failed"], 1);
  ASSERT_EQ(l["failed_runs"].size(), 1u);
  EXPECT_EQ(l["failed_runs"][0]["run"], bad.id);
  const Outcome life_table = Run("history --db fail_runs.sqlite life --plan fail.toml");
  ASSERT_EQ(life_table.exit_code, 0) << life_table.err;
  EXPECT_TRUE(Contains(life_table.out, "Failed runs (no life: left out of the percentiles)"))
      << life_table.out;
  EXPECT_TRUE(Contains(life_table.err, "left out of the life percentiles")) << life_table.err;
}

// A small real ensemble: 3 samples of the wear coefficient, swept, merged, banded: the band's
// last point is the percentiles of the runs' stored W3 at the common final MGT.
TEST_F(SweepEnsembleTest, ASmallEnsembleSweptMergedAndBanded) {
  Write("base.toml", SmallStudyOfPasses("3e4"));
  Write("small.toml", R"([sweep]
scene = "base.toml"
out_dir = "small_runs"
samples = 3
seed = 2
[[axis]]
key = "wear.k"
distribution = { kind = "lognormal" }
)");
  const Outcome sweep = Run("sweep small.toml");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const Outcome merge = Run("sweep small.toml --merge");
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  const Outcome bands = Run(
      "history --db small_runs.sqlite bands --plan small.toml --measures worn_area_mm2 --format json");
  ASSERT_EQ(bands.exit_code, 0) << bands.err;
  const nlohmann::json j = nlohmann::json::parse(bands.out);
  const Outcome last = Run(
      "history --db small_runs.sqlite sql \"SELECT s.worn_area_mm2 FROM steps s JOIN runs r ON r.id = "
      "s.run_id WHERE s.step = (SELECT max(step) FROM steps t WHERE t.run_id = s.run_id)\" --tsv");
  ASSERT_EQ(last.exit_code, 0) << last.err;
  std::vector<double> area;
  std::istringstream in(last.out);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) area.push_back(std::stod(line));
  ASSERT_EQ(area.size(), 3u);
  const nlohmann::json& m = j["classes"][0]["measures"]["worn_area_mm2"];
  // The same total traffic for every run: the grid ends at the common final MGT, on the stored
  // last steps (SQL prints REAL with 17 significant digits: round trip).
  // (GSL's (1 - d) a + d b against the hand's a + d (b - a): a few units in the last place.)
  constexpr double kUlps = 1e-14;
  EXPECT_NEAR(m["p50"].back().get<double>(), HandPercentile(area, 50.0), kUlps * area[0]);
  EXPECT_NEAR(m["p5"].back().get<double>(), HandPercentile(area, 5.0), kUlps * area[0]);
  // Monotone in MGT (the worn area only grows; W3 is not used here: at these 3e4 passes it is
  // 3e-4 mm, of the order of its reading on spline profiles, and starts at -5e-10 mm).
  for (size_t k = 1; k < m["p50"].size(); ++k) {
    EXPECT_GE(m["p50"][k].get<double>(), m["p50"][k - 1].get<double>());
  }
  EXPECT_GT(m["p50"].back().get<double>(), 0.0);  // the runs did wear

  // RCF damage (the scene has effect "damage"): the largest value of each step's rcf_damage
  // distribution, read here through ProfileStore.
  std::vector<double> damage;
  {
    const ProfileStore db = ProfileStore::OpenReadOnly((dir_ / "small_runs.sqlite").string());
    for (const RunInfo& run : db.Runs()) {
      const StepRecord last = db.LoadStep(run.id, db.Steps(run.id).back().step);
      for (const Distribution& d : last.distributions) {
        if (d.kind == "rcf_damage") damage.push_back(*std::max_element(d.value.begin(), d.value.end()));
      }
    }
  }
  ASSERT_EQ(damage.size(), 3u);
  const Outcome rcf = Run(
      "history --db small_runs.sqlite bands --plan small.toml --measures rcf_damage --format json");
  ASSERT_EQ(rcf.exit_code, 0) << rcf.err;
  const nlohmann::json d = nlohmann::json::parse(rcf.out)["classes"][0]["measures"]["rcf_damage"];
  EXPECT_NEAR(d["p50"].back().get<double>(), HandPercentile(damage, 50.0),
              kUlps * HandPercentile(damage, 50.0));
  // Life to the median run's final damage: that run reaches it (at its last step at the latest).
  const Outcome life = Run(fmt::format(
      "history --db small_runs.sqlite life --plan small.toml --limit rcf_damage={} --json",
      HandPercentile(damage, 50.0)));
  ASSERT_EQ(life.exit_code, 0) << life.err;
  int reached = 0;
  const nlohmann::json lives = nlohmann::json::parse(life.out);
  for (const auto& run : lives["runs"]) reached += !run["mgt"][0].is_null();
  EXPECT_GE(reached, 2);
}

}  // namespace
}  // namespace railwear::test
