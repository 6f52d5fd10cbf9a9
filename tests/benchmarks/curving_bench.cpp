// Google Benchmark programs for steady-state curving (issue 15; not timed tests):
//   BM_CurvingFreeWheelset  a free conical wheelset (lambda 0.05) on R 1000 m, draft half-space
//                           model (the predictor alone);
//   BM_CurvingRigidBogie    a bogie vehicle of cone wheelsets with stiff primary suspension on
//                           R 3000 m (four wheelsets, two frames, the car body), draft model;
//   BM_CurvingFreeWheelsetStandard  the free wheelset finished with the standard-accuracy
//                           half-space model after the draft predictor;
//   BM_CurvingExample/V/A   vehicle V (0: the coach, 1: the Y25 wagon) of the main job's scene
//                           (examples/curve_r600_vehicles.toml, R 600 m, both UIC60 rails) from
//                           the centred start, at the scene's accuracy (A = 0: draft) or the
//                           standard one (A = 1, the draft predictor first);
//   BM_CurvingExampleContinuation/V/A  the same vehicle 0.5 m/s faster, started from the solution
//                           at the scene's speed and its Jacobian (CurvingResult::Start): what
//                           each wear step's curving costs (it starts from the step before's).
//   BM_CurvingExampleWarm/V/A, BM_CurvingExampleContinuationWarm/V/A  the same two with warm
//                           contact solves (CurvingOptions::warm_contact), and how far their
//                           solution and Jacobian lie from the cold contact's through the model
//                           predictor (the default before: at standard the default is now the
//                           table predictor with warm contact solves, at draft unchanged);
//   BM_CurvingExampleWarmCombination/V/A/T  BM_CurvingExampleWarm with T = 1 the table
//                           predictor (at A = 1 the default), T = 0 the model predictor;
//   BM_CurvingExampleTable/V/A/T  as BM_CurvingExample with the table predictor
//                           (CurvingPredictor::kTable: the contact table built, its equilibrium
//                           finished with the full model); also reports the table's build time,
//                           its evaluations and whether it fell back to the model predictor;
//                           T = 0 the default table (nodes 0.1 mm apart, sampled at 0.1 mm),
//                           1 its nodes 0.2 mm apart, 2 also sampled at 0.2 mm, 3 the default
//                           nodes with the interpenetration patches
//                           (ContactTableOptions::Patch::kInterpenetration).
//   BM_CurvingExampleShiftedStart/V/S  vehicle V at draft from its own solution with every
//                           wheelset moved S x 0.1 mm toward the centre, without its Jacobian:
//                           how near a cold solve's start must be to save solves.
//   BM_ContactTableBuild/V  the contact table of vehicle V's wheels on the main job's rails.
// Each reports the wheelset contact solves it needed, and where its predictor's phase ended
// against the solution (predictor_off_y_mm, predictor_off_psi_mrad, the largest over the
// wheelsets; finish_start_residual, the full model's largest scaled residual there). Run:
//   build/tests/benchmarks/curving_bench --benchmark_repetitions=3
//   --benchmark_report_aggregates_only=true
#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>

#include "app/scene.h"
#include "tests/core/vehicle/curving_cases.h"
#include "wear/vehicle_traffic.h"

