// `railwear history ...`: the CLI11 wiring and the six readers of a profile-history database.
#include "app/history_command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/gnuplot.h"
#include "app/history_ensemble.h"
#include "app/history_plot.h"
#include "app/number_format.h"
#include "app/paths.h"
#include "app/stored_study.h"
#include "core/numerics/input_error.h"
#include "core/numerics/text_file.h"
#include "core/numerics/units.h"
#include "core/profile/profile_io.h"
#include "profiles_db/profile_store.h"
#include "wear/traffic.h"
#include "wear/wear_measures.h"
#include "wear/wear_simulation.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

// ---------------------------------------------------------------------------------------------
// Opening the database and finding runs and steps; every failure names the file.

// The run's step summaries; InputError when it has none.
std::vector<StepRecord> StepsOrThrow(const ProfileStore& db, const RunInfo& run) {
  std::vector<StepRecord> steps = db.Steps(run.id);
  if (steps.empty()) {
    throw InputError(fmt::format("database '{}': run '{}' has no steps yet", db.path(), run.name));
  }
  return steps;
}

// "0-3, 5, 8-9": the stored step numbers as ranges.
std::string StepRanges(const std::vector<StepRecord>& steps) {
  std::string out;
  for (size_t i = 0; i < steps.size();) {
    size_t j = i;
    while (j + 1 < steps.size() && steps[j + 1].step == steps[j].step + 1) ++j;
    out +=
        (out.empty() ? "" : ", ") + (j == i ? std::to_string(steps[i].step)
                                            : fmt::format("{}-{}", steps[i].step, steps[j].step));
    i = j + 1;
  }
  return out;
}

// The stored step numbered `step`. Steps are addressed by their stored number, never by their
// position in `steps` (a run's steps may have gaps: rows deleted by hand, issue 17); InputError
// (exit 2) naming the run and the steps it has when that number is not stored.
const StepRecord& StepOrThrow(const ProfileStore& db, const RunInfo& run,
                              const std::vector<StepRecord>& steps, int step,
                              const std::string& what) {
  const auto it = std::find_if(steps.begin(), steps.end(),
                               [step](const StepRecord& s) { return s.step == step; });
  if (it != steps.end()) return *it;
  throw InputError(fmt::format(
      "database '{}': run '{}' has no step {} ({}); expected one of its stored steps: {}",
      db.path(), run.name, step, what, StepRanges(steps)));
}

// The rail --rail names; InputError for another name.
RailSide RailOrThrow(const HistoryRailOption& o) {
  if (const auto side = RailSideFromString(o.rail)) return *side;
  throw InputError(
      fmt::format("--rail '{}': expected {}", o.rail, JoinEnumChoices(kRailSideNames, " or ")));
}

// A step's profile of the chosen rail; InputError naming the run when it has no low rail.
Profile LoadRailProfile(const ProfileStore& db, const RunInfo& run, int step, RailSide rail) {
  if (rail == RailSide::kHigh) return db.LoadProfile(run.id, step);
  const std::vector<StepRecord> steps = db.Steps(run.id);
  if (steps.empty() || !steps.front().low_rail) {
    throw InputError(fmt::format(
        "database '{}': run '{}' has one rail only: expected --rail high (or no --rail) for a "
        "single-rail run",
        db.path(), run.name));
  }
  return db.LoadLowRailProfile(run.id, step);
}

// A wearing wheel of a run (co-evolution): its traffic entry and that entry's name.
struct WheelRef {
  int traffic_index = 0;
  std::string name;
  int wheel = 0;  // WheelStepRecord::wheel: 0 an entry's one wheel, >= 1 a vehicle entry's
  bool Is(const WheelStepRecord& w) const {
    return w.traffic_index == traffic_index && w.wheel == wheel;
  }
  // How --wheel names it: the entry's index for an entry's one wheel, else "INDEX:WHEEL".
  std::string Address() const {
    return wheel == 0 ? std::to_string(traffic_index) : fmt::format("{}:{}", traffic_index, wheel);
  }
};

