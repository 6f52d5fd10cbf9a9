// CONTACT's published performance cases on CONTACT's own gaps and grids (issue 18 point 5; not a
// test). CONTACT (E.A.H. Vollebregt, Apache-2.0, github.com/eve70a/CONTACT) times these in its
// perfc_test directory; its reference run (perfc_test/get_times.ref_out, 2016) lists the cells
// in contact and CG iterations below. The inputs are read from its files:
//
//  BM_PerfcNormal/level  perfc_test/norm_problm_{1,2,4,8}p.inp: the normal problem of a right
//        wheel shifted 6.2 mm laterally. Both bodies G = 82 000 MPa, nu = 0.28 (the half-space,
//        Boussinesq), prescribed approach PEN = 0.02084 mm; grid MX x MY cells of DX = DY from
//        (XL, YL) = (-3.55, -6.15) mm: 71 x 81 at 0.1 mm (level 1), 143 x 163 at 0.05 (2),
//        287 x 323 at 0.025 (4), 575 x 647 at 0.0125 (8). Undeformed distance (IBASE = 2,
//        CONTACT's src/m_sdis.f90): h(x, y) = z(y) + (x - XM)^2 / (2 RM), XM = 0, RM = 483.931
//        mm, z(y) linear between the NN = 271 heights given from Y1 = -12 mm every DY1 = 0.1 mm
//        (extrapolated beyond them). CONTACT's reference: 3,148 / 12,902 / 50,796 / 200,980
//        cells in contact, 19 / 22 / 27 / 31 CG iterations at its EPS = 1e-7.
//
// Counters (bench_normal_solve.h): cells, in_contact, iterations, p_max_MPa, Fn_kN (railwear's
// default tolerance 1e-10 unless stated). Growth exponent of time against cells:
//   build/tests/benchmarks/contact_reference_bench --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true --benchmark_format=json
//     | python3 tests/benchmarks/scaling_exponent.py --cpu
#include <algorithm>
#include <array>
#include <cmath>

#include <benchmark/benchmark.h>

#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"
#include "tests/benchmarks/bench_normal_solve.h"

