// What the pressure limit (elastic-perfectly-plastic normal contact, issue 16) costs (not a
// test; docs/contact_plasticity.md quotes the measurements).
//
//  BM_PlasticSolve/n/limit_percent  the normal solve alone on an n x n planar Boussinesq grid
//                   with a Hertzian gap (elastic semi-axes at 0.45 of the grid's half-sizes, so
//                   the grown plastic patch still fits), prescribed load, operator built once
//                   outside the timing. limit_percent: 0 no limit; otherwise p_lim in percent of
//                   the elastic peak p0 (120: set but not reached, the elastic solve alone).
//  BM_GaugeCornerPlastic/limit_MPa  the whole pipeline (SolveContact) on examples/
//                   gauge_corner.toml's problem (S1002 on UIC60 1:40, shift -4 mm, 100 kN,
//                   conformal model, standard preset; elastic peak 2581 MPa); limit_MPa 0 for
//                   none.
//
// Run: build/tests/benchmarks/plastic_bench --benchmark_repetitions=3
//        --benchmark_report_aggregates_only=true
#include <cmath>
#include <string>

#include <benchmark/benchmark.h>

#include "core/contact/contact_solver.h"
#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"
#include "core/profile/builtin_profiles.h"
#include "tests/benchmarks/bench_grids.h"

namespace railwear {
namespace {

using bench::kCell_m;
const Material kSteel{210e9, 0.28};

void BM_PlasticSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const double percent = static_cast<double>(state.range(1));
  PatchGrid g = bench::MakeBenchGrid(n, n, /*planar=*/true);
  const double R = 0.3;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      g.gap_m[g.Index(i, j)] = (g.X(i) * g.X(i) + g.S(j) * g.S(j)) / (2 * R);
  const double a = 0.45 * 0.5 * n * kCell_m;
  const HertzSolution h =
      SolveHertzForApproach(1 / (2 * R), 1 / (2 * R), ContactModulus(kSteel, kSteel), a * a / R);
  const auto op =
      MakeInfluenceOperator(g, InfluenceSettings{KernelModel::kBoussinesq, {}, kSteel, kSteel});
  NormalProblem np;
  np.blocks = {op.get()};
  np.gap_m = g.gap_m;
  np.approach_weight = Eigen::VectorXd::Ones(g.cells());
  np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
  np.force_N = h.force_N;
  if (percent > 0) np.pressure_limit_Pa = percent / 100.0 * h.p0_Pa;
  NormalSolution sol;
  for (auto _ : state) {
    sol = SolveNormal(np);
    benchmark::DoNotOptimize(sol.pressure_Pa.data());
  }
  int in_contact = 0;
  for (int k = 0; k < sol.pressure_Pa.size(); ++k) in_contact += sol.pressure_Pa[k] > 0;
  state.counters["cells"] = g.cells();
  state.counters["in_contact"] = in_contact;
  state.counters["plastic"] = sol.plastic_cells;
  state.counters["iterations"] = sol.iterations;
  state.counters["applies"] = sol.operator_applications;
  state.counters["converged"] = sol.status == SolverStatus::kConverged;
}
BENCHMARK(BM_PlasticSolve)
    ->ArgsProduct({{40, 80}, {0, 120, 70, 50, 30}})
    ->Unit(benchmark::kMillisecond);

void BM_GaugeCornerPlastic(benchmark::State& state) {
  ContactProblem p;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.placement.lateral_shift_m = -4e-3;
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 100e3;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.accuracy = AccuracyPreset::kStandard;
  if (state.range(0) > 0) {
    p.pressure_limit.kind = PressureLimitKind::kValue;
    p.pressure_limit.value_Pa = state.range(0) * 1e6;
  }
  ContactResult r;
  for (auto _ : state) {
    r = SolveContact(p);
    benchmark::DoNotOptimize(r.patches.data());
  }
  state.counters["area_mm2"] = r.area_m2 * 1e6;
  state.counters["p_max_MPa"] = r.p_max_Pa * 1e-6;
  state.counters["plastic"] = r.plastic_cells;
  state.counters["iterations"] = r.iterations;
  state.counters["converged"] = r.status == SolverStatus::kConverged;
}
BENCHMARK(BM_GaugeCornerPlastic)
    ->Arg(0)
    ->Arg(2600)
    ->Arg(1800)
    ->Arg(1200)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
