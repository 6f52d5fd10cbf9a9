// The C API (include/railwear/railwear.h) over the contact engine: each call checks its
// arguments, turns the handle's set-up and state into the core's ContactCase and solves it with
// SolveContactCase, the entry point `railwear contact` uses too (core/contact/contact_case.h).
// Every entry point runs its body inside Guard, so no exception crosses the C boundary.
#include "railwear/railwear.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/contact/contact_case.h"
#include "core/contact/contact_forces.h"
#include "core/contact/contact_warm_start.h"
#include "core/contact/hertz_tread.h"
#include "core/contact/influence_constant_sets.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_exact.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "wear/pass_depth.h"

using railwear::AccuracyPreset;
using railwear::ContactCase;
using railwear::ContactCaseResult;
using railwear::ContactResult;
using railwear::GeometryModel;
using railwear::KernelModel;
using railwear::ModelKind;
using railwear::ModelOptions;
using railwear::PatchResult;
using railwear::Profile;
using railwear::SolverStatus;
using railwear::TangentialMethod;

namespace {

// A failed check of a call's arguments: the status and the message for rw_last_error.
struct ApiError {
  rw_status status;
  std::string message;
};

[[noreturn]] void Fail(rw_status status, std::string message) {
  throw ApiError{status, std::move(message)};
}

// The limits of the scene reader (app/scene.cpp), so both front ends accept the same.
constexpr double kMaxRoll_rad = 0.5;
constexpr double kMaxYaw_rad = 0.1;
constexpr double kMaxFriction = 2.0;
constexpr double kMinCell_m = 0.01e-3, kMaxCell_m = 20e-3;
// More profile points than any measured profile has (MiniProf: some 1000); refusing more keeps a
// wrong n (e.g. a byte count) from reading far past the caller's array.
constexpr size_t kMaxProfilePoints = 1000000;
constexpr uint32_t kKnownEffects = RW_EFFECT_TANGENTIAL | RW_EFFECT_DAMAGE | RW_EFFECT_COUPLING;
constexpr uint32_t kKnownStateFlags = RW_STATE_CREEPAGE;

}  // namespace

// The handle: the set-up, the state of the step and the last results. No global state.
struct rw_problem {
  rw_problem_kind kind = RW_PROBLEM_WHEEL;
  std::string last_error;

  std::optional<Profile> wheel_profile, rail_profile, left_rail_profile;  // rails before cant
  std::optional<Profile> canted_rail, canted_left_rail;                   // cant applied
  railwear::Material wheel_material, rail_material;
  ModelOptions model = railwear::MakeModelOptions(ModelKind::kConformal);
  TangentialMethod tangential = TangentialMethod::kFastsim;
  railwear::NormalSolverOptions normal_solver;  // rw_model's stopping rule (since 1.5)
  // rw_model's exact tangential stop (since 1.5), relative to mu p_max.
  double tangential_tolerance = railwear::kDefaultExactTangentialTolerance;
  uint32_t effects = 0;
  std::optional<double> friction;
  railwear::PressureLimit pressure_limit;
  rw_geometry geometry{};
  std::optional<rw_state> state;

  // Wear for co-simulation (rw_accumulate): the law, the bins and the accumulated depth per bin
  // of each rail (0 single or right, 1 left), on the canted rails' arc length.
  railwear::WearLaw wear_law;
  double wear_bin_m = 1e-4;
  railwear::WearGrid wear_grid[2];
  std::vector<double> depth_m[2];

  // The placed geometries of the last calculate, reused by the next one at the same pose on the
  // same profiles (core/contact/placement_cache.h): exact, so results do not depend on it.
  railwear::PlacementCache placement_cache;
  // rw_set_warm_start: the single wheel's (a wheelset's right wheel's) last measured patch and
  // balance, the next calculate's start (core/contact/contact_warm_start.h), and a wheelset's
  // left wheel's; off by default.
  bool warm_start_on = false;
  railwear::ContactWarmStart warm_start, warm_start_left;
  // The fast tread path's wheel-frame contact point of the last calculate (RW_MODEL_HERTZ with
  // rolling contact on a single wheel, core/contact/hertz_tread.h); empty for any other solve (a
  // wheelset's are in its result, WheelsetResult::right_tread_point and left_tread_point).
  std::optional<railwear::HertzTreadPoint> tread_point;

  std::optional<ContactCaseResult> result;
  struct PatchRef {
    int wheel;
    const ContactResult* contact;
    const PatchResult* patch;
  };
  std::vector<PatchRef> patches;  // right (or single) wheel's patches first, then the left's
};

