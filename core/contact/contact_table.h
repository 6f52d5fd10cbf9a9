// ContactTable: the rigid contact geometry of a wheelset on its two rails, tabulated against the
// wheelset's lateral displacement y at zero yaw, and the wheelset's contact forces from it with
// Hertz ellipses and Kalker's creep coefficients, as multibody codes compute them (Wickens,
// Fundamentals of Rail Vehicle Dynamics, ch. 2 and 8; Polach, Vehicle System Dynamics 2005, for
// the saturation): the cheap predictor of steady-state curving (core/vehicle/curving.h,
// CurvingPredictor::kTable).
//
// Built once per wheel and rail profile pair (a wear run: once per step, the rails change): at
// each node y_i (equal steps over [-half_range, half_range]) both wheels are placed at yaw 0
// (PlaceWheelsetAt), the wheelset rolled so that both touch their rails (two fixed-point steps
// on the wheels' heights, as the curving's own kinematic roll), and every contact candidate of
// each wheel's placed geometry (WheelRailGeometry::FindCandidates within candidate_threshold_m,
// so a second point that closes under load, the flange beside the tread, is kept) is stored with
// its gap, contact point, normal, radius and curvatures.
//
// Evaluate(y, psi): at the two nodes around y the wheelset's forces are computed and blended
// linearly in y (each node's candidate set is its own: no candidate matching across nodes):
//   1. normal part: per wheel the common vertical approach that carries the wheel load over all
//      candidates (Hertz at each, hertz_estimate.h's HertzApproachForLoad: two-point contact
//      shares the load by the candidates' gaps); the creep forces' vertical part is left out of
//      this balance (the grid models include it);
//   2. creepages at each loaded candidate's contact point from the wheel's rigid motion in the
//      curve (CurveWheelMotions, WheelRigidMotion::SlipVelocity: speed, pitch velocity, the
//      curve's yaw rate), the yaw psi entering through the axle's direction and the contact
//      point's lead x = psi dx/dpsi (first order: dx/dpsi = -(y_w + rho drho/dy_w) on the wheel's
//      body of revolution);
//   3. creep forces from Kalker's linear theory on the Hertz ellipse (CalcLinearCreepForces,
//      with spin), saturated by Shen, Hedrick and Elkins' formula at mu N;
//   4. the pitch velocity so that both wheels' F_x add up to the axle force (bisection).
// Approximations, stated: Hertz's constant curvatures over each patch (the conformal flange
// root is one ellipse per candidate, not a wrapped patch); geometry at yaw 0 with the lead to
// first order; linear creep theory with an empirical saturation instead of the rolling-contact
// solver. Its equilibrium is a start for the full model, never a result: docs/curving.md "Cost"
// measures how far it lies from the full model's.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "core/geometry/wheelset.h"
#include "core/profile/profile.h"

