// Per-pass wear depth on the rail profile (wear/pass_depth.h): Archard's identity V = k N s / H,
// the full-slip Hertz closed form, conservation of the worn area through the mapping on curved
// (conformal) grids, where the depth lands on the rail, damage and energy per position, errors.
#include "wear/pass_depth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include <gtest/gtest.h>

#include "core/contact/contact_solver.h"
#include "core/geometry/curve_locator.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/contact/hertz_grid.h"

namespace railwear {
namespace {

constexpr double kH = 2.6e9;  // rail hardness [Pa] (R260, DESIGN.md scene example)
constexpr double kV = 20.0;   // rolling speed [m/s]
constexpr double kMu = 0.3;   // friction coefficient
// The mapping only regroups the same column areas: sums agree to rounding (a few hundred terms
// of 1e-16 relative each).
constexpr double kConservationTolerance = 1e-12;
// Archard's identity holds exactly in the discrete sums; 1e-10 allows for summation order.
constexpr double kIdentityTolerance = 1e-10;

// A straight (flat) rail profile z = 0 for y in [-30, 30] mm: rail arc s = y + 30 mm.
constexpr double kFlatY0_m = -0.030;
Profile FlatRail() {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i <= 120; ++i) pts.emplace_back(kFlatY0_m + i * 0.5e-3, 0.0);
  return Profile(std::move(pts), "flat test rail");
}

// A planar Hertz patch on MakeHertzGrid (points on the flat rail's surface z = 0): pressure
// p0 sqrt(1 - x^2/a^2 - y^2/b^2), uniform slip velocity (vx, vs) in every loaded cell and full
// sliding traction q = -mu p v/|v| there.
PatchResult HertzPatch(double a, double b, int nx, int ns, double p0, double vx, double vs) {
  PatchResult r;
  r.grid = testing::MakeHertzGrid(a, b, nx, ns);
  const PatchGrid& g = r.grid;
  r.pressure_Pa = Eigen::VectorXd::Zero(g.cells());
  RollingPatch rp;
  rp.tangential = EmptyTangentialSolution(g.cells());
  TangentialSolution& t = rp.tangential;
  const double v = std::hypot(vx, vs);
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double u = 1.0 - std::pow(g.X(i) / a, 2) - std::pow(g.S(j) / b, 2);
      if (u <= 0.0) continue;
      const int k = g.Index(i, j);
      const double p = p0 * std::sqrt(u);
      r.pressure_Pa[k] = p;
      t.slip_x_m_s[k] = vx;
      t.slip_s_m_s[k] = vs;
      t.traction_x_Pa[k] = -kMu * p * vx / v;
      t.traction_s_Pa[k] = -kMu * p * vs / v;
      t.stick[k] = 0;
      t.frictional_power_W += kMu * p * v * g.CellArea();
      ++r.cells_in_contact;
    }
  }
  r.cells = g.cells();
  r.rolling = rp;
  return r;
}

double NormalForce(const PatchResult& r) { return r.pressure_Pa.sum() * r.grid.CellArea(); }

double ColumnArea(const std::vector<double>& dz, const PatchGrid& g) {
  return std::accumulate(dz.begin(), dz.end(), 0.0) * g.ds_m;
}

TEST(PassDepth, ArchardIdentityOnAHertzPatchWithUniformSlip) {
  // V = k N s / H with s = |v| / V per metre rolled: the worn area per metre of rail is
  // k N |v| / (H V), N = sum p dA. Bins of 0.13 mm do not line up with the 0.1 mm columns.
  const PatchResult patch = HertzPatch(6e-3, 4e-3, 60, 80, 1.2e9, 0.03, 0.04);
  WearLaw law;
  law.archard_k = 1.7e-4;
  const Profile rail = FlatRail();
  const WearGrid wg = WearGrid::ForProfile(rail, 0.13e-3);
  const std::vector<double> depth = CalcPatchPassDepth(patch, rail, law, kH, kV, wg);
  ASSERT_EQ(static_cast<int>(depth.size()), wg.n);
  const double expected = law.archard_k * NormalForce(patch) * 0.05 / (kH * kV);
  EXPECT_NEAR(WornArea(depth, wg), expected, kIdentityTolerance * expected);
  std::printf("[ measured ] Archard identity: worn area %.6e m^2 per pass, k N s/H %.6e\n",
              WornArea(depth, wg), expected);
}

