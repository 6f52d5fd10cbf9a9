// Influence operators: the compliance C that maps cell pressures to normal displacements.
//
// u_i = sum_j C_ij p_j, with p_j the uniform pressure on cell j [Pa] and u_i the sum of both
// bodies' normal surface displacements toward each other at the centre of cell i [m]
// (so the deformed gap is g = d - delta*w + C p). C = C_wheel + C_rail, each body with its own
// shear modulus and Poisson ratio.
//
// Kernels per body b (G, nu of that body), point load at cell j, field point i, with
// rho = |P_i - P_j|, dn = (P_i - P_j) . n_j, and (dx, ds) the offsets along the tangents at j:
//   boussinesq:  (1 - nu) / (2 pi G) / rho                       (Love's closed form per cell)
//   golubenko:   (1/rho) [c_f k_f + c_z k_d dn^2 / rho^2]          (seed eq. 4)
//                k_d = 1 / (8 pi (1 - nu) G),  k_f = (3 - 4 nu) k_d
//                (c_f, c_z of that body's set when the constants are separate per curvature
//                sign: InfluenceConstants::ForBody)
// Every kernel is integrated over cell j's tangent rectangle (dx by ds, centred at P_j, spanned
// by the x axis and the s tangent at j) in closed form (RectangleIntegral* below). Cells farther
// than 3.5 cell diagonals use the midpoint rule with its h^2 and h^4 Taylor terms instead: its
// relative error there is < 2.5e-5 on each integral and < 1.5e-6 on a kernel (measured by
// influence_operator_test.cpp), and it avoids the closed forms' cancellation at large distance.
// The x offset is taken as (i_x - j_x) dx, the exact value of (P_i - P_j) . e_x on this grid.
//
// Implementations exploit the grid's structure (see patch_grid.h): Toeplitz in x for a curved
// cross-section (FFT along x, a dense ns x ns block per frequency: memory (L/2 + 1) ns^2
// doubles, L >= 2 nx - 1; construction nx ns^2 kernel evaluations, N^1.5 per product on square
// grids), Toeplitz in x and s for a planar one and for a uniform arc of constant curvature
// (IsUniformArc, patch_grid.h: the kernel sees only the offsets of two cells in the source's
// tangent frame, which on a circle depend on the arc separation alone, evenly; 2-D FFT, nx ns
// kernel evaluations, N log N per product; SectionStructure). Both embed the Toeplitz matrix in a
// circulant one with zero padding, so they reproduce the dense matrix to rounding (~1e-15
// relative). The FFTs are FFTW's, planned once per transform size and shared by the operators of
// that size (FFTW_ESTIMATE: bit-reproducible from run to run; core/numerics/fftw.h). On tiny grids
// (at most kDenseProductMaxCells cells) the products use the full matrix expanded from the same
// coefficients instead, which beats the FFTs' fixed costs (OperatorProducts). A dense matrix
// assembled cell by cell serves as the naive reference on small grids.
//
// Approximate inverses (ApplyPreconditioner), the same structure run backwards: the 2-D
// operator (planar or uniform arc) inverts Strang's circulant on periods >= nx, ns (2-D FFTs,
// a quarter of Apply's bins), the curved one solves with each frequency's ns x ns block (its
// symmetric part, Cholesky-factored once in the constructor: another (L/2 + 1) ns^2 doubles and
// (L/2 + 1) ns^3 / 3 flops; each application costs about 1.5 Apply, the triangular solves being
// slower than Apply's products). On a uniform arc the 2-D inverse is circulant along s as well,
// where the blocks' inverse is exact along s: it loses at the s edges too, which costs a few
// iterations (docs/speed.md) and saves the blocks' ns^3 factorisations. Spectrum values and
// block eigenvalues below a floor are raised to it, so M stays positive definite. M inverts a
// circulant, not C itself: C M r - r is small for displacement fields r that are
// smooth and vanish toward the grid's edges (below 0.15 relative at every grid size,
// influence_operator_test.cpp), which is what makes it a good preconditioner (Vollebregt,
// J. Comput. Phys. 2014).
//
// Threads: the FFT operators keep scratch buffers for Apply (no allocation per call), so one
// operator must not be applied from several threads at once; build one per thread (building
// them in several threads at once is safe: FFTW's planner runs under a mutex).
#pragma once

#include <memory>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear {

class InfluenceOperator {
 public:
  virtual ~InfluenceOperator() = default;
  virtual int size() const = 0;
  // u = C p. p: [size()] pressures [Pa]; u: [size()] displacements [m]. u is resized.
  virtual void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) const = 0;
  // C_kk [m/Pa].
  virtual double Diagonal(int k) const = 0;
  // z = M r with M an approximate inverse of C, for preconditioning iterative solves.
  // r: [size()] displacements [m]; z: [size()] pressures [Pa], resized. M is symmetric positive
  // definite (whatever C's rounding or near-symmetry), so it can precondition conjugate
  // gradients. Returns false, leaving z untouched, when the operator has no such inverse (the
  // default; the dense reference operator).
  virtual bool ApplyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd* z) const {
    (void)r;
    (void)z;
    return false;
  }
  // Whether ApplyPreconditioner has an inverse to apply. By default it is asked with a zero
  // vector; the FFT operators answer without applying theirs (an application is as costly as
  // Apply, and the normal solver asks once per solve: issue 20, docs/library.md).
  virtual bool HasPreconditioner() const {
    Eigen::VectorXd z;
    return ApplyPreconditioner(Eigen::VectorXd::Zero(size()), &z);
  }
};

