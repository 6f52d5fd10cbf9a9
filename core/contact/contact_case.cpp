#include "core/contact/contact_case.h"

#include "core/contact/contact_forces.h"

namespace railwear {

ModelKind MatchingModelKind(GeometryModel geometry, KernelModel kernel) {
  for (const ModelKind k : {ModelKind::kHalfspace, ModelKind::kConformal}) {
    const ModelOptions o = MakeModelOptions(k);
    if (o.geometry == geometry && o.kernel == kernel) return k;
  }
  return ModelKind::kCustom;
}

ContactCaseResult SolveContactCase(const ContactCase& c) {
  ContactCaseResult out;
  if (c.wheelset) {
    WheelsetProblem problem = *c.wheelset;
    problem.wheel_rail = c.problem;
    out.wheelset = SolveWheelset(problem);
    return out;
  }
  out.wheel = SolveContact(c.problem);
  // Normal contact has no friction of its own; a friction the case gives still sets Nadal's
  // limit for the flange-climb check.
  if (!out.wheel.climb.friction && c.friction) {
    out.wheel.climb = CheckFlangeClimb(out.wheel, c.friction);
  }
  return out;
}

}  // namespace railwear
