// Kalker's creep-coefficient table (reference README §4) and its interpolation.
#include "core/contact/kalker_coefficients.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace railwear {
namespace {

constexpr int kRows = 19;      // a/b = 0.1 ... 1.0, then b/a = 0.9 ... 0.1
constexpr double kStep = 0.1;  // spacing of the rows in the abscissa u
constexpr double kUMin = -0.9;

// Kalker (1990) Table E.3, as printed in reference README §4. Each entry: nu = 0, 0.25, 0.5.
using Row = std::array<double, 3>;
constexpr std::array<Row, kRows> kC11 = {{
    {2.51, 3.31, 4.85}, {2.59, 3.37, 4.81}, {2.68, 3.44, 4.80}, {2.78, 3.53, 4.82},
    {2.88, 3.62, 4.83}, {2.98, 3.72, 4.91}, {3.09, 3.81, 4.97}, {3.19, 3.91, 5.05},
    {3.29, 4.01, 5.12}, {3.40, 4.12, 5.20}, {3.51, 4.22, 5.30}, {3.65, 4.36, 5.42},
    {3.82, 4.54, 5.58}, {4.06, 4.78, 5.80}, {4.37, 5.10, 6.11}, {4.84, 5.57, 6.57},
    {5.57, 6.34, 7.34}, {6.96, 7.78, 8.82}, {10.7, 11.7, 12.9},
}};
constexpr std::array<Row, kRows> kC22 = {{
    {2.51, 2.52, 2.53}, {2.59, 2.63, 2.66}, {2.68, 2.75, 2.81}, {2.78, 2.88, 2.98},
    {2.88, 3.01, 3.14}, {2.98, 3.14, 3.31}, {3.09, 3.28, 3.48}, {3.19, 3.41, 3.65},
    {3.29, 3.54, 3.82}, {3.40, 3.67, 3.98}, {3.51, 3.81, 4.16}, {3.65, 3.99, 4.39},
    {3.82, 4.21, 4.67}, {4.06, 4.50, 5.04}, {4.37, 4.90, 5.56}, {4.84, 5.48, 6.31},
    {5.57, 6.40, 7.51}, {6.96, 8.14, 9.79}, {10.7, 12.8, 16.0},
}};
constexpr std::array<Row, kRows> kC23 = {{
    {0.334, 0.473, 0.731}, {0.483, 0.603, 0.809}, {0.607, 0.715, 0.889}, {0.720, 0.823, 0.977},
    {0.827, 0.929, 1.07},  {0.930, 1.03, 1.18},   {1.03, 1.14, 1.29},    {1.13, 1.25, 1.40},
    {1.23, 1.36, 1.51},    {1.33, 1.47, 1.63},    {1.44, 1.59, 1.77},    {1.58, 1.75, 1.94},
    {1.76, 1.95, 2.18},    {2.01, 2.23, 2.50},    {2.35, 2.62, 2.96},    {2.88, 3.24, 3.70},
    {3.79, 4.32, 5.01},    {5.72, 6.63, 7.89},    {12.2, 14.6, 18.0},
}};

// Fritsch-Carlson slopes of equally spaced data y (spacing h), then the cubic Hermite value
// at row r + t (t in [0, 1]).
double MonotoneCubic(const std::array<double, kRows>& y, int r, double t) {
  auto secant = [&](int k) { return (y[k + 1] - y[k]) / kStep; };
  auto slope = [&](int k) {
    if (k == 0) return secant(0);
    if (k == kRows - 1) return secant(kRows - 2);
    const double d0 = secant(k - 1), d1 = secant(k);
    if (d0 * d1 <= 0.0) return 0.0;
    return 2.0 / (1.0 / d0 + 1.0 / d1);  // harmonic mean: keeps the cubic monotone
  };
  const double m0 = slope(r) * kStep, m1 = slope(r + 1) * kStep;
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y[r] + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * y[r + 1] +
         (t3 - t2) * m1;
}

double Interpolate(const std::array<Row, kRows>& table, int r, double t, double nu) {
  std::array<double, 3> at_nu{};
  for (int c = 0; c < 3; ++c) {
    std::array<double, kRows> column{};
    for (int k = 0; k < kRows; ++k) column[k] = table[k][c];
    at_nu[c] = MonotoneCubic(column, r, t);
  }
  // Quadratic (Lagrange) through nu = 0, 0.25, 0.5.
  const double n0 = 0.0, n1 = 0.25, n2 = 0.5;
  const double l0 = (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2));
  const double l1 = (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2));
  const double l2 = (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1));
  return l0 * at_nu[0] + l1 * at_nu[1] + l2 * at_nu[2];
}

}  // namespace

CreepCoefficients KalkerCoefficients(double a_over_b_along_x, double nu) {
  if (!std::isfinite(a_over_b_along_x) || a_over_b_along_x <= 0.0) {
    throw std::invalid_argument("KalkerCoefficients: a/b = " + std::to_string(a_over_b_along_x) +
                                ", expected a finite ratio > 0");
  }
  if (!std::isfinite(nu) || nu < 0.0 || nu > 0.5) {
    throw std::invalid_argument("KalkerCoefficients: nu = " + std::to_string(nu) +
                                ", expected a Poisson ratio in [0, 0.5]");
  }
  const double r = std::clamp(a_over_b_along_x, 0.1, 10.0);
  const double u = r <= 1.0 ? r - 1.0 : 1.0 - 1.0 / r;
  const double pos = (u - kUMin) / kStep;  // in [0, kRows - 1]
  const int row = std::clamp(static_cast<int>(std::floor(pos)), 0, kRows - 2);
  const double t = std::clamp(pos - row, 0.0, 1.0);
  return {Interpolate(kC11, row, t, nu), Interpolate(kC22, row, t, nu),
          Interpolate(kC23, row, t, nu)};
}

LinearCreepForces CalcLinearCreepForces(double a_m, double b_m, double shear_modulus_Pa, double nu,
                                        double xi, double eta, double phi_per_m) {
  if (!(a_m > 0.0) || !(b_m > 0.0) || !std::isfinite(a_m) || !std::isfinite(b_m)) {
    throw std::invalid_argument("CalcLinearCreepForces: semi-axes a = " + std::to_string(a_m) +
                                " m, b = " + std::to_string(b_m) + " m, expected finite > 0");
  }
  if (!(shear_modulus_Pa > 0.0) || !std::isfinite(shear_modulus_Pa)) {
    throw std::invalid_argument("CalcLinearCreepForces: G = " + std::to_string(shear_modulus_Pa) +
                                " Pa, expected finite > 0");
  }
  const CreepCoefficients cc = KalkerCoefficients(a_m / b_m, nu);
  const double c = std::sqrt(a_m * b_m);
  const double g = shear_modulus_Pa;
  return {-g * c * c * cc.c11 * xi, -g * c * c * cc.c22 * eta - g * c * c * c * cc.c23 * phi_per_m};
}

}  // namespace railwear