namespace {

// Copies a message without letting an allocation failure escape.
void Assign(std::string* to, const char* text) noexcept {
  try {
    *to = text;
  } catch (...) {  // out of memory: the status stands without its text
  }
}

void Invalidate(rw_problem* p) noexcept;

// After an internal failure (RW_ERROR_INTERNAL: a failed RAILWEAR_CHECK, core/numerics/check.h,
// or another unexpected exception) the handle drops what the failed call may have left half
// made: the results and the placed geometries it reuses (an exact cache, placement_cache.h, so
// dropping it changes no result). The set-up, the state and the depth field stay (each call
// stores them only when it has computed everything), so the handle stays usable: the next
// rw_calculate solves afresh.
void DropDerived(rw_problem* p) noexcept {
  Invalidate(p);
  p->placement_cache = railwear::PlacementCache();
}

// Runs `body` for an entry point: the status it returns, or the status of what it threw, with the
// message kept on the handle. Nothing escapes.
template <class Body>
rw_status Guard(rw_problem* p, Body&& body) noexcept {
  rw_status status = RW_ERROR_INTERNAL;
  std::string message;
  try {
    status = body();
  } catch (const ApiError& e) {
    status = e.status;
    Assign(&message, e.message.c_str());
  } catch (const railwear::InputError& e) {
    status = RW_ERROR_INPUT;
    Assign(&message, e.what());
  } catch (const std::bad_alloc&) {
    status = RW_ERROR_OUT_OF_MEMORY;
    Assign(&message, "out of memory");
  } catch (const railwear::InternalError& e) {
    // "internal check failed: EXPR (FILE:LINE)": the check, its file and line.
    status = RW_ERROR_INTERNAL;
    Assign(&message, e.what());
  } catch (const std::exception& e) {
    status = RW_ERROR_INTERNAL;
    Assign(&message, "internal error: ");
    try {
      message += e.what();
    } catch (...) {
    }
  } catch (...) {
    status = RW_ERROR_INTERNAL;
    Assign(&message, "internal error: an unknown exception");
  }
  if (p != nullptr) {
    if (status == RW_ERROR_INTERNAL) DropDerived(p);
    if (status == RW_OK) {
      p->last_error.clear();
    } else {
      p->last_error.swap(message);
    }
  }
  return status;
}

void RequireHandle(const rw_problem* p) {
  if (p == nullptr) Fail(RW_ERROR_NULL_ARGUMENT, "problem: a NULL handle");
}

void RequireNonNull(const void* ptr, const char* what) {
  if (ptr == nullptr) Fail(RW_ERROR_NULL_ARGUMENT, fmt::format("{}: a NULL pointer", what));
}

// The struct's size must be the size of this library's version of it.
template <class T>
void RequireSize(const T* s, const char* what) {
  RequireNonNull(s, what);
  if (s->struct_size != sizeof(T)) {
    Fail(RW_ERROR_STRUCT_SIZE,
         fmt::format("{}: struct_size = {}: expected {} (sizeof({}) of API version {}.{}; set it "
                     "with rw_init_*)",
                     what, s->struct_size, sizeof(T), what, RW_API_VERSION_MAJOR,
                     RW_API_VERSION_MINOR));
  }
}

void RequireFinite(double v, const char* what) {
  if (!std::isfinite(v)) {
    Fail(RW_ERROR_INVALID_VALUE, fmt::format("{} = {}: expected a finite number", what, v));
  }
}

void RequirePositive(double v, const char* what) {
  if (!(std::isfinite(v) && v > 0.0)) {
    Fail(RW_ERROR_INVALID_VALUE, fmt::format("{} = {}: expected a finite number > 0", what, v));
  }
}

void RequireInRange(double v, double lo, double hi, const char* what) {
  if (!(std::isfinite(v) && v >= lo && v <= hi)) {
    Fail(RW_ERROR_INVALID_VALUE,
         fmt::format("{} = {}: expected a number in [{}, {}]", what, v, lo, hi));
  }
}

// NaN (not given) or a finite number > 0.
std::optional<double> OptionalPositive(double v, const char* what) {
  if (std::isnan(v)) return std::nullopt;
  RequirePositive(v, what);
  return v;
}

std::optional<double> OptionalFinite(double v, const char* what) {
  if (std::isnan(v)) return std::nullopt;
  RequireFinite(v, what);
  return v;
}

void RequireEnum(int v, int lo, int hi, const char* what) {
  if (v < lo || v > hi) {
    Fail(RW_ERROR_UNKNOWN_FLAG, fmt::format("{} = {}: expected one of {}..{}", what, v, lo, hi));
  }
}

void RequireResult(const rw_problem* p) {
  if (!p->result) {
    Fail(RW_ERROR_CALL_ORDER,
         "no results: call rw_calculate first (any set-up or state call "
         "clears the results of the previous one)");
  }
}

const rw_problem::PatchRef& PatchAt(const rw_problem* p, int index) {
  RequireResult(p);
  if (index < 0 || index >= static_cast<int>(p->patches.size())) {
    Fail(RW_ERROR_INDEX, fmt::format("patch index {}: expected 0..{} (rw_get_patch_count)", index,
                                     static_cast<int>(p->patches.size()) - 1));
  }
  return p->patches[static_cast<size_t>(index)];
}

// Every set-up or state change makes the previous results stale.
void Invalidate(rw_problem* p) noexcept {
  p->result.reset();
  p->patches.clear();
  p->tread_point.reset();
}

// A set-up change (anything but the state) also ends the warm start's sequence: the next
// calculate is cold (core/contact/contact_warm_start.h's contract).
void SetUpChanged(rw_problem* p) {
  Invalidate(p);
  p->warm_start.Clear();
  p->warm_start_left.Clear();
}

// The canted rail each wheel of the handle runs on: rail 0 (single or right), 1 (left: its own
// profile when set, else the right one's); null before the rail is set.
const Profile* CantedRail(const rw_problem* p, int rail) {
  if (rail == 1 && p->canted_left_rail) return &*p->canted_left_rail;
  return p->canted_rail ? &*p->canted_rail : nullptr;
}

// The depth fields start again at zero, on bins of the current rails.
void ResetDepth(rw_problem* p) {
  for (int rail = 0; rail < 2; ++rail) {
    const Profile* profile = CantedRail(p, rail);
    p->wear_grid[rail] =
        profile ? railwear::WearGrid::ForProfile(*profile, p->wear_bin_m) : railwear::WearGrid{};
    p->depth_m[rail].assign(static_cast<size_t>(p->wear_grid[rail].n), 0.0);
  }
}

// Sets the rails (before cant; either may be empty) and the cant: the canted rails are computed
// before anything of the handle changes, so a failure there (ApplyCant throws) leaves the handle
// as it was, never a rail without its canted copy (which rw_calculate reads).
void SetRails(rw_problem* p, std::optional<Profile> rail, std::optional<Profile> left,
              double cant) {
  auto canted = [cant](const std::optional<Profile>& from) -> std::optional<Profile> {
    if (!from) return std::nullopt;
    return cant != 0.0 ? railwear::ApplyCant(*from, cant) : *from;
  };
  std::optional<Profile> canted_rail = canted(rail), canted_left = canted(left);
  SetUpChanged(p);
  p->rail_profile = std::move(rail);
  p->left_rail_profile = std::move(left);
  p->canted_rail = std::move(canted_rail);
  p->canted_left_rail = std::move(canted_left);
  p->geometry.rail_cant = cant;
  ResetDepth(p);
}

void SetProfile(rw_problem* p, rw_body body, Profile profile) {
  RequireEnum(body, RW_BODY_WHEEL, RW_BODY_LEFT_RAIL, "body");
  if (body == RW_BODY_LEFT_RAIL && p->kind != RW_PROBLEM_WHEELSET) {
    Fail(RW_ERROR_WRONG_KIND,
         "body = RW_BODY_LEFT_RAIL: a left rail needs a wheelset handle "
         "(RW_PROBLEM_WHEELSET)");
  }
  if (body == RW_BODY_WHEEL) {
    SetUpChanged(p);
    p->wheel_profile = std::move(profile);
    return;
  }
  if (body == RW_BODY_RAIL) {
    SetRails(p, std::move(profile), p->left_rail_profile, p->geometry.rail_cant);
  } else {
    SetRails(p, p->rail_profile, std::move(profile), p->geometry.rail_cant);
  }
}

railwear::Material ToMaterial(const rw_material* m, const char* what) {
  RequireSize(m, what);
  const std::string name(what);
  RequirePositive(m->youngs_modulus_Pa, (name + ".youngs_modulus_Pa").c_str());
  if (!(std::isfinite(m->poisson_ratio) && m->poisson_ratio >= 0.0 && m->poisson_ratio < 0.5)) {
    Fail(RW_ERROR_INVALID_VALUE, fmt::format("{}.poisson_ratio = {}: expected a number in [0, 0.5)",
                                             what, m->poisson_ratio));
  }
  railwear::Material out;
  out.youngs_modulus_Pa = m->youngs_modulus_Pa;
  out.poisson_ratio = m->poisson_ratio;
  if (OptionalPositive(m->hardness_Pa, (name + ".hardness_Pa").c_str())) {
    out.hardness_Pa = m->hardness_Pa;
  }
  if (OptionalPositive(m->shear_yield_Pa, (name + ".shear_yield_Pa").c_str())) {
    out.shear_yield_Pa = m->shear_yield_Pa;
  }
  return out;
}

// The handle's set-up and state as the core's contact case.
ContactCase MakeCase(const rw_problem* p) {
  if (!p->wheel_profile) {
    Fail(RW_ERROR_CALL_ORDER,
         "no wheel profile: call rw_set_profile_file or "
         "rw_set_profile_points with RW_BODY_WHEEL first");
  }
  if (!p->rail_profile) {
    Fail(RW_ERROR_CALL_ORDER,
         "no rail profile: call rw_set_profile_file or "
         "rw_set_profile_points with RW_BODY_RAIL first");
  }
  if (!p->state) Fail(RW_ERROR_CALL_ORDER, "no state: call rw_set_state first");
  const bool rolling = (p->effects & kKnownEffects) != 0;
  if (rolling && !p->friction) {
    Fail(RW_ERROR_CALL_ORDER,
         "rolling contact (RW_EFFECT_TANGENTIAL, DAMAGE or COUPLING) "
         "needs a friction coefficient: call rw_set_friction first");
  }
  if (p->pressure_limit.kind == railwear::PressureLimitKind::kHardness &&
      !(p->wheel_material.hardness_Pa > 0.0) && !(p->rail_material.hardness_Pa > 0.0)) {
    Fail(RW_ERROR_CALL_ORDER,
         "RW_PRESSURE_LIMIT_HARDNESS needs a hardness_Pa: set the rail's (or the wheel's) with "
         "rw_set_materials first");
  }
  if ((p->effects & RW_EFFECT_DAMAGE) && !(p->rail_material.shear_yield_Pa > 0.0)) {
    Fail(RW_ERROR_CALL_ORDER,
         "RW_EFFECT_DAMAGE needs the rail's shear_yield_Pa: set it with "
         "rw_set_materials first");
  }
  const rw_state& s = *p->state;
  ContactCase c;
  railwear::ContactProblem& problem = c.problem;
  problem.wheel_material = p->wheel_material;
  problem.rail_material = p->rail_material;
  problem.model = p->model;
  problem.tangential = p->tangential;
  problem.solver = p->normal_solver;
  problem.tangential_tolerance = p->tangential_tolerance;
  problem.damage = (p->effects & RW_EFFECT_DAMAGE) != 0;
  problem.pressure_limit = p->pressure_limit;
  // The wheel and the (canted) rail: lent by rw_calculate (LentProfiles), not copied.
  problem.placement.rolling_radius_m = p->geometry.rolling_radius_m;
  problem.placement.yaw_rad = s.yaw_rad;
  if (!std::isnan(s.vertical_force_N)) problem.load.vertical_force_N = s.vertical_force_N;
  if (!std::isnan(s.approach_m)) problem.load.approach_m = s.approach_m;
  if (rolling) {
    railwear::RollingOptions r;
    r.motion.speed_m_s = s.speed_m_s;
    if (!std::isnan(s.pitch_velocity_rad_s)) r.motion.pitch_velocity_rad_s = s.pitch_velocity_rad_s;
    r.motion.lateral_velocity_m_s = s.lateral_velocity_m_s;
    r.motion.yaw_velocity_rad_s = s.yaw_velocity_rad_s;
    if (s.flags & RW_STATE_CREEPAGE) {
      r.creepage = railwear::Creepage{s.creepage_xi, s.creepage_eta, s.creepage_spin_per_m};
    }
    r.friction = *p->friction;
    if (!std::isnan(s.longitudinal_force_N)) r.longitudinal_force_N = s.longitudinal_force_N;
    r.coupling = (p->effects & RW_EFFECT_COUPLING) != 0;
    problem.rolling = r;
  }
  c.friction = p->friction;
  if (p->kind == RW_PROBLEM_WHEELSET) {
    railwear::WheelsetProblem& w = c.wheelset.emplace();
    w.track.gauge_m = p->geometry.gauge_m;
    w.track.gauge_height_m = p->geometry.gauge_height_m;
    w.wheelset.flange_back_distance_m = p->geometry.flange_back_distance_m;
    w.wheelset.flange_back_position_m = p->geometry.flange_back_position_m;
    w.wheelset.lateral_displacement_m = s.lateral_m;
    w.wheelset.yaw_rad = s.yaw_rad;
    w.wheelset.roll_rad = s.roll_rad;
    w.wheelset.rolling_radius_m = p->geometry.rolling_radius_m;
    if (p->canted_left_rail) w.left_rail_profile = *p->canted_left_rail;
    if (!std::isnan(s.left_vertical_force_N)) w.left_vertical_force_N = s.left_vertical_force_N;
    w.curvature_per_m = s.curvature_per_m;
  } else {
    problem.placement.lateral_shift_m = s.lateral_m;
    problem.placement.roll_rad = s.roll_rad;
  }
  return c;
}

// The handle's wheel and canted rail profiles moved into a case for one solve and moved back when
// it ends, also by an exception (the results keep no reference to them): a copy of S1002 and
// UIC60 into every call's problem cost 8 us of CPU, a tenth of a fast tread call
// (docs/library.md, "The fast tread path").
class LentProfiles {
 public:
  LentProfiles(rw_problem* p, ContactCase* c) : p_(p), c_(c) {
    c->problem.wheel_profile = std::move(*p->wheel_profile);
    c->problem.rail_profile = std::move(*p->canted_rail);
  }
  ~LentProfiles() {
    *p_->wheel_profile = std::move(c_->problem.wheel_profile);
    *p_->canted_rail = std::move(c_->problem.rail_profile);
  }
  LentProfiles(const LentProfiles&) = delete;
  LentProfiles& operator=(const LentProfiles&) = delete;

