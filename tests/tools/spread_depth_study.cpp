// The depth-field study of the spread rule (issue 16, docs/wear.md "Why the depth field does not
// converge on the curve"): one wear step of a scene, on its unworn rails or on stored steps of a
// run, with several fixed Gauss-Hermite node counts and the adaptive rule, and per traffic entry,
// wheelset and rail the step's depth field per pass of each rule against the finest fixed one
// (relative L2 and worn area), plus every node's response (worn area per pass, contact angle and
// position of the most loaded patch) as CSV for the mechanism.
//
//   spread_depth_study SCENE.toml NODES [ADAPTIVE_TOL] [DB RUN STEP,STEP,...] > table.txt
//     NODES: comma-separated fixed rules (the last is the reference): N for N Gauss-Hermite
//            nodes, LM for the piecewise-linear rule on M nodes within +-3 std at (k + 1/2) 6/M
//            and M/8 in each tail at 3 + 16 j/M up to +-5 (L128: the draft test's fine
//            reference), e.g. 20,41,61,L128,L256
//     ADAPTIVE_TOL: the adaptive rule's tolerance, or 0 for none
//     DB RUN STEPS: stored steps of a run (its stored scene text is read instead of SCENE.toml's
//                   spread settings; the rails, curving starts and wheels are the step's)
//   The node responses go to stderr as CSV lines starting with "node,".
// A study tool, not a test: it prints (tests/tools, like traffic_study.sh).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "app/scene.h"
#include "app/stored_study.h"
#include "wear/spread_integration.h"
#include "wear/wear_simulation.h"

namespace {

using namespace railwear;

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

// Per (traffic entry, wheelset, rail): the weighted depth field per pass [m].
using Key = std::tuple<int, int, int>;
using Fields = std::map<Key, std::vector<double>>;

Fields WheelsetFields(const StepResult& step) {
  Fields f;
  for (const LoadCaseSummary& s : step.cases) {
    const LoadCase& c = s.load_case;
    const Key k{c.traffic_index, c.wheelset, static_cast<int>(c.rail)};
    std::vector<double>& d = f[k];
    if (d.empty()) d.assign(s.depth_per_pass_m.size(), 0.0);
    for (size_t b = 0; b < d.size(); ++b) d[b] += c.weight * s.depth_per_pass_m[b];
  }
  return f;
}

double Norm(const std::vector<double>& a) {
  double s = 0.0;
  for (const double v : a) s += v * v;
  return std::sqrt(s);
}

double Distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

double Sum(const std::vector<double>& a) {
  double s = 0.0;
  for (const double v : a) s += v;
  return s;
}

struct Rule {
  std::string name;
  StepResult step;
  Fields fields;
};

// A rule's cost in the step: its load cases (contact solves) and the step's wall time (not a
// benchmark: the machine is shared; compare rules run one after the other).
void PrintCost(const std::string& label, const std::string& rule, const StepResult& step,
               std::chrono::steady_clock::time_point start) {
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stdout, "%s: %s: %zu load cases, %.1f s wall\n", label.c_str(), rule.c_str(),
               step.cases.size(), s);
  std::fflush(stdout);
}

