// Fast influence operators: FFT convolution on the grid's Toeplitz structure (see
// influence_operator.h). The dense reference lives in influence_kernels.cpp.
//
// Both operators embed the Toeplitz matrix in a circulant one of length L >= 2n - 1 per
// Toeplitz direction (zero padding), so the products are exact linear convolutions, not
// periodic ones. The kernels are even in their Toeplitz offsets, so their spectra are real.
// FFTs use Eigen's unsupported FFT module (kissfft backend): real-input transforms with the
// half spectrum, and lengths 2^a 3^b 5^c (kissfft's radices), multiples of 4 for the real
// transforms (that selects kissfft's packed real FFT).
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/FFT>

#include "core/contact/influence_kernels.h"
#include "core/numerics/check.h"
#include "core/numerics/fft_size.h"

namespace railwear {
namespace {

using Complex = std::complex<double>;

using internal::NextFftSize;
// Lengths of the real (x) and complex (s) transforms for a Toeplitz direction of n cells.
int RealFftSize(int n) { return NextFftSize(2 * n - 1, 4); }
int ComplexFftSize(int n) { return NextFftSize(2 * n - 1, 1); }

// An unscaled, half-spectrum FFT object. Its plans are built on first use of each length;
// Warm() does that in the constructors so Apply never allocates.
Eigen::FFT<double> MakeFft() {
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::Unscaled);
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  return fft;
}

// The planar grid's promise: a straight cross-section with uniform spacing ds and one normal.
// Relative tolerance on positions (in units of ds) and on unit vectors; far above rounding of a
// grid built as origin + s * tangent, far below anything that would change a coefficient
// visibly.
constexpr double kPlanarGridTolerance = 1e-9;

// Floor of the approximate inverses, relative to the self-influence C_kk: circulant spectrum
// values (planar) and eigenvalues of the symmetric part of each frequency's block (curved) below
// kSpectrumFloor * C_kk are raised to it before inverting. The discrete half-space symbol is
// smallest at the highest frequency, where it is a fixed fraction of C_kk on any grid (about
// 0.5 C_kk for square Boussinesq cells, checked by influence_operator_test.cpp); the circulant
// embedding's wrap-around can dip below that and, in principle, below zero. 0.1 C_kk leaves
// every genuine value untouched and keeps M positive definite with a bounded norm.
constexpr double kSpectrumFloor = 0.1;

void CheckPlanarGrid(const PatchGrid& grid) {
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d expected = grid.point_yz_m[0] + (j * grid.ds_m) * grid.tangent_yz[0];
    RAILWEAR_CHECK((grid.point_yz_m[j] - expected).norm() <= kPlanarGridTolerance * grid.ds_m);
    RAILWEAR_CHECK((grid.tangent_yz[j] - grid.tangent_yz[0]).norm() <= kPlanarGridTolerance);
    RAILWEAR_CHECK((grid.normal_yz[j] - grid.normal_yz[0]).norm() <= kPlanarGridTolerance);
  }
}

