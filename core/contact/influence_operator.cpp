// Fast influence operators: FFT convolution on the grid's Toeplitz structure (see
// influence_operator.h). The dense reference lives in influence_kernels.cpp.
//
// Both operators embed the Toeplitz matrix in a circulant one of length L >= 2n - 1 per
// Toeplitz direction (zero padding), so the products are exact linear convolutions, not
// periodic ones. The kernels are even in their Toeplitz offsets, so their spectra are real.
// FFTs use FFTW (core/numerics/fftw.h): plans made once per operator with FFTW_ESTIMATE (bit-
// reproducible run to run) and executed on the operator's own buffers, real-input transforms
// with the half spectrum, lengths 2^a 3^b 5^c 7^d (core/numerics/fft_size.h), even for the
// real transforms.
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "core/contact/influence_kernels.h"
#include "core/numerics/check.h"
#include "core/numerics/factored_solve.h"
#include "core/numerics/fft_size.h"
#include "core/numerics/fftw.h"
#include "core/numerics/pooled_buffer.h"

namespace railwear {

const int kDenseProductMaxCells = 121;

namespace {

using Complex = internal::FftwComplex;

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

// u = C p with the dense matrix C [N x N] (OperatorProducts::kDense).
void DenseProduct(const Eigen::MatrixXd& c, const Eigen::VectorXd& p, Eigen::VectorXd* u) {
  RAILWEAR_CHECK(p.size() == c.cols());
  u->noalias() = c * p;
}

void CheckPlanarGrid(const PatchGrid& grid) {
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d expected = grid.point_yz_m[0] + (j * grid.ds_m) * grid.tangent_yz[0];
    RAILWEAR_CHECK((grid.point_yz_m[j] - expected).norm() <= kPlanarGridTolerance * grid.ds_m);
    RAILWEAR_CHECK((grid.tangent_yz[j] - grid.tangent_yz[0]).norm() <= kPlanarGridTolerance);
    RAILWEAR_CHECK((grid.normal_yz[j] - grid.normal_yz[0]).norm() <= kPlanarGridTolerance);
  }
}

// ---------------------------------------------------------------------------------------------
// Planar grid or uniform arc (IsUniformArc): C depends on |i_x - j_x| and |i_s - j_s|. 2-D
// linear convolution by FFT (PaddedFft2d: real FFTs along x, complex along s, half spectrum
// stored x-major [kx * ls + ks]).
class ToeplitzXsFftOperator final : public InfluenceOperator {
 public:
  // The caller has checked that the grid is planar (grid.planar: checked here) or a uniform arc.
  ToeplitzXsFftOperator(const PatchGrid& grid, const internal::KernelCoefficients& coefficients,
                        bool dense_products)
      : nx_(grid.nx), ns_(grid.ns), fft_(grid.nx, grid.ns), work_(fft_.NewSpectrum()) {
    if (grid.planar) CheckPlanarGrid(grid);
    const int lx = fft_.lx(), ls = fft_.ls();
    // Kernel on offsets d >= 0, e >= 0 (nx * ns evaluations; on an arc from the frame of row 0,
    // which every row shares up to a rotation), even extension into an lx by ls circulant
    // generator (x fastest).
    std::vector<double> generator(static_cast<size_t>(lx) * ls, 0.0);
    std::vector<double> row(nx_);
    std::vector<double> kernel(static_cast<size_t>(nx_) * ns_);
    for (int e = 0; e < ns_; ++e) {
      internal::CellInfluenceRow(grid, coefficients, e, 0, row.data());
      std::copy(row.begin(), row.end(), kernel.begin() + static_cast<size_t>(e) * nx_);
      for (int d = 0; d < nx_; ++d) {
        const double c = row[d];
        if (d == 0 && e == 0) diagonal_ = c;
        for (int ee : {e, (ls - e) % ls}) {
          for (int dd : {d, (lx - d) % lx}) generator[static_cast<size_t>(ee) * lx + dd] = c;
        }
      }
    }
    // Even generator -> real spectrum; the inverse FFTs are unscaled, so fold in 1/(lx ls).
    fft_.ForwardGenerator(generator.data(), work_.data());
    const double scale = 1.0 / (static_cast<double>(lx) * ls);
    spectrum_.resize(fft_.spectrum_size());
    for (size_t k = 0; k < spectrum_.size(); ++k) spectrum_[k] = work_[k].real() * scale;
    // The preconditioner (docs/speed.md, "A preconditioner on the grid's own period"): the
    // inverse of the circulant of period px >= nx by ps >= ns (the shortest fast lengths, not
    // the products' 2n - 1) whose generator is the kernel at the offsets |d| <= px / 2,
    // |e| <= ps / 2, wrapped (Strang's circulant of the Toeplitz matrix). A quarter of the
    // products' bins, with the same iteration counts on CONTACT's perfc cases to +-1.
    const int px = internal::NextFftSize(nx_, 2), ps = internal::NextFftSize(ns_, 1);
    preconditioner_fft_.emplace(nx_, ns_, px, ps);
    std::vector<double> wrapped(static_cast<size_t>(px) * ps, 0.0);
    for (int e = 0; e <= std::min(ps / 2, ns_ - 1); ++e) {
      for (int d = 0; d <= std::min(px / 2, nx_ - 1); ++d) {
        const double c = kernel[static_cast<size_t>(e) * nx_ + d];
        for (int ee : {e, (ps - e) % ps}) {
          for (int dd : {d, (px - d) % px}) wrapped[static_cast<size_t>(ee) * px + dd] = c;
        }
      }
    }
    preconditioner_work_ = preconditioner_fft_->NewSpectrum();
    preconditioner_fft_->ForwardGenerator(wrapped.data(), preconditioner_work_.data());
    // 1 / symbol, the symbol raised to the floor first, times 1/(px ps) for the unscaled
    // inverse FFT.
    const double floor = kSpectrumFloor * diagonal_;
    const double pc_scale = 1.0 / (static_cast<double>(px) * ps);
    inverse_spectrum_.resize(preconditioner_fft_->spectrum_size());
    for (size_t k = 0; k < inverse_spectrum_.size(); ++k) {
      const double symbol = preconditioner_work_[k].real();  // the circulant's eigenvalue [m/Pa]
      inverse_spectrum_[k] = pc_scale / std::max(symbol, floor);
    }
    if (dense_products) {
      dense_.resize(size(), size());
      for (int js = 0; js < ns_; ++js) {
        for (int jx = 0; jx < nx_; ++jx) {
          for (int is = 0; is < ns_; ++is) {
            const double* c = generator.data() + static_cast<size_t>(std::abs(is - js)) * lx;
            for (int ix = 0; ix < nx_; ++ix) {
              dense_(is * nx_ + ix, js * nx_ + jx) = c[std::abs(ix - jx)];
            }
          }
        }
      }
    }
  }