namespace railwear {
namespace {

void Run(benchmark::State& state, const CurvingProblem& p) {
  CurvingResult r;
  for (auto _ : state) {
    r = SolveCurving(p);
    if (r.status != CurvingStatus::kConverged) state.SkipWithError(r.message.c_str());
  }
  state.counters["contact_solves"] = r.contact_solves;
  state.counters["predictor_iterations"] = r.predictor_iterations;
  state.counters["full_iterations"] = r.full_iterations;
  state.counters["residual"] = r.largest_scaled_residual;
  state.counters["table_evaluations"] = r.table_evaluations;
  state.counters["table_build_s"] = r.table_build_s;
  state.counters["table_fell_back"] = r.table_predictor == TablePredictorOutcome::kFellBack;
  // Where the predictor's phase ended against the solution (the largest over the wheelsets) and
  // the full model's largest scaled residual there: how far the finish had to go.
  double off_y = 0.0, off_psi = 0.0;
  if (r.predictor_state.size() == r.state.size()) {
    for (int i = 0; i < static_cast<int>(r.wheelsets.size()); ++i) {
      off_y = std::max(off_y, std::abs(r.predictor_state[2 * i] - r.state[2 * i]));
      off_psi = std::max(off_psi, std::abs(r.predictor_state[2 * i + 1] - r.state[2 * i + 1]));
    }
  }
  state.counters["predictor_off_y_mm"] = off_y * 1e3;
  state.counters["predictor_off_psi_mrad"] = off_psi * 1e3;
  state.counters["finish_start_residual"] = r.finish_start_residual;
}

void BM_CurvingFreeWheelset(benchmark::State& state) {
  Run(state, test::BaseProblem(test::MakeCone(0.05), 1000.0));
}
BENCHMARK(BM_CurvingFreeWheelset)->Unit(benchmark::kMillisecond);

void BM_CurvingRigidBogie(benchmark::State& state) {
  Run(state, test::ConeBogie(0.05, 3000.0, 1e10));
}
BENCHMARK(BM_CurvingRigidBogie)->Unit(benchmark::kMillisecond);

void BM_CurvingFreeWheelsetStandard(benchmark::State& state) {
  CurvingProblem p = test::BaseProblem(test::MakeCone(0.05), 1000.0);
  p.contact.model.accuracy = AccuracyPreset::kStandard;  // the draft predictor by default
  Run(state, p);
}
BENCHMARK(BM_CurvingFreeWheelsetStandard)->Unit(benchmark::kMillisecond);

// Vehicle `v` of the main job's scene on its unworn rails, at the scene's accuracy (draft) or
// the standard one with that accuracy's defaults (the table predictor and warm contact solves).
CurvingProblem ExampleProblem(int v, bool standard) {
  const app::Scene scene =
      app::LoadScene(std::string(RAILWEAR_SOURCE_DIR) + "/examples/curve_r600_vehicles.toml");
  const WearStudy& study = *scene.wear;
  const WearState s0 = MakeInitialState(study);
  CurvingProblem p = VehicleCurvingProblem(study, v, RailInTrack(study, s0.rail, s0.rail),
                                           RailInTrack(study, *s0.low_rail, *s0.low_rail));
  p.options.start.reset();
  if (standard) p.contact.model.accuracy = AccuracyPreset::kStandard;
  return p;
}

// ExampleProblem 0.5 m/s faster, started from its solution at the scene's speed (a wear step's
// start: the step before's solution).
CurvingProblem ContinuedExample(int v, bool standard) {
  CurvingProblem p = ExampleProblem(v, standard);
  p.options.start = SolveCurving(p).Start();
  p.speed_m_s += 0.5;
  return p;
}

void BM_CurvingExample(benchmark::State& state) {
  Run(state, ExampleProblem(static_cast<int>(state.range(0)), state.range(1) == 1));
}
BENCHMARK(BM_CurvingExample)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_CurvingExampleContinuation(benchmark::State& state) {
  Run(state, ContinuedExample(static_cast<int>(state.range(0)), state.range(1) == 1));
}
BENCHMARK(BM_CurvingExampleContinuation)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// BM_CurvingExample and BM_CurvingExampleContinuation with warm contact solves
// (CurvingOptions::warm_contact): the same solve, each wheelset's contact starting from its
// stream's last solve; also reports how far the solution lies from the cold contact's (the
// largest over the wheelsets: off_cold_y_mm, off_cold_psi_mrad; off_cold_jacobian, the largest
// relative change of a wheelset's 2 x 2 block of the returned Jacobian).
void RunWarm(benchmark::State& state, CurvingProblem p, bool table = false) {
  // The reference: cold contact solves through the model predictor (the default before; at
  // standard the default is now the table with warm contact solves).
  p.options.cold_predictor = CurvingPredictor::kModel;
  p.options.warm_contact = false;
  const CurvingResult cold = SolveCurving(p);
  p.options.warm_contact = true;
  if (table) p.options.cold_predictor = CurvingPredictor::kTable;
  Run(state, p);
  const CurvingResult warm = SolveCurving(p);
  double off_y = 0.0, off_psi = 0.0, off_j = 0.0;
  for (int i = 0; i < static_cast<int>(cold.wheelsets.size()); ++i) {
    off_y = std::max(off_y, std::abs(warm.state[2 * i] - cold.state[2 * i]));
    off_psi = std::max(off_psi, std::abs(warm.state[2 * i + 1] - cold.state[2 * i + 1]));
    if (warm.jacobian.size() == cold.jacobian.size() && cold.jacobian.size() > 0) {
      const Eigen::Matrix2d c = cold.jacobian.block<2, 2>(2 * i, 2 * i);
      const Eigen::Matrix2d w = warm.jacobian.block<2, 2>(2 * i, 2 * i);
      off_j = std::max(off_j, (w - c).norm() / c.norm());
    }
  }
  state.counters["off_cold_y_mm"] = off_y * 1e3;
  state.counters["off_cold_psi_mrad"] = off_psi * 1e3;
  state.counters["off_cold_jacobian"] = off_j;
  state.counters["cold_contact_solves"] = cold.contact_solves;
}

void BM_CurvingExampleWarm(benchmark::State& state) {
  RunWarm(state, ExampleProblem(static_cast<int>(state.range(0)), state.range(1) == 1));
}
BENCHMARK(BM_CurvingExampleWarm)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_CurvingExampleContinuationWarm(benchmark::State& state) {
  RunWarm(state, ContinuedExample(static_cast<int>(state.range(0)), state.range(1) == 1));
}
BENCHMARK(BM_CurvingExampleContinuationWarm)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// BM_CurvingExampleWarm with T (third argument) = 0 as it is, 1 through the table predictor
// (CurvingPredictor::kTable): T = 1 at A = 1 is the default at standard.
void BM_CurvingExampleWarmCombination(benchmark::State& state) {
  RunWarm(state, ExampleProblem(static_cast<int>(state.range(0)), state.range(1) == 1),
          state.range(2) == 1);
}
BENCHMARK(BM_CurvingExampleWarmCombination)
    ->ArgsProduct({{0, 1}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// How near a cold solve's start must be (issue 15, docs/curving.md "Starts other than the centred
// one"): vehicle V at draft from its own solution's state with every wheelset moved S x 0.1 mm
// toward the track centre (the yaws, the frames and the body as solved), without its Jacobian,
// so the solve evaluates one afresh as a cold solve does. S = 0 is the floor (one evaluation).
void BM_CurvingExampleShiftedStart(benchmark::State& state) {
  CurvingProblem p = ExampleProblem(static_cast<int>(state.range(0)), false);
  const CurvingResult solved = SolveCurving(p);
  CurvingStart start{solved.state, {}, {}, {}};
  for (int i = 0; i < p.vehicle.wheelsets(); ++i) start.state[2 * i] -= state.range(1) * 1e-4;
  p.options.start = start;
  Run(state, p);
}
BENCHMARK(BM_CurvingExampleShiftedStart)
    ->ArgsProduct({{0, 1}, {0, 1, 5, 10, 20}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_CurvingExampleTable(benchmark::State& state) {
  CurvingProblem p = ExampleProblem(static_cast<int>(state.range(0)), state.range(1) == 1);
  p.options.cold_predictor = CurvingPredictor::kTable;
  // T (third argument): 0 the default table (0.1 mm nodes and sampling); 1 nodes 0.2 mm apart;
  // 2 nodes and sampling 0.2 mm.
  if (state.range(2) == 3) {
    p.options.table.patch = ContactTableOptions::Patch::kInterpenetration;
  } else {
    if (state.range(2) >= 1) p.options.table.node_spacing_m = 2e-4;
    if (state.range(2) >= 2) p.options.table.sampling_m = 2e-4;
  }
  Run(state, p);
}
BENCHMARK(BM_CurvingExampleTable)
    ->ArgsProduct({{0, 1}, {0, 1}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_ContactTableBuild(benchmark::State& state) {
  const CurvingProblem p = ExampleProblem(static_cast<int>(state.range(0)), false);
  ContactTableGeometry g;
  g.high_wheel = p.vehicle.wheel_profile;
  g.low_wheel = p.vehicle.wheel_profile;
  g.high_rail = p.high_rail;
  g.low_rail = p.low_rail;
  const double h = p.track.gauge_height_m;
  g.gauge_points = p.gauge_points ? *p.gauge_points
                                  : RailGaugePoints{RailGaugePoint(p.high_rail, h).x(),
                                                    RailGaugePoint(p.low_rail, h).x()};
  g.track = p.track;
  g.wheelset = p.vehicle.WheelsetAt(0.0, 0.0, 0.0);
  ContactTableOptions o = p.options.table;
  o.threads = p.options.threads;
  for (auto _ : state) {
    const ContactTable table(g, o);
    benchmark::DoNotOptimize(table.size());
  }
}
BENCHMARK(BM_ContactTableBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One wheelset evaluation on the coach's table: y 6 mm (flange contact on R 600 m), 2 mrad.
void BM_ContactTableEvaluate(benchmark::State& state) {
  const CurvingProblem p = ExampleProblem(0, false);
  ContactTableGeometry g;
  g.high_wheel = g.low_wheel = p.vehicle.wheel_profile;
  g.high_rail = p.high_rail;
  g.low_rail = p.low_rail;
  const double h = p.track.gauge_height_m;
  g.gauge_points =
      RailGaugePoints{RailGaugePoint(p.high_rail, h).x(), RailGaugePoint(p.low_rail, h).x()};
  g.track = p.track;
  g.wheelset = p.vehicle.WheelsetAt(0.0, 0.0, 0.0);
  const ContactTable table(g, p.options.table);
  ContactTableLoad load;
  load.high_load_N = load.low_load_N = 0.5 * p.vehicle.axle_load_N;
  load.speed_m_s = p.speed_m_s;
  load.curvature_per_m = p.curve.curvature_per_m();
  load.friction = p.friction;
  for (auto _ : state) benchmark::DoNotOptimize(table.Evaluate(6.05e-3, 2e-3, load));
}
BENCHMARK(BM_ContactTableEvaluate)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
