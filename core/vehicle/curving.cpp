// Steady-state curving (see curving.h).
#include "core/vehicle/curving.h"
#include "core/vehicle/curving_internal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "core/contact/contact_forces.h"
#include "core/contact/contact_warm_start.h"
#include "core/contact/rolling_stage.h"
#include "core/numerics/input_error.h"
#include "core/numerics/parallel.h"

namespace railwear {

namespace {

constexpr double kHalfBase_m = 0.75;  // l0: half the distance between the contact points
// A Newton iteration whose line search fails within this multiple of the tolerance has met the
// noise of the contact forces against the position (the grid moves with the patch): converged.
constexpr double kNoiseFloor = 3.0;
constexpr double kStepY_m = 2e-4;  // finite-difference steps of the contact Jacobian
constexpr double kStepYaw_rad = 2e-4;
// When no step from a fresh Jacobian reduces the residual: the steps times this, once.
constexpr double kCoarseStepFactor = 4.0;
// A draft solve stalled within this multiple of the tolerance goes on on the standard grid.
constexpr double kNearStall = 20.0;
constexpr double kMaxStepY_m = 2e-3;  // Newton steps are scaled down to these per iteration
constexpr double kMaxStepYaw_rad = 2e-3;
// Pseudo-transient continuation (Equilibrium::Relax) hands over to Newton below this shift.
constexpr double kNewtonSigma = 1e-2;
// A start that is not the last gives up when its merit fell by less than kStallRatio over
// kStallWindow iterations above kNearStall x the tolerance (Equilibrium::Solve).
constexpr int kStallWindow = 6;
constexpr double kStallRatio = 0.95;

// A wheel climbs when its contact lies on the flange beyond the flange's steepest flank, toward
// its tip: there the contact angle, and with it the flange's lateral restoring force, falls as
// the wheel moves on, so no steady state lies there (Nadal's limit is taken at the steepest
// angle for this reason). The flank's tip-side end is where the front face's slope comes within
// kFlankAngleBand_rad of its largest; a contact counts as beyond it kClimbMargin_m past that end,
// well outside the contact point's lateral error (the wheel-frame y is taken as the rail-frame
// y less the wheel's lateral shift, without the roll: under 0.3 mm at 10 mrad of roll and a
// contact 30 mm below the wheel's profile origin).
constexpr double kFlankAngleBand_rad = 0.5 * std::numbers::pi / 180.0;
constexpr double kClimbMargin_m = 1e-3;
constexpr double kClimbLoadShare = 0.5;
// ... and only when the wheelset's roll lifts one wheel over the other by more than this: a
// wheel in flange contact on its steepest flank is lifted by about 1 mm (S1002 on UIC60 1:40,
// roll 0.7 mrad at 70 deg), one that climbed toward the tip by much more (the near-climb coach's
// climbed state: 14.7 mm, roll 9.8 mrad), one on a worn gauge corner by less (step 66: 0.9 mrad).
constexpr double kClimbLift_m = 3e-3;
constexpr double kFlankScanStep_m = 1e-4;

}  // namespace

namespace internal {

double SteepestFlankTipSideY(const Profile& wheel) {
  // The tip: the profile's deepest point (z grows downward, the flange reaches below the tread).
  const int n = std::max(2, static_cast<int>(std::ceil(wheel.Length() / kFlankScanStep_m)));
  std::vector<double> y(n + 1), z(n + 1), angle(n + 1);
  int tip = 0;
  for (int k = 0; k <= n; ++k) {
    const double s = wheel.Length() * k / n;
    Eigen::Vector2d p, d1;
    wheel.Evaluate(s, &p, &d1, nullptr);
    y[k] = p.x();
    z[k] = p.y();
    angle[k] = std::atan2(std::abs(d1.y()), std::abs(d1.x()));
    if (z[k] > z[tip]) tip = k;
  }
  // The front face: from the tip toward the tread (larger y), down to the taping line's depth
  // (z = 0).
  const int dir = (tip + 1 <= n && y[tip + 1] > y[tip]) ? 1 : -1;
  double steepest = 0.0;
  int end = tip;
  for (int k = tip; k >= 0 && k <= n && z[k] > 0.0; k += dir) {
    steepest = std::max(steepest, angle[k]);
    end = k;
  }
  for (int k = tip; k != end + dir; k += dir) {
    if (angle[k] >= steepest - kFlankAngleBand_rad) return y[k];
  }
  return y[tip];
}

}  // namespace internal

namespace {

// Whether the wheel of `result` (its rail's frame) at `pose` rides on its flange beyond the
// steepest flank (see kClimbMargin_m): the patches there carry more than half of the wheel's
// vertical load (kClimbLoadShare); EvaluateWheelset also asks for the lift (kClimbLift_m).
// `flank_y_m` is that flank's tip-side end (wheel frame). A worn gauge corner can touch the
// flange's upper part beside the wheel's main contact without any climb (on the 10 MGT study's worn
// rails at 5.2 MGT, a temporary trace, not committed, showed a third patch 1.2 mm beyond the
// flank's end at 61 deg with up to 13 % of the load, the wheel 1.5 mm off its centred place): that
// is no climb, so the load decides, not the place alone.
bool Climbing(const ContactResult& result, const WheelPose& pose, double flank_y_m) {
  double beyond_N = 0.0, all_N = 0.0;
  for (const PatchResult& patch : result.patches) {
    all_N += patch.vertical_force_N;
    if (patch.contact_point_yz_m.x() - pose.lateral_shift_m < flank_y_m - kClimbMargin_m) {
      beyond_N += patch.vertical_force_N;
    }
  }
  return all_N > 0.0 && beyond_N > kClimbLoadShare * all_N;
}

// The layout of a vehicle: per wheelset and bogie its position x from the car body's centre and
// the index of its bogie; the unknown vector is [wheelsets (y, psi)..., bogies (y, psi)...,
// body (y, psi)].
struct Layout {
  int wheelsets = 1, bogies = 0;
  std::vector<double> wheelset_x, bogie_x;
  std::vector<int> bogie_of;  // per wheelset
  int size() const { return 2 * (wheelsets + bogies + (bogies > 0 ? 1 : 0)); }
  int BogieIndex(int j) const { return 2 * (wheelsets + j); }
  int BodyIndex() const { return 2 * (wheelsets + bogies); }
};

Layout MakeLayout(const VehicleSpec& v) {
  Layout l;
  l.wheelsets = v.wheelsets();
  l.bogies = v.bogies();
  if (v.kind == VehicleKind::kWheelset) {
    l.wheelset_x = {0.0};
    l.bogie_of = {-1};
    return l;
  }
  const double a = 0.5 * v.wheelbase_m, L = 0.5 * v.bogie_spacing_m;
  l.bogie_x = {L, -L};
  l.wheelset_x = {L + a, L - a, -L + a, -L - a};
  l.bogie_of = {0, 0, 1, 1};
  return l;
}

// The suspension's generalised forces (lateral force, yaw moment on each body) at state q, with
// the curve's offsets: linear in q.
Eigen::VectorXd SuspensionForces(const VehicleSpec& v, const Layout& l, double kappa,
                                 const Eigen::VectorXd& q) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
  if (l.bogies == 0) return f;
  // Absolute lateral position and yaw (against the car body centre's tangent) of a body at X.
  auto y_abs = [&](int k, double X) { return q[k] - 0.5 * kappa * X * X; };
  auto psi_abs = [&](int k, double X) { return q[k + 1] - kappa * X; };
  const double ky = 2.0 * v.primary_ky_N_m;
  const double kpsi = 2.0 * v.primary_kx_N_m * v.primary_semi_spacing_m * v.primary_semi_spacing_m;
  for (int i = 0; i < l.wheelsets; ++i) {
    const int j = l.bogie_of[i];
    const int w = 2 * i, b = l.BogieIndex(j);
    const double Xw = l.wheelset_x[i], Xb = l.bogie_x[j], x = Xw - Xb;
    const double d = y_abs(w, Xw) - (y_abs(b, Xb) + x * psi_abs(b, Xb));
    const double theta = psi_abs(w, Xw) - psi_abs(b, Xb);
    f[w] -= ky * d;
    f[w + 1] -= kpsi * theta;
    f[b] += ky * d;
    f[b + 1] += x * ky * d + kpsi * theta;
  }
  const int c = l.BodyIndex();
  for (int j = 0; j < l.bogies; ++j) {
    const int b = l.BogieIndex(j);
    const double X = l.bogie_x[j];
    const double d = y_abs(b, X) - (q[c] + X * q[c + 1]);
    const double theta = psi_abs(b, X) - q[c + 1];
    f[b] -= v.secondary_ky_N_m * d;
    f[b + 1] -= v.secondary_yaw_Nm_rad * theta;
    f[c] += v.secondary_ky_N_m * d;
    f[c + 1] += X * v.secondary_ky_N_m * d + v.secondary_yaw_Nm_rad * theta;
  }
  return f;
}

// The wheelset's roll from both wheels touching their rails (wheelset.h's KinematicRoll): taken
// without the yaw (its effect on the wheels' heights is of order yaw^2), on a coarse lateral
// sampling (dz to a micrometre is 1e-6 / 1.5 m of roll).
double WheelsetKinematicRoll(const WheelsetProblem& p) {
  constexpr double kSampling_m = 2e-4;
  const Profile& right_rail = p.wheel_rail.rail_profile;
  const Profile& left_rail = p.left_rail_profile ? *p.left_rail_profile : right_rail;
  const Profile& left_wheel =
      p.left_wheel_profile ? *p.left_wheel_profile : p.wheel_rail.wheel_profile;
  return KinematicRoll(p.wheel_rail.wheel_profile, right_rail, left_wheel, left_rail,
                       *p.gauge_points, p.track, p.wheelset, kSampling_m)
      .roll_rad;
}

// What one wheelset's contact solve needs besides its (y, psi).
struct WheelsetContext {
  const CurvingProblem* problem = nullptr;
  ModelOptions model;
  double high_load_N = 0.0, low_load_N = 0.0;
  double q0_N = 0.0;  // the static wheel load, the scale of the tolerance
  // This wheelset's own wheels (CurvingProblem::wheels), null: the vehicle's wheel_profile.
  const WheelsetWheels* wheels = nullptr;
  // The table predictor's contact functions (CurvingPredictor::kTable), null: `model`.
  const ContactTable* table = nullptr;
  // Tests' analytic forces in place of the contact and the table (curving_internal.h), null: none.
  const internal::WheelsetForceModel* forces = nullptr;
  int index = 0;  // this wheelset's, from the front
  // The contact solves start warm (CurvingOptions::warm_contact: the full model's phases only).
  bool warm = false;
  // The tip-side ends of the high and the low wheel's steepest flanks (wheel frames, each in its
  // rail's): a contact beyond one climbs (internal::SteepestFlankTipSideY, Climbing).
  double high_flank_y_m = 0.0, low_flank_y_m = 0.0;
};

// A wheelset's forces from the tests' model (internal::SolveCurvingWith): contact empty, its
// status converged.
CurvedWheelset EvaluateFromModel(const WheelsetContext& ctx, double y, double yaw) {
  const internal::WheelsetForces f = (*ctx.forces)(ctx.index, y, yaw);
  CurvedWheelset out;
  out.lateral_m = y;
  out.yaw_rad = yaw;
  out.high_load_N = ctx.high_load_N;
  out.low_load_N = ctx.low_load_N;
  out.contact.right.status = SolverStatus::kConverged;
  out.contact.left.status = SolverStatus::kConverged;
  out.force_N = Eigen::Vector3d(0.0, f.lateral_N, 0.0);
  out.yaw_moment_Nm = f.yaw_moment_Nm;
  return out;
}

// A wheelset's forces from the contact table (the table predictor's phase): its lateral force,
// yaw moment and pitch velocity; the contact results stay empty (only the full model's states
// are returned), their status converged unless the table could not place the wheelset.
CurvedWheelset EvaluateFromTable(const WheelsetContext& ctx, double y, double yaw) {
  const CurvingProblem& p = *ctx.problem;
  ContactTableLoad load;
  load.high_load_N = ctx.high_load_N;
  load.low_load_N = ctx.low_load_N;
  load.speed_m_s = p.speed_m_s;
  load.curvature_per_m = p.curve.curvature_per_m();
  load.friction = p.friction;
  load.axle_force_N = p.vehicle.traction_N_per_axle;
  load.wheel_material = p.contact.wheel_material;
  load.rail_material = p.contact.rail_material;
  const ContactTableForces f = ctx.table->Evaluate(y, yaw, load);
  CurvedWheelset out;
  out.lateral_m = y;
  out.yaw_rad = yaw;
  out.high_load_N = ctx.high_load_N;
  out.low_load_N = ctx.low_load_N;
  const SolverStatus status = f.valid ? SolverStatus::kConverged : SolverStatus::kNotConverged;
  out.contact.right.status = status;
  out.contact.left.status = status;
  out.roll_rad = f.roll_rad;
  out.pitch_velocity_rad_s = f.pitch_velocity_rad_s;
  out.force_N = f.force_N;
  out.yaw_moment_Nm = f.yaw_moment_Nm;
  out.high_lateral_N = f.high.lateral_force_on_rail_N;
  return out;
}

// What one stream of a wheelset's contact solves keeps between its calls (Equilibrium: per
// wheelset one stream for the iterates and one per finite-difference direction, each used by one
// task at a time): the placed geometries (exact, PlacementCache: a pose solved before is not
// placed again) and, with CurvingOptions::warm_contact, each wheel's warm start
// (contact_warm_start.h), cleared whenever the contact model changes.
struct ContactStream {
  PlacementCache placements;
  ContactWarmStart right, left;
};

CurvedWheelset EvaluateWheelset(const WheelsetContext& ctx, double y, double yaw,
                                ContactStream* stream = nullptr) {
  if (ctx.forces) return EvaluateFromModel(ctx, y, yaw);
  if (ctx.table) return EvaluateFromTable(ctx, y, yaw);
  const CurvingProblem& p = *ctx.problem;
  const VehicleSpec& v = p.vehicle;
  WheelsetProblem wp;
  wp.wheel_rail.setup() = p.contact;
  wp.wheel_rail.model = ctx.model;
  wp.wheel_rail.wheel_profile = ctx.wheels ? ctx.wheels->high : v.wheel_profile;
  if (ctx.wheels) wp.left_wheel_profile = ctx.wheels->low;
  wp.wheel_rail.rail_profile = p.high_rail;
  wp.wheel_rail.load.vertical_force_N = ctx.high_load_N;
  RollingOptions rolling;
  rolling.motion.speed_m_s = p.speed_m_s;
  rolling.friction = p.friction;
  rolling.longitudinal_force_N = v.traction_N_per_axle;
  wp.wheel_rail.rolling = rolling;
  wp.track = p.track;
  wp.wheelset = v.WheelsetAt(y, yaw, 0.0);
  wp.left_rail_profile = p.low_rail;
  wp.gauge_points = p.gauge_points;
  wp.left_vertical_force_N = ctx.low_load_N;
  wp.curvature_per_m = p.curve.curvature_per_m();
  // The axle's F_x to a twentieth of the equilibrium's tolerance (every round solves both wheels).
  wp.axle_force_tolerance_N = 0.05 * p.options.tolerance * ctx.q0_N;
  wp.wheelset.roll_rad = WheelsetKinematicRoll(wp);

  CurvedWheelset out;
  out.lateral_m = y;
  out.yaw_rad = yaw;
  out.roll_rad = wp.wheelset.roll_rad;
  out.high_load_N = ctx.high_load_N;
  out.low_load_N = ctx.low_load_N;
  out.contact = stream ? SolveWheelset(wp, &stream->placements, ctx.warm ? &stream->right : nullptr,
                                       ctx.warm ? &stream->left : nullptr)
                       : SolveWheelset(wp);
  out.pitch_velocity_rad_s = out.contact.right.pitch_velocity_rad_s;
  const WheelsetPlacement& placed = out.contact.placement;
  const double half_span =
      (0.5 * v.flange_back_distance_m - v.flange_back_position_m) * std::sin(yaw);
  // The rails' forces on the wheelset and their moment about its centre, patch by patch.
  auto add = [&](const ContactResult& r, bool left) {
    for (const PatchResult& patch : r.patches) {
      const Eigen::Vector3d f = -RailToTrackFrame(PatchForcesOnRail(patch).Net(), left);
      const double y_rail = patch.contact_point_yz_m.x();
      const double Y =
          left ? placed.left_rail_origin_Y_m - y_rail : placed.right_rail_origin_Y_m + y_rail;
      // The wheel's origin lies half_span sin(yaw) behind (right) or ahead of (left) the centre.
      const double x = (left ? half_span : -half_span) + patch.contact_x_m;
      out.force_N += f;
      out.yaw_moment_Nm += x * f.y() - Y * f.x();
    }
  };
  add(out.contact.right, false);
  add(out.contact.left, true);
  out.high_lateral_N = TotalForcesOnRail(out.contact.right).Net().y();
  out.high_climb = CheckFlangeClimbAtSteepest(out.contact.right, p.friction);
  out.low_climb = CheckFlangeClimbAtSteepest(out.contact.left, p.friction);
  // (and lifted: the wheelset's roll raises one wheel over the other by kClimbLift_m or more)
  const bool lifted = 2.0 * kHalfBase_m * std::abs(out.roll_rad) > kClimbLift_m;
  out.climbing = lifted && (Climbing(out.contact.right, placed.right, ctx.high_flank_y_m) ||
                            Climbing(out.contact.left, placed.left, ctx.low_flank_y_m));
  return out;
}

bool Converged(const CurvedWheelset& w) {
  return w.contact.right.status == SolverStatus::kConverged &&
         w.contact.left.status == SolverStatus::kConverged;
}

// Every one of the vehicle's `n` wheelsets evaluated, and each one's contact converged.
bool AllConverged(const std::vector<CurvedWheelset>& ws, int n) {
  return ws.size() == static_cast<size_t>(n) && std::all_of(ws.begin(), ws.end(), Converged);
}

// The Newton iteration of one phase (one contact model).
class Equilibrium {
 public:
  Equilibrium(const CurvingProblem& p, const Layout& layout, std::vector<WheelsetContext> ctx,
              double unbalanced_force_N, double q0)
      : p_(p),
        l_(layout),
        ctx_(std::move(ctx)),
        streams_(3 * layout.wheelsets),
        unbalanced_N_(unbalanced_force_N),
        q0_(q0) {
    const int n = l_.size();
    const double kappa = p.curve.curvature_per_m();
    // The suspension's stiffness: its forces are linear in q, exact by differences of one.
    const Eigen::VectorXd f0 = SuspensionForces(p.vehicle, l_, kappa, Eigen::VectorXd::Zero(n));
    suspension_offset_ = f0;
    suspension_ = Eigen::MatrixXd::Zero(n, n);
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
      e[k] = 1.0;
      suspension_.col(k) = SuspensionForces(p.vehicle, l_, kappa, e) - f0;
    }
    // The frames and the body carry no contact: their equations are linear in q, and solved
    // exactly for the wheelsets' positions at every iterate (Project).
    const int nw = 2 * l_.wheelsets, nf = n - nw;
    if (nf > 0) {
      frames_ = suspension_.bottomRightCorner(nf, nf).fullPivLu();
      frame_constant_ = suspension_offset_.tail(nf);
      frame_constant_[nf - 2] += unbalanced_N_;  // on the car body
    }
    scale_ = Eigen::VectorXd::Constant(n, 1.0 / q0_);
    for (int k = 1; k < n; k += 2) scale_[k] = 1.0 / (q0_ * kHalfBase_m);
  }

