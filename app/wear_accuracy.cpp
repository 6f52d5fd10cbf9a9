// `railwear accuracy` on a wear scene: the wear study at each accuracy level and step limit, run
// time and the error of the final worn profile against the finest run (wear_accuracy.h).
#include "app/wear_accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "app/accuracy_config.h"
#include "app/gnuplot.h"
#include "app/paths.h"
#include "core/numerics/enum_names.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "wear/wear_measures.h"
#include "wear/wear_simulation.h"

namespace railwear::app {
namespace {

namespace fs = std::filesystem;

constexpr double kToPercent = 100.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Profile errors below this are drawn at it on the log axis [mm] (0.1 um: far below any
// measurement of a rail profile).
constexpr double kPlotErrorFloor_mm = 1e-4;

// max |a - b| over samples where both are finite; NaN when none is.
double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = kNaN;
  for (size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    if (!std::isfinite(a[k]) || !std::isfinite(b[k])) continue;
    const double d = std::abs(a[k] - b[k]);
    worst = std::isnan(worst) ? d : std::max(worst, d);
  }
  return worst;
}

WearAccuracyRow RunOne(WearStudy study, const Profile& unworn, const WearGauge& gauge,
                       AccuracyPreset preset, double step_limit_mm) {
  study.model.accuracy = preset;
  study.model.cell_dx_m.reset();
  study.model.cell_ds_m.reset();
  study.options.max_depth_per_step_m = step_limit_mm / kToMm;
  WearAccuracyRow row;
  row.level = std::string(ToString(preset));
  row.step_limit_mm = step_limit_mm;
  const auto start = std::chrono::steady_clock::now();
  // A two-rail study runs both rails; the table measures the high rail.
  const WearState initial = internal::InitialState(study);
  const WearRunSummary summary = RunWear(study, UnwornRails(unworn, initial.low_rail), initial,
                                         [](const StepResult&) { return true; });
  row.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.steps = summary.steps_done;
  row.passes = summary.state.passes;
  row.mgt = summary.state.mgt;
  WearMeasureOptions measure;
  measure.gauge = gauge;
  const WearMeasures m = CompareProfiles(unworn, summary.state.rail, measure);
  row.max_depth_mm = m.max_depth_m * kToMm;
  row.worn_area_mm2 = m.worn_area_m2 * kToMm2;
  row.wear_45_mm = m.wear_45_m * kToMm;
  row.depth_m = m.depth_m;
  return row;
}

std::string Num(double v, const char* format) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string("-");
}

}  // namespace

