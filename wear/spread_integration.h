// Adaptive integration over a traffic entry's lateral spread (issue 16 point 5): the expectation
// of a wheel's worn area per pass over its normally distributed lateral position, refined where
// the response changes (the tread / gauge-corner / flange switches) until the step's worn area
// per pass of every rail is converged to a relative tolerance (and, when the nodes carry their
// depth fields, the step's depth field: see SpreadUnit).
//
// Rule. The position is x in standard-normal units (lateral shift = mean + std x). The response
// a(x) is known at sorted nodes x_0 < ... < x_m; between nodes it is taken as linear, beyond the
// outer nodes (+-5) constant, and that piecewise-linear function is integrated exactly against the
// normal density phi (closed forms in Phi and phi), so the weights are positive, sum to 1 and
// the rule is nested: adding a node changes only the weights of its interval's two ends. The
// rule is exact for piecewise-linear a (with kinks at nodes); a jump inside an interval costs
// at most that interval's probability mass times the jump.
//
// Refinement. Every interval [x_i, x_i+1] has an error estimate per rail: at first the bound for
// a monotone response between the nodes, mass_i |a_i+1 - a_i|; when its midpoint is added, the
// change that made to the integral, |d|, split half to each new interval (at least the monotone
// bound while the interval is wider than kSpreadBoundWidth: a midpoint on the chord must not
// hide a switch). Each round bisects, in all units of the step at once (their contact solves
// run in parallel), the intervals with the largest estimates until they hold half of each
// unconverged rail's estimates (Doerfler marking). The step stops when the estimates left are
// within tolerance x the step's worn area per pass on every rail, or when the worn area per pass of
// every rail changed by at most that in two successive rounds (the estimates sum the contact grid's
// noise between neighbouring positions, which the integral averages out: on the default study at
// draft the estimates stay at about 6 % while the integral is within 0.4 % of a 128-node
// reference). Intervals narrower than kMinSpreadInterval and units with kMaxSpreadNodes are not
// bisected; a step that runs out of intervals before either test is not converged.
//
// A unit is one spread: a prescribed entry's, or one wheelset of a vehicle entry (each wheelset
// has its own equilibrium, so its switches lie elsewhere). Everything is deterministic: the
// selection depends on the solved values only, ties are broken by unit and position.
#pragma once

#include <array>
#include <functional>
#include <string_view>
#include <vector>

#include "core/numerics/enum_names.h"