  // Sets the frames' and the body's (y, psi) in q to their equilibrium on the suspension for
  // the wheelsets' (y, psi) in q.
  void Project(Eigen::VectorXd* q) const {
    const int nw = 2 * l_.wheelsets, nf = static_cast<int>(q->size()) - nw;
    if (nf == 0) return;
    q->tail(nf) =
        frames_.solve(-(suspension_.bottomLeftCorner(nf, nw) * q->head(nw) + frame_constant_));
  }

  // Residual (generalised forces) at q; fills the wheelsets' states. False when a contact failed.
  bool Residual(const Eigen::VectorXd& q, std::vector<CurvedWheelset>* ws, Eigen::VectorXd* r) {
    if (Cancelled()) return false;  // no more contact solves; Solve stops at its next iteration
    *r = suspension_ * q + suspension_offset_;
    // The unbalanced lateral force: on the car body, or on the single wheelset.
    (*r)[l_.bogies > 0 ? l_.BodyIndex() : 0] += unbalanced_N_;
    ws->resize(l_.wheelsets);
    ParallelFor(l_.wheelsets, p_.options.threads, [&](int i) {
      (*ws)[i] = EvaluateWheelset(ctx_[i], q[2 * i], q[2 * i + 1], &streams_[3 * i]);
    });
    Count(l_.wheelsets);
    bool ok = true;
    for (int i = 0; i < l_.wheelsets; ++i) {
      (*ws)[i].x_m = l_.wheelset_x[i];
      ok = ok && Converged((*ws)[i]);
      (*r)[2 * i] += (*ws)[i].force_N.y();
      (*r)[2 * i + 1] += (*ws)[i].yaw_moment_Nm;
    }
    return ok;
  }