// The wheel --wheel names (a traffic entry's index or name; a vehicle entry's wheel by its name
// "ENTRY / wheelset W high" or "INDEX:WHEEL"); InputError naming the run's wheels.
WheelRef WheelOrThrow(const ProfileStore& db, const RunInfo& run, const std::string& wheel) {
  std::vector<WheelRef> wheels;
  for (const WheelStepRecord& w : db.WheelSteps(run.id)) {
    if (wheels.empty() || !wheels.back().Is(w)) wheels.push_back({w.traffic_index, w.name, w.wheel});
  }
  for (const WheelRef& w : wheels) {
    if (w.name == wheel || w.Address() == wheel) return w;
  }
  std::string known;
  for (const WheelRef& w : wheels) {
    known += fmt::format("{}{} ('{}')", known.empty() ? "" : ", ", w.Address(), w.name);
  }
  throw InputError(fmt::format(
      "database '{}': run '{}' has no wearing wheel '{}'; expected {}", db.path(), run.name, wheel,
      wheels.empty() ? std::string("no --wheel: the run's wheels do not wear (a [[traffic]] entry's "
                                   "wheel_wear makes them)")
                     : "a traffic entry index or name of its wearing wheels: " + known));
}

// --rail and --wheel name different bodies: not both.
void RequireRailOrWheel(const HistoryRailOption& r, const HistoryWheelOption& w) {
  if (!w.wheel.empty() && r.rail != "high") {
    throw InputError(fmt::format("--rail '{}' and --wheel '{}': expected one of the two", r.rail,
                                 w.wheel));
  }
}

// ---------------------------------------------------------------------------------------------
// Tables.

bool IsNumber(const std::string& s) {
  if (s.empty()) return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

}  // namespace

std::string AlignedTable(const std::vector<std::string>& columns,
                         const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> width(columns.size());
  std::vector<bool> numeric(columns.size(), !rows.empty());
  for (size_t c = 0; c < columns.size(); ++c) {
    width[c] = columns[c].size();
    for (const auto& row : rows) {
      width[c] = std::max(width[c], row[c].size());
      if (!IsNumber(row[c]) && row[c] != "NULL" && row[c] != "nan") numeric[c] = false;
    }
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string out;
    for (size_t c = 0; c < cells.size(); ++c) {
      const bool last = c + 1 == cells.size();
      if (c > 0) out += "  ";
      out += numeric[c] ? fmt::format("{:>{}}", cells[c], width[c])
                        : (last ? cells[c] : fmt::format("{:<{}}", cells[c], width[c]));
    }
    return out + "\n";
  };
  std::string out = line(columns);
  std::vector<std::string> rule;
  for (size_t w : width) rule.emplace_back(w, '-');
  out += line(rule);
  for (const auto& row : rows) out += line(row);
  return out;
}

namespace {

// Tab-separated: header line, then one line per row (tabs and newlines in cells become spaces).
std::string TsvTable(const std::vector<std::string>& columns,
                     const std::vector<std::vector<std::string>>& rows) {
  auto line = [](const std::vector<std::string>& cells) {
    std::string out;
    for (size_t c = 0; c < cells.size(); ++c) {
      if (c > 0) out += '\t';
      for (char ch : cells[c]) out += (ch == '\t' || ch == '\n' || ch == '\r') ? ' ' : ch;
    }
    return out + "\n";
  };
  std::string out = line(columns);
  for (const auto& row : rows) out += line(row);
  return out;
}

// ---------------------------------------------------------------------------------------------
// profile: format choice and writers.

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

HistoryProfileFormat ChooseFormat(const HistoryProfileOptions& o) {
  const std::string ext = Lower(fs::path(o.out).extension().string());
  if (!o.format.empty()) {
    const HistoryProfileFormat f = HistoryProfileFormatFromString(o.format);
    // The CSV and BAN writers choose by extension (core/profile/profile_io.h).
    if (!o.out.empty() && f != HistoryProfileFormat::kJson && ext != "." + ToString(f)) {
      throw InputError(
          fmt::format("--out '{}': extension '{}' does not match --format {}; "
                      "expected a file name ending in .{}",
                      o.out, ext, o.format, ToString(f)));
    }
    return f;
  }
  if (o.out.empty()) return HistoryProfileFormat::kCsv;
  if (ext == ".csv" || ext == ".ban" || ext == ".json") {
    return HistoryProfileFormatFromString(ext.substr(1));
  }
  throw InputError(
      fmt::format("--out '{}': cannot tell the format from extension '{}'; expected "
                  ".csv, .ban or .json, or give --format",
                  o.out, ext));
}

nlohmann::json ProfileJson(const ProfileStore& db, const RunInfo& run, const StepRecord& step,
                           const Profile& profile, RailSide rail) {
  nlohmann::json y = nlohmann::json::array(), z = nlohmann::json::array();
  for (const auto& p : profile.points()) {
    y.push_back(p.x() * kToMm);
    z.push_back(p.y() * kToMm);
  }
  return {
      {"database", db.path()},    {"run", run.name},
      {"step", step.step},        {"rail", std::string(ToString(rail))},
      {"passes", step.passes},    {"mgt", step.mgt},
      {"points", profile.size()}, {"frame", "rail frame: y toward the field side, z downward, mm"},
      {"y_mm", std::move(y)},     {"z_mm", std::move(z)}};
}

// ---------------------------------------------------------------------------------------------
// diff.

// A wear measure in mm; "n/a" where the profile does not reach the measuring point (never "nan"),
// and never "-0.0000".
std::string Mm(double metres, int decimals = 4) {
  return std::isfinite(metres) ? FixedNoNegativeZero(metres * kToMm, decimals) : std::string("n/a");
}

}  // namespace

