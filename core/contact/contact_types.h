// Plain value types shared by the contact pipeline: materials, model choices, influence
// constants, accuracy presets. Units are SI unless the name says otherwise.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "core/geometry/geometry_model.h"
#include "core/numerics/enum_names.h"

namespace railwear {

// Linear elastic, isotropic material of one body.
struct Material {
  double youngs_modulus_Pa = 210e9;  // E > 0
  double poisson_ratio = 0.28;       // nu in [0, 0.5)
  // Optional, used by wear and damage (issue 3/4); NaN when not given.
  double hardness_Pa = std::numeric_limits<double>::quiet_NaN();
  double shear_yield_Pa = std::numeric_limits<double>::quiet_NaN();

  double ShearModulus() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
  // k = (1 - nu^2) / (pi E)  [1/Pa]  (seed eq. 1)
  double Compliance() const;
};

// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2   [Pa]
double ContactModulus(const Material& a, const Material& b);

// Which influence function couples pressure to normal displacement.
enum class KernelModel {
  kBoussinesq,  // half-space, Love's closed form per cell
  kGolubenko,   // seed eq. 4, semi-empirical Kelvin type, cell-integrated
};
// The scene's `kind` shorthand. kHertz is analytic and uses no grid. kAuto chooses per patch
// the cheapest model whose error stays within the accuracy preset (core/contact/
// model_selection.h): Hertz or halfspace on non-conformal patches, the conformal geometry where
// the surface turns across the patch.
enum class ModelKind { kHertz, kHalfspace, kConformal, kCustom, kAuto };

// The names of each enum, in enum order (core/numerics/enum_names.h): ToString, FromString, the
// scene's choices and the command line's option values all come from these tables.
inline constexpr std::array<EnumName<KernelModel>, 2> kKernelModelNames = {{
    {KernelModel::kBoussinesq, "boussinesq"},
    {KernelModel::kGolubenko, "golubenko"},
}};
// "custom" is printed only: a scene reaches it by an explicit geometry or kernel, not by name.
inline constexpr std::array<EnumName<ModelKind>, 5> kModelKindNames = {{
    {ModelKind::kHertz, "hertz"},
    {ModelKind::kHalfspace, "halfspace"},
    {ModelKind::kConformal, "conformal"},
    {ModelKind::kCustom, "custom", /*selectable=*/false},
    {ModelKind::kAuto, "auto"},
}};

std::string_view ToString(KernelModel v);
std::string_view ToString(ModelKind v);
// Return std::nullopt for an unknown name (the caller reports the error with file and key).
std::optional<KernelModel> KernelModelFromString(std::string_view s);
std::optional<ModelKind> ModelKindFromString(std::string_view s);

// One set of the constants of the seed's eq. 4 (dimensionless; the seed's values).
struct InfluenceConstantSet {
  double c_f = 0.75;
  double c_z = 1.0;
  double c_s = 0.25;
  bool operator==(const InfluenceConstantSet&) const = default;
};

// A convex set and a concave set (issue 5: calibration may give bodies of either curvature
// sign their own constants).
struct SeparateInfluenceConstants {
  InfluenceConstantSet convex;
  InfluenceConstantSet concave;
  bool operator==(const SeparateInfluenceConstants&) const = default;
};

// Constants of the seed's eq. 4; the seed's values are the defaults. Dimensionless.
//   w_z = (1/rho) [c_f k_f + c_z k_d dn^2/rho^2],  w_x,y = c_t k_d d(x,s)/rho^2,
//   c_t = 1 + c_s sign(body)  (+1 concave body, -1 convex body).
// Either one set for both bodies (c_f, c_z, c_s: the default) or, when `separate` is given, a
// convex and a concave set: each body of a patch then uses the set of its own curvature sign
// (BodyCurvatureSign of its lateral curvature at the patch), both in the normal kernel (which
// sums the bodies: a = sum_b c_f(b) k_f,b, b = sum_b c_z(b) k_d,b) and in the coupling terms
// (c_t(b) = 1 + c_s(b) sign(b)); c_f, c_z, c_s are then unused.
struct InfluenceConstants {
  double c_f = 0.75;
  double c_z = 1.0;
  double c_s = 0.25;
  std::optional<SeparateInfluenceConstants> separate = std::nullopt;

