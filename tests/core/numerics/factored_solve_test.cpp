// SolveFactoredPair (core/numerics/factored_solve.h): two frequencies' substitutions at once give
// each frequency's own one-at-a-time substitution bit for bit, whatever its partner.
#include "core/numerics/factored_solve.h"

#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace railwear::internal {
namespace {

// The curved operator's one-frequency substitution before the pairing (influence_operator.cpp
// up to 181d73d, SolveFactored), kept here as the reference the pairs must reproduce; `divide`
// as it was (l's own diagonal), else by the diagonal's stored reciprocals (InvertFactorDiagonal)
// as the pairs now do.
void SolveFactoredAlone(int n, const double* l, double* a, double* b, bool divide = false) {
  auto by_diagonal = [divide](double x, double d) { return divide ? x / d : x * d; };
  for (int j = 0; j < n; ++j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    const double aj = by_diagonal(a[j], lj[j]), bj = by_diagonal(b[j], lj[j]);
    a[j] = aj;
    b[j] = bj;
    for (int i = j + 1; i < n; ++i) {
      a[i] -= lj[i] * aj;
      b[i] -= lj[i] * bj;
    }
  }
  for (int j = n - 1; j >= 0; --j) {
    const double* lj = l + static_cast<size_t>(j) * n;
    double a0 = 0.0, a1 = 0.0, b0 = 0.0, b1 = 0.0;
    int i = j + 1;
    for (; i + 1 < n; i += 2) {
      a0 += lj[i] * a[i];
      a1 += lj[i + 1] * a[i + 1];
      b0 += lj[i] * b[i];
      b1 += lj[i + 1] * b[i + 1];
    }
    if (i < n) {
      a0 += lj[i] * a[i];
      b0 += lj[i] * b[i];
    }
    a[j] = by_diagonal(a[j] - (a0 + a1), lj[j]);
    b[j] = by_diagonal(b[j] - (b0 + b1), lj[j]);
  }
}

std::vector<double> WithInvertedDiagonal(int n, std::vector<double> l) {
  InvertFactorDiagonal(n, l.data());
  return l;
}

// The Cholesky factor of a random symmetric positive definite n x n matrix (column-major, the
// lower triangle; the upper one left as Eigen's matrixLLT leaves it, as the operator stores it).
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

TEST(FactoredSolve, PairsGiveEachFrequencysOwnSubstitutionBitForBit) {
  // Sizes of the presets' grids (1, a single row; 30, the benchmark's; odd and even ones for
  // the backward pass's two partial sums).
  for (int n : {1, 2, 3, 7, 30, 45}) {
    std::mt19937 rng(n);
    const std::vector<double> l_factor = RandomFactor(n, &rng), m_factor = RandomFactor(n, &rng);
    const std::vector<double> l = WithInvertedDiagonal(n, l_factor);
    const std::vector<double> m = WithInvertedDiagonal(n, m_factor);
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

    // Against the divisions by the diagonal (before the reciprocals): the same to rounding, a
    // few units of the last place per substitution step (measured largest: see the output).
    std::vector<double> a_divided = a0, b_divided = b0;
    SolveFactoredAlone(n, l_factor.data(), a_divided.data(), b_divided.data(), true);
    const Eigen::Map<const Eigen::VectorXd> zd(a_divided.data(), n);
    const double moved = (z - zd).norm() / zd.norm();
    std::printf("[ measured ] n %d: reciprocals move the solve by %.1e\n", n, moved);
    EXPECT_LE(moved, 1e-14) << n;
  }
}

}  // namespace
}  // namespace railwear::internal
