// GeometryModel: which reference surface a contact patch's grid lives on (Model A's tangent
// plane or the seed's intermediate surface). Geometry builds the grid on it; the contact
// model's options choose it.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "core/numerics/enum_names.h"

namespace railwear {

// Which surface the contact grid lives on.
enum class GeometryModel {
  kPlanar,     // tangent plane of the first contact point, gap along its normal (Model A)
  kConformal,  // intermediate surface (seed eq. 1), gap by orthogonal projection (seed eq. 2)
};
inline constexpr std::array<EnumName<GeometryModel>, 2> kGeometryModelNames = {{
    {GeometryModel::kPlanar, "planar"},
    {GeometryModel::kConformal, "conformal"},
}};

std::string_view ToString(GeometryModel v);
// Return std::nullopt for an unknown name (the caller reports the error with file and key).
std::optional<GeometryModel> GeometryModelFromString(std::string_view s);

}  // namespace railwear
