// `railwear curving` and the scene keys of vehicle traffic: [track] radius and cant, [[vehicle]]
// tables, traffic entries naming a vehicle; a single S1002 wheelset on R 1500 m (about a second).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/scene.h"
#include "app/stored_study.h"
#include "core/contact/contact_solver.h"
#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/wear_scenes.h"
#include "tests/sqlite_test_support.h"
#include "wear/spread_integration.h"
#include "wear/vehicle_traffic.h"
#include "wear/wear_simulation.h"

namespace railwear::test {
namespace {

class CurvingCommandTest : public CliFixture {
 protected:
  // `railwear curving` of the 10 MGT run's scene on its stored step in tests/data/`database`
  // (tests/data/README.md): the equilibria's JSON, after checking the exit code and that the
  // output names `step` (e.g. "step 66 (5.197 MGT)").
  // `nodes`: the spread nodes of the run (the stored scene has 3; traffic_study.sh's
  // TRAFFIC_STUDY_SPREAD=N writes N in their place, and the database keeps that text).
  // `sql`: run on the database's copy first; `args`: more options of the command.
  nlohmann::json SolveOnStoredRails(const std::string& database, const std::string& step,
                                    int nodes = 3, const std::string& sql = "",
                                    const std::string& args = "") {
    const fs::path data = fs::path(RAILWEAR_SOURCE_DIR) / "tests/data";
    std::string scene = ReadFile(data / "r600_10mgt_scene.toml");
    const std::string three = "quadrature_points = 3";
    const size_t at = scene.find(three);
    EXPECT_NE(at, std::string::npos);
    std::ofstream(dir_ / "s.toml")
        << scene.replace(at, three.size(), "quadrature_points = " + std::to_string(nodes));
    fs::copy_file(data / database, dir_ / "w.sqlite", fs::copy_options::overwrite_existing);
    if (!sql.empty()) test::RawExec((dir_ / "w.sqlite").string(), sql);
    const Outcome o = Run("curving s.toml --db w.sqlite --json eq.json" + args);
    EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
    EXPECT_TRUE(Contains(o.out, step)) << o.out;
    return nlohmann::json::parse(ReadFile(dir_ / "eq.json"));
  }

  // Both vehicles on step 105 of the 20-node run (tests/data/README.md), `sql` run on the
  // database first: both converged, and the coach's flanging leading wheelset where the run had
  // it (10.26 mm, 3.45 mrad from the stored start, which converges to 10.28 mm, 3.47 mrad) to
  // the position tolerances' order: the step in its force is crossed, not run away from.
  nlohmann::json SolveOnStep105(const std::string& sql, const std::string& args = "") {
    const nlohmann::json j = SolveOnStoredRails("r600_10mgt_20nodes_step105.sqlite",
                                                "step 105 (8.508 MGT)", 20, sql, args);
    if (j.size() != 2u) {
      ADD_FAILURE() << "expected the coach and the wagon: " << j.dump();
      return j;
    }
    const nlohmann::json& coach = j[0];
    EXPECT_EQ(coach["vehicle"], "passenger coach");
    std::printf("coach: %s, %d solves\n", std::string(coach["message"]).c_str(),
                coach["contact_solves"].get<int>());
    EXPECT_EQ(coach["status"], "converged") << coach["message"];
    const nlohmann::json& lead = coach["wheelsets"][0];
    EXPECT_NEAR(lead["y_mm"].get<double>(), 10.28, 0.05);
    EXPECT_NEAR(lead["yaw_mrad"].get<double>(), 3.45, 0.1);
    EXPECT_EQ(j[1]["status"], "converged") << j[1]["message"];
    return j;
  }
};

const char* const kScene = kWheelsetCurveScene;

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The scene with both rails named and steps of 0.002 mm: a wear run of a few short steps.
std::string TwoRailWearScene() {
  return Replace(Replace(kScene, "high_rail = \"builtin:UIC60\"",
                         "high_rail = \"builtin:UIC60\"\nlow_rail = \"builtin:UIC60\""),
                 "total_passes = 1e5", "total_passes = 1e5\nmax_depth_per_step_mm = 0.002");
}

TEST_F(CurvingCommandTest, PrintsTheEquilibriumAndWritesJson) {
  std::ofstream(dir_ / "s.toml") << kScene;
  const Outcome o = Run("curving s.toml --json eq.json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "vehicle \"wheelset\" at 25.0 m/s on R 1500 m"));
  EXPECT_TRUE(Contains(o.out, "status converged"));
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir_ / "eq.json"));
  ASSERT_EQ(j.size(), 1u);
  const nlohmann::json& w = j[0]["wheelsets"][0];
  // 25 m/s on R 1500 m without cant: 0.42 m/s^2 outward; the high wheel carries more.
  EXPECT_NEAR(j[0]["cant_deficiency_mm"].get<double>(), 1500.0 * 625.0 / 1500.0 / 9.80665, 1e-6);
  EXPECT_GT(w["Q_high_N"].get<double>(), w["Q_low_N"].get<double>());
  EXPECT_GT(w["y_mm"].get<double>(), 0.0);  // pushed toward the high rail
  EXPECT_EQ(j[0]["status"], "converged");
}

