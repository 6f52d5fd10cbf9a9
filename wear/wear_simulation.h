// The wear simulation loop: the rails worn by a traffic mix over many axle passes.
//
// A study wears the high rail (WearStudy::rail_profile) and, when it has one, the low rail
// (low_rail_profile; issue 15), each in its own rail frame. One step (DESIGN.md §1, §2):
//   1. each rail's current profile (its own frame) is canted into its track frame with the
//      motion computed once on its unworn profile (CantTransform), so the frame stays fixed;
//   2. the step's load cases (internal::StepLoadCases: the prescribed traffic mix,
//      wear/traffic.h; vehicle curving, wear/vehicle_traffic.h; imported load collectives,
//      wear/collective_traffic.h) are solved as rolling contacts (normal + tangential, and damage
//      when asked) against the rail each case loads, in parallel threads; with the adaptive
//      spread rule (WearOptions::integration_tolerance, wear/spread_step.h) in rounds, each
//      adding nodes to the spreads until the step's worn area per pass is converged;
//   3. each case's per-pass wear depth (times its friction condition's wear factor, per patch
//      by the patch's zone: top of rail or gauge face, wear/friction_condition.h) and RCF damage
//      are binned along its rail's arc length (wear/pass_depth.h) and summed per rail with the
//      case weights in a fixed order per bin
//      (sorted by value), so the result depends neither on the thread count nor on the order of
//      cases;
//   4. each rail's summed per-pass depth is smoothed (wear/depth_smoothing.h: area kept, peak
//      not moved, non-negative, bin-scale noise removed);
//   5. step control: the passes of the step are chosen so the deepest smoothed wear of either
//      rail in the step equals max_depth_per_step (or the passes left, whichever is fewer);
//      every profile point moves along its rail's inward normal by the step's depth, and the
//      moved curve is resampled at a uniform arc-length spacing;
//      with WearOptions::time_step = kHeun (explicit trapezoidal, opt-in) the moved rails are
//      the predictor: steps 2-4 run again on them (a vehicle's curving started from the step's
//      own equilibrium), each rail's predictor field is brought onto the step's bins through the
//      predictor's material map, and the rails move instead by the step's passes times the mean
//      of the two fields, bin by bin (the passes, damage and cases stay the first field's);
//   6. accumulated damage grows by the step's damage (the WLRM's net damage: its falling branch
//      already models wear removing cracks, so wear removes nothing more unless the opt-in
//      damage_layer_m asks for the old rule) and moves with the material onto the next
//      profile's bins (wear/damage_transport.h: conserved over material);
//   7. the wheels of the entries that wear their own (TrafficCase::wheel_wear, co-evolution,
//      issue 16; a vehicle entry's: both wheels of each wheelset, each its own) wear from the
//      same solutions (wear/wheel_wear.h): each such wheel's per-pass
//      depth is summed over its cases with the cases' weights, smoothed as a rail's, and
//      its profile moves along its inward normal by the step's passes times that depth and is
//      resampled, every step; the step's passes (step 5) take the deepest smoothed wear of every
//      rail AND every wearing wheel, so no profile moves more than max_depth_per_step in a step;
//   8. the finished step goes to a callback (app/ stores it in the database).
//
// The loop knows nothing of storage. Its whole state between steps is WearState (profiles,
// passes, MGT, damage per position of each rail), so a run resumed from a stored state continues
// exactly as the uninterrupted run would have.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/contact/contact_forces.h"
#include "core/contact/contact_solver.h"
#include "core/numerics/enum_names.h"
#include "core/profile/profile.h"
#include "core/vehicle/curving.h"
#include "wear/damage_transport.h"
#include "wear/depth_smoothing.h"
#include "wear/friction_condition.h"
#include "wear/pass_depth.h"
#include "wear/spread_integration.h"
#include "wear/traffic.h"
#include "wear/wear_law.h"
#include "wear/wear_measures.h"

