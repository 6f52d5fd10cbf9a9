// Google Benchmark programs for steady-state curving (issue 15; not timed tests):
//   BM_CurvingFreeWheelset  a free conical wheelset (lambda 0.05) on R 1000 m, draft half-space
//                           model (the predictor alone);
//   BM_CurvingRigidBogie    a bogie vehicle of cone wheelsets with stiff primary suspension on
//                           R 3000 m (four wheelsets, two frames, the car body), draft model;
//   BM_CurvingFreeWheelsetStandard  the free wheelset finished with the standard-accuracy
//                           half-space model after the draft predictor.
// Each reports the wheelset contact solves it needed. Run:
//   build/tests/benchmarks/curving_bench --benchmark_repetitions=3
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "tests/core/vehicle/curving_cases.h"

namespace railwear {
namespace {

void Run(benchmark::State& state, const CurvingProblem& p) {
  int solves = 0;
  for (auto _ : state) {
    const CurvingResult r = SolveCurving(p);
    if (r.status != CurvingStatus::kConverged) state.SkipWithError(r.message.c_str());
    solves = r.contact_solves;
  }
  state.counters["contact_solves"] = solves;
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
  p.contact.model.accuracy = AccuracyPreset::kStandard;
  p.options.predictor = CurvingOptions::PredictorModel();
  Run(state, p);
}
BENCHMARK(BM_CurvingFreeWheelsetStandard)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
