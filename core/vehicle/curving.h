// Steady-state curving: where a vehicle's wheelsets run in a curve of constant radius and cant,
// found by balancing the contact forces of railwear's own wheel-rail contact against the
// suspension and the unbalanced lateral force.
//
// Unknowns (core/vehicle/vehicle.h for the layout), each in its own local track frame: every
// wheelset's lateral displacement y (toward the high rail, +Y) and angle of attack psi (yaw
// against the local track tangent, positive nose toward the high rail); a bogie vehicle adds
// each bogie frame's (y, psi) and the car body's (y, psi). Each wheelset's pitch velocity is
// found inside its contact solve (core/contact/wheelset_contact.h) so that its wheels' creep
// forces F_x add up to the axle's traction (0: free rolling), and its roll so that both wheels
// touch their rails. The equations: per body the lateral force and the yaw moment about its
// centre, with
//   - the contact forces of both wheels (normal and creep parts, with two-point contact and the
//     flange force as the contact finds them: the flange force is a result of the equilibrium);
//   - the primary and secondary springs, deflected by the bodies' positions against each other
//     and by the curve itself (a body at x from the car body's centre sits kappa x^2 / 2 inside
//     and yawed by -kappa x against the centre's tangent);
//   - the unbalanced lateral force m a_u (core/vehicle/curve.h), lumped on the car body (on the
//     wheelset of a single-wheelset vehicle), and the load transfer m a_u h_cg / (2 l0) from the
//     low to the high wheel of every axle.
// Solution: damped Newton with a finite-difference Jacobian of each wheelset's contact forces
// (the suspension's part is linear and exact). The iterates first use the cheap predictor contact
// model (the problem's own kernel and constants on the draft grid, the auto model for a conformal
// one, with the same rolling-contact method: a planar
// half-space patch on the tread, a conformal one where the patch wraps from the flange root
// onto the flange; a planar patch there keeps its first point's normal, and the lateral force
// jumped by 70 kN within 4 um of y at the S1002/UIC60 flange, leaving no equilibrium), as MBS
// codes use precomputed
// contact functions; the solution is then finished with the problem's own contact model, so the
// returned state and forces are those of the full contact at the scene's accuracy. Where the
// contact grid's force noise stops the line search: within 3x the tolerance the solve ends there
// (converged, said in the message); up to 20x the tolerance it ends there too when the Newton
// correction is within the position tolerances (stiff flange contact: converged in position),
// or when a probe within the position tolerances along the Newton direction reverses the sign of
// every residual above the tolerance (a step in the contact forces, as the worn gauge corner's
// contact switches between one and two patches: converged in position at the step);
// when the line search and the Levenberg-Marquardt trials fail above 3x and within 20x the
// tolerance, a natural-level step (accepted when the trial is nearer the equilibrium in
// position: its simplified Newton correction shorter than the step) crosses a step in the
// contact forces that no residual-reducing step crosses, and ends the solve converged in
// position when that correction is within the position tolerances;
// otherwise one retry with 4x wider finite differences; and a draft solve stalled within 20x the
// tolerance goes on once on the standard grid (docs/curving.md). The starts, in order: the
// given start (CurvingOptions::start), the fallback starts (CurvingOptions::fallback_starts: in
// a wear run the vehicle's equilibrium on the unworn rails), the centred start. A start that is
// not the last gives up when its merit fell by less than 5 % in 6 iterations while it was never
// within 20x the tolerance (stalled far off: the next start is tried). When every start fails,
// the centred start is tried once more, first relaxed toward the equilibrium by pseudo-transient
// continuation (each wheelset moved along its residual force, then Newton), said in the message.
// A start with its Jacobian (CurvingStart) uses that Jacobian as the first chord and goes to the
// full model directly (continuation), then, when that fails, through the predictor. A solution
// from a start after the first says so in its message; CurvingResult::attempts counts the
// solves of every start.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_table.h"
#include "core/contact/wheelset_contact.h"
#include "core/vehicle/curve.h"
#include "core/vehicle/vehicle.h"

