// Output of `railwear contact`: the human summary, the JSON object, the pressure-field CSV and
// the pressure samples the CSV and the plot share. Units of files: mm, N, MPa, ms, degrees.
#pragma once

#include <numbers>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/scene.h"
#include "core/contact/contact_solver.h"
#include "core/contact/wheelset_contact.h"

namespace railwear::app {

// rad -> degrees, for the angles of summaries, JSON and plots.
inline constexpr double kToDeg = 180.0 / std::numbers::pi;

// Keys of the contact JSON (MakeContactJson) that `railwear accuracy --reference` reads back
// (accuracy_study.cpp): the writer and the reader share this one spelling.
namespace contact_json {
inline constexpr char kTotal[] = "total";                      // totals over all patches
inline constexpr char kAreaMm2[] = "area_mm2";                 // total.area_mm2 [mm2]
inline constexpr char kPMaxMPa[] = "p_max_MPa";                // total.p_max_MPa [MPa]
inline constexpr char kVerticalForceN[] = "vertical_force_N";  // total.vertical_force_N [N]
inline constexpr char kLateralForceN[] = "lateral_force_N";    // total.lateral_force_N [N]
inline constexpr char kCreepForceXN[] = "creep_force_x_N";     // total, rolling only [N]
inline constexpr char kPatches[] = "patches";                  // one object per patch
inline constexpr char kCreepForceYzN[] = "creep_force_yz_N";   // per rolling patch: {y, z} [N]
}  // namespace contact_json

// One sample of a patch's pressure field. For grid models: one per cell, (x, s) its centre on
// the reference surface and (y, z) the cross-section point grid.point_yz_m[js]. For Hertz: the
// analytic ellipse sampled on kHertzSamples x kHertzSamples points over its bounding box, with
// (y, z) = contact point + s * (cos(angle), sin(angle)) (the tangent of the contact plane).
struct PressureSample {
  int patch = 0;  // 1-based, as in the summary
  int ix = 0;     // index along x (rolling)
  int js = 0;     // index along s (lateral arc)
  double x_mm = 0.0, s_mm = 0.0, y_mm = 0.0, z_mm = 0.0, p_MPa = 0.0;
};
constexpr int kHertzSamples = 41;

// Samples of one patch; `patch_number` is 1-based. Throws std::runtime_error when the pressure
// vector does not match the grid.
std::vector<PressureSample> PressureSamples(const PatchResult& patch, int patch_number);

// The model as JSON (kind, geometry, kernel, accuracy, influence_constants and the name of their
// set, "constants": fem, paper or custom) and as the summary's one line; shared by the contact
// and wear commands.
nlohmann::json ModelJson(const ModelOptions& m);
std::string ModelLine(const ModelOptions& m);

// "p_max ... exceeds the rail's (wheel's) hardness ...": when p_max passes the hardness of the
// softer body of those whose hardness_Pa is given (by more than rounding: a pressure limit at the
// hardness holds it there); `wheel` ("right wheel", ...) may be empty. Contact and wear warnings.
std::optional<std::string> HardnessWarning(const Material& wheel_material, const Material& rail,
                                           double p_max_Pa, const std::string& wheel);

// The warnings of a result: L/V beyond Nadal's limit (FlangeClimbWarning), and p_max beyond the
// hardness of the softer body whose hardness the scene gives (materials.*.hardness_MPa).
// `wheel` ("right wheel", ...) may be empty. Summary, JSON and stderr show the same strings.
std::vector<std::string> ContactWarnings(const Scene& scene, const ContactResult& result,
                                         const std::string& wheel);

// Human summary: model, status, approach, iterations, time, totals (net forces on the rail, and
// with rolling their pressure and creep parts), the vertical balance, L/V against Nadal's limit
// (a WARNING line per ContactWarnings), the placement when [load] lateral_mm gave it, and tables of
// patches. `left_wheel`: the result is a wheelset's left wheel (its track frame is its rail frame
// mirrored).
std::string FormatSummary(const Scene& scene, const ContactResult& result, bool left_wheel = false);

// The JSON object of DESIGN.md §4 (keys carry their units). Throws std::runtime_error naming
// the key when a number is NaN or infinite, so that no such value reaches a file. Besides the
// old keys (total.vertical_force_N / lateral_force_N: the pressure's part on the rail; the
// patches' creep_force_N: on the wheel): "forces" (on the rail; rail, track and patch frames;
// normal, creep and net parts; totals and per patch), "balance" (vertical balance iterations),
// "flange_climb_check" (L/V, Nadal's limit), "flange_climb" (true when L/V exceeds it) and
// "warnings" (strings).
nlohmann::json MakeContactJson(const Scene& scene, const ContactResult& result,
                               bool left_wheel = false);

// No NaN or infinity reaches an output (issue 6): throws std::runtime_error naming the key path
// (`where` + ".key[i]...") of the first non-finite number in `j`. MakeContactJson calls it; so
// does everything else that writes or stores JSON.
void RequireFiniteJson(const nlohmann::json& j, const std::string& where);

// Header "patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa" (plus traction, slip velocity and stick when
// the result has rolling contact), then one row per sample of every patch. With a `wheel`
// label every row starts with it, under a leading "wheel" column; `header` = false leaves the
// header out (for the second wheel of a wheelset).
void WritePressureCsv(const ContactResult& result, std::ostream& out, const std::string& wheel = "",
                      bool header = true);

// A wheelset: { status, scene, scene_file, placement: {...}, wheels: {left: {...}, right: {...}},
// warnings: [...], flange_climb } with each wheel's object as MakeContactJson gives it. Throws as
// MakeContactJson does.
nlohmann::json MakeWheelsetJson(const Scene& scene, const WheelsetResult& result);
std::string FormatWheelsetSummary(const Scene& scene, const WheelsetResult& result);

}  // namespace railwear::app
