// Contact solves: time against cell count for each model (not a test; see the README).
//
//  The third argument of both: the CG preconditioner (0 none, 1 the operator's inverse).
//  BM_HalfspaceSolve/nx/ns/pc planar grid, Boussinesq (the half-space model), Hertzian gap sized
//                             so that ~55 % of the cells are in contact, like CONTACT's figures
//                             (71 x 81 grid with 3,148 in contact; 575 x 647 with 201k).
//  BM_ConformalSolve/nx/ns/pc 10 mm arc cross-section, the seed's kernel, gap of a 10 mm wheel
//                             in a 10.25 mm groove; ~2,000 cells at 45 x 45. The arc is uniform
//                             (IsUniformArc), so the operator is the 2-D FFT (issue 18 point 3).
//  BM_ConformalSolveBlocks/nx/ns/pc  the same with the per-frequency blocks forced
//                             (SectionStructure::kBlocks): what every curved grid used before.
//  BM_ProfilePatchSolve/cell_um/pc  a real conformal patch: S1002 on UIC60 1:40 at the gauge
//                             corner (shift -4 mm), the flange-side candidate's grid from
//                             BuildPatchGrid (conformal, threshold 0.1 mm) with ds = cell_um and
//                             dx chosen so that nx ~ ns; prescribed approach of half the
//                             threshold; no uniform arc, so the blocks.
//  All time operator construction plus the normal solve, one thread.
//  BM_GaugeCorner/model/preset  the whole pipeline (SolveContact) on examples/gauge_corner.toml's
//                             problem: S1002 on UIC60 1:40, shift -4 mm, 100 kN. model: 0 hertz,
//                             1 halfspace, 2 conformal+boussinesq, 3 conformal+golubenko, 4 auto;
//                             preset: 0 draft, 1 standard, 2 reference, 3 fine.
//  BM_GaugeCornerYaw/model/preset/yaw_mrad  the same problem with the wheel yawed (0 or 15 mrad;
//                             issue 14): what yaw in the contact geometry costs against the
//                             unyawed solve (the yawed wheel's outline, grids centred on the
//                             leading contact point). model 1 halfspace, 2 conformal+boussinesq.
//
// Run: build/tests/benchmarks/contact_bench --benchmark_repetitions=3
//        --benchmark_report_aggregates_only=true
// Scaling exponents of time against cell count (log-log fit per benchmark family and series):
//      ... --benchmark_format=json | python3 tests/benchmarks/scaling_exponent.py
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/contact/contact_solver.h"
#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"
#include "core/geometry/patch_builder.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "core/profile/builtin_profiles.h"
#include "tests/benchmarks/bench_grids.h"
#include "tests/benchmarks/bench_normal_solve.h"

namespace railwear {
namespace {

using bench::kCell_m;
const Material kSteel{210e9, 0.28};

// Benchmark grid (bench_grids.h) with the gap x^2/(2 Rx) + s^2/(2 Rs).
PatchGrid MakeGrid(int nx, int ns, bool planar, double Rx, double Rs) {
  PatchGrid g = bench::MakeBenchGrid(nx, ns, planar);
  for (int j = 0; j < ns; ++j)
    for (int i = 0; i < nx; ++i)
      g.gap_m[g.Index(i, j)] = g.X(i) * g.X(i) / (2 * Rx) + g.S(j) * g.S(j) / (2 * Rs);
  return g;
}

void Solve(benchmark::State& state, bool planar, KernelModel kernel, double Rx, double Rs,
           SectionStructure structure = SectionStructure::kAuto) {
  const int nx = static_cast<int>(state.range(0)), ns = static_cast<int>(state.range(1));
  const PatchGrid g = MakeGrid(nx, ns, planar, Rx, Rs);
  // Hertz load for contact semi-axes at 0.834 of the grid's half-sizes (~55 % of the cells).
  const double a = 0.834 * 0.5 * nx * kCell_m, b = 0.834 * 0.5 * ns * kCell_m;
  const double estar = ContactModulus(kSteel, kSteel);
  const HertzSolution h =
      SolveHertzForApproach(1 / (2 * Rx), 1 / (2 * Rs), estar, std::max(a * a / Rx, b * b / Rs));
  InfluenceSettings settings{kernel, {}, kSteel, kSteel};
  NormalProblem np;
  np.gap_m = g.gap_m;
  np.approach_weight = Eigen::VectorXd::Ones(g.cells());
  np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
  np.force_N = h.force_N;
  NormalSolverOptions options;
  options.preconditioner =
      state.range(2) == 0 ? CgPreconditioner::kNone : CgPreconditioner::kInverseOperator;
  bench::TimeNormalSolve(state, g, settings, np, options, structure);
  state.SetLabel(std::string(ToString(options.preconditioner)));
}

void BM_HalfspaceSolve(benchmark::State& state) {
  // Laterally the Hertz radii of the ellipse follow the grid's aspect ratio.
  const double Rx = 0.3;
  const double Rs = Rx * std::pow(static_cast<double>(state.range(1)) / state.range(0), 2);
  Solve(state, /*planar=*/true, KernelModel::kBoussinesq, Rx, Rs);
}
BENCHMARK(BM_HalfspaceSolve)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (auto [nx, ns] : {std::pair{71, 81}, {142, 162}, {284, 324}, {575, 647}}) {
        for (int pc : {0, 1}) b->Args({nx, ns, pc});
      }
    })
    ->Unit(benchmark::kMillisecond);

