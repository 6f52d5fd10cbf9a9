// FFTW plans under one planner mutex, and the padded 2-D convolution transforms (fftw.h).
#include "core/numerics/fftw.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "core/numerics/fft_size.h"
#include "core/numerics/mru_cache.h"

namespace railwear::internal {

std::mutex& FftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

FftwPlan& FftwPlan::operator=(FftwPlan&& other) noexcept {
  if (this != &other) {
    Reset();
    plan_ = other.plan_;
    other.plan_ = nullptr;
  }
  return *this;
}

void FftwPlan::Reset() {
  if (plan_ == nullptr) return;
  std::lock_guard<std::mutex> lock(FftwPlannerMutex());
  fftw_destroy_plan(plan_);
  plan_ = nullptr;
}

SharedFftwPlan SharedPlan(std::initializer_list<long> description,
                          const std::function<fftw_plan()>& make) {
  // The cache's mutex is never held while the planner's is taken: plans are made outside it and
  // evicted ones released after it (MruCache).
  static MruCache<std::vector<long>, FftwPlan> cache(kSharedFftwPlans);
  return cache.Get(
      [&](const std::vector<long>& kept) {
        return std::equal(kept.begin(), kept.end(), description.begin(), description.end());
      },
      [&] { return std::vector<long>(description); },
      [&] { return std::make_shared<const FftwPlan>(FftwPlan::Make(make)); });
}

PaddedFft2d::PaddedFft2d(int nx, int ns)
    : PaddedFft2d(nx, ns, RealFftSize(nx), ComplexFftSize(ns)) {}

PaddedFft2d::PaddedFft2d(int nx, int ns, int x_period, int s_period)
    : nx_(nx),
      ns_(ns),
      lx_(x_period),
      hx_(lx_ / 2 + 1),
      ls_(s_period),
      padded_in_(static_cast<size_t>(ns) * lx_),
      padded_out_(static_cast<size_t>(ns) * lx_),
      x_spectrum_(spectrum_size()) {
  // Every transform runs through the new-array interface (the plans are shared, fftw.h); plan
  // them on buffers of the same alignment. The descriptions: a kind number, then the numbers
  // of the planner call. The spectra are x-major (fftw.h): the real transforms along x write
  // (read) bin kx of row j at kx * ls + j, so the complex transforms along s run on contiguous
  // columns. (Kinds 1-4 were the s-major layout's transforms until 2026-11-29.)
  RAILWEAR_CHECK(lx_ >= nx_ && lx_ % 2 == 0 && ls_ >= ns_);
  const int lx[] = {lx_}, ls[] = {ls_};
  std::optional<FftwBuffer<FftwComplex>> planning;
  auto planning_data = [&] {
    if (!planning) planning.emplace(spectrum_size());
    return AsFftw(planning->data());
  };
  x_forward_ = SharedPlan({11, lx_, ns_, ls_}, [&] {
    return fftw_plan_many_dft_r2c(1, lx, ns_, padded_in_.data(), nullptr, 1, lx_,
                                  AsFftw(x_spectrum_.data()), nullptr, ls_, 1, FFTW_ESTIMATE);
  });
  s_forward_ = SharedPlan({12, ls_, hx_}, [&] {
    return fftw_plan_many_dft(1, ls, hx_, AsFftw(x_spectrum_.data()), nullptr, 1, ls_,
                              planning_data(), nullptr, 1, ls_, FFTW_FORWARD, FFTW_ESTIMATE);
  });
  s_inverse_ = SharedPlan({13, ls_, hx_}, [&] {  // in place
    return fftw_plan_many_dft(1, ls, hx_, planning_data(), nullptr, 1, ls_, planning_data(),
                              nullptr, 1, ls_, FFTW_BACKWARD, FFTW_ESTIMATE);
  });
  x_inverse_ = SharedPlan({14, lx_, ns_, ls_}, [&] {
    return fftw_plan_many_dft_c2r(1, lx, ns_, planning_data(), nullptr, ls_, 1, padded_out_.data(),
                                  nullptr, 1, lx_, FFTW_ESTIMATE);
  });
}

void PaddedFft2d::ForwardGenerator(const double* g, FftwComplex* spectrum) const {
  FftwBuffer<double> generator(static_cast<size_t>(ls_) * lx_);
  std::copy(g, g + generator.size(), generator.data());
  // FFTW's 2-D real transform (s-major output, planned on a buffer of its own: the one it
  // runs on has the same alignment), transposed into the x-major layout: the same values.
  FftwBuffer<FftwComplex> s_major = NewSpectrum();
  const SharedFftwPlan plan = SharedPlan({5, ls_, lx_}, [&] {
    FftwBuffer<FftwComplex> planning = NewSpectrum();
    return fftw_plan_dft_r2c_2d(ls_, lx_, generator.data(), AsFftw(planning.data()),
                                FFTW_ESTIMATE);
  });
  fftw_execute_dft_r2c(plan->get(), generator.data(), AsFftw(s_major.data()));
  for (int kx = 0; kx < hx_; ++kx) {
    for (int ks = 0; ks < ls_; ++ks) {
      spectrum[static_cast<size_t>(kx) * ls_ + ks] = s_major[static_cast<size_t>(ks) * hx_ + kx];
    }
  }
}

void PaddedFft2d::Forward(const double* in, FftwComplex* spectrum) const {
  for (int j = 0; j < ns_; ++j) {
    std::copy(in + static_cast<size_t>(j) * nx_, in + static_cast<size_t>(j + 1) * nx_,
              padded_in_.data() + static_cast<size_t>(j) * lx_);
  }
  fftw_execute_dft_r2c(x_forward_->get(), padded_in_.data(), AsFftw(x_spectrum_.data()));
  fftw_execute_dft(s_forward_->get(), AsFftw(x_spectrum_.data()), AsFftw(spectrum));
}

void PaddedFft2d::Inverse(FftwComplex* spectrum, double* out) const {
  fftw_execute_dft(s_inverse_->get(), AsFftw(spectrum), AsFftw(spectrum));
  fftw_execute_dft_c2r(x_inverse_->get(), AsFftw(spectrum), padded_out_.data());
  for (int j = 0; j < ns_; ++j) {
    const double* row = padded_out_.data() + static_cast<size_t>(j) * lx_;
    std::copy(row, row + nx_, out + static_cast<size_t>(j) * nx_);
  }
}

}  // namespace railwear::internal
