// Exact steady-rolling tangential solver: Cerruti cell kernels, the rolling operator B (FFT and
// dense), and Kalker's block Gauss-Seidel with the exact local problem. See tangential_exact.h.
#include "core/contact/tangential_exact.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include <Eigen/Cholesky>

#include "core/contact/influence_operator.h"
#include "core/numerics/check.h"
#include "core/numerics/fft_size.h"
#include "core/numerics/fftw.h"
#include "core/numerics/input_error.h"
#include "core/numerics/target_clones.h"

namespace railwear {

// Measured (tangential_exact_bench's BM_TangentialExactSmallPatch, CPU, medians of 3 on a
// loaded machine; docs/speed.md): the loaded cells' matrix against the FFT products takes 0.71,
// 0.83, 0.59, 0.69, 0.71, 0.82 of the time at 37, 69, 97, 137, 177, 225 loaded cells and 1.40 at
// 349 (its 2m x 2m matrix, 3.9 MB, no longer fits a 2 MB L2 cache). 200 keeps the matrix at
// 1.3 MB.
const int kLoadedDenseMaxCells = 200;
// The exact solver's default stopping tolerance (relative to mu p_max, ExactTangentialOptions):
// 1e-6 keeps the forces' 4 significant digits with a wide margin (issue 18 point 4). Measured
// against 1e-9 (contact_reference_bench, docs/speed.md): F_x, F_y / (mu F_n) and M_z /
// (mu F_n c) within 1e-6 on every case of CONTACT's 3,220-case creep table (11 x 11 cells),
// within 1e-8 on tang_problm_1c / 2c, at 0.61-0.68 of the time; 1e-5 moved the table by 3e-6.
// Tests that compare tractions with a reference to more digits ask for 1e-9 themselves.
const double kDefaultExactTangentialTolerance = 1e-6;

namespace internal {
namespace {

// xi * asinh(eta / |xi|) with its limit 0 at xi = 0.
double XiAsinh(double xi, double eta) {
  if (xi == 0.0) return 0.0;
  return xi * std::asinh(eta / std::abs(xi));
}

// Sum over the four corners (X, S) of the rectangle in field-minus-source offsets, signs + - - +.
template <typename F>
double CornerSum(double x, double s, double hx, double hs, F f) {
  const double xs[2] = {x - 0.5 * hx, x + 0.5 * hx};
  const double ss[2] = {s - 0.5 * hs, s + 0.5 * hs};
  double sum = 0.0;
  for (int ix = 0; ix < 2; ++ix) {
    for (int is = 0; is < 2; ++is) sum += ((ix == is) ? 1.0 : -1.0) * f(xs[ix], ss[is]);
  }
  return sum;
}

void CheckMaterial(const Material& m, const char* which) {
  if (!(m.youngs_modulus_Pa > 0.0) || !(m.poisson_ratio >= 0.0 && m.poisson_ratio < 0.5)) {
    std::ostringstream msg;
    msg << "tangential exact: " << which << " material has E = " << m.youngs_modulus_Pa
        << " Pa and nu = " << m.poisson_ratio << "; expected E > 0 and 0 <= nu < 0.5";
    throw InputError(msg.str());
  }
}

}  // namespace

// Antiderivatives F with d2F/dXdS = integrand:
//   X^2/R^3: S asinh(X/|S|);  S^2/R^3: X asinh(S/|X|);  X S/R^3: -R.
double RectangleIntegralX2R3(double x, double s, double hx, double hs) {
  return CornerSum(x, s, hx, hs, [](double X, double S) { return XiAsinh(S, X); });
}
double RectangleIntegralS2R3(double x, double s, double hx, double hs) {
  return CornerSum(x, s, hx, hs, [](double X, double S) { return XiAsinh(X, S); });
}
double RectangleIntegralXSR3(double x, double s, double hx, double hs) {
  return CornerSum(x, s, hx, hs, [](double X, double S) { return -std::hypot(X, S); });
}

CerrutiCoefficients MakeCerrutiCoefficients(const Material& wheel, const Material& rail) {
  CheckMaterial(wheel, "wheel");
  CheckMaterial(rail, "rail");
  CerrutiCoefficients c;
  for (const Material* m : {&wheel, &rail}) {
    const double g = m->ShearModulus();
    c.inv_r += (1.0 - m->poisson_ratio) / (2.0 * std::numbers::pi * g);
    c.quad += m->poisson_ratio / (2.0 * std::numbers::pi * g);
  }
  return c;
}

TangentialBlock CerrutiCellInfluence(const CerrutiCoefficients& c, double x, double s, double hx,
                                     double hs) {
  // int 1/R = int X^2/R^3 + int S^2/R^3 in the plane, so one pair of integrals gives all three.
  const double x2 = RectangleIntegralX2R3(x, s, hx, hs);
  const double s2 = RectangleIntegralS2R3(x, s, hx, hs);
  const double inv_r = x2 + s2;
  TangentialBlock b;
  b.xx = c.inv_r * inv_r + c.quad * x2;
  b.ss = c.inv_r * inv_r + c.quad * s2;
  b.xs = c.quad * RectangleIntegralXSR3(x, s, hx, hs);
  return b;
}

}  // namespace internal

std::string ExactTangentialOptions::Validate() const {
  std::ostringstream msg;
  if (!(tolerance > 0.0)) msg << "tolerance = " << tolerance << ", expected > 0; ";
  if (!(relaxation > 0.0 && relaxation <= 1.0)) {
    msg << "relaxation = " << relaxation << ", expected in (0, 1]; ";
  }
  if (block_columns < 0) msg << "block_columns = " << block_columns << ", expected >= 0; ";
  if (max_iterations < 1) msg << "max_iterations = " << max_iterations << ", expected >= 1; ";
  if (anderson_depth < 0) msg << "anderson_depth = " << anderson_depth << ", expected >= 0; ";
  return msg.str();
}

namespace {

using Complex = std::complex<double>;
using internal::TangentialBlock;

// Residual growth (relative to the best residual so far) taken as a sign that the relaxed sweep
// does not contract; the relaxation is then halved. A converging run stays well below it: the
// residual of a contracting sweep may rise a little while the slip area settles.
constexpr double kDivergenceFactor = 10.0;

// Rolling operator block B(d, e) [1/Pa] = (A(d dx, e ds) - A((d + 1) dx, e ds)) / dx: slip per
// unit traction, field cell minus source cell = (d, e) in indices.
class RollingKernel {
 public:
  RollingKernel(const PatchGrid& grid, const internal::CerrutiCoefficients& c)
      : c_(c), dx_(grid.dx_m), ds_(grid.ds_m) {}
  TangentialBlock operator()(int d, int e) const {
    const TangentialBlock a = internal::CerrutiCellInfluence(c_, d * dx_, e * ds_, dx_, ds_);
    const TangentialBlock b = internal::CerrutiCellInfluence(c_, (d + 1) * dx_, e * ds_, dx_, ds_);
    return {(a.xx - b.xx) / dx_, (a.xs - b.xs) / dx_, (a.ss - b.ss) / dx_};
  }

