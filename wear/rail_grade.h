// Rail steel grades (issue 16 point 3): the material presets a scene names with
// `[materials] rail = { grade = "R260" }`, and where each number comes from.
//
// Hardness: EN 13674-1 (Vignole rails) gives each grade a Brinell range on the running surface:
//   R200    200-240 HBW   Rm >= 680 MPa   (non-heat-treated, C-Mn)
//   R260    260-300 HBW   Rm >= 880 MPa   (non-heat-treated, C-Mn; the standard grade)
//   R350HT  350-390 HBW   Rm >= 1175 MPa  (head-hardened)
// railwear takes the middle of the range and converts Brinell numbers (kgf/mm^2) to pressure:
// H = HB * 9.80665 MPa, so R200 2157 MPa, R260 2746 MPa, R350HT 3628 MPa. Archard and the KTH
// map read this H (Archard: k p |v_s| / H; KTH: the region boundary p = 0.8 H as well).
//
// Shear yield k (damage: Johnson's shakedown map, the Ekberg surface index): EN 13674-1 sets no
// yield strength. railwear's estimate scales the project's long-standing R260-type value,
// 350 MPa, with the grade's minimum tensile strength: k = 350 MPa * Rm / 880 MPa (R200 270 MPa,
// R350HT 467 MPa). This is railwear's choice, not a published value.
//
// Elastic constants and density: E 210 GPa, nu 0.28, 7850 kg/m^3 for every grade (pearlitic rail
// steels differ by less than 1 % in these).
//
// Wear coefficients: no grade-specific KTH map or USFD function is published in the sources
// railwear has checked (docs/wear.md "Rail grades"): the KTH map (Jendel 2002) was measured for
// one rail steel, and the USFD function is the R8T wheel steel's (Lewis & Dwyer-Joyce 2004;
// Braghin et al. 2006). So a grade changes Archard and KTH wear through H only, and USFD wear not
// at all (it has no hardness).
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "core/numerics/enum_names.h"

namespace railwear {

enum class RailGrade { kR200, kR260, kR350HT };
inline constexpr std::array<EnumName<RailGrade>, 3> kRailGradeNames = {{
    {RailGrade::kR200, "R200"},
    {RailGrade::kR260, "R260"},
    {RailGrade::kR350HT, "R350HT"},
}};
std::string_view ToString(RailGrade v);
std::optional<RailGrade> RailGradeFromString(std::string_view s);

struct RailGradeProperties {
  double hardness_min_HB = 0.0, hardness_max_HB = 0.0;  // EN 13674-1 range [HBW]
  double tensile_strength_min_Pa = 0.0;                 // EN 13674-1 minimum Rm [Pa]
  double hardness_Pa = 0.0;                             // middle of the range, HB * 9.80665e6 [Pa]
  double shear_yield_Pa = 0.0;                          // railwear's estimate (above) [Pa]
  double youngs_modulus_Pa = 210e9;
  double poisson_ratio = 0.28;
  double density_kg_m3 = 7850.0;
};

// The preset of a grade (values above).
RailGradeProperties RailGradeOf(RailGrade grade);

// Wheel steel grades (issue 16 points 3 and 6): the presets a scene names with
// `[materials] wheel = { grade = "R8" }` (or a traffic entry's `wheel_wear = { grade = ... }`),
// for the wear of a wheel that co-evolves with the rail (wear/wheel_wear.h).
//
// EN 13262 (railway wheels; its grades are written ER7, ER8) as commonly quoted, railwear could
// not check the standard's own text here:
//   R7 (ER7)  Rm 820-940 MPa   ReH >= 520 MPa   rim hardness >= 235 HBW
//   R8 (ER8)  Rm 860-980 MPa   ReH >= 540 MPa   rim hardness >= 245 HBW
// The standard gives the rim hardness as a minimum only (throughout the wear range of the rim),
// so railwear takes that minimum: H = 235 * 9.80665 = 2305 MPa (R7), 245 HB = 2403 MPa (R8).
// Delivered rims are often harder near the tread; the minimum is the conservative choice for
// wear (a softer wheel wears more). Shear yield: von Mises from the minimum yield strength,
// k = ReH / sqrt(3) (300 and 312 MPa) — railwear's estimate. E, nu and density as rail steel.
// The R8T wheel steel of the USFD wear function (wear/wear_law.h) is an R8 grade.
enum class WheelGrade { kR7, kR8 };
inline constexpr std::array<EnumName<WheelGrade>, 2> kWheelGradeNames = {{
    {WheelGrade::kR7, "R7"},
    {WheelGrade::kR8, "R8"},
}};
std::string_view ToString(WheelGrade v);
std::optional<WheelGrade> WheelGradeFromString(std::string_view s);

struct WheelGradeProperties {
  double hardness_min_HB = 0.0;                               // EN 13262 rim minimum [HBW]
  double tensile_strength_min_Pa = 0.0, tensile_strength_max_Pa = 0.0;  // EN 13262 Rm [Pa]
  double yield_strength_min_Pa = 0.0;                         // EN 13262 ReH minimum [Pa]
  double hardness_Pa = 0.0;     // the rim minimum, HB * 9.80665e6 [Pa]
  double shear_yield_Pa = 0.0;  // ReH / sqrt(3), railwear's estimate [Pa]
  double youngs_modulus_Pa = 210e9;
  double poisson_ratio = 0.28;
  double density_kg_m3 = 7850.0;
};

// The preset of a wheel grade (values above).
WheelGradeProperties WheelGradeOf(WheelGrade grade);

}  // namespace railwear
