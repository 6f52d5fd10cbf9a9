// FFTW wrapper (core/numerics/fftw.h) and FFT lengths (core/numerics/fft_size.h): the padded
// transforms against a naive linear convolution, bit-reproducible plans, plans made from several
// threads at once, and the lengths' properties against a naive search.
#include "core/numerics/fftw.h"

#include <array>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/numerics/fft_size.h"

namespace railwear::internal {
namespace {

// Relative error of an FFT convolution against the direct sum: a few ulps times log2(lx ls)
// growth, far above double rounding (1e-16) and far below any indexing or padding error (O(1)).
constexpr double kConvolutionTolerance = 1e-13;

std::vector<double> RandomField(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> f(n);
  for (double& v : f) v = value(rng);
  return f;
}

// out = crop(IFFT2(FFT2(generator) * FFT2(pad(in)))) / (lx ls): the product the influence
// operators make, on fft's own lengths.
std::vector<double> SpectralProduct(const PaddedFft2d& fft, const std::vector<double>& generator,
                                    const std::vector<double>& in) {
  FftwBuffer<FftwComplex> g_hat = fft.NewSpectrum(), f_hat = fft.NewSpectrum();
  fft.ForwardGenerator(generator.data(), g_hat.data());
  fft.Forward(in.data(), f_hat.data());
  const double n = static_cast<double>(fft.lx()) * fft.ls();
  for (size_t b = 0; b < f_hat.size(); ++b) f_hat[b] *= g_hat[b] / n;
  std::vector<double> out(in.size());
  fft.Inverse(f_hat.data(), out.data());
  return out;
}

// Expects out (nx x ns, x fastest) within kConvolutionTolerance of the direct sum
// sum_j k(ix, jx, is, js) in_j, relative to its largest value.
template <class Kernel>
void ExpectDirectSum(int nx, int ns, const std::vector<double>& in, const std::vector<double>& out,
                     Kernel k) {
  double scale = 0.0, error = 0.0;
  for (int is = 0; is < ns; ++is) {
    for (int ix = 0; ix < nx; ++ix) {
      double direct = 0.0;
      for (int js = 0; js < ns; ++js) {
        for (int jx = 0; jx < nx; ++jx) direct += k(ix, jx, is, js) * in[js * nx + jx];
      }
      scale = std::max(scale, std::abs(direct));
      error = std::max(error, std::abs(direct - out[is * nx + ix]));
    }
  }
  EXPECT_LE(error, kConvolutionTolerance * scale) << nx << " x " << ns;
}

// The padded product with the kernel k(d, e) wrapped into the generator, against the linear
// convolution sum_j k(ix - jx, is - js) in_j.
void ExpectLinearConvolution(int nx, int ns) {
  const PaddedFft2d fft(nx, ns);
  const int lx = fft.lx(), ls = fft.ls();
  ASSERT_GE(lx, 2 * nx - 1);
  ASSERT_GE(ls, 2 * ns - 1);
  const std::vector<double> kernel = RandomField((2 * nx - 1) * (2 * ns - 1), 3);
  auto k = [&](int d, int e) { return kernel[(e + ns - 1) * (2 * nx - 1) + d + nx - 1]; };
  std::vector<double> generator(static_cast<size_t>(lx) * ls, 0.0);
  for (int e = -(ns - 1); e < ns; ++e) {
    for (int d = -(nx - 1); d < nx; ++d) generator[((e + ls) % ls) * lx + (d + lx) % lx] = k(d, e);
  }
  const std::vector<double> in = RandomField(nx * ns, 5);
  ExpectDirectSum(nx, ns, in, SpectralProduct(fft, generator, in),
                  [&](int ix, int jx, int is, int js) { return k(ix - jx, is - js); });
}

// Fills the shared-plan cache with other transforms, so that the next transform of any earlier
// size is planned anew.
void EvictSharedPlans() {
  for (int ns = 100; ns < 100 + static_cast<int>(kSharedFftwPlans); ++ns) PaddedFft2d(2, ns);
}

TEST(PaddedFft2d, IsALinearConvolution) {
  for (auto [nx, ns] : {std::pair{1, 1}, {1, 6}, {6, 1}, {7, 5}, {11, 11}, {16, 9}}) {
    ExpectLinearConvolution(nx, ns);
  }
}

// With the caller's periods px >= nx (even), ps >= ns (the half-space preconditioner's, shorter
// than 2n - 1): the convolution wraps, out_i = sum_j g((ix - jx) mod px, (is - js) mod ps) in_j,
// against that periodic sum for a random generator on the whole period.
TEST(PaddedFft2d, CallersPeriodsGiveThePeriodicConvolution) {
  for (auto [nx, ns, px, ps] :
       {std::array{1, 1, 2, 1}, {7, 5, 8, 5}, {11, 13, 12, 14}, {6, 9, 10, 15}, {10, 4, 20, 7}}) {
    const PaddedFft2d fft(nx, ns, px, ps);
    ASSERT_EQ(fft.lx(), px);
    ASSERT_EQ(fft.ls(), ps);
    const std::vector<double> generator = RandomField(px * ps, 7);
    const std::vector<double> in = RandomField(nx * ns, 9);
    SCOPED_TRACE(testing::Message() << "periods " << px << " x " << ps);
    ExpectDirectSum(nx, ns, in, SpectralProduct(fft, generator, in),
                    [&](int ix, int jx, int is, int js) {
                      return generator[((is - js + ps) % ps) * px + (ix - jx + px) % px];
                    });
  }
}

// The spectrum's layout (x-major, bin (kx, ks) at kx * ls + ks) against the 2-D DFT summed
// directly, for Forward (the batched strided transforms) and ForwardGenerator (FFTW's 2-D
// transform, transposed): callers multiply the two bin by bin, so both must use it.
TEST(PaddedFft2d, SpectraAreXMajorFromBothTransforms) {
  constexpr double kPi = 3.14159265358979323846;
  const int nx = 5, ns = 4;
  const PaddedFft2d fft(nx, ns);
  const int lx = fft.lx(), hx = fft.hx(), ls = fft.ls();
  ASSERT_NE(lx, ls);  // a transposed layout would not pass unnoticed
  const std::vector<double> in = RandomField(nx * ns, 7);
  std::vector<double> padded(static_cast<size_t>(lx) * ls, 0.0);
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) padded[static_cast<size_t>(j) * lx + i] = in[j * nx + i];
  }
  FftwBuffer<FftwComplex> forward = fft.NewSpectrum(), generator = fft.NewSpectrum();
  fft.Forward(in.data(), forward.data());
  fft.ForwardGenerator(padded.data(), generator.data());
  double scale = 0.0;
  for (double v : in) scale += std::abs(v);
  for (int kx = 0; kx < hx; ++kx) {
    for (int ks = 0; ks < ls; ++ks) {
      FftwComplex direct = 0.0;
      for (int j = 0; j < ns; ++j) {
        for (int i = 0; i < nx; ++i) {
          const double phase =
              -2.0 * kPi * (static_cast<double>(kx) * i / lx + static_cast<double>(ks) * j / ls);
          direct += in[j * nx + i] * FftwComplex(std::cos(phase), std::sin(phase));
        }
      }
      const size_t bin = static_cast<size_t>(kx) * ls + ks;
      EXPECT_LE(std::abs(forward[bin] - direct), kConvolutionTolerance * scale) << kx << ", " << ks;
      EXPECT_LE(std::abs(generator[bin] - direct), kConvolutionTolerance * scale)
          << kx << ", " << ks;
    }
  }
}