TEST(PassDepth, UsfdMildRegimeIsProportionalToFrictionalEnergy) {
  // Below the first knee the USFD law is W = 5.3 Tg/A [ug/(m mm^2)], so the mass worn per metre
  // rolled is 5.3e-9 kg/J times the frictional energy per metre, mu N |v| / V here: worn area =
  // 5.3e-9 mu N |v| / (V rho). Local Tg/A = mu p |v| / V <= 0.3 * 1.2e9 * 0.05 / 20 Pa
  // = 0.9 N/mm^2 < 10.38 everywhere. This checks the power density |q . v| reaches the law.
  const PatchResult patch = HertzPatch(6e-3, 4e-3, 60, 80, 1.2e9, 0.03, 0.04);
  WearLaw law;
  law.kind = WearLawKind::kUsfd;
  const Profile rail = FlatRail();
  const WearGrid wg = WearGrid::ForProfile(rail, 0.1e-3);
  const std::vector<double> depth = CalcPatchPassDepth(patch, rail, law, kH, kV, wg);
  const double energy_J_m = kMu * NormalForce(patch) * 0.05 / kV;
  const double expected = 5.3e-9 * energy_J_m / law.density_kg_m3;
  EXPECT_NEAR(WornArea(depth, wg), expected, kIdentityTolerance * expected);
  // Frictional energy per position adds up to the patch's frictional power / V.
  const std::vector<double> e = CalcPatchPassEnergy(patch, rail, kV, wg);
  EXPECT_NEAR(WornArea(e, wg), energy_J_m, kIdentityTolerance * energy_J_m);
  EXPECT_NEAR(WornArea(e, wg), patch.rolling->tangential.frictional_power_W / kV,
              kIdentityTolerance * energy_J_m);
}

TEST(PassDepth, FullSlipHertzDepthMatchesTheClosedForm) {
  // Full slip at uniform |v|: dz(y) = k |v| / (H V) * integral of p dx
  //                                 = k |v| p0 (pi/2) a (1 - y^2/b^2) / (H V).
  // Bins of width ds whose edges fall on the column edges (the flat rail starts 26 mm = 260 ds
  // before the patch edge -b), so bin 260 + j holds column j's depth.
  constexpr double a = 6e-3, b = 4e-3, p0 = 1.2e9, v = 0.05;
  constexpr int nx = 200, ns = 80;
  const PatchResult patch = HertzPatch(a, b, nx, ns, p0, v, 0.0);
  WearLaw law;
  law.archard_k = 1e-4;
  const Profile rail = FlatRail();
  const double ds = patch.grid.ds_m;
  const WearGrid wg = WearGrid::ForProfile(rail, ds);
  const std::vector<double> depth = CalcPatchPassDepth(patch, rail, law, kH, kV, wg);
  const int offset = static_cast<int>(std::lround((-b - kFlatY0_m) / ds));
  ASSERT_EQ(offset, 260);
  const double peak = law.archard_k * v * p0 * std::numbers::pi / 2 * a / (kH * kV);
  // Tolerance from the x quadrature. Per column the sum along x is the midpoint rule on
  // sqrt(1 - x^2/A^2) over [-A, A], A = a sqrt(1 - y^2/b^2), with cells not aligned to the
  // ends, where the integrand behaves like sqrt(2 t / A) (t the distance from the end). The cell
  // at an end is off by at most one cell of that square root: it contributes at most
  // f(dx/2) dx = dx^1.5 / sqrt(A), or misses at most the integral over one cell,
  // (2/3) sqrt(2) dx^1.5 / sqrt(A). The interior cells add sum dx^3 |f''| / 24
  // = zeta(3/2) sqrt(2) / 96 dx^1.5 / sqrt(A) = 0.04 dx^1.5 / sqrt(A). Two ends: at most
  // 2.1 dx^1.5 / sqrt(A) in units of p0, i.e. 2.1 / (pi/2) (dx/a)^1.5 sqrt(a/A) of the peak's
  // (pi/2) a. Checked on the columns with A >= a/2 (|y| <= 0.87 b), sqrt(a/A) <= sqrt(2):
  // 1.9e-3 of the peak at dx/a = 1/100.
  const double dx_over_a = patch.grid.dx_m / a;
  const double kQuadratureTolerance =
      2.1 / (std::numbers::pi / 2) * std::pow(dx_over_a, 1.5) * std::sqrt(2.0);
  double max_err = 0.0;
  for (int j = 0; j < ns; ++j) {
    const double y = patch.grid.S(j);
    if (1.0 - y * y / (b * b) < 0.25) continue;  // A < a/2
    const double exact = peak * (1.0 - y * y / (b * b));
    EXPECT_NEAR(depth[offset + j], exact, kQuadratureTolerance * peak) << "column " << j;
    max_err = std::max(max_err, std::abs(depth[offset + j] - exact) / peak);
  }
  // Nothing outside the patch.
  for (int bb = 0; bb < wg.n; ++bb) {
    if (bb < offset || bb >= offset + ns) {
      EXPECT_EQ(depth[bb], 0.0) << "bin " << bb;
    }
  }
  std::printf(
      "[ measured ] full-slip Hertz depth: peak %.4e m per pass, max error %.2e of the "
      "peak on |y| <= 0.87 b (tolerance %.2e)\n",
      peak, max_err, kQuadratureTolerance);
}