  // The residual at *trial with the frames and the body projected onto it (Project): false when
  // a wheelset is beyond the lateral limit (no contact solved), a contact failed or a wheel
  // climbs its flange (CurvedWheelset::climbing: no steady state there, so no step goes there;
  // docs/curving.md, "Climbed states are refused").
  bool TrialResidual(Eigen::VectorXd* trial, std::vector<CurvedWheelset>* ws, Eigen::VectorXd* r) {
    Project(trial);
    if (!WithinBounds(*trial) || !Residual(*trial, ws, r)) return false;
    if (std::any_of(ws->begin(), ws->end(), [](const CurvedWheelset& w) { return w.climbing; })) {
      climb_refused_ = true;
      return false;
    }
    return true;
  }

  // The largest scaled residual (the convergence test) and the scaled 2-norm (the line search's
  // merit: the Newton direction descends on it, not always on the largest component).
  double Norm(const Eigen::VectorXd& r) const {
    return r.cwiseProduct(scale_).cwiseAbs().maxCoeff();
  }
  double Merit(const Eigen::VectorXd& r) const { return r.cwiseProduct(scale_).norm(); }

  // Newton from q; returns iterations, or -1 when it stopped without converging (message set).
  // `give_up_on_stall`: another start follows; stop early when stalled far from the equilibrium.
  int Solve(Eigen::VectorXd* q, std::vector<CurvedWheelset>* ws, Eigen::VectorXd* r,
            std::string* message, bool* no_equilibrium, bool give_up_on_stall = false) {
    const CurvingOptions& o = p_.options;
    message->clear();
    ending_ = CurvingEnding::kNone;
    Note(internal::NewtonEvent::kSolve);
    climb_refused_ = false;
    Project(q);
    if (!Residual(*q, ws, r)) return Fail("a wheel's contact did not converge", message);
    // A start with a climbing wheel lies where no step may go (TrialResidual): the next start.
    for (int i = 0; i < l_.wheelsets; ++i) {
      if ((*ws)[i].climbing) {
        return Fail(fmt::format("wheelset {} climbs its flange at the start (a wheel touches "
                                "beyond its flange's steepest flank): no steady state there",
                                i),
                    message);
      }
    }
    first_norm_ = Norm(*r);
    // The Jacobian of the last phase (the predictor's) starts the next one as a chord.
    Eigen::MatrixXd& J = jacobian_;
    bool fresh = false;  // J was evaluated at the current q
    // A Jacobian given (the start's, or the last phase's) is first used as it is.
    double last_ratio = 0.0;
    double step_factor = 1.0;  // of the finite-difference steps
    std::vector<double> merits;    // at the start of each iteration
    double least_norm = Norm(*r);  // the smallest largest scaled residual of this solve
    for (int it = 0; it < o.max_iterations; ++it) {
      if (Cancelled()) return Fail("cancelled", message);
      if (Norm(*r) <= o.tolerance) return Ended(CurvingEnding::kTolerance, it);
      merits.push_back(Merit(*r));
      least_norm = std::min(least_norm, Norm(*r));
      // Stalled far from the equilibrium (never within the position rules' band: a natural-level
      // step may raise the residual for an iteration on the way), where another start follows: on
      // the worn rails of the R 600 m curve at 8.5 MGT (20 spread nodes, step 105) the coach's
      // centred start stepped away from the flange and spent 252 wheelset solves at 0.52 Q0, its
      // merit falling 4 % in 9 iterations, before the relaxed start (the last) converged in 188. A
      // free wheelset's centred start on R 150 m plateaus for 3 iterations (5-8 %) before it rounds
      // onto the flange (CurvingTest.HardCasesConvergeOrNameTheirStatus), hence 6 iterations and 5
      // %.
      if (give_up_on_stall && it >= kStallWindow && least_norm > kNearStall * o.tolerance &&
          merits[it] > kStallRatio * merits[it - kStallWindow]) {
        Note(internal::NewtonEvent::kStalled);
        return Fail(fmt::format("stalled far from the equilibrium: the merit fell by {:.0f} % in "
                                "{} iterations at largest scaled residual {:.1e}",
                                100.0 * (1.0 - merits[it] / merits[it - kStallWindow]),
                                kStallWindow, Norm(*r)),
                    message);
      }
      // The Jacobian is kept while it still reduces the residual fast (chord steps); a slow or
      // failed step evaluates it again.
      if (J.size() == 0 || last_ratio > 0.9) {
        J = Jacobian(*q, *ws, step_factor);
        fresh = true;
        Note(internal::NewtonEvent::kFreshJacobian);
      }
      const Eigen::FullPivLU<Eigen::MatrixXd> lu = J.fullPivLu();
      Eigen::VectorXd step = lu.solve(-*r);
      if (!step.allFinite()) return Fail("singular equilibrium Jacobian", message);
      const double before = Merit(*r);
      // Backtracking on the scaled 2-norm, on the step limited on the wheelsets (the contact
      // forces are strongly nonlinear where a flange touches; the frames and the body follow
      // the wheelsets exactly, Project).
      auto try_step = [&](Eigen::VectorXd d, int halvings) {
        Limited(&d);
        double alpha = 1.0;
        for (int k = 0; k <= halvings; ++k, alpha *= 0.5) {
          Eigen::VectorXd trial = *q + alpha * d;
          std::vector<CurvedWheelset> trial_ws;
          Eigen::VectorXd trial_r;
          if (!TrialResidual(&trial, &trial_ws, &trial_r)) continue;
          if (Merit(trial_r) < (1.0 - 1e-4 * alpha) * before) {
            BroydenUpdate(&J, trial - *q, trial_r - *r);
            *q = trial;
            *ws = std::move(trial_ws);
            *r = trial_r;
            return true;
          }
        }
        return false;
      };
      // Within the noise floor one halving: a shorter step only meets the noise sooner.
      bool accepted = try_step(step, Norm(*r) <= kNoiseFloor * o.tolerance ? 1 : 3);
      Note(accepted ? internal::NewtonEvent::kLineSearch
                    : internal::NewtonEvent::kLineSearchFailed);
      // Stiff two-point contact on worn rails: the flange's lateral force turns by 100 kN
      // within 0.15 mm of y and steps by 1-2 kN as cells enter its patch, so no step meets the
      // force tolerance while the position is settled. A fresh Jacobian's Newton correction
      // within the position tolerances (and a residual near the tolerance) is the equilibrium.
      if (!accepted && fresh && Norm(*r) <= kNearStall * o.tolerance && PositionNorm(step) <= 1.0) {
        *message = fmt::format(
            "converged in position: the Newton correction moves no wheelset more than {:.3f} mm "
            "and {:.3f} mrad; largest scaled residual {:.1e} (tolerance {:.1e}), the contact "
            "forces' grid noise in stiff flange contact",
            o.position_tolerance_m * 1e3, o.yaw_tolerance_rad * 1e3, Norm(*r), o.tolerance);
        return Ended(CurvingEnding::kPosition, it + 1);
      }
      // A step in the contact forces, crossed: where the worn gauge corner's contact switches
      // between one and two patches, a flanging wheelset's lateral force jumps by several kN
      // within a few microradians of yaw (measured at 8.5 MGT on the default curve with 20
      // spread nodes: 6.5 kN, 11 % of Q0, between 0 and -0.05 mrad), so every point of the
      // Newton direction past the jump, and every Levenberg-Marquardt trial, has a larger
      // residual although the equilibrium lies across it: the lateral force's stiffness there
      // (1.5e9 N/m) makes kilonewtons of residual a few micrometres of position. Above the
      // noise floor and within kNearStall x the tolerance, when the line search failed, the
      // natural-level test (Deuflhard, Newton Methods for Nonlinear Problems, 2004, sec. 3.3)
      // measures the distance in position instead: a trial is accepted when its
      // simplified Newton correction (the same Jacobian) is shorter than the step, scaled by the
      // position tolerances. Accepted steps do not update the Jacobian (a jump is no slope); the
      // next iteration evaluates it afresh. A correction within the position tolerances there
      // ends the solve, converged in position. It comes before the Levenberg-Marquardt trials:
      // at such a step they cross it too and are refused, or take a step too short to matter
      // (on step 105's rails the coach's stored start spent 64 of its 232 wheelset solves in two
      // rounds of them before this step crossed; 148 solves in all with this order, the main
      // job's solves and the shipped examples' curving unchanged: docs/curving.md).
      if (!accepted && fresh && Norm(*r) > kNoiseFloor * o.tolerance &&
          Norm(*r) <= kNearStall * o.tolerance) {
        double correction = 0.0;
        const bool natural = NaturalLevelStep(lu, step, q, ws, r, &correction);
        Note(natural ? internal::NewtonEvent::kNaturalLevel
                     : internal::NewtonEvent::kNaturalLevelFailed);
        if (natural) {
          if (correction <= 1.0 && Norm(*r) <= kNearStall * o.tolerance) {
            *message = fmt::format(
                "converged in position across a step in the contact forces: the Newton "
                "correction after the step moves no wheelset more than {:.0f} % of the position "
                "tolerances ({:.3f} mm, {:.3f} mrad); largest scaled residual {:.1e} (tolerance "
                "{:.1e})",
                100.0 * correction, o.position_tolerance_m * 1e3, o.yaw_tolerance_rad * 1e3,
                Norm(*r), o.tolerance);
            return Ended(CurvingEnding::kNaturalLevel, it + 1);
          }
          last_ratio = 1.0;
          fresh = false;
          continue;
        }
      }
      // A fresh Jacobian whose Newton step fails (the tread's creep forces saturating, the
      // contact angle jumping): Levenberg-Marquardt steps on the scaled system, from nearly
      // Newton's toward the scaled gradient's direction. Not within the grid's noise floor
      // (below): there no step can reliably reduce the residual, and each trial costs a solve
      // of every wheelset. Within the near-stall band after the natural-level step refused.
      if (!accepted && fresh && Norm(*r) > kNoiseFloor * o.tolerance) {
        const Eigen::MatrixXd Js = scale_.asDiagonal() * J;
        const Eigen::VectorXd rs = scale_.cwiseProduct(*r);
        const Eigen::MatrixXd JtJ = Js.transpose() * Js;
        const Eigen::VectorXd g = Js.transpose() * rs;
        for (double lambda : {1e-2, 1e-1, 1.0, 10.0}) {
          Eigen::MatrixXd A = JtJ;
          A.diagonal() += lambda * JtJ.diagonal();
          const Eigen::VectorXd d = A.ldlt().solve(-g);
          if (d.allFinite() && try_step(d, 1)) {
            accepted = true;
            break;
          }
        }
        Note(accepted ? internal::NewtonEvent::kLevenbergMarquardt
                      : internal::NewtonEvent::kLevenbergMarquardtFailed);
      }
      last_ratio = accepted ? Merit(*r) / before : 1.0;
      // Near the solution the forces' grid noise stops the line search: within kNoiseFloor x
      // tolerance that is the solution at this grid, and said so, whether the step came from a
      // fresh Jacobian or a chord (a fresh one would cost two solves per wheelset and find the
      // same noise: on the wear's worn rails a warm start often begins there).
      if (!accepted && Norm(*r) <= kNoiseFloor * o.tolerance) {
        *message = fmt::format(
            "stopped at the contact grid's noise: largest scaled residual {:.1e} (tolerance "
            "{:.1e})",
            Norm(*r), o.tolerance);
        return Ended(CurvingEnding::kGridNoise, it + 1);
      }
      // A step in the contact forces: where the patch wraps the worn gauge corner, a wheelset's
      // forces can jump as the contact switches between one and two patches (measured at 5.2 MGT
      // on the main job's curve: the Y25 wagon's yaw moment from -1.3 to +2.0 kN m within 4 um
      // and 11 urad). No position meets the force tolerance there, and the Newton correction,
      // from differences 0.2 mm wide, does not see the jump. When a fresh Jacobian's step fails
      // or barely helps, one probe a position tolerance along the Newton direction: if every
      // residual above the tolerance changes sign there, the equilibrium (the jump through zero)
      // lies within the position tolerances of this state.
      if (fresh && (!accepted || last_ratio > 0.9) && Norm(*r) <= kNearStall * o.tolerance) {
        const int result = ProbeForceStep(J, q, ws, r, message);
        if (result > 0) return Ended(CurvingEnding::kForceStepProbe, it + 1);
        Note(result == 0 ? internal::NewtonEvent::kProbeMoved
                         : internal::NewtonEvent::kProbeFailed);
        if (result == 0) {  // the probe reduced the residual: go on from it
          last_ratio = 1.0;
          continue;
        }
      }
      if (!accepted && !fresh) continue;  // an old Jacobian: evaluate it again and retry
      fresh = false;
      if (!accepted) {
        if (AtBound(*q, step)) {
          *no_equilibrium = true;
          return Fail(fmt::format("a wheelset would pass the lateral limit of {:.1f} mm: it "
                                  "climbs the flange, no steady state",
                                  o.max_lateral_m * 1e3),
                      message);
        }
        // The finite differences may have met the grid's force noise (on worn rails the patch
        // wraps round the gauge corner and the forces step as cells enter it): once, a
        // Jacobian over kCoarseStepFactor times the steps, whose differences rise above it.
        if (step_factor == 1.0) {
          step_factor = kCoarseStepFactor;
          J.resize(0, 0);
          continue;
        }
        return Fail(
            fmt::format("no step reduced the residual (largest scaled residual {:.1e}){}", Norm(*r),
                        climb_refused_ ? "; trial steps would have had a wheel climb its flange "
                                         "beyond its steepest flank"
                                       : ""),
            message);
      }
    }
    if (Norm(*r) <= o.tolerance) return Ended(CurvingEnding::kTolerance, o.max_iterations);
    return Fail(fmt::format("{} iterations, largest scaled residual {:.2e} (tolerance {:.1e})",
                            o.max_iterations, Norm(*r), o.tolerance),
                message);
  }