TEST(PaddedFft2d, ReusedAndRebuiltTransformsAreBitIdentical) {
  const int nx = 23, ns = 17;
  const std::vector<double> in = RandomField(nx * ns, 7);
  auto round_trip = [&](const PaddedFft2d& fft) {
    FftwBuffer<FftwComplex> hat = fft.NewSpectrum();
    fft.Forward(in.data(), hat.data());
    std::vector<double> out(nx * ns);
    fft.Inverse(hat.data(), out.data());
    return out;
  };
  const PaddedFft2d fft(nx, ns);
  const std::vector<double> first = round_trip(fft);
  EXPECT_EQ(round_trip(fft), first);  // reused plans and buffers
  const PaddedFft2d sharing(nx, ns);
  EXPECT_TRUE(sharing.SharesPlansWith(fft));
  EXPECT_EQ(round_trip(sharing), first);  // shared plans, buffers of its own
  EvictSharedPlans();
  const PaddedFft2d planned_again(nx, ns);
  EXPECT_FALSE(planned_again.SharesPlansWith(fft));
  EXPECT_EQ(round_trip(planned_again), first);  // plans made again
  for (int k = 0; k < nx * ns; ++k) {
    EXPECT_NEAR(first[k], fft.lx() * fft.ls() * in[k], 1e-12 * fft.lx() * fft.ls());
  }
}