 private:
  rw_problem* p_;
  ContactCase* c_;
};

rw_status StatusOf(SolverStatus s) {
  switch (s) {
    case SolverStatus::kConverged:
      return RW_OK;
    case SolverStatus::kNoContact:
      return RW_ERROR_NO_CONTACT;
    case SolverStatus::kNotConverged:
      break;
  }
  return RW_ERROR_NOT_CONVERGED;
}

// The worse of the wheels' statuses: not converged before no contact before converged.
rw_status WorstStatus(const rw_problem* p, std::string* message) {
  rw_status worst = RW_OK;
  const ContactCaseResult& r = *p->result;
  std::vector<std::pair<const ContactResult*, const char*>> wheels;
  if (r.wheelset) {
    wheels = {{&r.wheelset->right, "right wheel: "}, {&r.wheelset->left, "left wheel: "}};
  } else {
    wheels = {{&r.wheel, ""}};
  }
  for (const auto& [c, name] : wheels) {
    const rw_status s = StatusOf(c->status);
    if (s == RW_OK) continue;
    if (worst == RW_OK || s == RW_ERROR_NOT_CONVERGED) {
      worst = s;
      *message = fmt::format("{}contact solve ended with status '{}': {}", name,
                             railwear::ToString(c->status), c->message);
    }
  }
  return worst;
}

// The caller's rw_model of this version or of 1.0-1.4 (RW_MODEL_SIZE_1_4, without the stopping
// rule) as this version's, the fields it lacks at their defaults (rw_init_model's).
rw_model ModelOfAnySize(const rw_model* model) {
  RequireNonNull(model, "rw_model");
  if (model->struct_size != RW_MODEL_SIZE_1_4) RequireSize(model, "rw_model");
  rw_model m{};
  m.normal_criterion = RW_NORMAL_PRESSURE_UPDATE;
  m.normal_tolerance = 0.0;
  m.tangential_tolerance = 0.0;
  std::memcpy(&m, model, model->struct_size);
  return m;
}

double OrNaN(const std::optional<double>& v) {
  return v ? *v : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

extern "C" {

int rw_api_version(void) { return RW_API_VERSION; }

const char* rw_status_name(rw_status status) {
  switch (status) {
    case RW_OK:
      return "RW_OK";
    case RW_ERROR_NULL_ARGUMENT:
      return "RW_ERROR_NULL_ARGUMENT";
    case RW_ERROR_STRUCT_SIZE:
      return "RW_ERROR_STRUCT_SIZE";
    case RW_ERROR_INVALID_VALUE:
      return "RW_ERROR_INVALID_VALUE";
    case RW_ERROR_UNKNOWN_FLAG:
      return "RW_ERROR_UNKNOWN_FLAG";
    case RW_ERROR_CALL_ORDER:
      return "RW_ERROR_CALL_ORDER";
    case RW_ERROR_BUFFER_TOO_SMALL:
      return "RW_ERROR_BUFFER_TOO_SMALL";
    case RW_ERROR_INDEX:
      return "RW_ERROR_INDEX";
    case RW_ERROR_INPUT:
      return "RW_ERROR_INPUT";
    case RW_ERROR_NOT_CONVERGED:
      return "RW_ERROR_NOT_CONVERGED";
    case RW_ERROR_NO_CONTACT:
      return "RW_ERROR_NO_CONTACT";
    case RW_ERROR_INTERNAL:
      return "RW_ERROR_INTERNAL";
    case RW_ERROR_OUT_OF_MEMORY:
      return "RW_ERROR_OUT_OF_MEMORY";
    case RW_ERROR_WRONG_KIND:
      return "RW_ERROR_WRONG_KIND";
    default:
      return "unknown status";
  }
}

rw_status rw_create(rw_problem_kind kind, rw_problem** out) {
  return Guard(nullptr, [&] {
    RequireNonNull(out, "out");
    *out = nullptr;
    RequireEnum(kind, RW_PROBLEM_WHEEL, RW_PROBLEM_WHEELSET, "kind");
    auto* p = new rw_problem;
    p->kind = kind;
    // Steel for both bodies, the scene reader's default (app/scene.cpp DefaultSteel).
    p->wheel_material.youngs_modulus_Pa = p->rail_material.youngs_modulus_Pa = 210e9;
    p->wheel_material.poisson_ratio = p->rail_material.poisson_ratio = 0.28;
    // The scenes' default influence constants, the FEM-calibrated sets (app/scene.h).
    p->model.constants =
        railwear::NamedInfluenceConstants(railwear::InfluenceConstantsName::kFem);
    p->geometry.struct_size = sizeof(rw_geometry);
    rw_init_geometry(&p->geometry);
    *out = p;
    return RW_OK;
  });
}

void rw_destroy(rw_problem* problem) { delete problem; }

const char* rw_last_error(const rw_problem* problem) {
  if (problem == nullptr) return "problem: a NULL handle";
  return problem->last_error.c_str();
}

rw_status rw_set_profile_file(rw_problem* problem, rw_body body, const char* path) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireNonNull(path, "path");
    RequireEnum(body, RW_BODY_WHEEL, RW_BODY_LEFT_RAIL, "body");
    const auto role =
        body == RW_BODY_WHEEL ? railwear::BodyRole::kWheel : railwear::BodyRole::kRail;
    SetProfile(problem, body, railwear::LoadProfileSpec(path, role, ""));
    return RW_OK;
  });
}

