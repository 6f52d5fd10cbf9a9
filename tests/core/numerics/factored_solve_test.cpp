// The curved operator's per-frequency kernels (core/numerics/factored_solve.h): the products in
// one pass over the block against Eigen's, and the preconditioner's substitutions two
// frequencies at a time, each frequency's own one-at-a-time substitution bit for bit whatever
// its partner, against the substitutions before issue 20's "one pass" change to rounding.
#include "core/numerics/factored_solve.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace railwear::internal {
namespace {

// One frequency's substitution on a factor prepared by PrepareFactor, each value's operations in
// SolveFactoredPair's order: the reference the pairs must reproduce.
void SolveFactoredAlone(int n, const double* l, double* a, double* b) {
  for (int j = 0; j < n; ++j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    const double aj = a[j] * lj[j], bj = b[j] * lj[j];
    a[j] = aj;
    b[j] = bj;
    for (int i = j + 1; i < n; ++i) {
      a[i] -= lj[i] * aj;
      b[i] -= lj[i] * bj;
    }
  }
  for (int j = n - 1; j >= 0; --j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    const double aj = a[j] * lj[j], bj = b[j] * lj[j];
    a[j] = aj;
    b[j] = bj;
    for (int i = 0; i < j; ++i) {
      a[i] -= lj[i] * aj;
      b[i] -= lj[i] * bj;
    }
  }
}

// The curved operator's substitution up to 181d73d (influence_operator.cpp, SolveFactored): the
// factor as Eigen leaves it (the diagonal itself), divisions by the diagonal, and the backward
// pass as dot products of L's columns with z in two partial sums.
void SolveFactoredByDotProducts(int n, const double* l, double* a) {
  for (int j = 0; j < n; ++j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    const double aj = a[j] / lj[j];
    a[j] = aj;
    for (int i = j + 1; i < n; ++i) a[i] -= lj[i] * aj;
  }
  for (int j = n - 1; j >= 0; --j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    double a0 = 0.0, a1 = 0.0;
    int i = j + 1;
    for (; i + 1 < n; i += 2) {
      a0 += lj[i] * a[i];
      a1 += lj[i + 1] * a[i + 1];
    }
    if (i < n) a0 += lj[i] * a[i];
    a[j] = (a[j] - (a0 + a1)) / lj[j];
  }
}

std::vector<double> Prepared(int n, std::vector<double> l) {
  PrepareFactor(n, l.data());
  return l;
}

// The Cholesky factor of a random symmetric positive definite n x n matrix (column-major, the
// lower triangle; the upper one left as Eigen's matrixLLT leaves it, as the operator stores it
// before PrepareFactor).
std::vector<double> RandomFactor(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd a(n, n);
  for (int k = 0; k < a.size(); ++k) a.data()[k] = value(*rng);
  const Eigen::MatrixXd spd = a * a.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd l = Eigen::LLT<Eigen::MatrixXd>(spd).matrixLLT();
  return {l.data(), l.data() + l.size()};
}

std::vector<double> RandomColumn(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> value(-1e-6, 1e-6);
  std::vector<double> v(n);
  for (double& x : v) x = value(*rng);
  return v;
}

// Sizes of the presets' grids (1, a single row; 30, the benchmark's) and odd and even ones
// around them (the products' groups of four columns, the vectorized loops' remainders).
constexpr int kSizes[] = {1, 2, 3, 4, 5, 7, 30, 45};

TEST(FactoredSolve, PrepareFactorInvertsTheDiagonalAndMirrorsTheFactorAboveIt) {
  std::mt19937 rng(3);
  const int n = 5;
  const std::vector<double> l = RandomFactor(n, &rng), p = Prepared(n, l);
  for (int j = 0; j < n; ++j) {
    EXPECT_EQ(p[j * n + j], 1.0 / l[j * n + j]);
    for (int i = j + 1; i < n; ++i) {
      EXPECT_EQ(p[j * n + i], l[j * n + i]);  // L below the diagonal, as it was
      EXPECT_EQ(p[i * n + j], l[j * n + i]);  // and L^T above it
    }
  }
}

TEST(FactoredSolve, PairsGiveEachFrequencysOwnSubstitutionBitForBit) {
  for (int n : kSizes) {
    std::mt19937 rng(n);
    const std::vector<double> l_factor = RandomFactor(n, &rng), m_factor = RandomFactor(n, &rng);
    const std::vector<double> l = Prepared(n, l_factor), m = Prepared(n, m_factor);
    const std::vector<double> a0 = RandomColumn(n, &rng), b0 = RandomColumn(n, &rng);
    const std::vector<double> c0 = RandomColumn(n, &rng), e0 = RandomColumn(n, &rng);
    std::vector<double> a_alone = a0, b_alone = b0, c_alone = c0, e_alone = e0;
    SolveFactoredAlone(n, l.data(), a_alone.data(), b_alone.data());
    SolveFactoredAlone(n, m.data(), c_alone.data(), e_alone.data());

    std::vector<double> a = a0, b = b0, c = c0, e = e0;
    SolveFactoredPair(n, l.data(), m.data(), a.data(), b.data(), c.data(), e.data());
    EXPECT_EQ(a, a_alone) << n;
    EXPECT_EQ(b, b_alone) << n;
    EXPECT_EQ(c, c_alone) << n;
    EXPECT_EQ(e, e_alone) << n;

    // An odd count's last frequency, paired with zeros on its own factor (Convolve).
    std::vector<double> a1 = a0, b1 = b0, zeros(2 * n, 0.0);
    SolveFactoredPair(n, l.data(), l.data(), a1.data(), b1.data(), zeros.data(), zeros.data() + n);
    EXPECT_EQ(a1, a_alone) << n;
    EXPECT_EQ(b1, b_alone) << n;
    EXPECT_EQ(zeros, std::vector<double>(2 * n, 0.0)) << n;

    // And it solves: L L^T z = y to rounding.
    const Eigen::Map<const Eigen::MatrixXd> lm(l_factor.data(), n, n);
    const Eigen::MatrixXd lower = lm.triangularView<Eigen::Lower>();
    const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(a0.data(), n);
    const Eigen::VectorXd z = Eigen::Map<const Eigen::VectorXd>(a.data(), n);
    EXPECT_LE((lower * (lower.transpose() * z) - y).norm(), 1e-12 * y.norm()) << n;

    // Against the substitution before (divisions, the backward pass by dot products): the same
    // to rounding, a few units of the last place per substitution step on these well-conditioned
    // factors (condition number below 10; measured largest: see the output).
    std::vector<double> a_before = a0;
    SolveFactoredByDotProducts(n, l_factor.data(), a_before.data());
    const Eigen::Map<const Eigen::VectorXd> zb(a_before.data(), n);
    const double moved = (z - zb).norm() / zb.norm();
    std::printf("[ measured ] n %d: the substitution moved by %.1e\n", n, moved);
    EXPECT_LE(moved, 1e-14) << n;
  }
}

// MultiplyBlockTwoColumns' sums in their documented order (factored_solve.h), written out.
double RowSumInOrder(int n, const std::vector<double>& k, const std::vector<double>& x, int i) {
  double s = 0.0;
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    s += (k[j * n + i] * x[j] + k[(j + 1) * n + i] * x[j + 1]) +
         (k[(j + 2) * n + i] * x[j + 2] + k[(j + 3) * n + i] * x[j + 3]);
  }
  for (; j < n; ++j) s += k[j * n + i] * x[j];
  return s;
}

