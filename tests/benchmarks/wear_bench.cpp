// Google Benchmark programs for the wear loop (issue 4 targets; not timed tests):
//   BM_WearStep100Cases   one wear step with 100 load cases (20 traffic entries x 5 Gauss-Hermite
//                         nodes) of S1002 on UIC60 1:40 at standard accuracy, all cores
//                         (target: under 10 s on 2 cores);
//   BM_WearRun1e5Passes   a whole run of 10^5 passes of the default study's traffic
//                         (examples/wear_high_rail.toml at standard accuracy), reporting the
//                         number of profile updates (target: under 10 minutes in at most 50);
//   BM_WearStepVehicles/W a wear step of the main job's scene (examples/curve_r600_vehicles.toml:
//                         coach and Y25 wagon, R 600 m, both rails, draft accuracy) with each
//                         vehicle entry also at a second speed (coach 22 m/s, wagon 17 m/s): four
//                         vehicles' curving and 96 load cases (4 wheelsets x 3 Gauss-Hermite
//                         nodes x 2 rails each, in place of the scene's own 20-node rule), all
//                         cores (issue 15's target: 100 cases with curving under 10 s
//                         on 2 cores). W = 0: the first step, every curving from the centred
//                         start; W = 1: the second, each curving from the first step's solution
//                         (WearState::curving), as every step of a run after the first.
// Run: build/tests/benchmarks/wear_bench --benchmark_repetitions=3
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "app/scene.h"
#include "core/profile/builtin_profiles.h"
#include "wear/wear_simulation.h"

namespace railwear {
namespace {

TrafficCase MakeTraffic(const char* name, double load_N, double axle_t, double mean_mm,
                        double yaw_mrad, double speed, double share) {
  TrafficCase c;
  c.name = name;
  c.wheel_profile = MakeS1002();
  c.vertical_force_N = load_N;
  c.axle_load_t = axle_t;
  c.lateral_shift_mean_m = mean_mm * 1e-3;
  c.lateral_shift_std_m = 1.0e-3;
  c.yaw_rad = yaw_mrad * 1e-3;
  c.friction = 0.35;
  c.speed_m_s = speed;
  c.share = share;
  return c;
}

WearStudy MakeStudy() {
  WearStudy study;
  study.rail_profile = MakeUic60();
  study.cant_ratio = 0.025;
  study.rail_material.hardness_Pa = 2.6e9;
  study.rail_material.shear_yield_Pa = 350e6;
  study.model = MakeModelOptions(ModelKind::kConformal);
  study.model.kernel = KernelModel::kBoussinesq;
  study.model.kind = ModelKind::kCustom;
  study.model.accuracy = AccuracyPreset::kStandard;
  study.damage = true;
  study.options.law.kind = WearLawKind::kKthContinuous;
  study.options.quadrature_points = 5;
  return study;
}

void BM_WearStep100Cases(benchmark::State& state) {
  WearStudy study = MakeStudy();
  for (int k = 0; k < 20; ++k) {  // a spread of loads, positions and angles of attack
    study.traffic.push_back(MakeTraffic("case", 60e3 + 3e3 * k, 12.0 + 0.6 * k, -5.5 + 0.1 * k,
                                        1.0 + 0.25 * k, 20.0 + k, 1.0));
  }
  study.options.total_passes = 1e9;
  const WearState start = MakeInitialState(study);
  for (auto _ : state) {
    StepResult step = RunWearStep(study, start.rail, start, 1e9);
    benchmark::DoNotOptimize(&step);
    state.counters["load_cases"] = static_cast<double>(step.cases.size());
  }
}
BENCHMARK(BM_WearStep100Cases)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_WearRun1e5Passes(benchmark::State& state) {
  WearStudy study = MakeStudy();
  study.traffic = {MakeTraffic("freight", 110e3, 22.5, -4.5, 4.0, 22.0, 0.4),
                   MakeTraffic("passenger", 80e3, 16.0, -5.0, 3.0, 33.0, 0.6)};
  study.options.total_passes = 1e5;
  for (auto _ : state) {
    const WearState start = MakeInitialState(study);
    const WearRunSummary run = RunWear(study, start.rail, start, nullptr);
    state.counters["profile_updates"] = run.steps_done;
    benchmark::DoNotOptimize(&run);
  }
}
BENCHMARK(BM_WearRun1e5Passes)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_WearStepVehicles(benchmark::State& state) {
  const app::Scene scene =
      app::LoadScene(std::string(RAILWEAR_SOURCE_DIR) + "/examples/curve_r600_vehicles.toml");
  WearStudy study = *scene.wear;
  study.options.spread_nodes.clear();  // the 100 cases: 3 Gauss-Hermite nodes
  study.options.quadrature_points = 3;
  const double second_speed[2] = {22.0, 17.0};
  for (int t = 0; t < 2; ++t) {
    TrafficCase c = study.traffic[t];
    c.name += " (second speed)";
    c.speed_m_s = second_speed[t];
    study.traffic.push_back(c);
  }
  WearState start = MakeInitialState(study);
  const UnwornRails unworn = UnwornRails::Of(start);
  if (state.range(0) == 1) start = RunWearStep(study, unworn, start, 1e12).state;
  for (auto _ : state) {
    StepResult step = RunWearStep(study, unworn, start, 1e12);
    benchmark::DoNotOptimize(&step);
    state.counters["load_cases"] = static_cast<double>(step.cases.size());
  }
}
BENCHMARK(BM_WearStepVehicles)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