namespace railwear {

// How a step integrates the wear over its passes (WearOptions::time_step; scenes: [wear]
// time_step, docs/wear.md "A second-order step"):
//   kEuler: the per-pass depth of the step's own profiles, applied for all the step's passes
//           (explicit Euler in the profile; first order in the step limit);
//   kHeun:  explicit trapezoidal predictor-corrector: the same per-pass depth f0 fixes the passes
//           N, the profiles moved by N f0 give the predictor's per-pass depth f1, and the step
//           moves the profiles by N (f0 + f1) / 2 (second order; twice the load cases a step).
//           Where N (f0 + f1) / 2 would go deeper than the limit by more than 10 % (the
//           predictor's contact moved onto a band f0 barely wore), the step is predicted again
//           with the passes at which the mean reaches the limit (up to twice), and the passes are
//           then cut so that the mean stays within the limit.
enum class WearTimeStep { kEuler, kHeun };
inline constexpr std::array<EnumName<WearTimeStep>, 2> kWearTimeStepNames = {{
    {WearTimeStep::kEuler, "euler"},
    {WearTimeStep::kHeun, "heun"},
}};
std::string_view ToString(WearTimeStep v);

struct WearOptions {
  WearLaw law;
  // The friction conditions traffic entries name (TrafficCase::condition, gauge_face_condition):
  // each one's mu and wear factors, and the gauge-face zone's contact-angle boundary.
  FrictionConditions conditions;
  // Step control: the deepest wear of one step [m], > 0 (with kHeun: f0 fixes the passes, and the
  // mean (f0 + f1) / 2 applied never goes deeper: see WearTimeStep).
  double max_depth_per_step_m = 1e-4;
  // The time step (above). kHeun refuses entries whose wheels wear (ValidateWearStudy).
  WearTimeStep time_step = WearTimeStep::kEuler;
  // Length of the run: exactly one of the two, > 0.
  std::optional<double> total_passes;
  std::optional<double> total_mgt;
  // Integration over each traffic entry's lateral spread (a prescribed entry's, or each
  // wheelset's of a vehicle entry). Absent: the fixed rule, `quadrature_points` Gauss-Hermite
  // nodes per spread. Given: the adaptive rule (wear/spread_integration.h), which adds nodes
  // where the response changes until the step's worn area per pass of every rail is converged
  // to this relative tolerance, in [1e-4, 0.1] (scenes: 0.005 unless they give quadrature_points).
  std::optional<double> integration_tolerance;
  // Gauss-Hermite nodes per traffic entry with a lateral spread, 1..kMaxQuadraturePoints (41;
  // the fixed rule).
  int quadrature_points = 5;
  // When not empty (without integration_tolerance), the fixed rule of every spread (a prescribed
  // entry's and each wheelset's of a vehicle entry) is the piecewise-linear rule
  // (LinearGaussianWeights, wear/spread_integration.h) on these strictly increasing nodes
  // [standard-normal units] instead of quadrature_points Gauss-Hermite nodes: the converged
  // reference on the vehicle curve (docs/wear.md), which no Gauss-Hermite rule up to 61 nodes
  // converges. Scenes: spread_rule = "piecewise_linear" with spread_nodes = m,
  // LinearSpreadNodes(m).
  std::vector<double> spread_nodes;
  // Width of the arc-length bins the wear depth is collected on [m], > 0.
  double bin_m = 1e-4;
  // Arc-length spacing of the rail profile's points after each update [m], > 0.
  double profile_spacing_m = 2e-4;
  DepthSmoothingOptions smoothing;
  // The pre-issue-16 removal of damage by wear, opt-in (absent: none, the default). Given, it is
  // the depth of a surface layer [m] > 0: wearing dz removes the fraction dz / damage_layer of
  // the accumulated damage. That counts wear's removal twice: the WLRM damage function already
  // falls to zero at 175 J/m because wear removes the cracks there (README "RCF damage").
  std::optional<double> damage_layer_m;
  // Worker threads for the load cases; 0 = std::thread::hardware_concurrency().
  int threads = 0;
  // Cancellation (issue 17), empty: never. RunWear asks it before each step, and every step
  // before each of its load cases (from the worker threads: it must be thread-safe, e.g. read an
  // atomic flag) and, through CurvingOptions::cancel, inside a vehicle entry's curving solve
  // before each Newton iteration and each evaluation of the wheelsets' contacts. Once it returns true the step in flight is dropped, never handed to the step
  // callback, and RunWear returns with WearRunSummary::cancelled. The library installs no
  // signal handler: app/ sets the flag from its own.
  std::function<bool()> cancel = {};
};

// The spread rule the options choose: the adaptive rule with integration_tolerance, the
// piecewise-linear rule with spread_nodes, else quadrature_points Gauss-Hermite nodes.
SpreadRule SpreadRuleOf(const WearOptions& o);

// Thrown by RunWearStep when WearOptions::cancel returned true during the step (RunWear catches
// it and reports WearRunSummary::cancelled).
class WearCancelled : public std::runtime_error {
 public:
  WearCancelled() : std::runtime_error("wear step cancelled") {}
};

// Everything a wear run needs: the contact set-up of every load case (base; rail_material needs
// hardness_Pa for Archard and KTH, shear_yield_Pa for damage; model a grid model, not Hertz;
// damage: RCF damage per position), the rails and the traffic mix.
struct WearStudy : ContactSetup {
  Profile rail_profile;  // the unworn high (right) rail, its own frame (as in the scene)
  // The unworn low (left) rail, its own frame (mirrored: y toward its field side); absent in a
  // single-rail study, which then has no low-rail traffic.
  std::optional<Profile> low_rail_profile;
  double cant_ratio = 0.0;  // rail inclination of both rails, 1:40 -> 0.025
  std::vector<TrafficCase> traffic;
  // Vehicle traffic (TrafficCase::vehicle): the vehicles, the track's gauge and its curve. Each
  // step solves steady-state curving (core/vehicle/curving.h) of every vehicle entry on the
  // current worn rails, which keep the unworn rails' places in the track.
  std::vector<VehicleSpec> vehicles;
  TrackSpec track;
  CurveSpec curve;
  // The cold predictor of every vehicle entry's curving (CurvingOptions::cold_predictor): the
  // solves on the unworn rails, and a step's fallback from the centred start (scenes: [curving]
  // predictor).
  // Absent: CurvingOptions::ColdPredictorFor's default (the table at standard and finer).
  std::optional<CurvingPredictor> curving_predictor;
  // Warm contact solves in every vehicle entry's curving (CurvingOptions::warm_contact; scenes:
  // [curving] warm_contact). Absent: CurvingOptions::WarmContactFor's default (on at standard
  // and finer, off at draft: it moves the equilibria within the curving's position tolerances).
  std::optional<bool> curving_warm_contact;
  // Per traffic entry, the curving solution on the unworn rails (empty, or an empty entry: the
  // centred start): the start of a step whose state carries none (WearState::curving), and the
  // fallback of one whose previous step's solution fails, before the centred start
  // (VehicleCurvingProblem). RunWear fills it with each vehicle's equilibrium on the unworn rails
  // of step 0 when the study has a vehicle entry.
  std::vector<CurvingStart> vehicle_starts;
  WearOptions options;
};

// Throws InputError for an inconsistent study (Hertz model, missing hardness, both or neither
// total, non-positive limits, bad traffic, damage without shear yield, low-rail traffic without
// a low rail).
void ValidateWearStudy(const WearStudy& study);

// The run's length in axle passes: total_passes, or total_MGT over the mix's MGT per pass.
double TotalPasses(const WearStudy& study);

// The state between steps: all a run needs to continue.
struct WearState {
  int step = 0;         // steps done (0: the unworn profile)
  double passes = 0.0;  // cumulative wheel passes
  double mgt = 0.0;     // cumulative million gross tonnes
  Profile rail;         // current high rail profile, its own frame
  // Accumulated RCF damage per arc-length bin of `rail` (WearGrid::ForProfile(rail, bin_m)).
  // Empty means zero everywhere (no damage effect, or nothing accumulated yet).
  std::vector<double> damage;
  // The low rail, as `rail` and `damage` (its own frame); absent in a single-rail study.
  std::optional<Profile> low_rail;
  std::vector<double> low_damage;
  // Per traffic entry, the curving solution of the step that led here (vehicle entries; empty
  // entries otherwise): the next step starts there, with its Jacobian as the first chord, so a
  // step's curving costs a few residual evaluations instead of a solve from the unworn start.
  // Part of the state: a resumed run reads it back and continues bit-identically. With
  // WearTimeStep::kHeun it is the solution on the step's predictor rails (the nearest the next
  // step's rails), itself started from the step's own. Empty (step 0,
  // or a run stored without it): each entry starts from WearStudy::vehicle_starts, which is also
  // the fallback when this start fails.
  std::vector<CurvingStart> curving;
  // Co-evolution (issue 16): per traffic entry, the current profile of an entry whose wheel wears
  // (TrafficCase::wheel_wear; wheel profile frame), an empty profile for the others; empty when
  // no entry's wheel wears. At step 0 each is the entry's wheel_profile as given (not
  // resampled: the first step's contacts are those of the same study without wheel wear).
  std::vector<Profile> wheels;
  // Co-evolution of a vehicle entry's wheels: per traffic entry, each wheelset's current wheels
  // (from the front; high and low, each in its rail's frame) of a vehicle entry whose wheels wear,
  // empty for the others; empty when no vehicle entry's wheels wear. At step 0 every wheel is the
  // vehicle's wheel_profile as given.
  std::vector<std::vector<WheelsetWheels>> vehicle_wheels;
};

// The current profile of wheel `wheel` (WheelStepResult::wheel: 0 an entry's one wheel, else a
// vehicle entry's VehicleWheelIndex) of traffic entry `traffic_index` in `state`; it must be there.
const Profile& StateWheel(const WearState& state, int traffic_index, int wheel);
// The same slot to write, made when missing (a state read back from storage).
Profile& StateWheelSlot(WearState* state, int traffic_index, int wheel);

// Step 0 of a run: the unworn rails resampled at the study's profile spacing.
WearState MakeInitialState(const WearStudy& study);

// The step-0 profiles the wear measures are taken against and whose cant fixes each rail's track
// frame. Implicit from one profile for single-rail callers.
struct UnwornRails {
  UnwornRails(Profile high_rail, std::optional<Profile> low_rail = std::nullopt)  // NOLINT
      : high(std::move(high_rail)), low(std::move(low_rail)) {}
  // The rails of a step-0 state (MakeInitialState, or step 0 read back from storage).
  static UnwornRails Of(const WearState& step0) { return {step0.rail, step0.low_rail}; }
  Profile high;
  std::optional<Profile> low;
};

// The contact problem a wear step solves for a load case on its rail (rail_track: the case's rail
// canted into its track frame): the study's set-up, the case's wheel (CaseWheelProfile), its
// placement, vertical load, motion and friction. Also what FlangeOnsetOffset solves
// (wear/vehicle_traffic.h), so that the flange onset is the nodes' own contact model's.
ContactProblem LoadCaseProblem(const WearStudy& study, const Profile& rail_track,
                               const LoadCase& load_case);

namespace internal {
// MakeInitialState without ValidateWearStudy, for callers that validated the study once already
// (the scene reader, railwear accuracy).
WearState InitialState(const WearStudy& study);
}  // namespace internal

// What one load case of a step gave.
struct LoadCaseSummary {
  LoadCase load_case;
  SolverStatus status = SolverStatus::kNoContact;
  std::string message;
  int patches = 0;
  // The pressure's part of the force on the rail, rail frame (vertical +z down, lateral +y).
  double vertical_force_N = 0.0, lateral_force_N = 0.0;
  // The force on the rail, rail frame: pressure, creep and net parts (contact_forces.h).
  ForceParts forces;
  FlangeClimbCheck climb;  // L/V (net, on the rail) against Nadal's limit
  double area_m2 = 0.0, p_max_Pa = 0.0;
  // The pressure limit of the study (absent: elastic) and the plastic cells at it, their area
  // [m^2] and normal load [N], summed over the patches (ContactResult).
  std::optional<double> pressure_limit_Pa;
  int plastic_cells = 0;
  double plastic_area_m2 = 0.0, plastic_force_N = 0.0;
  double plastic_force_share = 0.0;  // plastic_force_N over the patches' normal force [-]
  double creep_force_x_N = 0.0, creep_force_s_N = 0.0;  // sum over patches, ON THE WHEEL
  double t_gamma_N = 0.0;                               // sum over patches
  double spin_work_N = 0.0;  // |M_z phi| summed over patches [J/m]: spin's part beside T-gamma
  double rcf_damage_per_pass = 0.0;    // largest over patches
  double worn_area_per_pass_m2 = 0.0;  // sum_b depth_b h
  // Co-evolution: the case's wheel's worn area per pass on its profile [m^2] (sum_b depth_b h on
  // the wheel's bins, wear/wheel_wear.h), 0 when the entry's wheel does not wear.
  double wheel_worn_area_per_pass_m2 = 0.0;
  double contact_angle_rad = 0.0;      // of the most loaded patch
  double contact_y_m = 0.0;            // its pressure centre on the rail (track frame)
  // The case's own depth per pass on its rail's bins (unweighted: the step's field is the sum of
  // weight x this over the rail's cases) [m], shape [that rail's grid.n]: what studies of the
  // spread rule compare per wheelset (tests/tools/spread_depth_study.cpp).
  std::vector<double> depth_per_pass_m;
};

// What a step did to one rail (the low rail's part of StepResult; the high rail's are the fields
// of StepResult itself).
struct RailStepResult {
  WearGrid grid;                         // the bins of the profile the step started from
  std::vector<double> depth_per_pass_m;  // weighted mean depth per axle pass, shape [grid.n]
  std::vector<double> step_depth_m;      // smoothed depth removed in this step, shape [grid.n]
  double smoothing_area_error = 0.0;     // relative, before the area correction
  WearMeasures measures;                 // against step 0 (cumulative)
  std::vector<double> damage_per_pass;   // weighted WLRM damage per pass, [grid.n]; empty: none
  MaterialMap material_map;              // this profile's arc length -> the next one's
};

// What a step did to the wheel of one entry that wears its own (co-evolution).
struct WheelStepResult {
  int traffic_index = 0;                 // the entry (WearStudy::traffic)
  // Which wheel of the entry (VehicleWheelIndex, wear/traffic.h): 0 for a prescribed or
  // collective entry's one wheel; 1 + 2 x wheelset + (0 high, 1 low) for a vehicle entry's.
  int wheel = 0;
  WearGrid grid;                         // the bins of the wheel profile the step started from
  std::vector<double> depth_per_pass_m;  // weighted depth per axle pass of the mix, [grid.n]
  std::vector<double> step_depth_m;      // smoothed depth removed in this step, [grid.n]
  double smoothing_area_error = 0.0;     // relative, before the area correction
  // Against the entry's unworn wheel (cumulative; worn area and max depth, W1-W3 NaN).
  WearMeasures measures;
  WheelFlangeMeasures flange;  // Sh, Sd, qR of the wheel after the step (NaN: not measurable)
};

// A step. The grid, depths and measures below are the high rail's; `low_rail` holds the same for
// the low rail in a two-rail study.
struct StepResult {
  WearState state;                         // after this step
  double step_passes = 0.0;                // passes of this step
  WearGrid grid;                           // the bins of the profile the step started from
  std::vector<double> depth_per_pass_m;    // weighted mean depth per wheel pass, shape [grid.n]
  std::vector<double> step_depth_m;        // smoothed depth removed in this step, shape [grid.n]
  std::vector<double> damage_per_pass;     // weighted WLRM damage per pass, [grid.n]; empty: none
  MaterialMap material_map;                // where the material went: arc length -> next's
  double smoothing_area_error = 0.0;       // relative, before the area correction
  WearMeasures measures;                   // against step 0 (cumulative)
  std::optional<RailStepResult> low_rail;  // present when the study has a low rail
  // The wearing wheels, in entry order (a vehicle entry's by wheelset, high before low).
  std::vector<WheelStepResult> wheels;
  std::vector<LoadCaseSummary> cases;      // both rails' cases, in StepLoadCases order
  SpreadIntegrationSummary integration;    // the spread rule's nodes per entry and its error
  // WearTimeStep::kHeun: the load cases the predictor solved, summed over the step's predictions
  // (more than one when the mean overshot the step limit; 0 with kEuler). `cases`,
  // `integration` and the damage are the step's own rails' (f0); depth_per_pass_m and step_depth_m
  // the mean (f0 + f1) / 2 the step applied (docs/wear.md, "A second-order step").
  int predictor_load_cases = 0;
  double seconds = 0.0;                    // wall time of the step
};

// Called after each finished step; return false to stop the run after it.
using WearStepCallback = std::function<bool(const StepResult&)>;

struct WearRunSummary {
  int steps_done = 0;      // steps completed in this call
  bool finished = false;   // the total (passes or MGT) is reached
  bool cancelled = false;  // WearOptions::cancel stopped it (a step in flight was dropped)
  WearState state;         // the last state
};

// Runs steps from `start` until the total is reached, `max_steps` steps were done in this call
// (<= 0: no limit), the callback returns false or study.options.cancel returns true. `unworn` are
// the step-0 profiles (the wear measures are taken against them; a two-rail study needs both).
// `study` must have passed ValidateWearStudy, once per input: ReadWearScene (app/) runs it before
// any database is touched, MakeInitialState for library callers; neither this loop nor its steps
// check it again. Throws std::runtime_error when a load case fails to converge (the steps before it
// are complete and were handed out).
WearRunSummary RunWear(const WearStudy& study, const UnwornRails& unworn, WearState start,
                       const WearStepCallback& on_step, int max_steps = 0);

// One step from `state` (exposed for tests and benchmarks): solves the load cases and returns
// the step. `passes_left` caps the step's passes. Throws WearCancelled when
// study.options.cancel returns true before a load case.
StepResult RunWearStep(const WearStudy& study, const UnwornRails& unworn, const WearState& state,
                       double passes_left);

namespace internal {
// The load cases of one step: the seam every source of load cases goes through: the
// prescribed traffic expanded by Gauss-Hermite (ExpandValidTraffic), then, in entry order, each
// vehicle entry's (VehicleLoadCases) and each collective entry's (CollectiveLoadCases, fixed
// in the unworn track frame); sources that depend on the
// current rails (vehicle curving on the worn profiles) get each rail's current profile canted
// into its track frame: `high_rail_track`, and `low_rail_track` (absent in a single-rail study).
// Each rail's case weights sum to 1 (over the cases on it). Vehicle entries start from
// `curving_starts` (per traffic entry, WearState::curving; empty: WearStudy::vehicle_starts) and,
// when `curving_solved` is given, leave their solutions there (per traffic entry).
std::vector<LoadCase> StepLoadCases(const WearStudy& study, const Profile& high_rail_track,
                                    const std::optional<Profile>& low_rail_track,
                                    const std::vector<CurvingStart>& curving_starts = {},
                                    std::vector<CurvingStart>* curving_solved = nullptr);
}  // namespace internal

// A profile resampled at uniform arc length: ceil(L / spacing) + 1 points including both ends.
Profile ResampleProfile(const Profile& profile, double spacing_m);

// A wearing wheel's measures (worn area, max depth and where) against its unworn profile as
// given. The loop keeps the unworn wheel as given at step 0 (so that opting in to wheel wear
// changes no contact of the first step) and resamples a wheel every step that wears it
// (ResampleProfile). Natural cubic splines through samples at another spacing leave the curve
// off the given one where it curves near an end: up to 0.1 um at S1002's flange back (y = -70
// mm, about 20 mm radius) with no wear there, which a nearly unworn wheel reported as its
// deepest point. So a `worn` profile that is not `unworn` itself is measured against the spline
// through the feet of its points on `unworn` (their closest points: wear moved each point along
// the normal from there): off the worn band the two splines coincide to rounding, on it both
// sample the same curve at the same material points, and what is left is wear (WheelWearTest.
// AWheelWornInTheMiddleReportsItsDepthThereAndNoneAtItsEnds). A rail needs none of this: its
// step 0 is already resampled. `worn` with `unworn`'s points (a wheel that never wore) is
// measured against `unworn` as it is (all zero).
WearMeasures CompareWheelWithUnworn(const Profile& unworn, const Profile& worn);

}  // namespace railwear