TEST(PaddedFft2d, PlansMadeInSeveralThreadsAtOnceGiveTheSameResults) {
  // Four threads each plan and run their own transforms of several sizes at the same time
  // (planning goes through the planner mutex; execution is concurrent; the plans are shared
  // through SharedPlan's cache, which one thread empties on the way).
  const std::vector<double> in = RandomField(40 * 30, 11);
  auto run = [&](int nx, int ns) {
    const PaddedFft2d fft(nx, ns);
    FftwBuffer<FftwComplex> hat = fft.NewSpectrum();
    fft.Forward(in.data(), hat.data());
    std::vector<double> out(nx * ns);
    fft.Inverse(hat.data(), out.data());
    return out;
  };
  const std::vector<std::pair<int, int>> sizes = {{40, 30}, {13, 29}, {32, 8}, {21, 21}};
  std::vector<std::vector<double>> expected;
  for (auto [nx, ns] : sizes) expected.push_back(run(nx, ns));
  std::vector<std::vector<std::vector<double>>> got(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int repeat = 0; repeat < 5; ++repeat) {
        if (t == 3 && repeat == 2) EvictSharedPlans();  // the others' shared plans meanwhile
        for (auto [nx, ns] : sizes) got[t].push_back(run(nx, ns));
      }
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < 4; ++t) {
    ASSERT_EQ(got[t].size(), 5 * sizes.size());
    for (size_t k = 0; k < got[t].size(); ++k) EXPECT_EQ(got[t][k], expected[k % sizes.size()]);
  }
}

// Issue 18: plans are shared by transforms of the same description only, and a plan kept by
// its users outlives its eviction from the cache.
TEST(SharedFftwPlan, SharedOnlyForTheSameTransform) {
  const PaddedFft2d a(23, 17);
  EXPECT_TRUE(PaddedFft2d(23, 17).SharesPlansWith(a));
  // The same padded lengths (lx 48 for 23 and 24 cells): the same transforms, shared.
  ASSERT_EQ(PaddedFft2d(24, 17).lx(), a.lx());
  EXPECT_TRUE(PaddedFft2d(24, 17).SharesPlansWith(a));
  EXPECT_FALSE(PaddedFft2d(30, 17).SharesPlansWith(a));  // another lx
  EXPECT_FALSE(PaddedFft2d(23, 16).SharesPlansWith(a));  // another number of rows
  // Several descriptions of one kind differ in every number.
  int made = 0;
  auto make = [&] {
    ++made;
    static double in[8], out[10];
    return fftw_plan_dft_r2c_1d(8, in, reinterpret_cast<fftw_complex*>(out), FFTW_ESTIMATE);
  };
  const SharedFftwPlan p = SharedPlan({900, 8}, make);
  EXPECT_EQ(SharedPlan({900, 8}, make), p);
  EXPECT_NE(SharedPlan({900, 8, 0}, make), p);
  EXPECT_NE(SharedPlan({901, 8}, make), p);
  EXPECT_EQ(made, 3);
  // Evicted, still usable by its holder.
  const std::vector<double> in = RandomField(23 * 17, 2);
  FftwBuffer<FftwComplex> before = a.NewSpectrum(), after = a.NewSpectrum();
  a.Forward(in.data(), before.data());
  EvictSharedPlans();
  EXPECT_NE(SharedPlan({900, 8}, make), p);
  a.Forward(in.data(), after.data());
  for (size_t k = 0; k < before.size(); ++k) ASSERT_EQ(before[k], after[k]);
}

bool IsSevenSmooth(int l) {
  for (int p : {2, 3, 5, 7}) {
    while (l % p == 0) l /= p;
  }
  return l == 1;
}

TEST(FftSize, IsTheSmallestSevenSmoothLengthThatFits) {
  for (int cells = 1; cells <= 700; ++cells) {
    const int real = RealFftSize(cells), complex = ComplexFftSize(cells);
    EXPECT_TRUE(IsSevenSmooth(real) && real % 2 == 0 && real >= 2 * cells - 1) << cells;
    EXPECT_TRUE(IsSevenSmooth(complex) && complex >= std::max(2, 2 * cells - 1)) << cells;
    for (int l = std::max(2, 2 * cells - 1); l < real; ++l) {
      EXPECT_FALSE(IsSevenSmooth(l) && l % 2 == 0) << cells << ": " << l << " < " << real;
    }
    for (int l = std::max(2, 2 * cells - 1); l < complex; ++l) {
      EXPECT_FALSE(IsSevenSmooth(l)) << cells << ": " << l << " < " << complex;
    }
  }
  EXPECT_EQ(RealFftSize(70), 140);     // 139 -> 2^2 5 7 (kissfft's old length: 144)
  EXPECT_EQ(ComplexFftSize(81), 162);  // 161 = 7 23 -> 2 3^4
}

}  // namespace
}  // namespace railwear::internal
