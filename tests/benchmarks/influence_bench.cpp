// Influence operators: construction time and Apply time against cell count.
//
// Planar grid + Boussinesq (the half-space model, 2-D FFT) and circular-arc cross-section of
// radius 10 mm + Golubenko (the conformal model, x-FFT with an ns x ns block per frequency).
// Grids are built directly (uniform line / arc, 0.1 mm cells, zero gap); E = 210 GPa,
// nu = 0.28 for both bodies.
//
// Run: build/tests/benchmarks/influence_bench --benchmark_repetitions=3
//        --benchmark_report_aggregates_only=true
#include <cmath>
#include <random>

#include <benchmark/benchmark.h>

#include "core/contact/influence_operator.h"
#include "tests/benchmarks/bench_grids.h"

namespace railwear {
namespace {

PatchGrid MakeGrid(int nx, int ns, bool planar) { return bench::MakeBenchGrid(nx, ns, planar); }

InfluenceSettings MakeSettings(KernelModel kernel) {
  InfluenceSettings s;
  s.kernel = kernel;
  return s;  // default materials: E = 210 GPa, nu = 0.28
}

void SetCounters(benchmark::State& state, const PatchGrid& grid) {
  state.counters["cells"] = grid.cells();
  state.counters["nx"] = grid.nx;
  state.counters["ns"] = grid.ns;
}

void BM_PlanarBoussinesqConstruct(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, true);
  const InfluenceSettings settings = MakeSettings(KernelModel::kBoussinesq);
  for (auto _ : state) {
    auto op = MakeInfluenceOperator(grid, settings);
    benchmark::DoNotOptimize(op.get());
  }
  SetCounters(state, grid);
}

void BM_PlanarBoussinesqApply(benchmark::State& state) {
  const PatchGrid grid =
      MakeGrid(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), true);
  const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kBoussinesq));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> pressure(0.0, 1e9);
  Eigen::VectorXd p(grid.cells()), u;
  for (int k = 0; k < p.size(); ++k) p[k] = pressure(rng);
  for (auto _ : state) {
    op->Apply(p, &u);
    benchmark::DoNotOptimize(u.data());
  }
  SetCounters(state, grid);
}

void BM_CurvedGolubenkoConstruct(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, false);
  const InfluenceSettings settings = MakeSettings(KernelModel::kGolubenko);
  for (auto _ : state) {
    auto op = MakeInfluenceOperator(grid, settings);
    benchmark::DoNotOptimize(op.get());
  }
  SetCounters(state, grid);
}

void BM_CurvedGolubenkoApply(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, false);
  const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kGolubenko));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> pressure(0.0, 1e9);
  Eigen::VectorXd p(grid.cells()), u;
  for (int k = 0; k < p.size(); ++k) p[k] = pressure(rng);
  for (auto _ : state) {
    op->Apply(p, &u);
    benchmark::DoNotOptimize(u.data());
  }
  SetCounters(state, grid);
}

// The dense reference on the same curved grids, for the speed-up figure.
void BM_CurvedGolubenkoDenseApply(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, false);
  const auto op = MakeDenseInfluenceOperator(grid, MakeSettings(KernelModel::kGolubenko));
  Eigen::VectorXd p = Eigen::VectorXd::Ones(grid.cells()), u;
  for (auto _ : state) {
    op->Apply(p, &u);
    benchmark::DoNotOptimize(u.data());
  }
  SetCounters(state, grid);
}

BENCHMARK(BM_PlanarBoussinesqConstruct)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanarBoussinesqApply)
    ->Args({32, 32})
    ->Args({64, 64})
    ->Args({71, 81})
    ->Args({128, 128})
    ->Args({256, 256})
    ->Args({512, 512})
    ->Args({575, 647})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurvedGolubenkoConstruct)
    ->Arg(20)
    ->Arg(45)
    ->Arg(60)
    ->Arg(80)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurvedGolubenkoApply)
    ->Arg(20)
    ->Arg(45)
    ->Arg(60)
    ->Arg(80)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurvedGolubenkoDenseApply)->Arg(20)->Arg(45)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