// The products against Eigen's matrix-vector products (what Convolve ran before): equal to
// rounding. Bound: a dot product of n terms in any order is within n eps sum_j |k_ij x_j| of
// the exact one (Higham, Accuracy and Stability, eq. 3.5), so two orders within 2 n eps of it;
// kProductRoundingTolerance = 2 n eps with eps = 2^-52 (DBL_EPSILON, twice the unit roundoff,
// margin for the partial sums' own rounding).
TEST(FactoredSolve, ProductsInOnePassEqualEigensToRounding) {
  for (int n : kSizes) {
    std::mt19937 rng(100 + n);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::vector<double> k(static_cast<size_t>(n) * n), x(n), y(n), u(n), v(n);
    for (double& c : k) c = value(rng) * 1e-12;  // [m/Pa], an influence block's scale
    for (double& c : x) c = value(rng) * 1e9;    // [Pa]
    for (double& c : y) c = value(rng) * 1e9;
    MultiplyBlockTwoColumns(n, k.data(), x.data(), y.data(), u.data(), v.data());
    const Eigen::Map<const Eigen::MatrixXd> km(k.data(), n, n);
    const Eigen::VectorXd eu = km * Eigen::Map<const Eigen::VectorXd>(x.data(), n);
    const Eigen::VectorXd ev = km * Eigen::Map<const Eigen::VectorXd>(y.data(), n);
    const Eigen::VectorXd su =
        km.cwiseAbs() * Eigen::Map<const Eigen::VectorXd>(x.data(), n).cwiseAbs();
    const Eigen::VectorXd sv =
        km.cwiseAbs() * Eigen::Map<const Eigen::VectorXd>(y.data(), n).cwiseAbs();
    const double kProductRoundingTolerance = 2.0 * n * 2.220446049250313e-16;
    double moved = 0.0;
    for (int i = 0; i < n; ++i) {
      EXPECT_LE(std::abs(u[i] - eu[i]), kProductRoundingTolerance * su[i]) << n << " " << i;
      EXPECT_LE(std::abs(v[i] - ev[i]), kProductRoundingTolerance * sv[i]) << n << " " << i;
      moved = std::max({moved, std::abs(u[i] - eu[i]) / su[i], std::abs(v[i] - ev[i]) / sv[i]});
      // The documented order, bit for bit, so the result does not depend on the clone
      // (AVX2 or the baseline) or on how the compiler groups the rows.
      EXPECT_EQ(u[i], RowSumInOrder(n, k, x, i)) << n << " " << i;
      EXPECT_EQ(v[i], RowSumInOrder(n, k, y, i)) << n << " " << i;
    }
    std::printf("[ measured ] n %d: against Eigen's products, largest move %.1e of sum |k x|\n", n,
                moved);
  }
}

}  // namespace
}  // namespace railwear::internal