rw_status rw_set_profile_points(rw_problem* problem, rw_body body, const double* yz_m,
                                size_t n_points) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireNonNull(yz_m, "yz_m");
    if (n_points < 4 || n_points > kMaxProfilePoints) {
      Fail(RW_ERROR_INVALID_VALUE,
           fmt::format("n_points = {}: expected 4..{} points", n_points, kMaxProfilePoints));
    }
    std::vector<Eigen::Vector2d> points(n_points);
    for (size_t i = 0; i < n_points; ++i) {
      points[i] = {yz_m[2 * i], yz_m[2 * i + 1]};
      if (!points[i].allFinite()) {
        Fail(RW_ERROR_INVALID_VALUE,
             fmt::format("yz_m: point {} = ({}, {}): expected finite coordinates [m]", i,
                         points[i].x(), points[i].y()));
      }
    }
    SetProfile(problem, body, Profile(std::move(points), "points"));
    return RW_OK;
  });
}

rw_status rw_init_material(rw_material* material) {
  return Guard(nullptr, [&] {
    RequireSize(material, "rw_material");
    material->youngs_modulus_Pa = 210e9;
    material->poisson_ratio = 0.28;
    material->hardness_Pa = std::numeric_limits<double>::quiet_NaN();
    material->shear_yield_Pa = std::numeric_limits<double>::quiet_NaN();
    return RW_OK;
  });
}

rw_status rw_set_materials(rw_problem* problem, const rw_material* wheel, const rw_material* rail) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    const railwear::Material w = ToMaterial(wheel, "wheel");
    const railwear::Material r = ToMaterial(rail, "rail");
    SetUpChanged(problem);
    problem->wheel_material = w;
    problem->rail_material = r;
    return RW_OK;
  });
}

rw_status rw_init_model(rw_model* model) {
  return Guard(nullptr, [&] {
    rw_model m = ModelOfAnySize(model);
    m.kind = RW_MODEL_CONFORMAL;
    m.geometry = RW_GEOMETRY_DEFAULT;
    m.kernel = RW_KERNEL_DEFAULT;
    m.accuracy = RW_ACCURACY_STANDARD;
    m.tangential = RW_TANGENTIAL_FASTSIM;
    m.effects = 0;
    m.cell_dx_m = 0.0;
    m.cell_ds_m = 0.0;
    m.normal_criterion = RW_NORMAL_PRESSURE_UPDATE;  // beyond a 1.4 caller's size: not copied back
    m.normal_tolerance = 0.0;
    m.tangential_tolerance = 0.0;
    std::memcpy(model, &m, model->struct_size);  // a 1.4 caller's struct up to its size
    return RW_OK;
  });
}