std::string ToString(HistoryProfileFormat format) {
  return std::string(EnumToString(kHistoryProfileFormatNames, format, "csv"));
}

HistoryProfileFormat HistoryProfileFormatFromString(const std::string& text) {
  if (const auto f = EnumFromString(kHistoryProfileFormatNames, text)) return *f;
  throw InputError(fmt::format("--format '{}': expected csv, ban or json", text));
}

void SetupHistory(CLI::App& app) {
  auto common = std::make_shared<HistoryOptions>();
  CLI::App* history = app.add_subcommand(
      "history",
      "Read a profile-history database: runs, steps, profiles, wear, plots, SQL, ensemble bands "
      "and life to wear limits");
  history->require_subcommand(1);
  history->fallthrough();  // --db also after the subcommand
  history->add_option("--db", common->db, "Profile-history database (SQLite)")
      ->capture_default_str();

  history
      ->add_subcommand("runs",
                       "Table of the runs: name, state, created, steps, last MGT, "
                       "program version")
      ->callback([common]() { RunHistoryRuns(*common); });

  history
      ->add_subcommand("calibrations",
                       "Table of the influence-constant calibrations: id, "
                       "name, created, status, conditioning, fitted constants")
      ->callback([common]() { RunHistoryCalibrations(*common); });

  auto steps = std::make_shared<HistoryStepsOptions>();
  CLI::App* steps_cmd = history->add_subcommand(
      "steps", "Table of a run's steps: passes, MGT, worn area, max depth, W1 W2 W3, smoothing");
  steps_cmd->add_option("run", steps->run, "Run name")->required();
  steps_cmd->add_option("--wheel", steps->wheel,
                        "A wearing wheel's steps instead (its traffic entry's index or name)");
  steps_cmd->add_flag("--json", steps->json,
                      "One JSON object on stdout: every step's measures and its warnings");
  steps_cmd->callback([common, steps]() { RunHistorySteps(*common, *steps); });

  auto profile = std::make_shared<HistoryProfileOptions>();
  CLI::App* profile_cmd =
      history->add_subcommand("profile", "A step's rail profile as CSV, MiniProf BAN or JSON");
  profile_cmd->add_option("run", profile->run, "Run name")->required();
  profile_cmd->add_option("--step", profile->step, "Step number (default: the last step)");
  profile_cmd->add_option("--format", profile->format,
                          "csv, ban or json (default: by --out's extension, else csv)");
  profile_cmd->add_option("--out", profile->out, "File to write (default: stdout)");
  profile_cmd->add_option("--rail", profile->rail, "high or low: the rail of a two-rail run")
      ->capture_default_str();
  profile_cmd->add_option("--wheel", profile->wheel,
                          "A wearing wheel's profile instead (its traffic entry's index or name)");
  profile_cmd->callback([common, profile]() { RunHistoryProfile(*common, *profile); });

  auto diff = std::make_shared<HistoryDiffOptions>();
  CLI::App* diff_cmd = history->add_subcommand(
      "diff", "Wear between two steps: worn area, max depth and where, W1 W2 W3");
  diff_cmd->add_option("run", diff->run, "Run name")->required();
  diff_cmd->add_option("A", diff->from_step, "Earlier step")->required();
  diff_cmd->add_option("B", diff->to_step, "Later step")->required();
  diff_cmd->add_flag("--json", diff->json, "One JSON object on stdout");
  diff_cmd->add_option("--rail", diff->rail, "high or low: the rail of a two-rail run")
      ->capture_default_str();
  diff_cmd->add_option("--wheel", diff->wheel,
                       "A wearing wheel's wear instead (its traffic entry's index or name)");
  diff_cmd->callback([common, diff]() { RunHistoryDiff(*common, *diff); });

  auto plot = std::make_shared<HistoryPlotOptions>();
  CLI::App* plot_cmd = history->add_subcommand(
      "plot", "PNGs (gnuplot): profiles by MGT, wear depth, W1 W2 W3 against MGT");
  plot_cmd->add_option("run", plot->run, "Run name")->required();
  plot_cmd->add_option("--out", plot->prefix,
                       "File prefix: PREFIX_profiles.png, _depth.png, _measures.png "
                       "(default: RUN)");
  plot_cmd->callback([common, plot]() { RunHistoryPlot(*common, *plot); });

  auto sql = std::make_shared<HistorySqlOptions>();
  CLI::App* sql_cmd =
      history->add_subcommand("sql", "One read-only SQL statement (schema: profiles_db/SCHEMA.md)");
  sql_cmd->add_option("query", sql->sql, "e.g. \"SELECT step, mgt FROM steps\"")->required();
  sql_cmd->add_flag("--tsv", sql->tsv, "Tab-separated output instead of aligned columns");
  sql_cmd->callback([common, sql]() { RunHistorySql(*common, *sql); });

  SetupHistoryEnsemble(history, common);
}

