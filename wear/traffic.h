// Traffic mix of a wear run: the wheels that pass over the rail, each with its share of passes,
// and their expansion into the load cases one wear step solves.
//
// A traffic entry's lateral wheel position is normally distributed (mean, standard deviation):
// the expectation over it is integrated by Gauss-Hermite quadrature (probabilists' form, nodes
// and weights by the Golub-Welsch eigenvalue method), so a load case is one traffic entry at one
// quadrature node, weighted by share x quadrature weight. With std = 0 an entry is one load case.
//
// Totals: a wheel pass of entry c carries axle_load_t of gross tonnage, so one pass of the mix
// is sum_c share_c axle_load_t_c / 1e6 MGT (million gross tonnes).
#pragma once

#include <string>
#include <vector>

#include "core/profile/profile.h"

namespace railwear {

struct TrafficCase {
  std::string name;                   // for messages and reports, e.g. "traffic[0]"
  Profile wheel_profile;              // wheel profile frame (core/notation.md)
  double rolling_radius_m = 0.46;     // wheel radius at the wheel profile's z = 0, > 0
  double vertical_force_N = 0.0;      // wheel load on this rail, > 0
  double axle_load_t = 0.0;           // axle load for the MGT count [tonnes], > 0
  double lateral_shift_mean_m = 0.0;  // wheel profile origin in the track frame [m]
  double lateral_shift_std_m = 0.0;   // >= 0
  double roll_rad = 0.0;
  double yaw_rad = 0.0;     // angle of attack of the wheel [rad]
  double friction = 0.3;    // > 0
  double speed_m_s = 20.0;  // > 0
  double share = 1.0;       // relative share of passes, > 0 (normalised over the mix)
};

// One contact problem of a wear step.
struct LoadCase {
  int traffic_index = 0;         // into the traffic vector
  int node = 0;                  // quadrature node (0 when std = 0)
  double lateral_shift_m = 0.0;  // this node's lateral position
  double weight = 0.0;           // share (normalised) x quadrature weight; sums to 1 over cases
};

// Nodes x_k and weights w_k (sum 1) with E[f(X)] ~ sum_k w_k f(x_k) for X ~ N(0, 1), exact for
// polynomials up to degree 2n - 1. n in [1, 20].
void GaussHermiteProbabilists(int n, std::vector<double>* nodes, std::vector<double>* weights);

// Checks every entry (positive loads, radii, speeds, friction, shares; std >= 0; finite values)
// and throws InputError naming the entry and the value.
void ValidateTraffic(const std::vector<TrafficCase>& traffic);

// Throws InputError unless quadrature_points (Gauss-Hermite nodes per entry) is 1 to 20.
void ValidateQuadraturePoints(int quadrature_points);

// The load cases of the mix: each entry at `quadrature_points` Gauss-Hermite nodes (1 when its
// std is 0), in entry order. Weights sum to 1. Validates the traffic and quadrature_points.
std::vector<LoadCase> ExpandTraffic(const std::vector<TrafficCase>& traffic, int quadrature_points);

namespace internal {
// ExpandTraffic without its checks, for the wear loop, whose study was validated once at its
// entry (ValidateWearStudy): the traffic is not checked again at every step.
std::vector<LoadCase> ExpandValidTraffic(const std::vector<TrafficCase>& traffic,
                                         int quadrature_points);
}  // namespace internal

// Million gross tonnes per wheel pass of the mix: sum_c share_c axle_load_t_c / (1e6 sum share).
double MgtPerPass(const std::vector<TrafficCase>& traffic);

}  // namespace railwear
