#include "wear/traffic.h"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "wear/collective_traffic.h"
#include "wear/spread_integration.h"

namespace railwear {

std::string_view ToString(RailSide side) { return EnumToString(kRailSideNames, side); }

std::optional<RailSide> RailSideFromString(std::string_view name) {
  return EnumFromString(kRailSideNames, name);
}

bool TrafficCase::RunsOn(RailSide side) const {
  if (is_vehicle()) return true;
  if (is_collective()) return EntryCount(collective->collective, side) > 0;
  return rail == side;
}

static_assert(kMaxQuadraturePoints >= kMaxSpreadNodes,
              "fixed rules as fine as the adaptive rule's finest spread (traffic.h)");

void GaussHermiteProbabilists(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  RAILWEAR_CHECK(n >= 1 && n <= kMaxQuadraturePoints);
  // Golub-Welsch: the Jacobi matrix of the monic probabilists' Hermite polynomials has zero
  // diagonal and off-diagonal sqrt(k); nodes are its eigenvalues, weights the squared first
  // components of its normalised eigenvectors (the total mass of N(0,1) is 1).
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    jacobi(k, k - 1) = jacobi(k - 1, k) = std::sqrt(static_cast<double>(k));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jacobi);
  nodes->assign(n, 0.0);
  weights->assign(n, 0.0);
  for (int k = 0; k < n; ++k) {
    (*nodes)[k] = eig.eigenvalues()(k);
    (*weights)[k] = eig.eigenvectors()(0, k) * eig.eigenvectors()(0, k);
  }
  // Symmetrise exactly (the distribution is symmetric; keeps mirrored cases mirrored).
  for (int k = 0; k < n / 2; ++k) {
    const double x = 0.5 * ((*nodes)[n - 1 - k] - (*nodes)[k]);
    const double w = 0.5 * ((*weights)[n - 1 - k] + (*weights)[k]);
    (*nodes)[k] = -x;
    (*nodes)[n - 1 - k] = x;
    (*weights)[k] = (*weights)[n - 1 - k] = w;
  }
  if (n % 2 == 1) (*nodes)[n / 2] = 0.0;
}

void FixedSpreadRule(int quadrature_points, const std::vector<double>& linear_nodes,
                     std::vector<double>* nodes, std::vector<double>* weights) {
  if (linear_nodes.empty()) {
    GaussHermiteProbabilists(quadrature_points, nodes, weights);
  } else {
    *nodes = linear_nodes;
    *weights = LinearGaussianWeights(linear_nodes);
  }
}

namespace {

void Require(bool ok, const TrafficCase& c, const char* key, double value, const char* expected) {
  if (!ok || !std::isfinite(value)) {
    throw InputError(fmt::format("{}: {} = {}: expected {}", c.name, key, value, expected));
  }
}

}  // namespace

const Profile& CaseWheelProfile(const TrafficCase& entry, const LoadCase& load_case) {
  if (!entry.is_vehicle() || entry.vehicle_wheels.empty()) return entry.wheel_profile;
  const WheelsetWheels& w = entry.vehicle_wheels[load_case.wheelset];
  return load_case.rail == RailSide::kHigh ? w.high : w.low;
}

std::string WheelName(const TrafficCase& entry, int wheel) {
  if (wheel == 0) return entry.name;
  return fmt::format("{} / wheelset {} {}", entry.name, WheelsetOfWheel(wheel),
                     ToString(RailOfWheel(wheel)));
}

