#include "core/contact/contact_case.h"

#include <chrono>

#include "core/contact/contact_forces.h"
#include "core/contact/placement_stage.h"

namespace railwear {

ModelKind MatchingModelKind(GeometryModel geometry, KernelModel kernel) {
  for (const ModelKind k : {ModelKind::kHalfspace, ModelKind::kConformal}) {
    const ModelOptions o = MakeModelOptions(k);
    if (o.geometry == geometry && o.kernel == kernel) return k;
  }
  return ModelKind::kCustom;
}

ContactCaseResult SolveContactCase(const ContactCase& c, PlacementCache* cache) {
  ContactCaseResult out;
  if (c.wheelset) {
    WheelsetProblem problem = *c.wheelset;
    problem.wheel_rail = c.problem;
    out.wheelset = SolveWheelset(problem, cache);
    return out;
  }
  if (cache) {
    // SolveContact(problem)'s own order: the checks, then the placement, timed.
    internal::CheckContactProblem(c.problem);
    const auto t0 = std::chrono::steady_clock::now();
    const WheelRailGeometry& geom =
        cache->Get(PlacementCache::kRight, c.problem.wheel_profile, c.problem.rail_profile,
                   internal::PoseOf(c.problem));
    const double placement_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.wheel = SolveContact(c.problem, geom, placement_s);
  } else {
    out.wheel = SolveContact(c.problem);
  }
  // Normal contact has no friction of its own; a friction the case gives still sets Nadal's
  // limit for the flange-climb check.
  if (!out.wheel.climb.friction && c.friction) {
    out.wheel.climb = CheckFlangeClimb(out.wheel, c.friction);
  }
  return out;
}

}  // namespace railwear
