// CONTACT's published performance cases on CONTACT's own gaps and grids (issue 18 points 4 and
// 5; not a test). CONTACT (E.A.H. Vollebregt, Apache-2.0, github.com/eve70a/CONTACT) times these
// in its perfc_test directory; its reference run (perfc_test/get_times.ref_out, 2016) lists the
// cells in contact and CG iterations below. The inputs are read from its files:
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
//        Args: level, the normal solver's criterion (0 railwear's default gap residual, 1
//        CONTACT's pressure update, NormalStopCriterion) and tolerance 10^-exponent; the label
//        names both. "pressure-update 1e-7" is CONTACT's criterion at CONTACT's EPS.
//  BM_PerfcRolling  perfc_test/tang_problm_{1,2}c.inp: exact steady rolling on levels 1, 2.
//  BM_CreepTable    src/test_table.f90: the 3,220-case Hertzian creep table, 11/15/25 cells.
//  BM_Groove        testbank/examples_conformal/groove_li.inp case 1: the conformal groove.
//
// Counters (bench_normal_solve.h): cells, in_contact, iterations, p_max_MPa, Fn_kN; each family
// adds its own (see there). Growth exponent of time against cells, per family and label:
//   build/tests/benchmarks/contact_reference_bench --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true --benchmark_format=json
//     | python3 tests/benchmarks/scaling_exponent.py --cpu
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "app/scene.h"
#include "core/contact/contact_solver.h"
#include "core/contact/hertz.h"
#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_exact.h"
#include "tests/benchmarks/bench_normal_solve.h"
#include "tests/core/contact/hertz_grid.h"

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

// The normal problem of level 1, 2, 4 or 8 (prescribed approach, CONTACT's input).
NormalProblem MakePerfcNormalProblem(const PatchGrid& g) {
  NormalProblem np;
  np.gap_m = g.gap_m;
  np.approach_weight = Eigen::VectorXd::Ones(g.cells());
  np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
  np.approach_m = kPerfcPen_mm * 1e-3;
  return np;
}

// The normal solver's options of the arguments (criterion 0 gap residual, 1 pressure update;
// tolerance 10^-exponent) and the label naming them, e.g. "pressure-update 1e-7".
NormalSolverOptions PerfcSolverOptions(int64_t criterion, int64_t exponent, std::string* label) {
  NormalSolverOptions o;
  o.criterion =
      criterion == 0 ? NormalStopCriterion::kGapResidual : NormalStopCriterion::kPressureUpdate;
  o.tolerance = std::pow(10.0, -static_cast<double>(exponent));
  *label = std::string(ToString(o.criterion)) + " 1e-" + std::to_string(exponent);
  return o;
}

// The exact tangential solver's options with tolerance 10^-exponent, appended to the label.
ExactTangentialOptions TangentialOptions(int64_t exponent, std::string* label) {
  ExactTangentialOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(exponent));
  *label += ", tangential 1e-" + std::to_string(exponent);
  return o;
}

// Args: level, criterion, tolerance exponent.
void BM_PerfcNormal(benchmark::State& state) {
  const PatchGrid g = MakePerfcGrid(static_cast<int>(state.range(0)));
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, kPerfcSteel, kPerfcSteel};
  std::string label;
  const NormalSolverOptions options = PerfcSolverOptions(state.range(1), state.range(2), &label);
  bench::TimeNormalSolve(state, g, settings, MakePerfcNormalProblem(g), options);
  state.SetLabel(label);
}
// railwear's default (the gap residual at 1e-10); CONTACT's criterion at CONTACT's EPS = 1e-7
// (the tolerance-matched comparison, issue 18 point 4); both criteria at looser tolerances (what
// a 4-significant-digit default would cost and gain; docs/speed.md).
void PerfcNormalArgs(benchmark::internal::Benchmark* b) {
  for (const int level : {1, 2, 4, 8}) {
    for (const int exponent : {10, 8, 6, 5, 4}) b->Args({level, 0, exponent});
    for (const int exponent : {7, 6, 5, 4, 3}) b->Args({level, 1, exponent});
  }
}
BENCHMARK(BM_PerfcNormal)->Apply(PerfcNormalArgs)->Unit(benchmark::kMillisecond);