void ValidateTraffic(const std::vector<TrafficCase>& traffic) {
  if (traffic.empty()) throw InputError("traffic: no entries: expected at least one [[traffic]]");
  for (const TrafficCase& c : traffic) {
    Require(c.friction > 0.0 && c.friction <= 2.0, c, "friction", c.friction, "in (0, 2]");
    Require(c.speed_m_s > 0.0, c, "speed_m_s", c.speed_m_s, "> 0");
    Require(c.share > 0.0, c, "share", c.share, "> 0");
    Require(c.axle_load_t > 0.0, c, "axle_load_t", c.axle_load_t, "> 0");
    Require(c.lateral_shift_std_m >= 0.0, c, "lateral_shift_mm.std", c.lateral_shift_std_m * 1e3,
            ">= 0");
    if (c.wheel_wear) {
      Require(c.wheel_wear->distance_per_pass_m > 0.0 && c.wheel_wear->distance_per_pass_m <= 1e7,
              c, "wheel_wear.distance_per_pass_m", c.wheel_wear->distance_per_pass_m,
              "a distance in (0, 1e7] m");
      if (c.wheel_wear->hardness_Pa) {
        Require(*c.wheel_wear->hardness_Pa > 0.0, c, "wheel_wear.hardness_MPa",
                *c.wheel_wear->hardness_Pa * 1e-6, "> 0");
      }
    }
    if (c.is_vehicle()) continue;  // its wheels and positions come from the vehicle
    if (c.is_collective()) {       // its positions, loads and speeds come from its bins
      Require(c.rolling_radius_m > 0.0, c, "rolling_radius_mm", c.rolling_radius_m * 1e3, "> 0");
      if (c.collective->collective.entries.empty()) {
        throw InputError(fmt::format("{}: collective: no bins: expected at least one", c.name));
      }
      continue;
    }
    Require(c.rolling_radius_m > 0.0, c, "rolling_radius_mm", c.rolling_radius_m * 1e3, "> 0");
    Require(c.vertical_force_N > 0.0, c, "vertical_N", c.vertical_force_N, "> 0");
    Require(true, c, "lateral_shift_mm.mean", c.lateral_shift_mean_m * 1e3, "a finite number");
    Require(true, c, "roll_rad", c.roll_rad, "a finite number");
    Require(std::abs(c.yaw_rad) < 0.1, c, "yaw_mrad", c.yaw_rad * 1e3, "|yaw| < 100 mrad");
  }
}

void ValidateQuadraturePoints(int quadrature_points) {
  if (quadrature_points < 1 || quadrature_points > kMaxQuadraturePoints) {
    throw InputError(fmt::format("wear: quadrature_points = {}: expected 1 to {}",
                                 quadrature_points, kMaxQuadraturePoints));
  }
}

std::vector<LoadCase> ExpandTraffic(const std::vector<TrafficCase>& traffic,
                                    int quadrature_points) {
  ValidateTraffic(traffic);
  ValidateQuadraturePoints(quadrature_points);
  return internal::ExpandValidTraffic(traffic, quadrature_points);
}

namespace internal {

LoadCase PrescribedNodeCase(const std::vector<TrafficCase>& traffic, int t,
                            const std::array<double, 2>& rail_share_totals, double x, int node,
                            double node_weight) {
  const TrafficCase& c = traffic[t];
  LoadCase lc;
  lc.traffic_index = t;
  lc.node = node;
  lc.spread_x = x;
  lc.rail = c.rail;
  lc.placement.lateral_shift_m =
      x == 0.0 ? c.lateral_shift_mean_m : c.lateral_shift_mean_m + c.lateral_shift_std_m * x;
  lc.placement.roll_rad = c.roll_rad;
  lc.placement.rolling_radius_m = c.rolling_radius_m;
  lc.placement.yaw_rad = c.yaw_rad;
  lc.vertical_force_N = c.vertical_force_N;
  lc.motion.speed_m_s = c.speed_m_s;  // pure rolling at r0: no pitch velocity
  lc.friction = c.friction;
  // Shares are normalised per rail: each rail's case weights sum to 1.
  lc.weight = c.share / rail_share_totals[static_cast<int>(c.rail)] * node_weight;
  return lc;
}

std::vector<LoadCase> ExpandValidTraffic(const std::vector<TrafficCase>& traffic,
                                         int quadrature_points,
                                         const std::vector<double>& linear_nodes) {
  const std::array<double, 2> total_share = RailShareTotals(traffic);
  std::vector<double> nodes, weights;
  FixedSpreadRule(quadrature_points, linear_nodes, &nodes, &weights);
  std::vector<LoadCase> cases;
  for (int t = 0; t < static_cast<int>(traffic.size()); ++t) {
    const TrafficCase& c = traffic[t];
    if (c.is_vehicle() || c.is_collective()) continue;
    if (c.lateral_shift_std_m == 0.0) {
      cases.push_back(PrescribedNodeCase(traffic, t, total_share, 0.0, 0, 1.0));
      continue;
    }
    for (int k = 0; k < static_cast<int>(nodes.size()); ++k) {
      cases.push_back(PrescribedNodeCase(traffic, t, total_share, nodes[k], k, weights[k]));
    }
  }
  return cases;
}

}  // namespace internal

