// Names of GeometryModel, from its table kGeometryModelNames (geometry_model.h).
#include "core/geometry/geometry_model.h"

namespace railwear {

std::string_view ToString(GeometryModel v) { return EnumToString(kGeometryModelNames, v); }

std::optional<GeometryModel> GeometryModelFromString(std::string_view s) {
  return EnumFromString(kGeometryModelNames, s);
}

}  // namespace railwear