// --predictor table: the cold solve iterates on the contact table, then the full model finishes
// it, so the equilibrium is the model predictor's within the curving's position tolerances
// (CurvingOptions: 0.05 mm, 0.05 mrad; both solves stop within them of the same solution, so
// twice apart at most; measured 0.007 mm and 0.005 mrad on this wheelset); the
// output says how the table fared. A predictor it does not know is exit 2 naming the option.
TEST_F(CurvingCommandTest, TablePredictorReachesTheSameEquilibrium) {
  std::ofstream(dir_ / "s.toml") << kScene;
  const Outcome model = Run("curving s.toml --json model.json");
  ASSERT_EQ(model.exit_code, 0) << model.err;
  const Outcome table = Run("curving s.toml --predictor table --json table.json");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_TRUE(Contains(table.out, "; table predictor used (")) << table.out;
  const nlohmann::json m = nlohmann::json::parse(ReadFile(dir_ / "model.json"));
  const nlohmann::json t = nlohmann::json::parse(ReadFile(dir_ / "table.json"));
  ASSERT_EQ(m.size(), 1u);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(m[0]["predictor"], "model");
  EXPECT_EQ(m[0]["table_predictor"], "not_used");
  EXPECT_EQ(t[0]["predictor"], "table");
  EXPECT_EQ(t[0]["table_predictor"], "used");
  EXPECT_EQ(t[0]["status"], "converged") << t[0]["message"];
  const nlohmann::json& a = m[0]["wheelsets"][0];
  const nlohmann::json& b = t[0]["wheelsets"][0];
  EXPECT_NEAR(b["y_mm"].get<double>(), a["y_mm"].get<double>(), 2 * 0.05);
  EXPECT_NEAR(b["yaw_mrad"].get<double>(), a["yaw_mrad"].get<double>(), 2 * 0.05);

  const Outcome bad = Run("curving s.toml --predictor grid");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Contains(bad.err, "--predictor")) << bad.err;
  EXPECT_TRUE(Contains(bad.err, "grid")) << bad.err;
}

// The scene key [curving] predictor: absent or "model" the draft grid, "table" the contact table
// in every vehicle entry's curving problem (wear/vehicle_traffic.h's VehicleCurvingProblem, the
// wear run's and `railwear curving`'s), where --predictor overrides it; a wear run with it ends
// its step where the model predictor's run does, within the curving's position tolerances
// (CurvingOptions::position_tolerance_m, yaw_tolerance_rad: 0.05 mm, 0.05 mrad). Bad values:
// the bad-input corpus (curving_predictor_*).
// [curving] warm_contact (CurvingOptions::warm_contact; absent: on at standard accuracy and
// finer, off at draft) reaches every vehicle entry's curving problem, the wear run's and
// `railwear curving`'s (VehicleCurvingProblem); a value other than a boolean: the bad-input
// corpus (curving_warm_contact_not_a_bool). What the option does:
// CurvingTest.WarmContactSolvesAreThreadIndependentAndNearTheColdOnes.
TEST_F(CurvingCommandTest, SceneWarmContactKeyReachesTheCurvingProblem) {
  const app::Scene absent = app::ParseScene(TwoRailWearScene(), "s.toml");  // at draft
  EXPECT_FALSE(absent.wear->curving_warm_contact.has_value());
  const TrackRails rails = UnwornRailsInTrack(*absent.wear);
  CurvingProblem p = VehicleCurvingProblem(*absent.wear, 0, rails.high, rails.low);
  EXPECT_FALSE(p.options.warm_contact.has_value());
  EXPECT_FALSE(p.options.WarmContactFor(p.contact.model));  // draft: off
  p.contact.model.accuracy = AccuracyPreset::kStandard;
  EXPECT_TRUE(p.options.WarmContactFor(p.contact.model));  // standard: on
  for (const bool on : {true, false}) {
    const app::Scene scene = app::ParseScene(
        TwoRailWearScene() + "[curving]\nwarm_contact = " + (on ? "true\n" : "false\n"), "w.toml");
    ASSERT_EQ(scene.wear->curving_warm_contact, on);
    CurvingProblem q = VehicleCurvingProblem(*scene.wear, 0, rails.high, rails.low);
    EXPECT_EQ(q.options.warm_contact, on);
    q.contact.model.accuracy = AccuracyPreset::kStandard;  // the key holds at every accuracy
    EXPECT_EQ(q.options.WarmContactFor(q.contact.model), on);
    EXPECT_FALSE(scene.wear->curving_predictor.has_value());  // the other key unchanged
  }
}

TEST_F(CurvingCommandTest, ScenePredictorKeyReachesTheCurvingAndTheWearRun) {
  const std::string table_scene = TwoRailWearScene() + "[curving]\npredictor = \"table\"\n";
  const std::string model_scene = TwoRailWearScene() + "[curving]\npredictor = \"model\"\n";
  EXPECT_FALSE(app::ParseScene(TwoRailWearScene(), "s.toml").wear->curving_predictor.has_value());
  EXPECT_EQ(app::ParseScene(model_scene, "m.toml").wear->curving_predictor,
            CurvingPredictor::kModel);
  const app::Scene scene = app::ParseScene(table_scene, "t.toml");
  ASSERT_EQ(scene.wear->curving_predictor, CurvingPredictor::kTable);
  const TrackRails rails = UnwornRailsInTrack(*scene.wear);
  EXPECT_EQ(VehicleCurvingProblem(*scene.wear, 0, rails.high, rails.low).options.cold_predictor,
            CurvingPredictor::kTable);

  std::ofstream(dir_ / "t.toml") << table_scene;
  std::ofstream(dir_ / "m.toml") << model_scene;
  const Outcome t = Run("curving t.toml --json t.json");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const nlohmann::json tj = nlohmann::json::parse(ReadFile(dir_ / "t.json"));
  EXPECT_EQ(tj[0]["predictor"], "table");
  EXPECT_EQ(tj[0]["table_predictor"], "used") << tj[0]["message"];
  ASSERT_EQ(Run("curving t.toml --predictor model --json o.json").exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(ReadFile(dir_ / "o.json"))[0]["predictor"], "model");

  ASSERT_EQ(Run("wear t.toml --db t.sqlite --steps 1").exit_code, 0);
  ASSERT_EQ(Run("wear m.toml --db m.sqlite --steps 1").exit_code, 0);
  const ProfileStore a = ProfileStore::OpenReadOnly((dir_ / "t.sqlite").string());
  const ProfileStore b = ProfileStore::OpenReadOnly((dir_ / "m.sqlite").string());
  const StepRecord sa = a.LoadStep(a.FindRun("wheelset on R1500")->id, 1);
  const StepRecord sb = b.LoadStep(b.FindRun("wheelset on R1500")->id, 1);
  ASSERT_EQ(sa.curving_starts.size(), 1u);
  ASSERT_EQ(sb.curving_starts.size(), 1u);
  EXPECT_NEAR(sa.curving_starts[0].state[0], sb.curving_starts[0].state[0], 5e-5);
  EXPECT_NEAR(sa.curving_starts[0].state[1], sb.curving_starts[0].state[1], 5e-5);
}