namespace railwear {

// Where a solve starts: a solution of the same vehicle at a nearby speed or cant, or on slightly
// different rails (continuation: the wear's previous step), and the equilibrium Jacobian there.
struct CurvingStart {
  Eigen::VectorXd state;  // CurvingResult::state
  // CurvingResult::jacobian at that state [N/m, N/rad, N m/m, N m/rad]: the first iterations'
  // chord. Empty, or of another size: evaluated afresh at the start.
  Eigen::MatrixXd jacobian;
  // What the start is, for the result's message and attempts ("the previous step's solution");
  // empty: "the given start" (CurvingOptions::start) or "fallback start N".
  std::string label;
  // A start known only by how to find it, when `state` is empty: SolveCurving calls it once,
  // when the solve reaches this start, and tries what it returns (its state and Jacobian; its
  // label when `label` is empty) as it would have tried that start given: a fallback that costs
  // a solve of its own (`railwear curving --db`'s unworn rails' equilibrium) is solved only when
  // the starts before it fail. A returned state of another size (empty: none found) or equal to
  // an earlier start's is skipped. It must not throw; cancelled, it may return an empty start
  // (the solve then stops on CurvingOptions::cancel).
  std::function<CurvingStart()> lazy;
};

// The cold solve's predictor: the iterates' contact model before the full model finishes.
enum class CurvingPredictor {
  // A grid contact model: CurvingOptions::predictor, or the problem's own on the draft grid.
  kModel,
  // Tabulated rigid contact geometry with Hertz and Kalker (core/contact/contact_table.h), built
  // once per wheel and rail pair; its equilibrium is then finished with the full model. A start
  // with its Jacobian still goes to the full model directly; when the table's start fails, the
  // solve falls back to the model predictor (CurvingResult::table_predictor says so).
  kTable,
};
inline constexpr std::array<EnumName<CurvingPredictor>, 2> kCurvingPredictorNames = {{
    {CurvingPredictor::kModel, "model"},
    {CurvingPredictor::kTable, "table"},
}};
inline std::string_view ToString(CurvingPredictor p) {
  return EnumToString(kCurvingPredictorNames, p);
}

// What became of the table predictor in a solve.
enum class TablePredictorOutcome {
  kNotUsed,   // CurvingPredictor::kModel, or the solve ended before a table start
  kUsed,      // the table's equilibrium, finished with the full model, is the solution
  kFellBack,  // the table's start failed (table or finish): solved with the model predictor
};
inline constexpr std::array<EnumName<TablePredictorOutcome>, 3> kTablePredictorOutcomeNames = {{
    {TablePredictorOutcome::kNotUsed, "not_used"},
    {TablePredictorOutcome::kUsed, "used"},
    {TablePredictorOutcome::kFellBack, "fell_back"},
}};
inline std::string_view ToString(TablePredictorOutcome o) {
  return EnumToString(kTablePredictorOutcomeNames, o);
}

struct CurvingOptions {
  // The predictor of a solve that does not continue from a start with its Jacobian; absent
  // (ColdPredictorFor): the table (kTable) when the problem's model is finer than draft and no
  // `predictor` model is given, else the model predictor. At standard the table with warm_contact
  // took the main job's coach from 68 to 12 wheelset solves and the Y25 wagon from 92 to 20
  // (docs/curving.md, "Table and warm contact, the default at standard"); at draft, a single phase,
  // the model predictor stays (the main job's results unchanged). kModel here: the behaviour
  // before.
  std::optional<CurvingPredictor> cold_predictor;
  // The contact table's nodes when cold_predictor is kTable (its build threads: `threads`).
  ContactTableOptions table;
  // The contact model of the iterates (the predictor's phase): this model when given, otherwise
  // the problem's own model on the draft grid (PredictorFor), so that a problem at draft accuracy
  // is solved in one phase; the problem's own model here: the full model throughout (slower, no
  // better).
  // A start with its Jacobian (continuation) is first finished with the full model directly:
  // it is a solution of the full model nearby, and the predictor's equilibrium lies farther off
  // (0.06-0.07 mm and 0.03 mrad between draft and standard on the main job's rails).
  std::optional<ModelOptions> predictor;
  // Convergence: every residual below tolerance x Q0 (forces) or tolerance x Q0 x l0 (moments),
  // Q0 the static wheel load, l0 = 0.75 m. The default sits just above the noise of the draft
  // grid's forces against the wheelset's position (about 1.7e-3 Q0, measured at the S1002
  // flange): a tighter tolerance needs a finer grid.
  double tolerance = 3e-3;
  int max_iterations = 40;  // per phase (predictor, full)
  // A start that stops (not_converged) within this multiple of the tolerance is not retried from
  // the next start: it is the solution within the contact grid's force noise, which in flange
  // contact on worn rails was measured at up to 4.7x the tolerance. Callers may use such a
  // result (the wear does, with a warning); its status stays not_converged.
  double usable_multiple = 5.0;
  // Convergence in position, where the forces cannot meet the tolerance: in stiff two-point
  // flange contact on worn rails the lateral force turns by 100 kN within 0.15 mm of y and steps
  // by 1-2 kN as cells enter the patch (measured at 5 MGT on the main job's R 600 m curve). A
  // solve also ends, converged and said so, when no step reduces the residual, the largest
  // scaled residual is within 20x the tolerance and the Newton correction from a fresh Jacobian
  // moves no wheelset by more than these: of the order of the draft grid's own position error
  // (draft and standard differ by 0.06-0.07 mm and 0.03 mrad on the main job's unworn rails,
  // `railwear accuracy SCENE --curving`); 0.05 mrad is 1.5 % of the leading wheelsets' angle of
  // attack there. At 7.5 MGT the coach's corrections stopped at 0.033 mm and 0.038 mrad on both
  // the draft and the standard grid (docs/curving.md).
  double position_tolerance_m = 5e-5;
  double yaw_tolerance_rad = 5e-5;
  // A wheelset pushed beyond this lateral displacement has no equilibrium (it climbs) [m].
  double max_lateral_m = 0.02;
  // A solution to start from (CurvingResult::Start()); the centred start is tried after it.
  std::optional<CurvingStart> start;
  // Starts tried in order after `start` fails and before the centred start, each as `start` is
  // (with its Jacobian first on the full model, then through the predictor); one of another size,
  // or whose state equals an earlier start's, is skipped. In a wear run: the vehicle's
  // equilibrium on the unworn rails, when the previous step's solution (`start`) fails: on the
  // worn rails of the 10 MGT study's step 105 the coach from the centred start took 316 wheelset
  // solves (docs/curving.md, "The start sequence"). A lazy start (CurvingStart::lazy) is found
  // only when the solve reaches it.
  std::vector<CurvingStart> fallback_starts;
  // Workers for the wheelsets' contact solves (each iterate's wheelsets and finite differences
  // are independent): 0 = the machine's hardware threads. Results do not depend on it.
  int threads = 0;
  // In the full model's phases (not the predictor's, whose finite differences then met the warm
  // start's noise and took more iterations), each wheelset's contact solves start warm
  // (contact_warm_start.h) from the last solve of the same stream (the iterates, or one
  // finite-difference direction) under the same contact model: cheaper where the full model's
  // patches are conformal (their operators kept), and the results differ from cold solves by the
  // contact grid's discretization error (docs/curving.md, "Kept placements and warm contact
  // solves"). A problem without a predictor's phase (the predictor is its own model) is solved
  // warm throughout. Deterministic and independent of `threads`. Absent (WarmContactFor): on
  // when the problem's model is finer than draft, off at draft (where it did not pay: the main
  // job's coach took 96 solves instead of 56); false here: the behaviour before.
  std::optional<bool> warm_contact;
  // Cancellation (issue 17), empty: never. Asked before every Newton iteration and before every
  // evaluation of the wheelsets' contact forces (from the calling thread: it must be
  // thread-safe, e.g. read an atomic flag). Once it returns true the solve stops at once with
  // CurvingStatus::kCancelled. The library installs no signal handler: app/ sets the flag from
  // its own (WearOptions::cancel is passed on here by wear/).
  std::function<bool()> cancel = {};

