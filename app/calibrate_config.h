// The config of `railwear calibrate`: TOML -> typed, validated entries (the reference data read
// and checked, the scenes of contact results loaded), ready for FitInfluenceConstants.
//
// Config (strict: unknown keys, wrong types and out-of-range values are errors naming
// FILE:LINE and the key; paths are relative to the config file):
//
//   [calibration]
//   name = "paper experiment, R15/R80"   # default: the config file's name
//   fit = ["c_f", "c_z", "c_s"]          # any non-empty subset; default all three
//   separate_bodies = false              # true: a convex and a concave set
//   start = { c_f = 0.75, c_z = 1.0, c_s = 0.25 }   # or { convex = {...}, concave = {...} }
//   fit_offsets = true                   # one offset per curve (FE supports)
//   out = "calibrated_constants.toml"    # default: CONFIG-STEM_constants.toml beside the config
//   db = "calibration.sqlite"            # optional: store the calibration there
//   contact_relative_step = 0.01         # central-difference step on contact results
//   max_iterations = 100
//
//   [[displacement_curves]]              # any number, >= 1 in all with contact_results
//   file = "r15_convex.csv"              # required (displacement_curves.h format)
//   weight = 1.0                         # > 0
//   min_distance_mm = 0.5                # leave out points nearer the load (FE near field)
//   max_distance_mm = 20                 # ... and farther
//
//   [[contact_results]]
//   scene = "groove_conformal.toml"      # required: a single-wheel scene, golubenko kernel
//   area_mm2 = 60.2                      # required target contact area, > 0
//   p_max_MPa = 1234                     # required target peak pressure, > 0
//   weight = 1.0
//   # or fem_result = "reference/wheel_in_groove.toml" (a fem-reference contact result: its
//   # scene and finest level's area and peak pressure), with weight
#pragma once

#include <string>
#include <vector>

#include "app/scene.h"
#include "calibration/influence_fit.h"

namespace railwear::app {

// One [[displacement_curves]] table: the CSV, read, with its weight and distance window (SI).
struct CalibrateCurveEntry {
  std::string file;  // resolved against the config's folder
  CurveDataSet data;
};

// One [[contact_results]] table: the scene, loaded, and the target area [m^2] and peak [Pa].
struct CalibrateContactEntry {
  std::string scene;       // resolved
  std::string fem_result;  // resolved fem-reference result file, when the target came from one
  Scene loaded;
  ContactTarget target;
};

struct CalibrateConfig {
  std::string path;
  std::string text;  // the config file as read (the database keeps it)
  std::string name;
  InfluenceFitOptions fit;
  std::string out;  // resolved constants file
  std::string db;   // resolved; empty: none
  std::vector<CalibrateCurveEntry> curves;
  std::vector<CalibrateContactEntry> contacts;
};

// Reads and validates the config at `path`, the CSVs, fem-reference results and scenes it names.
// Throws InputError naming FILE:LINE and the key (or the named file's own FILE:LINE message).
CalibrateConfig ReadCalibrateConfig(const std::string& path);

}  // namespace railwear::app
