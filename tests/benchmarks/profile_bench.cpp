// Profile validation: the cost of the defect checks (duplicates, turn-backs, the self-crossing
// sweep of core/profile/profile_defects.h) against the number of points, on the built-in UIC60
// and S1002 sampled from 0.5 mm down to 0.01 mm (some 150 to 8000 points: the sizes of measured
// and tabulated profiles), beside the whole Profile construction (checks plus spline) that it
// is part of; and the evaluation of a profile at arbitrary arc lengths (the spline's interval
// lookup and polynomial: 35 % of a curving solve's time before the lookup became a bucket index,
// docs/speed.md).
//
// Run: build/tests/benchmarks/profile_bench --benchmark_repetitions=3
//        --benchmark_report_aggregates_only=true
#include <random>

#include <benchmark/benchmark.h>

#include "core/profile/builtin_profiles.h"
#include "core/profile/profile_defects.h"

namespace railwear {
namespace {

// state.range(0): sampling step in um.
Profile Sampled(const benchmark::State& state, bool wheel) {
  const double step_m = state.range(0) * 1e-6;
  return wheel ? MakeS1002(step_m) : MakeUic60(step_m);
}

void BM_FindProfileDefect(benchmark::State& state, bool wheel) {
  const Profile p = Sampled(state, wheel);
  for (auto _ : state) benchmark::DoNotOptimize(FindProfileDefect(p.points()));
  state.counters["points"] = p.size();
}

void BM_ConstructProfile(benchmark::State& state, bool wheel) {
  const Profile p = Sampled(state, wheel);
  for (auto _ : state) benchmark::DoNotOptimize(Profile(p.points(), "bench"));
  state.counters["points"] = p.size();
}

// 1000 evaluations of position and derivatives at uniformly random arc lengths (fixed seed).
void BM_EvaluateProfile(benchmark::State& state, bool wheel) {
  const Profile p = Sampled(state, wheel);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, p.Length());
  std::vector<double> s(1000);
  for (double& x : s) x = u(rng);
  Eigen::Vector2d pos, d1, d2;
  for (auto _ : state) {
    for (double x : s) {
      p.Evaluate(x, &pos, &d1, &d2);
      benchmark::DoNotOptimize(pos);
    }
  }
  state.counters["points"] = p.size();
}

BENCHMARK_CAPTURE(BM_FindProfileDefect, uic60, false)->Arg(500)->Arg(100)->Arg(30)->Arg(10);
BENCHMARK_CAPTURE(BM_FindProfileDefect, s1002, true)->Arg(500)->Arg(100)->Arg(30)->Arg(10);
BENCHMARK_CAPTURE(BM_ConstructProfile, uic60, false)->Arg(500)->Arg(100)->Arg(30)->Arg(10);
BENCHMARK_CAPTURE(BM_ConstructProfile, s1002, true)->Arg(500)->Arg(100)->Arg(30)->Arg(10);
BENCHMARK_CAPTURE(BM_EvaluateProfile, uic60, false)->Arg(500)->Arg(100)->Arg(30)->Arg(10);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
