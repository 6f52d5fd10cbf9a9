// TangentialMethod: which tangential solver a rolling contact uses, and the one seam that
// dispatches to it. A new method is one enum value, one name in kTangentialMethodNames and one
// entry in the solver table of tangential_method.cpp; the rolling stage (rolling_stage.h) only
// calls SolveTangential.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "core/contact/contact_types.h"
#include "core/contact/tangential_types.h"
#include "core/geometry/patch_grid.h"
#include "core/numerics/enum_names.h"

namespace railwear {

// Which tangential solver a rolling contact uses.
enum class TangentialMethod {
  kFastsim,  // Kalker's simplified theory, strip by strip (core/contact/fastsim.h)
  kExact,    // steady rolling with half-space tangential influence (tangential_exact.h)
};
inline constexpr std::array<EnumName<TangentialMethod>, 2> kTangentialMethodNames = {{
    {TangentialMethod::kFastsim, "fastsim"},
    {TangentialMethod::kExact, "exact"},
}};
std::string_view ToString(TangentialMethod v);
std::optional<TangentialMethod> TangentialMethodFromString(std::string_view s);

// The tangential solution of one patch by `method`: grid and pressure_Pa (per cell, shape
// [grid.cells()]) of the normal solution, the rigid slip `input` (kinematics.h), and the two
// bodies' materials (the solvers' elastic constants).
TangentialSolution SolveTangential(TangentialMethod method, const PatchGrid& grid,
                                   const Eigen::VectorXd& pressure_Pa, const RollingInput& input,
                                   const Material& wheel, const Material& rail);

}  // namespace railwear
