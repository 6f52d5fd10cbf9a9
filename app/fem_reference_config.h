// The config of `railwear fem-reference`: TOML -> typed, validated experiments (the FEM
// displacement experiment of calibration/fem/fem_displacement.h and the contact cases of
// calibration/fem/fem_contact.h), with every output path resolved.
//
// The config (keys of [fem] are defaults that an [[experiment]] may override):
//   [fem]
//   mesh_size_at_load_mm = 0.1      h0, element size at the load point, > 0
//   mesh_growth = 0.12              h = h0 + mesh_growth * r (mm per mm), in (0, 2]
//   max_element_mm = 20             largest element, >= h0
//   min_distance_mm = 0.5           distances written, from the load point
//   max_distance_mm = 25
//   supports = "bottom"             "bottom" (bottom face clamped) | "far_faces"
//   material = { E_MPa = 210000, nu = 0.28 }
//   loads = ["normal", "axial", "circumferential"]
//   compare_range_mm = [1, 10]      where comparisons fit the offset and report errors
//   jobs = 2                        ccx solves at once ([fem] only; --jobs overrides)
//   threads_per_job = 1             ([fem] only)
//   timeout_s = 3600                per gmsh or ccx run ([fem] only)
//   [[experiment]]
//   name = "r15_convex"             letters, digits, '_', '-', '.'; unique
//   kind = "displacement"           the default; "contact" is a contact case (below)
//   body = "convex"                 "flat" | "convex" | "concave"
//   radius_mm = 15                  convex and concave only
//   length_mm, width_mm, depth_mm   body size; defaults per body (DefaultFemBodySize)
//   output = "r15_convex.csv"       default NAME.csv; relative to the config file or --out-dir
//   compare_with = "other"          an earlier experiment of this config (run before this one,
//                                   or its output file when --only skipped it)
//
// A contact experiment (calibration/fem/fem_contact.h) runs its mesh levels one after the
// other (--jobs does not apply) and takes from [fem] only material, threads_per_job and
// timeout_s; its own keys (defaults per case, DefaultFemContactOptions):
//   [[experiment]]
//   name = "wheel_in_groove"
//   kind = "contact"
//   case = "wheel_in_groove"        "wheel_in_groove" | "rail_in_wheel_groove"
//   scene = "wheel_in_groove.toml"  the railwear scene of the same contact (config-relative;
//                                   written relative to the output into the result)
//   convex_radius_mm, groove_radius_mm, rolling_radius_mm = 460, load_N, material
//   length_mm = 80, width_mm = 60, depth_mm = 40       body size (whole length and width)
//   zone_x_mm, zone_s_mm, zone_depth_mm                refined and contact-search zone
//   mesh_sizes_mm = [0.7, 0.5, 0.35]                   one model per level, coarse to fine
//   mesh_growth = 0.4, max_element_mm = 8
//   penalty_MPa_per_mm = 5e6, initial_overlap_mm = 0.01, spring_N_per_mm = 10, sectors = 9
//   output = "wheel_in_groove.toml" default NAME.toml (format: app/fem_contact_result.h)
#pragma once

#include <string>
#include <vector>

#include "calibration/fem/fem_contact.h"
#include "calibration/fem/fem_displacement.h"

namespace railwear::app {

enum class FemExperimentKind { kDisplacement, kContact };

struct FemExperiment {
  std::string name;
  int line = 0;  // of its [[experiment]] table
  FemExperimentKind kind = FemExperimentKind::kDisplacement;
  FemDisplacementOptions options;  // kDisplacement; work_dir and progress are set when it runs
  FemContactOptions contact;       // kContact; likewise
  std::string scene;               // kContact: the matching scene as written (config-relative)
  std::string output;              // the CSV (contact: TOML) path, resolved
  std::string compare_with;        // empty: none
  double compare_from_m = 1e-3;
  double compare_to_m = 10e-3;
};

struct FemReferenceConfig {
  std::string path;
  std::vector<FemExperiment> experiments;
};

// Reads and validates a config. Throws InputError "FILE:LINE: key 'KEY' = VALUE: expected ..."
// for unknown keys, wrong types, out-of-range values (every numeric key has the range the mesher
// and solver bear, issue 17: docs/testing.md), unknown names and inconsistent options, and
// "FILE:LINE: experiment 'NAME': the mesh would have about N nodes ..." when the node count
// estimated before meshing (EstimateFemDisplacementNodes, EstimateFemContactNodes per level)
// exceeds 500,000 (at least 15 GB and hours per CalculiX solve), naming the keys to change.
FemReferenceConfig ReadFemReferenceConfig(const std::string& path, const std::string& out_dir);

}  // namespace railwear::app