  bool IsSeparate() const { return separate.has_value(); }
  // The set that applies to a body of curvature sign `sign` (+1 concave, -1 convex; 0, a flat
  // body, only without separate sets). With one set, that set whatever the sign.
  InfluenceConstantSet ForBody(int sign) const;
  bool operator==(const InfluenceConstants&) const = default;
};

// The curvature sign of eq. 4 for a body with lateral curvature `curvature_per_m` (convex
// positive, as ContactCandidate's): -1 convex (> 0), +1 concave (<= 0; a straight profile counts
// as concave, as the coupling effect always did). The one place this decision is made.
int BodyCurvatureSign(double curvature_per_m);

// Accuracy presets map to cell sizes relative to the estimated patch (see core/contact/grid_
// resolution.h for the definition and tests/core/contact for the errors they reach on Hertz
// cases: about 5 %, 1 % and 0.2 % on area and peak pressure).
enum class AccuracyPreset { kDraft, kStandard, kReference, kFine };
inline constexpr std::array<EnumName<AccuracyPreset>, 4> kAccuracyPresetNames = {{
    {AccuracyPreset::kDraft, "draft"},
    {AccuracyPreset::kStandard, "standard"},
    {AccuracyPreset::kReference, "reference"},
    {AccuracyPreset::kFine, "fine"},
}};
std::string_view ToString(AccuracyPreset v);
std::optional<AccuracyPreset> AccuracyPresetFromString(std::string_view s);

struct ModelOptions {
  ModelKind kind = ModelKind::kConformal;
  GeometryModel geometry = GeometryModel::kConformal;  // ignored for kHertz and kAuto
  // Ignored for kHertz; for kAuto the kernel of the patches it solves on the conformal geometry
  // (its planar patches always use Boussinesq).
  KernelModel kernel = KernelModel::kGolubenko;
  InfluenceConstants constants;
  AccuracyPreset accuracy = AccuracyPreset::kStandard;
  // Explicit cell size (dx along rolling, ds along the lateral arc) [m]; overrides accuracy.
  std::optional<double> cell_dx_m, cell_ds_m;
  bool operator==(const ModelOptions&) const = default;
};

// The elastic-perfectly-plastic limit on the contact pressure (issue 16): the normal solver
// bounds every cell's pressure by p_lim (NormalProblem::pressure_limit_Pa), so that a patch whose
// elastic pressure would pass it grows until it carries the load (docs/contact_plasticity.md).
//   kNone:     elastic, no limit (the default).
//   kHardness: p_lim = the softer body's hardness, min of the bodies' hardness_Pa that are given:
//              the mean pressure of a fully plastic indentation (Tabor: H ~ 2.8-3 Y; Johnson,
//              Contact Mechanics ch. 6), and the pressure axis of the KTH wear map.
//   kValue:    p_lim = value_Pa, given explicitly.
enum class PressureLimitKind { kNone, kHardness, kValue };
inline constexpr std::array<EnumName<PressureLimitKind>, 3> kPressureLimitKindNames = {{
    {PressureLimitKind::kNone, "none"},
    {PressureLimitKind::kHardness, "hardness"},
    {PressureLimitKind::kValue, "value", /*selectable=*/false},
}};
std::string_view ToString(PressureLimitKind v);

struct PressureLimit {
  PressureLimitKind kind = PressureLimitKind::kNone;
  double value_Pa = 0.0;  // kValue only: p_lim [Pa] > 0
};

// p_lim [Pa] for the pair: absent for kNone; for kHardness the smaller of the bodies' hardness_Pa
// that are given (NaN when neither is); for kValue value_Pa.
std::optional<double> PressureLimitOf(const PressureLimit& limit, const Material& wheel,
                                      const Material& rail);

// Builds ModelOptions for a `kind` shorthand: hertz, halfspace = planar + boussinesq,
// conformal = conformal + golubenko, auto = per patch, conformal patches with boussinesq.
ModelOptions MakeModelOptions(ModelKind kind);

}  // namespace railwear