  // Pseudo-transient continuation from q (Kelley and Keyes, SIAM J. Numer. Anal. 35, 1998):
  // steps of (sigma D - J) dq = r, D a stiffness of Q0 per millimetre (Q0 l0 per milliradian)
  // on the wheelsets' rows. A large sigma moves every wheelset along its residual force, as an
  // overdamped vehicle would roll toward its steady state; sigma falls with the residual
  // (switched evolution relaxation: sigma times the ratio of the residuals), so the steps turn
  // into Newton's near the equilibrium. It makes the centred start's way to the flange robust
  // where the tread's Jacobian points away from it (a worn tread's lateral stiffness against
  // y can change sign). The first sigma moves the wheelset with the largest residual by the
  // step limit; a step that doubles the merit, or leaves the lateral limit, is retried with
  // sigma four times larger and a fresh Jacobian. Ends (true) when the residual is within
  // kNearStall x the tolerance or sigma has fallen below kNewtonSigma, for Solve to finish;
  // false when a contact failed, the solve was cancelled or it ran out of iterations.
  bool Relax(Eigen::VectorXd* q, std::vector<CurvedWheelset>* ws, Eigen::VectorXd* r) {
    const CurvingOptions& o = p_.options;
    Project(q);
    if (!Residual(*q, ws, r)) return false;
    const int nw = 2 * l_.wheelsets;
    Eigen::VectorXd D = Eigen::VectorXd::Zero(q->size());
    double sigma = 0.0;
    for (int k = 0; k < nw; ++k) {
      D[k] = k % 2 == 0 ? q0_ / 1e-3 : q0_ * kHalfBase_m / 1e-3;
      const double limit = k % 2 == 0 ? kMaxStepY_m : kMaxStepYaw_rad;
      sigma = std::max(sigma, std::abs((*r)[k]) / (D[k] * limit));
    }
    Eigen::MatrixXd& J = jacobian_;
    J = Jacobian(*q, *ws, 1.0);
    for (int it = 0; it < o.max_iterations; ++it) {
      if (Cancelled()) return false;
      if (Norm(*r) <= kNearStall * o.tolerance || sigma < kNewtonSigma) return true;
      Eigen::MatrixXd A = J;
      A.diagonal() -= sigma * D;
      Eigen::VectorXd d = A.fullPivLu().solve(-*r);
      if (!d.allFinite()) return false;
      Limited(&d);
      Eigen::VectorXd trial = *q + d;
      std::vector<CurvedWheelset> trial_ws;
      Eigen::VectorXd trial_r;
      if (!TrialResidual(&trial, &trial_ws, &trial_r) || Merit(trial_r) > 2.0 * Merit(*r)) {
        if (Cancelled()) return false;
        sigma *= 4.0;
        J = Jacobian(*q, *ws, 1.0);
        continue;
      }
      BroydenUpdate(&J, trial - *q, trial_r - *r);
      sigma *= Norm(trial_r) / Norm(*r);
      *q = trial;
      *ws = std::move(trial_ws);
      *r = trial_r;
    }
    return false;
  }

