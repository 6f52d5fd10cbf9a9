// Exact steady-rolling tangential solver on the README §4 check case (Hertz a = 8 mm along x,
// b = 4 mm, Fn = 82 kN, G = 82 GPa, nu = 0.28, mu = 0.3, eta = -6.25e-4, phi = 0.625 /m) on an
// nx x ns grid covering the ellipse's bounding box, with the default options (Anderson-
// accelerated sweeps) and, for comparison, the previous method (plain sweeps, relaxation 0.3).
// Run e.g.
//   build/tests/benchmarks/tangential_exact_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>

#include "core/contact/tangential_exact.h"
#include "tests/core/contact/hertz_grid.h"

namespace railwear {
namespace {

void RunCheckCase(benchmark::State& state, const ExactTangentialOptions& opt) {
  const int nx = static_cast<int>(state.range(0));
  const int ns = static_cast<int>(state.range(1));
  const double a = 8e-3, b = 4e-3, fn = 82e3;
  const PatchGrid g = testing::MakeHertzGrid(a, b, nx, ns);
  Eigen::VectorXd p(g.cells());
  RollingInput in;
  in.creep_x.resize(g.cells());
  in.creep_s.resize(g.cells());
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int k = g.Index(i, j);
      const double u = g.X(i) / a, v = g.S(j) / b;
      p[k] = std::sqrt(std::max(0.0, 1.0 - u * u - v * v));
      in.creep_x[k] = -0.625 * g.S(j);
      in.creep_s[k] = -6.25e-4 + 0.625 * g.X(i);
    }
  }
  p *= fn / (p.sum() * g.CellArea());
  Material m;
  m.poisson_ratio = 0.28;
  m.youngs_modulus_Pa = 2 * 82e9 * 1.28;
  TangentialSolution s;
  for (auto _ : state) {
    s = SolveTangentialExact(g, p, in, m, m, opt);
    benchmark::DoNotOptimize(s.force_s_N);
  }
  state.counters["cells"] = g.cells();
  state.counters["iterations"] = s.iterations;
  state.counters["converged"] = s.status == SolverStatus::kConverged ? 1 : 0;
}
void BM_TangentialExactCheckCase(benchmark::State& state) { RunCheckCase(state, {}); }
BENCHMARK(BM_TangentialExactCheckCase)
    ->Args({40, 20})
    ->Args({64, 32})
    ->Args({70, 80})
    ->Unit(benchmark::kMillisecond);

// The method before the acceleration: plain relaxed sweeps at the relaxation that needs.
void BM_TangentialExactCheckCaseUnaccelerated(benchmark::State& state) {
  ExactTangentialOptions opt;
  opt.anderson_depth = 0;
  opt.relaxation = 0.3;
  RunCheckCase(state, opt);
}
BENCHMARK(BM_TangentialExactCheckCaseUnaccelerated)->Args({70, 80})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
