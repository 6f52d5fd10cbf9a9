// Both wheels of a wheelset on their rails.
#include "core/contact/wheelset_contact.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "core/contact/contact_forces.h"
#include "core/contact/hertz_tread.h"
#include "core/contact/normal_part_memo.h"
#include "core/contact/rolling_stage.h"
#include "core/numerics/input_error.h"

namespace railwear {

namespace {
// Rounds of (balanced solve at the pitch velocity, pitch-velocity search) for an axle force
// target under a prescribed load.
constexpr int kBalanceRounds = 8;

// The status message of an axle force target friction cannot carry.
std::string AxleForceNotCarried(double target_N, double reached_N, double mu_fn_N) {
  return fmt::format(
      "the axle's longitudinal force {:.1f} N cannot be carried: friction limits it to about "
      "{:.1f} N here (mu F_n = {:.1f} N)",
      target_N, std::abs(reached_N), mu_fn_N);
}

// Both wheels on the fast tread path (hertz_tread.h), each wheel's problem (*right_wheel,
// *left_wheel) placed and moving as SolveWheelset set it up, the axle force target (if any)
// already taken out of them. Every evaluation is the fast path's whole solve (placement, Hertz's
// ellipse, the tangential solution and the vertical balance), so the pitch search needs no balance
// rounds: its root is the balanced wheels'. False, with the wheel and the reason in *why_not, when
// either contact is not one Hertzian patch at the axle's pitch velocities the search tries.
bool SolveTreadWheels(ContactProblem* right_wheel, ContactProblem* left_wheel,
                      std::optional<double> target, const WheelsetProblem& problem,
                      WheelsetResult* out, std::string* why_not) {
  ContactProblem& right = *right_wheel;  // (their pitch velocities change with the search)
  ContactProblem& left = *left_wheel;
  auto solve = [&](const ContactProblem& wheel, const char* side, ContactResult* result,
                   HertzTreadPoint* point) {
    std::string why;
    auto fast = SolveHertzTread(wheel, &why, point);
    if (!fast) {
      *why_not = fmt::format("{} wheel: {}", side, why);
      return false;
    }
    *result = std::move(*fast);
    return true;
  };
  HertzTreadPoint right_point, left_point;
  auto both = [&](std::optional<double> omega) {
    if (omega) {
      right.rolling->motion.pitch_velocity_rad_s = *omega;
      left.rolling->motion.pitch_velocity_rad_s = *omega;
    }
    return solve(right, "right", &out->right, &right_point) &&
           solve(left, "left", &out->left, &left_point);
  };
  if (!both(std::nullopt)) return false;
  if (target && out->right.status == SolverStatus::kConverged &&
      out->left.status == SolverStatus::kConverged) {
    bool valid = true;
    double last_N = TotalForceX(out->right) + TotalForceX(out->left);
    auto fx = [&](double omega) {
      if (valid && both(omega)) {
        last_N = TotalForceX(out->right) + TotalForceX(out->left);
      } else {
        valid = false;
      }
      return last_N;
    };
    const double mu_fn =
        right.rolling->friction * (TotalNormalForce(out->right) + TotalNormalForce(out->left));
    const double tolerance_N = problem.axle_force_tolerance_N.value_or(1e-6 * mu_fn);
    const auto omega =
        SolvePitchVelocityForForce(fx, *target, problem.wheel_rail.rolling->motion.speed_m_s,
                                   problem.wheelset.rolling_radius_m, tolerance_N);
    if (!valid) return false;
    if (!omega) {
      const std::string message = AxleForceNotCarried(*target, last_N, mu_fn);
      for (ContactResult* r : {&out->right, &out->left}) {
        r->status = SolverStatus::kNotConverged;
        r->message = message;
      }
    } else if (!both(*omega)) {  // the wheels at the root, balanced
      return false;
    }
  }
  // Each wheel's point of the results returned (the C API's wheel-frame location: without it
  // rw_get_patch would look for a placed geometry the fast path never built).
  out->right_tread_point = right_point;
  out->left_tread_point = left_point;
  return true;
}

}  // namespace

WheelMotions CurveWheelMotions(const WheelMotion& axle, const WheelsetPlacement& placed,
                               double curvature_per_m, double rolling_radius_m) {
  WheelMotions out{axle, axle};
  const double ydot = axle.lateral_velocity_m_s, psidot = axle.yaw_velocity_rad_s;
  if (curvature_per_m == 0.0 && ydot == 0.0 && psidot == 0.0) return out;
  const double v = axle.speed_m_s;
  // Each wheel's origin: its distance from the curve's centre, and the wheelset's own yaw rate
  // about its centre (a wheel at +Y goes back at psidot Y), set its forward speed.
  const double y_right = placed.right_rail_origin_Y_m + placed.right.lateral_shift_m;
  const double y_left = placed.left_rail_origin_Y_m - placed.left.lateral_shift_m;
  out.right.speed_m_s = v * (1.0 + curvature_per_m * y_right) - psidot * y_right;
  out.left.speed_m_s = v * (1.0 + curvature_per_m * y_left) - psidot * y_left;
  // The wheelset turns with the curve (toward -Y) and at its own yaw rate; the left rail's frame
  // is mirrored (y toward its field side, -Y), so its yaw rate and lateral velocity change sign.
  out.right.yaw_velocity_rad_s = psidot - v * curvature_per_m;
  out.left.yaw_velocity_rad_s = v * curvature_per_m - psidot;
  if (ydot != 0.0) out.left.lateral_velocity_m_s = -ydot;  // (no -0.0 where there is none)
  // One axle, one pitch velocity: pure rolling of the centre's speed at r0 unless given.
  const double omega = axle.pitch_velocity_rad_s.value_or(-v / rolling_radius_m);
  out.right.pitch_velocity_rad_s = omega;
  out.left.pitch_velocity_rad_s = omega;
  return out;
}

WheelsetResult SolveWheelset(const WheelsetProblem& problem, PlacementCache* cache,
                             ContactWarmStart* right_warm, ContactWarmStart* left_warm) {
  WheelsetResult out;
  const Profile& right_rail = problem.wheel_rail.rail_profile;
  const Profile& left_rail =
      problem.left_rail_profile ? *problem.left_rail_profile : problem.wheel_rail.rail_profile;
  // Each rail's gauge point (PlaceWheelset's), kept by the cache across calls on the same rails.
  auto gauge_point = [&](PlacementCache::Slot slot, const Profile& rail) {
    const double h = problem.track.gauge_height_m;
    return (cache ? cache->GaugePoint(slot, rail, h) : RailGaugePoint(rail, h)).x();
  };
  if (problem.gauge_points) {
    out.placement = PlaceWheelsetAt(*problem.gauge_points, problem.track, problem.wheelset);
  } else if (problem.left_rail_profile) {
    out.placement = PlaceWheelsetAt({gauge_point(PlacementCache::kRight, right_rail),
                                     gauge_point(PlacementCache::kLeft, left_rail)},
                                    problem.track, problem.wheelset);
  } else {
    const double y_g = gauge_point(PlacementCache::kRight, right_rail);
    out.placement = PlaceWheelsetAt({y_g, y_g}, problem.track, problem.wheelset);
  }
  const WheelPose& r = out.placement.right;
  const WheelPose& l = out.placement.left;

  ContactProblem right = problem.wheel_rail;
  right.placement = {r.lateral_shift_m, r.roll_rad, r.rolling_radius_m, r.yaw_rad};

  // The left wheel and rail are the mirror images of the right ones in the track; in the left
  // rail's own frame (y toward its field side) they are the same profiles, so only the pose
  // (PlaceWheelset) and the yaw are mirrored.
  ContactProblem left = problem.wheel_rail;
  if (problem.left_rail_profile) left.rail_profile = *problem.left_rail_profile;
  if (problem.left_wheel_profile) left.wheel_profile = *problem.left_wheel_profile;
  left.placement = {l.lateral_shift_m, l.roll_rad, l.rolling_radius_m, l.yaw_rad};
  if (problem.left_vertical_force_N) {
    if (!left.load.vertical_force_N) {
      throw InputError("wheelset: a left wheel load needs a prescribed vertical load");
    }
    left.load.vertical_force_N = problem.left_vertical_force_N;
  }
  if (right.rolling) {
    const WheelMotions m =
        CurveWheelMotions(problem.wheel_rail.rolling->motion, out.placement,
                          problem.curvature_per_m, problem.wheelset.rolling_radius_m);
    right.rolling->motion = m.right;
    left.rolling->motion = m.left;
  }

  // A force target applies to the axle: both wheels share its pitch velocity, and their F_x add
  // up to the target. Solve both normal problems once, then only the rolling stage per trial.
  std::optional<double> target;
  if (right.rolling && right.rolling->longitudinal_force_N) {
    target = right.rolling->longitudinal_force_N;
    right.rolling->longitudinal_force_N.reset();
    left.rolling->longitudinal_force_N.reset();
  }
  // kind = hertz with rolling contact: both wheels on the fast tread path, or the whole wheelset
  // on its fallback (kind = auto at the same accuracy), each patch's model_reason saying why.
  if (IsHertzRolling(problem.wheel_rail)) {
    std::string why_not;
    if (SolveTreadWheels(&right, &left, target, problem, &out, &why_not)) return out;
    WheelsetProblem fallback = problem;
    fallback.wheel_rail.model = HertzTreadFallbackModel(problem.wheel_rail.model);
    WheelsetResult full = SolveWheelset(fallback, cache);
    MarkTreadFallback(why_not, &full.right);
    MarkTreadFallback(why_not, &full.left);
    return full;
  }
  // Each wheel's placed geometry, built once for all its solves and the trials of the search
  // (or kept from an earlier solve at the same pose: PlacementCache).
  std::optional<WheelRailGeometry> own_right, own_left;
  auto place = [&](PlacementCache::Slot slot, const ContactProblem& wheel, const WheelPose& pose,
                   std::optional<WheelRailGeometry>* own) -> const WheelRailGeometry& {
    if (cache) return cache->Get(slot, wheel.wheel_profile, wheel.rail_profile, pose);
    return own->emplace(wheel.wheel_profile, wheel.rail_profile, pose);
  };
  const WheelRailGeometry& right_geom = place(PlacementCache::kRight, right, r, &own_right);
  const WheelRailGeometry& left_geom = place(PlacementCache::kLeft, left, l, &own_left);
  // Each wheel's normal part (the grids, operators and normal solves, which do not depend on
  // the pitch velocity) kept for the solves of the balance rounds below (normal_part_memo.h);
  // only an axle force target has such rounds. Each round's vertical balance starts from the
  // last round's balanced state (warm balance): the same balance to its tolerance in fewer
  // normal solves.
  internal::NormalPartMemo right_memo(internal::NormalPartMemo::kWarmBalance),
      left_memo(internal::NormalPartMemo::kWarmBalance);
  // Each wheel may start warm; with a target the rounds below continue from this solve's
  // normal part (the memo), warm or cold.
  out.right =
      internal::SolveContact(right, right_geom, 0.0, target ? &right_memo : nullptr, right_warm);
  out.left = internal::SolveContact(left, left_geom, 0.0, target ? &left_memo : nullptr, left_warm);
  if (!target || out.right.status != SolverStatus::kConverged ||
      out.left.status != SolverStatus::kConverged) {
    return out;
  }
  auto fx = [&](double omega) {
    right.rolling->motion.pitch_velocity_rad_s = omega;
    left.rolling->motion.pitch_velocity_rad_s = omega;
    ApplyRolling(right, right_geom, &out.right);
    ApplyRolling(left, left_geom, &out.left);
    return TotalForceX(out.right) + TotalForceX(out.left);
  };
  const double mu_fn =
      right.rolling->friction * (TotalNormalForce(out.right) + TotalNormalForce(out.left));
  const double tolerance_N = problem.axle_force_tolerance_N.value_or(1e-6 * mu_fn);
  const auto omega =
      SolvePitchVelocityForForce(fx, *target, problem.wheel_rail.rolling->motion.speed_m_s,
                                 problem.wheelset.rolling_radius_m, tolerance_N);
  if (!omega) {
    const std::string message =
        AxleForceNotCarried(*target, TotalForceX(out.right) + TotalForceX(out.left), mu_fn);
    for (ContactResult* r : {&out.right, &out.left}) {
      r->status = SolverStatus::kNotConverged;
      r->message = message;
    }
    return out;
  }
  // The normal problems were balanced (vertical load with the creep forces) at the first pitch
  // velocity: solve both wheels again at the one found, and search again from there, until
  // the balanced wheels carry the target.
  double found = *omega;
  if (!right.load.vertical_force_N) {
    fx(found);  // a prescribed approach: the normal solution does not depend on the creep forces
  } else {
    for (int round = 0; round < kBalanceRounds; ++round) {
      right.rolling->motion.pitch_velocity_rad_s = found;
      left.rolling->motion.pitch_velocity_rad_s = found;
      out.right = internal::SolveContact(right, right_geom, 0.0, &right_memo);
      out.left = internal::SolveContact(left, left_geom, 0.0, &left_memo);
      if (out.right.status != SolverStatus::kConverged ||
          out.left.status != SolverStatus::kConverged || round + 1 == kBalanceRounds) {
        break;
      }
      const double error = TotalForceX(out.right) + TotalForceX(out.left) - *target;
      if (std::abs(error) <= tolerance_N) break;
      const auto again =
          SolvePitchVelocityForForce(fx, *target, problem.wheel_rail.rolling->motion.speed_m_s,
                                     problem.wheelset.rolling_radius_m, tolerance_N);
      if (!again) break;
      found = *again;
    }
  }
  out.right.climb = CheckFlangeClimb(out.right, right.rolling->friction);
  out.left.climb = CheckFlangeClimb(out.left, left.rolling->friction);
  return out;
}

}  // namespace railwear