// ---------------------------------------------------------------------------------------------
// Planar grid: C depends on (i_x - j_x, i_s - j_s). 2-D linear convolution by FFT.
//
// Layout: the x direction (cell index fastest) is transformed with real FFTs of length lx_ to
// hx_ = lx_/2 + 1 bins; the s direction with complex FFTs of length ls_. The 2-D spectrum is
// stored bin-major: rows_[kx * ls_ + ks].
class PlanarFftOperator final : public InfluenceOperator {
 public:
  PlanarFftOperator(const PatchGrid& grid, const internal::KernelCoefficients& coefficients)
      : nx_(grid.nx),
        ns_(grid.ns),
        lx_(RealFftSize(grid.nx)),
        hx_(lx_ / 2 + 1),
        ls_(ComplexFftSize(grid.ns)),
        fft_(MakeFft()),
        x_real_(lx_, 0.0),
        x_out_(lx_, 0.0),
        x_half_(hx_),
        rows_(static_cast<size_t>(hx_) * ls_, Complex(0.0, 0.0)),
        s_line_(ls_),
        s_out_(ls_),
        cropped_(static_cast<size_t>(hx_) * ns_) {
    CheckPlanarGrid(grid);
    // Kernel on offsets d >= 0, e >= 0 (nx * ns evaluations), even extension into an
    // lx_ by ls_ circulant generator (x fastest).
    std::vector<double> generator(static_cast<size_t>(lx_) * ls_, 0.0);
    for (int e = 0; e < ns_; ++e) {
      for (int d = 0; d < nx_; ++d) {
        const double c = internal::CellInfluence(grid, coefficients, d, e, 0, 0);
        if (d == 0 && e == 0) diagonal_ = c;
        for (int ee : {e, (ls_ - e) % ls_}) {
          for (int dd : {d, (lx_ - d) % lx_}) {
            generator[static_cast<size_t>(ee) * lx_ + dd] = c;
          }
        }
      }
    }
    TransformX(generator.data(), ls_, lx_);
    // Even generator -> real spectrum; the inverse FFTs are unscaled, so fold in 1/(lx ls).
    spectrum_.resize(static_cast<size_t>(hx_) * ls_);
    const double scale = 1.0 / (static_cast<double>(lx_) * ls_);
    for (int kx = 0; kx < hx_; ++kx) {
      const size_t row = static_cast<size_t>(kx) * ls_;
      fft_.fwd(s_line_.data(), rows_.data() + row, ls_);
      for (int ks = 0; ks < ls_; ++ks) spectrum_[row + ks] = s_line_[ks].real() * scale;
    }
    // The preconditioner's multiplier: 1 / symbol, the symbol raised to the floor first, times
    // 1/(lx ls) for the unscaled inverse FFT.
    const double floor = kSpectrumFloor * diagonal_;
    inverse_spectrum_.resize(spectrum_.size());
    for (size_t k = 0; k < spectrum_.size(); ++k) {
      const double symbol = spectrum_[k] / scale;  // the circulant's eigenvalue [m/Pa]
      inverse_spectrum_[k] = scale / std::max(symbol, floor);
    }
    // TransformX() filled all ls_ columns of rows_ and all of x_real_; Apply relies on columns
    // >= ns_ and entries >= nx_ being zero.
    std::fill(rows_.begin(), rows_.end(), Complex(0.0, 0.0));
    std::fill(x_real_.begin(), x_real_.end(), 0.0);
    // One product builds the inverse FFT plans, so Apply does not allocate.
    Eigen::VectorXd u;
    Apply(Eigen::VectorXd::Zero(size()), &u);
  }

  int size() const override { return nx_ * ns_; }
  double Diagonal(int) const override { return diagonal_; }

  void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) const override {
    Convolve(p, spectrum_, u);
  }

  // Same embedding, divided by the spectrum instead: z = crop(IFFT(FFT(pad(r)) / C^)). It
  // inverts the circulant exactly; on the grid it is close to the Toeplitz inverse except
  // within a few cells of the edges.
  bool ApplyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd* z) const override {
    Convolve(r, inverse_spectrum_, z);
    return true;
  }

 private:
  // out = crop(IFFT2(FFT2(pad(in)) * multiplier)); multiplier [hx_ * ls_], bin-major, with the
  // inverse FFTs' scaling folded in.
  void Convolve(const Eigen::VectorXd& in, const std::vector<double>& multiplier,
                Eigen::VectorXd* out) const {
    RAILWEAR_CHECK(in.size() == size());
    TransformX(in.data(), ns_, nx_);
    for (int kx = 0; kx < hx_; ++kx) {
      const size_t row = static_cast<size_t>(kx) * ls_;
      fft_.fwd(s_line_.data(), rows_.data() + row, ls_);
      for (int ks = 0; ks < ls_; ++ks) s_line_[ks] *= multiplier[row + ks];
      fft_.inv(s_out_.data(), s_line_.data(), ls_);
      for (int j = 0; j < ns_; ++j) cropped_[static_cast<size_t>(j) * hx_ + kx] = s_out_[j];
    }
    if (out->size() != size()) out->resize(size());
    for (int j = 0; j < ns_; ++j) {
      fft_.inv(x_out_.data(), cropped_.data() + static_cast<size_t>(j) * hx_, lx_);
      std::copy(x_out_.begin(), x_out_.begin() + nx_, out->data() + static_cast<size_t>(j) * nx_);
    }
  }

  // Real FFTs along x of n_rows s-rows of row_length values each (x fastest; the rest is zero
  // padding) into columns 0 .. n_rows-1 of rows_. The other columns must hold zeros (they do
  // after the constructor; nothing else writes them).
  void TransformX(const double* data, int n_rows, int row_length) const {
    for (int j = 0; j < n_rows; ++j) {
      std::copy(data + static_cast<size_t>(j) * row_length,
                data + static_cast<size_t>(j + 1) * row_length, x_real_.begin());
      fft_.fwd(x_half_.data(), x_real_.data(), lx_);
      for (int kx = 0; kx < hx_; ++kx) rows_[static_cast<size_t>(kx) * ls_ + j] = x_half_[kx];
    }
  }

  int nx_, ns_, lx_, hx_, ls_;
  double diagonal_ = 0.0;
  std::vector<double> spectrum_;          // [hx_ * ls_], bin-major, scaled by 1/(lx_ ls_)
  std::vector<double> inverse_spectrum_;  // [hx_ * ls_], 1 / max(spectrum, floor), scaled

  // Scratch reused by every Apply (hence mutable): the operator is not safe for concurrent
  // Apply calls from several threads; give each thread its own operator.
  mutable Eigen::FFT<double> fft_;
  mutable std::vector<double> x_real_;    // [lx_], entries >= row length stay zero
  mutable std::vector<double> x_out_;     // [lx_]
  mutable std::vector<Complex> x_half_;   // [hx_]
  mutable std::vector<Complex> rows_;     // [hx_ * ls_]
  mutable std::vector<Complex> s_line_;   // [ls_]
  mutable std::vector<Complex> s_out_;    // [ls_]
  mutable std::vector<Complex> cropped_;  // [ns_ * hx_], s-major for the inverse x FFTs
};

