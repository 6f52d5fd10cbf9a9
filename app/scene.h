// Scene files (TOML, DESIGN.md §3): read, validate strictly, and turn into a ContactProblem.
//
// Every problem with a scene is an InputError whose message reads
//   FILE:LINE: key 'section.key' = VALUE: expected WHAT
// (for a missing key: "FILE:LINE: key 'section.key' is missing: expected WHAT", with the line of
// its table). toml++ stays inside scene.cpp; callers see plain value types.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/contact/contact_solver.h"
#include "core/contact/influence_constant_sets.h"
#include "core/contact/kinematics.h"
#include "core/geometry/wheelset.h"
#include "wear/wear_simulation.h"

namespace railwear::app {

// The constants a scene uses unless it names others ([model] constants or influence_constants):
// the FEM-calibrated set, which the project's FEM contact cases support (docs/models.md).
inline constexpr InfluenceConstantsName kDefaultInfluenceConstants = InfluenceConstantsName::kFem;

struct Scene {
  std::string path;                  // as given ("<text>" for ParseScene without a file)
  std::string name;                  // [scene] name; defaults to the file's stem
  std::vector<std::string> effects;  // always contains "normal"; as listed, in order
  std::string text;  // the original TOML text, stored with results so a run can be repeated

  std::string wheel_profile_spec;     // [wheel] profile, as written
  std::string rail_profile_spec;      // [rail] profile or [track] high_rail, as written
  std::string low_rail_profile_spec;  // [track] low_rail (default high_rail); empty with [rail]
  std::string cant = "0";             // [rail] cant or [track] inclination, as written ("1:40")
  double cant_ratio = 0.0;            // 1:40 -> 0.025
  // [model] tangential as written ("fastsim" | "exact" | "auto"); the solver uses
  // problem.tangential.
  std::string tangential_method = "fastsim";
  // Where the influence constants came from: a named set ("fem", the default, or "paper"),
  // "inline" or the resolved file path.
  std::string influence_constants_source = "fem";

  std::optional<double> friction;   // [load] friction, in (0, 2]; used by rolling contact
  std::optional<double> speed_m_s;  // [load] or [wheelset] speed_m_s; used by rolling contact

  // Effects beyond "normal" (DESIGN.md §3), as read: "damage", "coupling" and "wear" imply
  // "tangential"; "wear" needs [wear] and [[traffic]]. The contact set-up (problem, wear) holds
  // what the solvers use (problem.damage, problem.rolling->coupling, wear).
  bool tangential = false;
  bool damage = false;
  // Rolling: the wheel's motion (speed, pitch velocity, yaw), or prescribed creepages instead.
  WheelMotion motion;
  std::optional<Creepage> creepage;
  // Prescribed total longitudinal force [N] ([load] for the wheel, [wheelset] for the axle)
  // instead of a pitch velocity: > 0 traction, < 0 braking.
  std::optional<double> longitudinal_force_N;

  // A single wheel placed from the centred wheelset ([load] lateral_mm) instead of by its
  // profile origin ([load] lateral_shift_mm): the reference track and wheelset, and where the
  // wheel's origin then stands. problem.placement.lateral_shift_m holds the result.
  struct CentredPlacement {
    double lateral_m = 0.0;  // [load] lateral_mm: from the centred wheelset, toward the field side
    TrackSpec track;         // [load] gauge_mm, gauge_height_mm (defaults 1435, 14)
    WheelsetSpec wheelset;   // [load] flange_back_distance_mm, flange_back_position_mm
    double centred_shift_m = 0.0;  // the wheel origin from the rail's when lateral_mm = 0
  };
  std::optional<CentredPlacement> centred;

  // A wheelset on a track ([track] + [wheelset]) instead of the single wheel of [load]; then
  // `problem` holds the right wheel's placement and the left one is its mirror image.
  std::optional<TrackSpec> track;
  std::optional<WheelsetSpec> wheelset;

  ContactProblem problem;  // profiles loaded (cant, mirroring applied), SI units throughout

  // A wear scene (effect "wear", [wear] and [[traffic]] tables, and [rail] for one rail or
  // [track] for both): the study to run. Then `problem` carries only the model, materials and
  // (high) rail; the loads come from the traffic mix.
  std::optional<WearStudy> wear;  // its rail profiles are the scene's before cant
  std::string wear_db;  // [wear] db resolved against the scene's directory; empty when not given
};

// Reads and validates the scene file at `path`; profile paths are relative to its directory.
// Throws InputError (file unreadable, TOML syntax, unknown/missing/mistyped/out-of-range keys,
// profile files).
Scene LoadScene(const std::string& path);

// The same for scene text already in memory; `path` names it in messages and anchors relative
// profile paths.
Scene ParseScene(const std::string& text, const std::string& path);

// Steel, the default of both bodies when a scene has no [materials] table.
Material DefaultSteel();

}  // namespace railwear::app