// A 10 mm wheel in a 10.25 mm rail groove, conformal model, rolling with prescribed creepage.
ContactProblem GrooveRollingProblem() {
  ContactProblem p;
  p.wheel_profile = MakeCircle(0.010, BodyRole::kWheel);
  p.rail_profile = MakeGroove(0.01025, BodyRole::kRail);
  p.wheel_material = {210e9, 0.28};
  p.rail_material = {210e9, 0.28};
  p.rail_material.shear_yield_Pa = 350e6;
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 10e3;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.accuracy = AccuracyPreset::kStandard;
  RollingOptions ro;
  ro.friction = kMu;
  ro.motion.speed_m_s = kV;
  ro.creepage = Creepage{-0.01, 0.005, 0.5};  // xi, eta, spin [1/m]
  p.damage = true;
  p.rolling = ro;
  return p;
}

// S1002 on UIC60 canted 1:40 at the gauge corner (examples/rolling_gauge_corner.toml: -4 mm
// shift, 100 kN, 20 m/s), conformal model at draft accuracy. Kinematic rolling with 5 mrad of
// yaw unless creepages are given.
ContactProblem GaugeCornerProblem(std::optional<Creepage> creepage = std::nullopt) {
  ContactProblem p;
  p.wheel_profile = MakeS1002();
  p.rail_profile = ApplyCant(MakeUic60(), 1.0 / 40.0);
  p.wheel_material = {210e9, 0.28};
  p.rail_material = {210e9, 0.28};
  p.rail_material.shear_yield_Pa = 350e6;
  p.placement.lateral_shift_m = -4e-3;
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 100e3;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.accuracy = AccuracyPreset::kStandard;
  RollingOptions ro;
  ro.friction = kMu;
  ro.motion.speed_m_s = kV;
  p.placement.yaw_rad = 5e-3;
  ro.creepage = creepage;
  p.damage = true;
  p.rolling = ro;
  return p;
}

// The patch with the largest normal force.
const PatchResult& MainPatch(const ContactResult& r) {
  return *std::max_element(r.patches.begin(), r.patches.end(),
                           [](const PatchResult& l, const PatchResult& q) {
                             return l.normal_force_N < q.normal_force_N;
                           });
}

