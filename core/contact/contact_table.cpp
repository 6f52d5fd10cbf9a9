// ContactTable (see contact_table.h).
#include "core/contact/contact_table.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

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

// A candidate's virtual interpenetration patch (ContactTableOptions::Patch::kInterpenetration;
// Kik and Piotrowski 1996): where the sampled vertical gap lies below ratio x the candidate's
// approach (the wheel's approach delta less the candidate's smallest gap). Each lateral strip j
// of depth d_j reaches x = +-sqrt(2 r d_j) along the rail (the wheel's circle of radius r), so
// the region's area is sum 2 sqrt(2 r d_j) dy; its lateral extent (the depth's zero crossings,
// interpolated between samples: continuous in delta) is 2 b, and a = area / (pi b). The contact
// point is the strips' load centre, each strip's load taken as its depth (Hertz's strip loads
// are in proportion to it), with the rail point, normal and lead interpolated between the
// stations there. Empty (Hertz at the smallest gap is kept) without samples, or when fewer than
// 3 samples are inside: a patch narrower than the sampling.
struct Interpenetration {
  double a_m = 0.0, b_m = 0.0;
  Eigen::Vector2d rail_point_m, normal;
  double dx_dpsi_m = 0.0;
};
std::optional<Interpenetration> InterpenetrationPatch(const ContactTable::Wheel::Samples& s,
                                                      const ContactCandidate& c, double delta_m,
                                                      double ratio) {
  const int n = static_cast<int>(s.y_m.size());
  if (n < 3 || s.stations.size() < 2) return std::nullopt;
  const double depth = ratio * (delta_m - c.gap_m);
  if (!(depth > 0.0)) return std::nullopt;
  const double h = s.y_m[1] - s.y_m[0];
  double sum_d = 0.0, sum_dy = 0.0, area = 0.0;
  int inside = 0, first = -1, last = -1;
  for (int j = 0; j < n; ++j) {
    const double d = depth - (s.gap_m[j] - c.gap_m);
    if (!(d > 0.0)) continue;
    if (first < 0) first = j;
    last = j;
    ++inside;
    sum_d += d;
    sum_dy += d * s.y_m[j];
    area += 2.0 * std::sqrt(2.0 * c.wheel_radius_m * d) * h;
  }
  if (inside < 3) return std::nullopt;
  auto crossing = [&](int in, int out) {  // where the depth reaches 0 between two samples
    if (out < 0 || out >= n) return s.y_m[in] + 0.5 * (in < out ? h : -h);
    const double d_in = depth - (s.gap_m[in] - c.gap_m);
    const double d_out = depth - (s.gap_m[out] - c.gap_m);
    return s.y_m[in] + (s.y_m[out] - s.y_m[in]) * d_in / (d_in - d_out);
  };
  const double y_a = crossing(first, first - 1), y_b = crossing(last, last + 1);
  Interpenetration e;
  e.b_m = 0.5 * (y_b - y_a);
  e.a_m = area / (std::numbers::pi * e.b_m);
  const double y_c = sum_dy / sum_d;
  const auto& st = s.stations;
  const int m = static_cast<int>(st.size());
  int i = 0;
  while (i + 2 < m && st[i + 1].y_m < y_c) ++i;
  const double t = std::clamp((y_c - st[i].y_m) / (st[i + 1].y_m - st[i].y_m), 0.0, 1.0);
  e.rail_point_m = (1.0 - t) * st[i].rail_point_m + t * st[i + 1].rail_point_m;
  e.normal = ((1.0 - t) * st[i].normal + t * st[i + 1].normal).normalized();
  e.dx_dpsi_m = (1.0 - t) * st[i].dx_dpsi_m + t * st[i + 1].dx_dpsi_m;
  return e;
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
      for (const ContactCandidate& c : w->candidates) {
        w->dx_dpsi_m.push_back(dx_dpsi(c));
        Wheel::Samples smp;
        if (o.patch == ContactTableOptions::Patch::kInterpenetration) {
          for (size_t j = 0; j < gy.size(); ++j) {
            if (gy[j] >= c.y_lo_m && gy[j] <= c.y_hi_m && std::isfinite(gg[j])) {
              smp.y_m.push_back(gy[j]);
              smp.gap_m.push_back(gg[j]);
            }
          }
          const int m =
              std::max(1, static_cast<int>(std::ceil((c.y_hi_m - c.y_lo_m) / o.station_spacing_m)));
          for (int j = 0; j <= m; ++j) {
            const ContactCandidate at = g.CandidateAt(c, c.y_lo_m + (c.y_hi_m - c.y_lo_m) * j / m);
            smp.stations.push_back({at.rail_point_m.x(), at.rail_point_m, at.normal, dx_dpsi(at)});
          }
        }
        w->samples.push_back(std::move(smp));
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
    for (size_t k = 0; k < w.candidates.size(); ++k) {
      if (!(hs[k].force_N > 0.0)) continue;
      const ContactCandidate& c = w.candidates[k];
      LoadedPoint lp;
      lp.normal_N = hs[k].force_N;
      lp.a_m = hs[k].semi_axis_x_m;
      lp.b_m = hs[k].semi_axis_y_m;
      Eigen::Vector2d rail_point = c.rail_point_m, normal = c.normal;
      double dx = w.dx_dpsi_m[k];
      if (const auto e =
              InterpenetrationPatch(w.samples[k], c, delta, options_.penetration_ratio)) {
        lp.a_m = e->a_m;
        lp.b_m = e->b_m;
        rail_point = e->rail_point_m;
        normal = e->normal;
        dx = e->dx_dpsi_m;
      }
      lp.point_m = {dx * pose.yaw_rad, rail_point.x(), rail_point.y()};
      lp.normal = {0.0, normal.x(), normal.y()};
      lp.tangent = {0.0, normal.y(), -normal.x()};
      p.normal_N += lp.normal_N;
      p.points.push_back(lp);
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
