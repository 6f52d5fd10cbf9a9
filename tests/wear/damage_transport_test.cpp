// Damage carried with the material through a wear step (wear/damage_transport.h, issue 16 point
// 7): a real UIC60 profile worn 1 mm deep at its gauge corner, whose arc length changes by a few
// bins. The remap conserves the integral of damage over material to 1e-12, keeps a uniform
// damage uniform, and moves a damaged point's bin to where its material went.
#include "wear/damage_transport.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "core/geometry/curve_locator.h"
#include "core/profile/builtin_profiles.h"
#include "wear/wear_simulation.h"

namespace railwear {
namespace {

constexpr double kBin = 1e-4;

// A step by hand, as the wear loop makes it: UIC60 at 0.2 mm spacing, its points moved inward
// by a 1 mm deep Gaussian (sigma 4 mm) centred at the gauge corner's arc length, resampled.
struct Step {
  Profile previous, moved, next;
  std::vector<Eigen::Vector2d> moved_points;
  MaterialMap map;
  WearGrid previous_grid, next_grid;
};

Step MakeStep() {
  Step st;
  st.previous = ResampleProfile(MakeUic60(), 2e-4);
  const CurveLocator locator(st.previous, /*material_toward_plus_z=*/true);
  // The gauge corner: the point of largest curvature away from the ends.
  double s_corner = 0.0, k_max = 0.0;
  for (int i = 10; i < st.previous.size() - 10; ++i) {
    const double k = std::abs(st.previous.Curvature(st.previous.KnotS(i)));
    const double y = st.previous.points()[i].x();
    if (y < -0.02 && y > -0.04 && k > k_max) {
      k_max = k;
      s_corner = st.previous.KnotS(i);
    }
  }
  st.moved_points = st.previous.points();
  for (int i = 0; i < st.previous.size(); ++i) {
    const double s = st.previous.KnotS(i);
    const double dz = 1e-3 * std::exp(-0.5 * std::pow((s - s_corner) / 4e-3, 2));
    st.moved_points[i] -= dz * locator.OutwardNormal(s);
  }
  st.moved = Profile(st.moved_points, "moved");
  st.next = ResampleProfile(st.moved, 2e-4);
  st.map = MaterialMapOfStep(st.previous, st.moved_points, st.moved, st.next);
  st.previous_grid = WearGrid::ForProfile(st.previous, kBin);
  st.next_grid = WearGrid::ForProfile(st.next, kBin);
  return st;
}

// Integral over material of a per-bin damage on the previous profile: bins of width h, the last
// one cut at the profile's end.
double PreviousIntegral(const std::vector<double>& d, const Step& st) {
  const std::vector<double> m = MaterialBinLengths(st.previous_grid, st.previous.Length(),
                                                   IdentityMaterialMap(st.previous.Length()));
  return std::inner_product(d.begin(), d.end(), m.begin(), 0.0);
}

double NextIntegral(const std::vector<double>& d, const Step& st) {
  const std::vector<double> m = MaterialBinLengths(st.next_grid, st.next.Length(), st.map);
  return std::inner_product(d.begin(), d.end(), m.begin(), 0.0);
}

// A varied damage field: smooth plus a sawtooth, so bins differ from their neighbours.
std::vector<double> VariedDamage(int n) {
  std::vector<double> d(n);
  for (int b = 0; b < n; ++b) d[b] = 0.3 + 0.2 * std::sin(0.05 * b) + 0.1 * (b % 7) / 7.0;
  return d;
}

TEST(DamageTransport, TheStepChangesTheArcLengthByMoreThanTwoBins) {
  const Step st = MakeStep();
  // The 1 mm dent changes the profile's length by more than two bins (0.285 mm longer).
  EXPECT_GT(std::abs(st.next.Length() - st.previous.Length()), 2 * kBin);
  // The map runs end to end and moves the far end by the whole change.
  EXPECT_EQ(st.map.ToNext(0.0), 0.0);
  EXPECT_NEAR(st.map.ToNext(st.previous.Length()), st.next.Length(), 1e-15);
}

TEST(DamageTransport, RemapConservesTheDamageOverMaterial) {
  const Step st = MakeStep();
  const std::vector<double> d = VariedDamage(st.previous_grid.n);
  const std::vector<double> remapped = RemapDamage(d, st.previous_grid, st.previous.Length(),
                                                   st.next_grid, st.next.Length(), st.map);
  ASSERT_EQ(static_cast<int>(remapped.size()), st.next_grid.n);
  const double before = PreviousIntegral(d, st);
  EXPECT_NEAR(NextIntegral(remapped, st), before, 1e-12 * before);
  // The material lengths of the next bins add up to the previous profile's length.
  const std::vector<double> m = MaterialBinLengths(st.next_grid, st.next.Length(), st.map);
  EXPECT_NEAR(std::accumulate(m.begin(), m.end(), 0.0), st.previous.Length(), 1e-15);
  // The pre-issue-16 rule (bin b keeps its value, bins beyond the shorter profile dropped) does
  // not conserve it.
  const std::vector<double> in_place(d.begin(), d.begin() + st.next_grid.n);
  EXPECT_GT(std::abs(NextIntegral(in_place, st) - before), 1e-4 * before);
}

TEST(DamageTransport, UniformDamageStaysUniform) {
  const Step st = MakeStep();
  const std::vector<double> d(st.previous_grid.n, 0.25);
  const std::vector<double> remapped = RemapDamage(d, st.previous_grid, st.previous.Length(),
                                                   st.next_grid, st.next.Length(), st.map);
  for (double v : remapped) EXPECT_NEAR(v, 0.25, 1e-14);
}

TEST(DamageTransport, DamageStaysWithItsMaterialPoint) {
  const Step st = MakeStep();
  // Damage in one bin on the far side of the worn corner, whose material moves by two to three
  // bins.
  const int b = st.previous_grid.n - 60;
  const double s_centre = st.previous_grid.Centre(b);
  const double t_centre = st.map.ToNext(s_centre);
  ASSERT_GT(std::abs(s_centre - t_centre), 2 * kBin);
  std::vector<double> d(st.previous_grid.n, 0.0);
  d[b] = 1.0;
  const std::vector<double> remapped = RemapDamage(d, st.previous_grid, st.previous.Length(),
                                                   st.next_grid, st.next.Length(), st.map);
  // The damage sits where the material went (the bin holding t(s_centre), or a neighbour that
  // shares the old bin), and has left the old bin index.
  const int peak =
      static_cast<int>(std::max_element(remapped.begin(), remapped.end()) - remapped.begin());
  EXPECT_LE(std::abs(peak - static_cast<int>(t_centre / kBin)), 1);
  EXPECT_EQ(remapped[b], 0.0);
  // Its material-weighted centre is the material point's new arc length, to a small fraction
  // of a bin.
  const std::vector<double> m = MaterialBinLengths(st.next_grid, st.next.Length(), st.map);
  double mass = 0.0, first_moment = 0.0;
  for (int c = 0; c < st.next_grid.n; ++c) {
    mass += remapped[c] * m[c];
    first_moment += remapped[c] * m[c] * st.map.ToPrevious(st.next_grid.Centre(c));
  }
  EXPECT_NEAR(mass, kBin, 1e-12 * kBin);
  EXPECT_NEAR(first_moment / mass, s_centre, 0.1 * kBin);
}

TEST(DamageTransport, IdentityMapLeavesTheFieldAlone) {
  const Step st = MakeStep();
  const std::vector<double> d = VariedDamage(st.previous_grid.n);
  const std::vector<double> same =
      RemapDamage(d, st.previous_grid, st.previous.Length(), st.previous_grid, st.previous.Length(),
                  IdentityMaterialMap(st.previous.Length()));
  ASSERT_EQ(same.size(), d.size());
  for (size_t b = 0; b < d.size(); ++b) EXPECT_NEAR(same[b], d[b], 1e-12 * d[b]);
}

}  // namespace
}  // namespace railwear