// A cold solve on worn rails through the table predictor, as a wear run with [curving]
// predictor = "table" makes one (its vehicles' problems from VehicleCurvingProblem, no stored
// start): the main job's curve after 5.2 MGT (tests/data/r600_10mgt_step66.sqlite, 2.4 mm of
// gauge-corner wear), the Y25 wagon from the centred start through the table and through the
// draft model predictor: the same full-model equilibrium within the curving's position
// tolerances (0.05 mm, 0.05 mrad: CurvingOptions::position_tolerance_m, yaw_tolerance_rad, of
// the order of the draft grid's own position error). (The coach on these rails: its table phase
// stops at 5.4e-1 Q0 and the solve falls back to the model predictor, said in its message;
// measured, docs/curving.md, not repeated here: 268 solves each way.)
TEST_F(CurvingCommandTest, TablePredictorOnWornRailsReachesTheModelPredictorsEquilibrium) {
  const fs::path data = fs::path(RAILWEAR_SOURCE_DIR) / "tests/data";
  const std::string text = ReadFile(data / "r600_10mgt_scene.toml");
  const ProfileStore db = ProfileStore::OpenReadOnly((data / "r600_10mgt_step66.sqlite").string());
  CurvingResult results[2];
  for (int k = 0; k < 2; ++k) {
    const app::Scene scene =
        app::ParseScene(k == 0 ? text : text + "\n[curving]\npredictor = \"table\"\n", "s.toml");
    const WearStudy& study = *scene.wear;
    const int64_t run = db.FindRun(scene.name)->id;
    const WearState unworn = app::StateFromStore(db, run, 0);
    const WearState worn = app::StateFromStore(db, run, 66);
    const Profile high = RailInTrack(study, unworn.rail, worn.rail);
    const Profile low = RailInTrack(study, *unworn.low_rail, *worn.low_rail);
    const int wagon = 1;  // the traffic entry of the Y25 wagon
    ASSERT_TRUE(study.traffic[wagon].is_vehicle());
    const CurvingProblem p = VehicleCurvingProblem(study, wagon, high, low);
    ASSERT_EQ(p.vehicle.name, "Y25 wagon");
    ASSERT_FALSE(p.options.start.has_value());  // cold: the run's unworn starts are not set
    EXPECT_EQ(p.options.ColdPredictorFor(p.contact.model),
              k == 0 ? CurvingPredictor::kModel : CurvingPredictor::kTable);
    results[k] = SolveCurving(p);
  }
  const CurvingResult &m = results[0], &t = results[1];
  std::printf(
      "wagon on step 66's rails, cold: model predictor %s, %d + %d iterations, %d solves, %.1f s; "
      "table %s (%s), %d + %d iterations, %d solves, %d table evaluations, %.1f s\n",
      std::string(ToString(m.status)).c_str(), m.predictor_iterations, m.full_iterations,
      m.contact_solves, m.time_s, std::string(ToString(t.status)).c_str(),
      std::string(ToString(t.table_predictor)).c_str(), t.predictor_iterations, t.full_iterations,
      t.contact_solves, t.table_evaluations, t.time_s);
  ASSERT_EQ(m.status, CurvingStatus::kConverged) << m.message;
  ASSERT_EQ(t.status, CurvingStatus::kConverged) << t.message;
  EXPECT_EQ(t.table_predictor, TablePredictorOutcome::kUsed) << t.message;
  ASSERT_EQ(m.wheelsets.size(), t.wheelsets.size());
  for (size_t i = 0; i < m.wheelsets.size(); ++i) {
    std::printf("  wheelset %zu: y %.3f / %.3f mm, psi %.3f / %.3f mrad\n", i,
                m.wheelsets[i].lateral_m * 1e3, t.wheelsets[i].lateral_m * 1e3,
                m.wheelsets[i].yaw_rad * 1e3, t.wheelsets[i].yaw_rad * 1e3);
    EXPECT_NEAR(t.wheelsets[i].lateral_m, m.wheelsets[i].lateral_m, 5e-5) << i;
    EXPECT_NEAR(t.wheelsets[i].yaw_rad, m.wheelsets[i].yaw_rad, 5e-5) << i;
  }
}