rw_status rw_set_model(rw_problem* problem, const rw_model* caller_model) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    const rw_model model_of_any_size = ModelOfAnySize(caller_model);
    const rw_model* model = &model_of_any_size;
    RequireEnum(model->kind, RW_MODEL_HERTZ, RW_MODEL_AUTO, "rw_model.kind");
    RequireEnum(model->geometry, RW_GEOMETRY_DEFAULT, RW_GEOMETRY_CONFORMAL, "rw_model.geometry");
    RequireEnum(model->kernel, RW_KERNEL_DEFAULT, RW_KERNEL_GOLUBENKO, "rw_model.kernel");
    RequireEnum(model->accuracy, RW_ACCURACY_DRAFT, RW_ACCURACY_FINE, "rw_model.accuracy");
    RequireEnum(model->tangential, RW_TANGENTIAL_FASTSIM, RW_TANGENTIAL_AUTO,
                "rw_model.tangential");
    if (model->effects & ~kKnownEffects) {
      Fail(RW_ERROR_UNKNOWN_FLAG,
           fmt::format("rw_model.effects = {:#x}: unknown bits {:#x} (known: RW_EFFECT_TANGENTIAL, "
                       "RW_EFFECT_DAMAGE, RW_EFFECT_COUPLING)",
                       model->effects, model->effects & ~kKnownEffects));
    }
    const bool explicit_cells = model->cell_dx_m != 0.0 || model->cell_ds_m != 0.0;
    if (explicit_cells) {
      RequireInRange(model->cell_dx_m, kMinCell_m, kMaxCell_m, "rw_model.cell_dx_m");
      RequireInRange(model->cell_ds_m, kMinCell_m, kMaxCell_m, "rw_model.cell_ds_m");
    }
    ModelOptions m;
    const bool geometry_given = model->geometry != RW_GEOMETRY_DEFAULT;
    const bool kernel_given = model->kernel != RW_KERNEL_DEFAULT;
    switch (model->kind) {
      case RW_MODEL_CUSTOM:
        if (!geometry_given || !kernel_given) {
          Fail(RW_ERROR_INVALID_VALUE,
               "rw_model.kind = RW_MODEL_CUSTOM: expected both geometry "
               "and kernel given (not RW_*_DEFAULT)");
        }
        m.geometry = static_cast<GeometryModel>(model->geometry);
        m.kernel = static_cast<KernelModel>(model->kernel);
        m.kind = railwear::MatchingModelKind(m.geometry, m.kernel);
        break;
      case RW_MODEL_AUTO:
        if (geometry_given) {
          Fail(RW_ERROR_INVALID_VALUE,
               "rw_model.geometry: expected RW_GEOMETRY_DEFAULT with "
               "RW_MODEL_AUTO (it picks the geometry per patch)");
        }
        m = railwear::MakeModelOptions(ModelKind::kAuto);
        if (kernel_given) m.kernel = static_cast<KernelModel>(model->kernel);
        break;
      default:
        if (geometry_given || kernel_given) {
          Fail(RW_ERROR_INVALID_VALUE,
               "rw_model.geometry, kernel: expected RW_*_DEFAULT with "
               "RW_MODEL_HERTZ, HALFSPACE or CONFORMAL (use RW_MODEL_CUSTOM "
               "for another geometry or kernel)");
        }
        m = railwear::MakeModelOptions(model->kind == RW_MODEL_HERTZ       ? ModelKind::kHertz
                                       : model->kind == RW_MODEL_HALFSPACE ? ModelKind::kHalfspace
                                                                           : ModelKind::kConformal);
    }
    // Since 1.3 the Hertz model rolls on a single wheel, since 1.4 on a wheelset too: the fast
    // tread path (core/contact/hertz_tread.h); coupling needs a grid model.
    if (m.kind == ModelKind::kHertz && (model->effects & RW_EFFECT_COUPLING)) {
      Fail(RW_ERROR_INVALID_VALUE,
           "rw_model.kind = RW_MODEL_HERTZ with RW_EFFECT_COUPLING: the "
           "coupling effect needs a patch grid (use HALFSPACE, CONFORMAL or AUTO)");
    }
    m.accuracy = static_cast<AccuracyPreset>(model->accuracy);
    if (explicit_cells) {
      m.cell_dx_m = model->cell_dx_m;
      m.cell_ds_m = model->cell_ds_m;
    }
    // The stopping rule as the scene reader maps normal_criterion and normal_tolerance
    // (app/scene.cpp ReadNormalSolver): the criterion's own options, then the tolerance if given.
    RequireEnum(model->normal_criterion, RW_NORMAL_PRESSURE_UPDATE, RW_NORMAL_GAP_RESIDUAL,
                "rw_model.normal_criterion");
    railwear::NormalSolverOptions solver = model->normal_criterion == RW_NORMAL_GAP_RESIDUAL
                                               ? railwear::StrictNormalSolverOptions()
                                               : railwear::NormalSolverOptions{};
    if (model->normal_tolerance != 0.0) {
      RequireInRange(model->normal_tolerance, railwear::kMinNormalTolerance,
                     railwear::kMaxNormalTolerance, "rw_model.normal_tolerance");
      solver.tolerance = model->normal_tolerance;
    }
    double tangential_tolerance = railwear::kDefaultExactTangentialTolerance;
    if (model->tangential_tolerance != 0.0) {
      RequireInRange(model->tangential_tolerance, railwear::kMinExactTangentialTolerance,
                     railwear::kMaxExactTangentialTolerance, "rw_model.tangential_tolerance");
      tangential_tolerance = model->tangential_tolerance;
    }
    SetUpChanged(problem);
    problem->normal_solver = solver;
    problem->tangential_tolerance = tangential_tolerance;
    m.constants = problem->model.constants;  // set apart, by rw_set_influence_constants
    problem->model = m;
    problem->tangential = static_cast<TangentialMethod>(model->tangential);
    problem->effects = model->effects;
    return RW_OK;
  });
}

rw_status rw_init_influence_constants(rw_influence_constants* c) {
  return Guard(nullptr, [&] {
    RequireSize(c, "rw_influence_constants");
    // The default, as the scene reader's: the FEM-calibrated convex and concave sets
    // (core/contact/influence_constant_sets.h); the one set is the seed's, for separate = 0.
    const railwear::InfluenceConstantSet seed;
    const railwear::SeparateInfluenceConstants fem =
        *railwear::NamedInfluenceConstants(railwear::InfluenceConstantsName::kFem).separate;
    c->c_f = seed.c_f;
    c->c_z = seed.c_z;
    c->c_s = seed.c_s;
    c->convex_c_f = fem.convex.c_f;
    c->convex_c_z = fem.convex.c_z;
    c->convex_c_s = fem.convex.c_s;
    c->concave_c_f = fem.concave.c_f;
    c->concave_c_z = fem.concave.c_z;
    c->concave_c_s = fem.concave.c_s;
    c->separate = 1;
    return RW_OK;
  });
}

rw_status rw_set_influence_constants(rw_problem* problem, const rw_influence_constants* c) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireSize(c, "rw_influence_constants");
    RequireEnum(c->separate, 0, 1, "rw_influence_constants.separate");
    railwear::InfluenceConstants k;
    auto read = [](double f, double z, double s, const char* set) {
      const std::string n(set);
      RequirePositive(f, (n + "c_f").c_str());
      RequirePositive(z, (n + "c_z").c_str());
      RequireInRange(s, -1.0, 1.0, (n + "c_s").c_str());
      return railwear::InfluenceConstantSet{f, z, s};
    };
    if (c->separate) {
      k.separate = railwear::SeparateInfluenceConstants{
          read(c->convex_c_f, c->convex_c_z, c->convex_c_s, "rw_influence_constants.convex_"),
          read(c->concave_c_f, c->concave_c_z, c->concave_c_s, "rw_influence_constants.concave_")};
    } else {
      const railwear::InfluenceConstantSet one =
          read(c->c_f, c->c_z, c->c_s, "rw_influence_constants.");
      k.c_f = one.c_f;
      k.c_z = one.c_z;
      k.c_s = one.c_s;
    }
    SetUpChanged(problem);
    problem->model.constants = k;
    return RW_OK;
  });
}

rw_status rw_set_friction(rw_problem* problem, double friction) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    if (!(std::isfinite(friction) && friction > 0.0 && friction <= kMaxFriction)) {
      Fail(RW_ERROR_INVALID_VALUE,
           fmt::format("friction = {}: expected a coefficient in (0, {}]", friction, kMaxFriction));
    }
    SetUpChanged(problem);
    problem->friction = friction;
    return RW_OK;
  });
}