  // Scales d down so that no wheelset moves by more than the step limits.
  void Limited(Eigen::VectorXd* d) const {
    double shrink = 1.0;
    for (int k = 0; k < 2 * l_.wheelsets; ++k) {
      const double limit = k % 2 == 0 ? kMaxStepY_m : kMaxStepYaw_rad;
      if (std::abs((*d)[k]) > limit) shrink = std::min(shrink, limit / std::abs((*d)[k]));
    }
    *d *= shrink;
  }

  // The largest wheelset move in d, in units of the position tolerances (1: at a tolerance).
  double PositionNorm(const Eigen::VectorXd& d) const {
    double n = 0.0;
    for (int i = 0; i < l_.wheelsets; ++i) {
      n = std::max({n, std::abs(d[2 * i]) / p_.options.position_tolerance_m,
                    std::abs(d[2 * i + 1]) / p_.options.yaw_tolerance_rad});
    }
    return n;
  }

  // The natural-level step of Solve (see there) along the Newton step `step` of the Jacobian
  // factorised in lu: the full step, then halved twice. True when a trial passed: q, ws, r are
  // its state and *correction its simplified Newton correction in position tolerances (1: at a
  // tolerance); false: nothing changed.
  bool NaturalLevelStep(const Eigen::FullPivLU<Eigen::MatrixXd>& lu, Eigen::VectorXd step,
                        Eigen::VectorXd* q, std::vector<CurvedWheelset>* ws, Eigen::VectorXd* r,
                        double* correction) {
    Limited(&step);
    const double full = PositionNorm(step);
    if (!(full > 0.0)) return false;
    for (double alpha : {1.0, 0.5, 0.25}) {
      Eigen::VectorXd trial = *q + alpha * step;
      std::vector<CurvedWheelset> trial_ws;
      Eigen::VectorXd trial_r;
      if (!TrialResidual(&trial, &trial_ws, &trial_r)) continue;
      const Eigen::VectorXd c = lu.solve(-trial_r);
      if (!c.allFinite()) return false;
      // Deuflhard's restricted monotonicity test.
      if (PositionNorm(c) <= (1.0 - 0.25 * alpha) * full) {
        *q = trial;
        *ws = std::move(trial_ws);
        *r = trial_r;
        *correction = PositionNorm(c);
        return true;
      }
    }
    return false;
  }

  // The sign-change probe of Solve at q (residual r, wheelsets ws) along J's Newton direction,
  // scaled so that no wheelset moves by more than the position tolerances. Returns 1 when every
  // residual component above the tolerance changes sign there (q, ws and r become the better of
  // the two states; message says so): converged in position at a step in the contact forces.
  // Returns 0 when the probe did not bracket but reduced the merit (q, ws, r are the probe's),
  // -1 otherwise (nothing changed).
  int ProbeForceStep(const Eigen::MatrixXd& J, Eigen::VectorXd* q, std::vector<CurvedWheelset>* ws,
                     Eigen::VectorXd* r, std::string* message) {
    const CurvingOptions& o = p_.options;
    const Eigen::VectorXd d = J.fullPivLu().solve(-*r);
    if (!d.allFinite()) return -1;
    double alpha = 1.0;
    for (int i = 0; i < l_.wheelsets; ++i) {
      if (std::abs(d[2 * i]) > o.position_tolerance_m) {
        alpha = std::min(alpha, o.position_tolerance_m / std::abs(d[2 * i]));
      }
      if (std::abs(d[2 * i + 1]) > o.yaw_tolerance_rad) {
        alpha = std::min(alpha, o.yaw_tolerance_rad / std::abs(d[2 * i + 1]));
      }
    }
    Eigen::VectorXd trial = *q + alpha * d;
    std::vector<CurvedWheelset> trial_ws;
    Eigen::VectorXd trial_r;
    if (!TrialResidual(&trial, &trial_ws, &trial_r)) return -1;
    // The components above the tolerance, and whether each one changes sign.
    std::string changed;
    bool bracketed = true;
    for (int k = 0; k < r->size(); ++k) {
      if (std::abs((*r)[k] * scale_[k]) <= o.tolerance) continue;
      if (!((*r)[k] * trial_r[k] < 0.0)) {
        bracketed = false;
        break;
      }
      const bool body = k >= 2 * l_.wheelsets;
      changed += fmt::format("{}{} {}'s {} from {:.1e} to {:.1e}", changed.empty() ? "" : ", ",
                             body ? "frame or body" : "wheelset", body ? k : k / 2,
                             k % 2 == 0 ? "lateral force" : "yaw moment", (*r)[k] * scale_[k],
                             trial_r[k] * scale_[k]);
    }
    const bool better = Merit(trial_r) < Merit(*r);
    if (bracketed && !changed.empty()) {
      const Eigen::VectorXd moved = alpha * d;
      double dy = 0.0, dpsi = 0.0;
      for (int i = 0; i < l_.wheelsets; ++i) {
        dy = std::max(dy, std::abs(moved[2 * i]));
        dpsi = std::max(dpsi, std::abs(moved[2 * i + 1]));
      }
      if (better) {
        *q = trial;
        *ws = std::move(trial_ws);
        *r = trial_r;
      }
      *message = fmt::format(
          "converged in position at a step in the contact forces: within {:.3f} mm and {:.3f} "
          "mrad the scaled residuals change sign ({}); largest scaled residual {:.1e} "
          "(tolerance {:.1e})",
          dy * 1e3, dpsi * 1e3, changed, Norm(*r), o.tolerance);
      return 1;
    }
    if (!better) return -1;
    *q = trial;
    *ws = std::move(trial_ws);
    *r = trial_r;
    return 0;
  }

  // The Jacobian at q: the suspension's exact part plus each wheelset's contact block by forward
  // differences (a wheelset's contact forces depend on its own (y, psi) only).
  Eigen::MatrixXd Jacobian(const Eigen::VectorXd& q, const std::vector<CurvedWheelset>& ws,
                           double step_factor) {
    const double step_y = step_factor * kStepY_m, step_yaw = step_factor * kStepYaw_rad;
    Eigen::MatrixXd J = suspension_;
    // Per wheelset a step in y (task 2i) and in psi (task 2i + 1).
    std::vector<CurvedWheelset> stepped(2 * l_.wheelsets);
    ParallelFor(2 * l_.wheelsets, p_.options.threads, [&](int t) {
      const int i = t / 2;
      ContactStream* stream = &streams_[3 * i + 1 + t % 2];
      stepped[t] = t % 2 == 0
                       ? EvaluateWheelset(ctx_[i], q[2 * i] + step_y, q[2 * i + 1], stream)
                       : EvaluateWheelset(ctx_[i], q[2 * i], q[2 * i + 1] + step_yaw, stream);
    });
    Count(2 * l_.wheelsets);
    for (int i = 0; i < l_.wheelsets; ++i) {
      const CurvedWheelset& dy = stepped[2 * i];
      const CurvedWheelset& dpsi = stepped[2 * i + 1];
      const CurvedWheelset& w = ws[i];
      J(2 * i, 2 * i) += (dy.force_N.y() - w.force_N.y()) / step_y;
      J(2 * i + 1, 2 * i) += (dy.yaw_moment_Nm - w.yaw_moment_Nm) / step_y;
      J(2 * i, 2 * i + 1) += (dpsi.force_N.y() - w.force_N.y()) / step_yaw;
      J(2 * i + 1, 2 * i + 1) += (dpsi.yaw_moment_Nm - w.yaw_moment_Nm) / step_yaw;
    }
    return J;
  }

