#include "core/contact/contact_case.h"

#include <chrono>

#include "core/contact/contact_forces.h"
#include "core/contact/hertz_tread.h"
#include "core/contact/normal_part_memo.h"
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
  return SolveContactCase(c, cache, nullptr);
}

ContactCaseResult SolveContactCase(const ContactCase& c, PlacementCache* cache,
                                   std::optional<HertzTreadPoint>* tread_point,
                                   ContactWarmStart* warm, ContactWarmStart* left_warm) {
  ContactCaseResult out;
  if (tread_point) tread_point->reset();
  if (c.wheelset) {
    WheelsetProblem problem = *c.wheelset;
    problem.wheel_rail = c.problem;
    out.wheelset = SolveWheelset(problem, cache, warm, left_warm);
    return out;
  }
  auto solve_full = [&](const ContactProblem& problem) {
    if (!cache && !warm) return SolveContact(problem);
    // SolveContact(problem)'s own order: the checks, then the placement, timed.
    internal::CheckContactProblem(problem);
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<WheelRailGeometry> own;
    const WheelRailGeometry& geom =
        cache ? cache->Get(PlacementCache::kRight, problem.wheel_profile, problem.rail_profile,
                           internal::PoseOf(problem))
              : own.emplace(internal::PlaceWheel(problem));
    const double placement_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return internal::SolveContact(problem, geom, placement_s, nullptr, warm);
  };
  // kind = hertz with rolling contact: the fast tread path, or the full path's fallback
  // (hertz_tread.h).
  out.wheel = IsHertzRolling(c.problem) ? SolveHertzRolling(c.problem, solve_full, tread_point)
                                        : solve_full(c.problem);
  // Normal contact has no friction of its own; a friction the case gives still sets Nadal's
  // limit for the flange-climb check.
  if (!out.wheel.climb.friction && c.friction) {
    out.wheel.climb = CheckFlangeClimb(out.wheel, c.friction);
  }
  return out;
}

}  // namespace railwear
