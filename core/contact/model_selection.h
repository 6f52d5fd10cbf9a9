// model.kind = "auto": per contact patch, the cheapest model whose error stays within the
// scene's accuracy (issue 6).
//
// The models, cheapest first: Hertz (analytic), halfspace (planar grid + Boussinesq) and the
// conformal geometry (intermediate surface, gap by orthogonal projection). Auto's conformal
// patches use the Boussinesq kernel unless the scene names a kernel: an independent FEM check
// of conformal pairs found the Boussinesq kernel on the curved grid within 2-4 % of FEM and the
// seed's constants 25-30 % high on peak pressure (DESIGN.md §1); the seed's kernel (Model B) is
// about 1.45x stiffer than half-space on any patch and is never used on a planar patch.
//
// The criterion measures the patch over t in [t_lo, t_hi] along the rail profile around the
// contact point (first an estimate of the patch, later the solved one):
//  - the normal turn: the range of the angle of the intermediate surface's normal
//    (K (-n_wheel) + (1 - K) n_rail) over the patch. A planar grid has one normal; the
//    conformal grid's cells turn with the surface, which changes the approach each cell sees
//    (delta cos theta), the direction of its pressure and its gap. The error of halfspace against
//    the conformal geometry (same kernel) grows with this turn;
//  - the approach-weight change: the range of cos(theta) over the patch against its value at the
//    contact point, theta the normal's angle against the (vertical) load direction;
//  - the gap deviation: how far the gap across the patch is from Hertz's quadratic (Hertz
//    assumes constant curvatures over the patch).
// Halfspace is chosen when the contact is no steeper than 45 degrees and the turn and the
// approach-weight change are within the preset's limits, on the estimated patch and again on the
// solved one; Hertz when in addition the gap deviation is within the preset's tolerance and the
// problem needs no grid (no rolling contact, no other patch that needs one); otherwise the
// conformal geometry. The limits were calibrated on S1002/UIC60 1:40, grooves and rolled crowns
// (the measurements are in model_selection.cpp).
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "core/contact/contact_types.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear {

// What the criterion measures on one candidate patch.
struct PatchConformity {
  // The stretch of the rail profile measured: arc-length offsets from the candidate's contact
  // point, t_lo_m < 0 < t_hi_m, growing toward +y [m]; `measured` true when it is the extent of a
  // solved patch (cells with p > 0), false for an estimate.
  double t_lo_m = 0.0, t_hi_m = 0.0;
  bool measured = false;
  double normal_angle_rad = 0.0;  // of the intermediate normal against the vertical at t = 0
  double normal_turn_rad = 0.0;   // range of the intermediate surface's normal angle [rad]
  // Range of cos(theta) over the patch divided by its value at the contact point, theta the
  // intermediate normal's angle against the vertical: how unevenly a vertical approach closes
  // the gap across the patch (a planar grid closes it evenly).
  double approach_weight_change = 0.0;
  // max |g(t) - g(0) - B0 t^2| / (B0 b^2), b = (t_hi - t_lo) / 2: how far the gap across the patch
  // (g the distance of the rail point at t to the wheel) is from Hertz's quadratic, B0 =
  // (k_rail + k_wheel) / 2 the relative lateral curvature at the contact point (convex
  // positive); +inf when B0 <= 0.
  double gap_deviation = 0.0;
  double lateral_radius_m = 0.0;  // 1 / max(|k_rail|, |k_wheel|) at the contact point [m]
};

// Measures the patch of `candidate` (a candidate of `geometry`) over rail arc-length offsets t in
// [t_lo_m, t_hi_m] from the candidate's contact point (t_lo_m < 0 < t_hi_m; t grows toward +y,
// as s on a PatchGrid) [m], on
// kConformitySamples points, against the contact point itself; stiffness_ratio_K = k_rail /
// (k_wheel + k_rail) of seed eq. 1 weighs the two normals. The result has measured = false.
constexpr int kConformitySamples = 9;
PatchConformity MeasureConformity(const WheelRailGeometry& geometry,
                                  const ContactCandidate& candidate, double t_lo_m, double t_hi_m,
                                  double stiffness_ratio_K);

// One sample of a patch's two surfaces at a rail arc offset t from its contact point.
struct ConformitySample {
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();  // intermediate normal (unit, out of the rail)
  double gap_m = 0.0;                  // distance of the rail point to the wheel [m]
  double k_rail = 0.0, k_wheel = 0.0;  // convex-positive lateral curvatures there [1/m]
};
// The measures of PatchConformity (measured = false) from `sample` at t = 0 and at
// kConformitySamples offsets spread over [t_lo_m, t_hi_m] (t_lo_m < 0 < t_hi_m) [m]:
// MeasureConformity's on a placed WheelRailGeometry, and the fast tread path's on its own
// placement (core/contact/hertz_tread.h).
PatchConformity ConformityFromSamples(const std::function<ConformitySample(double)>& sample,
                                      double t_lo_m, double t_hi_m);

// The model auto gives one patch.
enum class PatchModel { kHertz, kHalfspace, kConformal };
std::string_view ToString(PatchModel v);

// Tolerance on area and peak pressure that an accuracy preset stands for: what its grids reach
// on the Hertz cases (tests/core/contact/contact_solver_test.cpp AccuracyPresets...: draft 5 %,
// standard 1 %, reference and fine 0.3 %).
double PresetTolerance(AccuracyPreset preset);
// The limits of a planar patch (halfspace and Hertz) at a preset: the largest normal turn [rad]
// and approach-weight change for which halfspace's area and peak pressure stayed within
// PresetTolerance(preset) of the conformal geometry in the calibration (model_selection.cpp).
double MaxPlanarNormalTurn(AccuracyPreset preset);
double MaxPlanarApproachWeightChange(AccuracyPreset preset);
// Steepest contact (normal against the vertical) given to a planar grid at any preset [rad]: the
// planar model fails on the 68-70 degree S1002 flange (its solution collapses onto a few cells,
// at 100 kN at standard, at 2-2.4 mm shifts at reference); its calibration reaches 40 degrees.
constexpr double kMaxPlanarContactAngle_rad = 0.7853981633974483;  // 45 degrees
// The largest gap deviation for which Hertz is used: PresetTolerance(preset).
double MaxHertzGapDeviation(AccuracyPreset preset);

struct PatchModelChoice {
  PatchModel model = PatchModel::kConformal;
  GeometryModel geometry = GeometryModel::kConformal;  // of the grid (kPlanar for Hertz too)
  KernelModel kernel = KernelModel::kBoussinesq;       // of the grid (unused for Hertz)
  std::string label;   // "hertz", "halfspace", "conformal+boussinesq", "conformal+golubenko"
  std::string reason;  // the criterion with the measured values, for reports
  PatchConformity conformity;
};

// The choice for one patch. `options` gives the accuracy (an explicit cell size counts as
// "standard") and the kernel of conformal patches. no_hertz_reason empty: Hertz may be chosen;
// otherwise it says why not (e.g. "rolling contact needs a grid") and goes into the reason.
PatchModelChoice ChoosePatchModel(const PatchConformity& conformity, const ModelOptions& options,
                                  std::string_view no_hertz_reason);

// The label of a patch solved with a fixed (not auto) model: "hertz", "halfspace",
// "conformal+golubenko", "planar+golubenko", ...
std::string PatchModelLabel(const ModelOptions& options);

}  // namespace railwear
