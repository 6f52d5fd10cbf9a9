// FFTW plans under one planner mutex, and the padded 2-D convolution transforms (fftw.h).
#include "core/numerics/fftw.h"

#include <algorithm>

#include "core/numerics/fft_size.h"

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

PaddedFft2d::PaddedFft2d(int nx, int ns)
    : nx_(nx),
      ns_(ns),
      lx_(RealFftSize(nx)),
      hx_(lx_ / 2 + 1),
      ls_(ComplexFftSize(ns)),
      padded_in_(static_cast<size_t>(ns) * lx_),
      padded_out_(static_cast<size_t>(ns) * lx_),
      x_spectrum_(spectrum_size()) {
  // The s transforms run on the caller's spectra through the new-array interface; plan them on
  // a buffer of the same alignment.
  FftwBuffer<FftwComplex> planning = NewSpectrum();
  const int lx[] = {lx_}, ls[] = {ls_};
  x_forward_ = FftwPlan::Make([&] {
    return fftw_plan_many_dft_r2c(1, lx, ns_, padded_in_.data(), nullptr, 1, lx_,
                                  AsFftw(x_spectrum_.data()), nullptr, 1, hx_, FFTW_ESTIMATE);
  });
  s_forward_ = FftwPlan::Make([&] {
    return fftw_plan_many_dft(1, ls, hx_, AsFftw(x_spectrum_.data()), nullptr, hx_, 1,
                              AsFftw(planning.data()), nullptr, hx_, 1, FFTW_FORWARD,
                              FFTW_ESTIMATE);
  });
  s_inverse_ = FftwPlan::Make([&] {  // in place
    return fftw_plan_many_dft(1, ls, hx_, AsFftw(planning.data()), nullptr, hx_, 1,
                              AsFftw(planning.data()), nullptr, hx_, 1, FFTW_BACKWARD,
                              FFTW_ESTIMATE);
  });
  x_inverse_ = FftwPlan::Make([&] {
    return fftw_plan_many_dft_c2r(1, lx, ns_, AsFftw(planning.data()), nullptr, 1, hx_,
                                  padded_out_.data(), nullptr, 1, lx_, FFTW_ESTIMATE);
  });
}

void PaddedFft2d::ForwardGenerator(const double* g, FftwComplex* spectrum) const {
  FftwBuffer<double> generator(static_cast<size_t>(ls_) * lx_);
  std::copy(g, g + generator.size(), generator.data());
  const FftwPlan plan = FftwPlan::Make([&] {
    return fftw_plan_dft_r2c_2d(ls_, lx_, generator.data(), AsFftw(spectrum), FFTW_ESTIMATE);
  });
  fftw_execute(plan.get());
}

void PaddedFft2d::Forward(const double* in, FftwComplex* spectrum) const {
  for (int j = 0; j < ns_; ++j) {
    std::copy(in + static_cast<size_t>(j) * nx_, in + static_cast<size_t>(j + 1) * nx_,
              padded_in_.data() + static_cast<size_t>(j) * lx_);
  }
  fftw_execute_dft_r2c(x_forward_.get(), padded_in_.data(), AsFftw(x_spectrum_.data()));
  fftw_execute_dft(s_forward_.get(), AsFftw(x_spectrum_.data()), AsFftw(spectrum));
}

void PaddedFft2d::Inverse(FftwComplex* spectrum, double* out) const {
  fftw_execute_dft(s_inverse_.get(), AsFftw(spectrum), AsFftw(spectrum));
  fftw_execute_dft_c2r(x_inverse_.get(), AsFftw(spectrum), padded_out_.data());
  for (int j = 0; j < ns_; ++j) {
    const double* row = padded_out_.data() + static_cast<size_t>(j) * lx_;
    std::copy(row, row + nx_, out + static_cast<size_t>(j) * nx_);
  }
}

}  // namespace railwear::internal