void BM_ConformalSolve(benchmark::State& state) {
  // 10 mm wheel in a 10.25 mm groove: lateral relative radius 10 * 10.25 / 0.25 = 410 mm; the
  // longitudinal one is the 460 mm rolling radius.
  Solve(state, /*planar=*/false, KernelModel::kGolubenko, 0.46, 0.41);
}
BENCHMARK(BM_ConformalSolve)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int n : {20, 32, 45, 64, 90, 128, 181, 256}) {
        for (int pc : {0, 1}) b->Args({n, n, pc});
      }
    })
    ->Unit(benchmark::kMillisecond);

void BM_ConformalSolveBlocks(benchmark::State& state) {
  Solve(state, /*planar=*/false, KernelModel::kGolubenko, 0.46, 0.41, SectionStructure::kBlocks);
}
BENCHMARK(BM_ConformalSolveBlocks)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int n : {20, 32, 45, 64, 90, 128}) b->Args({n, n, 1});
    })
    ->Unit(benchmark::kMillisecond);

const Profile& S1002() {
  static const Profile p = MakeS1002();
  return p;
}
const Profile& Uic60Canted() {
  static const Profile p = ApplyCant(MakeUic60(), 1.0 / 40.0);
  return p;
}

// The flange-side conformal patch of S1002 on UIC60 1:40 at shift -4 mm (the candidate with the
// steepest normal), ds = cell_m and dx such that nx ~ ns, zero yaw.
PatchGrid ProfilePatchGrid(double cell_m) {
  WheelPose pose;
  pose.rolling_radius_m = 0.46;
  pose.lateral_shift_m = -0.004;
  const WheelRailGeometry geometry(S1002(), Uic60Canted(), pose);
  const std::vector<ContactCandidate> candidates = geometry.FindCandidates(1e-4);
  const ContactCandidate* flange = &candidates.at(0);
  for (const ContactCandidate& c : candidates) {
    if (c.normal.normalized().y() > flange->normal.normalized().y()) flange = &c;
  }
  PatchGridOptions o;
  o.geometry = GeometryModel::kConformal;
  o.threshold_m = 1e-4;
  o.cell_ds_m = o.cell_dx_m = cell_m;
  const PatchBuild first = BuildPatchGrid(geometry, *flange, o);
  o.cell_dx_m = cell_m * first.grid.nx / first.grid.ns;  // lengths in ratio of the extents
  const PatchBuild b = BuildPatchGrid(geometry, *flange, o);
  if (!b.valid) throw std::runtime_error("ProfilePatchGrid: no grid");
  return b.grid;
}

void BM_ProfilePatchSolve(benchmark::State& state) {
  const PatchGrid g = ProfilePatchGrid(state.range(0) * 1e-6);
  InfluenceSettings settings{KernelModel::kGolubenko, {}, kSteel, kSteel};
  NormalProblem np;
  np.gap_m = g.gap_m;
  np.approach_weight.resize(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    np.approach_weight.segment(j * g.nx, g.nx).setConstant(-g.normal_yz[j].y());
  }
  np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
  np.approach_m = 0.5e-4;
  NormalSolverOptions options;
  options.preconditioner =
      state.range(1) == 0 ? CgPreconditioner::kNone : CgPreconditioner::kInverseOperator;
  bench::TimeNormalSolve(state, g, settings, np, options);
  state.counters["nx"] = g.nx;
  state.counters["ns"] = g.ns;
  state.counters["uniform_arc"] = IsUniformArc(g);
  state.SetLabel(std::string(ToString(options.preconditioner)));
}
BENCHMARK(BM_ProfilePatchSolve)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int cell_um : {280, 200, 140, 100, 70}) b->Args({cell_um, 1});
    })
    ->Unit(benchmark::kMillisecond);

void BM_GaugeCorner(benchmark::State& state) {
  ContactProblem p;
  p.wheel_profile = S1002();
  p.rail_profile = Uic60Canted();
  p.wheel_material = p.rail_material = kSteel;
  p.placement.lateral_shift_m = -0.004;
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 100e3;
  if (state.range(2) != 0) p.placement.yaw_rad = state.range(2) * 1e-3;
  const int model = static_cast<int>(state.range(0));
  p.model = MakeModelOptions(model == 0   ? ModelKind::kHertz
                             : model == 1 ? ModelKind::kHalfspace
                             : model == 4 ? ModelKind::kAuto
                                          : ModelKind::kConformal);
  if (model == 2)
    p.model.kernel = KernelModel::kBoussinesq;  // conformal geometry, half-space kernel
  p.model.accuracy = static_cast<AccuracyPreset>(state.range(1));
  ContactResult r;
  for (auto _ : state) {
    r = SolveContact(p);
    benchmark::DoNotOptimize(r.patches.data());
  }
  static const char* kModels[] = {"hertz", "halfspace", "conformal+boussinesq",
                                  "conformal+golubenko", "auto"};
  state.SetLabel(std::string(kModels[model]) + " " + std::string(ToString(p.model.accuracy)) +
                 (state.range(2) != 0 ? " yaw " + std::to_string(state.range(2)) + " mrad" : ""));
  int cells = 0, in_contact = 0;
  for (const auto& pr : r.patches) {
    cells += pr.cells;
    in_contact += pr.cells_in_contact;
  }
  state.counters["area_mm2"] = r.area_m2 * 1e6;
  state.counters["p_max_MPa"] = r.p_max_Pa * 1e-6;
  state.counters["cells"] = cells;
  state.counters["in_contact"] = in_contact;
  state.counters["iterations"] = r.iterations;
}
BENCHMARK(BM_GaugeCorner)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1, 2, 3}, {0}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GaugeCorner)
    ->Name("BM_GaugeCornerYaw")
    ->ArgsProduct({{1, 2}, {0, 1, 2}, {0, 15}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