void RunHistoryRuns(const HistoryOptions& o) {
  const ProfileStore db = OpenExistingStudy(o.db);
  std::vector<std::vector<std::string>> rows;
  for (const auto& run : db.Runs()) {
    const std::vector<StepRecord> steps = db.Steps(run.id);
    rows.push_back({run.name, ToString(run.state), run.created_utc, std::to_string(steps.size()),
                    steps.empty() ? std::string("NULL") : fmt::format("{:.4f}", steps.back().mgt),
                    run.program_version});
  }
  std::cout << AlignedTable(
      {"name", "state", "created_utc", "steps", "last_MGT", "program_version"}, rows);
  std::cerr << fmt::format("railwear: {} run(s) in {}\n", rows.size(), db.path());
}

void RunHistoryCalibrations(const HistoryOptions& o) {
  const ProfileStore db = OpenExistingStudy(o.db);
  std::vector<std::vector<std::string>> rows;
  for (const auto& c : db.Calibrations()) {
    // "c_f 1.05 +- 0.001, c_z ..." from the stored constants (calibrate_command.cpp writes it).
    std::string fitted;
    const nlohmann::json j = nlohmann::json::parse(c.constants_json, nullptr, false);
    if (j.is_object() && j.contains("constants") && j["constants"].is_array()) {
      for (const auto& k : j["constants"]) {
        if (!k.is_object() || !k.contains("name") || !k.contains("value")) continue;
        fitted += fmt::format("{}{} {:.4g}", fitted.empty() ? "" : ", ",
                              k["name"].get<std::string>(), k["value"].get<double>());
        if (k.contains("standard_error") && k["standard_error"].is_number()) {
          fitted += fmt::format(" +- {:.2g}", k["standard_error"].get<double>());
        }
      }
    }
    rows.push_back({std::to_string(c.id), c.name, c.created_utc, c.status,
                    c.well_conditioned ? "yes" : "no", fitted.empty() ? "NULL" : fitted,
                    c.program_version});
  }
  std::cout << AlignedTable(
      {"id", "name", "created_utc", "status", "well_conditioned", "fitted", "program_version"},
      rows);
  std::cerr << fmt::format("railwear: {} calibration(s) in {}\n", rows.size(), db.path());
}