// Vehicle traffic in a wear run: each step's curving starts from the previous step's solution,
// stored with the step (curving_starts); a run stopped after one step and resumed reads it back
// and ends bit for bit where the uninterrupted run does.
TEST_F(CurvingCommandTest, WearRunStoresEachStepsCurvingAndResumesFromIt) {
  const std::string scene = TwoRailWearScene();
  std::ofstream(dir_ / "w.toml") << scene;
  const Outcome whole = Run("wear w.toml --db a.sqlite --steps 2");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  ASSERT_EQ(Run("wear w.toml --db b.sqlite --steps 1").exit_code, 0);
  const Outcome resumed = Run("wear w.toml --db b.sqlite --resume --steps 1");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;

  ProfileStore a = ProfileStore::Open((dir_ / "a.sqlite").string());
  ProfileStore b = ProfileStore::Open((dir_ / "b.sqlite").string());
  const int64_t run_a = a.FindRun("wheelset on R1500")->id;
  const int64_t run_b = b.FindRun("wheelset on R1500")->id;
  ASSERT_EQ(a.LastStep(run_a), 2);
  ASSERT_EQ(b.LastStep(run_b), 2);
  for (int step = 1; step <= 2; ++step) {
    const StepRecord sa = a.LoadStep(run_a, step), sb = b.LoadStep(run_b, step);
    // One vehicle entry: its wheelset's (y, psi) and the 2 x 2 Jacobian there.
    ASSERT_EQ(sa.curving_starts.size(), 1u) << step;
    EXPECT_EQ(sa.curving_starts[0].traffic_index, 0);
    EXPECT_EQ(sa.curving_starts[0].state.size(), 2u);
    EXPECT_EQ(sa.curving_starts[0].jacobian.size(), 4u);
    ASSERT_EQ(sb.curving_starts.size(), 1u) << step;
    EXPECT_EQ(sb.curving_starts[0].state, sa.curving_starts[0].state) << step;
    EXPECT_EQ(sb.curving_starts[0].jacobian, sa.curving_starts[0].jacobian) << step;
    EXPECT_EQ(sb.profile.points(), sa.profile.points()) << step;
    EXPECT_EQ(sb.low_rail->profile.points(), sa.low_rail->profile.points()) << step;
  }
  EXPECT_TRUE(a.LoadStep(run_a, 0).curving_starts.empty());
}

// `curving --db`: on a stored step's worn rails, from its stored curving, the solve is the one the
// run's next step makes: step 1's equilibrium is, bit for bit, what the run stored with step 2.
TEST_F(CurvingCommandTest, OnAStoredStepIsTheRunsNextStepsSolve) {
  const std::string scene = TwoRailWearScene();
  std::ofstream(dir_ / "w.toml") << scene;
  ASSERT_EQ(Run("wear w.toml --db a.sqlite --steps 2").exit_code, 0);
  const std::string before = ReadFile(dir_ / "a.sqlite");
  const Outcome o = Run("curving w.toml --db a.sqlite --step 1 --json eq.json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "on the worn rails of run 'wheelset on R1500' step 1")) << o.out;
  EXPECT_EQ(ReadFile(dir_ / "a.sqlite"), before);  // only read
  // The stored start converged: the unworn rails' equilibrium, its fallback, was not solved
  // (CurvingStart::lazy; CurvingRulesTest.LazyFallbackIsFoundOnlyWhenTheStartBeforeItFails).
  EXPECT_FALSE(Contains(o.err, "on the run's unworn rails")) << o.err;
  ASSERT_EQ(nlohmann::json::parse(ReadFile(dir_ / "eq.json"))[0]["starts"].size(), 1u);
  const nlohmann::json w = nlohmann::json::parse(ReadFile(dir_ / "eq.json"))[0]["wheelsets"][0];
  const ProfileStore db = ProfileStore::OpenReadOnly((dir_ / "a.sqlite").string());
  const StepRecord next = db.LoadStep(db.FindRun("wheelset on R1500")->id, 2);
  ASSERT_EQ(next.curving_starts.size(), 1u);
  EXPECT_EQ(w["y_mm"].get<double>(), next.curving_starts[0].state[0] * 1e3);
  EXPECT_EQ(w["yaw_mrad"].get<double>(), next.curving_starts[0].state[1] * 1e3);

  // The run's last step by default; a step it does not have, another scene or a missing
  // database: exit 2 naming what was expected.
  EXPECT_TRUE(Contains(Run("curving w.toml --db a.sqlite").out, "step 2 ("));
  const Outcome late = Run("curving w.toml --db a.sqlite --step 9");
  EXPECT_EQ(late.exit_code, 2);
  EXPECT_TRUE(Contains(late.err, "--step 9: run 'wheelset on R1500'")) << late.err;
  EXPECT_TRUE(Contains(late.err, "has steps 0 to 2")) << late.err;
  std::ofstream(dir_ / "other.toml") << Replace(scene, "speed_m_s = 25", "speed_m_s = 20");
  const Outcome other = Run("curving other.toml --db a.sqlite --run \"wheelset on R1500\"");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_TRUE(Contains(other.err, "from a different scene than other.toml")) << other.err;
  EXPECT_EQ(Run("curving w.toml --step 1").exit_code, 2);  // --step needs --db
  const Outcome missing = Run("curving w.toml --db none.sqlite");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(Contains(missing.err, "database 'none.sqlite': no such file")) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "none.sqlite"));
}

