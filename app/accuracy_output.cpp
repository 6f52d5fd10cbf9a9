// `railwear accuracy` on a contact scene: the terminal table, the CSV and the Pareto plot.
#include "app/accuracy_output.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/gnuplot.h"
#include "app/paths.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

constexpr double kToMiB = 1.0 / (1024.0 * 1024.0);
constexpr double kToPercent = 100.0;
// Errors below this are drawn at it on the plot's log axis [%].
constexpr double kPlotErrorFloor_pct = 1e-3;

// ---------------------------------------------------------------------------------------------
std::string Pct(double e) { return std::isnan(e) ? "-" : fmt::format("{:.3f}", e * kToPercent); }

std::string CsvNumber(double v, const char* format = "{:.6g}") {
  return std::isnan(v) ? std::string() : fmt::format(fmt::runtime(format), v);
}

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string FormatAccuracyTable(const AccuracyStudy& s) {
  std::string out;
  out += fmt::format("scene       {} ({})\n", s.scene_name, s.scene_path);
  out += fmt::format("reference   {}\n", s.reference.source);
  std::vector<std::string> how;
  for (const auto& [name, text] : s.reference.how) how.push_back(name + ": " + text);
  out += fmt::format("            {}\n", fmt::join(how, "; "));
  const AccuracyQuantities& r = s.reference.q;
  std::string values;
  if (s.reference.has_area) values += fmt::format("area {:.2f} mm2  ", r.area_m2 * kToMm2);
  if (s.reference.has_p_max) values += fmt::format("p_max {:.1f} MPa  ", r.p_max_Pa * kToMPa);
  if (s.reference.has_force) {
    values +=
        fmt::format("vertical {:.1f} N  lateral {:.1f} N  ", r.vertical_force_N, r.lateral_force_N);
  }
  if (s.reference.has_creep) {
    values += fmt::format("creep x {:.1f} N  creep y {:.1f} N", *r.creep_x_N, *r.creep_y_N);
  }
  out += fmt::format("            {}\n", values);
  for (const auto& n : s.notes) out += fmt::format("note        {}\n", n);
  out += "\n";
  const bool tan = s.compare_tangential;
  out += fmt::format("{:<21} {:<9}", "model", "level");
  if (tan) out += fmt::format(" {:<10}", "tangential");
  out += fmt::format(" {:>4} {:>9} {:>8} {:>15} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8}", "n/b",
                     "time_ms", "mem_MiB", "cells(contact)", "area_mm2", "p_max_MPa", "lateral_N",
                     "e_area%", "e_pmax%", "e_force%");
  out += s.rolling ? fmt::format(" {:>8}", "e_creep%") : std::string();
  if (tan) out += fmt::format(" {:>10}", "vs_exact%");
  out += tan ? "  patches (solvers)\n" : "  patches\n";
  for (const auto& row : s.rows) {
    const std::string n =
        row.cells_per_semi_axis > 0 ? fmt::format("{:.0f}", row.cells_per_semi_axis) : "-";
    const std::string mem =
        std::isnan(row.memory_bytes) ? "-" : fmt::format("{:.1f}", row.memory_bytes * kToMiB);
    const std::string cells =
        row.cells > 0 ? fmt::format("{}({})", row.cells, row.cells_in_contact) : "analytic";
    out += fmt::format("{:<21} {:<9}", row.model, row.level);
    if (tan) out += fmt::format(" {:<10}", row.tangential);
    out += fmt::format(
        " {:>4} {:>9.2f} {:>8} {:>15} {:>9.2f} {:>9.1f} {:>9.1f} {:>8} {:>8} {:>8}", n,
        row.time_median_s * kToMs, mem, cells, row.q.area_m2 * kToMm2, row.q.p_max_Pa * kToMPa,
        row.q.lateral_force_N, Pct(row.err_area), Pct(row.err_p_max), Pct(row.err_force));
    if (s.rolling) out += fmt::format(" {:>8}", Pct(row.err_creep));
    if (tan) out += fmt::format(" {:>10}", Pct(row.err_creep_vs_exact));
    out += fmt::format("  {}", row.patch_models);
    if (tan) out += fmt::format(" ({})", row.tangential_choices);
    if (row.status != SolverStatus::kConverged) {
      out += fmt::format("  [{}: {}]", ToString(row.status), row.message);
    }
    out += "\n";
  }
  return out;
}

