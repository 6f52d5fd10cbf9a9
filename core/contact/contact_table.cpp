// ContactTable (see contact_table.h).
#include "core/contact/contact_table.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "core/contact/contact_forces.h"
#include "core/contact/fastsim.h"
#include "core/contact/hertz_estimate.h"
#include "core/contact/kalker_coefficients.h"
#include "core/contact/rigid_motion.h"
#include "core/contact/wheelset_contact.h"
#include "core/numerics/input_error.h"
#include "core/numerics/parallel.h"

namespace railwear {

namespace {

constexpr double kRollSampling_m = 2e-4;  // the roll's fixed-point steps (the curving's as well)

// Shen, Hedrick and Elkins' saturation (Vehicle System Dynamics 12, 1983): the linear creep
// force F' of magnitude u mu N becomes mu N (u - u^2/3 + u^3/27) up to u = 3, mu N beyond; the
// factor on F'.
double SaturationFactor(double linear_N, double limit_N) {
  if (!(linear_N > 0.0) || !(limit_N > 0.0)) return 1.0;
  const double u = linear_N / limit_N;
  if (u >= 3.0) return 1.0 / u;
  return 1.0 - u / 3.0 + u * u / 27.0;
}

// One loaded candidate of an evaluation: its Hertz ellipse and where it lies.
struct LoadedPoint {
  double normal_N = 0.0;
  double a_m = 0.0, b_m = 0.0;  // semi-axes along x and laterally
  Eigen::Vector3d point_m;      // contact point, R (x the lead under yaw)
  Eigen::Vector3d normal;       // rail outward normal, R
  Eigen::Vector3d tangent;      // lateral tangent (0, n_z, -n_y), R
};

struct PreparedWheel {
  bool left = false;
  std::vector<LoadedPoint> points;
  WheelRigidMotion motion;  // pitch velocity set per trial
  double normal_N = 0.0;
};

// The rail's force on the wheel at one point, R, for pitch velocity omega.
Eigen::Vector3d PointForce(const LoadedPoint& p, const WheelRigidMotion& m, double omega, double G,
                           double nu, double friction) {
  WheelRigidMotion mo = m;
  mo.pitch_velocity_rad_s = omega;
  const double V = mo.speed_m_s;
  const Eigen::Vector3d v = mo.SlipVelocity(p.point_m);
  const double xi = v.x() / V;
  const double eta = v.dot(p.tangent) / V;
  // Spin about the pressure centre, as the grids' creepage fields define it (kinematics.h:
  // w_s = eta + phi x): phi = ((omega_wheel x e_x) . t) / V.
  const Eigen::Vector3d w =
      omega * mo.axle_direction + Eigen::Vector3d(0.0, 0.0, mo.yaw_velocity_rad_s);
  const double phi = w.cross(Eigen::Vector3d::UnitX()).dot(p.tangent) / V;
  const LinearCreepForces lin = CalcLinearCreepForces(p.a_m, p.b_m, G, nu, xi, eta, phi);
  const double f =
      SaturationFactor(std::hypot(lin.force_x_N, lin.force_y_N), friction * p.normal_N);
  return p.normal_N * p.normal + f * lin.force_x_N * Eigen::Vector3d::UnitX() +
         f * lin.force_y_N * p.tangent;
}

// The contact point's data at lateral position y [m], interpolated between the stations around
// it (clamped to the first and last).
ContactTable::Wheel::Station StationAt(const std::vector<ContactTable::Wheel::Station>& st,
                                       double y_m) {
  const int m = static_cast<int>(st.size());
  int i = 0;
  while (i + 2 < m && st[i + 1].y_m < y_m) ++i;
  const double t = std::clamp((y_m - st[i].y_m) / (st[i + 1].y_m - st[i].y_m), 0.0, 1.0);
  ContactTable::Wheel::Station out;
  out.y_m = y_m;
  out.rail_point_m = (1.0 - t) * st[i].rail_point_m + t * st[i + 1].rail_point_m;
  out.normal = ((1.0 - t) * st[i].normal + t * st[i + 1].normal).normalized();
  out.dx_dpsi_m = (1.0 - t) * st[i].dx_dpsi_m + t * st[i + 1].dx_dpsi_m;
  out.wheel_radius_m = (1.0 - t) * st[i].wheel_radius_m + t * st[i + 1].wheel_radius_m;
  return out;
}

// The virtual interpenetration patches of one wheel (ContactTableOptions::Patch::
// kInterpenetration; Kik and Piotrowski 1996), one per physical contact region: the runs of
// adjacent samples of the wheel's whole gap where the wheel's approach delta overlaps the rail
// (gap < delta). Two candidates split at a saddle that the approach overlaps are one region, so
// a region does not depend on where FindCandidates splits the gap (which moves from node to
// node at a flat gauge corner). In each run, of smallest gap g0, the virtual penetration is
// ratio x (delta - g0): the strips j of depth d_j = ratio (delta - g0) - (g_j - g0) > 0 reach
// x = +-sqrt(2 r d_j) along the rail (the wheel's circle of radius r), so the area is
// sum 2 sqrt(2 r d_j) dy; the lateral extent from the first to the last such strip (the
// depth's zero crossings interpolated between samples: continuous in delta, and across a
// shallow saddle inside the run the region is joined) is 2 b, and a = area / (pi b). The
// contact point is the strips' load centre, each strip's load taken as its depth (Hertz's strip
// loads are in proportion to it), with the rail point, normal and lead interpolated between the
// stations there. A run with fewer than 3 strips inside (a patch narrower than the sampling)
// gives no patch: its candidates keep their Hertz ellipses.
struct Interpenetration {
  double a_m = 0.0, b_m = 0.0;
  double y_lo_m = 0.0, y_hi_m = 0.0;  // the run (gap < delta), to which candidates belong
  ContactTable::Wheel::Station centre;
};
std::vector<Interpenetration> InterpenetrationPatches(const ContactTable::Wheel::Samples& s,
                                                      double delta_m, double ratio) {
  std::vector<Interpenetration> out;
  const int n = static_cast<int>(s.y_m.size());
  if (n < 3 || s.stations.size() < 2) return out;
  auto adjacent = [&](int j, int k) {
    return k >= 0 && k < n && std::abs(s.index[k] - s.index[j]) == 1;
  };
  const double h = s.y_m[1] - s.y_m[0];
  for (int j = 0; j < n;) {
    if (!(s.gap_m[j] < delta_m)) {
      ++j;
      continue;
    }
    int k = j;
    double g0 = s.gap_m[j];
    while (k + 1 < n && adjacent(k, k + 1) && s.gap_m[k + 1] < delta_m) {
      ++k;
      g0 = std::min(g0, s.gap_m[k]);
    }
    const int run_lo = j, run_hi = k;
    j = k + 1;
    const double level = g0 + ratio * (delta_m - g0);  // the virtual penetration's gap level
    double sum_d = 0.0, sum_dy = 0.0, area = 0.0;
    int inside = 0, first = -1, last = -1;
    for (int i = run_lo; i <= run_hi; ++i) {
      const double d = level - s.gap_m[i];
      if (!(d > 0.0)) continue;
      if (first < 0) first = i;
      last = i;
      ++inside;
      sum_d += d;
      sum_dy += d * s.y_m[i];
      area += 2.0 * std::sqrt(2.0 * StationAt(s.stations, s.y_m[i]).wheel_radius_m * d) * h;
    }
    if (inside < 3) continue;
    auto crossing = [&](int in, int out_i) {  // where the depth reaches 0 between two samples
      if (!adjacent(in, out_i)) return s.y_m[in] + 0.5 * (in < out_i ? h : -h);
      const double d_in = level - s.gap_m[in];
      const double d_out = level - s.gap_m[out_i];
      return s.y_m[in] + (s.y_m[out_i] - s.y_m[in]) * d_in / (d_in - d_out);
    };
    Interpenetration e;
    e.b_m = 0.5 * (crossing(last, last + 1) - crossing(first, first - 1));
    e.a_m = area / (std::numbers::pi * e.b_m);
    e.y_lo_m = s.y_m[run_lo] - 0.5 * h;
    e.y_hi_m = s.y_m[run_hi] + 0.5 * h;
    e.centre = StationAt(s.stations, sum_dy / sum_d);
    out.push_back(e);
  }
  return out;
}

}  // namespace

ContactTable::ContactTable(const ContactTableGeometry& geometry, const ContactTableOptions& options)
    : geometry_(geometry), options_(options) {
  const auto t0 = std::chrono::steady_clock::now();
  const ContactTableOptions& o = options_;
  if (!(o.node_spacing_m > 0.0) || !(o.half_range_m > 0.0) || !(o.sampling_m > 0.0) ||
      !(o.candidate_threshold_m > 0.0)) {
    throw InputError(
        fmt::format("contact table: node_spacing_m = {}, half_range_m = {}, sampling_m = {}, "
                    "candidate_threshold_m = {}: expected each > 0",
                    o.node_spacing_m, o.half_range_m, o.sampling_m, o.candidate_threshold_m));
  }
  if (o.patch == ContactTableOptions::Patch::kInterpenetration &&
      (!(o.penetration_ratio > 0.0 && o.penetration_ratio <= 1.0) ||
       !(o.station_spacing_m > 0.0))) {
    throw InputError(
        fmt::format("contact table: interpenetration patches with penetration_ratio = {}, "
                    "station_spacing_m = {}: expected a ratio in (0, 1] and a spacing > 0",
                    o.penetration_ratio, o.station_spacing_m));
  }
  const int n = 2 * static_cast<int>(std::lround(o.half_range_m / o.node_spacing_m)) + 1;
  if (n < 3) {
    throw InputError(
        fmt::format("contact table: half_range_m = {} with node_spacing_m = {} gives "
                    "{} nodes: expected at least 3",
                    o.half_range_m, o.node_spacing_m, n));
  }
  nodes_.resize(n);
  const WheelsetSpec& base = geometry_.wheelset;
  ParallelFor(n, o.threads, [&](int i) {
    Node& node = nodes_[i];
    node.y_m = (i - (n - 1) / 2) * o.node_spacing_m;
    WheelsetSpec ws = base;
    ws.lateral_displacement_m = node.y_m;
    ws.yaw_rad = 0.0;
    // The roll from both wheels touching their rails (wheelset.h's KinematicRoll, on a coarse
    // sampling: a height to a micrometre is 1e-6 / 1.5 m of roll), then the geometry at that roll.
    const KinematicRollResult kinematic = KinematicRoll(
        geometry_.high_wheel, geometry_.high_rail, geometry_.low_wheel, geometry_.low_rail,
        geometry_.gauge_points, geometry_.track, ws, std::max(o.sampling_m, kRollSampling_m));
    if (!kinematic.both_touch) return;
    const double roll = kinematic.roll_rad;
    ws.roll_rad = roll;
    const WheelsetPlacement placed = PlaceWheelsetAt(geometry_.gauge_points, geometry_.track, ws);
    const WheelRailGeometry high(geometry_.high_wheel, geometry_.high_rail, placed.right,
                                 o.sampling_m);
    const WheelRailGeometry low(geometry_.low_wheel, geometry_.low_rail, placed.left, o.sampling_m);
    if (!high.has_overlap() || !low.has_overlap()) return;
    node.roll_rad = roll;
    node.placement = placed;
    auto fill = [&](const WheelRailGeometry& g, Wheel* w) {
      w->pose = g.pose();
      w->candidates = g.FindCandidates(o.candidate_threshold_m);
      w->contact = !w->candidates.empty();
      w->axle_yz_m = g.WheelToRail({0.0, -g.pose().rolling_radius_m});
      w->origin_yz_m = g.WheelToRail({0.0, 0.0});
      // A body of revolution yawed by psi touches a prismatic rail where its normal has no
      // x part: at x = -psi (y_w + rho drho/dy_w) to first order (y_w along the axle, rho the
      // radius; drho/dy_w the profile's slope in W, from the contact normal).
      auto dx_dpsi = [&](const ContactCandidate& c) {
        const double y_w = g.RailToWheel(c.rail_point_m).x();
        const Eigen::Vector2d n_w = g.RailDirectionToWheel(c.normal);
        const double slope = std::abs(n_w.y()) > 1e-9 ? -n_w.x() / n_w.y() : 0.0;
        return -(y_w + c.wheel_radius_m * slope);
      };
      const std::vector<double>& gy = g.gap_samples_y();
      const std::vector<double>& gg = g.gap_samples();
      const bool stations = o.patch == ContactTableOptions::Patch::kInterpenetration;
      for (const ContactCandidate& c : w->candidates) {
        w->dx_dpsi_m.push_back(dx_dpsi(c));
        if (!stations) continue;
        for (size_t j = 0; j < gy.size(); ++j) {
          if (gy[j] >= c.y_lo_m && gy[j] <= c.y_hi_m && std::isfinite(gg[j])) {
            w->samples.y_m.push_back(gy[j]);
            w->samples.gap_m.push_back(gg[j]);
            w->samples.index.push_back(static_cast<int>(j));
          }
        }
        const int m =
            std::max(1, static_cast<int>(std::ceil((c.y_hi_m - c.y_lo_m) / o.station_spacing_m)));
        for (int j = 0; j <= m; ++j) {
          const ContactCandidate at = g.CandidateAt(c, c.y_lo_m + (c.y_hi_m - c.y_lo_m) * j / m);
          w->samples.stations.push_back(
              {at.rail_point_m.x(), at.rail_point_m, at.normal, dx_dpsi(at), at.wheel_radius_m});
        }
      }
    };
    fill(high, &node.high);
    fill(low, &node.low);
  });
  build_time_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

ContactTableForces ContactTable::EvaluateNode(int i, double yaw_rad,
                                              const ContactTableLoad& load) const {
  ContactTableForces out;
  const Node& node = nodes_.at(i);
  if (!node.high.contact || !node.low.contact) {
    out.why_not = fmt::format("no contact on the {} wheel at y = {:.2f} mm in the contact table",
                              node.high.contact ? "low" : "high", node.y_m * 1e3);
    return out;
  }
  WheelsetSpec ws = geometry_.wheelset;
  ws.lateral_displacement_m = node.y_m;
  ws.yaw_rad = yaw_rad;
  ws.roll_rad = node.roll_rad;
  const WheelsetPlacement placed = PlaceWheelsetAt(geometry_.gauge_points, geometry_.track, ws);
  WheelMotion axle;
  axle.speed_m_s = load.speed_m_s;
  const double r0 = ws.rolling_radius_m;
  const WheelMotions motions = CurveWheelMotions(axle, placed, load.curvature_per_m, r0);
  const double estar = ContactModulus(load.wheel_material, load.rail_material);
  const CombinedElastic elastic = CombineElastic(load.wheel_material, load.rail_material);

  auto prepare = [&](const Wheel& w, const WheelPose& pose, const WheelMotion& motion, double q,
                     bool left) {
    PreparedWheel p;
    p.left = left;
    p.motion = MakeWheelRigidMotion(w.axle_yz_m, w.origin_yz_m, w.pose.roll_rad, pose.yaw_rad,
                                    w.pose.rolling_radius_m, motion);
    const double delta = internal::HertzApproachForLoad(w.candidates, w.pose.roll_rad, estar, q);
    std::vector<HertzSolution> hs;
    internal::HertzVerticalLoad(w.candidates, w.pose.roll_rad, estar, delta, &hs);
    auto add = [&](double normal_N, double a_m, double b_m, const Eigen::Vector2d& rail_point,
                   const Eigen::Vector2d& normal, double dx) {
      LoadedPoint lp;
      lp.normal_N = normal_N;
      lp.a_m = a_m;
      lp.b_m = b_m;
      lp.point_m = {dx * pose.yaw_rad, rail_point.x(), rail_point.y()};
      lp.normal = {0.0, normal.x(), normal.y()};
      lp.tangent = {0.0, normal.y(), -normal.x()};
      p.normal_N += lp.normal_N;
      p.points.push_back(lp);
    };
    // (kInterpenetration) The wheel's physical regions and the vertical load of the Hertz
    // candidates in each (the candidates' load sharing, kept; the patch's normal force carries
    // that vertical load along the patch's own normal, as the wheel's vertical balance has it).
    const std::vector<Interpenetration> regions =
        options_.patch == ContactTableOptions::Patch::kInterpenetration
            ? InterpenetrationPatches(w.samples, delta, options_.penetration_ratio)
            : std::vector<Interpenetration>{};
    std::vector<double> region_vertical_N(regions.size(), 0.0);
    for (size_t k = 0; k < w.candidates.size(); ++k) {
      if (!(hs[k].force_N > 0.0)) continue;
      const ContactCandidate& c = w.candidates[k];
      const auto in = std::find_if(regions.begin(), regions.end(), [&](const Interpenetration& e) {
        return c.y_m >= e.y_lo_m && c.y_m <= e.y_hi_m;
      });
      if (in != regions.end()) {
        region_vertical_N[in - regions.begin()] +=
            hs[k].force_N * internal::CandidateCurvatures(c, w.pose.roll_rad).w0;
        continue;
      }
      add(hs[k].force_N, hs[k].semi_axis_x_m, hs[k].semi_axis_y_m, c.rail_point_m, c.normal,
          w.dx_dpsi_m[k]);
    }
    for (size_t r = 0; r < regions.size(); ++r) {
      if (!(region_vertical_N[r] > 0.0)) continue;
      const Interpenetration& e = regions[r];
      const double w0 = std::max(-e.centre.normal.y(), 1e-3);  // as CandidateCurvatures'
      add(region_vertical_N[r] / w0, e.a_m, e.b_m, e.centre.rail_point_m, e.centre.normal,
          e.centre.dx_dpsi_m);
    }
    return p;
  };
  const std::array<PreparedWheel, 2> wheels = {
      prepare(node.high, placed.right, motions.right, load.high_load_N, false),
      prepare(node.low, placed.left, motions.left, load.low_load_N, true)};
  const double G = elastic.shear_modulus_Pa, nu = elastic.poisson_ratio;
  auto axle_fx = [&](double omega) {
    double fx = 0.0;
    for (const PreparedWheel& w : wheels) {
      for (const LoadedPoint& p : w.points) {
        fx += PointForce(p, w.motion, omega, G, nu, load.friction).x();
      }
    }
    return fx - load.axle_force_N;
  };
  // The pitch velocity: F_x grows as the wheel turns faster (omega more negative), so the root
  // is bracketed from pure rolling outward and bisected to a micro-fraction of the adhesion.
  const double omega0 = -load.speed_m_s / r0;
  double lo = omega0 * 0.98, hi = omega0 * 1.02;  // lo: slower (F_x lower), hi: faster
  for (int k = 0; k < 8 && axle_fx(lo) > 0.0; ++k) lo = omega0 + 2.0 * (lo - omega0);
  for (int k = 0; k < 8 && axle_fx(hi) < 0.0; ++k) hi = omega0 + 2.0 * (hi - omega0);
  const double tol_N = 1e-6 * load.friction * (wheels[0].normal_N + wheels[1].normal_N);
  double omega = 0.5 * (lo + hi);
  for (int k = 0; k < 80; ++k) {
    omega = 0.5 * (lo + hi);
    const double g = axle_fx(omega);
    if (std::abs(g) <= tol_N) break;
    (g > 0.0 ? hi : lo) = omega;
  }
  out.pitch_velocity_rad_s = omega;
  out.roll_rad = node.roll_rad;
  const double half_span =
      (0.5 * ws.flange_back_distance_m - ws.flange_back_position_m) * std::sin(yaw_rad);
  for (const PreparedWheel& w : wheels) {
    ContactTableWheelForces& wf = w.left ? out.low : out.high;
    wf.normal_force_N = w.normal_N;
    for (const LoadedPoint& p : w.points) {
      const Eigen::Vector3d f_rail_frame = PointForce(p, w.motion, omega, G, nu, load.friction);
      const Eigen::Vector3d f = RailToTrackFrame(f_rail_frame, w.left);
      const double y_rail = p.point_m.y();
      const double Y =
          w.left ? placed.left_rail_origin_Y_m - y_rail : placed.right_rail_origin_Y_m + y_rail;
      const double x = (w.left ? half_span : -half_span) + p.point_m.x();
      out.force_N += f;
      out.yaw_moment_Nm += x * f.y() - Y * f.x();
      wf.lateral_force_on_rail_N -= f_rail_frame.y();
      wf.largest_contact_angle_rad =
          std::max(wf.largest_contact_angle_rad, std::atan2(std::abs(p.normal.y()), -p.normal.z()));
      ++wf.loaded_points;
    }
  }
  out.valid = true;
  return out;
}

ContactTableForces ContactTable::Evaluate(double y_m, double yaw_rad,
                                          const ContactTableLoad& load) const {
  const int n = size();
  const double y0 = nodes_.front().y_m, h = options_.node_spacing_m;
  if (!(y_m >= y0 && y_m <= nodes_.back().y_m)) {
    ContactTableForces out;
    out.why_not = fmt::format("y = {:.2f} mm is outside the contact table's +-{:.1f} mm", y_m * 1e3,
                              options_.half_range_m * 1e3);
    return out;
  }
  const int i = std::clamp(static_cast<int>(std::floor((y_m - y0) / h)), 0, n - 2);
  const double t = std::clamp((y_m - nodes_[i].y_m) / h, 0.0, 1.0);
  const ContactTableForces a = EvaluateNode(i, yaw_rad, load);
  if (!a.valid) return a;
  const ContactTableForces b = EvaluateNode(i + 1, yaw_rad, load);
  if (!b.valid) return b;
  ContactTableForces out;
  out.valid = true;
  auto mix = [t](double u, double v) { return (1.0 - t) * u + t * v; };
  out.force_N = (1.0 - t) * a.force_N + t * b.force_N;
  out.yaw_moment_Nm = mix(a.yaw_moment_Nm, b.yaw_moment_Nm);
  out.pitch_velocity_rad_s = mix(a.pitch_velocity_rad_s, b.pitch_velocity_rad_s);
  out.roll_rad = mix(a.roll_rad, b.roll_rad);
  auto wheel = [&](const ContactTableWheelForces& u, const ContactTableWheelForces& v) {
    ContactTableWheelForces w;
    w.normal_force_N = mix(u.normal_force_N, v.normal_force_N);
    w.lateral_force_on_rail_N = mix(u.lateral_force_on_rail_N, v.lateral_force_on_rail_N);
    w.largest_contact_angle_rad = mix(u.largest_contact_angle_rad, v.largest_contact_angle_rad);
    w.loaded_points = std::max(u.loaded_points, v.loaded_points);
    return w;
  };
  out.high = wheel(a.high, b.high);
  out.low = wheel(a.low, b.low);
  return out;
}

}  // namespace railwear
