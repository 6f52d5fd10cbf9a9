// The outputs of `railwear calibrate`: the text report, the provenance header of the constants
// file, the JSON (every number, every point's residual, both Ceres reports), the residual CSV
// and the study-database record with every input verbatim. Formatting only: the fit is done.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "app/calibrate_config.h"
#include "calibration/influence_fit.h"
#include "profiles_db/profile_store.h"

namespace railwear::app {

// The report on stdout: data, fit, status, constants with standard errors, correlations,
// conditioning, residuals per curve and per contact result; Ceres's brief report (and the full
// one when `verbose`).
std::string CalibrateReportText(const CalibrateConfig& config, const InfluenceFitSummary& s,
                                bool verbose);

// The comment lines atop the constants file written to `out`: how to use it, the config and
// data (paths relative to the file's folder), `created` (UTC), status and the fitted constants
// with their standard errors, the warnings. InfluenceConstantsFileText adds the table.
std::string CalibrateConstantsHeader(const CalibrateConfig& config, const InfluenceFitSummary& s,
                                     const std::string& out, const std::string& created);

// The time now as "YYYY-MM-DDTHH:MM:SSZ".
std::string NowUtc();

// Everything as JSON; `out` and `db` are the files written (empty: none, null in the JSON).
nlohmann::json CalibrateJson(const CalibrateConfig& config, const InfluenceFitSummary& s,
                             const std::string& out, const std::string& db);

// One row per curve point: distance [mm], data and model before/after [nm/N], residuals.
std::string CalibratePointCsv(const InfluenceFitSummary& s);

// The database record: the fit's numbers as JSON, the constants file text `constants_toml`, and
// every input verbatim (config, CSVs, fem-reference results, scenes and the profile files they
// name). Throws InputError when an input can no longer be read.
CalibrationRecord CalibrateRecord(const CalibrateConfig& config, const InfluenceFitSummary& s,
                                  const std::string& constants_toml);

}  // namespace railwear::app