  // The secant (Broyden) update of each wheelset's contact block from an accepted step dq and
  // its residual change dr: the suspension's part of J is exact, and a wheelset's contact forces
  // depend on its own (y, psi) only, so each 2 x 2 block is corrected on its own rows. In flange
  // contact the lateral force turns from the tread's to the flange's stiffness within about
  // 0.1 mm, less than a finite-difference step above the grids' noise: the steps' secants give
  // the local slope there.
  void BroydenUpdate(Eigen::MatrixXd* J, const Eigen::VectorXd& dq, const Eigen::VectorXd& dr) {
    for (int i = 0; i < l_.wheelsets; ++i) {
      // y [m] and psi [rad] have the same scale here (mm and mrad).
      const Eigen::Vector2d d = dq.segment<2>(2 * i);
      const double dd = d.squaredNorm();
      if (dd < 1e-18) continue;  // below 1 nm: the change is the grids' noise
      const Eigen::Vector2d miss = dr.segment<2>(2 * i) - J->middleRows<2>(2 * i) * dq;
      J->block<2, 2>(2 * i, 2 * i) += miss * d.transpose() / dd;
    }
  }

  int solves() const { return solves_; }
  int table_evaluations() const { return table_evaluations_; }
  // The largest scaled residual at the start of the last Solve.
  double first_norm() const { return first_norm_; }
  // CurvingOptions::cancel returned true (once it has, it is not asked again).
  bool Cancelled() {
    cancelled_ = cancelled_ || (p_.options.cancel && p_.options.cancel());
    return cancelled_;
  }
  bool cancelled() const { return cancelled_; }
  const Eigen::MatrixXd& jacobian() const { return jacobian_; }
  void set_contexts(std::vector<WheelsetContext> ctx) {
    ctx_ = std::move(ctx);
    ClearWarmStarts();
  }
  // A new start: the contexts of the first phase and the chord to begin with (empty, or of
  // another size: none, the first iteration evaluates it).
  void Restart(std::vector<WheelsetContext> ctx, const Eigen::MatrixXd& jacobian) {
    ctx_ = std::move(ctx);
    ClearWarmStarts();
    const Eigen::Index n = l_.size();
    if (jacobian.rows() == n && jacobian.cols() == n && jacobian.allFinite()) {
      jacobian_ = jacobian;
    } else {
      jacobian_.resize(0, 0);
    }
  }

  // The rule that ended the last Solve (kNone: it failed).
  CurvingEnding ending() const { return ending_; }
  // Records what the iteration did (internal::SolveCurvingWith's `events`, null: nothing).
  void set_events(std::vector<internal::NewtonEvent>* events) { events_ = events; }

 private:
  bool WithinBounds(const Eigen::VectorXd& q) const {
    for (int i = 0; i < l_.wheelsets; ++i) {
      if (std::abs(q[2 * i]) > p_.options.max_lateral_m) return false;
    }
    return true;
  }
  // A wheelset within one step limit of max_lateral_m that the Newton step pushes outward.
  bool AtBound(const Eigen::VectorXd& q, const Eigen::VectorXd& step) const {
    for (int i = 0; i < l_.wheelsets; ++i) {
      const double y = q[2 * i];
      if (std::abs(y) + kMaxStepY_m > p_.options.max_lateral_m && y * step[2 * i] > 0.0) {
        return true;
      }
    }
    return false;
  }
  // A new contact model (or a new start): every stream's next solve is cold. The placements are
  // kept (a pure function of the profiles and the pose).
  void ClearWarmStarts() {
    for (ContactStream& s : streams_) {
      s.right.Clear();
      s.left.Clear();
    }
  }
  // Counts n wheelset evaluations: contact solves, or the table's.
  void Count(int n) { (ctx_.empty() || !ctx_[0].table ? solves_ : table_evaluations_) += n; }
  int Ended(CurvingEnding rule, int iterations) {
    ending_ = rule;
    Note(internal::NewtonEvent::kEnded);
    return iterations;
  }
  void Note(internal::NewtonEvent e) {
    if (events_) events_->push_back(e);
  }
  static int Fail(std::string text, std::string* message) {
    *message = std::move(text);
    return -1;
  }

  const CurvingProblem& p_;
  const Layout& l_;
  std::vector<WheelsetContext> ctx_;
  // Per wheelset: the iterates' stream, then the y and the yaw differences' (ContactStream).
  std::vector<ContactStream> streams_;
  double unbalanced_N_ = 0.0, q0_ = 1.0;
  Eigen::MatrixXd suspension_, jacobian_;
  Eigen::FullPivLU<Eigen::MatrixXd> frames_;  // the frames' and body's block of the suspension
  Eigen::VectorXd frame_constant_;
  Eigen::VectorXd suspension_offset_, scale_;
  int solves_ = 0, table_evaluations_ = 0;
  double first_norm_ = 0.0;
  bool climb_refused_ = false;  // a trial of this solve was refused as climbing (TrialResidual)
  bool cancelled_ = false;
  CurvingEnding ending_ = CurvingEnding::kNone;
  std::vector<internal::NewtonEvent>* events_ = nullptr;
};

void Validate(const CurvingProblem& p) {
  ValidateCurve(p.curve);
  ValidateVehicle(p.vehicle, fmt::format("vehicle \"{}\"", p.vehicle.name));
  if (!(p.speed_m_s > 0.0) || !std::isfinite(p.speed_m_s)) {
    throw InputError(fmt::format("curving: speed_m_s = {}: expected a speed > 0", p.speed_m_s));
  }
  if (!(p.friction > 0.0) || !std::isfinite(p.friction)) {
    throw InputError(fmt::format("curving: friction = {}: expected mu > 0", p.friction));
  }
  if (!p.wheels.empty() && static_cast<int>(p.wheels.size()) != p.vehicle.wheelsets()) {
    throw InputError(fmt::format("curving: {} wheelset wheel pairs: expected none or one per "
                                 "wheelset of vehicle \"{}\" ({})",
                                 p.wheels.size(), p.vehicle.name, p.vehicle.wheelsets()));
  }
  for (const WheelsetWheels& w : p.wheels) {
    if (w.high.size() < 2 || w.low.size() < 2) {
      throw InputError(fmt::format("curving: vehicle \"{}\": a wheelset's wheel profile is "
                                   "empty: expected a wheel profile on each wheel",
                                   p.vehicle.name));
    }
  }
}

}  // namespace

CurvingPredictor CurvingOptions::ColdPredictorFor(const ModelOptions& full) const {
  if (cold_predictor) return *cold_predictor;
  return full.accuracy == AccuracyPreset::kDraft || predictor ? CurvingPredictor::kModel
                                                              : CurvingPredictor::kTable;
}

bool CurvingOptions::WarmContactFor(const ModelOptions& full) const {
  return warm_contact.value_or(full.accuracy != AccuracyPreset::kDraft);
}

ModelOptions CurvingOptions::PredictorModel() {
  ModelOptions m = MakeModelOptions(ModelKind::kAuto);
  m.accuracy = AccuracyPreset::kDraft;
  return m;
}

ModelOptions CurvingOptions::PredictorFor(const ModelOptions& full) {
  ModelOptions m = full;
  if (m.kind == ModelKind::kConformal) m.kind = ModelKind::kAuto;
  m.accuracy = AccuracyPreset::kDraft;
  m.cell_dx_m.reset();
  m.cell_ds_m.reset();
  return m;
}

CurvingResult SolveCurving(const CurvingProblem& problem) {
  return internal::SolveCurvingWith(problem, {});
}

