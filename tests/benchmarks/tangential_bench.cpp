// FASTSIM timing on a Hertz patch (the README §4 check case: a = 8, b = 4 mm, Fn = 82 kN,
// eta = -6.25e-4, phi = 0.625 /m) on a 70 x 80 grid covering the ellipse.
// Run: build/tests/benchmarks/tangential_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "core/contact/fastsim.h"
#include "tests/core/contact/hertz_grid.h"

namespace railwear {
namespace {

void BM_Fastsim(benchmark::State& state) {
  const int nx = static_cast<int>(state.range(0)), ns = static_cast<int>(state.range(1));
  const double a = 8e-3, b = 4e-3, fn = 82e3;
  const PatchGrid g = testing::MakeHertzGrid(a, b, nx, ns);
  const double p0 = 3.0 * fn / (2.0 * std::numbers::pi * a * b);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(g.cells());
  RollingInput in;
  in.creep_x.resize(g.cells());
  in.creep_s.resize(g.cells());
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double r = 1.0 - std::pow(g.X(i) / a, 2) - std::pow(g.S(j) / b, 2);
      p[g.Index(i, j)] = r > 0.0 ? p0 * std::sqrt(r) : 0.0;
      in.creep_x[g.Index(i, j)] = -0.625 * g.S(j);
      in.creep_s[g.Index(i, j)] = -6.25e-4 + 0.625 * g.X(i);
    }
  }
  FastsimOptions opt;
  opt.shear_modulus_Pa = 82e9;
  for (auto _ : state) {
    TangentialSolution s = SolveFastsim(g, p, in, opt);
    benchmark::DoNotOptimize(s.force_s_N);
  }
  state.counters["cells"] = g.cells();
}
BENCHMARK(BM_Fastsim)->Args({70, 80})->Args({200, 200})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
