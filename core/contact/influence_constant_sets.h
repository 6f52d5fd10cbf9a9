// Named sets of the influence constants of the seed's eq. 4 (issue 17, point 7): a scene picks
// one with [model] constants = "fem" | "paper", `railwear contact --constants NAME` too.
//   fem:   fitted by `railwear calibrate` to CalculiX displacement curves of large convex and
//          concave bodies (examples/calibration/calibrated_paper.toml, docs/calibration.md: c_f
//          at the half-space value, c_t near Cerruti's). Never fitted to a contact case, it is
//          within 1.7 % on area and 1.9 % on peak pressure of both FEM contact cases
//          (docs/fem_contact_cases.md). The scenes' default (app/scene.h).
//   paper: the seed's (c_f 0.75, c_z 1, c_s 0.25, one set; InfluenceConstants' defaults), which
//          the same FEM cases find 24 % low on area and 29 % high on peak pressure.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "core/contact/contact_types.h"
#include "core/numerics/enum_names.h"

namespace railwear {

enum class InfluenceConstantsName { kFem, kPaper };
inline constexpr std::array<EnumName<InfluenceConstantsName>, 2> kInfluenceConstantsNames = {{
    {InfluenceConstantsName::kFem, "fem"},
    {InfluenceConstantsName::kPaper, "paper"},
}};
std::string_view ToString(InfluenceConstantsName v);
std::optional<InfluenceConstantsName> InfluenceConstantsNameFromString(std::string_view s);

InfluenceConstants NamedInfluenceConstants(InfluenceConstantsName name);
// The name of the named set equal to `c` (exactly), else std::nullopt.
std::optional<InfluenceConstantsName> NameOf(const InfluenceConstants& c);

}  // namespace railwear