std::array<double, 2> RailShareTotals(const std::vector<TrafficCase>& traffic) {
  std::array<double, 2> total = {0.0, 0.0};
  for (const TrafficCase& c : traffic) {
    for (const RailSide side : {RailSide::kHigh, RailSide::kLow}) {
      if (c.RunsOn(side)) total[static_cast<int>(side)] += c.share;
    }
  }
  return total;
}

bool HasTrafficOn(const std::vector<TrafficCase>& traffic, RailSide side) {
  for (const TrafficCase& c : traffic) {
    if (c.RunsOn(side)) return true;
  }
  return false;
}

std::vector<TrafficCase> ExpandWheelPopulation(const TrafficCase& entry,
                                               const std::vector<PopulationWheel>& wheels) {
  if (entry.is_vehicle()) {
    throw InputError(fmt::format(
        "{}: a wheel population on a vehicle entry: expected a prescribed or collective entry (a "
        "vehicle's wheels are its own)",
        entry.name));
  }
  if (wheels.empty()) {
    throw InputError(
        fmt::format("{}: wheel population: no wheels: expected at least one wheel", entry.name));
  }
  double total = 0.0;
  for (size_t i = 0; i < wheels.size(); ++i) {
    const PopulationWheel& w = wheels[i];
    const std::string where = fmt::format("{}: wheel population: wheel {} ('{}')", entry.name,
                                          i, w.name);
    if (w.name.empty()) throw InputError(where + ": no name: expected a name");
    if (!(w.weight > 0.0) || !std::isfinite(w.weight)) {
      throw InputError(fmt::format("{}: weight = {}: expected a finite number > 0", where,
                                   w.weight));
    }
    if (!(w.rolling_radius_m > 0.0) || !std::isfinite(w.rolling_radius_m)) {
      throw InputError(fmt::format("{}: rolling_radius_mm = {}: expected > 0", where,
                                   w.rolling_radius_m * 1e3));
    }
    if (w.profile.size() < 2) throw InputError(where + ": empty profile: expected a wheel profile");
    for (size_t j = 0; j < i; ++j) {
      if (wheels[j].name == w.name) {
        throw InputError(fmt::format("{}: the name is wheel {}'s too: expected unique names", where,
                                     j));
      }
    }
    total += w.weight;
  }
  std::vector<TrafficCase> out;
  for (const PopulationWheel& w : wheels) {
    TrafficCase c = entry;
    c.name = fmt::format("{} / {}", entry.name, w.name);
    c.wheel_profile = w.profile;
    c.rolling_radius_m = w.rolling_radius_m;
    c.share = entry.share * (w.weight / total);
    out.push_back(std::move(c));
  }
  return out;
}

double MgtPerPass(const std::vector<TrafficCase>& traffic) {
  // A pass is one axle: counted once, from the high rail's wheels (the low rail's without any).
  const RailSide counted =
      HasTrafficOn(traffic, RailSide::kHigh) ? RailSide::kHigh : RailSide::kLow;
  double share = 0.0, tonnes = 0.0;
  for (const TrafficCase& c : traffic) {
    if (!c.RunsOn(counted)) continue;
    share += c.share;
    tonnes += c.share * c.axle_load_t;
  }
  return tonnes / share / 1e6;
}

}  // namespace railwear
