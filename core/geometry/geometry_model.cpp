// Names of GeometryModel (geometry_model.h).
#include "core/geometry/geometry_model.h"

namespace railwear {

std::string_view ToString(GeometryModel v) {
  return v == GeometryModel::kPlanar ? "planar" : "conformal";
}

std::optional<GeometryModel> GeometryModelFromString(std::string_view s) {
  if (s == "planar") return GeometryModel::kPlanar;
  if (s == "conformal") return GeometryModel::kConformal;
  return std::nullopt;
}

}  // namespace railwear
