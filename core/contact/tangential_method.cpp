// The tangential methods' table: each TangentialMethod's name and solver, in enum order.
#include "core/contact/tangential_method.h"

#include <array>

#include "core/contact/fastsim.h"
#include "core/contact/tangential_exact.h"
#include "core/numerics/check.h"

namespace railwear {

namespace {

using TangentialSolver = TangentialSolution (*)(const PatchGrid&, const Eigen::VectorXd&,
                                                const RollingInput&, const Material&,
                                                const Material&);

TangentialSolution SolveByFastsim(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                  const RollingInput& input, const Material& wheel,
                                  const Material& rail) {
  const CombinedElastic elastic = CombineElastic(wheel, rail);
  FastsimOptions fo;
  fo.shear_modulus_Pa = elastic.shear_modulus_Pa;
  fo.poisson_ratio = elastic.poisson_ratio;
  return SolveFastsim(grid, pressure_Pa, input, fo);
}

TangentialSolution SolveByExact(const PatchGrid& grid, const Eigen::VectorXd& pressure_Pa,
                                const RollingInput& input, const Material& wheel,
                                const Material& rail) {
  return SolveTangentialExact(grid, pressure_Pa, input, wheel, rail, ExactTangentialOptions{});
}

// The solver of each method (keyed by the method, like kTangentialMethodNames).
struct TangentialEntry {
  TangentialMethod method;
  TangentialSolver solve;
};
constexpr std::array<TangentialEntry, 2> kTangentialSolvers = {{
    {TangentialMethod::kFastsim, &SolveByFastsim},
    {TangentialMethod::kExact, &SolveByExact},
}};

}  // namespace

std::string_view ToString(TangentialMethod v) { return EnumToString(kTangentialMethodNames, v); }

std::optional<TangentialMethod> TangentialMethodFromString(std::string_view s) {
  return EnumFromString(kTangentialMethodNames, s);
}

TangentialSolution SolveTangential(TangentialMethod method, const PatchGrid& grid,
                                   const Eigen::VectorXd& pressure_Pa, const RollingInput& input,
                                   const Material& wheel, const Material& rail) {
  for (const auto& e : kTangentialSolvers) {
    if (e.method == method) return e.solve(grid, pressure_Pa, input, wheel, rail);
  }
  RAILWEAR_CHECK(false && "a TangentialMethod without a solver");
  return {};
}

}  // namespace railwear