namespace {

// A rate cell [mm/MGT]; NULL for the first step and where no traffic passed.
std::string RateCell(double mm_per_mgt) {
  return std::isfinite(mm_per_mgt) ? FixedNoNegativeZero(mm_per_mgt, 4) : std::string("NULL");
}

// One rail's measure cells of step k and its W2 / W3 rates since step k - 1.
std::vector<std::string> MeasureCells(const std::vector<StepRecord>& steps, size_t k) {
  const StepRecord& st = steps[k];
  const WearRates rate =
      k == 0 ? WearRates{std::nan(""), std::nan("")} : RatesBetween(steps[k - 1], st);
  return {FixedNoNegativeZero(st.worn_area_mm2, 4),
          FixedNoNegativeZero(st.max_depth_mm, 4),
          FixedNoNegativeZero(st.max_depth_y_mm, 3),
          FixedNoNegativeZero(st.w1_mm, 4),
          FixedNoNegativeZero(st.w2_mm, 4),
          FixedNoNegativeZero(st.w3_mm, 4),
          fmt::format("{:.3e}", st.smoothing_area_error + 0.0),  // + 0.0: -0 prints as 0
          RateCell(rate.w2_mm_per_mgt),
          RateCell(rate.w3_mm_per_mgt)};
}

// `history steps RUN --json`: the measures of each step (high or only rail; the low rail's under
// "low_rail"), the W2/W3 rates from the previous step (null for step 0 and where MGT did not
// grow), and the step's stored warnings.
nlohmann::json StepsJson(const ProfileStore& db, const RunInfo& run,
                         const std::vector<StepRecord>& steps, const std::vector<StepRecord>& low) {
  auto rate = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  auto measures = [&](const std::vector<StepRecord>& rail, size_t k) {
    const StepRecord& st = rail[k];
    const WearRates r =
        k == 0 ? WearRates{std::nan(""), std::nan("")} : RatesBetween(rail[k - 1], st);
    return nlohmann::json{{"worn_area_mm2", st.worn_area_mm2 + 0.0},
                          {"max_depth_mm", st.max_depth_mm + 0.0},
                          {"max_depth_y_mm", st.max_depth_y_mm + 0.0},
                          {"w1_mm", st.w1_mm + 0.0},
                          {"w2_mm", st.w2_mm + 0.0},
                          {"w3_mm", st.w3_mm + 0.0},
                          {"smoothing_area_error", st.smoothing_area_error + 0.0},
                          {"w2_mm_per_mgt", rate(r.w2_mm_per_mgt)},
                          {"w3_mm_per_mgt", rate(r.w3_mm_per_mgt)}};
  };
  nlohmann::json out = {{"database", db.path()},
                        {"run", run.name},
                        {"state", ToString(run.state)},
                        {"schema_version", db.SchemaVersion()},
                        {"steps", nlohmann::json::array()}};
  for (size_t k = 0; k < steps.size(); ++k) {
    nlohmann::json j = {{"step", steps[k].step}, {"passes", steps[k].passes},
                        {"mgt", steps[k].mgt + 0.0}};
    j.update(measures(steps, k));
    if (!low.empty()) j["low_rail"] = measures(low, k);
    j["warnings"] = nlohmann::json::array();
    for (const StepWarningRecord& w : steps[k].warnings) {
      j["warnings"].push_back({{"kind", w.kind}, {"message", w.message}});
    }
    out["steps"].push_back(std::move(j));
  }
  return out;
}

}  // namespace

namespace {

// `history steps RUN --wheel ENTRY`: the wheel's measures per stored step.
void PrintWheelSteps(const ProfileStore& db, const RunInfo& run, const std::string& wheel) {
  const WheelRef ref = WheelOrThrow(db, run, wheel);
  const std::vector<StepRecord> steps = db.Steps(run.id);
  std::vector<std::vector<std::string>> rows;
  for (const WheelStepRecord& w : db.WheelSteps(run.id)) {
    if (!ref.Is(w)) continue;
    const auto st = std::find_if(steps.begin(), steps.end(),
                                 [&](const StepRecord& r) { return r.step == w.step; });
    if (st == steps.end()) continue;
    const auto flange = [](const std::optional<double>& mm) {
      return mm ? FixedNoNegativeZero(*mm, 3) : std::string("NULL");
    };
    rows.push_back({std::to_string(w.step), fmt::format("{:.6g}", st->passes),
                    FixedNoNegativeZero(st->mgt, 4), FixedNoNegativeZero(w.worn_area_mm2, 4),
                    FixedNoNegativeZero(w.max_depth_mm, 4),
                    FixedNoNegativeZero(w.max_depth_y_mm, 3), flange(w.flange_height_mm),
                    flange(w.flange_thickness_mm), flange(w.flange_slope_mm),
                    fmt::format("{:.3e}", w.smoothing_area_error + 0.0)});
  }
  std::cout << AlignedTable({"step", "passes", "MGT", "worn_area_mm2", "max_depth_mm", "at_y_mm",
                             "Sh_mm", "Sd_mm", "qR_mm", "smoothing_area_error"},
                            rows);
  std::cerr << fmt::format(
      "railwear: run '{}' ({}), {} step(s), wheel of traffic entry {} ('{}'; wheel profile frame), "
      "in {}\n",
      run.name, ToString(run.state), rows.size(), ref.traffic_index, ref.name, db.path());
}

}  // namespace