WearAccuracyStudy RunWearAccuracyStudy(const Scene& scene, const WearAccuracyOptions& o,
                                       const std::function<void(const std::string&)>& progress) {
  if (!scene.wear) {
    throw InputError(
        fmt::format("{}: not a wear scene (no effect \"wear\" with [wear] and "
                    "[[traffic]]); the wear-step study needs one",
                    scene.path));
  }
  const std::vector<AccuracyPreset> presets = ParseAccuracyLevels(o.levels);
  std::vector<double> limits = o.step_limits_mm;
  for (double l : limits) {
    if (!(l > 0.0) || !std::isfinite(l)) {
      throw InputError(fmt::format("--step-limits: {} mm: expected a step limit > 0", l));
    }
  }
  if (limits.empty()) throw InputError("--step-limits: expected at least one step limit");
  std::sort(limits.begin(), limits.end(), std::greater<>());
  limits.erase(std::unique(limits.begin(), limits.end()), limits.end());

  WearStudy study = *scene.wear;
  if (o.total_mgt) {
    if (!(*o.total_mgt > 0.0) || !std::isfinite(*o.total_mgt)) {
      throw InputError(fmt::format("--mgt {}: expected a total > 0 MGT", *o.total_mgt));
    }
    study.options.total_mgt = *o.total_mgt;
    study.options.total_passes.reset();
  }
  if (o.threads > 0) study.options.threads = o.threads;
  ValidateWearStudy(study);  // the study as changed above: once, before its runs

  WearAccuracyStudy s;
  s.scene_name = scene.name;
  s.scene_path = scene.path;
  const Profile unworn = internal::InitialState(study).rail;
  const WearGauge gauge = MakeWearGauge(unworn);
  for (AccuracyPreset p : presets) {
    for (double limit : limits) {
      s.rows.push_back(RunOne(study, unworn, gauge, p, limit));
      const WearAccuracyRow& r = s.rows.back();
      s.total_mgt = r.mgt;
      if (progress) {
        progress(fmt::format("{} / {} mm: {} steps, {:.1f} s, max depth {:.3f} mm", r.level,
                             r.step_limit_mm, r.steps, r.time_s, r.max_depth_mm));
      }
    }
  }
  s.reference_row = static_cast<int>(s.rows.size()) - 1;
  const WearAccuracyRow& ref = s.rows[s.reference_row];
  for (auto& r : s.rows) {
    r.err_profile_mm = MaxAbsDifference(r.depth_m, ref.depth_m) * kToMm;
    r.err_max_depth = std::abs(r.max_depth_mm / ref.max_depth_mm - 1.0);
    r.err_area = std::abs(r.worn_area_mm2 / ref.worn_area_mm2 - 1.0);
  }
  // The reference's own error: its distance to the next coarser run in each direction.
  const int n_limits = static_cast<int>(limits.size());
  if (n_limits > 1) {
    const WearAccuracyRow& coarser_step = s.rows[s.reference_row - 1];
    s.notes.push_back(fmt::format(
        "step limit {} -> {} mm at {} changes the final profile by {} mm (an estimate of the "
        "reference's step error)",
        coarser_step.step_limit_mm, ref.step_limit_mm, ref.level,
        Num(coarser_step.err_profile_mm, "{:.4f}")));
  }
  if (presets.size() > 1) {
    const WearAccuracyRow& coarser_level = s.rows[s.reference_row - n_limits];
    s.notes.push_back(fmt::format(
        "level {} -> {} at {} mm changes the final profile by {} mm (an estimate of the "
        "reference's grid error)",
        coarser_level.level, ref.level, ref.step_limit_mm,
        Num(coarser_level.err_profile_mm, "{:.4f}")));
  }
  return s;
}

std::string FormatWearAccuracyTable(const WearAccuracyStudy& s) {
  const WearAccuracyRow& ref = s.rows.at(s.reference_row);
  std::string out;
  out += fmt::format("scene       {} ({}), wear study to {:.3g} MGT\n", s.scene_name, s.scene_path,
                     s.total_mgt);
  out += fmt::format(
      "reference   {} level, step limit {} mm: max depth {:.4f} mm, worn area "
      "{:.4f} mm2\n",
      ref.level, ref.step_limit_mm, ref.max_depth_mm, ref.worn_area_mm2);
  for (const auto& n : s.notes) out += fmt::format("note        {}\n", n);
  out += "\n";
  out += fmt::format("{:<10} {:>9} {:>6} {:>9} {:>13} {:>12} {:>9} {:>14} {:>10} {:>8}\n", "level",
                     "limit_mm", "steps", "time_s", "max_depth_mm", "worn_area_mm2", "W3_mm",
                     "e_profile_mm", "e_depth%", "e_area%");
  for (const auto& r : s.rows) {
    out += fmt::format(
        "{:<10} {:>9.3f} {:>6} {:>9.1f} {:>13.4f} {:>12.4f} {:>9} {:>14} {:>10} "
        "{:>8}\n",
        r.level, r.step_limit_mm, r.steps, r.time_s, r.max_depth_mm, r.worn_area_mm2,
        Num(r.wear_45_mm, "{:.4f}"), Num(r.err_profile_mm, "{:.4f}"),
        Num(r.err_max_depth * kToPercent, "{:.3f}"), Num(r.err_area * kToPercent, "{:.3f}"));
  }
  return out;
}

