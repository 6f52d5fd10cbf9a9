// FFTW plans and buffers, shared by the FFT influence and rolling operators.
//
// Plans are made with FFTW_ESTIMATE only: the plan (and so every rounding error) depends on the
// transform sizes and on the buffers' alignment alone, so results are bit-reproducible from run
// to run (FFTW_MEASURE times candidate algorithms and may pick differently each run). Buffers
// come from fftw_malloc, which gives every buffer the same (SIMD) alignment: a plan made on one
// buffer may be executed on another with FFTW's new-array functions, and the plan never depends
// on where malloc happened to put a buffer.
//
// Threads: FFTW's planner is not thread-safe, so FftwPlan creates and destroys plans under one
// process-wide mutex. Executing a plan (fftw_execute_dft_r2c etc. on arrays of the caller's)
// is thread-safe, so operators built in different threads run concurrently.
//
// Shared plans (issue 18, set-up reuse): an FFTW_ESTIMATE plan is a function of the transform's
// description (kind, lengths, batch count, strides, distances, in place or not) and of the
// arrays' alignment alone, and every array here comes from fftw_malloc (one alignment; split
// arrays at an offset fixed by the description). So the operators take their plans from
// SharedPlan, a process-wide cache keyed by the whole description: a kept plan is the plan the
// planner would make again, and the transforms give the same results bit for bit. Planning was
// 3 % of the main job's CPU time, every influence operator planning its transforms anew. Users
// execute shared plans only through FFTW's new-array functions on arrays of their own.
#pragma once

#include <complex>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <memory>
#include <mutex>

#include <fftw3.h>

#include "core/numerics/check.h"

namespace railwear::internal {

using FftwComplex = std::complex<double>;  // layout-compatible with fftw_complex

// A zero-filled array of n values from fftw_malloc.
template <class T>
class FftwBuffer {
 public:
  FftwBuffer() = default;
  explicit FftwBuffer(size_t n)
      : data_(static_cast<T*>(fftw_malloc(sizeof(T) * (n > 0 ? n : 1)))), size_(n) {
    RAILWEAR_CHECK(data_ != nullptr);
    for (size_t k = 0; k < n; ++k) data_[k] = T(0);
  }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  size_t size() const { return size_; }
  T& operator[](size_t k) { return data_[k]; }
  const T& operator[](size_t k) const { return data_[k]; }

 private:
  struct Free {
    void operator()(T* p) const { fftw_free(p); }
  };
  std::unique_ptr<T[], Free> data_;
  size_t size_ = 0;
};

inline fftw_complex* AsFftw(FftwComplex* p) { return reinterpret_cast<fftw_complex*>(p); }

// The mutex around FFTW's planner (plan creation and destruction).
std::mutex& FftwPlannerMutex();

// An owned fftw_plan.
class FftwPlan {
 public:
  FftwPlan() = default;
  // Calls make() (returning an fftw_plan) under the planner mutex. A null plan (FFTW cannot
  // plan the transform) is a bug and aborts.
  template <class MakePlan>
  static FftwPlan Make(MakePlan make) {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    FftwPlan plan;
    plan.plan_ = make();
    RAILWEAR_CHECK(plan.plan_ != nullptr);
    return plan;
  }
  FftwPlan(FftwPlan&& other) noexcept : plan_(other.plan_) { other.plan_ = nullptr; }
  FftwPlan& operator=(FftwPlan&& other) noexcept;
  FftwPlan(const FftwPlan&) = delete;
  FftwPlan& operator=(const FftwPlan&) = delete;
  ~FftwPlan() { Reset(); }
  fftw_plan get() const { return plan_; }

 private:
  void Reset();
  fftw_plan plan_ = nullptr;
};

// A plan shared by every user of the same transform description (above); immutable.
using SharedFftwPlan = std::shared_ptr<const FftwPlan>;

// Plans kept by SharedPlan: the most recently used ones (a plan holds a few kB to a few hundred
// kB of twiddle factors; a wear step's patches need some tens of distinct sizes).
inline constexpr size_t kSharedFftwPlans = 96;

// The kept plan for `description` (every number the planner call takes, with a distinct first
// number per kind of call), else the plan of make() (called under the planner mutex, as
// FftwPlan::Make), kept as the most recently used. Thread-safe.
SharedFftwPlan SharedPlan(std::initializer_list<long> description,
                          const std::function<fftw_plan()>& make);

// Linear 2-D convolutions on an nx by ns grid (x fastest) by zero-padded real FFTs: the field is
// padded to lx = RealFftSize(nx) by ls = ComplexFftSize(ns) and transformed to the half spectrum
// of hx = lx/2 + 1 by ls complex bins, stored x-major (bin (kx, ks) at kx * ls + ks). Batched
// 1-D transforms (real along x over the ns rows that hold data, complex along s over the hx
// columns), so the padding rows are never transformed. The real transforms write (read) their
// bins straight into (from) the x-major columns (FFTW's strided output and input), so the
// complex transforms along s run on contiguous columns of ls bins: 0.7-0.85x the time of the
// s-major layout (ks * hx + kx, FFTW's own 2-D r2c layout, used until 2026-11-29), whose s
// transforms ran along columns strided by hx bins (docs/speed.md, "The padded FFT's layout").
// Callers only multiply spectra bin by bin, so the layout is theirs to ignore.
// Transforms are unscaled: Inverse(Forward(f)) = lx ls f.
// Not for concurrent use of one object (it keeps its padding buffers); one per operator.
class PaddedFft2d {
 public:
  PaddedFft2d(int nx, int ns);
  // Periods of the caller's: lx >= nx even, ls >= ns (lx >= 2 nx - 1 and ls >= 2 ns - 1 for a
  // linear convolution; shorter ones give a periodic one).
  PaddedFft2d(int nx, int ns, int lx, int ls);
  int lx() const { return lx_; }
  int hx() const { return hx_; }
  int ls() const { return ls_; }
  size_t spectrum_size() const { return static_cast<size_t>(hx_) * ls_; }
  // A zeroed spectrum buffer [hx * ls] of the alignment the plans expect.
  FftwBuffer<FftwComplex> NewSpectrum() const { return FftwBuffer<FftwComplex>(spectrum_size()); }
  // spectrum = FFT2 of an lx by ls periodic generator g [ls * lx], x fastest (construction time).
  void ForwardGenerator(const double* g, FftwComplex* spectrum) const;
  // spectrum = FFT2 of the field in [ns * nx] (x fastest), zero-padded. spectrum: from
  // NewSpectrum().
  void Forward(const double* in, FftwComplex* spectrum) const;
  // out [ns * nx] = the nx by ns corner of the inverse FFT2 of spectrum (which it overwrites).
  void Inverse(FftwComplex* spectrum, double* out) const;
  // True when both use the same shared plans (for tests of the sharing).
  bool SharesPlansWith(const PaddedFft2d& other) const {
    return x_forward_ == other.x_forward_ && s_forward_ == other.s_forward_ &&
           s_inverse_ == other.s_inverse_ && x_inverse_ == other.x_inverse_;
  }

 private:
  int nx_, ns_, lx_, hx_, ls_;
  mutable FftwBuffer<double> padded_in_;        // [ns * lx], entries x >= nx stay zero
  mutable FftwBuffer<double> padded_out_;       // [ns * lx]
  mutable FftwBuffer<FftwComplex> x_spectrum_;  // [ls * hx], rows ks >= ns stay zero
  SharedFftwPlan x_forward_, s_forward_, s_inverse_, x_inverse_;
};

}  // namespace railwear::internal
