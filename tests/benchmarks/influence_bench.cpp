// Influence operators: construction time and Apply time against cell count.
//
// Planar grid + Boussinesq (the half-space model, 2-D FFT) and circular-arc cross-section of
// radius 10 mm + Golubenko (the conformal model): BM_CurvedGolubenko* with the x-FFT and an
// ns x ns block per frequency forced (SectionStructure::kBlocks, what every curved grid used
// before issue 18 point 3), BM_ArcGolubenko* as MakeInfluenceOperator chooses on the uniform
// arc (the 2-D FFT, Toeplitz in s as well).
// Grids are built directly (uniform line / arc, 0.1 mm cells, zero gap); E = 210 GPa,
// nu = 0.28 for both bodies.
//
// Apply families: the last argument picks the products (0 FFT, 1 dense; OperatorProducts).
//
// Run: build/tests/benchmarks/influence_bench --benchmark_repetitions=3
//        --benchmark_report_aggregates_only=true
#include <cmath>
#include <random>
#include <utility>

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

// The products' last argument: 0 FFT, 1 dense (OperatorProducts; kAuto picks dense up to
// kDenseProductMaxCells cells, the crossover these two measure).
OperatorProducts ProductsArg(int64_t arg) {
  return arg == 0 ? OperatorProducts::kFft : OperatorProducts::kDense;
}

void BM_PlanarBoussinesqApply(benchmark::State& state) {
  const PatchGrid grid =
      MakeGrid(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), true);
  const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kBoussinesq),
                                        ProductsArg(state.range(2)));
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

void ArcConstruct(benchmark::State& state, SectionStructure structure) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, false);
  const InfluenceSettings settings = MakeSettings(KernelModel::kGolubenko);
  for (auto _ : state) {
    auto op = MakeInfluenceOperator(grid, settings, OperatorProducts::kAuto, structure);
    benchmark::DoNotOptimize(op.get());
  }
  SetCounters(state, grid);
}
void BM_CurvedGolubenkoConstruct(benchmark::State& state) {
  ArcConstruct(state, SectionStructure::kBlocks);
}
void BM_ArcGolubenkoConstruct(benchmark::State& state) {
  ArcConstruct(state, SectionStructure::kAuto);
}

void ArcApply(benchmark::State& state, SectionStructure structure) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, false);
  const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kGolubenko),
                                        ProductsArg(state.range(1)), structure);
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
void BM_CurvedGolubenkoApply(benchmark::State& state) {
  ArcApply(state, SectionStructure::kBlocks);
}
void BM_ArcGolubenkoApply(benchmark::State& state) { ArcApply(state, SectionStructure::kAuto); }

// The curved operator's preconditioner (one triangular-solve pair per x frequency), at the sizes
// of a gauge-corner call's grids (33 x 30 at standard) and above.
void BM_CurvedGolubenkoPreconditioner(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PatchGrid grid = MakeGrid(n, n, false);
  const auto op = MakeInfluenceOperator(grid, MakeSettings(KernelModel::kGolubenko),
                                        OperatorProducts::kFft, SectionStructure::kBlocks);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> residual(-1e-6, 1e-6);
  Eigen::VectorXd r(grid.cells()), z;
  for (int k = 0; k < r.size(); ++k) r[k] = residual(rng);
  for (auto _ : state) {
    op->ApplyPreconditioner(r, &z);
    benchmark::DoNotOptimize(z.data());
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
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (auto [nx, ns] : {std::pair{32, 32},
                            {64, 64},
                            {71, 81},
                            {128, 128},
                            {256, 256},
                            {512, 512},
                            {575, 647}}) {
        b->Args({nx, ns, 0});
      }
      // The dense-product crossover.
      for (int n : {6, 8, 10, 11, 12, 13, 14, 16, 20, 25}) {
        for (int dense : {0, 1}) b->Args({n, n, dense});
      }
    })
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurvedGolubenkoConstruct)
    ->Arg(20)
    ->Arg(45)
    ->Arg(60)
    ->Arg(80)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurvedGolubenkoApply)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int n : {20, 30, 45, 60, 80, 100}) b->Args({n, 0});
      for (int n : {6, 8, 10, 11, 12, 13, 14, 16, 20, 25}) b->Args({n, 1});
      for (int n : {6, 8, 10, 11, 12, 13, 14, 16, 25}) b->Args({n, 0});
    })
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ArcGolubenkoConstruct)
    ->Arg(20)
    ->Arg(45)
    ->Arg(60)
    ->Arg(80)
    ->Arg(100)
    ->Arg(181)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ArcGolubenkoApply)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int n : {20, 45, 60, 80, 100, 181, 256}) b->Args({n, 0});
    })
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurvedGolubenkoPreconditioner)
    ->Arg(30)
    ->Arg(45)
    ->Arg(100)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CurvedGolubenkoDenseApply)->Arg(20)->Arg(45)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
