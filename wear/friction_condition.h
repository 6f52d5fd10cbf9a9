// Friction conditions of the wheel-rail interface (issue 16 point 1): dry, wet, lubricated and
// friction-modified contact, each with the friction coefficient the rolling contact is solved at
// and a factor on each wear law's coefficient.
//
// Why a wear factor and not only a friction coefficient: lowering mu alone makes a lubricated
// flange wear MORE under Archard-type laws (the traction saturates sooner, so the slip and the
// sliding distance grow while k stays the dry one). Measured on the default study at -4.0 mm
// (issue 16): KTH 2.25e-3 mm^2 at mu 0.1 against 2.00e-3 at 0.4. The practice (Jendel 2002;
// Enblom & Berg, Wear 258 (2005) 1055-1063) scales the dry wear coefficients by about 1/5-1/10
// for wet or lubricated contact; the factor is that scaling.
//
// Defaults (docs/wear.md "Friction conditions" gives the source of every value):
//   condition          mu     archard  kth   usfd
//   dry                0.40   1        1     1
//   wet                0.25   0.2      0.2   0.2
//   lubricated         0.10   0.1      0.1   0.1
//   friction_modified  0.35   0.5      0.5   0.5
// USFD takes the same factors (railwear's choice): its wear rate is a function of the
// frictional energy T-gamma/A, but on the flange T-gamma/A lies on the law's plateau
// (W = 55 ug/(m mm^2) from 10.4 to 77.2 N/mm^2), where a lower mu changes nothing: measured on
// the default study, the flange (patches above 30 degrees) at mu 0.1 without a factor wore 1 %
// MORE than dry.
// Every value can be overridden in the scene ([wear.conditions.NAME]).
//
// Zones: a traffic entry's `condition` applies to the top of the rail, its
// `gauge_face_condition` to the gauge corner and gauge face: patches whose contact angle
// (PatchResult::contact_angle_rad, positive toward the gauge side) exceeds
// gauge_face_angle_rad. Each patch is solved at one mu (the contact core takes one friction
// coefficient per patch), so the zone of a patch is that of its resultant contact angle.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "core/numerics/enum_names.h"
#include "wear/wear_law.h"

namespace railwear {

enum class FrictionCondition { kDry, kWet, kLubricated, kFrictionModified };
inline constexpr std::array<EnumName<FrictionCondition>, 4> kFrictionConditionNames = {{
    {FrictionCondition::kDry, "dry"},
    {FrictionCondition::kWet, "wet"},
    {FrictionCondition::kLubricated, "lubricated"},
    {FrictionCondition::kFrictionModified, "friction_modified"},
}};
std::string_view ToString(FrictionCondition v);
std::optional<FrictionCondition> FrictionConditionFromString(std::string_view s);

// What one condition does to the contact and to each wear law.
struct FrictionConditionParams {
  double friction = 0.4;        // mu of the rolling contact, in (0, 2]
  double archard_factor = 1.0;  // factor on the Archard coefficient k, in (0, 10]
  double kth_factor = 1.0;      // factor on every coefficient of the KTH map (both forms)
  double usfd_factor = 1.0;     // factor on the USFD wear rate W
};

// The published or chosen defaults of a condition (table above).
FrictionConditionParams DefaultFrictionConditionParams(FrictionCondition condition);

// The factor of `params` that belongs to `law` (kth and kth-continuous share kth_factor).
double WearFactor(const FrictionConditionParams& params, WearLawKind law);

// Contact angle above which a patch lies on the gauge corner or gauge face: 15 degrees, where
// the R80 arc of a UIC60 (60E1) head canted 1:40 ends and its R13 gauge-corner arc begins (slope
// 14.6-15.0 degrees at y = -33.2 to -33.5 mm from the head's centre line, from the built-in
// profile). Tread contact on the crown (R300 and R80 arcs) stays below; gauge-corner, flange-root
// and flange contact, where gauge-face lubricators put their grease, lie above.
inline constexpr double kDefaultGaugeFaceAngle_rad = 15.0 * 3.14159265358979323846 / 180.0;

// Every condition's parameters and the zone boundary of a study.
struct FrictionConditions {
  std::array<FrictionConditionParams, 4> params = {
      DefaultFrictionConditionParams(FrictionCondition::kDry),
      DefaultFrictionConditionParams(FrictionCondition::kWet),
      DefaultFrictionConditionParams(FrictionCondition::kLubricated),
      DefaultFrictionConditionParams(FrictionCondition::kFrictionModified)};
  double gauge_face_angle_rad = kDefaultGaugeFaceAngle_rad;  // in (0, pi/2)

  const FrictionConditionParams& operator[](FrictionCondition c) const {
    return params[static_cast<int>(c)];
  }
  FrictionConditionParams& operator[](FrictionCondition c) { return params[static_cast<int>(c)]; }
};

// Throws InputError naming the condition, the parameter, its value and the expected range.
void ValidateFrictionConditions(const FrictionConditions& conditions);

}  // namespace railwear
