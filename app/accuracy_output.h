// Output of `railwear accuracy` on a contact scene: the terminal table, the CSV and the Pareto
// plot of an AccuracyStudy (accuracy_study.h). Units of the outputs: mm2, MPa, N, ms, MiB, %.
#pragma once

#include <iosfwd>
#include <string>

#include "app/accuracy_study.h"

namespace railwear::app {

// The table for the terminal (mm2, MPa, ms, MiB, %).
std::string FormatAccuracyTable(const AccuracyStudy& study);
// One row per run, then one "reference" row; units in the column names.
void WriteAccuracyCsv(const AccuracyStudy& study, std::ostream& out);
// The Pareto plot: error [%] against time per solve [ms], log-log, one panel per quantity.
// Throws std::runtime_error when gnuplot is missing or fails.
void PlotAccuracy(const AccuracyStudy& study, const std::string& png_path);

}  // namespace railwear::app