// ---------------------------------------------------------------------------------------------
// Curved grid: C depends on (i_x - j_x, i_s, j_s), even in the x offset. FFT along x, one real
// ns x ns matrix per x frequency k = 0 .. lx/2.
class CurvedFftOperator final : public InfluenceOperator {
 public:
  CurvedFftOperator(const PatchGrid& grid, const internal::KernelCoefficients& coefficients)
      : nx_(grid.nx),
        ns_(grid.ns),
        lx_(RealFftSize(grid.nx)),
        hx_(lx_ / 2 + 1),
        diagonal_(grid.ns),
        fft_(MakeFft()),
        x_real_(lx_, 0.0),
        x_out_(lx_, 0.0),
        x_half_(hx_),
        p_hat_(grid.ns, 2 * hx_),
        u_hat_(grid.ns, 2 * hx_) {
    // Kernel on x offsets d >= 0 (nx * ns^2 evaluations): values(js * ns + is, d).
    const int pairs = ns_ * ns_;
    Eigen::MatrixXd values(pairs, nx_);
    for (int d = 0; d < nx_; ++d) {
      for (int js = 0; js < ns_; ++js) {
        for (int is = 0; is < ns_; ++is) {
          values(js * ns_ + is, d) = internal::CellInfluence(grid, coefficients, d, is, 0, js);
        }
      }
    }
    for (int j = 0; j < ns_; ++j) diagonal_[j] = values(j * ns_ + j, 0);
    // Spectrum of the even extension: K_k = sum_d w_d c(d) cos(2 pi k d / lx), w_0 = 1 and
    // w_d = 2, with the unscaled inverse FFT's 1/lx folded in. One product for all pairs;
    // column k of kernel_ is K_k stored column-major (ns x ns).
    Eigen::MatrixXd cosines(nx_, hx_);
    for (int d = 0; d < nx_; ++d) {
      const double w = (d == 0 ? 1.0 : 2.0) / lx_;
      for (int k = 0; k < hx_; ++k) {
        const long phase = (static_cast<long>(k) * d) % lx_;  // exact argument reduction
        cosines(d, k) = w * std::cos(2.0 * std::numbers::pi * phase / lx_);
      }
    }
    kernel_.noalias() = values * cosines;
    MakeInverseBlocks();
    // Build the FFT plans now, so Apply does not allocate.
    fft_.fwd(x_half_.data(), x_real_.data(), lx_);
    fft_.inv(x_out_.data(), x_half_.data(), lx_);
  }

  int size() const override { return nx_ * ns_; }
  double Diagonal(int k) const override { return diagonal_[k / nx_]; }

