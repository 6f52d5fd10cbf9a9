// The text `railwear fem-reference` prints on stdout: per experiment a summary (body, mesh,
// solves; for a contact case its mesh levels), the comparisons of displacement curves with a
// reference (the half-space, or another experiment), and the lines of --report-only.
// Distances in the text are in mm, displacements in nm/N, pressures in MPa.
#pragma once

#include <string>

#include "app/fem_contact_result.h"
#include "app/fem_reference_config.h"
#include "calibration/curve_comparison.h"

namespace railwear::app {

// Comparison of `curves` with `reference` (titled `title`; its values named `ref_name` in the
// table heads): per curve the offset fitted over the experiment's compare range and the largest
// raw and offset-removed errors there, then a table at a few distances.
std::string FemComparisonText(const FemExperiment& e, const DisplacementCurves& curves,
                              const CurveReference& reference, const std::string& title,
                              const std::string& ref_name);

// The summary of a displacement experiment that ran with `jobs` ccx solves at once.
std::string FemDisplacementSummaryText(const FemExperiment& e, const FemDisplacementResult& r,
                                       int jobs);

// The summary of a contact experiment: the case, the model, one row per mesh level.
std::string FemContactSummaryText(const FemExperiment& e, const FemContactResult& r);

// --report-only for a contact experiment: the measures of its result file, one line.
std::string FemContactTargetText(const FemExperiment& e, const FemContactTarget& t);

}  // namespace railwear::app