// CONTACT's rigid slip in steady rolling evaluates the spin term a sixth of a cell ahead,
// w_y = eta + phi (x + dq / 6) with dq = dx (src/m_sdis.f90, set_tang_rhs: xofs_dq = dq FACPHI,
// FACPHI = 1/6 by default, "multiplication factor 1/6 for mysterious additional term for spin
// creepage", m_hierarch_data.f90). railwear's rigid slip has no such term; the benchmarks add it
// so that both solve the same problem (on the 11 x 11 table it moves F_y by up to 0.11 mu F_n).
void AddContactSpinOffset(const PatchGrid& g, double phi_per_m, RollingInput* in) {
  in->creep_s.array() += phi_per_m * g.dx_m / 6.0;
}

// perfc_test/tang_problm_1c.inp and 2c.inp: the normal problem of level 1 / 2 (as
// BM_PerfcNormal), then steady rolling with creepages CKSI = 0.0005, CETA = 0, CPHI = 0.0003
// /mm, FSTAT = FKIN = 0.3, VELOC = 30 000 mm/s (Kalker's rigid slip w_x = xi - phi y,
// w_y = eta + phi x, railwear's RollingInput for a planar patch, plus AddContactSpinOffset).
// CONTACT's reference run: 1,872 / 7,735 cells in slip, 56 / 90 iterations (ItGS, its EPS 1e-7);
// the input's comment quotes F_x / (mu F_n) = -0.573 and F_y / (mu F_n) = -0.327. Times operator
// construction, the normal solve and the exact tangential solve (args: level, then the normal
// criterion and tolerance exponent as BM_PerfcNormal, then the exact tangential solver's
// tolerance 10^-exponent, ExactTangentialOptions). Extra counters: in_slip, tang_iterations,
// fx_rel, fy_rel (F / (mu F_n)) and mz_rel (M_z / (mu F_n c), c = 1 mm).
constexpr double kPerfcCksi = 0.0005, kPerfcCeta = 0.0, kPerfcCphi_per_mm = 0.0003;
constexpr double kPerfcFriction = 0.3, kPerfcSpeed_m_s = 30.0;

void BM_PerfcRolling(benchmark::State& state) {
  const PatchGrid g = MakePerfcGrid(static_cast<int>(state.range(0)));
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, kPerfcSteel, kPerfcSteel};
  std::string label;
  const NormalSolverOptions options = PerfcSolverOptions(state.range(1), state.range(2), &label);
  const ExactTangentialOptions tangential = TangentialOptions(state.range(3), &label);
  NormalProblem np = MakePerfcNormalProblem(g);
  RollingInput in = testing::KalkerCreepage(g, kPerfcCksi, kPerfcCeta, kPerfcCphi_per_mm * 1e3,
                                            kPerfcSpeed_m_s, kPerfcFriction);
  AddContactSpinOffset(g, kPerfcCphi_per_mm * 1e3, &in);
  NormalSolution normal;
  TangentialSolution tang;
  for (auto _ : state) {
    const auto op = MakeInfluenceOperator(g, settings);
    np.blocks = {op.get()};
    normal = SolveNormal(np, options);
    tang = SolveTangentialExact(g, normal.pressure_Pa, in, kPerfcSteel, kPerfcSteel, tangential);
    benchmark::DoNotOptimize(tang.traction_x_Pa.data());
  }
  int in_contact = 0, in_slip = 0;
  for (int k = 0; k < g.cells(); ++k) {
    in_contact += normal.pressure_Pa[k] > 0;
    in_slip += tang.stick[k] == 0;
  }
  state.counters["cells"] = g.cells();
  state.counters["in_contact"] = in_contact;
  state.counters["iterations"] = normal.iterations;
  state.counters["in_slip"] = in_slip;
  state.counters["tang_iterations"] = tang.iterations;
  state.counters["converged"] =
      normal.status == SolverStatus::kConverged && tang.status == SolverStatus::kConverged;
  state.counters["Fn_kN"] = normal.force_N * 1e-3;
  state.counters["fx_rel"] = tang.force_x_N / (kPerfcFriction * normal.force_N);
  state.counters["fy_rel"] = tang.force_s_N / (kPerfcFriction * normal.force_N);
  state.counters["mz_rel"] = tang.spin_moment_Nm / (kPerfcFriction * normal.force_N * 1e-3);
  state.SetLabel(label);
}
// The strict settings (gap residual 1e-10, tangential 1e-9), CONTACT's criterion and EPS, and the
// defaults (issue 18 point 4: pressure update 1e-4) with the tangential tolerance from 1e-9 to
// 1e-5 (what a 4-digit tangential default keeps; docs/speed.md).
void PerfcRollingArgs(benchmark::internal::Benchmark* b) {
  for (const int level : {1, 2}) {
    b->Args({level, 0, 10, 9});
    b->Args({level, 1, 7, 9});
    for (const int exponent : {9, 7, 6, 5}) b->Args({level, 1, 4, exponent});
  }
}
BENCHMARK(BM_PerfcRolling)->Apply(PerfcRollingArgs)->Unit(benchmark::kMillisecond);