  void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) const override {
    Convolve(p, /*inverse=*/false, u);
  }

  // Per frequency, a solve with the symmetric part of K_k: the exact inverse of the
  // x-circulant embedding when C is symmetric.
  bool ApplyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd* z) const override {
    Convolve(r, /*inverse=*/true, z);
    return true;
  }

 private:
  // factor_ column k = the Cholesky factor L_k of sym K_k = (K_k + K_k^T) / 2 [m/Pa] (lower
  // triangle of an ns x ns column-major block). Factors rather than inverses: a third of the
  // flops to build (ns^3 / 3 per frequency), which matters on laterally long patches (ns of a
  // few hundred), for about 1.5 times the cost to apply (measured at ns = 45 and 90). A block whose
  // symmetric part is not positive definite (Cholesky fails) is rebuilt from its eigenvalues, those
  // below kSpectrumFloor * min_j C_jj raised to it, and factored again.
  void MakeInverseBlocks() {
    factor_.resize(kernel_.rows(), kernel_.cols());
    const double floor = kSpectrumFloor * diagonal_.minCoeff();
    Eigen::MatrixXd sym(ns_, ns_);
    Eigen::LLT<Eigen::MatrixXd> llt(ns_);
    for (int k = 0; k < hx_; ++k) {
      const Eigen::Map<const Eigen::MatrixXd> k_k(kernel_.col(k).data(), ns_, ns_);
      sym = (0.5 * lx_) * (k_k + k_k.transpose());  // kernel_ holds K_k / lx
      llt.compute(sym);
      if (llt.info() != Eigen::Success) {
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sym);
        RAILWEAR_CHECK(eig.info() == Eigen::Success);
        const Eigen::VectorXd lambda = eig.eigenvalues().cwiseMax(floor);
        sym = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
        llt.compute(sym);
        RAILWEAR_CHECK(llt.info() == Eigen::Success);
      }
      Eigen::Map<Eigen::MatrixXd>(factor_.col(k).data(), ns_, ns_) = llt.matrixLLT();
    }
  }

  // out = crop_x(IFFT_x(B_k FFT_x(pad_x(in)))) with B_k = K_k (inverse = false) or
  // (sym K_k)^-1 (inverse = true) per x frequency k.
  void Convolve(const Eigen::VectorXd& p, bool inverse, Eigen::VectorXd* u) const {
    RAILWEAR_CHECK(p.size() == size());
    for (int j = 0; j < ns_; ++j) {
      std::copy(p.data() + static_cast<size_t>(j) * nx_,
                p.data() + static_cast<size_t>(j + 1) * nx_, x_real_.begin());
      fft_.fwd(x_half_.data(), x_real_.data(), lx_);
      for (int k = 0; k < hx_; ++k) {
        p_hat_(j, 2 * k) = x_half_[k].real();
        p_hat_(j, 2 * k + 1) = x_half_[k].imag();
      }
    }
    if (inverse) {
      // L L^T z = p / lx (the unscaled inverse FFT's factor), both columns at once.
      u_hat_ = p_hat_ * (1.0 / lx_);
      for (int k = 0; k < hx_; ++k) {
        const Eigen::Map<const Eigen::MatrixXd> l_k(factor_.col(k).data(), ns_, ns_);
        auto z_k = u_hat_.middleCols<2>(2 * k);
        l_k.triangularView<Eigen::Lower>().solveInPlace(z_k);
        l_k.transpose().triangularView<Eigen::Upper>().solveInPlace(z_k);
      }
    } else {
      for (int k = 0; k < hx_; ++k) {
        const Eigen::Map<const Eigen::MatrixXd> k_k(kernel_.col(k).data(), ns_, ns_);
        u_hat_.middleCols<2>(2 * k).noalias() = k_k * p_hat_.middleCols<2>(2 * k);
      }
    }
    if (u->size() != size()) u->resize(size());
    for (int j = 0; j < ns_; ++j) {
      for (int k = 0; k < hx_; ++k) x_half_[k] = Complex(u_hat_(j, 2 * k), u_hat_(j, 2 * k + 1));
      fft_.inv(x_out_.data(), x_half_.data(), lx_);
      std::copy(x_out_.begin(), x_out_.begin() + nx_, u->data() + static_cast<size_t>(j) * nx_);
    }
  }

  int nx_, ns_, lx_, hx_;
  Eigen::VectorXd diagonal_;  // [ns], C_kk depends on the s index only
  Eigen::MatrixXd kernel_;    // [ns^2 x hx_]: column k is K_k (ns x ns, column-major)
  Eigen::MatrixXd factor_;    // [ns^2 x hx_]: column k is L_k, sym K_k = L_k L_k^T [m/Pa]

  // Scratch reused by every Apply (hence mutable): not safe for concurrent Apply calls.
  mutable Eigen::FFT<double> fft_;
  mutable std::vector<double> x_real_;   // [lx_], entries >= nx_ stay zero
  mutable std::vector<double> x_out_;    // [lx_]
  mutable std::vector<Complex> x_half_;  // [hx_]
  mutable Eigen::MatrixXd p_hat_;        // [ns x 2 hx_]: (real, imag) column pair per bin
  mutable Eigen::MatrixXd u_hat_;        // [ns x 2 hx_]
};

}  // namespace

std::unique_ptr<InfluenceOperator> MakeInfluenceOperator(const PatchGrid& grid,
                                                         const InfluenceSettings& settings) {
  internal::CheckGrid(grid);
  const internal::KernelCoefficients coefficients = internal::MakeKernelCoefficients(settings);
  if (grid.planar) return std::make_unique<PlanarFftOperator>(grid, coefficients);
  return std::make_unique<CurvedFftOperator>(grid, coefficients);
}

double EstimateOperatorBytes(int nx, int ns, bool planar) {
  const double n_x = nx, n_s = ns;
  const double doubles = planar ? 8.0 * (2.0 * n_x) * (2.0 * n_s) : 2.0 * (n_x + 1.0) * n_s * n_s;
  return doubles * sizeof(double);
}

}  // namespace railwear
