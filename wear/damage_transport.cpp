// Damage carried with the material through a wear step; see damage_transport.h.
#include "wear/damage_transport.h"

#include <algorithm>
#include <cmath>

#include "core/numerics/check.h"

namespace railwear {
namespace {

// Linear interpolation of the knots (x, y) at v, clamped to the ends; x increasing.
double Interpolate(const std::vector<double>& x, const std::vector<double>& y, double v) {
  if (v <= x.front()) return y.front();
  if (v >= x.back()) return y.back();
  const size_t k = std::upper_bound(x.begin(), x.end(), v) - x.begin();  // x[k-1] <= v < x[k]
  const double u = (v - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + u * (y[k] - y[k - 1]);
}

}  // namespace

double MaterialMap::ToNext(double s) const { return Interpolate(s_m, t_m, s); }
double MaterialMap::ToPrevious(double t) const { return Interpolate(t_m, s_m, t); }

MaterialMap IdentityMaterialMap(double length_m) { return {{0.0, length_m}, {0.0, length_m}}; }

MaterialMap MaterialMapOfStep(const Profile& previous,
                              const std::vector<Eigen::Vector2d>& moved_points,
                              const Profile& moved, const Profile& next) {
  RAILWEAR_CHECK(static_cast<int>(moved_points.size()) == previous.size());
  // The moved curve's arc length u_i of each moved point (the Profile keeps every given point,
  // in order, and may insert subdivision points between them).
  std::vector<double> u(moved_points.size());
  int j = 0;
  for (size_t i = 0; i < moved_points.size(); ++i) {
    while (j < moved.size() && moved.points()[j] != moved_points[i]) ++j;
    RAILWEAR_CHECK(j < moved.size());
    u[i] = moved.KnotS(j);
  }
  // Resampling: next's point k is the moved curve at u = L_moved k / m, at next's arc length t_k.
  const int m = next.size() - 1;
  std::vector<double> u_of_k(m + 1), t_of_k(m + 1);
  for (int k = 0; k <= m; ++k) {
    u_of_k[k] = moved.Length() * k / m;
    t_of_k[k] = next.KnotS(k);
  }
  MaterialMap map;
  map.s_m.resize(u.size());
  map.t_m.resize(u.size());
  for (size_t i = 0; i < u.size(); ++i) {
    map.s_m[i] = previous.KnotS(static_cast<int>(i));
    map.t_m[i] = Interpolate(u_of_k, t_of_k, u[i]);
  }
  map.t_m.front() = 0.0;  // exact ends: the end points stay the end points
  map.t_m.back() = next.Length();
  for (size_t i = 1; i < u.size(); ++i) RAILWEAR_CHECK(map.t_m[i] > map.t_m[i - 1]);
  return map;
}

std::vector<double> MaterialBinLengths(const WearGrid& next_grid, double next_length_m,
                                       const MaterialMap& map) {
  std::vector<double> m(next_grid.n);
  for (int c = 0; c < next_grid.n; ++c) {
    const double lo = std::min(c * next_grid.h_m, next_length_m);
    const double hi = std::min((c + 1) * next_grid.h_m, next_length_m);
    m[c] = map.ToPrevious(hi) - map.ToPrevious(lo);
  }
  return m;
}

std::vector<double> RemapDamage(const std::vector<double>& damage, const WearGrid& previous_grid,
                                double previous_length_m, const WearGrid& next_grid,
                                double next_length_m, const MaterialMap& map) {
  const auto d = [&](int b) { return b < static_cast<int>(damage.size()) ? damage[b] : 0.0; };
  const double h = previous_grid.h_m;
  std::vector<double> out(next_grid.n, 0.0);
  for (int c = 0; c < next_grid.n; ++c) {
    const double t_lo = std::min(c * next_grid.h_m, next_length_m);
    const double t_hi = std::min((c + 1) * next_grid.h_m, next_length_m);
    const double s_lo = std::min(map.ToPrevious(t_lo), previous_length_m);
    const double s_hi = std::min(map.ToPrevious(t_hi), previous_length_m);
    const int first = std::clamp(static_cast<int>(std::floor(s_lo / h)), 0, previous_grid.n - 1);
    if (!(s_hi > s_lo)) {  // a bin of no material length: the damage where it sits
      out[c] = d(first);
      continue;
    }
    double sum = 0.0;
    for (int b = first; b < previous_grid.n && b * h < s_hi; ++b) {
      const double overlap = std::min(s_hi, (b + 1) * h) - std::max(s_lo, b * h);
      if (overlap > 0.0) sum += d(b) * overlap;
    }
    out[c] = sum / (s_hi - s_lo);
  }
  return out;
}

}  // namespace railwear