rw_status rw_init_geometry(rw_geometry* g) {
  return Guard(nullptr, [&] {
    RequireSize(g, "rw_geometry");
    const railwear::TrackSpec track;
    const railwear::WheelsetSpec wheelset;
    g->rolling_radius_m = wheelset.rolling_radius_m;
    g->rail_cant = 0.0;
    g->gauge_m = track.gauge_m;
    g->gauge_height_m = track.gauge_height_m;
    g->flange_back_distance_m = wheelset.flange_back_distance_m;
    g->flange_back_position_m = wheelset.flange_back_position_m;
    return RW_OK;
  });
}

rw_status rw_set_geometry(rw_problem* problem, const rw_geometry* g) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireSize(g, "rw_geometry");
    RequirePositive(g->rolling_radius_m, "rw_geometry.rolling_radius_m");
    // Cant up to 1:5 (a rail is inclined 1:20 or 1:40): more is a typo such as 40 for 1:40.
    RequireInRange(g->rail_cant, -0.2, 0.2, "rw_geometry.rail_cant");
    RequirePositive(g->gauge_m, "rw_geometry.gauge_m");
    RequireInRange(g->gauge_height_m, 0.0, 0.05, "rw_geometry.gauge_height_m");
    RequirePositive(g->flange_back_distance_m, "rw_geometry.flange_back_distance_m");
    RequireFinite(g->flange_back_position_m, "rw_geometry.flange_back_position_m");
    // A new cant turns the rails first (SetRails: a refused cant leaves the handle as it was).
    if (g->rail_cant != problem->geometry.rail_cant) {
      SetRails(problem, problem->rail_profile, problem->left_rail_profile, g->rail_cant);
    }
    SetUpChanged(problem);
    problem->geometry = *g;
    return RW_OK;
  });
}

rw_status rw_set_pressure_limit(rw_problem* problem, rw_pressure_limit kind, double value_Pa) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireEnum(kind, RW_PRESSURE_LIMIT_NONE, RW_PRESSURE_LIMIT_VALUE, "kind");
    railwear::PressureLimit limit;
    if (kind == RW_PRESSURE_LIMIT_VALUE) {
      // The scene reader's range: 1 MPa (far below any steel's yield) to 1e6 MPa.
      RequireInRange(value_Pa, 1e6, 1e12, "value_Pa");
      limit.kind = railwear::PressureLimitKind::kValue;
      limit.value_Pa = value_Pa;
    } else {
      if (!std::isnan(value_Pa)) {
        Fail(RW_ERROR_INVALID_VALUE,
             fmt::format("value_Pa = {}: expected NaN with RW_PRESSURE_LIMIT_NONE or _HARDNESS "
                         "(a value goes with RW_PRESSURE_LIMIT_VALUE)",
                         value_Pa));
      }
      limit.kind = kind == RW_PRESSURE_LIMIT_HARDNESS ? railwear::PressureLimitKind::kHardness
                                                       : railwear::PressureLimitKind::kNone;
    }
    SetUpChanged(problem);
    problem->pressure_limit = limit;
    return RW_OK;
  });
}

rw_status rw_init_state(rw_state* s) {
  return Guard(nullptr, [&] {
    RequireSize(s, "rw_state");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const size_t size = s->struct_size;
    std::memset(static_cast<void*>(s), 0, sizeof(*s));
    s->struct_size = size;
    s->vertical_force_N = s->approach_m = s->left_vertical_force_N = nan;
    s->speed_m_s = 1.0;
    s->pitch_velocity_rad_s = nan;
    s->longitudinal_force_N = nan;
    return RW_OK;
  });
}

rw_status rw_set_state(rw_problem* problem, const rw_state* s) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireSize(s, "rw_state");
    const bool wheelset = problem->kind == RW_PROBLEM_WHEELSET;
    if (s->flags & ~kKnownStateFlags) {
      Fail(RW_ERROR_UNKNOWN_FLAG,
           fmt::format("rw_state.flags = {:#x}: unknown bits {:#x} (known: RW_STATE_CREEPAGE)",
                       s->flags, s->flags & ~kKnownStateFlags));
    }
    // Lateral positions are millimetres; 0.1 m catches millimetres passed as metres.
    RequireInRange(s->lateral_m, -0.1, 0.1, "rw_state.lateral_m");
    RequireInRange(s->yaw_rad, -kMaxYaw_rad, kMaxYaw_rad, "rw_state.yaw_rad");
    RequireInRange(s->roll_rad, -kMaxRoll_rad, kMaxRoll_rad, "rw_state.roll_rad");
    const auto force = OptionalPositive(s->vertical_force_N, "rw_state.vertical_force_N");
    const auto approach = OptionalPositive(s->approach_m, "rw_state.approach_m");
    if (force.has_value() == approach.has_value()) {
      Fail(RW_ERROR_INVALID_VALUE,
           fmt::format("rw_state.vertical_force_N = {}, approach_m = {}: expected exactly one "
                       "of them (the other NaN)",
                       s->vertical_force_N, s->approach_m));
    }
    if (wheelset && approach) {
      Fail(RW_ERROR_WRONG_KIND,
           "rw_state.approach_m: a wheelset takes a vertical force per "
           "wheel (vertical_force_N), not an approach");
    }
    if (OptionalPositive(s->left_vertical_force_N, "rw_state.left_vertical_force_N") && !wheelset) {
      Fail(RW_ERROR_WRONG_KIND,
           "rw_state.left_vertical_force_N: expected NaN for a single wheel "
           "(a wheelset's left wheel load)");
    }
    RequirePositive(s->speed_m_s, "rw_state.speed_m_s");
    OptionalFinite(s->pitch_velocity_rad_s, "rw_state.pitch_velocity_rad_s");
    RequireFinite(s->lateral_velocity_m_s, "rw_state.lateral_velocity_m_s");
    RequireFinite(s->yaw_velocity_rad_s, "rw_state.yaw_velocity_rad_s");
    const auto fx = OptionalFinite(s->longitudinal_force_N, "rw_state.longitudinal_force_N");
    RequireInRange(s->curvature_per_m, 0.0, 0.1, "rw_state.curvature_per_m");
    if (s->curvature_per_m != 0.0 && !wheelset) {
      Fail(RW_ERROR_WRONG_KIND,
           "rw_state.curvature_per_m: expected 0 for a single wheel (a "
           "wheelset's track curvature)");
    }
    if (s->flags & RW_STATE_CREEPAGE) {
      RequireInRange(s->creepage_xi, -1.0, 1.0, "rw_state.creepage_xi");
      RequireInRange(s->creepage_eta, -1.0, 1.0, "rw_state.creepage_eta");
      RequireFinite(s->creepage_spin_per_m, "rw_state.creepage_spin_per_m");
      if (fx || !std::isnan(s->pitch_velocity_rad_s)) {
        Fail(RW_ERROR_INVALID_VALUE,
             "rw_state: RW_STATE_CREEPAGE with a pitch velocity or a "
             "longitudinal force: expected either prescribed creepages "
             "or the motion, not both");
      }
    }
    if (fx && !std::isnan(s->pitch_velocity_rad_s)) {
      Fail(RW_ERROR_INVALID_VALUE,
           "rw_state: pitch_velocity_rad_s and longitudinal_force_N both "
           "given: expected at most one (the other NaN)");
    }
    Invalidate(problem);
    problem->state = *s;
    return RW_OK;
  });
}