namespace railwear {
namespace {

// perfc_test/norm_problm_1p.inp (the same in 2p, 4p and 8p): z(y) [mm] at y = -12 + 0.1 k mm.
constexpr std::array<double, 271> kPerfcHeights_mm = {
    1.83370,  1.75764, 1.68158, 1.60552, 1.53141, 1.45971, 1.38801, 1.31631, 1.24460, 1.17364,
    1.10603,  1.03843, 0.97083, 0.90322, 0.83562, 0.77490, 0.71609, 0.65729, 0.59970, 0.55101,
    0.50233,  0.45687, 0.41512, 0.37446, 0.33826, 0.30272, 0.27126, 0.24069, 0.21339, 0.18755,
    0.16401,  0.14263, 0.12253, 0.10536, 0.08920, 0.07527, 0.06306, 0.05195, 0.04348, 0.03604,
    0.03014,  0.02600, 0.02268, 0.02074, 0.02028, 0.02044, 0.01893, 0.01818, 0.01813, 0.01790,
    0.01747,  0.01674, 0.01702, 0.01711, 0.01589, 0.01592, 0.01643, 0.01519, 0.01469, 0.01496,
    0.01428,  0.01370, 0.01372, 0.01336, 0.01282, 0.01272, 0.01247, 0.01203, 0.01181, 0.01164,
    0.01121,  0.01093, 0.01084, 0.01045, 0.00999, 0.01003, 0.00983, 0.00922, 0.00916, 0.00939,
    0.00869,  0.00811, 0.00837, 0.00819, 0.00746, 0.00720, 0.00718, 0.00685, 0.00650, 0.00618,
    0.00598,  0.00604, 0.00576, 0.00516, 0.00501, 0.00510, 0.00472, 0.00424, 0.00399, 0.00378,
    0.00387,  0.00381, 0.00322, 0.00281, 0.00276, 0.00263, 0.00240, 0.00208, 0.00168, 0.00154,
    0.00161,  0.00141, 0.00105, 0.00075, 0.00048, 0.00050, 0.00065, 0.00048, 0.00019, 0.00001,
    -0.00013, 0.00001, 0.00028, 0.00036, 0.00034, 0.00038, 0.00046, 0.00077, 0.00124, 0.00174,
    0.00226,  0.00275, 0.00318, 0.00378, 0.00466, 0.00566, 0.00699, 0.00828, 0.00936, 0.01047,
    0.01205,  0.01362, 0.01570, 0.01781, 0.02023, 0.02273, 0.02535, 0.02803, 0.03104, 0.03441,
    0.03801,  0.04211, 0.04629, 0.05094, 0.05559, 0.06079, 0.06601, 0.07196, 0.07812, 0.08485,
    0.09201,  0.09951, 0.10757, 0.11566, 0.12387, 0.13209, 0.13987, 0.14763, 0.15506, 0.16234,
    0.16943,  0.17624, 0.18298, 0.18913, 0.19529, 0.20117, 0.20697, 0.21263, 0.21810, 0.22356,
    0.22873,  0.23389, 0.23888, 0.24376, 0.24855, 0.25301, 0.25746, 0.26174, 0.26597, 0.27013,
    0.27414,  0.27815, 0.28200, 0.28580, 0.28956, 0.29315, 0.29675, 0.30022, 0.30361, 0.30699,
    0.31012,  0.31326, 0.31630, 0.31925, 0.32220, 0.32502, 0.32781, 0.33058, 0.33323, 0.33588,
    0.33847,  0.34099, 0.34351, 0.34594, 0.34834, 0.35074, 0.35304, 0.35533, 0.35760, 0.35981,
    0.36201,  0.36416, 0.36625, 0.36834, 0.37037, 0.37237, 0.37437, 0.37632, 0.37828, 0.38023,
    0.38215,  0.38407, 0.38598, 0.38788, 0.38978, 0.39168, 0.39358, 0.39548, 0.39738, 0.39928,
    0.40119,  0.40310, 0.40503, 0.40696, 0.40891, 0.41088, 0.41285, 0.41484, 0.41687, 0.41889,
    0.42094,  0.42303, 0.42513, 0.42725, 0.42943, 0.43161, 0.43382, 0.43609, 0.43837, 0.44067,
    0.44306,  0.44545, 0.44786, 0.45038, 0.45290, 0.45542, 0.45808, 0.46075, 0.46341, 0.46621,
    0.46902,
};
constexpr double kPerfcY1_mm = -12.0, kPerfcDy1_mm = 0.1, kPerfcXm_mm = 0.0, kPerfcRm_mm = 483.9310;
constexpr double kPerfcPen_mm = 0.02084;
const Material kPerfcSteel{2.0 * 82000e6 * (1.0 + 0.28), 0.28};  // G = 82 000 MPa

// CONTACT's IBASE = 2 distance at (x, y) [mm], as src/m_sdis.f90 computes it.
double PerfcDistance_mm(double x, double y) {
  const int nn = static_cast<int>(kPerfcHeights_mm.size());
  const double yn = kPerfcY1_mm + (nn - 1) * kPerfcDy1_mm;
  int left = 0;  // 0-based index of the left point
  double y_left = kPerfcY1_mm;
  if (y < kPerfcY1_mm) {
    left = 0;
  } else if (y >= yn) {
    left = nn - 2;
    y_left = yn - kPerfcDy1_mm;
  } else {
    left = static_cast<int>((y - kPerfcY1_mm) / kPerfcDy1_mm);
    y_left = kPerfcY1_mm + left * kPerfcDy1_mm;
  }
  const double slope = (kPerfcHeights_mm[left + 1] - kPerfcHeights_mm[left]) / kPerfcDy1_mm;
  return kPerfcHeights_mm[left] + slope * (y - y_left) +
         (x - kPerfcXm_mm) * (x - kPerfcXm_mm) / (2.0 * kPerfcRm_mm);
}

// The planar grid of level 1, 2, 4 or 8 with CONTACT's element centres and distances.
PatchGrid MakePerfcGrid(int level) {
  const int mx[] = {71, 143, 287, 575}, my[] = {81, 163, 323, 647};
  const int k = level == 1 ? 0 : level == 2 ? 1 : level == 4 ? 2 : 3;
  const double d_mm = 0.1 / level;
  PatchGrid g;
  g.nx = mx[k];
  g.ns = my[k];
  g.dx_m = g.ds_m = d_mm * 1e-3;
  g.x0_m = (-3.55 + 0.5 * d_mm) * 1e-3;
  g.s0_m = (-6.15 + 0.5 * d_mm) * 1e-3;
  g.planar = true;
  for (int j = 0; j < g.ns; ++j) {
    g.point_yz_m.emplace_back(g.S(j), 0.0);
    g.tangent_yz.emplace_back(1.0, 0.0);
    g.normal_yz.emplace_back(0.0, -1.0);
  }
  g.gap_m.resize(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      g.gap_m[g.Index(i, j)] = 1e-3 * PerfcDistance_mm(1e3 * g.X(i), 1e3 * g.S(j));
    }
  }
  return g;
}

void BM_PerfcNormal(benchmark::State& state) {
  const PatchGrid g = MakePerfcGrid(static_cast<int>(state.range(0)));
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, kPerfcSteel, kPerfcSteel};
  NormalProblem np;
  np.gap_m = g.gap_m;
  np.approach_weight = Eigen::VectorXd::Ones(g.cells());
  np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
  np.approach_m = kPerfcPen_mm * 1e-3;
  bench::TimeNormalSolve(state, g, settings, np, NormalSolverOptions());
}
BENCHMARK(BM_PerfcNormal)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