void RunHistorySteps(const HistoryOptions& o, const HistoryStepsOptions& s) {
  const ProfileStore db = OpenExistingStudy(o.db);
  const RunInfo run = FindRunOrThrow(db, s.run);
  if (!s.wheel.empty() && s.json) {
    throw InputError(
        "history steps: --json with --wheel: expected one of them (the JSON holds the rail's "
        "steps; a wheel's are the table of --wheel)");
  }
  if (!s.wheel.empty()) return PrintWheelSteps(db, run, s.wheel);
  const std::vector<StepRecord> steps = db.Steps(run.id);
  const std::vector<StepRecord> low = LowRailSteps(steps);
  if (s.json) {
    std::cout << StepsJson(db, run, steps, low).dump(2) << "\n";
    return;
  }
  std::vector<std::string> columns = {
      "step",  "passes", "MGT",   "worn_area_mm2",        "max_depth_mm",  "at_y_mm",
      "W1_mm", "W2_mm",  "W3_mm", "smoothing_area_error", "W2_mm_per_MGT", "W3_mm_per_MGT"};
  if (!low.empty()) {
    for (const std::string& c : std::vector<std::string>(columns.begin() + 3, columns.end())) {
      columns.push_back("low_" + c);
    }
  }
  std::vector<std::vector<std::string>> rows;
  for (size_t k = 0; k < steps.size(); ++k) {
    const StepRecord& st = steps[k];
    std::vector<std::string> row = {std::to_string(st.step), fmt::format("{:.6g}", st.passes),
                                    FixedNoNegativeZero(st.mgt, 4)};
    for (std::string& cell : MeasureCells(steps, k)) row.push_back(std::move(cell));
    if (!low.empty()) {
      for (std::string& cell : MeasureCells(low, k)) row.push_back(std::move(cell));
    }
    rows.push_back(std::move(row));
  }
  std::cout << AlignedTable(columns, rows);
  std::cerr << fmt::format("railwear: run '{}' ({}), {} step(s){}, in {}\n", run.name,
                           ToString(run.state), rows.size(),
                           low.empty() ? "" : ", high and low rail (low_*)", db.path());
  // The steps' stored warnings (schema 8) on stderr, so that stdout stays the table:
  // "railwear: step N warning KIND: MESSAGE" (--json has them on stdout).
  for (const StepRecord& st : steps) {
    for (const StepWarningRecord& w : st.warnings) {
      std::cerr << fmt::format("railwear: step {} warning {}: {}\n", st.step, w.kind, w.message);
    }
  }
  const std::vector<WheelStepRecord> wheels = db.WheelSteps(run.id);
  if (!wheels.empty()) {
    std::cerr << fmt::format("railwear: its wheels wear too: `history steps '{}' --wheel ENTRY`",
                             run.name);
    std::optional<WheelRef> last;
    for (const WheelStepRecord& w : wheels) {
      if (last && last->Is(w)) continue;
      const WheelRef ref{w.traffic_index, w.name, w.wheel};
      std::cerr << fmt::format("{} {} ('{}')", last ? "," : ", ENTRY:", ref.Address(), w.name);
      last = ref;
    }
    std::cerr << "\n";
  }
}

