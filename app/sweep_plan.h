// Sweep plans (issue 19): a base wear scene and axes of values for scene keys, expanded into the
// lines of a manifest, one wear run each (app/sweep_command.h runs them).
//
// A plan (TOML; paths relative to the plan file):
//
//   [sweep]
//   scene = "base.toml"          # the base wear scene (required)
//   out_dir = "runs"             # each run's database and scene go here (default: PLAN-STEM_runs)
//
//   [[axis]]                     # a list of values for one scene key
//   key = "wear.k"               # dotted key path; [[traffic]] entries as traffic[0].friction
//   values = [1.0e-4, 2.0e-4]
//
//   [[axis]]                     # a range: stop included; step, or count evenly spaced values
//   key = "track.radius_m"
//   range = { start = 300, stop = 900, step = 300 }
//
//   [[axis]]                     # a file of cases: a header of keys, one case per row
//   cases = "cases.csv"          # cells: TOML values (0.3, "x") or plain strings, no commas
//
// The lines are the Cartesian product of the axes, the first axis varying slowest (a cases file
// is one axis: its rows). A line's scene is the base scene with its overrides set (a key the base
// lacks is added; a [[traffic]] entry must exist), written back as TOML and read by the normal
// scene reader: a value the scene does not accept is the scene's error, prefixed with the plan
// file and line of the axis (or the cases file and row), the key and the value (exit 2).
//
// Each line has a stable run id "NNNN-HHHHHHHH": its index and a hash (FNV-1a, 32 bits) of its
// whole scene text, so the same id always means the same scene.
#pragma once

#include <string>
#include <vector>

#include "app/scene.h"

namespace railwear::app {

// One scene key set by a line: its dotted path, the value as TOML text, and where it came from
// ("plan.toml:12" for an axis, "cases.csv:3" for a row of a cases file).
struct SweepOverride {
  std::string key;
  std::string value;
  std::string origin;
};

struct SweepLine {
  int index = 0;
  std::vector<SweepOverride> overrides;  // in axis order
  std::string scene_text;                // the base scene with the overrides, as TOML
  std::string id;                        // "NNNN-HHHHHHHH"
  // "key=value key=value ..." (the manifest's differences column).
  std::string Differences() const;
};

struct SweepPlan {
  std::string path;        // the plan file as given
  std::string scene_path;  // the base scene, resolved against the plan's folder
  std::string out_dir;     // resolved against the plan's folder
  std::vector<SweepLine> lines;
};

// Reads and expands a plan. Throws InputError "FILE:LINE: ..." for a malformed plan (TOML
// syntax, unknown or missing keys, a bad key path, an empty axis, a bad range, a malformed
// cases file, a [[traffic]] entry the base scene lacks, more than kMaxSweepLines lines) and for
// an unreadable base scene. The lines' scenes are not read yet (SweepLineScene).
SweepPlan LoadSweepPlan(const std::string& path);

// The line's scene, read and validated by the scene reader (ParseScene, relative paths against
// the base scene's folder). Throws InputError naming the plan's file and line, the axis key and
// value, and the scene's own message when the scene rejects the line's values, or when it is not
// a wear scene.
Scene SweepLineScene(const SweepPlan& plan, const SweepLine& line);

// The expected cost of a line's run, in arbitrary units, for ordering the runs (largest first;
// `sweep --mpi`): total MGT x load cases per step x grid cells per contact patch, where
// - load cases per step: per traffic entry, its spread's nodes (quadrature_points; 9 under the
//   adaptive rule, its typical count, 5 to start and a few refinements; 1 without spread), times
//   the wheelsets of a vehicle entry (4 for a bogie vehicle, 1 for a wheelset) on both rails, or
//   an imported collective's bins;
// - grid cells: CellsPerSemiAxis(accuracy)^2 (the standard preset's for explicit cell sizes).
// A relative estimate only: it ignores the wear rate (the number of steps follows the deepest
// wear per step, so a larger wear coefficient costs more than this says) and the curving solves.
double SweepLineCost(const Scene& scene);

// A plan expands to at most this many lines (a typo in a range is refused, not run).
constexpr int kMaxSweepLines = 100000;

}  // namespace railwear::app