// The main job's curve after 5.2 MGT (tests/data/README.md), where the 10 MGT run once stopped
// ("no step reduced the residual" after 752 wheelset solves, 1.6e-2 Q0): the Y25 wagon's rear
// bogie on the worn rails. (The coach on the same rails converges on its forces.)
TEST_F(CurvingCommandTest, WornRailsOfStep66Converge) {
  const nlohmann::json j =
      SolveOnStoredRails("r600_10mgt_step66.sqlite", "step 66 (5.197 MGT)");
  ASSERT_EQ(j.size(), 2u);
  const nlohmann::json& wagon = j[1];
  ASSERT_EQ(wagon["vehicle"], "Y25 wagon");
  std::printf("wagon: %s, %d solves\n", std::string(wagon["message"]).c_str(),
              wagon["contact_solves"].get<int>());
  // The step in wheelset 2's yaw moment that this case was made for (-1.3 to +2.0 kN m within
  // 4 um) came from a planar patch's plane jumping with its smallest gap; with the plane on the
  // pressure centre the wagon converges outright (36 solves, where the probe rule took 112 and
  // the solve without it failed after 752), within the tolerance the wear accepts.
  EXPECT_EQ(wagon["status"], "converged");
  EXPECT_LE(wagon["largest_scaled_residual"].get<double>(), 5.0 * 3e-3);
  EXPECT_LT(wagon["contact_solves"].get<int>(), 112);
  EXPECT_EQ(j[0]["status"], "converged");
}

// The spread nodes on step 66's worn rails (issue 16; docs/wear.md, "The flange onset, once per
// wheelset" and "The spike below the flange onset"), where the Y25 wagon's leading wheelset on
// the high rail reaches its flange's onset at about +0.15 std of the 1 mm spread: each node used
// to bisect its own onset to 10 um, and the third (flange) patch appeared at scattered nodes (x =
// 0.53-0.60, 1.25, 2.29, 4.06 of the 320-node rule), decided by where each bisection stopped. Now
// every node beyond the onset is the same wheelset position, bit for bit. And the onset is the
// elastic contact's: the rigid first contact reaches 45 degrees only at +0.21 std, but from +0.15
// std on the wheel's approach (about 0.1 mm) already brings a flange patch (61 degrees) in, which
// carried up to 6 times the held response (the spike). The held position has no flange patch;
// 20 um further out (two of the bisection's resolution) it has one. (The wagon's curving from the
// step's stored start, and the onset's and these two contact solves; no wear step.)
TEST(CurvingOnStoredRailsTest, SpreadNodesOnStep66AreHeldAtOneFlangeOnset) {
  const fs::path data = fs::path(RAILWEAR_SOURCE_DIR) / "tests/data";
  const app::Scene scene = app::ParseScene(ReadFile(data / "r600_10mgt_scene.toml"), "s.toml");
  const WearStudy& study = *scene.wear;
  const ProfileStore db = ProfileStore::OpenReadOnly((data / "r600_10mgt_step66.sqlite").string());
  const int64_t run = db.FindRun(scene.name)->id;
  const WearState unworn = app::StateFromStore(db, run, 0);
  const WearState worn = app::StateFromStore(db, run, 66);
  const int wagon = 1;  // the traffic entry of the Y25 wagon
  ASSERT_EQ(static_cast<int>(worn.curving.size()), 2);
  const VehicleEquilibrium eq = SolveVehicleEquilibrium(
      study, wagon, RailInTrack(study, unworn.rail, worn.rail),
      RailInTrack(study, *unworn.low_rail, *worn.low_rail), &worn.curving[wagon]);
  ASSERT_EQ(eq.flange_onset_m.size(), 4u);
  const double std_m = study.traffic[wagon].lateral_shift_std_m;
  const double onset_m = eq.flange_onset_m[0][0];  // leading wheelset, toward the high rail
  std::printf("wagon's leading wheelset on step 66: flange onset %.4f std toward the high rail\n",
              onset_m / std_m);
  EXPECT_GT(onset_m, 0.1 * std_m);
  EXPECT_LT(onset_m, 0.3 * std_m);
  const auto high_case = [&](double x) {
    return VehicleNodeCases(study, wagon, eq, 0, x, 0, 1.0)[0];
  };
  const LoadCase held = high_case(0.3);
  for (const double x : {0.53, 0.60, 1.25, 1.5, 2.29, 3.0, 4.06, 5.0}) {
    const LoadCase c = high_case(x);
    EXPECT_EQ(c.placement.lateral_shift_m, held.placement.lateral_shift_m) << x;
    EXPECT_EQ(c.placement.roll_rad, held.placement.roll_rad) << x;
    EXPECT_EQ(c.placement.yaw_rad, held.placement.yaw_rad) << x;
    EXPECT_EQ(c.placement.rolling_radius_m, held.placement.rolling_radius_m) << x;
    EXPECT_EQ(c.motion.speed_m_s, held.motion.speed_m_s) << x;
    EXPECT_EQ(c.motion.yaw_velocity_rad_s, held.motion.yaw_velocity_rad_s) << x;
    EXPECT_EQ(c.vertical_force_N, held.vertical_force_N) << x;
  }
  // Below the onset a node keeps its own offset.
  EXPECT_NE(high_case(0.05).placement.lateral_shift_m, held.placement.lateral_shift_m);

  // The onset is the elastic contact's, below the rigid one.
  const double rigid_m = RigidFlangeOnsetOffset(eq, 0, RailSide::kHigh, std_m);
  std::printf("rigid onset %.4f std\n", rigid_m / std_m);
  EXPECT_LT(onset_m, rigid_m - 0.03 * std_m);
  const auto steepest_patch_rad = [&](double offset_m) {
    const LoadCase c =
        internal::VehicleCasesAtOffset(study, wagon, eq, 0, offset_m, 0.0, 0, 1.0)[0];
    const ContactResult r = SolveContact(LoadCaseProblem(study, eq.problem.high_rail, c));
    EXPECT_EQ(r.status, SolverStatus::kConverged);
    double steepest = 0.0;
    for (const PatchResult& p : r.patches) steepest = std::max(steepest, p.contact_angle_rad);
    return steepest;
  };
  EXPECT_LT(steepest_patch_rad(onset_m), kFlangeContactAngle_rad);
  EXPECT_GE(steepest_patch_rad(onset_m + 2.0 * kFlangeOnsetResolution_m), kFlangeContactAngle_rad);
}

