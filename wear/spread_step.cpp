// The load cases of a wear step under the adaptive spread rule (see spread_step.h).
#include "wear/spread_step.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/numerics/check.h"
#include "wear/collective_traffic.h"
#include "wear/vehicle_traffic.h"

namespace railwear {

SpreadStep IntegrateSpreads(const WearStudy& study, const Profile& high_rail_track,
                            const std::optional<Profile>& low_rail_track,
                            const std::vector<CurvingStart>& curving_starts,
                            std::vector<CurvingStart>* curving_solved, double tolerance,
                            const SolveCaseBatch& solve,
                            const std::optional<SpreadRailBins>& bins) {
  RAILWEAR_CHECK(tolerance > 0.0);
  const std::vector<TrafficCase>& traffic = study.traffic;
  const int n_traffic = static_cast<int>(traffic.size());
  const std::array<double, 2> share_totals = RailShareTotals(traffic);
  std::vector<std::optional<VehicleEquilibrium>> equilibria(n_traffic);
  if (curving_solved) curving_solved->assign(n_traffic, CurvingStart{});

  SpreadStep out;
  std::vector<SpreadUnit> units;
  std::vector<int> case_unit;                // per case: its unit, -1 for a case without spread
  std::vector<double> base_weight;           // per case: its weight without the node weight
  std::array<double, 2> fixed = {0.0, 0.0};  // the cases without spread, per rail
  std::vector<std::map<double, SpreadResponse>> response;  // per unit: x -> response
  std::vector<LoadCase> batch;
  std::vector<int> batch_unit;

  const auto add = [&](const std::vector<LoadCase>& cases, int unit) {
    for (const LoadCase& c : cases) {
      batch.push_back(c);
      batch_unit.push_back(unit);
    }
  };
  // The cases of unit u at node x, at node weight 1.
  const auto node_cases = [&](int u, double x) -> std::vector<LoadCase> {
    const int t = units[u].traffic_index;
    if (equilibria[t]) {
      return VehicleNodeCases(study, t, *equilibria[t], units[u].wheelset, x, 0, 1.0);
    }
    return {internal::PrescribedNodeCase(traffic, t, share_totals, x, 0, 1.0)};
  };
  const auto new_unit = [&](int t, int wheelset) {
    SpreadUnit unit;
    unit.traffic_index = t;
    unit.wheelset = wheelset;
    units.push_back(unit);
    response.emplace_back();
    const int u = static_cast<int>(units.size()) - 1;
    for (const double x : kSpreadInitialNodes) add(node_cases(u, x), u);
  };
  // Solves the batch and books each case's response.
  std::vector<char> dropped;  // per case: its node failed (a refinement node not converged)
  const auto run_batch = [&](bool refinement) {
    const std::vector<SolvedCase> solved = solve(batch, refinement);
    RAILWEAR_CHECK(solved.size() == batch.size());
    // A node failed when any of its cases did (a vehicle node has two).
    std::map<std::pair<int, double>, bool> node_failed;
    for (size_t i = 0; i < batch.size(); ++i) {
      if (std::isnan(solved[i].worn_area_per_pass_m2))
        node_failed[{batch_unit[i], batch[i].spread_x}] = true;
    }
    for (size_t i = 0; i < batch.size(); ++i) {
      const LoadCase& c = batch[i];
      const int r = static_cast<int>(c.rail);
      const bool failed = node_failed.count({batch_unit[i], c.spread_x}) > 0;
      if (failed) {
        response[batch_unit[i]][c.spread_x].value[r] = std::nan("");
      } else if (batch_unit[i] < 0) {
        fixed[r] += c.weight * solved[i].worn_area_per_pass_m2;
      } else {
        SpreadResponse& node = response[batch_unit[i]][c.spread_x];
        node.value[r] += c.weight * solved[i].worn_area_per_pass_m2;
        if (bins) {
          // Both rails' fields on their bins (zero where the node has no case), so that every
          // node of every unit has fields of the same shapes.
          for (int q = 0; q < 2; ++q) {
            if (node.field[q].empty()) node.field[q].assign(bins->count[q], 0.0);
          }
          const std::vector<double>& d = solved[i].depth_per_pass_m;
          RAILWEAR_CHECK(static_cast<int>(d.size()) == bins->count[r]);
          for (size_t b = 0; b < d.size(); ++b) node.field[r][b] += c.weight * d[b];
        }
      }
      out.cases.push_back(c);
      case_unit.push_back(batch_unit[i]);
      base_weight.push_back(c.weight);
      dropped.push_back(failed ? 1 : 0);
    }
    batch.clear();
    batch_unit.clear();
  };
  // The first nodes, in StepLoadCases' order of sources: prescribed entries, then vehicles and
  // collectives.
  for (int t = 0; t < n_traffic; ++t) {
    const TrafficCase& c = traffic[t];
    if (c.is_vehicle() || c.is_collective()) continue;
    if (c.lateral_shift_std_m > 0.0) {
      new_unit(t, 0);
    } else {
      add({internal::PrescribedNodeCase(traffic, t, share_totals, 0.0, 0, 1.0)}, -1);
    }
  }
  for (int t = 0; t < n_traffic; ++t) {
    const TrafficCase& c = traffic[t];
    if (c.is_vehicle()) {
      const CurvingStart* start =
          t < static_cast<int>(curving_starts.size()) ? &curving_starts[t] : nullptr;
      equilibria[t] = SolveVehicleEquilibrium(study, t, high_rail_track, *low_rail_track, start);
      if (curving_solved) (*curving_solved)[t] = equilibria[t]->result.Start();
      const int wheelsets = static_cast<int>(equilibria[t]->result.wheelsets.size());
      for (int w = 0; w < wheelsets; ++w) {
        if (c.lateral_shift_std_m > 0.0) {
          new_unit(t, w);
        } else {
          add(VehicleNodeCases(study, t, *equilibria[t], w, 0.0, 0, 1.0), -1);
        }
      }
    } else if (c.is_collective()) {
      add(CollectiveLoadCases(study, t), -1);
    }
  }
  run_batch(/*refinement=*/false);
  const auto take_responses = [&](SpreadUnit* unit, const std::map<double, SpreadResponse>& r) {
    unit->x.clear();
    unit->value.clear();
    unit->field.clear();
    for (const auto& [x, v] : r) {
      unit->x.push_back(x);
      unit->value.push_back(v.value);
      if (bins) unit->field.push_back(v.field);
    }
    if (bins) unit->bin_m = bins->width_m;
  };
  for (size_t u = 0; u < units.size(); ++u) {
    take_responses(&units[u], response[u]);
    units[u].SetInitialErrors();
  }

  // Rounds of bisections until the step's worn area per pass is converged on every rail.
  out.summary =
      RefineSpreads(&units, fixed, tolerance,
                    [&](const std::vector<SpreadInterval>& where, const std::vector<double>& x) {
                      for (size_t k = 0; k < where.size(); ++k)
                        add(node_cases(where[k].unit, x[k]), where[k].unit);
                      run_batch(/*refinement=*/true);
                      std::vector<SpreadResponse> values;
                      for (size_t k = 0; k < where.size(); ++k)
                        values.push_back(response[where[k].unit].at(x[k]));
                      return values;
                    });
  SpreadIntegrationSummary& summary = out.summary;

  // Final weights and node numbers: the rule's weight of each node times the case's own.
  std::vector<std::vector<double>> weights(units.size());
  for (size_t u = 0; u < units.size(); ++u) weights[u] = LinearGaussianWeights(units[u].x);
  summary.nodes.assign(n_traffic, 0);
  for (const SpreadUnit& u : units) summary.nodes[u.traffic_index] += static_cast<int>(u.x.size());
  for (size_t i = 0; i < out.cases.size(); ++i) {
    const int u = case_unit[i];
    if (u < 0 || dropped[i]) continue;
    const std::vector<double>& x = units[u].x;
    const auto at = std::lower_bound(x.begin(), x.end(), out.cases[i].spread_x);
    RAILWEAR_CHECK(at != x.end() && *at == out.cases[i].spread_x);
    const int k = static_cast<int>(at - x.begin());
    out.cases[i].node = k;
    out.cases[i].weight = base_weight[i] * weights[u][k];
  }
  // StepLoadCases' order: prescribed entries first, then the others, each by wheelset and node
  // (cases of one node, and a collective's cases, in the order they were made).
  const auto key = [&](int i) {
    const LoadCase& c = out.cases[i];
    const TrafficCase& t = traffic[c.traffic_index];
    const bool prescribed = !t.is_vehicle() && !t.is_collective();
    return std::make_tuple(prescribed ? 0 : 1, c.traffic_index, c.wheelset, c.spread_x);
  };
  for (int i = 0; i < static_cast<int>(out.cases.size()); ++i) {
    if (!dropped[i]) out.order.push_back(i);
  }
  summary.failed_nodes = 0;
  for (const auto& r : response) {
    for (const auto& [x, v] : r) summary.failed_nodes += std::isnan(v.value[0]) ? 1 : 0;
  }
  std::stable_sort(out.order.begin(), out.order.end(),
                   [&](int a, int b) { return key(a) < key(b); });
  return out;
}

}  // namespace railwear
