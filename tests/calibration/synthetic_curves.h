// Test helper: displacement curves generated from eq. 4 with known constants
// (SeedKernelDisplacement), plus Gaussian noise and a constant offset per curve, both relative to
// the curve's RMS: the data of the calibration's recovery tests (wear and CLI).
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "calibration/displacement_curves.h"

namespace railwear::testing {

struct SyntheticCurveSpec {
  CurveBody body = CurveBody::kConvex;
  double radius_mm = 15.0;
  std::vector<std::pair<CurveLoad, CurvePath>> curves = {
      {CurveLoad::kNormal, CurvePath::kArc},
      {CurveLoad::kNormal, CurvePath::kAxis},
      {CurveLoad::kCircumferential, CurvePath::kArc},
      {CurveLoad::kAxial, CurvePath::kAxis}};
  double distance_min_mm = 0.5;
  double distance_max_mm = 20.0;
  double distance_step_mm = 0.5;
  double noise = 0.0;   // standard deviation per point, relative to the curve's RMS
  double offset = 0.0;  // added to every point of a curve, relative to its RMS
};

// Standard normal deviates by Box-Muller from std::mt19937's raw output: unlike
// std::normal_distribution, the same on every standard library, so that generated files can be
// compared with committed ones (examples/calibration).
class PortableGauss {
 public:
  explicit PortableGauss(unsigned seed) : rng_(seed) {}
  double operator()() {
    if (have_spare_) {
      have_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(rng_()) + 0.5) / 4294967296.0;
    const double u2 = (static_cast<double>(rng_()) + 0.5) / 4294967296.0;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    have_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937 rng_;
  bool have_spare_ = false;
  double spare_ = 0.0;
};

// The noise comes from PortableGauss(seed).
inline DisplacementCurves MakeSyntheticCurves(const InfluenceConstants& truth,
                                              const SyntheticCurveSpec& spec, unsigned seed = 1,
                                              const std::string& path = "") {
  PortableGauss gauss(seed);
  DisplacementCurves out;
  out.path = path;
  out.body = spec.body;
  out.radius_m = spec.body == CurveBody::kFlat ? 0.0 : spec.radius_mm * 1e-3;
  out.material.youngs_modulus_Pa = 210e9;
  out.material.poisson_ratio = 0.28;
  out.metadata = {{"source", "synthetic: eq. 4 with known constants, noise and offset"}};
  for (const auto& [load, curve_path] : spec.curves) {
    std::vector<DisplacementPoint> points;
    double sum = 0.0;
    const int n =
        static_cast<int>(std::floor(
            (spec.distance_max_mm - spec.distance_min_mm) / spec.distance_step_mm + 1e-9)) +
        1;
    for (int i = 0; i < n; ++i) {
      DisplacementPoint p;
      p.load = load;
      p.path = curve_path;
      p.distance_m = (spec.distance_min_mm + i * spec.distance_step_mm) * 1e-3;
      p.w_m_per_N = SeedKernelDisplacement(truth, out.body, out.radius_m, out.material, load,
                                           curve_path, p.distance_m);
      sum += p.w_m_per_N * p.w_m_per_N;
      points.push_back(p);
    }
    const double rms = std::sqrt(sum / n);
    for (DisplacementPoint& p : points) {
      p.w_m_per_N += spec.offset * rms;
      if (spec.noise > 0.0) p.w_m_per_N += spec.noise * rms * gauss();
      out.points.push_back(p);
    }
  }
  return out;
}

}  // namespace railwear::testing