void RunHistoryProfile(const HistoryOptions& o, const HistoryProfileOptions& p) {
  const HistoryProfileFormat format = ChooseFormat(p);  // before touching the database
  const ProfileStore db = OpenExistingStudy(o.db);
  const RunInfo run = FindRunOrThrow(db, p.run);
  const std::vector<StepRecord> steps = StepsOrThrow(db, run);
  const int step_number = p.step.value_or(steps.back().step);
  const StepRecord& step = StepOrThrow(db, run, steps, step_number, "--step");
  RequireRailOrWheel(p, p);
  const RailSide rail = RailOrThrow(p);
  std::optional<WheelRef> wheel;
  if (!p.wheel.empty()) {
    wheel = WheelOrThrow(db, run, p.wheel);
    if (format == HistoryProfileFormat::kBan) {
      throw InputError(fmt::format(
          "--wheel '{}' with the BAN format: expected csv or json (MiniProf .ban is a rail "
          "profile format)",
          p.wheel));
    }
  }
  const Profile profile = wheel ? db.LoadWheelProfile(run.id, step_number, wheel->traffic_index, wheel->wheel)
                                : LoadRailProfile(db, run, step_number, rail);

  if (format == HistoryProfileFormat::kJson) {
    nlohmann::json j = ProfileJson(db, run, step, profile, rail);
    if (wheel) {
      j.erase("rail");
      j["wheel"] = {{"traffic_index", wheel->traffic_index}, {"traffic", wheel->name}};
      if (wheel->wheel != 0) j["wheel"]["wheel"] = wheel->wheel;  // a vehicle entry's wheel
      j["frame"] = "wheel profile frame: y lateral (as the rail's), z toward the rail, mm";
    }
    const std::string text = j.dump(1) + "\n";
    if (p.out.empty()) {
      std::cout << text;
    } else {
      std::ofstream out(p.out);
      out << text;
      if (!out) throw InputError(fmt::format("--out '{}': cannot write the file", p.out));
    }
  } else if (!p.out.empty()) {
    WriteProfileFile(profile, p.out);
  } else {
    // To stdout through the file writer, so stdout and --out hold the same bytes.
    const ScopedTempDir tmp("railwear-profile");
    const fs::path file =
        tmp.path() / fmt::format("{}_step{}.{}", run.name, step_number, ToString(format));
    WriteProfileFile(profile, file.string());
    std::cout << ReadTextFile(file.string()).value_or("");
  }
  std::cerr << fmt::format("railwear: run '{}' step {}{} ({:.4f} MGT), {} points{}\n", run.name,
                           step_number,
                           wheel ? fmt::format(" wheel of '{}'", wheel->name)
                                 : std::string(rail == RailSide::kLow ? " low rail" : ""),
                           step.mgt,
                           profile.size(), p.out.empty() ? std::string() : ", written to " + p.out);
}

