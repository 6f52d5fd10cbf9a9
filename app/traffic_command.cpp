// `railwear traffic import`: MBS time history -> load collective file.
#include "app/traffic_command.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/load_collective_file.h"
#include "app/toml_fields.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace {

// The option values in the CLI's units, converted to SI after parsing.
struct BinOptions {
  double y_mm = 0.5;
  double yaw_mrad = 0.5;
  double q_kN = 5.0;
  double v_m_s = 2.0;
  double mu = 0.05;
  double xi = 0.001;
};

}  // namespace

void SetupTraffic(CLI::App& app) {
  CLI::App* traffic = app.add_subcommand("traffic", "Traffic for wear studies: MBS import");
  traffic->require_subcommand(1);

  auto options = std::make_shared<TrafficImportOptions>();
  auto bins = std::make_shared<BinOptions>();
  CLI::App* import_cmd = traffic->add_subcommand(
      "import",
      "Bin an MBS time history (CSV, one row per wheel per time step) into a load collective "
      "(docs/mbs_import.md)");
  import_cmd->add_option("file", options->input, "MBS time-history CSV")->required();
  import_cmd->add_option("--out", options->output, "Load collective file to write (TOML)")
      ->required();
  import_cmd->add_flag("--force", options->force, "Overwrite an existing --out file");
  import_cmd
      ->add_option("--bin-y-mm", bins->y_mm,
                   "Bin width of the wheelset lateral "
                   "displacement [mm]")
      ->capture_default_str();
  import_cmd->add_option("--bin-yaw-mrad", bins->yaw_mrad, "Bin width of the wheelset yaw [mrad]")
      ->capture_default_str();
  import_cmd->add_option("--bin-q-kN", bins->q_kN, "Bin width of the wheel load Q [kN]")
      ->capture_default_str();
  import_cmd->add_option("--bin-v-m-s", bins->v_m_s, "Bin width of the speed [m/s]")
      ->capture_default_str();
  import_cmd->add_option("--bin-mu", bins->mu, "Bin width of the friction coefficient")
      ->capture_default_str();
  import_cmd->add_option("--bin-xi", bins->xi, "Bin width of the longitudinal creepage")
      ->capture_default_str();
  import_cmd->callback([options, bins]() {
    TrafficImportOptions o = *options;
    o.widths.wheelset_y_m = bins->y_mm * kMm;
    o.widths.yaw_rad = bins->yaw_mrad * 1e-3;
    o.widths.vertical_force_N = bins->q_kN * 1e3;
    o.widths.speed_m_s = bins->v_m_s;
    o.widths.friction = bins->mu;
    o.widths.creepage_x = bins->xi;
    RunTrafficImport(o);
  });
}

void RunTrafficImport(const TrafficImportOptions& o) {
  ValidateBinWidths(o.widths);
  if (!o.force && std::filesystem::exists(o.output)) {
    throw InputError(
        fmt::format("{}: file exists; traffic import overwrites it only with --force", o.output));
  }
  const MbsTimeHistory history = ReadMbsTimeHistory(o.input);
  const LoadCollective collective = BinLoadCollective(history, o.widths);
  WriteOutputFile(o.output, LoadCollectiveFileText(collective, RAILWEAR_VERSION),
                  "the load collective file");
  // The file must read back as a scene will read it.
  const LoadCollective back = ReadLoadCollective(o.output);
  if (back.entries.size() != collective.entries.size()) {
    throw std::runtime_error(fmt::format("{}: reads back with {} entries, not {}", o.output,
                                         back.entries.size(), collective.entries.size()));
  }

  const std::string_view unit = collective.weight_unit == WeightUnit::kPasses ? "passes" : "m run";
  std::cout << fmt::format("read {} rows from {}", collective.rows_read, o.input);
  if (collective.rows_zero_weight > 0) {
    std::cout << fmt::format(" ({} of weight 0, not binned)", collective.rows_zero_weight);
  }
  std::cout << "\n";
  for (const RailSide rail : {RailSide::kHigh, RailSide::kLow}) {
    const double total =
        rail == RailSide::kHigh ? collective.total_weight_high : collective.total_weight_low;
    std::cout << fmt::format("{:<4} rail: {:>4} bins, weight {:.6g} {}\n", ToString(rail),
                             EntryCount(collective, rail), total, unit);
  }
  std::cout << fmt::format("wrote {} ({} [[traffic]] entries)\n", o.output,
                           collective.entries.size());
}

}  // namespace railwear::app