namespace railwear {

struct ContactTableOptions {
  // Nodes over [-half_range, half_range] of the wheelset's y (S1002 on UIC60 1:40 is in flange
  // contact from about 6 mm); their spacing; the placed geometries' lateral sampling of the gap
  // (the roll's two steps sample at 0.2 mm, as the curving's kinematic roll does). 0.1 mm and
  // 0.1 mm: 0.2 mm each took the main job's cold solves from 16-20 wheelset solves to 20-44
  // (docs/curving.md "Cost").
  double half_range_m = 0.012;
  double node_spacing_m = 1e-4;
  double sampling_m = 1e-4;
  // Candidates up to this gap at first contact are kept (a wheel load's approach is 50-100 um).
  double candidate_threshold_m = 3e-4;
  int threads = 0;  // of the build (nodes are independent): 0 = the hardware threads
  // Each loaded candidate's patch: kHertz (the default), Hertz's ellipse from the curvatures at
  // the smallest gap, placed there; kInterpenetration, one patch per physical contact region
  // (Kik and Piotrowski, Vehicle System Dynamics 1996; Piotrowski and Chollet 2005): the
  // wheel's whole sampled gap is cut into the runs where the wheel's approach overlaps the
  // rail (gap < approach; candidates whose saddle lies inside one run are one region), each
  // run's virtual interpenetration at penetration_ratio times its own approach gives b (its
  // lateral extent), its area pi a b and its load centre (contact point, normal, lead), and it
  // carries the vertical load of the Hertz candidates inside it. On
  // S1002/UIC60 the tread and the gauge corner are nearly conformal, and Hertz at the smallest
  // gap put the patch 1-4 mm from the grids' pressure centre with half their width
  // (docs/curving.md, "The table's patches"); it brings the table's equilibrium nearer the full
  // model's, but the wagon's finish at draft took more solves: an option, not the default.
  enum class Patch { kHertz, kInterpenetration };
  Patch patch = Patch::kHertz;
  // (kInterpenetration; the constructor throws InputError outside (0, 1] and > 0.)
  double penetration_ratio = 0.55;  // Kik and Piotrowski's; 0.5 gives the circular Hertz area
  double station_spacing_m = 1e-3;  // the contact point's data along each candidate's interval
};

// What a table is built from: the wheelset's wheels and rails in their own frames (the low wheel
// and rail mirrored as WheelsetProblem's left ones are), where the rails stand, and the
// wheelset's flange-back distance, flange-back position and rolling radius (its y, yaw and roll
// are the table's).
struct ContactTableGeometry {
  Profile high_wheel, low_wheel, high_rail, low_rail;
  RailGaugePoints gauge_points;
  TrackSpec track;
  WheelsetSpec wheelset;
};

// The conditions of one evaluation (besides y and psi).
struct ContactTableLoad {
  double high_load_N = 0.0, low_load_N = 0.0;  // vertical wheel loads
  double speed_m_s = 20.0;                     // the wheelset centre's
  double curvature_per_m = 0.0;                // curve turning toward -Y (the high rail at +Y)
  double friction = 0.3;
  double axle_force_N = 0.0;  // the wheels' F_x sum: traction (> 0), braking (< 0), 0 free rolling
  Material wheel_material, rail_material;
};

// One wheel's contact in a table evaluation.
struct ContactTableWheelForces {
  double normal_force_N = 0.0;             // all candidates
  double lateral_force_on_rail_N = 0.0;    // the wheel's on its rail, rail frame y (field side +)
  double largest_contact_angle_rad = 0.0;  // of the loaded candidates
  int loaded_points = 0;
};

struct ContactTableForces {
  bool valid = false;  // false: y outside the table, or a node without contact on a wheel
  std::string why_not;
  // The rails' forces on the wheelset, track frame (x forward, Y toward the high rail) [N], and
  // their yaw moment about the wheelset's centre (+z down) [N m], as the curving sums them.
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  double yaw_moment_Nm = 0.0;
  double pitch_velocity_rad_s = 0.0;
  double roll_rad = 0.0;
  ContactTableWheelForces high, low;
};

class ContactTable {
 public:
  // Throws InputError for bad options (spacing or range not > 0, fewer than 3 nodes).
  ContactTable(const ContactTableGeometry& geometry, const ContactTableOptions& options = {});

  // The forces at lateral displacement y [m] and yaw psi [rad] (both against the local track),
  // blended linearly between the two nodes around y.
  ContactTableForces Evaluate(double y_m, double yaw_rad, const ContactTableLoad& load) const;
  // The forces from node i's geometry alone (no blending), at that node's y.
  ContactTableForces EvaluateNode(int i, double yaw_rad, const ContactTableLoad& load) const;

  // One wheel's tabulated geometry at a node (the placed geometry's, at yaw 0).
  struct Wheel {
    bool contact = false;
    WheelPose pose;
    std::vector<ContactCandidate> candidates;  // FindCandidates(candidate_threshold_m)
    // Per candidate: the wheel point's lateral coordinate in the wheel frame and the contact
    // point's lead per radian of yaw, dx/dpsi [m].
    std::vector<double> dx_dpsi_m;
    // (kInterpenetration) The wheel's sampled gap over all its candidates' intervals, in
    // lateral order (positions, gaps [m], R, and each sample's index in the placed geometry's
    // sampling, so that runs of adjacent samples are found), and the contact point's data at
    // stations along each interval (the candidates' stations in lateral order): the
    // interpenetration regions are taken from this whole gap, not per candidate.
    struct Station {
      double y_m = 0.0;
      Eigen::Vector2d rail_point_m = Eigen::Vector2d::Zero(), normal = Eigen::Vector2d::Zero();
      double dx_dpsi_m = 0.0;
      double wheel_radius_m = 0.0;
    };
    struct Samples {
      std::vector<double> y_m, gap_m;
      std::vector<int> index;
      std::vector<Station> stations;
    };
    Samples samples;
    Eigen::Vector2d axle_yz_m = Eigen::Vector2d::Zero();    // W (0, -r0) in R
    Eigen::Vector2d origin_yz_m = Eigen::Vector2d::Zero();  // W (0, 0) in R
  };
  struct Node {
    double y_m = 0.0;
    double roll_rad = 0.0;
    WheelsetPlacement placement;  // at yaw 0
    Wheel high, low;
  };
  int size() const { return static_cast<int>(nodes_.size()); }
  const Node& node(int i) const { return nodes_[i]; }
  double build_time_s() const { return build_time_s_; }
  const ContactTableOptions& options() const { return options_; }

 private:
  ContactTableGeometry geometry_;
  ContactTableOptions options_;
  std::vector<Node> nodes_;
  double build_time_s_ = 0.0;
};

}  // namespace railwear