// Issue 16's must-show on the curve's worn rails: the adaptive spread rule at the scenes' default
// tolerance (0.005), and the fixed piecewise-linear rule on 80 nodes (L64), against the converged
// fixed reference, 320 piecewise-linear nodes per wheelset (L256, docs/wear.md "The converged
// fixed reference on the curve"), on step 66 (5.2 MGT), the high rail's depth field per pass
// summed over all wheelsets of both vehicles. Before each wheelset's flange onset was found once,
// the adaptive rule was 12.1 % off here (a two-valued response at per-node onsets); with the
// rigid onset found once 0.6 %, L64 3.0 % (the spike of elastic flange patches below the rigid
// onset); with the elastic onset 0.9 % and 0.1 % (`spread_depth_study`, docs/wear.md "The spike
// below the flange onset"). The bounds: the issue's 2 % for the adaptive rule, 1 % for L64 (the
// brief's target; the rigid onset's 3.0 % fails it). Three wear steps (6872 load cases), 84 s CPU
// on cores shared at a load average of 10.
TEST(CurvingOnStoredRailsTest, AdaptiveAndL64SpreadRulesAreNearTheReferenceOnStep66) {
  constexpr double kIssueBound = 0.02, kL64Bound = 0.01;
  const fs::path data = fs::path(RAILWEAR_SOURCE_DIR) / "tests/data";
  const ProfileStore db = ProfileStore::OpenReadOnly((data / "r600_10mgt_step66.sqlite").string());
  const RunInfo run = app::FindRunOrThrow(db, "R600 curve, coach and Y25 wagon");
  const app::Scene scene = app::ParseScene(run.scene_text, "stored.toml");
  const UnwornRails unworn = UnwornRails::Of(app::StateFromStore(db, run.id, 0));
  const WearState worn = app::StateFromStore(db, run.id, 66);
  const auto high_rail_field = [&](const WearOptions& spread) {
    WearStudy study = *scene.wear;
    study.options.spread_nodes = spread.spread_nodes;
    study.options.integration_tolerance = spread.integration_tolerance;
    const StepResult step = RunWearStep(study, unworn, worn, 1e30);
    std::vector<double> field;
    for (const LoadCaseSummary& c : step.cases) {
      if (c.load_case.rail != RailSide::kHigh) continue;
      if (field.empty()) field.assign(c.depth_per_pass_m.size(), 0.0);
      for (size_t b = 0; b < field.size(); ++b) {
        field[b] += c.load_case.weight * c.depth_per_pass_m[b];
      }
    }
    return field;
  };
  WearOptions reference, adaptive, l64;
  reference.spread_nodes = LinearSpreadNodes(256);
  adaptive.integration_tolerance = 0.005;
  l64.spread_nodes = LinearSpreadNodes(64);
  const std::vector<double> ref = high_rail_field(reference);
  const auto relative_to_ref = [&](const std::vector<double>& got) {
    EXPECT_EQ(got.size(), ref.size());
    double diff2 = 0.0, ref2 = 0.0;
    for (size_t b = 0; b < ref.size() && b < got.size(); ++b) {
      diff2 += (got[b] - ref[b]) * (got[b] - ref[b]);
      ref2 += ref[b] * ref[b];
    }
    EXPECT_GT(ref2, 0.0);
    return std::sqrt(diff2 / ref2);
  };
  const double adaptive_off = relative_to_ref(high_rail_field(adaptive));
  const double l64_off = relative_to_ref(high_rail_field(l64));
  std::printf("step 66, high rail: depth field off L256's: adaptive rule %.2f %%, L64 %.2f %%\n",
              100 * adaptive_off, 100 * l64_off);
  EXPECT_LE(adaptive_off, kIssueBound);
  EXPECT_LE(l64_off, kL64Bound);
}

// Step 81 of the same run (6.24 MGT), where the 10 MGT run stopped after 1040 wheelset solves
// without an equilibrium: the Y25 wagon's rear bogie's low wheel runs on the worn tread's wide,
// nearly conformal patch, whose smallest gap jumps between its two ends as the wheelset moves by
// micrometres; the planar grid's plane (and the spin and creep forces) jumped with it (F_x 14.0
// to 16.7 kN within 7 um of y). With the plane on the patch's pressure centre
// (core/contact/potential_area.h) both vehicles converge in a few dozen solves.
TEST_F(CurvingCommandTest, WornTreadPlaneOnThePressureCentreConverges) {
  const nlohmann::json j =
      SolveOnStoredRails("r600_10mgt_step81.sqlite", "step 81 (6.236 MGT)");
  ASSERT_EQ(j.size(), 2u);
  for (const nlohmann::json& vehicle : j) {
    EXPECT_EQ(vehicle["status"], "converged") << vehicle["message"];
    // Within the 5x tolerance the wear accepts (3e-3), and far from the failed 1040 solves.
    EXPECT_LE(vehicle["largest_scaled_residual"].get<double>(), 5.0 * 3e-3) << vehicle["vehicle"];
    EXPECT_LT(vehicle["contact_solves"].get<int>(), 300) << vehicle["vehicle"];
  }
}