// Rail-arc span [lo, hi] of the loaded columns (any cell with p > 0).
std::pair<double, double> LoadedSpan(const PatchResult& patch, const CurveLocator& rail) {
  const std::vector<double> edges = CalcColumnEdgesOnRail(patch.grid, rail);
  double lo = 1e9, hi = -1e9;
  for (int j = 0; j < patch.grid.ns; ++j) {
    bool loaded = false;
    for (int i = 0; i < patch.grid.nx; ++i) loaded |= patch.pressure_Pa[patch.grid.Index(i, j)] > 0;
    if (!loaded) continue;
    lo = std::min({lo, edges[j], edges[j + 1]});
    hi = std::max({hi, edges[j], edges[j + 1]});
  }
  return {lo, hi};
}

TEST(PassDepth, WornAreaIsConservedOnACurvedGrooveGrid) {
  const ContactProblem problem = GrooveRollingProblem();
  const ContactResult r = SolveContact(problem);
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  ASSERT_EQ(r.patches.size(), 1u);
  const PatchResult& patch = r.patches[0];
  ASSERT_FALSE(patch.grid.planar);
  const CurveLocator rail(problem.rail_profile, true);
  const WearGrid wg = WearGrid::ForProfile(problem.rail_profile, 0.07e-3);
  for (WearLawKind kind :
       {WearLawKind::kArchard, WearLawKind::kKthContinuous, WearLawKind::kUsfd}) {
    WearLaw law;
    law.kind = kind;
    const std::vector<double> dz = CalcColumnPassDepth(patch, law, kH, kV);
    const double columns = ColumnArea(dz, patch.grid);
    ASSERT_GT(columns, 0.0) << ToString(kind);
    const std::vector<double> depth = CalcPatchPassDepth(patch, rail, law, kH, kV, wg);
    EXPECT_NEAR(WornArea(depth, wg), columns, kConservationTolerance * columns) << ToString(kind);
  }
  // The mapping is not the identity: the intermediate surface lies inside the overlap, off the
  // rail surface, so its columns project onto a rail arc of a different length than their own
  // and the depth on the rail differs from the column depth (measured: 6e-4 longer).
  const std::vector<double> edges = CalcColumnEdgesOnRail(patch.grid, rail);
  const double rail_arc = std::abs(edges.back() - edges.front());
  const double grid_arc = patch.grid.ns * patch.grid.ds_m;
  std::printf(
      "[ measured ] groove patch: %d columns of %.4f mm span %.6f mm of rail arc "
      "(%.6f mm on the reference surface)\n",
      patch.grid.ns, patch.grid.ds_m * 1e3, rail_arc * 1e3, grid_arc * 1e3);
  EXPECT_GT(std::abs(rail_arc / grid_arc - 1.0), 1e-4);
  // Frictional energy per position conserves the patch's frictional power / V.
  const std::vector<double> e = CalcPatchPassEnergy(patch, rail, kV, wg);
  const double energy = patch.rolling->tangential.frictional_power_W / kV;
  ASSERT_GT(energy, 0.0);
  EXPECT_NEAR(WornArea(e, wg), energy, kConservationTolerance * energy);
}

TEST(PassDepth, GaugeCornerDepthIsConservedAndLandsUnderThePatch) {
  // Real profiles at the gauge corner with kinematic creepage (yaw, spin from the contact angle).
  const ContactProblem problem = GaugeCornerProblem();
  const ContactResult r = SolveContact(problem);
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  const PatchResult& patch = MainPatch(r);
  const CurveLocator rail(problem.rail_profile, true);
  const WearGrid wg = WearGrid::ForProfile(problem.rail_profile, 0.1e-3);
  WearLaw law;
  const std::vector<double> dz = CalcColumnPassDepth(patch, law, kH, kV);
  const double columns = ColumnArea(dz, patch.grid);
  ASSERT_GT(columns, 0.0);
  const std::vector<double> depth = CalcPatchPassDepth(patch, rail, law, kH, kV, wg);
  EXPECT_NEAR(WornArea(depth, wg), columns, kConservationTolerance * columns);
  // Every bin with depth lies within the rail arc the loaded columns project onto.
  const auto [lo, hi] = LoadedSpan(patch, rail);
  int nonzero = 0;
  for (int b = 0; b < wg.n; ++b) {
    if (depth[b] == 0.0) continue;
    ++nonzero;
    EXPECT_GT((b + 1) * wg.h_m, lo) << "bin " << b;
    EXPECT_LT(b * wg.h_m, hi) << "bin " << b;
  }
  EXPECT_GT(nonzero, 10);
  // At the gauge corner: the worn bins sit on the gauge side of the canted head (y < -15 mm).
  const int peak = static_cast<int>(std::max_element(depth.begin(), depth.end()) - depth.begin());
  const Eigen::Vector2d at_peak = problem.rail_profile.Position(wg.Centre(peak));
  std::printf(
      "[ measured ] gauge corner (kinematic): worn area %.4e m^2 per pass, peak depth "
      "%.3e m at rail (y, z) = (%.2f, %.2f) mm; patch on rail arc [%.2f, %.2f] mm\n",
      WornArea(depth, wg), depth[peak], at_peak.x() * 1e3, at_peak.y() * 1e3, lo * 1e3, hi * 1e3);
  EXPECT_LT(at_peak.x(), -15e-3);
}