rw_status rw_set_warm_start(rw_problem* problem, int enable) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    if (enable != 0 && enable != 1) {
      Fail(RW_ERROR_INVALID_VALUE,
           fmt::format("enable = {}: expected 0 (every calculate cold, the default) or 1", enable));
    }
    problem->warm_start_on = enable == 1;
    problem->warm_start.Clear();
    problem->warm_start_left.Clear();
    return RW_OK;
  });
}

rw_status rw_calculate(rw_problem* problem) {
  std::string message;
  return Guard(problem, [&] {
    RequireHandle(problem);
    Invalidate(problem);
    ContactCase c = MakeCase(problem);
    {
      const LentProfiles lent(problem, &c);
      problem->result =
          railwear::SolveContactCase(c, &problem->placement_cache, &problem->tread_point,
                                     problem->warm_start_on ? &problem->warm_start : nullptr,
                                     problem->warm_start_on ? &problem->warm_start_left : nullptr);
    }
    const ContactCaseResult& r = *problem->result;
    auto add = [&](int wheel, const ContactResult& contact) {
      for (const PatchResult& patch : contact.patches) {
        problem->patches.push_back({wheel, &contact, &patch});
      }
    };
    if (r.wheelset) {
      add(0, r.wheelset->right);
      add(1, r.wheelset->left);
    } else {
      add(0, r.wheel);
    }
    const rw_status status = WorstStatus(problem, &message);
    if (status != RW_OK) Fail(status, message);
    return RW_OK;
  });
}

rw_status rw_get_summary(rw_problem* problem, rw_summary* out) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireSize(out, "rw_summary");
    RequireResult(problem);
    const ContactCaseResult& r = *problem->result;
    std::string unused;
    rw_summary s{};
    s.struct_size = sizeof(rw_summary);
    s.status = WorstStatus(problem, &unused);
    s.patches = static_cast<int>(problem->patches.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const ContactResult* wheels[2] = {r.wheelset ? &r.wheelset->right : &r.wheel,
                                      r.wheelset ? &r.wheelset->left : nullptr};
    for (int i = 0; i < 2; ++i) {
      s.approach_m[i] = wheels[i] ? wheels[i]->approach_m : nan;
      s.l_over_v[i] = wheels[i] ? wheels[i]->climb.l_over_v : nan;
      s.nadal_limit[i] = wheels[i] ? OrNaN(wheels[i]->climb.nadal_limit) : nan;
      if (wheels[i]) s.time_s += wheels[i]->time_s;
    }
    s.pitch_velocity_rad_s = wheels[0]->pitch_velocity_rad_s;
    if (r.wheelset) {
      s.wheelset_lateral_m = r.wheelset->placement.right.lateral_shift_m;
      s.right_rail_origin_Y_m = r.wheelset->placement.right_rail_origin_Y_m;
      s.left_rail_origin_Y_m = r.wheelset->placement.left_rail_origin_Y_m;
    } else {
      s.wheelset_lateral_m = s.right_rail_origin_Y_m = s.left_rail_origin_Y_m = nan;
    }
    *out = s;
    return RW_OK;
  });
}

rw_status rw_get_patch_count(rw_problem* problem, int* count) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireNonNull(count, "count");
    RequireResult(problem);
    *count = static_cast<int>(problem->patches.size());
    return RW_OK;
  });
}

rw_status rw_get_patch(rw_problem* problem, int index, rw_patch* out) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireNonNull(out, "rw_patch");
    // A 1.1 caller's smaller struct (without the wheel-frame location) is filled up to its size.
    const size_t size = out->struct_size;
    if (size != RW_PATCH_SIZE_1_1) RequireSize(out, "rw_patch");
    const rw_problem::PatchRef& ref = PatchAt(problem, index);
    const PatchResult& p = *ref.patch;
    rw_patch o{};
    o.struct_size = sizeof(rw_patch);
    o.wheel = ref.wheel;
    o.contact_x_m = p.contact_x_m;
    o.contact_y_m = p.contact_point_yz_m.x();
    o.contact_z_m = p.contact_point_yz_m.y();
    o.contact_track_Y_m = o.contact_y_m;
    if (problem->result->wheelset) {
      const railwear::WheelsetPlacement& w = problem->result->wheelset->placement;
      // The left rail's own frame is the track's mirrored (y = -Y about its origin).
      o.contact_track_Y_m = ref.wheel == 0 ? w.right_rail_origin_Y_m + o.contact_y_m
                                           : w.left_rail_origin_Y_m - o.contact_y_m;
    }
    o.contact_angle_rad = p.contact_angle_rad;
    o.area_m2 = p.area_m2;
    o.p_max_Pa = p.p_max_Pa;
    o.normal_force_N = p.normal_force_N;
    const Eigen::Vector3d f = railwear::PatchForcesOnRail(p).Net();
    for (int i = 0; i < 3; ++i) o.force_on_rail_N[i] = f[i];
    if (p.rolling) {
      o.creepage_xi = p.rolling->creepage.xi;
      o.creepage_eta = p.rolling->creepage.eta;
      o.creepage_spin_per_m = p.rolling->creepage.spin_per_m;
      o.creep_force_x_N = p.rolling->tangential.force_x_N;
      o.creep_force_s_N = p.rolling->tangential.force_s_N;
      o.spin_moment_Nm = p.rolling->tangential.spin_moment_Nm;
      if (p.rolling->damage) {
        o.t_gamma_N = p.rolling->damage->t_gamma_N;
        o.wlrm_damage = p.rolling->damage->wlrm_damage;
        o.fi_surf = p.rolling->damage->fi_surf;
      }
    }
    o.cells = p.cells;
    o.cells_in_contact = p.cells_in_contact;
    const std::optional<railwear::HertzTreadPoint>& tread_point =
        !problem->result->wheelset ? problem->tread_point
        : ref.wheel == 0           ? problem->result->wheelset->right_tread_point
                                   : problem->result->wheelset->left_tread_point;
    if (tread_point && p.model == "hertz") {
      // The fast tread path placed the wheel itself: its contact point on the wheel.
      o.contact_wheel_x_m = tread_point->wheel_x_m;
      o.contact_wheel_y_m = tread_point->wheel_y_m;
      o.contact_wheel_z_m = tread_point->wheel_z_m;
    } else {
      // The wheel frame: the pressure centre in the wheel's placed geometry of this solve (the
      // handle's placement cache holds each wheel's last one, core/contact/placement_cache.h).
      const railwear::WheelRailGeometry* geometry = problem->placement_cache.Last(
          ref.wheel == 0 ? railwear::PlacementCache::kRight : railwear::PlacementCache::kLeft);
      RAILWEAR_CHECK(geometry != nullptr);
      const Eigen::Vector3d p_R(p.contact_x_m, o.contact_y_m, o.contact_z_m);
      const Eigen::Vector2d meridian = geometry->Meridian(p_R);  // (y_W, r - r0)
      // x along the wheel's rolling direction: Meridian's own rotation about the vertical through
      // the wheel profile origin (its yaw undone), of which it returns y and r only.
      const double yaw = geometry->pose().yaw_rad;
      const double y_roll_undone = geometry->RailToWheel({o.contact_y_m, o.contact_z_m}).x();
      o.contact_wheel_x_m = yaw == 0.0 ? p.contact_x_m
                                       : std::cos(yaw) * p.contact_x_m +
                                             std::sin(yaw) * y_roll_undone;
      o.contact_wheel_y_m = meridian.x();
      o.contact_wheel_z_m = meridian.y();
    }
    if (size == RW_PATCH_SIZE_1_1) {
      o.struct_size = size;
      std::memcpy(out, &o, size);
    } else {
      *out = o;
    }
    return RW_OK;
  });
}