// src/test_table.f90 (CONTACT's creep-table test; reference forces for 11 x 11 in
// testbank/test_table_mx11.ref_fx): 3,220 Hertzian cases of steady rolling, one pass of the
// table per benchmark iteration. Semi-axes aa = 4, 6, 9, 12, 20 mm along x and bb = aa / (a/b)
// for a/b = 0.2, 0.5, 1, 2, 5 (CONTACT's IPOTCN = -3: the curvatures A1, B1 of the Hertzian gap
// A1 x^2 + B1 y^2 that give these semi-axes under Fn = 82 000 N, G = 82 000 MPa, nu = 0.28, so
// E* = G / (1 - nu)); an mx x mx grid over [-aa s, aa s] x [-bb s, bb s], s = mx / (mx - 4); the
// normal problem under the prescribed load, then exact steady rolling with mu = 0.3 at the
// creepages xi = m mu cos(t) c / rho, eta = m mu sin(t) c / rho, phi = mu spin / rho (c =
// sqrt(aa bb), rho = 2 / (A1 + B1)) over spin = 0, 0.5, 1, 2, t = -90 .. 90 deg in steps of 30
// and m = 0 .. 12 (23 values), CONTACT's order of the cases. CONTACT solves at EPS = 1e-6; the
// normal solve here runs at the criterion of the args (mx, normal criterion, exponent, reuse,
// tangential exponent), the tangential one at 10^-(tangential exponent). reuse: 0 builds everything
// for every case, as CONTACT's test_table does (its flags C = 2, I = 0: influence coefficients
// computed and the normal problem solved from the undeformed distance in every case); 1 builds the
// influence operator and the exact solver's ExactTangentialSetup once per ellipse (the 644 cases of
// an ellipse share one grid) and solves the normal problem in every case; 2 also solves the normal
// problem once per ellipse (it is the same problem in all its cases). The three give the same
// numbers bit for bit (reuse of identical inputs). 3 is 2 with each tangential solve warm-started
// from the previous case's solution when that is the previous creepage magnitude in the same
// direction and spin (CONTACT's I = 1; results to the tangential tolerance, not bit for bit).
// Counters: ms_per_case, cells (mx^2, for the growth exponent), tang_iterations (the tangential
// solves' mean); with RAILWEAR_CONTACT_TABLE_REF naming CONTACT's reference file (e.g.
// testbank/test_table_mx11.ref_fx for mx = 11) also the largest differences of F_x / (mu F_n), F_y
// / (mu F_n) and M_z / (mu F_n c) from it (dfx_max, dfy_max, dmz_max); with
// RAILWEAR_CONTACT_TABLE_OUT naming a file, railwear's values in CONTACT's format.
constexpr int kTableCases = 5 * 4 * 7 * 23;
constexpr double kTableFn_N = 82000.0, kTableFriction = 0.3, kTableSpeed_m_s = 10.0;

struct TableCase {
  int ellipse = 0;
  double xi = 0.0, eta = 0.0, phi_per_m = 0.0;
};

// The curvatures A1, B1 [1/m] of the Hertz ellipse with semi-axes a along x and b along y [m].
std::pair<double, double> HertzCurvatures(double a_m, double b_m, double contact_modulus_Pa,
                                          double force_N) {
  const double major = std::max(a_m, b_m), minor = std::min(a_m, b_m);
  const double g = minor / major, m = 1.0 - g * g;
  const double K = internal::CompleteEllipticK(m), E = internal::CompleteEllipticE(m);
  const double ratio = m > 0.0 ? ((major / minor) * (major / minor) * E - K) / (K - E) : 1.0;
  const double c3 = std::pow(std::sqrt(a_m * b_m), 3);
  const double sum = 3.0 * force_N * E / (2.0 * M_PI * contact_modulus_Pa * c3 * std::sqrt(g));
  const double small = sum / (1.0 + ratio), large = sum - small;
  // The major axis lies along the smaller curvature.
  return a_m >= b_m ? std::pair{small, large} : std::pair{large, small};
}

