// Exact steady-rolling tangential solver on the README §4 check case (Hertz a = 8 mm along x,
// b = 4 mm, Fn = 82 kN, G = 82 GPa, nu = 0.28, mu = 0.3, eta = -6.25e-4, phi = 0.625 /m) on an
// nx x ns grid covering the ellipse's bounding box, with the default options (Anderson-
// accelerated sweeps) and, for comparison, the previous method (plain sweeps, relaxation 0.3).
// BM_TangentialExactSmallPatch: the products on small patches (ExactTangentialOptions::Method
// kAuto's loaded cells' matrix against kFft), for kLoadedDenseMaxCells. Run e.g.
//   build/tests/benchmarks/tangential_exact_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>

#include "core/contact/tangential_exact.h"
#include "tests/core/contact/hertz_grid.h"

namespace railwear {
namespace {

// The check case's pressure and creepage on g (semi-axes a, b).
void CheckCaseInputs(const PatchGrid& g, double a, double b, double fn, Eigen::VectorXd* p_out,
                     RollingInput* in_out) {
  const int nx = g.nx, ns = g.ns;
  Eigen::VectorXd& p = *p_out;
  RollingInput& in = *in_out;
  p.resize(g.cells());
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
  in.speed_m_s = 1.0;
  in.friction = 0.3;
}

Material Steel() {
  Material m;
  m.poisson_ratio = 0.28;
  m.youngs_modulus_Pa = 2 * 82e9 * 1.28;
  return m;
}

void RunCheckCase(benchmark::State& state, const ExactTangentialOptions& opt) {
  const int nx = static_cast<int>(state.range(0));
  const int ns = static_cast<int>(state.range(1));
  const double a = 8e-3, b = 4e-3, fn = 82e3;
  const PatchGrid g = testing::MakeHertzGrid(a, b, nx, ns);
  Eigen::VectorXd p;
  RollingInput in;
  CheckCaseInputs(g, a, b, fn, &p, &in);
  const Material m = Steel();
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

// The check case on a creep table's grid: a circular patch (a = b = 8 mm) on mx x mx cells over
// [-a s, a s]^2, s = mx / (mx - 4) (CONTACT's test_table), the setup built once (as a table
// does); args mx, method (0 kAuto, 1 kFft). Counter loaded: the cells with pressure (kAuto uses
// the loaded cells' matrix up to kLoadedDenseMaxCells of them).
void BM_TangentialExactSmallPatch(benchmark::State& state) {
  const int mx = static_cast<int>(state.range(0));
  const double a = 8e-3, scale = static_cast<double>(mx) / (mx - 4);
  const PatchGrid g = testing::MakeHertzGrid(a * scale, a * scale, mx, mx);
  Eigen::VectorXd p;
  RollingInput in;
  CheckCaseInputs(g, a, a, 82e3, &p, &in);
  ExactTangentialOptions opt;
  opt.method = state.range(1) == 0 ? ExactTangentialOptions::Method::kAuto
                                   : ExactTangentialOptions::Method::kFft;
  const ExactTangentialSetup setup(g, Steel(), Steel(), opt.method);
  TangentialSolution s;
  for (auto _ : state) {
    s = SolveTangentialExact(g, p, in, setup, opt);
    benchmark::DoNotOptimize(&s.force_s_N);
  }
  state.counters["cells"] = g.cells();
  state.counters["loaded"] = static_cast<double>((p.array() > 0.0).count());
  state.counters["iterations"] = s.iterations;
  state.counters["converged"] = s.status == SolverStatus::kConverged ? 1 : 0;
}
BENCHMARK(BM_TangentialExactSmallPatch)
    ->ArgsProduct({{11, 13, 15, 17, 19, 21, 25}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
