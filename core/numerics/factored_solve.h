// The curved influence operator's per-frequency kernels (core/contact/influence_operator.cpp,
// CurvedFftOperator::Convolve; issue 20, the cold gauge-corner call's normal solves,
// docs/library.md): its products (MultiplyBlockTwoColumns) and its preconditioner's
// substitutions (SolveFactoredPair), each compiled for AVX2 and for the baseline
// (core/numerics/target_clones.h) with the same bits from both.
#pragma once

#include <cstddef>

namespace railwear::internal {

// u = K x and v = K y for one column-major n x n block K (the curved operator's K_k, x and y its
// frequency's real and imaginary parts): one pass over K for both columns, where two Eigen
// matrix-vector products read the whole block twice. Four columns of K per pass over u and v
// (as the tangential sweeps' AddKernelProducts, core/contact/tangential_exact.cpp): each entry
// of K is loaded once and multiplied by x_j and y_j, u and v are read and written once per four
// columns, and the loop over the rows vectorizes. Each row sums its columns in a fixed order,
// u_i = (...((k_i0 x_0 + k_i1 x_1) + (k_i2 x_2 + k_i3 x_3)) + ...) for the whole groups of four,
// then the last n mod 4 columns one at a time: not Eigen's order, so the products move by
// rounding against Eigen's (tests/core/numerics/factored_solve_test.cpp).
void MultiplyBlockTwoColumns(int n, const double* k, const double* x, const double* y, double* u,
                             double* v);

// A Cholesky factor L (the lower triangle of a column-major n x n block, sym K_k = L L^T) made
// ready for SolveFactoredPair, in place: its diagonal replaced by the reciprocals 1 / L_jj and
// its upper triangle (unused by the factorization) by L^T, so that column j holds L's column j
// below the diagonal and L's row j above it.
inline void PrepareFactor(int n, double* l) {
  for (int j = 0; j < n; ++j) {
    double* lj = l + static_cast<size_t>(j) * n;
    lj[j] = 1.0 / lj[j];
    for (int i = 0; i < j; ++i) lj[i] = l[static_cast<size_t>(i) * n + j];
  }
}

// L L^T z = y for the two columns a and b of one frequency and c and e of another (the real
// and imaginary parts, ns values each, overwritten with z), L = l and m the two frequencies'
// blocks as PrepareFactor leaves them. Plain substitutions rather than Eigen's triangularView
// solves: on a 2-column right-hand side those run the blocked matrix path (packing the block on
// every call, gebp_kernel), a quarter of a gauge-corner call's normal solve (docs/library.md).
// Both passes walk the columns of the block, an axpy over contiguous values per column: the
// forward one (L w = y) subtracts w_j times L's column j below the diagonal, the backward one
// (L^T z = w) z_j times L's row j, stored above the diagonal (PrepareFactor). Until issue 20's
// "one pass" change the backward pass took row j of L^T as a dot product with z, whose in-order
// sum the compiler cannot vectorize (rounding moves, factored_solve_test.cpp).
// Two frequencies at once: each substitution is a chain of dependent steps (w_j waits for the
// axpy of column j - 1, z_j for that of column j + 1) whose latency, not the arithmetic, bounds
// one frequency's solve; a second frequency's independent chains fill the gaps
// (tests/benchmarks/influence_bench.cpp's BM_CurvedGolubenkoPreconditioner; docs/library.md,
// "The cold call's preconditioner takes two frequencies at a time"). Each frequency's operations
// and their order are those of a solve on its own, so the result does not depend on its partner
// (factored_solve_test.cpp). Multiplications by the diagonal's reciprocals rather than divisions
// (a multiplication's latency is a few cycles, a division's several times that).
void SolveFactoredPair(int n, const double* l, const double* m, double* a, double* b, double* c,
                       double* e);

}  // namespace railwear::internal
