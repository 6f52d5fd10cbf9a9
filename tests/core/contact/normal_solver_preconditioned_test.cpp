// Tests of the preconditioned normal solver (NormalSolverOptions::preconditioner) on the real
// FFT influence operators: the same solution as plain projected CG (fast versus naive) on Hertz
// problems, on a curved grid with the seed's kernel and on two patches; iteration counts that
// barely grow with the grid; the fallback and the not-converged outcome.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/contact/hertz.h"
#include "core/contact/influence_operator.h"
#include "core/contact/normal_solver.h"

namespace railwear {
namespace {

// Both solves stop at 1e-10 of the gap scale (the strict setting); on these grids that bounds
// the pressure difference at ~1e-9 of the peak (as in normal_solver_test.cpp's naive check).
constexpr double kSameSolutionRelTol = 1e-8;
// Brief: iterations may grow by at most 1.5x from 30 x 30 to 120 x 120 (measured: 15, 15, 14;
// unpreconditioned 28, 36, 54).
constexpr double kIterationGrowthLimit = 1.5;

const Material kSteel{210e9, 0.28};
// Hertz case H4 of reference README §1 (normal_solver_test.cpp): 10 kN, R_x = 460 mm,
// R_y = 300 mm; a = 3.3382 mm, b = 2.5111 mm.
constexpr double kForce = 10e3;
const double kA = 1.0 / (2 * 0.46), kB = 1.0 / (2 * 0.30);

// Planar (straight section along y) or circular-arc (radius_m) grid, nx x ns cells of dx x ds
// centred on the origin, with the gap A x^2 + B s^2.
PatchGrid MakeGrid(int nx, int ns, double dx, double ds, double radius_m = 0.0) {
  PatchGrid g;
  g.nx = nx;
  g.ns = ns;
  g.dx_m = dx;
  g.ds_m = ds;
  g.x0_m = -0.5 * (nx - 1) * dx;
  g.s0_m = -0.5 * (ns - 1) * ds;
  g.planar = radius_m == 0.0;
  for (int j = 0; j < ns; ++j) {
    if (g.planar) {
      g.point_yz_m.emplace_back(g.S(j), 0.0);
      g.tangent_yz.emplace_back(1.0, 0.0);
      g.normal_yz.emplace_back(0.0, -1.0);
    } else {
      const double th = g.S(j) / radius_m;
      const Eigen::Vector2d n(std::sin(th), -std::cos(th));
      g.point_yz_m.push_back(Eigen::Vector2d(0.0, radius_m) + radius_m * n);
      g.tangent_yz.emplace_back(std::cos(th), std::sin(th));
      g.normal_yz.push_back(n);
    }
  }
  g.gap_m.resize(g.cells());
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) {
      g.gap_m[g.Index(i, j)] = kA * g.X(i) * g.X(i) + kB * g.S(j) * g.S(j);
    }
  }
  return g;
}

// cells_per_semi_axis cells along each H4 semi-axis, the grid 1.5 times the ellipse.
PatchGrid MakeHertzGrid(int cells_per_semi_axis, double radius_m = 0.0) {
  const HertzSolution h = SolveHertz(kA, kB, ContactModulus(kSteel, kSteel), kForce);
  const int n = 3 * cells_per_semi_axis;
  return MakeGrid(n, n, h.semi_axis_x_m / cells_per_semi_axis,
                  h.semi_axis_y_m / cells_per_semi_axis, radius_m);
}

// One patch; w = -n_y (the vertical share of each cell's normal), uniform areas.
NormalProblem MakeProblem(const PatchGrid& g, const InfluenceOperator* op) {
  NormalProblem pr;
  pr.blocks = {op};
  pr.gap_m = g.gap_m;
  pr.approach_weight.resize(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    pr.approach_weight.segment(j * g.nx, g.nx).setConstant(-g.normal_yz[j].y());
  }
  pr.cell_area_m2 = Eigen::VectorXd::Constant(g.cells(), g.CellArea());
  return pr;
}

// The strict setting (the gap residual at 1e-10), asked for explicitly since the default became
// the 4-digit pressure update (issue 18 point 4): kSameSolutionRelTol and the iteration counts
// below are the strict criterion's.
NormalSolution Solve(const NormalProblem& pr, CgPreconditioner pc) {
  NormalSolverOptions options = StrictNormalSolverOptions();
  options.preconditioner = pc;
  return SolveNormal(pr, options);
}