// Step 105 (8.51 MGT) of the same scene run with 20 fixed spread nodes
// (TRAFFIC_STUDY_SPREAD=20), where that run stopped: the coach's curving ended with "no step
// reduced the residual" at 3.1e-2 Q0 from the stored start and at 5.2e-1 from the centred one.
// Its leading wheelset (y 10.28 mm, 3.48 mrad, flange at 67-70 deg) has a step in its lateral
// force: -1.6 to -8.1 kN between 0 and -0.05 mrad of yaw as its gauge-corner contact switches
// between two patches and one, while the force turns by 1.5e9 N/m with y. Every trial past the
// step had a larger residual; the natural-level test (core/vehicle/curving.cpp) takes the
// step by its distance in position. Since that test comes before the Levenberg-Marquardt trials
// the solve goes on to the grid's noise floor (residual 4.0e-3 in 148 solves; it ended in
// position at 2.6e-2 in 232 before, docs/curving.md).
TEST_F(CurvingCommandTest, ForceStepInFlangeContactIsCrossed) {
  const nlohmann::json j = SolveOnStep105("");
  ASSERT_EQ(j.size(), 2u);
  // Converged on the forces, or at the grid's noise floor (kNoiseFloor = 3 x the tolerance
  // 3e-3), far below the 3.1e-2 the failed solve stopped at.
  EXPECT_LE(j[0]["largest_scaled_residual"].get<double>(), 3.0 * 3e-3);
}

// The same rails from the centred start alone (--start centred: a cold solve). The coach's
// Newton steps went 2 mm an iteration away from the flange (the worn tread's Jacobian there
// points that way) and stopped at 5.2e-1 Q0 after 252 solves; the centred start relaxed by
// pseudo-transient continuation (core/vehicle/curving.cpp, Relax) reaches the stored run's
// equilibrium.
TEST_F(CurvingCommandTest, CentredStartIsRelaxedOntoTheFlange) {
  const nlohmann::json j = SolveOnStep105("", " --start centred");
  ASSERT_EQ(j.size(), 2u);
  EXPECT_TRUE(Contains(j[0]["message"], "relaxed")) << j[0]["message"];
  EXPECT_LE(j[0]["largest_scaled_residual"].get<double>(), 20 * 3e-3);
  ASSERT_EQ(j[0]["starts"].size(), 2u);
  EXPECT_EQ(j[0]["starts"][0]["start"], "the centred start");
  EXPECT_EQ(j[0]["starts"][1]["start"], "the centred start relaxed");
}

// The start sequence (issue 15; docs/curving.md, "The start sequence"): a previous step's
// solution that fails falls back to the vehicle's equilibrium on the unworn rails before the
// centred start. The coach's stored start on step 105 replaced by the track centre with unyawed
// wheelsets (every unknown 0, no Jacobian): from there it walks past the 20 mm lateral limit
// (244 solves; since the climb rule, refused on the way as climbing), which used to end the
// solve `no_equilibrium` and the wear run with it. Now the
// unworn rails' equilibrium (on the run's step 0, as the run solves it; the command solves it
// only once the stored start has failed, CurvingStart::lazy) follows and
// converges where the stored start does, in fewer solves than the centred start takes (316:
// --start centred), and the message and the JSON's "starts" say so. The wagon's stored start
// converges first: no start is named.
TEST_F(CurvingCommandTest, FailedStartFallsBackToTheUnwornRailsEquilibrium) {
  const nlohmann::json j = SolveOnStep105(
      "UPDATE curving_starts SET state = zeroblob(14 * 8), jacobian = zeroblob(0) "
      "WHERE step = 105 AND traffic_index = 0");
  ASSERT_EQ(j.size(), 2u);
  const nlohmann::json& starts = j[0]["starts"];
  ASSERT_EQ(starts.size(), 2u) << starts.dump();
  EXPECT_EQ(starts[0]["start"], "the previous step's solution");
  EXPECT_FALSE(starts[0]["converged"].get<bool>());
  // It climbs: past the lateral limit, or refused on the way as climbing beyond the flange's
  // steepest flank (docs/curving.md, "Climbed states are refused").
  EXPECT_TRUE(Contains(starts[0]["message"], "climb")) << starts[0]["message"];
  EXPECT_EQ(starts[1]["start"], "the unworn rails' equilibrium");
  EXPECT_TRUE(starts[1]["converged"].get<bool>());
  EXPECT_EQ(starts[0]["contact_solves"].get<int>() + starts[1]["contact_solves"].get<int>(),
            j[0]["contact_solves"].get<int>());
  const std::string message = j[0]["message"];
  EXPECT_EQ(message.rfind("from the unworn rails' equilibrium (before it: the previous step's "
                          "solution: ",
                          0),
            0u)
      << message;
  ASSERT_EQ(j[1]["starts"].size(), 1u);
  EXPECT_EQ(j[1]["starts"][0]["start"], "the previous step's solution");
  EXPECT_FALSE(Contains(j[1]["message"], "from ")) << j[1]["message"];
  // The centred start on the same rails: more solves than the unworn rails' equilibrium took.
  const nlohmann::json centred = SolveOnStep105("", " --start centred");
  ASSERT_EQ(centred.size(), 2u);
  std::printf("coach from the unworn rails' equilibrium: %d solves; from the centred start: %d\n",
              starts[1]["contact_solves"].get<int>(), centred[0]["contact_solves"].get<int>());
  EXPECT_LT(starts[1]["contact_solves"].get<int>(), centred[0]["contact_solves"].get<int>());
}

