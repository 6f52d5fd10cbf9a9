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

}  // namespace railwear