// Replaces the patch's tangential solution by full sliding at one slip velocity (vx, vs) in
// every loaded cell: the depth per column is then proportional to the column's load.
void SetUniformSlip(PatchResult* patch, double vx, double vs) {
  TangentialSolution& t = patch->rolling->tangential;
  t = EmptyTangentialSolution(patch->grid.cells());
  const double v = std::hypot(vx, vs);
  for (int k = 0; k < patch->grid.cells(); ++k) {
    const double p = patch->pressure_Pa[k];
    if (!(p > 0.0)) continue;
    t.slip_x_m_s[k] = vx;
    t.slip_s_m_s[k] = vs;
    t.traction_x_Pa[k] = -kMu * p * vx / v;
    t.traction_s_Pa[k] = -kMu * p * vs / v;
    t.stick[k] = 0;
  }
}

TEST(PassDepth, UniformSlipDepthSitsOnThePressureCentre) {
  // The conformal gauge-corner patch with uniform full slip: the depth per column is
  // k |v| / (H V) times the column's load sum_i p dx, so on the rail the depth profile is the
  // load profile. Its centroid is the pressure centre, which SolveContact projects onto the
  // rail (PatchResult::contact_point_yz_m), and its peak is the most loaded column.
  const ContactProblem problem = GaugeCornerProblem();
  const ContactResult r = SolveContact(problem);
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  PatchResult patch = MainPatch(r);
  SetUniformSlip(&patch, 0.6, 0.8);
  const CurveLocator rail(problem.rail_profile, true);
  const WearGrid wg = WearGrid::ForProfile(problem.rail_profile, 0.02e-3);
  const std::vector<double> depth = CalcPatchPassDepth(patch, rail, WearLaw{}, kH, kV, wg);
  double sum = 0.0, moment = 0.0;
  for (int b = 0; b < wg.n; ++b) {
    sum += depth[b];
    moment += depth[b] * wg.Centre(b);
  }
  const double s_depth = moment / sum;
  const double s_centre = rail.Project(patch.contact_point_yz_m).s;
  const auto [lo, hi] = LoadedSpan(patch, rail);
  // Centroid tolerance: the bins' centres stand for their contents (at most h/2 each), and the
  // midpoint of a column's projected interval differs from the projection of its centre, and
  // the projection of an interpolated point from the interpolated projections, by second-order
  // terms ~ ds^2 / R (0.36 mm columns on a 13 mm gauge-corner radius: 0.01 mm).
  const double kCentroidTolerance_m = 0.5 * wg.h_m + 0.01e-3;
  EXPECT_NEAR(s_depth, s_centre, kCentroidTolerance_m);
  // The peak lies in the rail interval of the most loaded column.
  const PatchGrid& g = patch.grid;
  int j_max = 0;
  double load_max = -1.0;
  for (int j = 0; j < g.ns; ++j) {
    double load = 0.0;
    for (int i = 0; i < g.nx; ++i) load += patch.pressure_Pa[g.Index(i, j)];
    if (load > load_max) {
      load_max = load;
      j_max = j;
    }
  }
  const std::vector<double> edges = CalcColumnEdgesOnRail(g, rail);
  const int peak = static_cast<int>(std::max_element(depth.begin(), depth.end()) - depth.begin());
  EXPECT_GE(wg.Centre(peak), std::min(edges[j_max], edges[j_max + 1]) - wg.h_m);
  EXPECT_LE(wg.Centre(peak), std::max(edges[j_max], edges[j_max + 1]) + wg.h_m);
  std::printf(
      "[ measured ] gauge corner (uniform slip): depth centroid at rail s = %.4f mm, "
      "pressure centre %.4f mm; peak at %.3f mm (most loaded column [%.3f, %.3f] mm); "
      "patch [%.3f, %.3f] mm\n",
      s_depth * 1e3, s_centre * 1e3, wg.Centre(peak) * 1e3, edges[j_max] * 1e3,
      edges[j_max + 1] * 1e3, lo * 1e3, hi * 1e3);
  for (int b = 0; b < wg.n; ++b) {
    if (depth[b] != 0.0) {
      EXPECT_GT((b + 1) * wg.h_m, lo);
      EXPECT_LT(b * wg.h_m, hi);
    }
  }
}