  int size() const override { return nx_ * ns_; }
  double Diagonal(int) const override { return diagonal_; }

  void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) const override {
    if (dense_.size() > 0) return DenseProduct(dense_, p, u);
    Convolve(fft_, p, spectrum_, &work_, u);
  }

  // z = crop(IFFT(FFT(pad(r)) / S^)) on the px by ps period: Strang's circulant S of the
  // Toeplitz matrix (the constructor), inverted exactly. Until 2026-11-29 the inverse of the
  // products' own 2n - 1 embedding, cropped: 4 times the bins for the same iterations to +-1
  // (docs/speed.md).
  bool HasPreconditioner() const override { return true; }
  bool ApplyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd* z) const override {
    Convolve(*preconditioner_fft_, r, inverse_spectrum_, &preconditioner_work_, z);
    return true;
  }

 private:
  // out = crop(IFFT2(FFT2(pad(in)) * multiplier)); multiplier [hx * ls], x-major, with the
  // inverse FFTs' scaling folded in.
  void Convolve(const internal::PaddedFft2d& fft, const Eigen::VectorXd& in,
                const std::vector<double>& multiplier, internal::FftwBuffer<Complex>* work,
                Eigen::VectorXd* out) const {
    RAILWEAR_CHECK(in.size() == size());
    fft.Forward(in.data(), work->data());
    for (size_t k = 0; k < multiplier.size(); ++k) (*work)[k] *= multiplier[k];
    if (out->size() != size()) out->resize(size());
    fft.Inverse(work->data(), out->data());
  }

  int nx_, ns_;
  double diagonal_ = 0.0;
  std::vector<double> spectrum_;          // [hx * ls], x-major, scaled by 1/(lx ls)
  std::vector<double> inverse_spectrum_;  // [(px / 2 + 1) * ps], 1 / max(S^, floor), scaled
  Eigen::MatrixXd dense_;                 // [N x N] for dense products, else empty [m/Pa]

  // Scratch reused by every Apply (hence mutable): the operator is not safe for concurrent
  // Apply calls from several threads; give each thread its own operator.
  internal::PaddedFft2d fft_;
  mutable internal::FftwBuffer<Complex> work_;  // [hx * ls]
  // The preconditioner's transforms on the px by ps period and their scratch (the same rules).
  std::optional<internal::PaddedFft2d> preconditioner_fft_;
  mutable internal::FftwBuffer<Complex> preconditioner_work_;  // [(px / 2 + 1) * ps]
};