 private:
  internal::CerrutiCoefficients c_;
  double dx_, ds_;
};

// Columns per block of the sweep (see the header): balances the direct refreshes inside a block
// (about cells_loaded * (block / 2) * mean loaded column length multiply-adds per sweep) against
// the FFT products between blocks (span / block per sweep, span the x-columns from the first to
// the last loaded one, each about lx ls log2(lx ls) work for the padded lx by ls transforms of
// the whole nx by ns grid); kBlockCostRatio, measured on the benchmark grids (40 x 20 to 70 x 80,
// best block 16 to 24 columns), converts the FFT work to refresh units. The blocks then share the
// span evenly: ceil(span / k) blocks of equal width (to one column) instead of blocks of k with a
// remainder, which keeps the products and lowers the refreshes (they grow as the square of a
// block's width). Re-measured with the deferred refreshes (SweepBlock; docs/speed.md): on
// tang_problm_2c blocks of 22 (this ratio), 28 and 34 columns within the noise of each other, 44
// slower; tang_problm_1c flat from 17 to 34; so the ratio stays.
constexpr double kBlockCostRatio = 2.0;
int FftBlockColumns(int nx, int ns, int span, int cells_loaded, double mean_column_length) {
  const double lx = internal::RealFftSize(nx), ls = internal::ComplexFftSize(ns);
  const double product = lx * ls * std::log2(lx * ls);
  const double refresh = std::max(1.0, 0.5 * cells_loaded * mean_column_length);
  const double k = std::sqrt(kBlockCostRatio * span * product / refresh);
  const int width = std::clamp(static_cast<int>(std::lround(k)), 1, span);
  const int blocks = (span + width - 1) / width;
  return (span + blocks - 1) / blocks;
}

// The cell kernel A(d dx, e ds) (CerrutiCellInfluence, not divided by dx) on the offsets
// d in [-nx, nx], e in (-ns, ns), d fastest: evaluated once per set-up, the source of both the
// rolling operator's generator and the sweeps' tables. Each entry is the very call RollingKernel
// and the tables made before (the same arguments), so the set-up's results are unchanged bit for
// bit; it evaluates the closed forms once per offset instead of three times (twice for B's
// difference, once for the tables).
struct CellKernelTable {
  int nx = 0, ns = 0, tx = 0;
  std::vector<TangentialBlock> a;
  CellKernelTable(const PatchGrid& grid, const internal::CerrutiCoefficients& c)
      : nx(grid.nx), ns(grid.ns), tx(2 * grid.nx + 1) {
    a.resize(static_cast<size_t>(tx) * (2 * ns - 1));
    for (int e = -(ns - 1); e <= ns - 1; ++e) {
      for (int d = -nx; d <= nx; ++d) {
        a[At(d, e)] =
            internal::CerrutiCellInfluence(c, d * grid.dx_m, e * grid.ds_m, grid.dx_m, grid.ds_m);
      }
    }
  }
  size_t At(int d, int e) const {
    return static_cast<size_t>(e + ns - 1) * tx + static_cast<size_t>(d + nx);
  }
};

// The rolling operator's blocks B(d, e) on the offsets of the grid, d in (-nx, nx), e in (-ns, ns)
// (d fastest): the generator of the FFT products and the source of the loaded cells' dense
// matrix (LoadedDenseProduct). B(d, e) = (A(d, e) - A(d + 1, e)) / dx, as RollingKernel.
struct RollingGenerator {
  int nx = 0, ns = 0;
  std::vector<double> xx, xs, ss;
  RollingGenerator(const PatchGrid& grid, const CellKernelTable& table) : nx(grid.nx), ns(grid.ns) {
    const size_t size = static_cast<size_t>(2 * nx - 1) * (2 * ns - 1);
    xx.resize(size);
    xs.resize(size);
    ss.resize(size);
    const double dx = grid.dx_m;
    for (int e = -(ns - 1); e <= ns - 1; ++e) {
      for (int d = -(nx - 1); d <= nx - 1; ++d) {
        const TangentialBlock& a = table.a[table.At(d, e)];
        const TangentialBlock& b = table.a[table.At(d + 1, e)];
        const size_t k = At(d, e);
        xx[k] = (a.xx - b.xx) / dx;
        xs[k] = (a.xs - b.xs) / dx;
        ss[k] = (a.ss - b.ss) / dx;
      }
    }
  }
  size_t At(int d, int e) const {
    return static_cast<size_t>(e + ns - 1) * (2 * nx - 1) + static_cast<size_t>(d + nx - 1);
  }
};

// The rolling operator applied to a traction field: s = B q, (q_x, q_s) -> (s_x, s_s).
class RollingOperator {
 public:
  virtual ~RollingOperator() = default;
  // qx, qs: [cells] [Pa]; sx, ss: [cells] [-], resized.
  virtual void Apply(const Eigen::VectorXd& qx, const Eigen::VectorXd& qs, Eigen::VectorXd* sx,
                     Eigen::VectorXd* ss) const = 0;
};

// Dense reference: the 2N x 2N matrix [Bxx Bxs; Bsx Bss].
class DenseRollingOperator final : public RollingOperator {
 public:
  DenseRollingOperator(const PatchGrid& grid, const RollingKernel& kernel) : n_(grid.cells()) {
    b_.resize(2 * n_, 2 * n_);
    for (int js = 0; js < grid.ns; ++js) {
      for (int jx = 0; jx < grid.nx; ++jx) {
        const int j = grid.Index(jx, js);
        for (int is = 0; is < grid.ns; ++is) {
          for (int ix = 0; ix < grid.nx; ++ix) {
            const int i = grid.Index(ix, is);
            const TangentialBlock blk = kernel(ix - jx, is - js);
            b_(i, j) = blk.xx;
            b_(i, n_ + j) = blk.xs;
            b_(n_ + i, j) = blk.xs;
            b_(n_ + i, n_ + j) = blk.ss;
          }
        }
      }
    }
  }
  void Apply(const Eigen::VectorXd& qx, const Eigen::VectorXd& qs, Eigen::VectorXd* sx,
             Eigen::VectorXd* ss) const override {
    *sx = b_.topLeftCorner(n_, n_) * qx + b_.topRightCorner(n_, n_) * qs;
    *ss = b_.bottomLeftCorner(n_, n_) * qx + b_.bottomRightCorner(n_, n_) * qs;
  }

 private:
  int n_;
  Eigen::MatrixXd b_;
};

// 2-D Toeplitz products by FFT: each block's generator on offsets d in (-nx, nx), e in (-ns, ns)
// is wrapped into an lx by ls circulant (lx >= 2 nx - 1, ls >= 2 ns - 1: linear, not periodic,
// convolution). B is not even in d, so the spectra are complex. internal::PaddedFft2d (FFTW):
// real FFTs along x (half spectrum, hx = lx/2 + 1 bins), complex FFTs along s; spectra stored
// x-major [kx * ls + ks].
class FftRollingOperator final : public RollingOperator {
 public:
  // The products on an nx by ns grid (at most the generator's: the products of a sub-rectangle
  // of that size anywhere in the generator's grid, CroppedRollingProduct).
  FftRollingOperator(int nx, int ns, const RollingGenerator& generator)
      : nx_(nx),
        ns_(ns),
        fft_(nx, ns),
        spec_xx_(fft_.NewSpectrum()),
        spec_xs_(fft_.NewSpectrum()),
        spec_ss_(fft_.NewSpectrum()),
        qx_hat_(fft_.NewSpectrum()),
        qs_hat_(fft_.NewSpectrum()),
        out_hat_(fft_.NewSpectrum()),
        out_s_hat_(fft_.NewSpectrum()) {
    const int lx = fft_.lx(), ls = fft_.ls();
    const size_t size = static_cast<size_t>(lx) * ls;
    std::vector<double> gxx(size, 0.0), gxs(size, 0.0), gss(size, 0.0);
    for (int e = -(ns_ - 1); e <= ns_ - 1; ++e) {
      for (int d = -(nx_ - 1); d <= nx_ - 1; ++d) {
        const size_t g = generator.At(d, e);
        const size_t k =
            static_cast<size_t>((e + ls) % ls) * lx + static_cast<size_t>((d + lx) % lx);
        gxx[k] = generator.xx[g];
        gxs[k] = generator.xs[g];
        gss[k] = generator.ss[g];
      }
    }
    // The unscaled inverse transforms need 1 / (lx ls); fold it into the spectra.
    const double scale = 1.0 / (static_cast<double>(lx) * ls);
    for (auto [g, spec] : {std::pair{&gxx, &spec_xx_}, {&gxs, &spec_xs_}, {&gss, &spec_ss_}}) {
      fft_.ForwardGenerator(g->data(), spec->data());
      for (size_t k = 0; k < spec->size(); ++k) (*spec)[k] *= scale;
    }
  }