rw_status rw_get_patch_model(rw_problem* problem, int index, const char** model,
                             const char** reason) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    const PatchResult& p = *PatchAt(problem, index).patch;
    if (model) *model = p.model.c_str();
    if (reason) *reason = p.model_reason.c_str();
    return RW_OK;
  });
}

rw_status rw_get_cell_count(rw_problem* problem, int index, size_t* count) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireNonNull(count, "count");
    *count = static_cast<size_t>(PatchAt(problem, index).patch->grid.cells());
    return RW_OK;
  });
}

rw_status rw_get_cells(rw_problem* problem, int index, size_t capacity, double* x_m, double* s_m,
                       double* pressure_Pa, double* traction_x_Pa, double* traction_s_Pa,
                       double* slip_x_m_s, double* slip_s_m_s) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    const PatchResult& p = *PatchAt(problem, index).patch;
    const railwear::PatchGrid& g = p.grid;
    const size_t n = static_cast<size_t>(g.cells());
    if (capacity < n) {
      Fail(RW_ERROR_BUFFER_TOO_SMALL,
           fmt::format("capacity = {}: patch {} has {} cells (rw_get_cell_count)", capacity, index,
                       n));
    }
    const railwear::TangentialSolution* t =
        p.rolling && p.rolling->tangential.traction_x_Pa.size() == g.cells()
            ? &p.rolling->tangential
            : nullptr;
    for (int j = 0; j < g.ns; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const int k = g.Index(i, j);
        if (x_m) x_m[k] = g.X(i);
        if (s_m) s_m[k] = g.S(j);
        if (pressure_Pa) pressure_Pa[k] = p.pressure_Pa[k];
        if (traction_x_Pa) traction_x_Pa[k] = t ? t->traction_x_Pa[k] : 0.0;
        if (traction_s_Pa) traction_s_Pa[k] = t ? t->traction_s_Pa[k] : 0.0;
        if (slip_x_m_s) slip_x_m_s[k] = t ? t->slip_x_m_s[k] : 0.0;
        if (slip_s_m_s) slip_s_m_s[k] = t ? t->slip_s_m_s[k] : 0.0;
      }
    }
    return RW_OK;
  });
}

rw_status rw_init_wear(rw_wear* wear) {
  return Guard(nullptr, [&] {
    RequireSize(wear, "rw_wear");
    const railwear::WearLaw law;
    wear->law = RW_WEAR_ARCHARD;
    wear->archard_k = law.archard_k;
    wear->bin_m = 1e-4;  // WearOptions::bin_m, the wear scene's default
    return RW_OK;
  });
}

rw_status rw_set_wear(rw_problem* problem, const rw_wear* wear) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireSize(wear, "rw_wear");
    RequireEnum(wear->law, RW_WEAR_ARCHARD, RW_WEAR_USFD, "rw_wear.law");
    RequirePositive(wear->archard_k, "rw_wear.archard_k");
    // Bins from 1 micrometre to 10 mm (a profile spans some 0.2 m).
    RequireInRange(wear->bin_m, 1e-6, 1e-2, "rw_wear.bin_m");
    railwear::WearLaw law;
    law.kind = static_cast<railwear::WearLawKind>(wear->law);
    law.archard_k = wear->archard_k;
    railwear::ValidateWearLaw(law);
    problem->wear_law = law;
    problem->wear_bin_m = wear->bin_m;
    ResetDepth(problem);
    return RW_OK;
  });
}

rw_status rw_accumulate(rw_problem* problem, double passes) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    if (!(std::isfinite(passes) && passes >= 0.0)) {
      Fail(RW_ERROR_INVALID_VALUE,
           fmt::format("passes = {}: expected a finite weight >= 0 (V dt / L)", passes));
    }
    RequireResult(problem);
    std::string message;
    if (WorstStatus(problem, &message) != RW_OK) {
      Fail(RW_ERROR_CALL_ORDER, "rw_accumulate needs a converged rw_calculate: " + message);
    }
    if (!(problem->effects & RW_EFFECT_TANGENTIAL)) {
      Fail(RW_ERROR_CALL_ORDER,
           "rw_accumulate needs rolling contact: set RW_EFFECT_TANGENTIAL "
           "with rw_set_model (the wear laws use slip and traction)");
    }
    const railwear::WearLawKind kind = problem->wear_law.kind;
    const double hardness = problem->rail_material.hardness_Pa;
    if (kind != railwear::WearLawKind::kUsfd && !(hardness > 0.0)) {
      Fail(RW_ERROR_CALL_ORDER,
           "the Archard and KTH wear laws need the rail's hardness_Pa: set "
           "it with rw_set_materials");
    }
    // All of a step's depth first, then the sum: a failure leaves the field as it was.
    const double speed = problem->state->speed_m_s;
    std::vector<double> step[2];
    for (int rail = 0; rail < 2; ++rail) step[rail].assign(problem->depth_m[rail].size(), 0.0);
    for (const rw_problem::PatchRef& ref : problem->patches) {
      const std::vector<double> depth = railwear::CalcPatchPassDepth(
          *ref.patch, *CantedRail(problem, ref.wheel), problem->wear_law, hardness, speed,
          problem->wear_grid[ref.wheel]);
      for (size_t b = 0; b < depth.size(); ++b) step[ref.wheel][b] += depth[b];
    }
    for (int rail = 0; rail < 2; ++rail) {
      for (size_t b = 0; b < step[rail].size(); ++b)
        problem->depth_m[rail][b] += passes * step[rail][b];
    }
    return RW_OK;
  });
}

rw_status rw_get_depth_count(rw_problem* problem, int rail, size_t* count) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireNonNull(count, "count");
    RequireEnum(rail, 0, 1, "rail");
    *count = problem->depth_m[rail].size();
    return RW_OK;
  });
}

rw_status rw_get_depth(rw_problem* problem, int rail, size_t capacity, double* s_m,
                       double* depth_m) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    RequireEnum(rail, 0, 1, "rail");
    const std::vector<double>& d = problem->depth_m[rail];
    if (capacity < d.size()) {
      Fail(RW_ERROR_BUFFER_TOO_SMALL,
           fmt::format("capacity = {}: rail {} has {} bins (rw_get_depth_count)", capacity, rail,
                       d.size()));
    }
    for (size_t b = 0; b < d.size(); ++b) {
      if (s_m) s_m[b] = problem->wear_grid[rail].Centre(static_cast<int>(b));
      if (depth_m) depth_m[b] = d[b];
    }
    return RW_OK;
  });
}

rw_status rw_reset_depth(rw_problem* problem) {
  return Guard(problem, [&] {
    RequireHandle(problem);
    ResetDepth(problem);
    return RW_OK;
  });
}

}  // extern "C"
