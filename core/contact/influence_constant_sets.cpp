// The named sets of influence constants (influence_constant_sets.h).
#include "core/contact/influence_constant_sets.h"

namespace railwear {

InfluenceConstants NamedInfluenceConstants(InfluenceConstantsName name) {
  InfluenceConstants c;  // the seed's ("paper")
  if (name == InfluenceConstantsName::kFem) {
    // examples/calibration/calibrated_paper.toml, to the last digit (tested against the file).
    c.separate = SeparateInfluenceConstants{
        .convex = {.c_f = 1.1090795420498247, .c_z = 0.001, .c_s = 0.32737817242879863},
        .concave = {.c_f = 1.098660789752127, .c_z = 0.001, .c_s = -0.3602580498293686}};
  }
  return c;
}

std::optional<InfluenceConstantsName> NameOf(const InfluenceConstants& c) {
  for (const auto& n : kInfluenceConstantsNames) {
    if (NamedInfluenceConstants(n.value) == c) return n.value;
  }
  return std::nullopt;
}

std::string_view ToString(InfluenceConstantsName v) {
  return EnumToString(kInfluenceConstantsNames, v);
}

std::optional<InfluenceConstantsName> InfluenceConstantsNameFromString(std::string_view s) {
  return EnumFromString(kInfluenceConstantsNames, s);
}

}  // namespace railwear