  void Apply(const Eigen::VectorXd& qx, const Eigen::VectorXd& qs, Eigen::VectorXd* sx,
             Eigen::VectorXd* ss) const override {
    fft_.Forward(qx.data(), qx_hat_.data());
    fft_.Forward(qs.data(), qs_hat_.data());
    // out_x = xx qx + xs qs and out_s = xs qx + ss qs per frequency, in one pass over the
    // spectra. Written out in real arithmetic: the same products and sums, in the same order,
    // as std::complex's operator* and operator+ (so the same bits), without their NaN
    // recovery branch, which kept the loop from vectorising (no spectrum here is NaN).
    const size_t n = out_hat_.size();
    const double* __restrict a = reinterpret_cast<const double*>(spec_xx_.data());
    const double* __restrict b = reinterpret_cast<const double*>(spec_xs_.data());
    const double* __restrict c = reinterpret_cast<const double*>(spec_ss_.data());
    const double* __restrict u = reinterpret_cast<const double*>(qx_hat_.data());
    const double* __restrict v = reinterpret_cast<const double*>(qs_hat_.data());
    double* __restrict ox = reinterpret_cast<double*>(out_hat_.data());
    double* __restrict os = reinterpret_cast<double*>(out_s_hat_.data());
    for (size_t k = 0; k < n; ++k) {
      const double ar = a[2 * k], ai = a[2 * k + 1], br = b[2 * k], bi = b[2 * k + 1];
      const double cr = c[2 * k], ci = c[2 * k + 1], ur = u[2 * k], ui = u[2 * k + 1];
      const double vr = v[2 * k], vi = v[2 * k + 1];
      ox[2 * k] = (ar * ur - ai * ui) + (br * vr - bi * vi);
      ox[2 * k + 1] = (ar * ui + ai * ur) + (br * vi + bi * vr);
      os[2 * k] = (br * ur - bi * ui) + (cr * vr - ci * vi);
      os[2 * k + 1] = (br * ui + bi * ur) + (cr * vi + ci * vr);
    }
    if (sx->size() != nx_ * ns_) sx->resize(nx_ * ns_);
    fft_.Inverse(out_hat_.data(), sx->data());
    if (ss->size() != nx_ * ns_) ss->resize(nx_ * ns_);
    fft_.Inverse(out_s_hat_.data(), ss->data());
  }

 private:
  using Spectrum = internal::FftwBuffer<internal::FftwComplex>;
  int nx_, ns_;
  internal::PaddedFft2d fft_;
  Spectrum spec_xx_, spec_xs_, spec_ss_;  // [hx * ls], scaled by 1/(lx ls)
  // Scratch (hence mutable; not for concurrent use).
  mutable Spectrum qx_hat_, qs_hat_, out_hat_, out_s_hat_;
};

// The rolling operator restricted to the m loaded cells, a dense 2m x 2m matrix [Bxx Bxs; Bsx Bss]
// from the generator: s = B q at the loaded cells for a q that is zero elsewhere, which is all
// the solve reads (the slip of an unloaded cell is never used; it is set to 0 here). On small
// patches this beats the padded FFTs' fixed costs (kLoadedDenseMaxCells); it agrees with them
// to rounding.
class LoadedDenseProduct final : public RollingOperator {
 public:
  LoadedDenseProduct(const PatchGrid& grid, const RollingGenerator& generator,
                     const std::vector<int>& loaded)
      : n_(grid.cells()), loaded_(loaded) {
    const int m = static_cast<int>(loaded_.size());
    b_.resize(2 * m, 2 * m);
    q_.resize(2 * m);
    s_.resize(2 * m);
    for (int j = 0; j < m; ++j) {
      const int jx = loaded_[j] % grid.nx, js = loaded_[j] / grid.nx;
      for (int i = 0; i < m; ++i) {
        const int ix = loaded_[i] % grid.nx, is = loaded_[i] / grid.nx;
        const size_t k = generator.At(ix - jx, is - js);
        b_(i, j) = generator.xx[k];
        b_(i, m + j) = generator.xs[k];
        b_(m + i, j) = generator.xs[k];
        b_(m + i, m + j) = generator.ss[k];
      }
    }
  }
  void Apply(const Eigen::VectorXd& qx, const Eigen::VectorXd& qs, Eigen::VectorXd* sx,
             Eigen::VectorXd* ss) const override {
    const int m = static_cast<int>(loaded_.size());
    for (int t = 0; t < m; ++t) {
      q_[t] = qx[loaded_[t]];
      q_[m + t] = qs[loaded_[t]];
    }
    s_.noalias() = b_ * q_;
    sx->setZero(n_);
    ss->setZero(n_);
    for (int t = 0; t < m; ++t) {
      (*sx)[loaded_[t]] = s_[t];
      (*ss)[loaded_[t]] = s_[m + t];
    }
  }

 private:
  int n_;
  const std::vector<int>& loaded_;
  Eigen::MatrixXd b_;
  mutable Eigen::VectorXd q_, s_;  // scratch
};

// The FFT products on the loaded cells' bounding rectangle: columns x0 .. x0 + mx - 1 and rows
// s0 .. s0 + ms - 1 of the grid, the smallest rectangle holding every loaded cell. B is
// Toeplitz, so the rectangle's operator is the generator's on its own offsets, and the padded
// transforms shrink with it (lengths for mx and ms instead of nx and ns; the potential contact
// area of a conformal patch is often twice as long as its contact). Tractions outside the
// rectangle are 0 (unloaded) and the slip there is never read (set to 0 here), so the products
// agree with the whole grid's to rounding.
class CroppedRollingProduct final : public RollingOperator {
 public:
  CroppedRollingProduct(const PatchGrid& grid, const RollingGenerator& generator, int x0, int mx,
                        int s0, int ms)
      : nx_(grid.nx),
        n_(grid.cells()),
        x0_(x0),
        mx_(mx),
        s0_(s0),
        ms_(ms),
        inner_(mx, ms, generator),
        qx_(mx * ms),
        qs_(mx * ms) {}
  bool Covers(int x0, int mx, int s0, int ms) const {
    return x0 == x0_ && mx == mx_ && s0 == s0_ && ms == ms_;
  }
  void Apply(const Eigen::VectorXd& qx, const Eigen::VectorXd& qs, Eigen::VectorXd* sx,
             Eigen::VectorXd* ss) const override {
    for (int j = 0; j < ms_; ++j) {
      const int from = (s0_ + j) * nx_ + x0_;
      qx_.segment(j * mx_, mx_) = qx.segment(from, mx_);
      qs_.segment(j * mx_, mx_) = qs.segment(from, mx_);
    }
    inner_.Apply(qx_, qs_, &sx_, &ss_);
    sx->setZero(n_);
    ss->setZero(n_);
    for (int j = 0; j < ms_; ++j) {
      const int to = (s0_ + j) * nx_ + x0_;
      sx->segment(to, mx_) = sx_.segment(j * mx_, mx_);
      ss->segment(to, mx_) = ss_.segment(j * mx_, mx_);
    }
  }