void WriteAccuracyCsv(const AccuracyStudy& s, std::ostream& out) {
  out << "model,level,cells_per_semi_axis,status,repeats,time_ms_median,time_ms_min,time_ms_max,"
         "memory_MiB,patches,cells,cells_in_contact,iterations,area_mm2,p_max_MPa,vertical_N,"
         "lateral_N,creep_x_N,creep_y_N,err_area_pct,err_p_max_pct,err_force_pct,err_creep_pct,"
         "patch_models,tangential,tangential_solvers,err_creep_vs_exact_pct\n";
  auto opt = [](const std::optional<double>& v) { return v ? CsvNumber(*v) : std::string(); };
  for (const auto& r : s.rows) {
    out << fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
        CsvField(r.model), CsvField(r.level), CsvNumber(r.cells_per_semi_axis), ToString(r.status),
        r.repeats, CsvNumber(r.time_median_s * kToMs), CsvNumber(r.time_min_s * kToMs),
        CsvNumber(r.time_max_s * kToMs), CsvNumber(r.memory_bytes * kToMiB), r.patches, r.cells,
        r.cells_in_contact, r.iterations, CsvNumber(r.q.area_m2 * kToMm2, "{:.9g}"),
        CsvNumber(r.q.p_max_Pa * kToMPa, "{:.9g}"), CsvNumber(r.q.vertical_force_N, "{:.9g}"),
        CsvNumber(r.q.lateral_force_N, "{:.9g}"), opt(r.q.creep_x_N), opt(r.q.creep_y_N),
        CsvNumber(r.err_area * kToPercent), CsvNumber(r.err_p_max * kToPercent),
        CsvNumber(r.err_force * kToPercent), CsvNumber(r.err_creep * kToPercent),
        CsvField(r.patch_models), CsvField(r.tangential), CsvField(r.tangential_choices),
        CsvNumber(r.err_creep_vs_exact * kToPercent));
  }
  const AccuracyReference& ref = s.reference;
  auto if_has = [](bool has, double v) { return has ? CsvNumber(v, "{:.9g}") : std::string(); };
  out << fmt::format(
      "reference,{},,,,,,,,,,,,{},{},{},{},{},{},,,,,,,,\n", CsvField(ref.source),
      if_has(ref.has_area, ref.q.area_m2 * kToMm2), if_has(ref.has_p_max, ref.q.p_max_Pa * kToMPa),
      if_has(ref.has_force, ref.q.vertical_force_N), if_has(ref.has_force, ref.q.lateral_force_N),
      ref.has_creep ? opt(ref.q.creep_x_N) : std::string(),
      ref.has_creep ? opt(ref.q.creep_y_N) : std::string());
}

void PlotAccuracy(const AccuracyStudy& s, const std::string& png_path) {
  RequireGnuplotFor("railwear accuracy's Pareto plot", "pass --no-plot");
  ScopedTempDir dir("railwear-accuracy");
  // One data file per model: time_ms, the errors [%] (floored for the log axis), level.
  std::vector<std::string> models;
  for (const auto& r : s.rows) {
    if (std::find(models.begin(), models.end(), r.model) == models.end()) models.push_back(r.model);
  }
  auto floored = [](double e) {
    return std::isnan(e) ? std::string("NaN")
                         : fmt::format("{:.6g}", std::max(e * kToPercent, kPlotErrorFloor_pct));
  };
  std::vector<std::string> files;
  for (size_t m = 0; m < models.size(); ++m) {
    std::string data;
    for (const auto& r : s.rows) {
      if (r.model != models[m] || r.status != SolverStatus::kConverged) continue;
      data +=
          fmt::format("{:.6g} {} {} {} {} {}\n", r.time_median_s * kToMs, floored(r.err_area),
                      floored(r.err_p_max), floored(r.err_force), floored(r.err_creep), r.level);
    }
    const fs::path file = dir.path() / fmt::format("model{}.dat", m);
    std::ofstream(file) << data;
    files.push_back(file.string());
  }
  struct Panel {
    int column;
    const char* label;
  };
  std::vector<Panel> panels = {
      {2, "area error [%]"}, {3, "peak pressure error [%]"}, {4, "total force error [%]"}};
  if (s.rolling && s.reference.has_creep) panels.push_back({5, "creep force error [%]"});
  std::ostringstream g;
  g << GnuplotPngTerminal(520 * static_cast<int>(panels.size()), 560);
  g << "set output " << GnuplotQuote(png_path) << "\n";
  g << "set multiplot layout 1," << panels.size() << " title "
    << GnuplotQuote(fmt::format("{}: error against time per solve (reference: {}; errors below "
                                "{:g} % drawn at it)",
                                s.scene_name, s.reference.source, kPlotErrorFloor_pct))
    << "\n";
  g << "set logscale xy\nset grid\nset key below\nset xlabel 'time per solve [ms]'\n";
  g << "set format y '%g'\nset format x '%g'\n";
  for (const auto& panel : panels) {
    g << "set ylabel " << GnuplotQuote(panel.label) << "\nplot ";
    for (size_t m = 0; m < models.size(); ++m) {
      const std::string f = GnuplotQuote(files[m]);
      g << (m ? ", " : "") << f
        << fmt::format(" using 1:{} with linespoints pt 7 lw 2 lc {} title ", panel.column, m + 1)
        << GnuplotQuote(models[m]) << ", " << f
        << fmt::format(" using 1:{}:6 with labels offset 0,0.8 font ',8' tc lt {} notitle",
                       panel.column, m + 1);
    }
    g << "\n";
  }
  g << "unset multiplot\n";
  RunGnuplot(g.str(), dir, {png_path});
}

}  // namespace railwear::app
