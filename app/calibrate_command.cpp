// `railwear calibrate`: the outline. Config (calibrate_config.h) -> FitInfluenceConstants ->
// outputs (calibrate_output.h, influence_constants_file.h). See calibrate_command.h.
#include "app/calibrate_command.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/calibrate_config.h"
#include "app/calibrate_output.h"
#include "app/influence_constants_file.h"
#include "app/toml_fields.h"
#include "calibration/influence_fit.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"

namespace railwear::app {

namespace {

// The JSON path and value of the first non-finite number in `j` ("" when all are finite).
std::string FirstNonFinite(const nlohmann::json& j, const std::string& path) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    return fmt::format("{} = {}", path.empty() ? "/" : path, j.get<double>());
  }
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      if (std::string b = FirstNonFinite(v, path + "/" + k); !b.empty()) return b;
    }
  }
  if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) {
      if (std::string b = FirstNonFinite(j[i], fmt::format("{}/{}", path, i)); !b.empty()) return b;
    }
  }
  return "";
}

}  // namespace

void SetupCalibrate(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit the influence constants c_f, c_z, c_s (seed eq. 4) to displacement curves and contact "
      "results; write an influence-constants TOML for scenes");
  cmd->add_option("config", o->config,
                  "Calibration config (TOML; see `railwear calibrate "
                  "--help` and the README)")
      ->required();
  cmd->add_option("--out", o->out,
                  "Constants file to write (default: [calibration] out, else "
                  "CONFIG-STEM_constants.toml beside the config)");
  cmd->add_option("--db", o->db,
                  "Store the calibration and its inputs in this study database "
                  "(default: [calibration] db, if any)");
  cmd->add_option("--json", o->json, "Write everything as JSON to FILE, or '-' for stdout");
  cmd->add_option("--csv", o->csv, "Write every point's residual before and after to FILE");
  cmd->add_flag("--verbose", o->verbose, "Print Ceres's full report");
  cmd->callback([o]() { RunCalibrate(*o); });
}

void RunCalibrate(const CalibrateOptions& o) {
  const CalibrateConfig config = ReadCalibrateConfig(o.config);
  const std::string out = o.out ? *o.out : config.out;
  const std::string db = o.db ? *o.db : config.db;
  if (o.json && *o.json != "-" && o.csv && *o.json == *o.csv) {
    throw InputError(fmt::format("--json and --csv both name '{}'; expected two files", *o.csv));
  }

  InfluenceFitData data;
  for (const CalibrateCurveEntry& e : config.curves) data.curves.push_back(e.data);
  for (const CalibrateContactEntry& e : config.contacts) data.contacts.push_back(e.target);
  std::cerr << fmt::format(
      "railwear: fitting {} constant(s) to {} curve file(s) and {} contact "
      "result(s)...\n",
      config.fit.fit.size() * (config.fit.separate_bodies ? 2 : 1), config.curves.size(),
      config.contacts.size());
  const InfluenceFitSummary s = FitInfluenceConstants(data, config.fit);

  const bool json_stdout = o.json && *o.json == "-";
  std::ostream& report = json_stdout ? std::cerr : std::cout;
  if (s.status == InfluenceFitStatus::kFailure) {
    report << CalibrateReportText(config, s, o.verbose);
    throw std::runtime_error("calibration failed: " + s.message + "; nothing written");
  }
  for (const auto& w : s.warnings) std::cerr << "railwear: warning: " << w << "\n";
  // No output carries an infinity or NaN (issue 17): every number of the report is in the JSON,
  // checked here before anything is written (exit 1: the inputs passed their checks).
  if (const std::string bad = FirstNonFinite(CalibrateJson(config, s, out, db), ""); !bad.empty()) {
    throw std::runtime_error(fmt::format(
        "calibration failed: the fit produced a non-finite value ({}); nothing written: check "
        "the ranges of the curve files' and contact results' values",
        bad));
  }

  // The constants file, checked by reading it back as a scene would.
  const std::string created = NowUtc();
  const std::string toml =
      InfluenceConstantsFileText(CalibrateConstantsHeader(config, s, out, created), s.fitted);
  WriteInfluenceConstantsFile(out, toml, s.fitted);
  report << CalibrateReportText(config, s, o.verbose);
  report << fmt::format("wrote {}\n", out);

  if (o.csv) {
    WriteOutputFile(*o.csv, CalibratePointCsv(s), "the residual CSV");
    report << fmt::format("wrote {}\n", *o.csv);
  }
  if (!db.empty()) {
    const CalibrationRecord r = CalibrateRecord(config, s, toml);
    ProfileStore store = ProfileStore::Open(db);
    const int64_t id = store.AddCalibration(r);
    report << fmt::format("stored calibration {} in {}\n", id, db);
  }
  if (o.json) {
    const std::string text = CalibrateJson(config, s, out, db).dump(2) + "\n";
    if (json_stdout) {
      std::cout << text << std::flush;
    } else {
      WriteOutputFile(*o.json, text, "the JSON");
      report << fmt::format("wrote {}\n", *o.json);
    }
  }
  if (s.status == InfluenceFitStatus::kNoConvergence) {
    throw std::runtime_error("Ceres stopped without converging (" + s.message +
                             "); the outputs were written from the last iterate");
  }
}

}  // namespace railwear::app
