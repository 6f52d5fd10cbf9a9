// Exact steady-rolling tangential contact (Kalker's theory as in his program CONTACT): given the
// normal pressure on a patch grid and the rigid slip (creepage) of every cell, find the
// tangential tractions q with |q| <= mu p, the stick and slip areas and the local slip.
//
// Conventions: see tangential_types.h (tractions on the wheel, creepage w = rigid slip / V, the
// wheel rolls toward +x so material enters the patch at the largest x).
//
// Elasticity. u = u_wheel - u_rail, the tangential displacement difference at the cell centres,
// is u_i = sum_j A_ij q_j with 2 x 2 blocks A_ij (directions x and s) from Cerruti's half-space
// surface solution, per body b with its own G_b and nu_b, integrated over the source cell
// (uniform traction on a dx by ds rectangle) in closed form:
//   A_xx = sum_b 1/(2 pi G_b) int [(1 - nu_b)/R + nu_b X^2/R^3] dA
//   A_ss = sum_b 1/(2 pi G_b) int [(1 - nu_b)/R + nu_b S^2/R^3] dA
//   A_xs = A_sx = sum_b nu_b/(2 pi G_b) int X S/R^3 dA
// (X, S) = field point minus source point, R = |(X, S)|. The rail carries -q and its half-space
// faces the other way, so both bodies' in-plane compliances add. For identical materials this is
// Kalker's (1/(pi G)) [(1 - nu)/R + nu X^2/R^3].
// Neglected: the normal-tangential coupling (zero for quasi-identical materials; the coupled
// problem is a separate effect, DESIGN.md §1), so the pressure is an input and stays fixed.
// Curved grids: the coefficients are the flat half-space ones with arc-length offsets
// (X, S) = (x_i - x_j, s_i - s_j), and the s direction of each cell is its own tangent. This
// neglects the out-of-plane offset dn and the rotation of the tangent across the patch (both of
// relative order (patch width / lateral radius)^2 on the coefficients); it keeps the operator
// Toeplitz in x and s on every grid, so one 2-D FFT product serves planar and curved patches.
//
// Steady rolling. A material particle at x_i was at x_i + dx one step dt = dx/V earlier (material
// moves toward -x through the patch), so the time derivative of u at the particle becomes
//   du/dt = -V du/dx  ~  V (u(x_i) - u(x_i + dx)) / dx        (first-order upwind),
// and the slip per unit rolling speed is
//   s_i = w_i + (u_i - u'_i) / dx,   u'_i = sum_j A(x_i + dx - x_j, s_i - s_j) q_j,
// i.e. s = w + B q with the rolling operator B(d) = (A(d) - A(d + 1)) / dx (d = x-index offset
// field minus source). u' is evaluated with the same kernel at the shifted point, so the cells of
// the last (leading) column need no displacement from outside the grid. The local slip velocity
// is V s [m/s].
// Conditions per cell with p > 0: stick: s = 0 and |q| <= mu p; slip: q = -mu p s / |s|.
// Cells with p = 0 carry no traction.
//
// Method: nonlinear block Gauss-Seidel with the exact 2 x 2 local problem per cell, in
// "chain" form. In plain variables B is a difference operator (a constant traction along x gives
// no slip), and Gauss-Seidel on it does not converge in full stick. So a Gauss-Seidel step at
// cell k changes the traction of k and of every loaded cell downstream of it in its x-row, up to
// the contact edge (the chain): q_j += dq for j = e .. k. This is Gauss-Seidel on the increments
// q_k - q_(k+1), where the operator becomes (A(m - k) - A(m - e + 1)) / dx, close to the
// symmetric positive A / dx. The local diagonal is D_k = (A(0) - A(k - e + 1)) / dx (diagonal,
// positive); with r the slip the cell would have with q_k = 0, stick is q_k = -D^-1 r when that
// lies in the friction disc, otherwise q_k = -mu p r_k / (sigma + mu p D_kk) with sigma = |s| > 0
// the root of sum_k r_k^2 / (sigma + mu p D_kk)^2 = 1 (Newton, monotone from sigma = 0). Cells
// are swept from the leading edge (largest x) to the trailing edge, so a chain update only moves
// cells not yet visited in the sweep. The step is under-relaxed (`relaxation`): the chain
// operator is not symmetric near the trailing edge and the unrelaxed plain sweep diverges in full
// stick on fine grids (measured: 1.0 and 0.5 diverge in full stick at 32 x 16 cells of the Hertz
// test case, 0.3 converges there and at 64 x 32 in about 110 iterations).
// Acceleration: the sweep is a fixed-point map q -> G(q); the outer iteration is Anderson-
// accelerated (type II, Walker & Ni 2011, depth `anderson_depth`): the next iterate mixes the
// last sweeps' images so as to minimise the linearised residual G(q) - q. The fixed point is the
// same. Measured on the Hertz cases (grids 16 x 8 to 140 x 70 and 70 x 80, a/b from 1/3 to 5,
// full stick, spin, the README case, full slip): depth 8 with relaxation 0.5 converges in 15 to
// 61 iterations everywhere, where the plain sweep at 0.3 needs 42 to 552 and stalls (2000
// iterations) at xi = 1e-4, eta = -1e-4 on 64 x 32 cells and finer. With acceleration, 0.5
// converges also in full stick (and beats 0.3: 46 against 66 iterations on the README case); the
// divergence guard (see ExactTangentialOptions::relaxation) stays.
// Each outer iteration evaluates s = w + B q exactly (one FFT product of the four blocks, or the
// dense matrix; on small patches the dense matrix of the loaded cells, Method::kAuto), checks
// convergence, then sweeps once and mixes. The sweep runs over blocks of
// adjacent x-columns, leading block first. Inside a block the slip of the loaded cells not yet
// visited is kept exact from a table of A on the offsets (the chain's effect
// (A(m - k) - A(m - v)) / dx: a source at the cell and an opposite one at the virtual cell v
// beyond the chain end): the cells after an update in its own column at once, a later column of
// the block when the sweep reaches it, from all the block's changes so far (one Toeplitz product
// per earlier column, and one with the virtual cells' sources, summed per row and chain end).
// After a block one operator product refreshes the slip of all cells at once. Cells of later
// blocks are read only after that product and visited cells not again in the sweep, so every
// local solve sees the exact slip of the current iterate: the iterates are those of the plain
// sweep with a full refresh after every update (to rounding), at a cost per sweep of about
// N_contact * (block / 2) * (loaded column length) multiply-adds (4 per source and target cell)
// plus span / block products, span the x-columns from the first to the last
// loaded one (the blocks cover those only, in equal widths). The block width balances the two
// (FftBlockColumns in the .cpp: 17 and 22 columns on CONTACT's tang_problm_1c / 2c grids), or
// ExactTangentialOptions::block_columns sets it. The FFT products run on the loaded cells'
// bounding rectangle when its padded transforms are shorter than the grid's
// (CroppedRollingProduct in the .cpp; a conformal patch's potential contact area can be twice its
// contact's length), with the same result to rounding. With the dense operator a product costs a
// full sweep of refreshes, so there one block spans the grid (the plain sweep, O(N_contact N)).
// Measured (tangential_exact_bench, README check case, one core, median of 5): 70 x 80 cells
// 0.69 s before acceleration (relaxation 0.3, 109 sweeps), 0.30 s with it (46 sweeps, ratio
// 0.44); about 6.5 ms per sweep, 55 % of it the in-block refreshes and 40 % the FFT products.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"