// Solves with and without the preconditioner; both converge to the same pressures and approach.
void ExpectSameSolution(const NormalProblem& pr) {
  const NormalSolution plain = Solve(pr, CgPreconditioner::kNone);
  const NormalSolution pre = Solve(pr, CgPreconditioner::kInverseOperator);
  ASSERT_EQ(plain.status, SolverStatus::kConverged) << plain.message;
  ASSERT_EQ(pre.status, SolverStatus::kConverged) << pre.message;
  EXPECT_FALSE(plain.preconditioned);
  EXPECT_TRUE(pre.preconditioned);
  EXPECT_EQ(plain.preconditioner_applications, 0);
  EXPECT_GT(pre.preconditioner_applications, 0);
  const double pmax = plain.pressure_Pa.maxCoeff();
  EXPECT_LE((pre.pressure_Pa - plain.pressure_Pa).cwiseAbs().maxCoeff(),
            kSameSolutionRelTol * pmax);
  EXPECT_NEAR(pre.approach_m, plain.approach_m, kSameSolutionRelTol * std::abs(plain.approach_m));
  EXPECT_NEAR(pre.force_N, plain.force_N, kSameSolutionRelTol * plain.force_N);
  EXPECT_LE(pre.load_error_relative, kStrictNormalTolerance);
  EXPECT_LT(pre.iterations, plain.iterations);
}

TEST(PreconditionedNormalSolver, HertzSameSolutionAsPlainCg) {
  const PatchGrid g = MakeHertzGrid(15);
  const auto op = MakeInfluenceOperator(g, {KernelModel::kBoussinesq, {}, kSteel, kSteel});
  NormalProblem pr = MakeProblem(g, op.get());
  pr.force_N = kForce;
  {
    SCOPED_TRACE("prescribed load");
    ExpectSameSolution(pr);
  }
  pr.force_N.reset();
  pr.approach_m = SolveHertz(kA, kB, ContactModulus(kSteel, kSteel), kForce).approach_m;
  {
    SCOPED_TRACE("prescribed approach");
    ExpectSameSolution(pr);
  }
  // kAuto picks the preconditioner when the operator has one.
  EXPECT_TRUE(Solve(pr, CgPreconditioner::kAuto).preconditioned);
  EXPECT_TRUE(SolveNormal(pr).preconditioned);
}

TEST(PreconditionedNormalSolver, CurvedGridWithSeedKernelSameSolution) {
  // 10 mm arc (a flange-root-like section), the seed's kernel (only nearly symmetric there),
  // w = cos of the normal's angle: non-uniform weights.
  const PatchGrid g = MakeHertzGrid(10, 6e-3);
  const auto op = MakeInfluenceOperator(g, {KernelModel::kGolubenko, {}, kSteel, kSteel});
  NormalProblem pr = MakeProblem(g, op.get());
  ASSERT_LT(pr.approach_weight.minCoeff(), 0.9);
  pr.force_N = kForce;
  SCOPED_TRACE("curved, load");
  ExpectSameSolution(pr);
}

TEST(PreconditionedNormalSolver, UniformArcSameSolutionWithEitherStructure) {
  // On a uniform arc the 2-D FFT operator (the default there) and the per-frequency blocks give
  // the same products to rounding but different preconditioners (circulant along s, or exact
  // along s): the preconditioned solves agree to the solver's tolerance.
  const PatchGrid g = MakeHertzGrid(10, 6e-3);
  const InfluenceSettings settings{KernelModel::kGolubenko, {}, kSteel, kSteel};
  ASSERT_EQ(ChooseSectionStructure(g), SectionStructure::kToeplitzXs);
  const auto toeplitz = MakeInfluenceOperator(g, settings);
  const auto blocks =
      MakeInfluenceOperator(g, settings, OperatorProducts::kAuto, SectionStructure::kBlocks);
  NormalProblem pr_t = MakeProblem(g, toeplitz.get()), pr_b = MakeProblem(g, blocks.get());
  pr_t.force_N = pr_b.force_N = kForce;
  const NormalSolution t = Solve(pr_t, CgPreconditioner::kInverseOperator);
  const NormalSolution b = Solve(pr_b, CgPreconditioner::kInverseOperator);
  ASSERT_EQ(t.status, SolverStatus::kConverged) << t.message;
  ASSERT_EQ(b.status, SolverStatus::kConverged) << b.message;
  SCOPED_TRACE(::testing::Message()
               << "iterations 2-D " << t.iterations << ", blocks " << b.iterations);
  const double pmax = b.pressure_Pa.maxCoeff();
  EXPECT_LE((t.pressure_Pa - b.pressure_Pa).cwiseAbs().maxCoeff(), kSameSolutionRelTol * pmax);
  EXPECT_NEAR(t.approach_m, b.approach_m, kSameSolutionRelTol * std::abs(b.approach_m));
  EXPECT_LE(t.iterations, kIterationGrowthLimit * b.iterations);
}

