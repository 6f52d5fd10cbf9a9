// FASTSIM timing on a Hertz patch (the README §4 check case: a = 8, b = 4 mm, Fn = 82 kN,
// eta = -6.25e-4, phi = 0.625 /m) on a 70 x 80 grid covering the ellipse; and the tangential
// stage of each method on the spin-dominated flange patch of issue 16 (BM_FlangeTangential).
// Run: build/tests/benchmarks/tangential_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <numbers>

#include "core/contact/contact_solver.h"
#include "core/contact/fastsim.h"
#include "core/contact/kinematics.h"
#include "core/contact/placement_stage.h"
#include "core/contact/tangential_method.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "tests/core/contact/flange_case.h"
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

// The tangential stage alone (the method's solve on the patch's grid, pressure and rigid slip)
// on the S1002 flange at -3 mm on UIC60 1:40, 80 kN, mu 0.35, yaw -5 mrad, conformal geometry
// with the Boussinesq kernel at standard (tests/core/contact/tangential_method_test.cpp,
// SpinDominatedFlangeIsWithinTheToleranceOfExact): the normal solution is computed once with
// FASTSIM's creep forces, then each iteration solves its tangential problem. Arg: 0 fastsim,
// 1 exact, 2 auto (which chooses exact here: FASTSIM's 1 sweep plus the exact solve).
void BM_FlangeTangential(benchmark::State& state) {
  static const auto setup = [] {
    const ContactProblem p = testing::SpinDominatedFlangeProblem(TangentialMethod::kFastsim);
    const ContactResult res = SolveContact(p);
    const PatchResult& patch = *std::max_element(
        res.patches.begin(), res.patches.end(),
        [](const PatchResult& a, const PatchResult& b) {
          return a.normal_force_N < b.normal_force_N;
        });
    const WheelRailGeometry geom = internal::PlaceWheel(p);  // as SolveContact places it
    const RollingInput in =
        RigidSlipFromMotion(geom, patch.grid, p.rolling->motion, p.rolling->friction);
    return std::make_tuple(p, patch, in);
  }();
  const auto& [problem, patch, input] = setup;
  const TangentialMethod method = state.range(0) == 0   ? TangentialMethod::kFastsim
                                  : state.range(0) == 1 ? TangentialMethod::kExact
                                                        : TangentialMethod::kAuto;
  TangentialChoice choice;
  for (auto _ : state) {
    const TangentialSolution s =
        SolveTangential(method, AccuracyPreset::kStandard, patch.grid, patch.pressure_Pa, input,
                        problem.wheel_material, problem.rail_material, &choice);
    benchmark::DoNotOptimize(s.force_s_N);
    state.counters["Fx_N"] = s.force_x_N;
    state.counters["Fy_N"] = s.force_s_N;
  }
  state.counters["exact"] = choice.method == TangentialMethod::kExact ? 1 : 0;
  state.counters["cells_in_contact"] = patch.cells_in_contact;
  state.SetLabel(std::string(ToString(method)));
}
BENCHMARK(BM_FlangeTangential)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