namespace railwear {

// The crossover of ExactTangentialOptions::Method::kAuto [loaded cells]: 200. Measured with
// tangential_exact_bench's BM_TangentialExactSmallPatch (docs/speed.md): the loaded cells' matrix
// is faster than the FFT products up to 225 loaded cells and slower at 349. Defined in the .cpp.
extern const int kLoadedDenseMaxCells;
// ExactTangentialOptions::tolerance's default (tangential_exact.cpp).
extern const double kDefaultExactTangentialTolerance;
// The tolerances a scene ([model] tangential_tolerance) or the C API
// (rw_model.tangential_tolerance) may ask for: from 1e-10 (a tenth of the strict 1e-9 the
// solver's tests use, far above the FFT products' rounding) to 1e-2 (2 digits).
inline constexpr double kMinExactTangentialTolerance = 1e-10, kMaxExactTangentialTolerance = 1e-2;

struct ExactTangentialOptions {
  // How the rolling operator B is applied.
  //   kAuto:  kFft, except on small patches (at most kLoadedDenseMaxCells loaded cells), where the
  //           products use the dense 2m x 2m matrix of the m loaded cells, taken from the same
  //           coefficients (4 m^2 multiply-adds per product, beating the padded FFTs' fixed
  //           costs there; the matrix is built per solve, 3 m^2 table reads).
  //   kFft:   2-D FFT products (padded, exact to rounding), O(N log N) per product,
  //           N = grid.cells().
  //   kDense: the full 2N x 2N matrix (the naive reference, for tests; memory 32 N^2 bytes).
  // All run the same sweeps (kAuto and kFft the same blocks), so they give the same iterates to
  // rounding.
  enum class Method { kAuto, kFft, kDense };
  Method method = Method::kAuto;
  // Stopping criterion (dimensionless, > 0): the largest change of any cell's traction that one
  // exact local solve would make, with a freshly applied operator, relative to mu * max(p):
  //   max_k |q_k - LocalSolve_k(q)| <= tolerance * mu * max_k p_k.
  // The default, kDefaultExactTangentialTolerance, is defined in tangential_exact.cpp (its
  // value and what it keeps are documented there).
  double tolerance = kDefaultExactTangentialTolerance;
  // Outer iterations (one operator product and one sweep each) before giving up with
  // kNotConverged. >= 1.
  int max_iterations = 2000;
  // Under-relaxation of the Gauss-Seidel step, in (0, 1]. The fixed point does not depend on it;
  // with the acceleration 0.5 converges on every Hertz case measured (see the header comment;
  // without it, use 0.3). The solver halves it (and restarts the acceleration) when the residual
  // grows tenfold above its best value.
  double relaxation = 0.5;
  // Columns per block of the sweep with kFft (see the header comment), >= 0; 0 chooses the width
  // that balances refreshes against products. The iterates do not depend on it (to rounding).
  // kDense always sweeps in one block.
  int block_columns = 0;
  // Anderson acceleration of the outer iteration (see the header comment): the number of past
  // sweeps mixed, >= 0; 0 runs the plain relaxed sweeps. Memory: 2 * depth vectors of twice the
  // loaded cells.
  int anderson_depth = 8;
  // Returns "" when valid, otherwise what is wrong.
  std::string Validate() const;
};

// grid: the patch grid (planar or curved, see the header comment for the curved approximation).
// pressure_Pa: [grid.cells()] normal pressure per cell, >= 0 (cells with 0 carry no traction).
// in: creep_x, creep_s of size grid.cells() [-]; speed_m_s > 0; friction mu > 0.
// wheel, rail: each body's elastic constants.
// Throws InputError for bad options, materials (E <= 0, nu outside [0, 0.5)) or inputs (sizes,
// negative or non-finite pressure, speed or friction <= 0). Returns kNoContact when no cell is
// loaded, kNotConverged (with the last iterate) when max_iterations is reached.
TangentialSolution SolveTangentialExact(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                        const RollingInput& in, const Material& wheel,
                                        const Material& rail,
                                        const ExactTangentialOptions& opt = {});

// The parts of the exact solve that depend only on the grid's shape (nx, ns, dx_m, ds_m), the two
// materials and the operator method: the rolling operator B (its FFT spectra or dense matrix) and
// the table of the displacement kernel the sweeps read (step 1 of the header comment; kernel
// evaluations and FFTs, about a quarter of a solve on a creep table's 11 x 11 grid, perf in
// docs/speed.md). A caller that solves many problems on one grid (a creep table, a search over
// creepages) builds one setup and passes it to every solve; the results are those of the solve
// that builds its own, bit for bit (the same computations; tangential_exact_test.cpp). Not for
// concurrent use: the FFT products keep scratch buffers (build one per thread).
class ExactTangentialSetup {
 public:
  // Throws InputError for a grid without cells of positive size or a bad material (as
  // SolveTangentialExact).
  ExactTangentialSetup(
      const PatchGrid& grid, const Material& wheel, const Material& rail,
      ExactTangentialOptions::Method method = ExactTangentialOptions::Method::kFft);
  ~ExactTangentialSetup();
  ExactTangentialSetup(ExactTangentialSetup&&) noexcept;
  ExactTangentialSetup& operator=(ExactTangentialSetup&&) noexcept;
  // True when the setup serves this grid: the same nx, ns, dx_m and ds_m (the operator does not
  // depend on the rest of the grid, see the header comment on curved grids).
  bool Fits(const PatchGrid& grid) const;
  // True when the setup serves this method: kDense needs a setup built for kDense, kAuto and
  // kFft one built for either of them.
  bool Serves(ExactTangentialOptions::Method method) const;

