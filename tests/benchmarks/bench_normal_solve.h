// The timed loop of the normal-solve benchmarks (contact_bench, contact_reference_bench): build
// the influence operator and solve, then report the solution as counters.
#pragma once

#include <benchmark/benchmark.h>

#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"

namespace railwear::bench {

// Times operator construction plus SolveNormal on grid g (np's gap, weights, areas and load or
// approach set by the caller; np.blocks is set here), the operator's structure along s as
// `structure` asks (influence_operator.h). Counters: cells, in_contact, iterations,
// converged, applies, pc_applies, p_max_MPa, Fn_kN. Returns the last solution.
inline NormalSolution TimeNormalSolve(benchmark::State& state, const PatchGrid& g,
                                      const InfluenceSettings& settings, NormalProblem np,
                                      const NormalSolverOptions& options,
                                      SectionStructure structure = SectionStructure::kAuto) {
  NormalSolution sol;
  for (auto _ : state) {
    const auto op = MakeInfluenceOperator(g, settings, OperatorProducts::kAuto, structure);
    np.blocks = {op.get()};
    sol = SolveNormal(np, options);
    benchmark::DoNotOptimize(sol.pressure_Pa.data());
  }
  int in_contact = 0;
  for (int k = 0; k < sol.pressure_Pa.size(); ++k) in_contact += sol.pressure_Pa[k] > 0;
  state.counters["cells"] = g.cells();
  state.counters["in_contact"] = in_contact;
  state.counters["iterations"] = sol.iterations;
  state.counters["converged"] = sol.status == SolverStatus::kConverged;
  state.counters["applies"] = sol.operator_applications;
  state.counters["pc_applies"] = sol.preconditioner_applications;
  state.counters["p_max_MPa"] = sol.pressure_Pa.size() > 0 ? sol.pressure_Pa.maxCoeff() * 1e-6 : 0;
  state.counters["Fn_kN"] = sol.pressure_Pa.sum() * g.CellArea() * 1e-3;
  return sol;
}

}  // namespace railwear::bench
