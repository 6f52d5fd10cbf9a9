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
//
// Uncertainty ensembles (issue 19 point 4): an axis can be a distribution instead of values,
//
//   [sweep]
//   samples = 32                 # the ensemble's size (required with a distribution axis)
//   seed = 7                     # default 1
//   sampling = "latin-hypercube" # or "sobol" (wear/ensemble.h); default latin-hypercube
//
//   [[axis]]
//   key = "wear.k"
//   distribution = { kind = "lognormal" }   # median: the base scene's value; sigma_ln: the
//                                           # literature's scatter (kWearCoefficientSigmaLn)
//   [[axis]]
//   key = "traffic[0].friction"
//   distribution = { kind = "uniform", min = 0.3, max = 0.5 }
//   [[axis]]
//   key = "traffic[0].lateral_shift_mm.std"
//   distribution = { kind = "normal", mean = 1.5, std = 0.5, min = 0.0 }  # min/max truncate
//
// All distribution axes together are ONE axis of `samples` rows (a design of that many points,
// drawn by wear/ensemble.h DrawSamples from the seed), placed where the first of them is; each
// row sets every distribution key. The other axes (the curve classes: radius, cant, traffic...)
// multiply it, so every class gets the same samples. A sampled value is written into the line's
// scene (and the manifest) in its shortest round-trip form: the scene reads back the drawn
// double bit for bit. A line of an ensemble has its sample number, and its scene a second header
// line "# railwear ensemble sample S of N (METHOD, seed SEED)".
//
// Rail-life limits (issue 19 point 5, read by `history life`):
//
//   [life]
//   annual_mgt = 25                      # traffic per year: life also in years
//   [[life.limit]]
//   name = "grinding"                    # default "MEASURE VALUE"
//   measure = "w3_mm"                    # kEnsembleMeasures
//   value = 2.0
//   [[life.class]]                       # a curve class's length on the line (line summary)
//   match = "track.radius_m=600"         # the class label (SweepLine::group)
//   length_km = 12.5
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/scene.h"
#include "wear/ensemble.h"

namespace railwear::app {

// One scene key set by a line: its dotted path, the value as TOML text, and where it came from
// ("plan.toml:12" for an axis, "cases.csv:3" for a row of a cases file).
struct SweepOverride {
  std::string key;
  std::string value;
  std::string origin;
  bool sampled = false;  // a value drawn for a distribution axis
};

struct SweepLine {
  int index = 0;
  std::vector<SweepOverride> overrides;  // in axis order
  std::string scene_text;                // the base scene with the overrides, as TOML
  std::string id;                        // "NNNN-HHHHHHHH"
  int sample = -1;                       // the ensemble sample (0-based); -1: no ensemble
  // The curve class: Differences() of the overrides that are not sampled ("(base scene)" when
  // none). The runs of one class form one ensemble for `history bands` and `history life`.
  std::string group;
  // "key=value key=value ..." (the manifest's differences column).
  std::string Differences() const;
};

// The measures of a stored step that ensembles and life limits read: W1/W2/W3 [mm], the worn area
// [mm^2] (StepRecord columns) and the largest RCF damage of the step's "rcf_damage"
// distribution [-] (runs with effect "damage").
inline constexpr std::array<const char*, 5> kEnsembleMeasures = {
    "w1_mm", "w2_mm", "w3_mm", "worn_area_mm2", "rcf_damage"};

struct SweepEnsemble {
  int samples = 0;
  uint64_t seed = 1;
  SamplingMethod method = SamplingMethod::kLatinHypercube;
  std::vector<std::string> keys;                 // the distribution axes' keys, in plan order
  std::vector<SampleDistribution> distributions;  // of each key
  std::vector<std::vector<double>> values;        // [sample][key], as drawn
};

struct LifeLimit {
  std::string name;
  std::string measure;  // one of kEnsembleMeasures
  double value = 0.0;   // in the measure's unit
  std::string origin;   // "plan.toml:LINE"
};

struct LifeClassLength {
  std::string match;  // a SweepLine::group
  double length_km = 0.0;
  std::string origin;
};

struct SweepLife {
  std::vector<LifeLimit> limits;
  std::optional<double> annual_mgt;
  std::vector<LifeClassLength> classes;
};

struct SweepPlan {
  std::string path;        // the plan file as given
  std::string scene_path;  // the base scene, resolved against the plan's folder
  std::string out_dir;     // resolved against the plan's folder
  std::vector<SweepLine> lines;
  std::optional<SweepEnsemble> ensemble;  // when the plan has distribution axes
  SweepLife life;                         // [life]
};

std::string ToString(SamplingMethod method);

// Reads and expands a plan. Throws InputError "FILE:LINE: ..." for a malformed plan (TOML
// syntax, unknown or missing keys, a bad key path, an empty axis, a bad range, a malformed
// cases file, a [[traffic]] entry the base scene lacks, more than kMaxSweepLines lines, a bad
// distribution or [life] table, samples without a distribution axis or none with one) and for
// an unreadable base scene. The lines' scenes are not read yet (SweepLineScene).
SweepPlan LoadSweepPlan(const std::string& path);

// The line's scene, read and validated by the scene reader (ParseScene, relative paths against
// the base scene's folder). Throws InputError naming the plan's file and line, the axis key and
// value, and the scene's own message when the scene rejects the line's values, or when it is not
// a wear scene.
Scene SweepLineScene(const SweepPlan& plan, const SweepLine& line);

// The expected cost of a line's run, in arbitrary units, for ordering the runs (largest first;
// `sweep --mpi`): total MGT x load cases per step x grid cells per contact patch, where
// - load cases per step: per traffic entry, its spread's nodes (quadrature_points, or the
//   piecewise-linear rule's spread_nodes; 11 under the adaptive rule, its typical count, 7 to
//   start and a few refinements; 1 without spread), times
//   the wheelsets of a vehicle entry (4 for a bogie vehicle, 1 for a wheelset) on both rails, or
//   an imported collective's bins;
// - grid cells: CellsPerSemiAxis(accuracy)^2 (the standard preset's for explicit cell sizes).
// A relative estimate only: it ignores the wear rate (the number of steps follows the deepest
// wear per step, so a larger wear coefficient costs more than this says) and the curving solves.
double SweepLineCost(const Scene& scene);

// A plan expands to at most this many lines (a typo in a range is refused, not run).
constexpr int kMaxSweepLines = 100000;

}  // namespace railwear::app
