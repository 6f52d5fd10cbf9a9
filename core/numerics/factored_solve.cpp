// The curved influence operator's per-frequency kernels (factored_solve.h).
#include "core/numerics/factored_solve.h"

#include "core/numerics/target_clones.h"

namespace railwear::internal {

RAILWEAR_AVX2_CLONES
void MultiplyBlockTwoColumns(int n, const double* __restrict k, const double* __restrict x,
                             const double* __restrict y, double* __restrict u,
                             double* __restrict v) {
  for (int i = 0; i < n; ++i) u[i] = v[i] = 0.0;
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    const double* k0 = k + static_cast<size_t>(j) * n;
    const double *k1 = k0 + n, *k2 = k1 + n, *k3 = k2 + n;
    const double x0 = x[j], x1 = x[j + 1], x2 = x[j + 2], x3 = x[j + 3];
    const double y0 = y[j], y1 = y[j + 1], y2 = y[j + 2], y3 = y[j + 3];
    for (int i = 0; i < n; ++i) {
      u[i] += (k0[i] * x0 + k1[i] * x1) + (k2[i] * x2 + k3[i] * x3);
      v[i] += (k0[i] * y0 + k1[i] * y1) + (k2[i] * y2 + k3[i] * y3);
    }
  }
  for (; j < n; ++j) {
    const double* kj = k + static_cast<size_t>(j) * n;
    const double xj = x[j], yj = y[j];
    for (int i = 0; i < n; ++i) {
      u[i] += kj[i] * xj;
      v[i] += kj[i] * yj;
    }
  }
}

namespace {

// Step j of both frequencies' substitutions: their values at j times the diagonal's reciprocal,
// then subtracted, times column j's entries i in [begin, end), from their values at i (the
// forward pass below the diagonal, the backward one above it). Inlined into each clone.
inline void EliminateColumn(int n, int j, int begin, int end, const double* __restrict l,
                            const double* __restrict m, double* __restrict a, double* __restrict b,
                            double* __restrict c, double* __restrict e) {
  const double* lj = l + static_cast<size_t>(j) * n;
  const double* mj = m + static_cast<size_t>(j) * n;
  const double aj = a[j] * lj[j], bj = b[j] * lj[j];
  const double cj = c[j] * mj[j], ej = e[j] * mj[j];
  a[j] = aj;
  b[j] = bj;
  c[j] = cj;
  e[j] = ej;
  for (int i = begin; i < end; ++i) {
    a[i] -= lj[i] * aj;
    b[i] -= lj[i] * bj;
    c[i] -= mj[i] * cj;
    e[i] -= mj[i] * ej;
  }
}

}  // namespace

RAILWEAR_AVX2_CLONES
void SolveFactoredPair(int n, const double* __restrict l, const double* __restrict m,
                       double* __restrict a, double* __restrict b, double* __restrict c,
                       double* __restrict e) {
  for (int j = 0; j < n; ++j) EliminateColumn(n, j, j + 1, n, l, m, a, b, c, e);
  for (int j = n - 1; j >= 0; --j) EliminateColumn(n, j, 0, j, l, m, a, b, c, e);
}

}  // namespace railwear::internal