// CONTACT's reference values (F_x, F_y, M_z per case), from lines "Fx= .., Fy= .., Mz= .., ...".
std::vector<std::array<double, 3>> ReadTableReference(const char* path) {
  std::vector<std::array<double, 3>> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::array<double, 3> v{};
    if (std::sscanf(line.c_str(), " Fx= %lf, Fy= %lf, Mz= %lf", &v[0], &v[1], &v[2]) == 3) {
      out.push_back(v);
    }
  }
  return out;
}

void BM_CreepTable(benchmark::State& state) {
  const int mx = static_cast<int>(state.range(0));
  std::string label;
  const NormalSolverOptions options = PerfcSolverOptions(state.range(1), state.range(2), &label);
  const ExactTangentialOptions tangential = TangentialOptions(state.range(4), &label);
  const double aa_mm[] = {4.0, 6.0, 9.0, 12.0, 20.0}, ellip[] = {0.2, 0.5, 1.0, 2.0, 5.0};
  const double spin[] = {0.0, 0.5, 1.0, 2.0};
  const double magn[] = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 0.9, 1.1, 1.4, 1.7, 2.0,
                         2.5, 3.0, 3.5, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10., 12.};
  const double estar = 82000e6 / (1.0 - 0.28);
  // The five grids and gaps, and the creepages of every case.
  std::vector<PatchGrid> grids;
  std::vector<double> cp_m, rho_m;
  for (int e = 0; e < 5; ++e) {
    const double a = aa_mm[e] * 1e-3, b = a / ellip[e];
    const auto [A, B] = HertzCurvatures(a, b, estar, kTableFn_N);
    const double scale = static_cast<double>(mx) / (mx - 4);
    PatchGrid g = testing::MakeHertzGrid(a * scale, b * scale, mx, mx);
    for (int j = 0; j < g.ns; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        g.gap_m[g.Index(i, j)] = A * g.X(i) * g.X(i) + B * g.S(j) * g.S(j);
      }
    }
    grids.push_back(std::move(g));
    cp_m.push_back(std::sqrt(a * b));
    rho_m.push_back(2.0 / (A + B));
  }
  std::vector<TableCase> cases;
  for (int e = 0; e < 5; ++e) {
    for (const double sp : spin) {
      for (int t = 0; t < 7; ++t) {
        const double angle = (t - 3) * M_PI / 6.0;
        for (const double m : magn) {
          cases.push_back({e, m * kTableFriction * std::cos(angle) * cp_m[e] / rho_m[e],
                           m * kTableFriction * std::sin(angle) * cp_m[e] / rho_m[e],
                           kTableFriction * sp / rho_m[e]});
        }
      }
    }
  }
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, kPerfcSteel, kPerfcSteel};
  const int reuse = static_cast<int>(state.range(3));
  std::vector<std::array<double, 3>> result(cases.size());
  int not_converged = 0;
  // What a case builds or solves: with reuse, once per ellipse (the cases run ellipse by ellipse)
  // and built inside the timed loop, so the table's time includes it.
  std::unique_ptr<InfluenceOperator> op;
  std::optional<ExactTangentialSetup> setup;
  std::optional<NormalSolution> kept_normal;
  TangentialSolution last;  // the previous case's solution (reuse 3)
  int built_for = -1;
  auto solve_normal = [&](const PatchGrid& g) {
    NormalProblem np;
    np.blocks = {op.get()};
    np.gap_m = g.gap_m;
    np.approach_weight = Eigen::VectorXd::Ones(g.cells());
    np.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
    np.force_N = kTableFn_N;
    return SolveNormal(np, options);
  };
  double tang_iterations = 0.0;
  for (auto _ : state) {
    not_converged = 0;
    tang_iterations = 0.0;
    built_for = -1;
    for (size_t c = 0; c < cases.size(); ++c) {
      const PatchGrid& g = grids[cases[c].ellipse];
      if (reuse == 0 || built_for != cases[c].ellipse) {
        op = MakeInfluenceOperator(g, settings);
        if (reuse >= 1) setup.emplace(g, kPerfcSteel, kPerfcSteel);
        if (reuse >= 2) kept_normal = solve_normal(g);
        built_for = cases[c].ellipse;
      }
      const NormalSolution normal = reuse >= 2 ? *kept_normal : solve_normal(g);
      RollingInput in = testing::KalkerCreepage(g, cases[c].xi, cases[c].eta, cases[c].phi_per_m,
                                                kTableSpeed_m_s, kTableFriction);
      AddContactSpinOffset(g, cases[c].phi_per_m, &in);
      // reuse 3: warm-started from the previous case when it is the previous creepage magnitude
      // of the same direction and spin (not at m = 0, whose solution is no traction).
      const bool warm = reuse >= 3 && c % std::size(magn) != 0;
      TangentialSolution t = reuse >= 1
                                 ? SolveTangentialExact(g, normal.pressure_Pa, in, *setup,
                                                        tangential, warm ? &last : nullptr)
                                 : SolveTangentialExact(g, normal.pressure_Pa, in, kPerfcSteel,
                                                        kPerfcSteel, tangential);
      not_converged +=
          normal.status != SolverStatus::kConverged || t.status != SolverStatus::kConverged;
      tang_iterations += t.iterations;
      const double mu_fn = kTableFriction * normal.force_N;
      result[c] = {t.force_x_N / mu_fn, t.force_s_N / mu_fn,
                   t.spin_moment_Nm / (mu_fn * cp_m[cases[c].ellipse])};
      benchmark::DoNotOptimize(result[c]);
      if (reuse >= 3) last = std::move(t);
    }
  }
  state.counters["cells"] = mx * mx;
  state.counters["cases"] = static_cast<double>(cases.size());
  state.counters["not_converged"] = not_converged;
  state.counters["tang_iterations"] = tang_iterations / static_cast<double>(cases.size());
  state.counters["ms_per_case"] = benchmark::Counter(
      static_cast<double>(cases.size()) * 1e-3,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(label);
  if (const char* out_path = std::getenv("RAILWEAR_CONTACT_TABLE_OUT")) {
    std::ofstream out(out_path);  // CONTACT's format, for a line-by-line comparison
    for (const auto& r : result) {
      out << fmt::format("Fx= {:10.6f}, Fy= {:10.6f}, Mz= {:10.6f}\n", r[0], r[1], r[2]);
    }
  }
  if (const char* ref_path = std::getenv("RAILWEAR_CONTACT_TABLE_REF")) {
    const auto ref = ReadTableReference(ref_path);
    if (ref.size() != static_cast<size_t>(kTableCases)) {
      state.SkipWithError("RAILWEAR_CONTACT_TABLE_REF: not 3,220 lines 'Fx= .., Fy= .., Mz= ..'");
      return;
    }
    std::array<double, 3> worst{};
    for (size_t c = 0; c < cases.size(); ++c) {
      for (int k = 0; k < 3; ++k) worst[k] = std::max(worst[k], std::abs(result[c][k] - ref[c][k]));
    }
    state.counters["dfx_max"] = worst[0];
    state.counters["dfy_max"] = worst[1];
    state.counters["dmz_max"] = worst[2];
  }
}
// The last argument: the exact tangential solver's tolerance 10^-exponent (ExactTangentialOptions;
// 9 the strict setting). The defaults of issue 18 point 4 (pressure update 1e-4) with tangential
// 1e-9 to 1e-5, for what a 4-digit tangential default keeps (docs/speed.md).
void CreepTableArgs(benchmark::internal::Benchmark* b) {
  for (const int mx : {11, 15, 25}) {
    for (const int reuse : {0, 1, 2, 3}) b->Args({mx, 0, 10, reuse, 9});
    for (const int reuse : {0, 2}) b->Args({mx, 1, 6, reuse, 9});
    for (const int exponent : {9, 7, 6, 5}) b->Args({mx, 1, 4, 2, exponent});
  }
}
BENCHMARK(BM_CreepTable)->Apply(CreepTableArgs)->Iterations(1)->Unit(benchmark::kMillisecond);