namespace railwear {

// The first nodes of every unit [standard-normal units]: the median, the shoulders, +-3 and the
// far tails at +-5, beyond which the response is taken constant (2.9e-7 of the probability on
// each side). The tails are not negligible: where a wheel's flange meets the rail only beyond
// +3 std, its flange contact wears 5-25 times more per pass than the tread and gauge corner
// inside, and the 1.35e-3 of probability beyond +3 carried 8-22 % of the step's worn area in the
// default study's 10 MGT run with 30 Gauss-Hermite nodes (docs/wear.md, "The tails"); with the
// first nodes at +-3 only, the rule took the response at +3 for all of it.
inline constexpr std::array<double, 7> kSpreadInitialNodes = {-5.0, -3.0, -1.5, 0.0, 1.5, 3.0, 5.0};
// The most nodes one unit takes in a step (7 first nodes and 74 bisections; 41 until the
// depth-field criterion, which needs more where a wheelset's contact sweeps across the gauge
// corner: docs/wear.md, "Why the depth field does not converge on the curve").
inline constexpr int kMaxSpreadNodes = 81;
// The narrowest interval that is bisected [standard-normal units]: six halvings of the first
// nodes' 1.5 (0.023 std: 23 um at a 1 mm spread, below every contact grid's cell).
inline constexpr double kMinSpreadInterval = 1.5 / 64;
// Intervals wider than this [standard-normal units] (the first two levels of bisection) keep
// the monotone bound as a floor of their estimate.
inline constexpr double kSpreadBoundWidth = 0.375;
// With depth fields (SpreadUnit), a round is quiet when, besides the worn area's change, the
// L1 change of each rail's depth field times its bin width is at most this many times the
// tolerance x the rail's worn area per pass: the field's change sums the contact grid's noise
// of the new nodes' patches bin by bin (5-10 % between neighbouring positions at the flange on
// the draft grid), which the area averages out, so the area's tolerance would drive every spread
// to kMaxSpreadNodes.
inline constexpr double kSpreadFieldChangeFactor = 4.0;
// The share of the estimates a round bisects (Doerfler's marking parameter).
inline constexpr double kSpreadMarkingShare = 0.5;
// The range of the adaptive rule's relative tolerance: below 1e-4 the contact grid's own noise
// (a few 1e-4 of the worn area between neighbouring positions) would drive refinement to the
// node limit; above 0.1 the rule is no better than the fixed one.
inline constexpr double kMinIntegrationTolerance = 1e-4;
inline constexpr double kMaxIntegrationTolerance = 0.1;
// The tolerance scenes use unless they give one (or quadrature_points, the fixed rule).
inline constexpr double kDefaultIntegrationTolerance = 0.005;

// The rules over a spread (a scene's wear.spread_rule; WearOptions chooses by its fields, see
// SpreadRuleOf in wear/wear_simulation.h):
//   kAdaptive:        this file's rule, nodes added until the step is converged (the default);
//   kGaussHermite:    quadrature_points fixed Gauss-Hermite nodes;
//   kPiecewiseLinear: the fixed piecewise-linear rule on LinearSpreadNodes(m) (the converged
//                     reference on the vehicle curve, docs/wear.md).
enum class SpreadRule { kAdaptive, kGaussHermite, kPiecewiseLinear };
inline constexpr std::array<EnumName<SpreadRule>, 3> kSpreadRuleNames = {{
    {SpreadRule::kAdaptive, "adaptive"},
    {SpreadRule::kGaussHermite, "gauss_hermite"},
    {SpreadRule::kPiecewiseLinear, "piecewise_linear"},
}};
std::string_view ToString(SpreadRule v);

// Weights w_k (sum 1, all >= 0) of E[a(X)], X ~ N(0, 1), for the piecewise-linear interpolant
// of a at the strictly increasing nodes `x` (shape [m]), constant beyond the outer nodes.
std::vector<double> LinearGaussianWeights(const std::vector<double>& x);

// The fixed piecewise-linear rule's nodes (a scene's spread_rule = "piecewise_linear", the
// converged reference on the vehicle curve: docs/wear.md, "The converged fixed reference"): m
// uniform nodes within +-3 std at (k + 1/2) 6/m, k = -m/2..m/2-1, and m/8 in each tail at +-(3 + 16
// j/m), j = 1..m/8, up to +-5 std (the adaptive rule's outer first nodes), strictly
// increasing, 1.25 m in all; with LinearGaussianWeights. m = 128 is the draft test's fine reference
// (nodes 0.047 std apart). m is a multiple of 8 from kMinLinearSpreadNodes to
// kMaxLinearSpreadNodes.
std::vector<double> LinearSpreadNodes(int m);
// The range of LinearSpreadNodes' m: 8 puts the inner nodes 0.75 std apart (a coarse rule, still
// positive weights); 512 (640 nodes per spread) is four times the curve's converged reference.
inline constexpr int kMinLinearSpreadNodes = 8;
inline constexpr int kMaxLinearSpreadNodes = 512;

// A node's response per rail ([0] high, [1] low): its worn area per pass times its cases' weights
// without the node weight [m^2] and, optionally (empty: not given), its depth field per pass on
// that rail's bins with the same weights [m], shape [the rail's bins].
struct SpreadResponse {
  std::array<double, 2> value = {0.0, 0.0};
  std::array<std::vector<double>, 2> field;
};

// One spread being integrated: its nodes and, per node and rail ([0] high, [1] low), the
// response (the node's worn area per pass on that rail times its cases' weights without the
// node weight [m^2]), and per interval and rail the error estimate [m^2].
//
// The depth field (when every node has one: `field` and `bin_m` set). On a vehicle curve a
// wheelset's contact sweeps across the gauge corner as the wheelset moves: 15 mm of the rail's arc
// length within 1.5 std of a 1 mm spread, a patch 2-4 mm wide (docs/wear.md, "Why the depth
// field does not converge on the curve"). The worn area per pass changes little along the sweep,
// so a rule that converges the area leaves the depth field a comb of the nodes' separate patches.
// With fields, every difference the rule measures is the depth field's L1 norm times the bin
// width, bin_m sum_b |f_b - g_b| [m^2] instead of |a - b|: never less than the area's change
// (the two are equal where one field lies wholly above the other), and as large as both areas
// together where two nodes' patches do not overlap; so an interval is bisected until its two
// nodes' patches overlap, and the step stops when the depth field (not only its area) changed
// by at most kSpreadFieldChangeFactor x the tolerance in two successive rounds.
struct SpreadUnit {
  int traffic_index = 0;
  int wheelset = 0;                          // vehicle entries: the wheelset; else 0
  std::vector<double> x;                     // sorted nodes, shape [m]
  std::vector<std::array<double, 2>> value;  // shape [m]
  std::vector<std::array<double, 2>> error;  // shape [m - 1]
  std::vector<char> frozen;  // per interval: its midpoint failed, never bisected; shape [m - 1]
  // Optional: per node and rail the depth field per pass [m] (shape [m], or empty: the area
  // alone), and per rail the bin width [m] (see above).
  std::vector<std::array<std::vector<double>, 2>> field;
  std::array<double, 2> bin_m = {0.0, 0.0};
  // The integral per rail: sum_k w_k value_k.
  std::array<double, 2> Integral() const;
  // The depth field's integral on rail r, sum_k w_k field_k[r] (empty without fields).
  std::vector<double> FieldIntegral(int r) const;
  // What the rule measures between two responses of this unit on rail r: the depth fields' L1
  // distance times the bin width when the unit has fields, else |a - b| [m^2].
  double Difference(int r, double a, const std::vector<double>* fa, double b,
                    const std::vector<double>* fb) const;
  // Sets every interval's estimate to the monotone bound mass_i |value_i+1 - value_i|.
  void SetInitialErrors();
  // Inserts the midpoint of interval i with its response (its field when the unit has fields);
  // its two intervals get half the change of the integral (Difference) each.
  void Bisect(int interval, const SpreadResponse& midpoint);
};

// How a step integrated its traffic entries' spreads (StepResult::integration).
struct SpreadIntegrationSummary {
  bool adaptive = false;   // the adaptive rule (else the fixed Gauss-Hermite rule)
  double tolerance = 0.0;  // the adaptive rule's relative tolerance
  int rounds = 0;          // refinement rounds after the first nodes (adaptive)
  // The rule met its tolerance (false: it ran out of intervals to bisect first).
  bool converged = true;
  // Per rail ([0] high, [1] low), relative to the step's worn area per pass: the change of the
  // last round, and the sum of the error estimates left (an upper estimate: it sums the contact
  // grid's noise too).
  std::array<double, 2> last_change = {0.0, 0.0};
  std::array<double, 2> estimated_error = {0.0, 0.0};
  // Refinement nodes left out because their contact did not converge (their intervals are not
  // bisected).
  int failed_nodes = 0;
  // Per traffic entry: the spread nodes used in the step, summed over a vehicle's wheelsets (0
  // for an entry without spread and for collectives).
  std::vector<int> nodes;
};

// An interval to bisect: unit index and interval index in that unit.
struct SpreadInterval {
  int unit = 0;
  int interval = 0;
};

// The intervals to bisect in the next round, in (unit, interval) order: on every rail r whose
// estimates exceed tolerance x rail_total[r] (the step's worn area per pass on rail r, > 0 to
// count), the largest estimates until they hold kSpreadMarkingShare of that rail's; none when no
// rail exceeds (then `converged`, when given, is true) or when no interval can be bisected
// (narrower than kMinSpreadInterval, or its unit at kMaxSpreadNodes).
std::vector<SpreadInterval> SelectSpreadIntervals(const std::vector<SpreadUnit>& units,
                                                  const std::array<double, 2>& rail_total,
                                                  double tolerance, bool* converged = nullptr);

// The responses of new nodes: for each (unit, interval being bisected) and its midpoint x, the
// unit's response there per rail, in the order given; NaN for a node that could not be solved
// (its interval is then frozen: kept as it is, never bisected). With fields (SpreadUnit::field)
// every response carries its fields.
using SpreadEvaluator = std::function<std::vector<SpreadResponse>(
    const std::vector<SpreadInterval>& where, const std::vector<double>& x)>;

// The rounds of the adaptive rule on `units` (their first nodes evaluated, SetInitialErrors
// done): each round bisects SelectSpreadIntervals' choice, evaluated together, until the
// estimates meet the tolerance, or every rail's total (`fixed_total`, the parts without spread,
// plus the units' integrals) changed by at most tolerance x itself in two successive rounds (with
// fields also the L1 change of the rail's summed depth field times its bin width, by at most
// kSpreadFieldChangeFactor x that), or nothing is left to bisect. Returns the summary without
// `nodes`; its last_change is the worn area's.
SpreadIntegrationSummary RefineSpreads(std::vector<SpreadUnit>* units,
                                       const std::array<double, 2>& fixed_total, double tolerance,
                                       const SpreadEvaluator& evaluate);

// The estimated relative error per rail: sum of the estimates over rail_total (0 without wear).
std::array<double, 2> SpreadErrorEstimate(const std::vector<SpreadUnit>& units,
                                          const std::array<double, 2>& rail_total);

}  // namespace railwear