void RunHistoryDiff(const HistoryOptions& o, const HistoryDiffOptions& d) {
  const ProfileStore db = OpenExistingStudy(o.db);
  const RunInfo run = FindRunOrThrow(db, d.run);
  const std::vector<StepRecord> steps = StepsOrThrow(db, run);
  const StepRecord& a = StepOrThrow(db, run, steps, d.from_step, "step A");
  const StepRecord& b = StepOrThrow(db, run, steps, d.to_step, "step B");
  RequireRailOrWheel(d, d);
  const RailSide rail = RailOrThrow(d);
  // A wearing wheel (co-evolution): worn area and max depth along its profile, no W1/W2/W3.
  std::optional<WheelRef> wheel;
  if (!d.wheel.empty()) wheel = WheelOrThrow(db, run, d.wheel);
  WearMeasureOptions options;
  WearMeasures m;
  if (wheel) {
    const Profile pa = db.LoadWheelProfile(run.id, a.step, wheel->traffic_index, wheel->wheel);
    const Profile pb = db.LoadWheelProfile(run.id, b.step, wheel->traffic_index, wheel->wheel);
    // From step 0 (the wheel as given, not resampled) as the run measured it: against the
    // unworn wheel resampled as the worn one was (wear/wear_simulation.h).
    m = a.step == steps.front().step ? CompareWheelWithUnworn(pa, pb)
                                     : CompareWheelProfiles(pa, pb, options);
  } else {
    const Profile unworn = LoadRailProfile(db, run, steps.front().step, rail);
    const Profile pa = LoadRailProfile(db, run, a.step, rail);
    const Profile pb = LoadRailProfile(db, run, b.step, rail);
    options.gauge = MakeWearGauge(unworn, options.side_wear_depth_m);
    m = CompareProfiles(pa, pb, options);
  }

  if (d.json) {
    // NaN (a line that misses a profile) is written as null.
    nlohmann::json j = {{"database", db.path()},
                        {"run", run.name},
                        {"from", {{"step", a.step}, {"passes", a.passes}, {"mgt", a.mgt}}},
                        {"to", {{"step", b.step}, {"passes", b.passes}, {"mgt", b.mgt}}},
                        {"worn_area_mm2", m.worn_area_m2 * kToMm2},
                        {"max_depth_mm", m.max_depth_m * kToMm},
                        {"max_depth_s_mm", m.max_depth_s_m * kToMm},
                        {"max_depth_y_mm", m.max_depth_y_m * kToMm},
                        {"max_depth_z_mm", m.max_depth_z_m * kToMm},
                        {"unmatched_samples", m.unmatched_samples}};
    if (wheel) {
      j["wheel"] = {{"traffic_index", wheel->traffic_index}, {"traffic", wheel->name}};
      if (wheel->wheel != 0) j["wheel"]["wheel"] = wheel->wheel;  // a vehicle entry's wheel
    } else {
      j["rail"] = std::string(ToString(rail));
      j["w1_mm"] = m.vertical_wear_m * kToMm;
      j["w2_mm"] = m.side_wear_m * kToMm;
      j["w3_mm"] = m.wear_45_m * kToMm;
    }
    std::cout << j.dump(2) << "\n";
  } else {
    std::string out;
    out += fmt::format("run           {}\n", run.name);
    if (wheel) {
      out += fmt::format("wheel         of '{}' (traffic entry {}), wheel profile frame\n",
                         wheel->name, wheel->traffic_index);
    } else if (rail == RailSide::kLow) {
      out += "rail          low\n";
    }
    out += fmt::format("from step     {} ({:.4f} MGT, {:.6g} passes)\n", a.step, a.mgt, a.passes);
    out += fmt::format("to step       {} ({:.4f} MGT, {:.6g} passes)\n", b.step, b.mgt, b.passes);
    out += fmt::format("worn area     {:.4f} mm^2\n", m.worn_area_m2 * kToMm2);
    out += fmt::format("max depth     {} mm at s = {} mm (y = {}, z = {} mm) on step {}\n",
                       Mm(m.max_depth_m), Mm(m.max_depth_s_m, 2), Mm(m.max_depth_y_m, 2),
                       Mm(m.max_depth_z_m, 2), a.step);
    if (!wheel) {
      out += fmt::format("W1 vertical   {} mm (centre line)\n", Mm(m.vertical_wear_m));
      out += fmt::format("W2 side       {} mm (14 mm below the top of rail)\n", Mm(m.side_wear_m));
      out += fmt::format("W3 45 deg     {} mm (gauge corner)\n", Mm(m.wear_45_m));
    }
    std::cout << out;
  }
  if (m.unmatched_samples > 0) {
    std::cerr << fmt::format(
        "railwear: {} of {} depth samples found no worn surface within {} mm "
        "of step {} (left out of area and max depth)\n",
        m.unmatched_samples, m.s_m.size(), options.max_normal_distance_m * kToMm, a.step);
  }
}

void RunHistoryPlot(const HistoryOptions& o, const HistoryPlotOptions& p) {
  RequireGnuplotFor("history plot", "use `history profile` / `history sql` for the numbers");
  const ProfileStore db = OpenExistingStudy(o.db);
  const RunInfo run = FindRunOrThrow(db, p.run);
  const std::vector<StepRecord> summaries = StepsOrThrow(db, run);
  std::vector<StepRecord> steps;
  steps.reserve(summaries.size());
  for (const auto& s : summaries) steps.push_back(db.LoadStep(run.id, s.step));
  const std::string prefix = p.prefix.empty() ? run.name : p.prefix;
  for (const auto& file : PlotHistory(run.name, steps, prefix)) {
    std::cerr << fmt::format("railwear: wrote {}\n", file);
  }
}

void RunHistorySql(const HistoryOptions& o, const HistorySqlOptions& s) {
  const ProfileStore db = OpenExistingStudy(o.db);
  const QueryResult r = db.Query(s.sql);
  std::cout << (s.tsv ? TsvTable(r.columns, r.rows) : AlignedTable(r.columns, r.rows));
  std::cerr << fmt::format("railwear: {} row(s)\n", r.rows.size());
}

}  // namespace railwear::app