// testbank/examples_conformal/groove_li.inp, case 1 (after Li, 2002): CONTACT's circ_r10.prw
// wheel profile (a 10 mm circle) in its groove_r1025.prr rail profile (a 10.25 mm groove), both
// read from ../shared/data/profiles (the same files); G = 80 000 MPa and nu = 0.28 on both
// bodies, wheel radius 420 mm, F_z = 10 kN; cells DX = 0.095833 mm along the rail and DS = 0.25
// mm along the profile; CONTACT's conformal approach with half-space influence coefficients, here
// the conformal geometry with the Boussinesq kernel. Args: rolling (0 the normal problem only, 1
// free rolling: F_x = 0 at mu = 0.3, 420 mm/s, the exact solver), then the normal criterion and
// tolerance exponent as BM_PerfcNormal. CONTACT's reference output (groove_li.ref_out, case 1,
// free rolling at EPS 1e-7): 1,187 cells in contact of 3,515, 325 of them in slip, p_max 530.2
// MPa, approach 0.02237 mm, pitch velocity -1.0002301 rad/s (CKSI -2.809e-4 at its reference
// point; railwear's cksi counter is the pressure-weighted patch average). Times railwear's whole
// contact solve (placement, grid, operator, normal and rolling stages).
void BM_Groove(benchmark::State& state) {
  const std::string dir = std::string(RAILWEAR_SOURCE_DIR) + "/../shared/data/profiles/";
  if (!std::ifstream(dir + "circ_r10.prw")) {
    state.SkipWithError(("no " + dir + "circ_r10.prw (CONTACT's profiles in ../shared)").c_str());
    return;
  }
  const bool rolling = state.range(0) != 0;
  std::string label;
  const NormalSolverOptions options = PerfcSolverOptions(state.range(1), state.range(2), &label);
  const double e_MPa = 2.0 * 80000.0 * 1.28;
  std::string text = fmt::format(
      "[scene]\neffects = [{}]\n[model]\ngeometry = \"conformal\"\nkernel = \"boussinesq\"\n"
      "cell_mm = [0.095833, 0.25]\ntangential = \"exact\"\n"
      "[materials]\nwheel = {{ E_MPa = {}, nu = 0.28 }}\nrail = {{ E_MPa = {}, nu = 0.28 }}\n"
      "[wheel]\nprofile = \"{}circ_r10.prw\"\nrolling_radius_mm = 420\n"
      "[rail]\nprofile = \"{}groove_r1025.prr\"\n[load]\nvertical_N = 10000\n",
      rolling ? "\"normal\", \"tangential\"" : "\"normal\"", e_MPa, e_MPa, dir, dir);
  if (rolling) text += "friction = 0.3\nspeed_m_s = 0.42\nlongitudinal_force_N = 0\n";
  app::Scene scene = app::ParseScene(text, "groove_li_case1.toml");
  scene.problem.solver = options;
  ContactResult r;
  for (auto _ : state) {
    r = SolveContact(scene.problem);
    benchmark::DoNotOptimize(r.patches.data());
  }
  int cells = 0, in_contact = 0, in_slip = 0;
  double fx = 0.0, cksi = 0.0;
  for (const PatchResult& p : r.patches) {
    cells += p.cells;
    in_contact += p.cells_in_contact;
    if (p.rolling) {
      fx += p.rolling->tangential.force_x_N;
      cksi = p.rolling->creepage.xi;
      for (int k = 0; k < p.rolling->tangential.stick.size(); ++k) {
        in_slip += p.rolling->tangential.stick[k] == 0;
      }
    }
  }
  state.counters["cells"] = cells;
  state.counters["in_contact"] = in_contact;
  state.counters["patches"] = static_cast<double>(r.patches.size());
  state.counters["iterations"] = r.iterations;
  state.counters["converged"] = r.status == SolverStatus::kConverged;
  state.counters["p_max_MPa"] = r.p_max_Pa * 1e-6;
  state.counters["Fz_kN"] = r.vertical_force_N * 1e-3;
  state.counters["approach_um"] = r.approach_m * 1e6;
  if (rolling) {
    state.counters["in_slip"] = in_slip;
    state.counters["fx_N"] = fx;
    state.counters["cksi"] = cksi;
    state.counters["pitch_rad_s"] = r.pitch_velocity_rad_s;
  }
  state.SetLabel(label);
}
BENCHMARK(BM_Groove)
    ->Args({0, 0, 10})
    ->Args({1, 0, 10})
    ->Args({0, 1, 7})
    ->Args({1, 1, 7})
    ->Args({0, 1, 4})  // the default (issue 18 point 4)
    ->Args({1, 1, 4})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace railwear

BENCHMARK_MAIN();