TEST(PassDepth, DamageCoversTheLoadedPositions) {
  // Synthetic planar patch: all 80 columns are loaded, covering y in [-b, b] = rail arc
  // [26, 34] mm; bins of 0.3 mm leave partly covered bins at both ends.
  PatchResult patch = HertzPatch(6e-3, 4e-3, 60, 80, 1.2e9, 0.03, 0.04);
  PatchDamage d;
  d.wlrm_damage = 3.7e-6;
  patch.rolling->damage = d;
  const Profile rail = FlatRail();
  const WearGrid wg = WearGrid::ForProfile(rail, 0.3e-3);
  const std::vector<double> damage = CalcPatchDamageSpread(patch, rail, wg);
  const double lo = 0.026, hi = 0.034;
  int full = 0;
  for (int b = 0; b < wg.n; ++b) {
    const double overlap = std::max(0.0, std::min(hi, (b + 1) * wg.h_m) - std::max(lo, b * wg.h_m));
    const double expected = d.wlrm_damage * overlap / wg.h_m;
    EXPECT_NEAR(damage[b], expected, kConservationTolerance * d.wlrm_damage) << "bin " << b;
    if (overlap >= (1.0 - kConservationTolerance) * wg.h_m) ++full;  // intensive: all of it
  }
  EXPECT_GT(full, 20);
}

// A patch the vertical balance left without pressure (the default study's dry KTH run at step
// 13: a second patch of 319 cells, "no cell carries pressure") has no tractions, so no damage
// indices: it damages nothing, where it stopped the run as if the damage effect were off.
TEST(PassDepth, AnUnloadedPatchSpreadsNoDamage) {
  PatchResult patch = HertzPatch(6e-3, 4e-3, 20, 20, 1e9, 0.01, 0.0);
  patch.pressure_Pa.setZero();
  patch.rolling->tangential.status = SolverStatus::kNoContact;
  ASSERT_FALSE(patch.rolling->damage.has_value());
  const Profile rail = FlatRail();
  const WearGrid wg = WearGrid::ForProfile(rail, 0.3e-3);
  const std::vector<double> damage = CalcPatchDamageSpread(patch, rail, wg);
  ASSERT_EQ(static_cast<int>(damage.size()), wg.n);
  for (double d : damage) EXPECT_EQ(d, 0.0);
}

