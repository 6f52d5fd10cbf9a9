// The result file of a `fem-reference` contact experiment (kind = "contact"): a small TOML file
// that calibration and the README read as a FEM target, without rerunning CalculiX.
//
//   [contact_result]                 the finest mesh level: the target
//   name = "wheel_in_groove"         the experiment
//   case = "wheel_in_groove"         "wheel_in_groove" | "rail_in_wheel_groove"
//   scene = "../wheel_in_groove.toml"   the railwear scene of the same contact, relative to
//                                       this file's folder ("" when the config names none)
//   status = "ok"                    "ok" | "no_contact" | "patch_at_zone_edge" | "fit_failed"
//   load_N = 10000                   applied vertical load (whole wheel)
//   area_mm2 = 38.63                 contact area (edge fit, see calibration/fem/fem_contact.h)
//   p_max_MPa = 400.9                peak contact pressure
//   half_length_x_mm = 2.82          patch half-length along x (rolling direction)
//   half_width_s_mm = 4.34           patch half-width along the lateral arc
//   total_force_N = 10037.5          vertical resultant of the FEM contact pressure
//   area_nodes_mm2 = 44.1            lumped area of the nodes with p > 0 (upper bound)
//   [model]                          the model: radii, material, body size, supports, contact
//   [metadata]                       generated_by, gmsh_version, ccx_version, wall_time_s
//   [[convergence]]                  one per mesh level, coarse to fine: mesh_size_mm, nodes,
//                                    elements, slave_faces, mesh_time_s, solve_time_s,
//                                    iterations, spring_force_N (the wheel's force on its
//                                    far-face springs, z up: -0.33 means they carry 0.33 N),
//                                    the measures above, status
// Units are in the key names (mm, MPa, N, s).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "calibration/fem/fem_contact.h"

namespace railwear::app {

// What a calibration target needs from a result file.
struct FemContactTarget {
  std::string name;
  std::string contact_case;
  std::string scene;  // resolved against the result file's folder ("" when none)
  std::string status;
  double load_N = 0.0;
  double area_mm2 = 0.0;
  double p_max_MPa = 0.0;
  double half_length_x_mm = 0.0;
  double half_width_s_mm = 0.0;
  double total_force_N = 0.0;
  int levels = 0;  // [[convergence]] rows
};

// The file's text. `scene` is written as given (relative to the result file's folder);
// `metadata` pairs go to [metadata] as strings, before wall_time_s.
std::string FemContactResultText(const std::string& name, const FemContactResult& result,
                                 const std::string& scene,
                                 const std::vector<std::pair<std::string, std::string>>& metadata);

// Reads a result file. Throws InputError "FILE:LINE: key ...: expected ..." when it is not
// one (unknown keys in [contact_result], missing or non-positive measures).
FemContactTarget ReadFemContactTarget(const std::string& path);

}  // namespace railwear::app