void Study(WearStudy study, const UnwornRails& unworn, const WearState& state,
           const std::vector<std::string>& nodes, double adaptive_tolerance,
           const std::string& label) {
  std::vector<Rule> rules;
  std::vector<int> order;
  for (const std::string& rule : nodes) {
    study.options.integration_tolerance.reset();
    study.options.spread_nodes.clear();
    std::string name;
    if (rule[0] == 'L') {
      study.options.spread_nodes = LinearSpreadNodes(std::stoi(rule.substr(1)));
      name = rule + " linear";
    } else {
      study.options.quadrature_points = std::stoi(rule);
      name = rule + " GH";
    }
    const auto start = std::chrono::steady_clock::now();
    Rule r{name, RunWearStep(study, unworn, state, 1e30), {}};
    PrintCost(label, name, r.step, start);
    r.fields = WheelsetFields(r.step);
    rules.push_back(std::move(r));
  }
  if (adaptive_tolerance > 0.0) {
    study.options.integration_tolerance = adaptive_tolerance;
    const auto start = std::chrono::steady_clock::now();
    Rule r{"adaptive", RunWearStep(study, unworn, state, 1e30), {}};
    PrintCost(label, "adaptive", r.step, start);
    r.fields = WheelsetFields(r.step);
    std::fprintf(stdout, "%s: adaptive: %d rounds, last change %.3g %% high %.3g %% low, nodes",
                 label.c_str(), r.step.integration.rounds, 100 * r.step.integration.last_change[0],
                 100 * r.step.integration.last_change[1]);
    for (const int k : r.step.integration.nodes) std::fprintf(stdout, " %d", k);
    std::fprintf(stdout, "\n");
    rules.push_back(std::move(r));
  }
  const Rule& ref = rules[nodes.size() - 1];
  const double h_high = ref.step.grid.h_m;
  const double h_low = ref.step.low_rail ? ref.step.low_rail->grid.h_m : h_high;
  // Totals per rail of the reference, for each wheelset's share.
  std::map<int, std::vector<double>> total;
  for (const auto& [k, d] : ref.fields) {
    std::vector<double>& t = total[std::get<2>(k)];
    if (t.empty()) t.assign(d.size(), 0.0);
    for (size_t b = 0; b < d.size(); ++b) t[b] += d[b];
  }
  std::fprintf(stdout,
               "%s: per entry/wheelset/rail: reference (%s) worn area per pass [mm^2], its share "
               "of the rail's; then per rule: area ratio, relative L2 of the depth field, L2 of "
               "the difference over the rail's whole field\n",
               label.c_str(), ref.name.c_str());
  for (const auto& [k, d] : ref.fields) {
    const auto [t, w, rail] = k;
    const double h = rail == 0 ? h_high : h_low;
    const double area = Sum(d) * h;
    std::fprintf(stdout, "%s t%d w%d %s area %.4e share %5.1f%% |", label.c_str(), t, w,
                 rail == 0 ? "high" : "low ", area * 1e6, 100 * Sum(d) / Sum(total[rail]));
    for (const Rule& r : rules) {
      const auto it = r.fields.find(k);
      if (it == r.fields.end()) continue;
      std::fprintf(stdout, " %s %.4f %5.1f%% %5.1f%% |", r.name.c_str(), Sum(it->second) / Sum(d),
                   100 * Distance(it->second, d) / Norm(d),
                   100 * Distance(it->second, d) / Norm(total[rail]));
    }
    std::fprintf(stdout, "\n");
  }
  // Whole rails.
  for (int rail = 0; rail < 2; ++rail) {
    const std::vector<double>& dref =
        rail == 0 ? ref.step.depth_per_pass_m : ref.step.low_rail->depth_per_pass_m;
    std::fprintf(stdout, "%s whole %s area %.4e |", label.c_str(), rail == 0 ? "high" : "low ",
                 Sum(dref) * (rail == 0 ? h_high : h_low) * 1e6);
    for (const Rule& r : rules) {
      const std::vector<double>& d =
          rail == 0 ? r.step.depth_per_pass_m : r.step.low_rail->depth_per_pass_m;
      std::fprintf(stdout, " %s %.4f %5.1f%% |", r.name.c_str(), Sum(d) / Sum(dref),
                   100 * Distance(d, dref) / Norm(dref));
    }
    std::fprintf(stdout, "\n");
  }
  std::fflush(stdout);
  // Node responses.
  for (const Rule& r : rules) {
    for (const LoadCaseSummary& s : r.step.cases) {
      const LoadCase& c = s.load_case;
      std::fprintf(stderr, "node,%s,%s,%d,%d,%s,%.6f,%.6e,%.6e,%.3f,%.3f,%d\n", label.c_str(),
                   r.name.c_str(), c.traffic_index, c.wheelset,
                   c.rail == RailSide::kHigh ? "high" : "low", c.spread_x, c.weight,
                   s.worn_area_per_pass_m2 * 1e6, s.contact_angle_rad * 180 / M_PI,
                   s.contact_y_m * 1e3, s.patches);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4 && argc != 7) {
    std::cerr << "usage: spread_depth_study SCENE.toml NODES [ADAPTIVE_TOL] [DB RUN STEPS]\n";
    return 2;
  }
  try {
    const std::vector<std::string> nodes = Split(argv[2]);
    const double tolerance = argc >= 4 ? std::stod(argv[3]) : 0.0;
    if (argc == 7) {
      const ProfileStore store = app::OpenExistingStudy(argv[4]);
      const RunInfo run = app::FindRunOrThrow(store, argv[5]);
      app::Scene scene = app::ParseScene(run.scene_text, argv[1]);
      const UnwornRails unworn = UnwornRails::Of(app::StateFromStore(store, run.id, 0));
      for (const std::string& s : Split(argv[6])) {
        const WearState state = app::StateFromStore(store, run.id, std::stoi(s));
        Study(*scene.wear, unworn, state, nodes, tolerance,
              "step" + s + "@" + std::to_string(state.mgt).substr(0, 4) + "MGT");
      }
    } else {
      app::Scene scene = app::LoadScene(argv[1]);
      const WearState state = internal::InitialState(*scene.wear);
      Study(*scene.wear, UnwornRails::Of(state), state, nodes, tolerance, "unworn");
    }
  } catch (const std::exception& e) {
    std::cerr << "spread_depth_study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