CurvingResult internal::SolveCurvingWith(const CurvingProblem& problem_in,
                                         const WheelsetForceModel& forces,
                                         std::vector<NewtonEvent>* events) {
  Validate(problem_in);
  const WheelsetForceModel* force_model = forces ? &forces : nullptr;
  const auto start = std::chrono::steady_clock::now();
  CurvingProblem p = problem_in;
  if (!p.gauge_points) {
    const double h = p.track.gauge_height_m;
    p.gauge_points =
        RailGaugePoints{RailGaugePoint(p.high_rail, h).x(), RailGaugePoint(p.low_rail, h).x()};
  }
  const VehicleSpec& v = p.vehicle;
  const Layout layout = MakeLayout(v);
  CurvingResult out;
  out.unbalanced_acceleration_m_s2 = UnbalancedLateralAcceleration(p.curve, p.speed_m_s);
  out.cant_deficiency_m = CantDeficiency(p.curve, p.speed_m_s);
  // Quasi-static loads: the axle load normal to the track plane, and the load transfer.
  const double g_ratio = TrackNormalAcceleration(p.curve, p.speed_m_s) / kGravity_m_s2;
  const double axle_mass_kg = v.axle_load_N / kGravity_m_s2;
  const double q0 = 0.5 * v.axle_load_N * g_ratio;
  const double transfer =
      axle_mass_kg * out.unbalanced_acceleration_m_s2 * v.cg_height_m / (2.0 * kHalfBase_m);
  if (q0 - std::abs(transfer) <= 0.0) {
    out.status = CurvingStatus::kNoEquilibrium;
    out.message =
        fmt::format("the load transfer {:.0f} N unloads a wheel of {:.0f} N: the vehicle overturns",
                    transfer, q0);
    return out;
  }
  // The predictor's phase, then the full model's; one phase when they are the same model.
  const ModelOptions predictor =
      p.options.predictor ? *p.options.predictor : CurvingOptions::PredictorFor(p.contact.model);
  const bool has_predictor = !(predictor == p.contact.model);
  const bool warm_contact = p.options.WarmContactFor(p.contact.model);
  // Each wheel's flank end, once for the solve's phases (they share the wheels).
  std::vector<std::pair<double, double>> flank_y_m(layout.wheelsets);
  for (int i = 0; i < layout.wheelsets; ++i) {
    const Profile& high = p.wheels.empty() ? p.vehicle.wheel_profile : p.wheels[i].high;
    const Profile& low = p.wheels.empty() ? p.vehicle.wheel_profile : p.wheels[i].low;
    flank_y_m[i] = {internal::SteepestFlankTipSideY(high), internal::SteepestFlankTipSideY(low)};
  }
  auto contexts = [&](const ModelOptions& model) {
    std::vector<WheelsetContext> ctx(layout.wheelsets);
    for (int i = 0; i < layout.wheelsets; ++i) {
      ctx[i] = {&p,
                model,
                q0 + transfer,
                q0 - transfer,
                q0,
                p.wheels.empty() ? nullptr : &p.wheels[i],
                nullptr,
                force_model,
                i,
                warm_contact && !(has_predictor && model == predictor)};
      std::tie(ctx[i].high_flank_y_m, ctx[i].low_flank_y_m) = flank_y_m[i];
    }
    return ctx;
  };
  const double unbalanced_N = axle_mass_kg * layout.wheelsets * out.unbalanced_acceleration_m_s2;

  // Start: centred, every wheelset and bogie along its local tangent (the frames and the body
  // then follow the wheelsets, Equilibrium::Project).
  Eigen::VectorXd centred = Eigen::VectorXd::Zero(layout.size());
  const double kappa = p.curve.curvature_per_m();
  for (int i = 0; i < layout.wheelsets && layout.bogies > 0; ++i) {
    const double X = layout.wheelset_x[i], Xb = layout.bogie_x[layout.bogie_of[i]];
    centred[2 * i + 1] = kappa * (X - Xb);  // rigid with a frame on its tangent
  }
  // Each start, and whether it goes to the full model directly (a start with its Jacobian is a
  // solution of the full model nearby: continuation); when that fails, the same start goes
  // through the predictor's phase before the next start is tried.
  struct Attempted {
    CurvingStart start;
    bool full_directly = false;
    bool relaxed = false;  // pseudo-transient continuation first (Equilibrium::Relax)
    bool table = false;    // the contact table's phase first (CurvingPredictor::kTable)
    std::string name;      // CurvingAttempt::start
    int start_index = 0;   // which start (a start's two tries share it)
    std::string label;     // the start's, for the message
    bool lazy = false;     // CurvingStart::lazy, not yet called: replaced by its tries when reached
  };
  std::vector<Attempted> starts;
  int start_count = 0;
  // The tries of start `s` (number `index`) at `at` in `starts`: none when it is not of the
  // layout's size or is a start before `at`; two for a start with its Jacobian.
  auto insert_start = [&](size_t at, const CurvingStart& s, const std::string& label, int index) {
    if (s.state.size() != layout.size()) return;
    for (size_t k = 0; k < at; ++k) {
      if (!starts[k].lazy && starts[k].start.state == s.state) return;
    }
    const bool has_jacobian =
        s.jacobian.rows() == layout.size() && s.jacobian.cols() == layout.size();
    // (Without a predictor both attempts would be the same solve.)
    const bool both = has_jacobian && has_predictor;
    std::vector<Attempted> tries;
    if (both) {
      tries.push_back(
          {s, true, false, false, label + ", continued on the full model", index, label, false});
    }
    tries.push_back({s, false, false, false, both ? label + ", through the predictor" : label,
                     index, label, false});
    starts.insert(starts.begin() + static_cast<std::ptrdiff_t>(at), tries.begin(), tries.end());
  };
  // The given start, then the fallbacks: each of the layout's size and not an earlier one; a
  // lazy one kept as it is until the loop reaches it.
  auto add_start = [&](const CurvingStart& s, const std::string& label) {
    if (s.state.size() == 0 && s.lazy) {
      starts.push_back({s, false, false, false, label, start_count, label, true});
    } else {
      insert_start(starts.size(), s, label, start_count);
    }
    ++start_count;
  };
  if (p.options.start) {
    add_start(*p.options.start,
              p.options.start->label.empty() ? "the given start" : p.options.start->label);
  }
  for (size_t i = 0; i < p.options.fallback_starts.size(); ++i) {
    const CurvingStart& s = p.options.fallback_starts[i];
    add_start(s, s.label.empty() ? fmt::format("fallback start {}", i + 1) : s.label);
  }
  // The centred starts follow (`starts` from here on).
  const int centred_from = start_count;
  // A centred start (each its own start): named `name`, `label` in the message.
  auto add_centred = [&](bool relaxed, bool table, const std::string& name,
                         const std::string& label) {
    starts.push_back(
        {{centred, {}, {}, {}}, false, relaxed, table, name, start_count++, label, false});
  };
  // The table predictor: from the centred start through the contact table's equilibrium; when
  // that fails, the model predictor's centred start below is the fallback.
  if (p.options.ColdPredictorFor(p.contact.model) == CurvingPredictor::kTable) {
    const std::string label = "the centred start through the contact table";
    add_centred(false, true, label, label);
  }
  add_centred(false, false, "the centred start", "the centred start");
  // Last, when no start has converged nor stopped within the usable residual: the centred start
  // again, relaxed toward the equilibrium before Newton (on the worn rails of the default curve
  // with 20 spread nodes at 8.5 MGT the coach's Newton steps from the centred start went 2 mm
  // per iteration away from the flange and stopped at 5.2e-1 Q0).
  add_centred(true, false, "the centred start relaxed",
              "the centred start relaxed toward the equilibrium first by pseudo-transient "
              "continuation");
  Eigen::VectorXd q;
  std::vector<CurvedWheelset> ws;
  Eigen::VectorXd r;
  bool no_equilibrium = false;
  Equilibrium eq(p, layout, contexts(predictor), unbalanced_N, q0);
  eq.set_events(events);
  int iterations = 0;
  // The best stopped attempt (smallest largest scaled residual) when no start converges: a later
  // start that goes astray does not replace a nearer one.
  struct Attempt {
    Eigen::VectorXd q, r;
    std::vector<CurvedWheelset> ws;
    Eigen::MatrixXd jacobian;
    std::string message;
    size_t k = 0;  // in `starts`
  };
  // The attempt (in `starts`) whose state is returned.
  std::optional<size_t> returned;
  std::optional<Attempt> best;
  // The contact tables, one per distinct wheel pair (one for all wheelsets without
  // CurvingProblem::wheels), built when a table start is reached.
  std::vector<std::unique_ptr<ContactTable>> tables;
  auto table_contexts = [&]() {
    const auto t0 = std::chrono::steady_clock::now();
    const int n = p.wheels.empty() ? 1 : layout.wheelsets;
    ContactTableOptions topt = p.options.table;
    topt.threads = p.options.threads;
    for (int i = static_cast<int>(tables.size()); i < n; ++i) {
      ContactTableGeometry g;
      g.high_wheel = p.wheels.empty() ? v.wheel_profile : p.wheels[i].high;
      g.low_wheel = p.wheels.empty() ? v.wheel_profile : p.wheels[i].low;
      g.high_rail = p.high_rail;
      g.low_rail = p.low_rail;
      g.gauge_points = *p.gauge_points;
      g.track = p.track;
      g.wheelset = v.WheelsetAt(0.0, 0.0, 0.0);
      tables.push_back(std::make_unique<ContactTable>(g, topt));
    }
    out.table_build_s +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<WheelsetContext> ctx = contexts(p.contact.model);
    for (int i = 0; i < layout.wheelsets; ++i)
      ctx[i].table = tables[p.wheels.empty() ? 0 : i].get();
    return ctx;
  };
  std::string table_note;  // why the table's start failed
  for (size_t k = 0; k < starts.size(); ++k) {
    // A lazy start is found now and replaced by its tries, as if it had been given (none when
    // it finds nothing new: then the next start is at k, itself perhaps lazy).
    while (k < starts.size() && starts[k].lazy) {
      const Attempted pending = starts[k];
      starts.erase(starts.begin() + static_cast<std::ptrdiff_t>(k));
      const CurvingStart found = pending.start.lazy();
      const bool named = found.label.empty() || !pending.start.label.empty();
      insert_start(k, found, named ? pending.label : found.label, pending.start_index);
    }
    if (k == starts.size()) break;
    const auto& [start, full_directly, relaxed, table, name, start_index, label, lazy] = starts[k];
    const bool another_follows = k + 1 < starts.size();
    const int solves_before = eq.solves();
    q = start.state;
    no_equilibrium = false;
    const bool two_phases = (has_predictor || table) && !full_directly;
    eq.Restart(table ? table_contexts() : contexts(two_phases ? predictor : p.contact.model),
               start.jacobian);
    if (relaxed && !eq.Relax(&q, &ws, &r) && eq.cancelled()) break;
    iterations = eq.Solve(&q, &ws, &r, &out.message, &no_equilibrium, another_follows);
    bool table_phase_failed = false;
    if (two_phases) {
      out.predictor_iterations += std::max(iterations, 0);
      table_phase_failed = table && iterations < 0;
      if (iterations >= 0) {
        out.predictor_state = q;
        eq.set_contexts(contexts(p.contact.model));
        iterations = eq.Solve(&q, &ws, &r, &out.message, &no_equilibrium);
        out.full_iterations += std::max(iterations, 0);
        out.finish_start_residual = eq.first_norm();
      }
    } else {
      out.full_iterations += std::max(iterations, 0);
    }
    const bool converged = iterations >= 0 && !eq.cancelled();
    out.attempts.push_back({name, eq.solves() - solves_before, converged,
                            r.size() == q.size() ? eq.Norm(r) : 0.0,
                            converged ? std::string() : out.message});
    if (converged) returned = k;
    if (table) {
      if (converged) {
        out.table_predictor = TablePredictorOutcome::kUsed;
        break;
      }
      if (eq.cancelled()) break;
      // Fall back to the model predictor's starts; a limit or a failure found on the table is
      // the table's, not the vehicle's.
      out.table_predictor = TablePredictorOutcome::kFellBack;
      table_note = fmt::format(
          "the table predictor's start failed ({}: {}); solved with the "
          "model predictor",
          table_phase_failed ? "on the table" : "in the full model's finish", out.message);
      no_equilibrium = false;
      if (table_phase_failed) continue;  // the states are the table's: no candidate for `best`
    }
    // A given or fallback start that walked past the lateral limit says nothing of the vehicle:
    // the next start is tried (on the worn rails of step 105 a start at the track centre with
    // unyawed wheelsets went past 20 mm in 244 wheelset solves; from the unworn rails'
    // equilibrium the coach converged in 148). From a centred start it ends the solve.
    if (no_equilibrium && !eq.cancelled() && start_index < centred_from) continue;
    if (!table && (iterations >= 0 || no_equilibrium || eq.cancelled())) break;
    if (AllConverged(ws, layout.wheelsets) && r.size() == q.size() &&
        (!best || eq.Norm(r) < eq.Norm(best->r))) {
      best = Attempt{q, r, ws, eq.jacobian(), out.message, k};
    }
    if (best && eq.Norm(best->r) <= p.options.usable_multiple * p.options.tolerance) break;
  }
  if (!returned && best) returned = best->k;
  out.jacobian = eq.jacobian();
  // Returns attempt `a` as the result's state.
  auto take = [&](const Attempt& a) {
    q = a.q;
    r = a.r;
    ws = a.ws;
    out.jacobian = a.jacobian;
    out.message = a.message;
  };
  // A solve that stalled on a draft grid above the usable residual but near an equilibrium
  // (within kNearStall x the tolerance: the draft grid's force noise grows where a worn gauge
  // corner wraps the patch): once more from the best state on the standard grid, whose forces
  // are smoother, said in the message. Kept when it ends nearer the equilibrium. Farther stalls
  // (no steady state, as on R 150 m at 1.2 m/s^2) are not retried: the finer grid costs 2-3x.
  const ModelOptions& model = p.contact.model;
  if (iterations < 0 && !no_equilibrium && best && !eq.cancelled() &&
      eq.Norm(best->r) > p.options.usable_multiple * p.options.tolerance &&
      eq.Norm(best->r) <= kNearStall * p.options.tolerance &&
      model.accuracy == AccuracyPreset::kDraft && !model.cell_dx_m && !model.cell_ds_m) {
    ModelOptions finer = model;
    finer.accuracy = AccuracyPreset::kStandard;
    Eigen::VectorXd fq = best->q;
    std::vector<CurvedWheelset> fws;
    Eigen::VectorXd fr;
    std::string fmessage;
    bool fno = false;
    const int solves_before = eq.solves();
    eq.Restart(contexts(finer), best->jacobian);
    const int fit = eq.Solve(&fq, &fws, &fr, &fmessage, &fno);
    out.attempts.push_back({"the best stopped attempt on the standard grid",
                            eq.solves() - solves_before, fit >= 0 && !eq.cancelled(),
                            fr.size() == fq.size() ? eq.Norm(fr) : 0.0,
                            fit >= 0 ? std::string() : fmessage});
    if (AllConverged(fws, layout.wheelsets) && fr.size() == fq.size() &&
        eq.Norm(fr) < eq.Norm(best->r)) {
      const std::string draft = fmt::format("the draft grid stalled at {:.1e}", eq.Norm(best->r));
      out.full_iterations += std::max(fit, 0);
      iterations = fit;
      no_equilibrium = fno;
      best = Attempt{fq,
                     fr,
                     fws,
                     eq.jacobian(),
                     fit >= 0 ? fmt::format("{}; finished on the standard grid{}", draft,
                                            fmessage.empty() ? "" : ": " + fmessage)
                              : fmt::format("{}; on the standard grid: {}", draft, fmessage),
                     best->k};
      take(*best);
    }
  }
  if (eq.cancelled()) {  // a state of an unfinished iteration: no solution to report
    out.status = CurvingStatus::kCancelled;
    out.message = "cancelled";
    out.contact_solves = eq.solves();
    out.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
  if (iterations < 0 && !no_equilibrium && best) take(*best);
  // A state from a start after the first says so, and why the starts before it failed.
  if (returned && !no_equilibrium && starts[*returned].start_index != starts[0].start_index) {
    std::string before;
    for (size_t k = 0; k < *returned && k < out.attempts.size(); ++k) {
      const CurvingAttempt& a = out.attempts[k];
      before += fmt::format("{}{}: {} solves{}", before.empty() ? "" : "; ", a.start,
                            a.contact_solves, a.message.empty() ? "" : ", " + a.message);
    }
    out.message = fmt::format("from {} (before it: {})", starts[*returned].label, before) +
                  (out.message.empty() ? "" : "; " + out.message);
  }
  if (!table_note.empty())
    out.message = table_note + (out.message.empty() ? "" : "; " + out.message);
  out.table_evaluations = eq.table_evaluations();
  if (r.size() == q.size()) out.largest_scaled_residual = eq.Norm(r);
  out.contact_solves = eq.solves();
  out.wheelsets = ws;
  out.state = q;
  for (int j = 0; j < layout.bogies; ++j) {
    out.bogies.emplace_back(q[layout.BogieIndex(j)], q[layout.BogieIndex(j) + 1]);
  }
  if (layout.bogies > 0) out.body = q.segment<2>(layout.BodyIndex());
  for (int k = 0; k < r.size(); ++k) {
    double& largest = k % 2 == 0 ? out.lateral_residual_N : out.yaw_residual_Nm;
    largest = std::max(largest, std::abs(r[k]));
  }
  for (const CurvedWheelset& w : ws) {
    out.longitudinal_residual_N =
        std::max(out.longitudinal_residual_N, std::abs(w.force_N.x() - v.traction_N_per_axle));
  }
  if (iterations < 0) {
    out.status = no_equilibrium ? CurvingStatus::kNoEquilibrium : CurvingStatus::kNotConverged;
  } else {
    out.status = CurvingStatus::kConverged;
    out.ending = eq.ending();  // the last Solve's: the one whose state is returned
    for (const CurvedWheelset& w : ws) {
      for (const FlangeClimbCheck* c : {&w.high_climb, &w.low_climb}) {
        if (c->exceeded && out.status != CurvingStatus::kFlangeClimb) {
          out.status = CurvingStatus::kFlangeClimb;
          out.message = FlangeClimbWarning(*c, fmt::format("wheelset {} {} wheel", &w - ws.data(),
                                                           c == &w.high_climb ? "high" : "low"));
        }
      }
    }
  }
  out.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace railwear
