// The adaptive rule over a traffic entry's lateral spread (issue 16 point 5): its weights against
// closed forms, its refinement on a jump, on a flange onset in the tail and on a smooth response,
// and on the default study: the step-1 worn area per pass and depth field against a fine fixed
// reference, deterministic, and independent of the thread count.
#include "wear/spread_integration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "tests/wear/default_study.h"
#include "wear/wear_simulation.h"

namespace railwear {
namespace {

// The step-1 depth field per pass of the adaptive rule against the fine reference's, relative
// L2 over the bins: measured 3.8 % on the default study at draft with the worn area alone as the
// criterion, 1.7 % since the depth-field criterion (20 fixed Gauss-Hermite nodes 6.1 %). Not the
// rule's 0.5 %: the rule converges the worn area, and a bin's depth keeps the draft grid's noise of
// the few nodes that put their patch on it (5-10 % between neighbouring positions at the flange),
// which the area averages over the profile; 5 % leaves that margin.
constexpr double kDepthFieldTolerance = 0.05;

double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double Density(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI); }

// Integrates a(x) (the same on both rails) by the adaptive rule to `tolerance`, as a step does
// (RefineSpreads after the first nodes). Returns the integral; `nodes` the nodes used.
double IntegrateAdaptively(const std::function<double(double)>& a, double tolerance,
                           int* nodes = nullptr, bool* converged = nullptr) {
  SpreadUnit unit;
  for (const double x : kSpreadInitialNodes) {
    unit.x.push_back(x);
    unit.value.push_back({a(x), a(x)});
  }
  unit.SetInitialErrors();
  std::vector<SpreadUnit> units = {unit};
  const SpreadIntegrationSummary s =
      RefineSpreads(&units, {0.0, 0.0}, tolerance,
                    [&](const std::vector<SpreadInterval>&, const std::vector<double>& x) {
                      std::vector<SpreadResponse> v;
                      for (const double xi : x) v.push_back({{a(xi), a(xi)}, {}});
                      return v;
                    });
  if (nodes) *nodes = static_cast<int>(units[0].x.size());
  if (converged) *converged = s.converged;
  return units[0].Integral()[0];
}

TEST(SpreadIntegrationTest, WeightsArePositiveAndSumToOne) {
  const std::vector<double> x = {-3.0, -1.5, -0.4, 0.0, 0.1, 1.5, 2.2, 3.0};
  const std::vector<double> w = LinearGaussianWeights(x);
  double sum = 0.0;
  for (const double v : w) {
    EXPECT_GT(v, 0.0);
    sum += v;
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
  // One node: all the mass.
  EXPECT_NEAR(LinearGaussianWeights({0.3})[0], 1.0, 1e-15);
}

// The piecewise-linear rule's nodes (spread_rule = "piecewise_linear"): m uniform nodes 6/m apart
// within +-3 std, symmetric, m/8 per tail to +-5 std, strictly increasing, 1.25 m in all.
TEST(SpreadIntegrationTest, LinearSpreadNodesAreUniformWithTails) {
  for (const int m : {kMinLinearSpreadNodes, 64, 128, kMaxLinearSpreadNodes}) {
    const std::vector<double> x = LinearSpreadNodes(m);
    ASSERT_EQ(x.size(), static_cast<size_t>(m + m / 4)) << m;
    EXPECT_DOUBLE_EQ(x.front(), -5.0);
    EXPECT_DOUBLE_EQ(x.back(), 5.0);
    for (size_t k = 0; k < x.size(); ++k) {
      EXPECT_NEAR(x[k], -x[x.size() - 1 - k], 1e-14);
      if (k > 0) {
        EXPECT_GT(x[k], x[k - 1]);
      }
    }
    const size_t inner = static_cast<size_t>(m / 8);  // the first inner node
    EXPECT_NEAR(x[inner], -3.0 + 3.0 / m, 1e-14);
    EXPECT_NEAR(x[inner + 1] - x[inner], 6.0 / m, 1e-14);
  }
}

// The rule integrates the piecewise-linear interpolant exactly: a(x) = max(0, min(x, 3)) has its
// kinks at the nodes 0 and 3, so E[a] = phi(0) - phi(3) + 3 (1 - Phi(3)) to rounding.
TEST(SpreadIntegrationTest, ExactForPiecewiseLinearResponses) {
  const std::vector<double> x = {-3.0, -1.5, 0.0, 1.5, 3.0};
  const std::vector<double> w = LinearGaussianWeights(x);
  double sum = 0.0;
  for (size_t k = 0; k < x.size(); ++k) sum += w[k] * std::max(0.0, std::min(x[k], 3.0));
  const double exact = Density(0.0) - Density(3.0) + 3.0 * (1.0 - Phi(3.0));
  EXPECT_NEAR(sum, exact, 1e-14);
  // Symmetric nodes: E[x] = 0 and the weights mirror.
  for (size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(w[k], w[x.size() - 1 - k], 1e-15);
}

// A response that switches from 1 (tread) to 5 (flange) between x = 0.7 and 0.8, between first
// nodes (the default study's flange onset spans about 0.15 std at its 1 mm spread): the rule
// bisects the intervals holding the switch until the worn area is within the tolerance.
TEST(SpreadIntegrationTest, ConvergesOnASwitchBetweenNodes) {
  const auto jump = [](double x) { return x < 0.7 ? 1.0 : x > 0.8 ? 5.0 : 1.0 + 40.0 * (x - 0.7); };
  // E = 1 + 4 P(X > 0.8) + 40 int_0.7^0.8 (x - 0.7) phi(x) dx
  const double exact = 1.0 + 4.0 * (1.0 - Phi(0.8)) +
                       40.0 * ((Density(0.7) - Density(0.8)) - 0.7 * (Phi(0.8) - Phi(0.7)));
  const std::vector<double> first(kSpreadInitialNodes.begin(), kSpreadInitialNodes.end());
  const std::vector<double> w = LinearGaussianWeights(first);
  double coarse = 0.0;
  for (size_t k = 0; k < first.size(); ++k) coarse += w[k] * jump(first[k]);
  int nodes = 0;
  bool converged = false;
  const double adaptive = IntegrateAdaptively(jump, 0.005, &nodes, &converged);
  std::printf(
      "[ measured ] switch: exact %.6f, first nodes %.6f (%.2f %%), adaptive %.6f (%.3f %%) "
      "with %d nodes\n",
      exact, coarse, 100 * (coarse / exact - 1), adaptive, 100 * (adaptive / exact - 1), nodes);
  EXPECT_TRUE(converged);
  EXPECT_LT(std::abs(adaptive / exact - 1.0), 0.005);
  EXPECT_LT(std::abs(adaptive / exact - 1.0), std::abs(coarse / exact - 1.0));
  EXPECT_LT(nodes, kMaxSpreadNodes);
}

// A flange onset in the tail: a(x) = 1 (tread) below x = 3.4, rising to 100 (flange) at 3.6 and
// constant beyond, the shape of the default study's freight response after 1 MGT (its flange
// contact starts near +3.2 std and wears 25-100 times the step's mean; docs/wear.md, "The
// tails"). First nodes at +-3 only took the response at +3 for the whole tail (E = 1, 2.3 %
// low); with the first nodes at +-5 the rule bisects [3, 5] down to the onset.
TEST(SpreadIntegrationTest, ConvergesOnAFlangeOnsetInTheTail) {
  const double lo = 3.4, hi = 3.6, top = 100.0;
  const auto onset = [&](double x) {
    return x < lo ? 1.0 : x > hi ? top : 1.0 + (top - 1.0) * (x - lo) / (hi - lo);
  };
  // E = 1 + (top - 1) [P(X > hi) + int_lo^hi (x - lo) / (hi - lo) phi(x) dx]
  const double ramp = ((Density(lo) - Density(hi)) - lo * (Phi(hi) - Phi(lo))) / (hi - lo);
  const double exact = 1.0 + (top - 1.0) * ((1.0 - Phi(hi)) + ramp);
  // The old first nodes, +-3 std, and the rule's weights on them.
  const std::vector<double> old_first = {-3.0, -1.5, 0.0, 1.5, 3.0};
  const std::vector<double> w = LinearGaussianWeights(old_first);
  double old_rule = 0.0;
  for (size_t k = 0; k < old_first.size(); ++k) old_rule += w[k] * onset(old_first[k]);
  int nodes = 0;
  bool converged = false;
  const double adaptive = IntegrateAdaptively(onset, 0.005, &nodes, &converged);
  std::printf(
      "[ measured ] flange onset at +3.5 std: exact %.6f, first nodes at +-3 only %.6f (%.2f "
      "%%), adaptive %.6f (%.3f %%) with %d nodes\n",
      exact, old_rule, 100 * (old_rule / exact - 1), adaptive, 100 * (adaptive / exact - 1), nodes);
  EXPECT_LT(old_rule / exact - 1.0, -0.02);  // what the tail fix is for
  EXPECT_TRUE(converged);
  EXPECT_LT(std::abs(adaptive / exact - 1.0), 0.005);
  EXPECT_LT(nodes, kMaxSpreadNodes);
}

// A smooth response growing toward the flange, a(x) = exp(x / 2): E = exp(1/8), less the part
// the constant tails beyond +-5 leave out (1e-6); the adaptive rule lands within 0.5 % of it.
TEST(SpreadIntegrationTest, ConvergesOnASmoothResponse) {
  int nodes = 0;
  bool converged = false;
  const double adaptive =
      IntegrateAdaptively([](double x) { return std::exp(0.5 * x); }, 0.002, &nodes, &converged);
  const double exact = std::exp(0.125);
  std::printf("[ measured ] exp(x/2): exact %.6f, adaptive %.6f (%.3f %%) with %d nodes\n", exact,
              adaptive, 100 * (adaptive / exact - 1), nodes);
  EXPECT_TRUE(converged);
  EXPECT_LT(std::abs(adaptive / exact - 1.0), 0.005);
}

// Nothing to refine where nothing wears: no round, no division by zero.
TEST(SpreadIntegrationTest, ZeroResponseNeedsNoRound) {
  int nodes = 0;
  bool converged = false;
  EXPECT_EQ(IntegrateAdaptively([](double) { return 0.0; }, 0.005, &nodes, &converged), 0.0);
  EXPECT_EQ(nodes, static_cast<int>(kSpreadInitialNodes.size()));
  EXPECT_TRUE(converged);
}

// A patch that sweeps across the rail as the wheelset moves, the vehicle curve's leading
// wheelsets in miniature (docs/wear.md, "Why the depth field does not converge on the curve":
// their contact crosses the gauge corner, 15 mm of arc length, within 1.5 std of a 1 mm spread,
// with a patch 2-4 mm wide and a worn area per pass that changes little along the way). Here a
// semi-elliptic depth profile of half-width 1.5 mm and of constant area, centred at y = 7.5 mm x
// for |x| <= 1 (15 mm within 2 std) and still beyond:
// the worn area is the same at every node, so the area alone asks for no bisection and leaves the
// field a comb of the seven first nodes' patches; with the depth field the rule bisects until
// neighbouring patches overlap. Exact field: the patch convolved with the normal density, by the
// trapezoidal rule on 40001 positions over +-5 std (the rule's constant tails beyond +-5 leave
// 2.9e-7 of the mass on each side; the trapezoid's error is below 1e-6 relative).
std::vector<double> SweepingPatch(double x, const std::vector<double>& y) {
  const double half_width = 1.5e-3, centre = 7.5e-3 * std::clamp(x, -1.0, 1.0);
  std::vector<double> f(y.size(), 0.0);
  for (size_t b = 0; b < y.size(); ++b) {
    const double u = (y[b] - centre) / half_width;
    if (std::abs(u) < 1.0) f[b] = 1e-9 * std::sqrt(1.0 - u * u);
  }
  return f;
}

// Relative L2 distance ||a - b|| / ||b||.
double RelativeL2(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, n = 0.0;
  for (size_t k = 0; k < b.size(); ++k) {
    d += (a[k] - b[k]) * (a[k] - b[k]);
    n += b[k] * b[k];
  }
  return std::sqrt(d / n);
}

// The comb left by the area alone against the depth-field criterion's field: its bound is the
// tolerance of the curve's per-wheelset fields in docs/wear.md's study (a few per cent, not the
// rule's 0.5 %: the tolerance is on the L1 change of the whole field per round, and the L2
// distance weighs the patch's steep edges), and the comb is measured far outside it.
constexpr double kSweepFieldTolerance = 0.03;

TEST(SpreadIntegrationTest, DepthFieldCriterionResolvesASweepingPatch) {
  const double h = 1e-4;  // bins [m]
  std::vector<double> y;
  for (int b = -600; b < 600; ++b) y.push_back((b + 0.5) * h);
  std::vector<double> exact(y.size(), 0.0);
  const int n = 40000;
  for (int k = 0; k <= n; ++k) {
    const double x = -5.0 + 10.0 * k / n;
    const double w = (k == 0 || k == n ? 0.5 : 1.0) * (10.0 / n) * Density(x);
    const std::vector<double> f = SweepingPatch(x, y);
    for (size_t b = 0; b < y.size(); ++b) exact[b] += w * f[b];
  }
  const auto integrate = [&](bool with_fields, int* nodes) {
    SpreadUnit unit;
    const auto response = [&](double x) {
      SpreadResponse r;
      const std::vector<double> f = SweepingPatch(x, y);
      double area = 0.0;
      for (const double d : f) area += d * h;
      r.value = {area, 0.0};
      if (with_fields) r.field = {f, std::vector<double>(y.size(), 0.0)};
      return r;
    };
    for (const double x : kSpreadInitialNodes) {
      const SpreadResponse r = response(x);
      unit.x.push_back(x);
      unit.value.push_back(r.value);
      if (with_fields) unit.field.push_back(r.field);
    }
    if (with_fields) unit.bin_m = {h, h};
    if (!with_fields) unit.field.clear();
    unit.SetInitialErrors();
    std::vector<SpreadUnit> units = {unit};
    RefineSpreads(&units, {0.0, 0.0}, 0.005,
                  [&](const std::vector<SpreadInterval>&, const std::vector<double>& x) {
                    std::vector<SpreadResponse> v;
                    for (const double xi : x) v.push_back(response(xi));
                    return v;
                  });
    *nodes = static_cast<int>(units[0].x.size());
    // The field of the rule's weights (the area-only unit carries none: rebuild it).
    const std::vector<double> w = LinearGaussianWeights(units[0].x);
    std::vector<double> field(y.size(), 0.0);
    for (size_t k = 0; k < w.size(); ++k) {
      const std::vector<double> f = SweepingPatch(units[0].x[k], y);
      for (size_t b = 0; b < y.size(); ++b) field[b] += w[k] * f[b];
    }
    return field;
  };
  int area_nodes = 0, field_nodes = 0;
  const double area_only = RelativeL2(integrate(false, &area_nodes), exact);
  const double with_field = RelativeL2(integrate(true, &field_nodes), exact);
  std::printf(
      "[ measured ] sweeping patch, depth field against the exact (relative L2): worn area alone "
      "%.1f %% with %d nodes, depth-field criterion %.2f %% with %d nodes\n",
      100 * area_only, area_nodes, 100 * with_field, field_nodes);
  EXPECT_EQ(area_nodes, static_cast<int>(kSpreadInitialNodes.size()));
  EXPECT_GT(area_only, 0.5);  // a comb: the seven patches do not overlap
  EXPECT_LT(with_field, kSweepFieldTolerance);
  EXPECT_LE(field_nodes, kMaxSpreadNodes);
}

// With fields, the rule's difference is the fields' L1 distance times the bin width: the
// area's change when one field lies wholly above the other, both areas when they do not overlap.
TEST(SpreadIntegrationTest, FieldDifferenceIsTheL1Distance) {
  SpreadUnit unit;
  unit.field.resize(1);
  unit.bin_m = {0.5, 0.5};
  const std::vector<double> low = {0.0, 1.0, 2.0, 0.0}, high = {0.0, 2.0, 3.0, 0.0};
  const std::vector<double> apart = {4.0, 0.0, 0.0, 2.0};
  EXPECT_DOUBLE_EQ(unit.Difference(0, 1.5, &low, 2.5, &high), 1.0);   // nested: the areas' 1.0
  EXPECT_DOUBLE_EQ(unit.Difference(0, 1.5, &low, 3.0, &apart), 4.5);  // apart: 1.5 + 3.0
  EXPECT_DOUBLE_EQ(SpreadUnit().Difference(0, 1.5, &low, 3.0, &apart), 1.5);  // no fields: areas
}

// Worn area per pass of the high rail in the first step, and the step.
double StepOneArea(const WearStudy& study, StepResult* out = nullptr) {
  const WearState start = MakeInitialState(study);
  StepResult step = RunWearStep(study, UnwornRails::Of(start), start, 1e12);
  double area = 0.0;
  for (const double d : step.depth_per_pass_m) area += d * step.grid.h_m;
  if (out) *out = std::move(step);
  return area;
}

// The relative L2 distance of a step's depth per pass (per bin of the same grid) from the
// reference's: ||d - d_ref||_2 / ||d_ref||_2.
double DepthFieldDistance(const StepResult& step, const StepResult& reference) {
  EXPECT_EQ(step.depth_per_pass_m.size(), reference.depth_per_pass_m.size());
  double diff = 0.0, norm = 0.0;
  for (size_t b = 0; b < reference.depth_per_pass_m.size(); ++b) {
    const double r = reference.depth_per_pass_m[b];
    diff += (step.depth_per_pass_m[b] - r) * (step.depth_per_pass_m[b] - r);
    norm += r * r;
  }
  return std::sqrt(diff / norm);
}

// A fixed reference finer than any rule under test: the piecewise-linear rule on 160 nodes per
// spread, 128 at x = (k + 1/2) 3/64, k = -64..63 (to +-2.98 std), and 16 in each tail at
// +-(3 + j/8), j = 1..16 (to +-5 std, as far as the adaptive rule's first nodes), as one step
// whose traffic has an entry without spread per node and entry, weighted by share x node
// weight. On the default study at draft the contact grid's noise between neighbouring positions
// (5-10 % at the flange) scatters fixed rules with the node offset: 32 nodes by +-1.5 %, 64 by
// +-0.7 %, 128 by +-0.16 % around the same rule on 257 nodes within +-3 std (measured once from
// a 257-position scan, 50 s).
double FineReference(WearStudy study, StepResult* out) {
  const std::vector<double> x = LinearSpreadNodes(128);
  const std::vector<double> w = LinearGaussianWeights(x);
  std::vector<TrafficCase> fixed;
  for (const TrafficCase& c : study.traffic) {
    for (size_t k = 0; k < x.size(); ++k) {
      TrafficCase node = c;
      node.lateral_shift_mean_m += c.lateral_shift_std_m * x[k];
      node.lateral_shift_std_m = 0.0;
      node.share = c.share * w[k];
      fixed.push_back(node);
    }
  }
  study.traffic = fixed;
  return StepOneArea(study, out);
}

// Issue 16's must-show, on the default study's load collective (examples/wear_high_rail.toml:
// both traffic entries with their means, 1 mm spreads, yaws, loads and speeds) at draft accuracy
// (tests/wear/default_study.h): the full scene's standard grid takes minutes for the reference
// solves, while the draft grid keeps the tread / gauge-corner / flange switches across the
// spread (the flange's onset at +0.7 and +1.2 std) that make fixed nodes miss.
// - The adaptive rule (default tolerance) is within 1 % of the fine fixed reference above.
// - The issue asked for 1 % of a 20-node Gauss-Hermite reference. At draft that reference is
//   itself 2-3 % below the fine one (its nodes are 0.3-0.5 std apart across the flange's
//   onset), so the test checks that the adaptive rule is closer to the fine reference than the
//   20 fixed nodes are, and prints both (docs/wear.md).
// - The step's depth field (W2 is a depth at one height, so the shape matters, not only the
//   area): the adaptive rule's depth per pass per bin within kDepthFieldTolerance (relative L2)
//   of the fine reference's, and closer to it than the 20 fixed nodes' (docs/wear.md).
TEST(SpreadIntegrationTest, DefaultStudyStepOneConvergedAgainstFixedReferences) {
  WearStudy study = DefaultStudy(WearLawKind::kKthContinuous);
  StepResult fine_step, twenty_step, step;
  const double fine = FineReference(study, &fine_step);
  study.options.quadrature_points = 20;
  const double twenty = StepOneArea(study, &twenty_step);
  study.options.integration_tolerance = kDefaultIntegrationTolerance;
  const double adaptive = StepOneArea(study, &step);
  const double twenty_field = DepthFieldDistance(twenty_step, fine_step);
  const double adaptive_field = DepthFieldDistance(step, fine_step);
  std::printf(
      "[ measured ] default study (draft), step 1 worn area per pass: fine fixed "
      "reference (2 x 160 nodes) %.6e mm2, 20 Gauss-Hermite nodes %.6e (%+.2f %%), adaptive "
      "%.6e (%+.3f %%) with nodes %d + %d in %d rounds, last change %.3f %%, estimates "
      "%.2f %%; depth field against the reference's (relative L2): 20 nodes %.2f %%, adaptive "
      "%.2f %%\n",
      fine * 1e6, twenty * 1e6, 100 * (twenty / fine - 1), adaptive * 1e6,
      100 * (adaptive / fine - 1), step.integration.nodes[0], step.integration.nodes[1],
      step.integration.rounds, 100 * step.integration.last_change[0],
      100 * step.integration.estimated_error[0], 100 * twenty_field, 100 * adaptive_field);
  EXPECT_LT(std::abs(adaptive / fine - 1.0), 0.01);
  EXPECT_LT(std::abs(adaptive / fine - 1.0), std::abs(twenty / fine - 1.0));
  EXPECT_LT(adaptive_field, kDepthFieldTolerance);
  EXPECT_LT(adaptive_field, twenty_field);
  // What was used is recorded: per entry, and each case's node and weight.
  ASSERT_EQ(step.integration.nodes.size(), 2u);
  EXPECT_TRUE(step.integration.adaptive);
  EXPECT_TRUE(step.integration.converged);
  EXPECT_LE(step.integration.last_change[0], kDefaultIntegrationTolerance);
  // Every spread reaches its far tails: a node at -5 and one at +5 std per entry.
  int tails = 0;
  int cases = 0;
  double weight = 0.0;
  for (const LoadCaseSummary& c : step.cases) {
    ++cases;
    weight += c.load_case.weight;
    tails += std::abs(std::abs(c.load_case.spread_x) - 5.0) < 1e-12 ? 1 : 0;
  }
  EXPECT_EQ(tails, 4);
  EXPECT_EQ(cases, step.integration.nodes[0] + step.integration.nodes[1]);
  EXPECT_NEAR(weight, 1.0, 1e-12);
  // In StepLoadCases order: by entry, then by node position.
  for (size_t k = 1; k < step.cases.size(); ++k) {
    const LoadCase& a = step.cases[k - 1].load_case;
    const LoadCase& b = step.cases[k].load_case;
    EXPECT_TRUE(
        a.traffic_index < b.traffic_index ||
        (a.traffic_index == b.traffic_index && a.spread_x < b.spread_x && b.node == a.node + 1));
  }
}

// The adaptive rule is deterministic: the same step twice, and on 1 and 2 threads, gives the
// same nodes and the same depths bit for bit.
TEST(SpreadIntegrationTest, AdaptiveRuleIsDeterministic) {
  WearStudy study = DefaultStudy(WearLawKind::kKthContinuous);
  study.options.integration_tolerance = 0.01;
  study.options.threads = 1;
  StepResult a, b, c;
  StepOneArea(study, &a);
  StepOneArea(study, &b);
  study.options.threads = 2;
  StepOneArea(study, &c);
  EXPECT_EQ(a.integration.nodes, b.integration.nodes);
  EXPECT_EQ(a.integration.nodes, c.integration.nodes);
  EXPECT_EQ(a.depth_per_pass_m, b.depth_per_pass_m);
  EXPECT_EQ(a.depth_per_pass_m, c.depth_per_pass_m);
  EXPECT_EQ(a.state.rail.points(), c.state.rail.points());
}

TEST(SpreadIntegrationTest, ToleranceOutsideItsRangeIsRefused) {
  WearStudy study = DefaultStudy(WearLawKind::kKthContinuous);
  for (const double bad : {0.0, 5e-5, 0.5, std::nan("")}) {
    study.options.integration_tolerance = bad;
    try {
      ValidateWearStudy(study);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("integration_tolerance"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("expected 0.0001 to 0.1"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace railwear