struct InfluenceSettings {
  KernelModel kernel = KernelModel::kBoussinesq;
  InfluenceConstants constants;
  Material wheel;
  Material rail;
  // Curvature signs of the two bodies on this patch (+1 concave, -1 convex; BodyCurvatureSign).
  // Used only with separate convex and concave constant sets, which then require +1 or -1.
  int wheel_curvature_sign = 0;
  int rail_curvature_sign = 0;
};

// How the operator's products C p are formed.
//   kAuto:  kDense on grids of at most kDenseProductMaxCells cells, kFft above.
//   kFft:   the FFT convolution (O(N log N) per product on planar grids, N^1.5 on curved ones).
//   kDense: the full matrix expanded from the same Toeplitz coefficients (N^2 doubles, N^2
//           multiply-adds per product): faster than the FFTs' fixed costs on tiny grids.
// Either way the coefficients, Diagonal() and the FFT-based preconditioner are the same; the
// products agree to rounding (~1e-15 relative).
enum class OperatorProducts { kAuto, kFft, kDense };

// The crossover of OperatorProducts::kAuto [cells]: 121 (the 11 x 11 grids of a creep table).
// Measured with influence_bench's Apply families (docs/speed.md): dense products are ~15 %
// faster at 11 x 11, the FFTs from 12 x 12 on, on planar and curved grids alike. Defined in the
// .cpp so that re-tuning it rebuilds one file.
extern const int kDenseProductMaxCells;

// How the operator uses the cross-section's structure along s.
//   kAuto:       kToeplitzXs when grid.planar or IsUniformArc(grid) with ns >= 2 (a single row
//                keeps its 1 x 1 blocks: nothing to gain, and the patch builder's one-row grids
//                stay bit for bit as before), else kBlocks.
//   kToeplitzXs: the 2-D FFT (Toeplitz in x and s); the grid must be planar or a uniform arc
//                (a bug otherwise: aborts).
//   kBlocks:     the FFT along x with a dense ns x ns block per x frequency, on any grid (for
//                comparisons and benchmarks; what every curved grid used before issue 18).
// On a uniform arc both give the same products to rounding (the coefficients of one are those
// of the other up to the arc's rounding, InfluenceOperator.UniformArcToeplitzEqualsBlocks); the
// preconditioners differ (the 2-D one is circulant along s too), so solves agree to the solver's
// tolerance, not bit for bit.
enum class SectionStructure { kAuto, kToeplitzXs, kBlocks };

// The structure MakeInfluenceOperator uses for `requested` on this grid (kToeplitzXs or kBlocks).
SectionStructure ChooseSectionStructure(const PatchGrid& grid,
                                        SectionStructure requested = SectionStructure::kAuto);

// Chooses the fastest exact-structure implementation for the grid (2-D FFT when grid.planar or
// the cross-section is a uniform arc, x-Toeplitz FFT with per-frequency blocks otherwise;
// `structure` may force either; products as `products` says). grid.planar promises a straight
// cross-section with points at uniform spacing ds_m along one tangent and one normal (to 1e-9
// relative); a grid that breaks the promise is a bug and aborts. Throws InputError for a
// material with E <= 0 or nu outside [0, 0.5).
std::unique_ptr<InfluenceOperator> MakeInfluenceOperator(
    const PatchGrid& grid, const InfluenceSettings& settings,
    OperatorProducts products = OperatorProducts::kAuto,
    SectionStructure structure = SectionStructure::kAuto);

// Memory the operator MakeInfluenceOperator builds for a grid of this shape would hold [bytes]
// (an estimate within a factor of about 2: the curved operator's per-frequency blocks and their
// Cholesky factors, 2 (L/2 + 1) ns^2 doubles with L ~ 2 nx, and the nx (L/2 + 1) cosine table
// its construction holds; the planar one's padded FFT buffers). Lets a caller refuse a grid
// before it computes anything for it. A non-planar shape is costed as blocks: an overestimate
// for a uniform arc, which the shape alone does not tell (the patch builder asks before it has
// points, and its grids are never uniform arcs).
double EstimateOperatorBytes(int nx, int ns, bool planar);

// Naive reference: the full dense matrix [cells x cells], C(i, j) in m/Pa. For tests and small
// grids only (memory grows as cells^2).
Eigen::MatrixXd AssembleDenseInfluence(const PatchGrid& grid, const InfluenceSettings& settings);

// Dense-matrix operator (wraps AssembleDenseInfluence).
std::unique_ptr<InfluenceOperator> MakeDenseInfluenceOperator(const PatchGrid& grid,
                                                              const InfluenceSettings& settings);

// Closed-form integrals over a rectangle [-hx/2, hx/2] x [-hs/2, hs/2] in the plane, field point
// at in-plane offset (x, s) and out-of-plane offset n from the rectangle's centre [m]:
//   RectangleIntegralInvR  = integral of 1/R      dA   [m]
//   RectangleIntegralN2R3  = integral of n^2/R^3  dA   [m]
// with R = sqrt((x - xi)^2 + (s - eta)^2 + n^2). At the centre of a square of side h,
// RectangleIntegralInvR = 4 h ln(1 + sqrt 2) (Love).
double RectangleIntegralInvR(double x, double s, double n, double hx, double hs);
double RectangleIntegralN2R3(double x, double s, double n, double hx, double hs);

}  // namespace railwear