// ---------------------------------------------------------------------------------------------
// Curved grid: C depends on (i_x - j_x, i_s, j_s), even in the x offset. FFT along x, one real
// ns x ns matrix per x frequency k = 0 .. lx/2.
//
// The x transforms are batched over the ns rows and write (read) their spectra straight into
// (from) the ns x 2 hx matrices the per-frequency blocks multiply: FFTW's split-complex guru
// interface puts bin k's real parts in column 2k and its imaginary parts in column 2k + 1, so
// there is no transpose and no copy between transforms and products.
class CurvedFftOperator final : public InfluenceOperator {
 public:
  CurvedFftOperator(const PatchGrid& grid, const internal::KernelCoefficients& coefficients,
                    bool dense_products)
      : nx_(grid.nx),
        ns_(grid.ns),
        lx_(internal::RealFftSize(grid.nx)),
        hx_(lx_ / 2 + 1),
        diagonal_(grid.ns),
        padded_in_(static_cast<size_t>(ns_) * lx_),
        padded_out_(static_cast<size_t>(ns_) * lx_),
        p_hat_(static_cast<size_t>(ns_) * 2 * hx_),
        u_hat_(static_cast<size_t>(ns_) * 2 * hx_),
        odd_scratch_(static_cast<size_t>(2 * ns_)) {
    // Kernel on x offsets d >= 0 (nx * ns^2 values, a row of offsets per pair of s indices:
    // CellInfluenceRow): values(js * ns + is, d).
    const int pairs = ns_ * ns_;
    // (the three large matrices on recycled memory, pooled_buffer.h: fresh pages cost a fifth
    // of a cold gauge-corner call)
    PooledBuffer values_memory(static_cast<size_t>(pairs) * nx_);
    Eigen::Map<Eigen::MatrixXd, Eigen::Aligned16> values(values_memory.data(), pairs, nx_);
    std::vector<double> row(nx_);
    for (int js = 0; js < ns_; ++js) {
      for (int is = 0; is < ns_; ++is) {
        internal::CellInfluenceRow(grid, coefficients, is, js, row.data());
        for (int d = 0; d < nx_; ++d) values(js * ns_ + is, d) = row[d];
      }
    }
    for (int j = 0; j < ns_; ++j) diagonal_[j] = values(j * ns_ + j, 0);
    if (dense_products) {
      dense_.resize(size(), size());
      for (int js = 0; js < ns_; ++js) {
        for (int jx = 0; jx < nx_; ++jx) {
          for (int is = 0; is < ns_; ++is) {
            for (int ix = 0; ix < nx_; ++ix) {
              dense_(is * nx_ + ix, js * nx_ + jx) = values(js * ns_ + is, std::abs(ix - jx));
            }
          }
        }
      }
    }
    // Spectrum of the even extension: K_k = sum_d w_d c(d) cos(2 pi k d / lx), w_0 = 1 and
    // w_d = 2, with the unscaled inverse FFT's 1/lx folded in. One product for all pairs;
    // column k of kernel() is K_k stored column-major (ns x ns).
    Eigen::MatrixXd cosines(nx_, hx_);
    for (int d = 0; d < nx_; ++d) {
      const double w = (d == 0 ? 1.0 : 2.0) / lx_;
      for (int k = 0; k < hx_; ++k) {
        const long phase = (static_cast<long>(k) * d) % lx_;  // exact argument reduction
        cosines(d, k) = w * std::cos(2.0 * std::numbers::pi * phase / lx_);
      }
    }
    kernel_memory_ = PooledBuffer(static_cast<size_t>(pairs) * hx_);
    kernel().noalias() = values * cosines;
    MakeInverseBlocks();
    // Row j of the padded field (x fastest, stride lx) <-> bin k of row j at (j, 2k) and
    // (j, 2k + 1) of the column-major ns x 2 hx spectrum matrices.
    const fftw_iodim forward_dims{lx_, 1, 2 * ns_}, forward_rows{ns_, lx_, 1};
    const fftw_iodim inverse_dims{lx_, 2 * ns_, 1}, inverse_rows{ns_, 1, lx_};
    // Shared plans (core/numerics/fftw.h), described by the kind and lx, ns (every dimension
    // and stride above, and the split arrays' offset ns, follow from them).
    forward_ = internal::SharedPlan({6, lx_, ns_}, [&] {
      return fftw_plan_guru_split_dft_r2c(1, &forward_dims, 1, &forward_rows, padded_in_.data(),
                                          p_hat_.data(), p_hat_.data() + ns_, FFTW_ESTIMATE);
    });
    inverse_ = internal::SharedPlan({7, lx_, ns_}, [&] {
      return fftw_plan_guru_split_dft_c2r(1, &inverse_dims, 1, &inverse_rows, u_hat_.data(),
                                          u_hat_.data() + ns_, padded_out_.data(), FFTW_ESTIMATE);
    });
  }