// Near climb (issue 15's hard cases), the documented near-climb run of docs/curving.md without
// the wagon (about 2 + 5 s): the main job's coach on R 150 m with 150 mm cant and a dry mu of
// 0.5, at 15 m/s (78 mm cant deficiency) and at 19 m/s (216 mm). The leading wheelsets run on
// their flanges at about twice the geometric angle of attack a/R (1.28 m / 150 m = 8.5 mrad),
// the equilibrium finds the flange force, and the leading high wheel's L/V comes near Nadal's
// limit without passing it: status converged (at 15 m/s at the grid's noise, said in the
// message), the residuals reported. The faster run's flange force is larger.
TEST_F(CurvingCommandTest, NearClimbOnR150ConvergesBelowNadalWithTheFlangeForceFromEquilibrium) {
  std::string scene = ReadFile(fs::path(RAILWEAR_SOURCE_DIR) / "examples/curve_r600_vehicles.toml");
  scene = scene.substr(0, scene.find("[[traffic]]\nname = \"wagon"));  // the coach alone
  scene = Replace(Replace(Replace(scene, "radius_m = 600", "radius_m = 150"), "cant_mm = 100",
                          "cant_mm = 150"),
                  "friction = 0.35", "friction = 0.5");
  double flange_force_N = 0.0;
  for (const char* speed : {"15.0", "19.0"}) {
    std::ofstream(dir_ / "s.toml") << Replace(scene, "speed_m_s = 25.0",
                                              std::string("speed_m_s = ") + speed);
    const Outcome o = Run("curving s.toml --json eq.json");
    ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
    const nlohmann::json j = nlohmann::json::parse(ReadFile(dir_ / "eq.json"));
    ASSERT_EQ(j.size(), 1u);
    const nlohmann::json& coach = j[0];
    std::printf("near climb at %s m/s: %s (%s), residual %.1e, %d solves\n", speed,
                std::string(coach["status"]).c_str(), std::string(coach["message"]).c_str(),
                coach["largest_scaled_residual"].get<double>(), coach["contact_solves"].get<int>());
    EXPECT_EQ(coach["status"], "converged") << coach["message"];
    // Converged or stopped at the grid's noise floor (3x the tolerance 3e-3 Q0).
    EXPECT_LE(coach["largest_scaled_residual"].get<double>(), 3.0 * 3e-3);
    const nlohmann::json& lead = coach["wheelsets"][0];
    EXPECT_GT(lead["high_contact_angle_deg"].get<double>(), 65.0);  // on the flange (70 deg)
    const double psi_geometric_mrad = 1e3 * 0.5 * 2.56 / 150.0;
    EXPECT_GT(lead["yaw_mrad"].get<double>(), psi_geometric_mrad);
    EXPECT_LT(lead["yaw_mrad"].get<double>(), 3.0 * psi_geometric_mrad);
    // Near climb: within 40 % of Nadal's limit (0.95 at 70 deg and mu 0.5), not above it.
    const double l_over_v = lead["high_l_over_v"].get<double>();
    const double nadal = lead["high_nadal_limit"].get<double>();
    EXPECT_GT(l_over_v, 0.6 * nadal);
    EXPECT_LT(l_over_v, nadal);
    // The flange force from the equilibrium grows with the cant deficiency.
    EXPECT_GT(lead["Y_high_N"].get<double>(), flange_force_N);
    flange_force_N = lead["Y_high_N"].get<double>();
  }
}

TEST_F(CurvingCommandTest, BadVehicleInputIsExitTwoWithFileAndKey) {
  struct Case {
    std::string from, to, expected;
  };
  const Case cases[] = {
      {"vehicle = \"wheelset\"\nspeed", "vehicle = \"tram\"\nspeed",
       "key 'traffic[0].vehicle' = \"tram\": expected one of 'wheelset'"},
      {"axle_load_t = 16", "axle_load_t = -1", "vehicle[0].axle_load_t"},
      {"radius_m = 1500", "radius_m = 10", "track.radius_m"},
      {"cant_mm = 0", "cant_mm = 400", "track.cant_mm"},
      {"kind = \"wheelset\"", "kind = \"bogie\"", "key 'vehicle[0].wheelbase_m' is missing"},
      {"source = \"a test\"", "source = \"a test\"\nspring = 3", "vehicle[0].spring"},
  };
  for (const Case& c : cases) {
    std::ofstream(dir_ / "bad.toml") << Replace(kScene, c.from, c.to);
    const Outcome o = Run("curving bad.toml");
    EXPECT_EQ(o.exit_code, 2) << c.to << "\n" << o.err;
    EXPECT_TRUE(Contains(o.err, "bad.toml:")) << o.err;
    EXPECT_TRUE(Contains(o.err, c.expected)) << o.err;
  }
  // A scene without vehicles is not a curving scene.
  std::ofstream(dir_ / "none.toml") << "[scene]\nname = \"x\"\n";
  EXPECT_EQ(Run("curving none.toml").exit_code, 2);
  // --start names one of three starts and needs --db (the stored step it starts on).
  std::ofstream(dir_ / "good.toml") << kScene;
  const Outcome no_db = Run("curving good.toml --start unworn");
  EXPECT_EQ(no_db.exit_code, 2) << no_db.err;
  EXPECT_TRUE(Contains(no_db.err, "--start")) << no_db.err;
  EXPECT_TRUE(Contains(no_db.err, "--db")) << no_db.err;
  const Outcome bad = Run("curving good.toml --db w.sqlite --start warm");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_TRUE(Contains(bad.err, "warm")) << bad.err;
  EXPECT_TRUE(Contains(bad.err, "centred")) << bad.err;
}

}  // namespace
}  // namespace railwear::test
