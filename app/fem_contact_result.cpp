// Writes and reads the FEM contact result files (TOML). See fem_contact_result.h.
#include "app/fem_contact_result.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "app/paths.h"
#include "app/toml_fields.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"
#include "core/numerics/text_file.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace {

constexpr double kMm2 = 1e-6;
constexpr double kMPa = 1e6;

// A TOML basic string (quotes and backslashes escaped).
std::string Quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string MeasuresText(const FemContactPatch& p) {
  return fmt::format(
      "area_mm2 = {:.4f}\np_max_MPa = {:.3f}\nhalf_length_x_mm = {:.4f}\nhalf_width_s_mm = {:.4f}\n"
      "total_force_N = {:.2f}\nnormal_force_N = {:.2f}\narea_nodes_mm2 = {:.4f}\n",
      p.area_m2 / kMm2, p.p_max_Pa / kMPa, p.half_length_x_m / kMm, p.half_width_s_m / kMm,
      p.vertical_force_N, p.normal_force_N, p.area_nodes_m2 / kMm2);
}

}  // namespace

std::string FemContactResultText(const std::string& name, const FemContactResult& r,
                                 const std::string& scene,
                                 const std::vector<std::pair<std::string, std::string>>& metadata) {
  const FemContactOptions& o = r.options;
  RAILWEAR_CHECK(!r.levels.empty());
  const FemContactLevel& best = r.levels.back();
  // The header names the model's old home (now calibration/fem/fem_contact.h): kept as the
  // committed references in examples/fem/reference/ carry it, so the written files stay identical.
  std::string out = fmt::format(
      "# FEM contact reference (railwear fem-reference, CalculiX): {}.\n"
      "# [contact_result] is the finest mesh level; [[convergence]] lists every level.\n"
      "# Format: app/fem_contact_result.h; model: calibration/fem/fem_contact.h.\n\n"
      "[contact_result]\nname = {}\ncase = {}\nscene = {}\nstatus = {}\nload_N = {:g}\n",
      name, Quoted(name), Quoted(std::string(ToString(o.contact_case))), Quoted(scene),
      Quoted(std::string(ToString(best.patch.status))), o.load_N);
  out += MeasuresText(best.patch);
  if (!best.patch.message.empty()) out += fmt::format("message = {}\n", Quoted(best.patch.message));
  out += fmt::format(
      "\n[model]\nconvex_radius_mm = {:g}\ngroove_radius_mm = {:g}\nrolling_radius_mm = {:g}\n"
      "E_MPa = {:g}\nnu = {:g}\nlength_mm = {:g}\nwidth_mm = {:g}\ndepth_mm = {:g}\n"
      "symmetry = \"quarter model: planes x = 0 and y = 0\"\n"
      "supports = \"rail bottom clamped; uniform pressure on the wheel's far face; far-face "
      "springs {:g} N/mm in total\"\n"
      "contact = \"ccx surface-to-surface, frictionless, linear penalty; slave = rail face\"\n"
      "penalty_MPa_per_mm = {:g}\ninitial_overlap_mm = {:g}\nspring_N_per_mm = {:g}\n"
      "zone_x_mm = {:g}\nzone_s_mm = {:g}\nzone_depth_mm = {:g}\nelement = \"C3D10\"\n"
      "mesh_growth = {:g}\nmax_element_mm = {:g}\nsectors = {}\n",
      o.convex_radius_m / kMm, o.groove_radius_m / kMm, o.rolling_radius_m / kMm,
      o.material.youngs_modulus_Pa / kMPa, o.material.poisson_ratio, o.length_m / kMm,
      o.width_m / kMm, o.depth_m / kMm, o.spring_N_per_m * kMm, o.penalty_Pa_per_m / kMPa * kMm,
      o.initial_overlap_m / kMm, o.spring_N_per_m * kMm, o.zone_x_m / kMm, o.zone_s_m / kMm,
      o.zone_depth_m / kMm, o.mesh_growth, o.max_element_m / kMm, o.sectors);
  out += "\n[metadata]\n";
  for (const auto& [key, value] : metadata) out += fmt::format("{} = {}\n", key, Quoted(value));
  out += fmt::format("wall_time_s = {:.1f}\n", r.wall_time_s);
  for (const FemContactLevel& L : r.levels) {
    out += fmt::format(
        "\n[[convergence]]\nmesh_size_mm = {:g}\nnodes = {}\nelements = {}\nslave_faces = {}\n"
        "master_faces = {}\nmesh_time_s = {:.2f}\nsolve_time_s = {:.2f}\niterations = {}\n"
        "spring_force_N = {:.4f}\nstatus = {}\n",
        L.mesh_size_m / kMm, L.nodes, L.elements, L.slave_faces, L.master_faces, L.mesh_time_s,
        L.solve_time_s, L.iterations, L.spring_force_N,
        Quoted(std::string(ToString(L.patch.status))));
    out += MeasuresText(L.patch);
  }
  return out;
}

FemContactTarget ReadFemContactTarget(const std::string& path) {
  const std::optional<std::string> text = ReadTextFile(path);
  if (!text) throw InputError(fmt::format("{}: cannot read the FEM contact result", path));
  const toml::table root = ParseToml(*text, path);
  const Fields top(root, "", path);
  top.AllowOnly({"contact_result", "model", "metadata", "convergence"});
  const auto r = top.Table("contact_result", "a [contact_result] table");
  if (!r) top.FailMissing("contact_result", "a [contact_result] table (a FEM contact result)");
  r->AllowOnly({"name", "case", "scene", "status", "load_N", "area_mm2", "p_max_MPa",
                "half_length_x_mm", "half_width_s_mm", "total_force_N", "normal_force_N",
                "area_nodes_mm2", "message"});
  FemContactTarget t;
  t.name = r->RequiredString("name", "the experiment's name");
  const auto contact_case = r->Choice("case", {"wheel_in_groove", "rail_in_wheel_groove"});
  if (!contact_case) r->FailMissing("case", "'wheel_in_groove' or 'rail_in_wheel_groove'");
  t.contact_case = *contact_case;
  const std::string scene = r->String("scene").value_or("");
  t.scene = scene.empty() ? "" : ResolveRelativeTo(DirectoryOf(path), scene);
  t.status = r->RequiredString("status", "a status");
  t.load_N = r->RequiredNumber("load_N", Positive());
  t.area_mm2 = r->RequiredNumber("area_mm2", Positive());
  t.p_max_MPa = r->RequiredNumber("p_max_MPa", Positive());
  t.half_length_x_mm = r->RequiredNumber("half_length_x_mm", Positive());
  t.half_width_s_mm = r->RequiredNumber("half_width_s_mm", Positive());
  t.total_force_N = r->RequiredNumber("total_force_N", Positive());
  if (const toml::node* c = top.Node("convergence"); c != nullptr && c->is_array_of_tables()) {
    t.levels = static_cast<int>(c->as_array()->size());
  }
  return t;
}

}  // namespace railwear::app