 private:
  int nx_, n_, x0_, mx_, s0_, ms_;
  FftRollingOperator inner_;
  mutable Eigen::VectorXd qx_, qs_, sx_, ss_;  // scratch
};

// Anderson acceleration (type II, Walker & Ni 2011) of the fixed-point map x -> G(x) of one
// sweep: with the last m differences of the residuals f = G(x) - x (columns of dF) and of the
// images (dG), the next iterate is G(x_k) - dG gamma, gamma = argmin |f_k - dF gamma|_2. The
// least-squares problem is solved through the m x m Gram matrix dF^T dF, kept up to date as
// columns enter and leave (O(size m) work per iteration), with a relative Tikhonov term
// kAndersonRegularisation against dependent columns. A fixed point of G is one of the
// accelerated iteration; depth 0 gives the plain iteration.
constexpr double kAndersonRegularisation = 1e-10;
class AndersonMixer {
 public:
  // depth >= 0 columns of vectors of the given size.
  AndersonMixer(int depth, int size)
      : depth_(depth), df_(size, depth), dg_(size, depth), gram_(depth, depth) {}
  void Clear() {
    count_ = next_ = 0;
    have_previous_ = false;
  }
  // x: the iterate the sweep started from; g: G(x), overwritten by the next iterate.
  void Mix(const Eigen::VectorXd& x, Eigen::VectorXd* g) {
    if (depth_ == 0) return;
    const Eigen::VectorXd f = *g - x;
    if (have_previous_) {
      const int slot = next_;
      next_ = (next_ + 1) % depth_;
      count_ = std::min(count_ + 1, depth_);
      df_.col(slot) = f - f_prev_;
      dg_.col(slot) = *g - g_prev_;
      for (int c = 0; c < count_; ++c) {
        gram_(slot, c) = gram_(c, slot) = df_.col(slot).dot(df_.col(c));
      }
    }
    f_prev_ = f;
    g_prev_ = *g;
    have_previous_ = true;
    if (count_ == 0) return;
    // The columns in use are slots 0 .. count_ - 1 (the ring fills from slot 0).
    const int m = count_;
    Eigen::MatrixXd a = gram_.topLeftCorner(m, m);
    a.diagonal().array() += kAndersonRegularisation * a.diagonal().maxCoeff();
    const Eigen::VectorXd rhs = df_.leftCols(m).transpose() * f;
    const Eigen::VectorXd gamma = a.ldlt().solve(rhs);
    *g -= dg_.leftCols(m) * gamma;
  }

 private:
  int depth_;
  Eigen::MatrixXd df_, dg_, gram_;
  Eigen::VectorXd f_prev_, g_prev_;
  int count_ = 0, next_ = 0;
  bool have_previous_ = false;
};

// The exact local problem of one cell. r: slip the cell would have with zero traction [-];
// d: the cell's own diagonal block of B (both > 0) [1/Pa]; g = mu p [Pa]. Returns the traction
// and whether the cell sticks.
struct LocalResult {
  double qx, qs;
  bool stick;
};
LocalResult SolveLocal(double rx, double rs, double dxx, double dss, double g) {
  const double tx = -rx / dxx;
  const double ts = -rs / dss;
  if (tx * tx + ts * ts <= g * g) return {tx, ts, true};
  // Slip: q = -g s/|s|, s = r + D q  =>  s_k = r_k sigma / (sigma + g d_k), sigma = |s| the root
  // of f(sigma) = sum r_k^2 / (sigma + g d_k)^2 - 1, convex and decreasing: Newton from a point
  // left of the root climbs monotonically to it. The start: sigma_0 = max(0, |r| - g max_k d_k),
  // where every sigma_0 + g d_k <= |r|, so f(sigma_0) >= sum r_k^2 / |r|^2 - 1 = 0 (at 0, f > 0
  // in this branch). From 0 Newton gains only a factor of about 1.5 per step while sigma << |r|
  // (about 20 steps in full slip); from sigma_0 it needs 3 to 5.
  const double ax = g * dxx;
  const double as = g * dss;
  double sigma = std::max(0.0, std::sqrt(rx * rx + rs * rs) - std::max(ax, as));
  for (int it = 0; it < 100; ++it) {
    const double ex = sigma + ax;
    const double es = sigma + as;
    const double f = rx * rx / (ex * ex) + rs * rs / (es * es) - 1.0;
    const double df = -2.0 * (rx * rx / (ex * ex * ex) + rs * rs / (es * es * es));
    const double step = -f / df;
    sigma += step;
    if (step <= 1e-15 * sigma) break;
  }
  return {-g * rx / (sigma + ax), -g * rs / (sigma + as), false};
}

void CheckInputs(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa, const RollingInput& in,
                 const ExactTangentialOptions& opt) {
  std::ostringstream msg;
  const std::string opt_error = opt.Validate();
  if (!opt_error.empty()) msg << "options: " << opt_error;
  if (grid.nx < 1 || grid.ns < 1 || !(grid.dx_m > 0.0) || !(grid.ds_m > 0.0)) {
    msg << "grid " << grid.nx << " x " << grid.ns << " cells of " << grid.dx_m << " x " << grid.ds_m
        << " m, expected at least one cell of positive size; ";
  }
  const long n = static_cast<long>(grid.nx) * grid.ns;
  if (pressure_Pa.size() != n || in.creep_x.size() != n || in.creep_s.size() != n) {
    msg << "sizes: pressure " << pressure_Pa.size() << ", creep_x " << in.creep_x.size()
        << ", creep_s " << in.creep_s.size() << ", expected grid.cells() = " << n << "; ";
  } else {
    if (!pressure_Pa.allFinite() || (pressure_Pa.array() < 0.0).any()) {
      msg << "pressure must be finite and >= 0; ";
    }
    if (!in.creep_x.allFinite() || !in.creep_s.allFinite()) msg << "creepage must be finite; ";
  }
  if (!(in.speed_m_s > 0.0) || !std::isfinite(in.speed_m_s)) {
    msg << "speed_m_s = " << in.speed_m_s << ", expected > 0; ";
  }
  if (!(in.friction > 0.0) || !std::isfinite(in.friction)) {
    msg << "friction = " << in.friction << ", expected > 0; ";
  }
  if (!msg.str().empty()) throw InputError("tangential exact: " + msg.str());
  RAILWEAR_CHECK(static_cast<int>(grid.tangent_yz.size()) == grid.ns);
}

// Step 1 of SolveTangentialExact, the tables of the sweeps: the displacement kernel A / dx on
// offsets d in [-nx, nx], e in (-ns, ns) (a_*: row length tx, d fastest; c_*: transposed, the s
// offset fastest, for the refreshes along s; both depend on the grid's shape and the materials
// only, so ExactTangentialSetup keeps them), each cell's chain end and each x-column's loaded
// span (these depend on the pressure).
struct KernelTables {
  int nx = 0, ns = 0;
  int tx = 0;         // table row length (d = -nx .. nx)
  int col_table = 0;  // c_* entries per x offset
  std::vector<double> a_xx, a_xs, a_ss;
  std::vector<double> c_xx, c_xs, c_ss;
};

struct SweepTables {
  const KernelTables* kernel = nullptr;
  int nx = 0, ns = 0;
  // Downstream end of each cell's chain: the smallest ix' <= ix with all of ix' .. ix loaded.
  std::vector<int> chain_end;
  // Loaded span of each x-column [first, last] in s.
  std::vector<int> first_loaded_col, last_loaded_col;
  // The first and the last x-column with a loaded cell (the sweeps visit these and the columns
  // between them only).
  int col_lo = 0, col_hi = -1;