TEST(PassDepth, DamageSpreadOnARealPatch) {
  const ContactProblem problem = GrooveRollingProblem();
  const ContactResult r = SolveContact(problem);
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  const PatchResult& patch = r.patches[0];
  ASSERT_TRUE(patch.rolling->damage.has_value());
  const double d = patch.rolling->damage->wlrm_damage;
  std::printf("[ measured ] groove patch: T-gamma %.1f J/m, WLRM damage %.3e per axle\n",
              patch.rolling->damage->t_gamma_N, d);
  ASSERT_GT(d, 0.0);
  const CurveLocator rail(problem.rail_profile, true);
  const WearGrid wg = WearGrid::ForProfile(problem.rail_profile, 0.1e-3);
  const std::vector<double> damage = CalcPatchDamageSpread(patch, rail, wg);
  const auto [lo, hi] = LoadedSpan(patch, rail);
  int full = 0;
  for (int b = 0; b < wg.n; ++b) {
    EXPECT_LE(damage[b], d) << "bin " << b;
    EXPECT_GE(damage[b], 0.0) << "bin " << b;
    if ((b + 1) * wg.h_m <= lo || b * wg.h_m >= hi) {
      EXPECT_EQ(damage[b], 0.0) << "bin " << b;
    }
    // Bins well inside the loaded span are fully covered (the loaded columns are contiguous).
    if (b * wg.h_m >= lo && (b + 1) * wg.h_m <= hi) {
      EXPECT_NEAR(damage[b], d, kConservationTolerance * d) << "bin " << b;
      ++full;
    }
  }
  EXPECT_GT(full, 5);
}

TEST(PassDepth, ErrorsNameWhatWearNeeds) {
  const Profile rail = FlatRail();
  const WearGrid wg = WearGrid::ForProfile(rail, 0.1e-3);
  // Hertz model: no grid.
  ContactProblem hertz = GrooveRollingProblem();
  hertz.wheel_profile = MakeCircle(0.02, BodyRole::kWheel);
  hertz.rail_profile = MakeCircle(0.3, BodyRole::kRail);
  hertz.model = MakeModelOptions(ModelKind::kHertz);
  hertz.rolling.reset();
  const ContactResult rh = SolveContact(hertz);
  ASSERT_EQ(rh.status, SolverStatus::kConverged) << rh.message;
  auto expect_message = [](auto&& call, const std::string& part) {
    try {
      call();
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_message([&] { CalcPatchPassDepth(rh.patches[0], rail, WearLaw{}, kH, kV, wg); },
                 "Hertz model, which has no grid: wear needs a grid model");
  expect_message([&] { CalcPatchPassDepth(rh.patches[0], rail, WearLaw{}, kH, kV, wg); },
                 "and the tangential effect");
  expect_message([&] { CalcPatchDamageSpread(rh.patches[0], rail, wg); }, "needs a grid model");
  // Grid but no rolling stage.
  PatchResult normal_only = HertzPatch(6e-3, 4e-3, 20, 20, 1e9, 0.01, 0.0);
  normal_only.rolling.reset();
  expect_message([&] { CalcPatchPassDepth(normal_only, rail, WearLaw{}, kH, kV, wg); },
                 "no rolling solution: wear needs a grid model and the tangential effect");
  expect_message([&] { CalcPatchPassEnergy(normal_only, rail, kV, wg); }, "tangential effect");
  // Rolling without the damage effect.
  const PatchResult no_damage = HertzPatch(6e-3, 4e-3, 20, 20, 1e9, 0.01, 0.0);
  expect_message([&] { CalcPatchDamageSpread(no_damage, rail, wg); }, "the damage effect");
  // Bad numbers.
  expect_message([&] { CalcPatchPassDepth(no_damage, rail, WearLaw{}, 0.0, kV, wg); },
                 "rail hardness H [Pa] = 0");
  expect_message([&] { CalcPatchPassDepth(no_damage, rail, WearLaw{}, kH, -1.0, wg); },
                 "rolling speed V [m/s] = -1");
  expect_message([&] { WearGrid::ForProfile(rail, 0.0); }, "bin width h = 0 m");
}

TEST(PassDepth, WearGridCoversTheProfile) {
  const Profile rail = FlatRail();  // 60 mm
  const WearGrid wg = WearGrid::ForProfile(rail, 0.7e-3);
  EXPECT_EQ(wg.n, 86);  // ceil(60 / 0.7)
  EXPECT_GE(wg.n * wg.h_m, rail.Length());
  EXPECT_LT((wg.n - 1) * wg.h_m, rail.Length());
  EXPECT_DOUBLE_EQ(wg.Centre(0), 0.35e-3);
}

}  // namespace
}  // namespace railwear
