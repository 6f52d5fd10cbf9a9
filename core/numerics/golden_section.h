// Golden-section minimisation of a unimodal function on an interval (the first-contact search of
// core/geometry/wheel_rail_geometry.cpp and the fast tread path, core/contact/hertz_tread.cpp).
#pragma once

#include <cmath>

namespace railwear {

// The minimiser of f on [a, b] to the absolute tolerance tol (> 0): the midpoint of the last
// bracket. f is evaluated about log(tol / (b - a)) / log(0.618) + 2 times.
template <typename F>
double GoldenMinimise(F&& f, double a, double b, double tol) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - r * (b - a), d = a + r * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > tol) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace railwear