TEST(PreconditionedNormalSolver, TwoPatchesArePreconditionedBlockByBlock) {
  // A planar and a curved patch (different cell sizes), gap offset 3 um on the second.
  const PatchGrid g1 = MakeHertzGrid(8);
  PatchGrid g2 = MakeHertzGrid(6, 8e-3);
  g2.gap_m.array() += 3e-6;
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, kSteel, kSteel};
  const auto op1 = MakeInfluenceOperator(g1, settings);
  const auto op2 = MakeInfluenceOperator(g2, settings);
  const NormalProblem p1 = MakeProblem(g1, op1.get());
  const NormalProblem p2 = MakeProblem(g2, op2.get());
  NormalProblem both;
  both.blocks = {op1.get(), op2.get()};
  const int n1 = g1.cells(), n2 = g2.cells();
  both.gap_m.resize(n1 + n2);
  both.gap_m << p1.gap_m, p2.gap_m;
  both.approach_weight.resize(n1 + n2);
  both.approach_weight << p1.approach_weight, p2.approach_weight;
  both.cell_area_m2.resize(n1 + n2);
  both.cell_area_m2 << p1.cell_area_m2, p2.cell_area_m2;
  both.force_N = kForce;
  ExpectSameSolution(both);
  const NormalSolution s = SolveNormal(both);
  EXPECT_GT(s.pressure_Pa.tail(n2).maxCoeff(), 0.0);  // both patches carry load
}

TEST(PreconditionedNormalSolver, IterationsBarelyGrowWithTheGrid) {
  // 30 x 30 -> 60 x 60 -> 120 x 120 cells, ~35 % in contact, prescribed load.
  std::vector<int> iterations;
  for (int cells_per_semi_axis : {10, 20, 40}) {
    const PatchGrid g = MakeHertzGrid(cells_per_semi_axis);
    const auto op = MakeInfluenceOperator(g, {KernelModel::kBoussinesq, {}, kSteel, kSteel});
    NormalProblem pr = MakeProblem(g, op.get());
    pr.force_N = kForce;
    const NormalSolution s = Solve(pr, CgPreconditioner::kInverseOperator);
    ASSERT_EQ(s.status, SolverStatus::kConverged) << s.message;
    iterations.push_back(s.iterations);
  }
  SCOPED_TRACE(::testing::Message()
               << "iterations " << iterations[0] << ", " << iterations[1] << ", " << iterations[2]);
  EXPECT_LE(iterations[2], kIterationGrowthLimit * iterations[0]);
  EXPECT_LE(iterations[1], kIterationGrowthLimit * iterations[0]);
}

TEST(PreconditionedNormalSolver, OperatorWithoutInverseRunsUnpreconditioned) {
  const PatchGrid g = MakeHertzGrid(4);
  const InfluenceSettings settings{KernelModel::kBoussinesq, {}, kSteel, kSteel};
  const auto dense = MakeDenseInfluenceOperator(g, settings);
  const auto fast = MakeInfluenceOperator(g, settings);
  NormalProblem pr = MakeProblem(g, dense.get());
  pr.force_N = kForce;
  const NormalSolution s = Solve(pr, CgPreconditioner::kInverseOperator);
  ASSERT_EQ(s.status, SolverStatus::kConverged) << s.message;
  EXPECT_FALSE(s.preconditioned);
  EXPECT_EQ(s.preconditioner_applications, 0);
  // One block without an inverse is enough to switch it off for all.
  NormalProblem two = pr;
  two.blocks = {fast.get(), dense.get()};
  const int n = g.cells();
  two.gap_m.resize(2 * n);
  two.gap_m << pr.gap_m, pr.gap_m;
  two.approach_weight = Eigen::VectorXd::Ones(2 * n);
  two.cell_area_m2 = Eigen::VectorXd::Constant(2 * n, g.CellArea());
  const NormalSolution t = Solve(two, CgPreconditioner::kAuto);
  ASSERT_EQ(t.status, SolverStatus::kConverged) << t.message;
  EXPECT_FALSE(t.preconditioned);
}

TEST(PreconditionedNormalSolver, IterationLimitGivesNotConverged) {
  const PatchGrid g = MakeHertzGrid(10);
  const auto op = MakeInfluenceOperator(g, {KernelModel::kBoussinesq, {}, kSteel, kSteel});
  NormalProblem pr = MakeProblem(g, op.get());
  pr.force_N = kForce;
  NormalSolverOptions options;
  options.max_iterations = 2;
  const NormalSolution s = SolveNormal(pr, options);
  EXPECT_TRUE(s.preconditioned);
  EXPECT_EQ(s.status, SolverStatus::kNotConverged);
  EXPECT_EQ(s.iterations, 2);
  EXPECT_NE(s.message.find("after 2 iterations"), std::string::npos) << s.message;
  // Still a usable, load-balanced estimate.
  EXPECT_NEAR(s.force_N, kForce, 1e-10 * kForce);
  EXPECT_GE(s.pressure_Pa.minCoeff(), 0.0);
}

TEST(PreconditionedNormalSolver, PreconditionerNames) {
  EXPECT_EQ(ToString(CgPreconditioner::kAuto), "auto");
  EXPECT_EQ(ToString(CgPreconditioner::kNone), "none");
  EXPECT_EQ(ToString(CgPreconditioner::kInverseOperator), "inverse-operator");
}

}  // namespace
}  // namespace railwear
