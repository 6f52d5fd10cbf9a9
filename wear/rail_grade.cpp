// Rail steel grade presets: EN 13674-1 hardness ranges and minimum tensile strengths, and the
// values railwear derives from them (rail_grade.h).
#include "wear/rail_grade.h"

#include <cmath>

namespace railwear {

std::string_view ToString(RailGrade v) { return EnumToString(kRailGradeNames, v); }

std::optional<RailGrade> RailGradeFromString(std::string_view s) {
  return EnumFromString(kRailGradeNames, s);
}

namespace {

constexpr double kBrinellToPa = 9.80665e6;         // 1 HB = 1 kgf/mm^2
constexpr double kReferenceShearYield_Pa = 350e6;  // the project's R260-type value
constexpr double kReferenceTensile_Pa = 880e6;     // R260's minimum Rm

RailGradeProperties Make(double hb_min, double hb_max, double rm_min_MPa) {
  RailGradeProperties p;
  p.hardness_min_HB = hb_min;
  p.hardness_max_HB = hb_max;
  p.tensile_strength_min_Pa = rm_min_MPa * 1e6;
  p.hardness_Pa = 0.5 * (hb_min + hb_max) * kBrinellToPa;
  p.shear_yield_Pa = kReferenceShearYield_Pa * p.tensile_strength_min_Pa / kReferenceTensile_Pa;
  return p;
}

}  // namespace

RailGradeProperties RailGradeOf(RailGrade grade) {
  switch (grade) {
    case RailGrade::kR200:
      return Make(200.0, 240.0, 680.0);
    case RailGrade::kR260:
      return Make(260.0, 300.0, 880.0);
    case RailGrade::kR350HT:
      return Make(350.0, 390.0, 1175.0);
  }
  return {};
}

std::string_view ToString(WheelGrade v) { return EnumToString(kWheelGradeNames, v); }

std::optional<WheelGrade> WheelGradeFromString(std::string_view s) {
  return EnumFromString(kWheelGradeNames, s);
}

namespace {

WheelGradeProperties MakeWheel(double hb_min, double rm_min_MPa, double rm_max_MPa,
                               double reh_min_MPa) {
  WheelGradeProperties p;
  p.hardness_min_HB = hb_min;
  p.tensile_strength_min_Pa = rm_min_MPa * 1e6;
  p.tensile_strength_max_Pa = rm_max_MPa * 1e6;
  p.yield_strength_min_Pa = reh_min_MPa * 1e6;
  p.hardness_Pa = hb_min * kBrinellToPa;
  p.shear_yield_Pa = p.yield_strength_min_Pa / std::sqrt(3.0);
  return p;
}

}  // namespace

WheelGradeProperties WheelGradeOf(WheelGrade grade) {
  switch (grade) {
    case WheelGrade::kR7:
      return MakeWheel(235.0, 820.0, 940.0, 520.0);
    case WheelGrade::kR8:
      return MakeWheel(245.0, 860.0, 980.0, 540.0);
  }
  return {};
}

}  // namespace railwear