  int size() const override { return nx_ * ns_; }
  double Diagonal(int k) const override { return diagonal_[k / nx_]; }

  void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) const override {
    if (dense_.size() > 0) return DenseProduct(dense_, p, u);
    Convolve(p, /*inverse=*/false, u);
  }

  // Per frequency, a solve with the symmetric part of K_k: the exact inverse of the
  // x-circulant embedding when C is symmetric.
  bool HasPreconditioner() const override { return true; }
  bool ApplyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd* z) const override {
    Convolve(r, /*inverse=*/true, z);
    return true;
  }

 private:
  // factor column k = the Cholesky factor L_k of sym K_k = (K_k + K_k^T) / 2 [m/Pa] (lower
  // triangle of an ns x ns column-major block, its diagonal as reciprocals 1 / L_jj and L_k^T
  // above it: internal::PrepareFactor). Factors rather than inverses: a third of the
  // flops to build (ns^3 / 3 per frequency), which matters on laterally long patches (ns of a
  // few hundred), for about 1.5 times the cost to apply (measured at ns = 45 and 90). A block whose
  // symmetric part is not positive definite (Cholesky fails) is rebuilt from its eigenvalues, those
  // below kSpectrumFloor * min_j C_jj raised to it, and factored again.
  void MakeInverseBlocks() {
    factor_memory_ = PooledBuffer(kernel_memory_.size());
    const double floor = kSpectrumFloor * diagonal_.minCoeff();
    Eigen::MatrixXd sym(ns_, ns_);
    Eigen::LLT<Eigen::MatrixXd> llt(ns_);
    for (int k = 0; k < hx_; ++k) {
      const Eigen::Map<const Eigen::MatrixXd> k_k(KernelBlock(k), ns_, ns_);
      sym = (0.5 * lx_) * (k_k + k_k.transpose());  // kernel() holds K_k / lx
      llt.compute(sym);
      if (llt.info() != Eigen::Success) {
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sym);
        RAILWEAR_CHECK(eig.info() == Eigen::Success);
        const Eigen::VectorXd lambda = eig.eigenvalues().cwiseMax(floor);
        sym = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
        llt.compute(sym);
        RAILWEAR_CHECK(llt.info() == Eigen::Success);
      }
      Eigen::Map<Eigen::MatrixXd>(FactorBlock(k), ns_, ns_) = llt.matrixLLT();
      internal::PrepareFactor(ns_, FactorBlock(k));  // (for SolveFactoredPair)
    }
  }

  // out = crop_x(IFFT_x(B_k FFT_x(pad_x(in)))) with B_k = K_k (inverse = false) or
  // (sym K_k)^-1 (inverse = true) per x frequency k (core/numerics/factored_solve.h): Apply
  // multiplies each block with the real and the imaginary column in one pass over the block
  // (internal::MultiplyBlockTwoColumns; until issue 20 two Eigen matrix-vector products, as
  // Eigen treats a 2-column right-hand side as a matrix product and repacks the whole block on
  // every call, gemm_pack_lhs, issue 18), the preconditioner solves two frequencies at a time
  // (internal::SolveFactoredPair).
  void Convolve(const Eigen::VectorXd& p, bool inverse, Eigen::VectorXd* u) const {
    RAILWEAR_CHECK(p.size() == size());
    for (int j = 0; j < ns_; ++j) {
      std::copy(p.data() + static_cast<size_t>(j) * nx_,
                p.data() + static_cast<size_t>(j + 1) * nx_,
                padded_in_.data() + static_cast<size_t>(j) * lx_);
    }
    fftw_execute_split_dft_r2c(forward_->get(), padded_in_.data(), p_hat_.data(),
                               p_hat_.data() + ns_);
    const Eigen::Map<const Eigen::MatrixXd> p_hat(p_hat_.data(), ns_, 2 * hx_);
    Eigen::Map<Eigen::MatrixXd> u_hat(u_hat_.data(), ns_, 2 * hx_);
    if (inverse) {
      // L L^T z = p / lx (the unscaled inverse FFT's factor), both columns at once.
      u_hat = p_hat * (1.0 / lx_);
      auto column = [&](int c) { return u_hat_.data() + static_cast<size_t>(c) * ns_; };
      int k = 0;
      for (; k + 1 < hx_; k += 2) {
        internal::SolveFactoredPair(ns_, FactorBlock(k), FactorBlock(k + 1), column(2 * k),
                                    column(2 * k + 1), column(2 * k + 2), column(2 * k + 3));
      }
      if (k < hx_) {
        // The last frequency of an odd count, paired with a zero right-hand side on the same
        // factor (its chains cost no more than the frequency's own; the zeros are discarded).
        std::fill(odd_scratch_.begin(), odd_scratch_.end(), 0.0);
        internal::SolveFactoredPair(ns_, FactorBlock(k), FactorBlock(k), column(2 * k),
                                    column(2 * k + 1), odd_scratch_.data(),
                                    odd_scratch_.data() + ns_);
      }
    } else {
      for (int k = 0; k < hx_; ++k) {
        internal::MultiplyBlockTwoColumns(ns_, KernelBlock(k), p_hat.col(2 * k).data(),
                                          p_hat.col(2 * k + 1).data(), u_hat.col(2 * k).data(),
                                          u_hat.col(2 * k + 1).data());
      }
    }
    fftw_execute_split_dft_c2r(inverse_->get(), u_hat_.data(), u_hat_.data() + ns_,
                               padded_out_.data());  // overwrites u_hat_
    if (u->size() != size()) u->resize(size());
    for (int j = 0; j < ns_; ++j) {
      const double* row = padded_out_.data() + static_cast<size_t>(j) * lx_;
      std::copy(row, row + nx_, u->data() + static_cast<size_t>(j) * nx_);
    }
  }

  int nx_, ns_, lx_, hx_;
  Eigen::VectorXd diagonal_;  // [ns], C_kk depends on the s index only
  // kernel [ns^2 x hx_]: column k is K_k (ns x ns, column-major); factor [ns^2 x hx_]: column
  // k is L_k, sym K_k = L_k L_k^T [m/Pa]. Column-major on recycled memory (pooled_buffer.h).
  PooledBuffer kernel_memory_, factor_memory_;
  Eigen::Map<Eigen::MatrixXd, Eigen::Aligned16> kernel() {
    return {kernel_memory_.data(), static_cast<Eigen::Index>(ns_) * ns_, hx_};
  }
  const double* KernelBlock(int k) const {
    return kernel_memory_.data() + static_cast<size_t>(k) * ns_ * ns_;
  }
  double* FactorBlock(int k) { return factor_memory_.data() + static_cast<size_t>(k) * ns_ * ns_; }
  const double* FactorBlock(int k) const {
    return factor_memory_.data() + static_cast<size_t>(k) * ns_ * ns_;
  }
  Eigen::MatrixXd dense_;     // [N x N] for dense products, else empty [m/Pa]

  // Scratch reused by every Apply (hence mutable): not safe for concurrent Apply calls.
  mutable internal::FftwBuffer<double> padded_in_;   // [ns * lx], x entries >= nx stay zero
  mutable internal::FftwBuffer<double> padded_out_;  // [ns * lx]
  mutable internal::FftwBuffer<double> p_hat_;  // [ns x 2 hx_] column-major: (real, imag) per bin
  mutable internal::FftwBuffer<double> u_hat_;  // [ns x 2 hx_]
  mutable std::vector<double> odd_scratch_;     // [2 ns]: an odd hx_'s pair (SolveFactoredPair)
  internal::SharedFftwPlan forward_;            // padded_in_ -> p_hat_
  internal::SharedFftwPlan inverse_;            // u_hat_ -> padded_out_ (overwrites u_hat_)
};

}  // namespace