  double Table(const std::vector<double>& t, int d, int e) const {
    return t[static_cast<size_t>(e + ns - 1) * kernel->tx + (d + nx)];
  }
  // The local diagonal of a chain update at ix with chain end e: (A(0) - A(ix - e + 1)) / dx.
  void LocalDiagonal(const PatchGrid& grid, int ix, int js, double* dxx, double* dss) const {
    const int v = chain_end[grid.Index(ix, js)] - 1;
    *dxx = Table(kernel->a_xx, 0, 0) - Table(kernel->a_xx, ix - v, 0);
    *dss = Table(kernel->a_ss, 0, 0) - Table(kernel->a_ss, ix - v, 0);
  }
};

KernelTables MakeKernelTables(const PatchGrid& grid, const CellKernelTable& cells) {
  const int tx = 2 * grid.nx + 1;  // table row length (d = -nx .. nx)
  const int ts = 2 * grid.ns - 1;
  std::vector<double> a_xx(static_cast<size_t>(tx) * ts), a_xs(a_xx.size()), a_ss(a_xx.size());
  for (int e = -(grid.ns - 1); e <= grid.ns - 1; ++e) {
    for (int d = -grid.nx; d <= grid.nx; ++d) {
      const TangentialBlock& b = cells.a[cells.At(d, e)];
      const size_t k = static_cast<size_t>(e + grid.ns - 1) * tx + (d + grid.nx);
      a_xx[k] = b.xx / grid.dx_m;
      a_xs[k] = b.xs / grid.dx_m;
      a_ss[k] = b.ss / grid.dx_m;
    }
  }
  auto table = [&](const std::vector<double>& t, int d, int e) {
    return t[static_cast<size_t>(e + grid.ns - 1) * tx + (d + grid.nx)];
  };
  // The table transposed (s offset fastest: col_table entries per x offset) for the refreshes
  // along s in the sweeps.
  const int col_table = ts;
  std::vector<double> c_xx(a_xx.size()), c_xs(a_xx.size()), c_ss(a_xx.size());
  for (int e = -(grid.ns - 1); e <= grid.ns - 1; ++e) {
    for (int d = -grid.nx; d <= grid.nx; ++d) {
      const size_t kc = static_cast<size_t>(d + grid.nx) * col_table + (e + grid.ns - 1);
      c_xx[kc] = table(a_xx, d, e);
      c_xs[kc] = table(a_xs, d, e);
      c_ss[kc] = table(a_ss, d, e);
    }
  }
  KernelTables out;
  out.nx = grid.nx;
  out.ns = grid.ns;
  out.tx = tx;
  out.col_table = col_table;
  out.a_xx = std::move(a_xx);
  out.a_xs = std::move(a_xs);
  out.a_ss = std::move(a_ss);
  out.c_xx = std::move(c_xx);
  out.c_xs = std::move(c_xs);
  out.c_ss = std::move(c_ss);
  return out;
}

SweepTables MakeSweepTables(const PatchGrid& grid, const KernelTables& kernel,
                            const Eigen::VectorXd& pressure_Pa) {
  const int n = grid.cells();
  // Downstream end of each cell's chain: the smallest ix' <= ix with all of ix' .. ix loaded.
  std::vector<int> chain_end(n, -1);
  for (int js = 0; js < grid.ns; ++js) {
    int end = -1;
    for (int ix = 0; ix < grid.nx; ++ix) {
      const int k = grid.Index(ix, js);
      if (!(pressure_Pa[k] > 0.0)) {
        end = -1;
        continue;
      }
      if (end < 0) end = ix;
      chain_end[k] = end;
    }
  }
  // Loaded span of each x-column [first, last] in s.
  std::vector<int> first_loaded_col(grid.nx, grid.ns), last_loaded_col(grid.nx, -1);
  for (int ix = 0; ix < grid.nx; ++ix) {
    for (int js = 0; js < grid.ns; ++js) {
      if (!(pressure_Pa[grid.Index(ix, js)] > 0.0)) continue;
      first_loaded_col[ix] = std::min(first_loaded_col[ix], js);
      last_loaded_col[ix] = js;
    }
  }
  SweepTables out;
  out.kernel = &kernel;
  out.nx = grid.nx;
  out.ns = grid.ns;
  out.chain_end = std::move(chain_end);
  out.first_loaded_col = std::move(first_loaded_col);
  out.last_loaded_col = std::move(last_loaded_col);
  out.col_lo = grid.nx;
  for (int ix = 0; ix < grid.nx; ++ix) {
    if (out.last_loaded_col[ix] < 0) continue;
    out.col_lo = std::min(out.col_lo, ix);
    out.col_hi = ix;
  }
  return out;
}

// The x-columns per block of a sweep (some cell loaded). The blocks cover the loaded columns'
// span (tables.col_lo .. col_hi) only: columns outside it hold nothing to sweep, and a product
// after the last block that holds loaded cells would refresh a slip no later block reads.
int ChooseBlockColumns(const PatchGrid& grid, const SweepTables& tables, bool dense,
                       const ExactTangentialOptions& opt) {
  const std::vector<int>& first_loaded_col = tables.first_loaded_col;
  const std::vector<int>& last_loaded_col = tables.last_loaded_col;
  const int span = tables.col_hi - tables.col_lo + 1;
  // Blocks of the sweep: with the dense operator a product costs as much as a sweep of direct
  // refreshes, so one block spans the loaded columns (the plain sweep).
  int block_columns = span;
  if (!dense && opt.block_columns > 0) {
    block_columns = std::min(opt.block_columns, span);
  } else if (!dense) {
    int cells_loaded = 0, columns_loaded = 0;
    for (int ix = 0; ix < grid.nx; ++ix) {
      if (last_loaded_col[ix] < 0) continue;
      ++columns_loaded;
      cells_loaded += last_loaded_col[ix] - first_loaded_col[ix] + 1;
    }
    block_columns = FftBlockColumns(grid.nx, grid.ns, span, cells_loaded,
                                    static_cast<double>(cells_loaded) / columns_loaded);
  }
  return block_columns;
}

// The local solution at cell (ix, js) from the current slip sx, ss and traction qx, qs.
LocalResult LocalSolveAt(const PatchGrid& grid, const SweepTables& tables,
                         const Eigen::VectorXd& pressure_Pa, double mu, const Eigen::VectorXd& sx,
                         const Eigen::VectorXd& ss, const Eigen::VectorXd& qx,
                         const Eigen::VectorXd& qs, int ix, int js) {
  const int k = grid.Index(ix, js);
  double dxx = 0.0, dss = 0.0;
  tables.LocalDiagonal(grid, ix, js, &dxx, &dss);
  return SolveLocal(sx[k] - dxx * qx[k], ss[k] - dss * qs[k], dxx, dss, mu * pressure_Pa[k]);
}

// The sweeps' two inner loops (most of a sweep's time on the benchmark grids, perf in
// docs/speed.md) are compiled twice, for AVX2 and for the baseline
// (core/numerics/target_clones.h): the loops are element-wise, so both clones give the same bits.

// One column's slip refreshed right after a chain update in that column (the cells after the
// updated one), from the table rows of the cell (*1) and of the virtual cell beyond the chain
// end (*2).
RAILWEAR_AVX2_CLONES
void RefreshColumn(int len, const double* __restrict xx1, const double* __restrict xx2,
                   const double* __restrict xs1, const double* __restrict xs2,
                   const double* __restrict ss1, const double* __restrict ss2, double dqx,
                   double dqs, double* __restrict ox, double* __restrict os) {
#pragma GCC ivdep
  for (int j = 0; j < len; ++j) {
    const double bxs = xs1[j] - xs2[j];
    ox[j] += (xx1[j] - xx2[j]) * dqx + bxs * dqs;
    os[j] += bxs * dqx + (ss1[j] - ss2[j]) * dqs;
  }
}

// The deferred refreshes' loop: adds to one target column's slip (len consecutive cells along s,
// ox, os) the displacement of n_src sources on consecutive rows of one x-column with traction
// changes qx[t], qs[t]: a Toeplitz product with the table row of their x offset. xx, xs, ss point
// at the table entries of source 0 for the first target cell; source t's entries start t
// entries earlier (its row is t further along s). Four sources per pass over the target, so the
// target is read and written once per four.
RAILWEAR_AVX2_CLONES
void AddKernelProducts(int len, int n_src, const double* xx, const double* xs, const double* ss,
                       const double* qx, const double* qs, double* __restrict ox,
                       double* __restrict os) {
  int t = 0;
  for (; t + 4 <= n_src; t += 4) {
    // Source t + u reads a[j - u] (one base pointer per table keeps the loop in registers).
    const double* __restrict a = xx - t, * __restrict b = xs - t, * __restrict c = ss - t;
    const double x0 = qx[t], x1 = qx[t + 1], x2 = qx[t + 2], x3 = qx[t + 3];
    const double s0 = qs[t], s1 = qs[t + 1], s2 = qs[t + 2], s3 = qs[t + 3];
#pragma GCC ivdep
    for (int j = 0; j < len; ++j) {
      ox[j] += ((a[j] * x0 + b[j] * s0) + (a[j - 1] * x1 + b[j - 1] * s1)) +
               ((a[j - 2] * x2 + b[j - 2] * s2) + (a[j - 3] * x3 + b[j - 3] * s3));
      os[j] += ((b[j] * x0 + c[j] * s0) + (b[j - 1] * x1 + c[j - 1] * s1)) +
               ((b[j - 2] * x2 + c[j - 2] * s2) + (b[j - 3] * x3 + c[j - 3] * s3));
    }
  }
  for (; t < n_src; ++t) {
    const double* __restrict a = xx - t, * __restrict b = xs - t, * __restrict c = ss - t;
    const double x = qx[t], s = qs[t];
#pragma GCC ivdep
    for (int j = 0; j < len; ++j) {
      ox[j] += a[j] * x + b[j] * s;
      os[j] += b[j] * x + c[j] * s;
    }
  }
}

// Scratch of the block sweeps, kept across the blocks and sweeps of a solve.
struct SweepScratch {
  // The block's slip and the traction changes of its updated cells, column-major
  // [ix * ns + js] (the refreshes run along s, contiguous).
  Eigen::VectorXd sx_col, ss_col, dqx_col, dqs_col;
  // The virtual cells' sources (the changes' telescoped chain ends, see SweepBlock): one entry
  // per row and chain end met in the block, the negated sum of the chain updates there.
  std::vector<int> virtual_row, virtual_col;
  std::vector<double> virtual_qx, virtual_qs;
  std::vector<int> row_entry;  // [ns]: the row's latest entry, -1 for none
  SweepScratch(int cells, int ns)
      : sx_col(cells), ss_col(cells), dqx_col(cells), dqs_col(cells), row_entry(ns, -1) {}
};

// One block (columns block_lo .. block_hi) of a Gauss-Seidel sweep from the leading edge with
// relaxation w: tractions *qx_io, *qs_io updated chain by chain, the block's slip (from sx, ss)
// refreshed in the column-major copies of *scratch.
// A change dq at cell (ix, js) moves the whole chain ix .. chain end (the cell and everything
// downstream of it up to the contact edge), whose slip is the telescoped sum
// (A(m - ix) - A(m - v)) / dx, v the virtual cell just beyond the chain end: a source dq at the
// cell and a source -dq at the virtual cell. The cells after it in its own column are refreshed
// at once (RefreshColumn); the block's later columns only when the sweep reaches them, each
// once, from all the changes made since the block began (deferred refreshes): one Toeplitz
// product per earlier column of the block (the cells' sources) and one with the virtual cells'
// sources, which sum per row and chain end (a row's cells share their chain end), so that term
// costs one product per target column instead of one per changed cell. The slip each local
// solve reads is the same as with a refresh after every update (to rounding: the sums run in
// another order).
void SweepBlock(const PatchGrid& grid, const SweepTables& tables,
                const Eigen::VectorXd& pressure_Pa, double mu, double w, int block_lo, int block_hi,
                const Eigen::VectorXd& sx, const Eigen::VectorXd& ss, Eigen::VectorXd* qx_io,
                Eigen::VectorXd* qs_io, SweepScratch* scratch) {
  Eigen::VectorXd& qx = *qx_io;
  Eigen::VectorXd& qs = *qs_io;
  SweepScratch& sc = *scratch;
  const int ns = grid.ns;
  const std::vector<int>& chain_end = tables.chain_end;
  const std::vector<int>& first_loaded_col = tables.first_loaded_col;
  const std::vector<int>& last_loaded_col = tables.last_loaded_col;
  const double* c_xx = tables.kernel->c_xx.data();
  const double* c_xs = tables.kernel->c_xs.data();
  const double* c_ss = tables.kernel->c_ss.data();
  const int col_table = tables.kernel->col_table;
  // The table entries (d, e = jm_lo - js) of x offset d, for the target rows from jm_lo and a
  // source in row js.
  auto table_at = [&](int d, int jm_lo, int js) {
    return static_cast<size_t>(d + grid.nx) * col_table + static_cast<size_t>(ns - 1 - js + jm_lo);
  };
  for (int im = block_lo; im <= block_hi; ++im) {
    for (int jm = 0; jm < ns; ++jm) {
      const size_t t = static_cast<size_t>(im) * ns + jm;
      sc.sx_col[t] = sx[grid.Index(im, jm)];
      sc.ss_col[t] = ss[grid.Index(im, jm)];
    }
  }
  const size_t block_at = static_cast<size_t>(block_lo) * ns;
  const size_t block_size = static_cast<size_t>(block_hi - block_lo + 1) * ns;
  std::fill_n(sc.dqx_col.data() + block_at, block_size, 0.0);
  std::fill_n(sc.dqs_col.data() + block_at, block_size, 0.0);
  sc.virtual_row.clear();
  sc.virtual_col.clear();
  sc.virtual_qx.clear();
  sc.virtual_qs.clear();
  std::fill(sc.row_entry.begin(), sc.row_entry.end(), -1);
  for (int ix = block_hi; ix >= block_lo; --ix) {
    const int lo = first_loaded_col[ix], hi = last_loaded_col[ix];
    if (hi < lo) continue;  // no loaded cell in this column
    const int len = hi - lo + 1;
    const size_t col_at = static_cast<size_t>(ix) * ns;
    double* ox = sc.sx_col.data() + col_at + lo;
    double* os = sc.ss_col.data() + col_at + lo;
    // The deferred refreshes: the changes of the block's earlier columns ...
    for (int jx = ix + 1; jx <= block_hi; ++jx) {
      const int s_lo = first_loaded_col[jx], s_hi = last_loaded_col[jx];
      if (s_hi < s_lo) continue;
      const size_t r = table_at(ix - jx, lo, s_lo);
      const size_t from = static_cast<size_t>(jx) * ns + s_lo;
      AddKernelProducts(len, s_hi - s_lo + 1, c_xx + r, c_xs + r, c_ss + r,
                        sc.dqx_col.data() + from, sc.dqs_col.data() + from, ox, os);
    }
    // ... and their virtual cells', in runs of consecutive rows with the same virtual column.
    const int entries = static_cast<int>(sc.virtual_row.size());
    for (int e = 0; e < entries;) {
      int run = 1;
      while (e + run < entries && sc.virtual_col[e + run] == sc.virtual_col[e] &&
             sc.virtual_row[e + run] == sc.virtual_row[e] + run) {
        ++run;
      }
      const size_t r = table_at(ix - sc.virtual_col[e], lo, sc.virtual_row[e]);
      AddKernelProducts(len, run, c_xx + r, c_xs + r, c_ss + r, sc.virtual_qx.data() + e,
                        sc.virtual_qs.data() + e, ox, os);
      e += run;
    }
    for (int js = lo; js <= hi; ++js) {
      const int k = grid.Index(ix, js);
      if (!(pressure_Pa[k] > 0.0)) continue;
      const size_t t = col_at + js;
      double dxx = 0.0, dss = 0.0;
      tables.LocalDiagonal(grid, ix, js, &dxx, &dss);
      const LocalResult loc = SolveLocal(sc.sx_col[t] - dxx * qx[k], sc.ss_col[t] - dss * qs[k],
                                         dxx, dss, mu * pressure_Pa[k]);
      const double dqx = w * (loc.qx - qx[k]);
      const double dqs = w * (loc.qs - qs[k]);
      if (dqx == 0.0 && dqs == 0.0) continue;
      const int v = chain_end[k] - 1;
      for (int i = v + 1; i <= ix; ++i) {
        qx[grid.Index(i, js)] += dqx;
        qs[grid.Index(i, js)] += dqs;
      }
      // This column's cells after js at once (table rows d = 0 for the cell, ix - v for the
      // virtual cell).
      if (js < hi) {
        const size_t r1 = table_at(0, js + 1, js), r2 = table_at(ix - v, js + 1, js);
        RefreshColumn(hi - js, c_xx + r1, c_xx + r2, c_xs + r1, c_xs + r2, c_ss + r1, c_ss + r2,
                      dqx, dqs, ox + (js + 1 - lo), os + (js + 1 - lo));
      }
      // The later columns' refreshes deferred: the cell's source and its virtual cell's.
      sc.dqx_col[t] = dqx;
      sc.dqs_col[t] = dqs;
      int& entry = sc.row_entry[js];
      if (entry < 0 || sc.virtual_col[entry] != v) {
        entry = static_cast<int>(sc.virtual_row.size());
        sc.virtual_row.push_back(js);
        sc.virtual_col.push_back(v);
        sc.virtual_qx.push_back(0.0);
        sc.virtual_qs.push_back(0.0);
      }
      sc.virtual_qx[entry] -= dqx;
      sc.virtual_qs[entry] -= dqs;
    }
  }
}

// Step 3 of SolveTangentialExact: the returned tractions (the final local solutions), stick
// flags, slip velocities, forces and frictional power from the last exact slip sx, ss.
void CollectExactResults(const PatchGrid& grid, const SweepTables& tables,
                         const Eigen::VectorXd& pressure_Pa, const RollingInput& in,
                         const Eigen::VectorXd& sx, const Eigen::VectorXd& ss,
                         TangentialSolution* sol_io) {
  TangentialSolution& sol = *sol_io;
  const double x_ref = grid.XCentre();  // moments about the contact point
  Eigen::VectorXd& qx = sol.traction_x_Pa;
  Eigen::VectorXd& qs = sol.traction_s_Pa;
  const double mu = in.friction;
  auto local_solve = [&](int ix, int js) {
    return LocalSolveAt(grid, tables, pressure_Pa, mu, sx, ss, qx, qs, ix, js);
  };
  const double area = grid.CellArea();
  const double v = in.speed_m_s;
  for (int js = 0; js < grid.ns; ++js) {
    for (int ix = 0; ix < grid.nx; ++ix) {
      const int k = grid.Index(ix, js);
      if (!(pressure_Pa[k] > 0.0)) continue;
      const LocalResult loc = local_solve(ix, js);
      // The returned traction is the final local solution (it differs from the iterate by at
      // most the residual): it satisfies the bound exactly, which chain updates of the last
      // sweep need not.
      qx[k] = loc.qx;
      qs[k] = loc.qs;
      sol.stick[k] = loc.stick ? 1 : 0;
      if (loc.stick) {
        sol.stick_area_m2 += area;
      } else {
        sol.slip_area_m2 += area;
        sol.slip_x_m_s[k] = v * sx[k];
        sol.slip_s_m_s[k] = v * ss[k];
      }
      sol.force_x_N += qx[k] * area;
      sol.force_s_N += qs[k] * area;
      sol.force_s_yz_N += qs[k] * area * grid.tangent_yz[js];
      sol.spin_moment_Nm += ((grid.X(ix) - x_ref) * qs[k] - grid.S(js) * qx[k]) * area;
      sol.frictional_power_W +=
          std::abs(qx[k] * sol.slip_x_m_s[k] + qs[k] * sol.slip_s_m_s[k]) * area;
    }
  }
}

TangentialSolution NoContactSolution(const PatchGrid& grid) {
  TangentialSolution sol = EmptyTangentialSolution(grid.cells());
  sol.status = SolverStatus::kNoContact;
  sol.message = "no cell carries pressure";
  return sol;
}

// The solve proper (inputs checked, some cell loaded): steps 2 and 3 of the header comment.
TangentialSolution SolveWithSetup(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                  const RollingInput& in, const ExactTangentialSetup::Impl& setup,
                                  const ExactTangentialOptions& opt,
                                  const TangentialSolution* start = nullptr);

}  // namespace

// Step 1 of the solve, the parts that depend on the grid's shape and the materials only: the
// rolling operator (for the exact slip of each outer iteration) and the table of the
// displacement kernel A / dx on offsets d in [-nx, nx], e in (-ns, ns) (for the sweeps).
struct ExactTangentialSetup::Impl {
  int nx = 0, ns = 0;
  double dx_m = 0.0, ds_m = 0.0;
  ExactTangentialOptions::Method method = ExactTangentialOptions::Method::kAuto;
  std::unique_ptr<RollingGenerator> generator;  // with kFft only
  // The products on the whole grid: the dense matrix (kDense), or the FFT products, built at the
  // first solve that uses them (a solve on a small patch uses the loaded cells' matrix, one whose
  // loaded rectangle pads to shorter transforms uses those, and neither needs the grid's).
  mutable std::unique_ptr<RollingOperator> op;
  // The products on the last solve's loaded rectangle when it pads to shorter transforms than
  // the grid (kFft only): kept for the next solve with the same rectangle (the solves of a
  // pitch search or a vertical balance on one patch), built anew for another.
  mutable std::unique_ptr<CroppedRollingProduct> cropped;
  KernelTables kernel_tables;
};

ExactTangentialSetup::ExactTangentialSetup(const PatchGrid& grid, const Material& wheel,
                                           const Material& rail,
                                           ExactTangentialOptions::Method method)
    : impl_(std::make_unique<Impl>()) {
  if (grid.nx < 1 || grid.ns < 1 || !(grid.dx_m > 0.0) || !(grid.ds_m > 0.0)) {
    std::ostringstream msg;
    msg << "tangential exact setup: grid " << grid.nx << " x " << grid.ns << " cells of "
        << grid.dx_m << " x " << grid.ds_m << " m, expected at least one cell of positive size";
    throw InputError(msg.str());
  }
  const internal::CerrutiCoefficients coefficients = internal::MakeCerrutiCoefficients(wheel, rail);
  impl_->nx = grid.nx;
  impl_->ns = grid.ns;
  impl_->dx_m = grid.dx_m;
  impl_->ds_m = grid.ds_m;
  impl_->method = method;
  const CellKernelTable cells(grid, coefficients);
  if (method == ExactTangentialOptions::Method::kDense) {
    impl_->op = std::make_unique<DenseRollingOperator>(grid, RollingKernel(grid, coefficients));
  } else {
    impl_->generator = std::make_unique<RollingGenerator>(grid, cells);
  }
  impl_->kernel_tables = MakeKernelTables(grid, cells);
}

ExactTangentialSetup::~ExactTangentialSetup() = default;
ExactTangentialSetup::ExactTangentialSetup(ExactTangentialSetup&&) noexcept = default;
ExactTangentialSetup& ExactTangentialSetup::operator=(ExactTangentialSetup&&) noexcept = default;

bool ExactTangentialSetup::Fits(const PatchGrid& grid) const {
  return grid.nx == impl_->nx && grid.ns == impl_->ns && grid.dx_m == impl_->dx_m &&
         grid.ds_m == impl_->ds_m;
}

bool ExactTangentialSetup::Serves(ExactTangentialOptions::Method method) const {
  return (method == ExactTangentialOptions::Method::kDense) ==
         (impl_->method == ExactTangentialOptions::Method::kDense);
}

TangentialSolution SolveTangentialExact(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                        const RollingInput& in, const Material& wheel,
                                        const Material& rail, const ExactTangentialOptions& opt) {
  CheckInputs(grid, pressure_Pa, in, opt);
  internal::MakeCerrutiCoefficients(wheel, rail);  // throws for bad materials
  if (!(pressure_Pa.maxCoeff() > 0.0)) return NoContactSolution(grid);
  const ExactTangentialSetup setup(grid, wheel, rail, opt.method);
  return SolveWithSetup(grid, pressure_Pa, in, setup.impl(), opt);
}

TangentialSolution SolveTangentialExact(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                        const RollingInput& in, const ExactTangentialSetup& setup,
                                        const ExactTangentialOptions& opt,
                                        const TangentialSolution* start) {
  CheckInputs(grid, pressure_Pa, in, opt);
  if (start != nullptr && (start->traction_x_Pa.size() != grid.cells() ||
                           start->traction_s_Pa.size() != grid.cells())) {
    std::ostringstream msg;
    msg << "tangential exact: the warm start has " << start->traction_x_Pa.size() << " and "
        << start->traction_s_Pa.size() << " tractions, expected grid.cells() = " << grid.cells();
    throw InputError(msg.str());
  }
  if (!setup.Fits(grid) || !setup.Serves(opt.method)) {
    std::ostringstream msg;
    msg << "tangential exact: the setup was built for " << setup.impl().nx << " x "
        << setup.impl().ns << " cells of " << setup.impl().dx_m << " x " << setup.impl().ds_m
        << " m with the "
        << (setup.impl().method == ExactTangentialOptions::Method::kDense ? "dense" : "FFT")
        << " operator; expected the grid's " << grid.nx << " x " << grid.ns << " cells of "
        << grid.dx_m << " x " << grid.ds_m << " m and the options' "
        << (opt.method == ExactTangentialOptions::Method::kDense ? "dense" : "FFT") << " operator";
    throw InputError(msg.str());
  }
  if (!(pressure_Pa.maxCoeff() > 0.0)) return NoContactSolution(grid);
  return SolveWithSetup(grid, pressure_Pa, in, setup.impl(), opt, start);
}

namespace {

TangentialSolution SolveWithSetup(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                  const RollingInput& in, const ExactTangentialSetup::Impl& setup,
                                  const ExactTangentialOptions& opt,
                                  const TangentialSolution* start) {
  const int n = grid.cells();
  const double mu = in.friction;
  TangentialSolution sol = EmptyTangentialSolution(n);
  const double p_max = pressure_Pa.maxCoeff();
  const bool dense = opt.method == ExactTangentialOptions::Method::kDense;
  const SweepTables tables = MakeSweepTables(grid, setup.kernel_tables, pressure_Pa);
  SweepScratch scratch(n, grid.ns);
  const int block_columns = ChooseBlockColumns(grid, tables, dense, opt);

  // 2. Iterate: exact slip, convergence check, one Gauss-Seidel sweep from the leading edge.
  Eigen::VectorXd& qx = sol.traction_x_Pa;
  Eigen::VectorXd& qs = sol.traction_s_Pa;
  Eigen::VectorXd sx, ss;
  const double threshold = opt.tolerance * mu * p_max;
  double residual = 0.0;
  bool converged = false;
  int iteration = 0;
  double w = opt.relaxation;
  double best_residual = std::numeric_limits<double>::infinity();
  // The accelerated vector: [q_x; q_s] of the loaded cells (the others stay 0).
  std::vector<int> loaded;
  for (int k = 0; k < n; ++k) {
    if (pressure_Pa[k] > 0.0) loaded.push_back(k);
  }
  const int n_loaded = static_cast<int>(loaded.size());
  if (start != nullptr) {  // the warm start's tractions on the cells loaded now
    for (int k : loaded) {
      qx[k] = start->traction_x_Pa[k];
      qs[k] = start->traction_s_Pa[k];
    }
  }
  // The products: the setup's (FFT or full dense), or on small patches the loaded cells' matrix.
  const RollingOperator* op = nullptr;
  std::optional<LoadedDenseProduct> loaded_product;
  if (setup.generator && opt.method == ExactTangentialOptions::Method::kAuto &&
      n_loaded <= kLoadedDenseMaxCells) {
    loaded_product.emplace(grid, *setup.generator, loaded);
    op = &*loaded_product;
  } else if (setup.generator) {
    // The loaded cells' bounding rectangle: its products when they pad to shorter transforms.
    int s0 = grid.ns, s1 = -1;
    for (int ix = tables.col_lo; ix <= tables.col_hi; ++ix) {
      if (tables.last_loaded_col[ix] < 0) continue;
      s0 = std::min(s0, tables.first_loaded_col[ix]);
      s1 = std::max(s1, tables.last_loaded_col[ix]);
    }
    const int x0 = tables.col_lo, mx = tables.col_hi - tables.col_lo + 1, ms = s1 - s0 + 1;
    if (internal::RealFftSize(mx) < internal::RealFftSize(grid.nx) ||
        internal::ComplexFftSize(ms) < internal::ComplexFftSize(grid.ns)) {
      if (!setup.cropped || !setup.cropped->Covers(x0, mx, s0, ms)) {
        setup.cropped =
            std::make_unique<CroppedRollingProduct>(grid, *setup.generator, x0, mx, s0, ms);
      }
      op = setup.cropped.get();
    }
  }
  if (op == nullptr) {  // the whole grid's products
    if (!setup.op) {
      setup.op = std::make_unique<FftRollingOperator>(setup.nx, setup.ns, *setup.generator);
    }
    op = setup.op.get();
  }
  AndersonMixer mixer(opt.anderson_depth, 2 * n_loaded);
  Eigen::VectorXd x_start(2 * n_loaded), x_next(2 * n_loaded);  // before and after a sweep
  auto gather = [&](Eigen::VectorXd* v) {
    for (int t = 0; t < n_loaded; ++t) {
      (*v)[t] = qx[loaded[t]];
      (*v)[n_loaded + t] = qs[loaded[t]];
    }
  };
  auto local_solve = [&](int ix, int js) {
    return LocalSolveAt(grid, tables, pressure_Pa, mu, sx, ss, qx, qs, ix, js);
  };
  for (;;) {
    op->Apply(qx, qs, &sx, &ss);
    sx += in.creep_x;
    ss += in.creep_s;
    residual = 0.0;
    for (int js = 0; js < grid.ns; ++js) {
      for (int ix = 0; ix < grid.nx; ++ix) {
        const int k = grid.Index(ix, js);
        if (!(pressure_Pa[k] > 0.0)) continue;
        const LocalResult loc = local_solve(ix, js);
        const double ex = loc.qx - qx[k], es = loc.qs - qs[k];
        residual = std::max(residual, std::sqrt(ex * ex + es * es));
      }
    }
    if (residual <= threshold) {
      converged = true;
      break;
    }
    if (iteration >= opt.max_iterations) break;
    // Safeguard: a residual far above the best one so far means the relaxed sweep is not
    // contracting on this problem; halve the relaxation (the fixed point does not depend on it).
    best_residual = std::min(best_residual, residual);
    if (residual > kDivergenceFactor * best_residual) {
      w *= 0.5;
      best_residual = residual;
      mixer.Clear();
    }
    ++iteration;
    gather(&x_start);
    for (int block_hi = tables.col_hi; block_hi >= tables.col_lo; block_hi -= block_columns) {
      const int block_lo = std::max(tables.col_lo, block_hi - block_columns + 1);
      SweepBlock(grid, tables, pressure_Pa, mu, w, block_lo, block_hi, sx, ss, &qx, &qs, &scratch);
      // The exact slip of the rest (one operator product); the last block needs none, the next
      // iteration starts with one.
      if (block_lo > tables.col_lo) {
        op->Apply(qx, qs, &sx, &ss);
        sx += in.creep_x;
        ss += in.creep_s;
      }
    }
    // The accelerated next iterate (the next iteration starts with its exact slip).
    gather(&x_next);
    mixer.Mix(x_start, &x_next);
    for (int t = 0; t < n_loaded; ++t) {
      qx[loaded[t]] = x_next[t];
      qs[loaded[t]] = x_next[n_loaded + t];
    }
  }

  // 3. Results from the last exact slip (sx, ss are w + B q for the returned q).
  sol.iterations = iteration;
  sol.status = converged ? SolverStatus::kConverged : SolverStatus::kNotConverged;
  {
    std::ostringstream msg;
    msg << (converged ? "converged" : "not converged") << " after " << iteration
        << " iterations; largest local traction change " << residual << " Pa (threshold "
        << threshold << " Pa)";
    sol.message = msg.str();
  }
  CollectExactResults(grid, tables, pressure_Pa, in, sx, ss, &sol);
  return sol;
}

}  // namespace
}  // namespace railwear