void WriteWearAccuracyCsv(const WearAccuracyStudy& s, std::ostream& out) {
  out << "level,step_limit_mm,time_s,steps,passes,MGT,max_depth_mm,worn_area_mm2,W3_mm,"
         "err_profile_mm,err_max_depth_pct,err_area_pct,reference\n";
  for (size_t k = 0; k < s.rows.size(); ++k) {
    const WearAccuracyRow& r = s.rows[k];
    out << fmt::format("{},{:.6g},{:.6g},{},{:.9g},{:.6g},{:.9g},{:.9g},{},{},{},{},{}\n", r.level,
                       r.step_limit_mm, r.time_s, r.steps, r.passes, r.mgt, r.max_depth_mm,
                       r.worn_area_mm2, Num(r.wear_45_mm, "{:.9g}"),
                       Num(r.err_profile_mm, "{:.6g}"), Num(r.err_max_depth * kToPercent, "{:.6g}"),
                       Num(r.err_area * kToPercent, "{:.6g}"),
                       static_cast<int>(k) == s.reference_row ? 1 : 0);
  }
}

void PlotWearAccuracy(const WearAccuracyStudy& s, const std::string& png_path) {
  RequireGnuplotFor("railwear accuracy's wear plot", "pass --no-plot");
  ScopedTempDir dir("railwear-wear-accuracy");
  std::vector<std::string> levels;
  for (const auto& r : s.rows) {
    if (std::find(levels.begin(), levels.end(), r.level) == levels.end()) levels.push_back(r.level);
  }
  std::vector<std::string> files, titles;
  for (size_t l = 0; l < levels.size(); ++l) {
    std::string data;
    for (size_t k = 0; k < s.rows.size(); ++k) {
      const WearAccuracyRow& r = s.rows[k];
      if (r.level != levels[l] || static_cast<int>(k) == s.reference_row) continue;
      data += fmt::format("{:.6g} {:.6g} {:g}mm\n", r.time_s,
                          std::max(r.err_profile_mm, kPlotErrorFloor_mm), r.step_limit_mm);
    }
    if (data.empty()) continue;  // only the reference run at this level
    const fs::path file = dir.path() / fmt::format("level{}.dat", l);
    std::ofstream(file) << data;
    files.push_back(file.string());
    titles.push_back(levels[l]);
  }
  if (files.empty()) {
    throw InputError(
        "the wear accuracy plot needs runs besides the reference: give more than "
        "one level or step limit, or pass --no-plot");
  }
  std::ostringstream g;
  g << GnuplotPngTerminal(900, 600);
  g << "set output " << GnuplotQuote(png_path) << "\n";
  g << "set title "
    << GnuplotQuote(fmt::format("{}: error of the final worn profile against run time (reference: "
                                "{} level, {} mm steps)",
                                s.scene_name, s.rows.at(s.reference_row).level,
                                s.rows.at(s.reference_row).step_limit_mm))
    << "\n";
  g << "set logscale xy\nset grid\nset key below\nset format y '%g'\nset format x '%g'\n";
  g << "set xlabel 'run time [s]'\nset ylabel 'max |d - d_ref| over the profile [mm]'\nplot ";
  for (size_t l = 0; l < files.size(); ++l) {
    const std::string f = GnuplotQuote(files[l]);
    g << (l ? ", " : "") << f
      << fmt::format(" using 1:2 with linespoints pt 7 lw 2 lc {} title ", l + 1)
      << GnuplotQuote(titles[l] + " (step limits marked)") << ", " << f
      << fmt::format(" using 1:2:3 with labels offset 0,0.8 font ',8' tc lt {} notitle", l + 1);
  }
  g << "\n";
  RunGnuplot(g.str(), dir, {png_path});
}

}  // namespace railwear::app
