// SolveFactoredPair: the curved influence operator's preconditioner substitutions
// (core/contact/influence_operator.cpp, CurvedFftOperator::Convolve), two x frequencies at a
// time (issue 20, the cold gauge-corner call's normal solves; docs/library.md).
#pragma once

#include <cstddef>

namespace railwear::internal {

// L L^T z = y for the two columns a and b of one frequency and c and e of another (the real
// and imaginary parts, ns values each, overwritten with z), L = l and m the lower triangles of
// the two frequencies' column-major ns x ns blocks, their diagonals as reciprocals
// (InvertFactorDiagonal below). Plain substitutions rather than Eigen's
// triangularView solves: on a 2-column right-hand side those run the blocked matrix path
// (packing the block on every call, gebp_kernel), a quarter of a gauge-corner call's normal
// solve (docs/library.md). The forward pass walks the columns of L (contiguous: an axpy per
// column), the backward pass takes column j of L as row j of L^T (a dot product, in two
// partial sums per right-hand side). The same factor, other rounding: the preconditioner
// agrees with the blocked solve to rounding (influence_operator_test.cpp,
// PreconditionerSolvesEachFrequencysBlockExactly).
// Two frequencies at once (issue 20): each substitution is a chain of dependent divisions and
// sums (a[j] waits for a[j - 1]'s division in the forward pass, for a[j + 1]'s in the backward
// one), whose latency, not the arithmetic, bounds one frequency's solve; a second frequency's
// independent chains fill the gaps (tests/benchmarks/influence_bench.cpp's
// BM_CurvedGolubenkoPreconditioner; the figures in docs/library.md, "The cold call's
// preconditioner takes two frequencies at a time"). Each frequency's operations and their order
// are those of a solve on its own, so the result does not depend on its partner and is the
// one-frequency substitution's bit for bit (tests/core/numerics/factored_solve_test.cpp).
// Reciprocals instead of divisions (issue 20): the factor's diagonal holds 1 / L_jj
// (InvertFactorDiagonal, once per factor), so that the substitutions' chains multiply where they
// divided (a multiplication's latency is a few cycles, a division's several times that). Not bit
// for bit with the divisions: a [j] * (1 / L_jj) rounds twice; the solve agrees to rounding
// (factored_solve_test.cpp).
inline void InvertFactorDiagonal(int n, double* l) {
  for (int j = 0; j < n; ++j) {
    double& d = l[static_cast<size_t>(j) * n + j];
    d = 1.0 / d;
  }
}

inline void SolveFactoredPair(int n, const double* __restrict l, const double* __restrict m,
                              double* __restrict a, double* __restrict b, double* __restrict c,
                              double* __restrict e) {
  for (int j = 0; j < n; ++j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    const double* mj = m + static_cast<size_t>(j) * n;
    const double aj = a[j] * lj[j], bj = b[j] * lj[j];
    const double cj = c[j] * mj[j], ej = e[j] * mj[j];
    a[j] = aj;
    b[j] = bj;
    c[j] = cj;
    e[j] = ej;
    for (int i = j + 1; i < n; ++i) {
      a[i] -= lj[i] * aj;
      b[i] -= lj[i] * bj;
      c[i] -= mj[i] * cj;
      e[i] -= mj[i] * ej;
    }
  }
  for (int j = n - 1; j >= 0; --j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    const double* mj = m + static_cast<size_t>(j) * n;
    double a0 = 0.0, a1 = 0.0, b0 = 0.0, b1 = 0.0;
    double c0 = 0.0, c1 = 0.0, e0 = 0.0, e1 = 0.0;
    int i = j + 1;
    for (; i + 1 < n; i += 2) {
      a0 += lj[i] * a[i];
      a1 += lj[i + 1] * a[i + 1];
      b0 += lj[i] * b[i];
      b1 += lj[i + 1] * b[i + 1];
      c0 += mj[i] * c[i];
      c1 += mj[i + 1] * c[i + 1];
      e0 += mj[i] * e[i];
      e1 += mj[i + 1] * e[i + 1];
    }
    if (i < n) {
      a0 += lj[i] * a[i];
      b0 += lj[i] * b[i];
      c0 += mj[i] * c[i];
      e0 += mj[i] * e[i];
    }
    a[j] = (a[j] - (a0 + a1)) * lj[j];
    b[j] = (b[j] - (b0 + b1)) * lj[j];
    c[j] = (c[j] - (c0 + c1)) * mj[j];
    e[j] = (e[j] - (e0 + e1)) * mj[j];
  }
}

}  // namespace railwear::internal