  struct Impl;  // defined in the .cpp
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// The same solve with a setup built beforehand for this grid and the materials (wheel, rail of
// the overload above). Throws InputError as above, and when the setup does not fit the grid or
// does not serve opt.method.
// start (optional): a warm start, an earlier solution on a grid of the same shape (a search over
// creepages or pitch velocities, a vertical balance that moves the pressure a little): the
// iteration starts from its tractions on the cells loaded now (0 on the others) instead of 0.
// The fixed point does not depend on the start, so the result is the cold start's to the
// stopping tolerance, not bit for bit; near solutions need fewer iterations (docs/speed.md,
// the groove's free rolling). Throws InputError when its tractions are not of grid.cells().
TangentialSolution SolveTangentialExact(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                        const RollingInput& in, const ExactTangentialSetup& setup,
                                        const ExactTangentialOptions& opt = {},
                                        const TangentialSolution* start = nullptr);

namespace internal {

// Cerruti coefficients of the cell kernel, both bodies summed [1/Pa]:
//   inv_r = sum_b (1 - nu_b)/(2 pi G_b),  quad = sum_b nu_b/(2 pi G_b).
struct CerrutiCoefficients {
  double inv_r = 0.0;
  double quad = 0.0;
};
CerrutiCoefficients MakeCerrutiCoefficients(const Material& wheel, const Material& rail);

// Tangential displacement difference [m/Pa] at offset (x, s) [m] (field point minus the centre
// of the source cell) from a unit uniform traction on a hx by hs rectangle: xx = u_x per q_x,
// xs = u_x per q_s (= u_s per q_x), ss = u_s per q_s.
struct TangentialBlock {
  double xx = 0.0, xs = 0.0, ss = 0.0;
};
TangentialBlock CerrutiCellInfluence(const CerrutiCoefficients& c, double x, double s, double hx,
                                     double hs);

// Closed-form rectangle integrals on the plane (field point in the plane), arguments as
// RectangleIntegralInvR [m]: int X^2/R^3 dA, int S^2/R^3 dA, int X S/R^3 dA, with (X, S) the
// field point minus the integration point.
double RectangleIntegralX2R3(double x, double s, double hx, double hs);
double RectangleIntegralS2R3(double x, double s, double hx, double hs);
double RectangleIntegralXSR3(double x, double s, double hx, double hs);

}  // namespace internal
}  // namespace railwear