std::unique_ptr<InfluenceOperator> MakeInfluenceOperator(const PatchGrid& grid,
                                                         const InfluenceSettings& settings,
                                                         OperatorProducts products,
                                                         SectionStructure structure) {
  internal::CheckGrid(grid);
  const internal::KernelCoefficients coefficients = internal::MakeKernelCoefficients(settings);
  const bool dense = products == OperatorProducts::kDense ||
                     (products == OperatorProducts::kAuto && grid.cells() <= kDenseProductMaxCells);
  if (ChooseSectionStructure(grid, structure) == SectionStructure::kToeplitzXs) {
    return std::make_unique<ToeplitzXsFftOperator>(grid, coefficients, dense);
  }
  return std::make_unique<CurvedFftOperator>(grid, coefficients, dense);
}

SectionStructure ChooseSectionStructure(const PatchGrid& grid, SectionStructure requested) {
  switch (requested) {
    case SectionStructure::kBlocks:
      return SectionStructure::kBlocks;
    case SectionStructure::kToeplitzXs:
      RAILWEAR_CHECK(grid.planar || IsUniformArc(grid));
      return SectionStructure::kToeplitzXs;
    case SectionStructure::kAuto:
      break;
  }
  // One row is a uniform arc of any curvature: the patch builder makes such grids (a barely
  // touching patch, a cropped one), and their 1 x 1 blocks have no structure along s to use.
  // They keep the blocks, so every grid the patch builder makes takes the path it took before.
  const bool arc = grid.ns >= 2 && IsUniformArc(grid);
  return grid.planar || arc ? SectionStructure::kToeplitzXs : SectionStructure::kBlocks;
}

double EstimateOperatorBytes(int nx, int ns, bool planar) {
  const double n_x = nx, n_s = ns;
  double doubles = planar ? 8.0 * (2.0 * n_x) * (2.0 * n_s) : 2.0 * (n_x + 1.0) * n_s * n_s;
  if (!planar) {
    // The curved operator's cosine table, nx x (lx / 2 + 1), a temporary of its construction:
    // negligible on the presets' grids, but an explicit cell_mm of 1 um along x made it 3 GB of
    // a 19 000-column grid whose ns^2 part was small (issue 17). lx is within 25 % of 2 nx.
    const double hx = nx < (1 << 28) ? internal::RealFftSize(nx) / 2 + 1.0 : 1.25 * n_x + 1.0;
    doubles += n_x * hx;
  }
  // In doubles: the grid builder asks about sizes whose nx * ns overflows an int (issue 17).
  if (n_x * n_s <= kDenseProductMaxCells) doubles += (n_x * n_s) * (n_x * n_s);  // kAuto's matrix
  return doubles * sizeof(double);
}

}  // namespace railwear