  // cold_predictor and warm_contact as a solve of the full model `full` uses them: as given, or
  // when absent the table and warm contact solves at standard accuracy and finer
  // (full.accuracy other than AccuracyPreset::kDraft; the table only without a `predictor`
  // model given), the model predictor and cold contact solves at draft.
  CurvingPredictor ColdPredictorFor(const ModelOptions& full) const;
  bool WarmContactFor(const ModelOptions& full) const;

  // The auto model on the draft grid with the default constants (a cheap contact for tests).
  static ModelOptions PredictorModel();
  // The predictor of a full model: the same kernel and constants on the draft grid, the auto
  // model (planar patches on the tread, conformal ones where the patch wraps the gauge corner)
  // for a conformal one; a planar (half-space) patch at the flange keeps its first point's
  // normal, and there the lateral force jumped by 70 kN within 4 um of y on S1002/UIC60.
  static ModelOptions PredictorFor(const ModelOptions& full);
};

// The two wheels of one wheelset, each in its own rail's frame (the low wheel mirrored as the low
// rail is, core/notation.md): worn wheels of one wheelset differ (wear co-evolution, issue 16).
struct WheelsetWheels {
  Profile high, low;
};

struct CurvingProblem {
  ContactSetup contact;  // materials, model (the solution's accuracy), tangential method, damage
  Profile high_rail;     // the right (outer) rail, its own frame, inclination applied
  Profile low_rail;      // the left (inner) rail, its own frame, inclination applied
  // Where the rails stand; absent: from the profiles (pass the unworn rails' for worn ones).
  std::optional<RailGaugePoints> gauge_points;
  TrackSpec track;
  CurveSpec curve;
  VehicleSpec vehicle;
  // Each wheelset's own wheels, from the front (one per wheelset); empty: vehicle.wheel_profile
  // on every wheel.
  std::vector<WheelsetWheels> wheels;
  double speed_m_s = 20.0;
  double friction = 0.3;
  CurvingOptions options;
};

enum class CurvingStatus {
  kConverged,      // equilibrium found, every wheel below Nadal's limit
  kFlangeClimb,    // equilibrium found, but a wheel in flange contact exceeds Nadal's limit
  kNoEquilibrium,  // a wheelset went past max_lateral_m, or a wheel unloaded: no steady state
  kNotConverged,   // the iterations stopped before the tolerance
  kCancelled,      // CurvingOptions::cancel returned true: stopped, the state is not a solution
};

inline constexpr std::array<EnumName<CurvingStatus>, 5> kCurvingStatusNames = {{
    {CurvingStatus::kConverged, "converged"},
    {CurvingStatus::kFlangeClimb, "flange_climb"},
    {CurvingStatus::kNoEquilibrium, "no_equilibrium"},
    {CurvingStatus::kNotConverged, "not_converged"},
    {CurvingStatus::kCancelled, "cancelled"},
}};
inline std::string_view ToString(CurvingStatus s) { return EnumToString(kCurvingStatusNames, s); }

// The Newton rule that ended the solve of the returned state (docs/curving.md, "The Newton
// rules"); its message says the same in words. Not written by `railwear curving --json`.
enum class CurvingEnding {
  kNone,            // no solve ended on a rule: not converged, no equilibrium, cancelled
  kTolerance,       // every residual below the tolerance
  kGridNoise,       // no step reduced a residual within 3x the tolerance: the grid's noise
  kPosition,        // a fresh Newton correction within the position tolerances (<= 20x)
  kNaturalLevel,    // the natural-level step's correction within the position tolerances
  kForceStepProbe,  // a probe within the position tolerances reversed every residual's sign
};
inline constexpr std::array<EnumName<CurvingEnding>, 6> kCurvingEndingNames = {{
    {CurvingEnding::kNone, "none"},
    {CurvingEnding::kTolerance, "tolerance"},
    {CurvingEnding::kGridNoise, "grid_noise"},
    {CurvingEnding::kPosition, "position"},
    {CurvingEnding::kNaturalLevel, "natural_level"},
    {CurvingEnding::kForceStepProbe, "force_step_probe"},
}};
inline std::string_view ToString(CurvingEnding e) { return EnumToString(kCurvingEndingNames, e); }

// One start's attempt in a solve (CurvingResult::attempts), in the order tried.
struct CurvingAttempt {
  // The start (CurvingStart::label, "the centred start", "the centred start relaxed", "the centred
  // start through the contact table", "the best stopped attempt on the standard grid"), and for a
  // start with its Jacobian which of its two tries: ", continued on the full model" or ", through
  // the predictor".
  std::string start;
  int contact_solves = 0;  // of this attempt, all its phases (not the table's evaluations)
  bool converged = false;  // it ended on a Newton rule (its ending may still be flange_climb)
  // Where it stopped (0 when it evaluated nothing), and why when it did not converge.
  double largest_scaled_residual = 0.0;
  std::string message;
};

// One wheelset's steady state.
struct CurvedWheelset {
  double x_m = 0.0;        // position from the car body's centre (0 for a single wheelset)
  double lateral_m = 0.0;  // y, toward the high rail, against the local track centre line
  double yaw_rad = 0.0;    // angle of attack against the local tangent
  double roll_rad = 0.0;   // from both wheels touching their rails
  double pitch_velocity_rad_s = 0.0;
  double high_load_N = 0.0, low_load_N = 0.0;  // prescribed vertical wheel loads
  WheelsetResult contact;  // right = high rail, left = low rail (each in its rail's frame)
  // The rails' forces on the wheelset, track frame (x forward, Y toward the high rail) [N], and
  // their yaw moment about the wheelset centre (+z down: positive turns the nose toward +Y) [N m].
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  double yaw_moment_Nm = 0.0;
  // The high rail's lateral force from this wheelset's high wheel (on the rail, toward its field
  // side, all patches) [N]: the flange force when the wheel is in flange contact.
  double high_lateral_N = 0.0;
  // Nadal's check of each wheel (its own rail's frame): its L/V (all patches, with the creep
  // forces) against Nadal's limit at the steepest contact angle that carries load, the flange's
  // in flange contact even where one conformal patch wraps from the flange root onto the flange
  // (contact.right.climb takes each patch's resultant angle instead).
  FlangeClimbCheck high_climb, low_climb;
  // A wheel rides on its flange beyond the flange's steepest flank, toward the tip (more than
  // half its vertical load 1 mm or more past the flank's end, in the wheel's frame), lifted by
  // the roll more than 3 mm over the other: it climbs, and the contact angle and the flange's
  // restoring force fall as it goes on. No steady state lies there: the solve refuses such
  // trial states and starts (docs/curving.md, "Climbed states are refused").
  bool climbing = false;
};

struct CurvingResult {
  CurvingStatus status = CurvingStatus::kNotConverged;
  CurvingEnding ending = CurvingEnding::kNone;  // converged and flange_climb: the rule that ended
  std::string message;
  double unbalanced_acceleration_m_s2 = 0.0;
  double cant_deficiency_m = 0.0;
  std::vector<CurvedWheelset> wheelsets;           // from the front
  std::vector<Eigen::Vector2d> bogies;             // (y, psi) of each bogie frame, local
  Eigen::Vector2d body = Eigen::Vector2d::Zero();  // (y, psi) of the car body
  // All unknowns, [wheelsets (y, psi)..., frames (y, psi)..., body (y, psi)]: a start for
  // CurvingOptions::start.
  Eigen::VectorXd state;
  // The equilibrium's Jacobian (d residual / d state) as the solve last had it: finite
  // differences of the wheelsets' contact forces, secant-updated along the accepted steps, plus
  // the suspension's exact part. Empty when the solve evaluated none.
  Eigen::MatrixXd jacobian;
  // The largest residuals of all bodies at the solution: lateral [N], yaw [N m], and the
  // wheelsets' longitudinal (F_x minus traction) [N].
  double lateral_residual_N = 0.0;
  double yaw_residual_Nm = 0.0;
  double longitudinal_residual_N = 0.0;
  // The largest residual scaled as CurvingOptions::tolerance is (forces / Q0, moments / (Q0 l0)):
  // below the tolerance when converged; the best start's when not_converged.
  double largest_scaled_residual = 0.0;
  int predictor_iterations = 0;  // of the predictor's phase (none when it is the full model)
  int full_iterations = 0;       // of the full model's phase
  int contact_solves = 0;        // wheelset contact solves, all phases (not the table's)
  // Every start tried, in order, with its solves (their sum is contact_solves).
  std::vector<CurvingAttempt> attempts;
  // The table predictor (CurvingOptions::cold_predictor): what became of it, its wheelset
  // evaluations, and the tables' build time [s] (one table per distinct wheelset wheel pair).
  TablePredictorOutcome table_predictor = TablePredictorOutcome::kNotUsed;
  // Where the last predictor phase ended (its own equilibrium, the start of the full model's
  // finish; empty without one), and the full model's largest scaled residual there.
  Eigen::VectorXd predictor_state;
  double finish_start_residual = 0.0;
  int table_evaluations = 0;
  double table_build_s = 0.0;
  double time_s = 0.0;

  // This solution as the start of a nearby solve (CurvingOptions::start).
  CurvingStart Start() const { return {state, jacobian, {}, {}}; }
};

// Throws InputError for bad input (curve, vehicle, speed, friction; the contact set-up as
// SolveContact does). Failure to converge or to find an equilibrium is a status, never an
// exception.
CurvingResult SolveCurving(const CurvingProblem& problem);

}  // namespace railwear
