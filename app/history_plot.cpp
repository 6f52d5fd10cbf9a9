// History plots via gnuplot: one data file per plot (blocks per step, MGT in the colour column),
// one script writing all three PNGs.
#include "app/history_plot.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "app/gnuplot.h"
#include "core/numerics/units.h"
#include "wear/wear_measures.h"
#include "wear/wear_simulation.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

constexpr const char* kWearDepthKind = "wear_depth_mm";
// The gauge-corner zoom around the 45-degree point P45 of the unworn profile [mm]: on UIC60 it
// spans y -40..-10 mm and z -2..20 mm, the corner, the gauge face down to 20 mm and the shoulder.
constexpr double kZoomGaugeSide_mm = 8.0, kZoomCrownSide_mm = 22.0;
constexpr double kZoomAbove_mm = 8.0, kZoomBelow_mm = 14.0;

const Distribution* FindDistribution(const StepRecord& step, const std::string& kind) {
  for (const auto& d : step.distributions) {
    if (d.kind == kind) return &d;
  }
  return nullptr;
}

// The colour range of the MGT palette; gnuplot refuses an empty range.
std::string CbRange(const std::vector<StepRecord>& steps) {
  double lo = steps.front().mgt, hi = steps.front().mgt;
  for (const auto& s : steps) {
    lo = std::min(lo, s.mgt);
    hi = std::max(hi, s.mgt);
  }
  if (!(hi > lo)) hi = lo + 1.0;
  return fmt::format("set cbrange [{:.9g}:{:.9g}]\n", lo, hi);
}

void WriteFile(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) throw std::runtime_error("cannot write plot data to " + file.string());
}

std::string ProfilesScript(const std::string& run, const std::vector<StepRecord>& steps,
                           const WearGauge& gauge, const fs::path& dir, const std::string& png) {
  std::string data;
  for (const auto& s : steps) {
    for (const auto& p : s.profile.points()) {
      data += fmt::format("{:.6f} {:.6f} {:.9g}\n", p.x() * kToMm, p.y() * kToMm, s.mgt);
    }
    data += "\n";
  }
  const fs::path file = dir / "profiles.dat";
  WriteFile(file, data);

  std::ostringstream g;
  g << GnuplotPngTerminal(900, 800) << "set output " << GnuplotQuote(png) << "\n";
  g << "set title "
    << GnuplotQuote(fmt::format("run {}: rail profile after each step "
                                "(gauge corner)",
                                run))
    << "\n";
  g << "set xlabel 'y [mm] (gauge side left)'\nset ylabel 'z [mm] (down)'\n";
  g << "set cblabel 'MGT'\nset palette rgb 33,13,10\nset size ratio -1\nset grid\n";
  g << CbRange(steps);
  const Eigen::Vector2d p45 = gauge.corner45.point_m * kToMm;
  g << fmt::format("set xrange [{:.3f}:{:.3f}]\nset yrange [{:.3f}:{:.3f}]\n",
                   p45.x() - kZoomGaugeSide_mm, p45.x() + kZoomCrownSide_mm,
                   p45.y() + kZoomBelow_mm, p45.y() - kZoomAbove_mm);
  g << "plot " << GnuplotQuote(file.string()) << " using 1:2:3 with lines lc palette lw 1.5 "
    << "notitle\n";
  return g.str();
}

// The depth data file of one rail's curves; returns how many were stored with s.
int WriteDepthData(const std::vector<DepthCurve>& curves, const fs::path& file) {
  std::string data;
  int stored = 0;
  for (const auto& c : curves) {
    if (c.source == DepthSource::kStoredWithS) ++stored;
    for (size_t i = 0; i < c.s_mm.size(); ++i) {
      if (std::isnan(c.depth_mm[i])) {  // a gap: a blank line breaks the curve there
        if (!data.empty() && !data.ends_with("\n\n")) data += "\n";
        continue;
      }
      data += fmt::format("{:.6f} {:.9g} {:.9g}\n", c.s_mm[i], c.depth_mm[i], c.mgt);
    }
    data += "\n";
  }
  WriteFile(file, data);
  return stored;
}

std::string DepthSourceText(int stored, size_t curves) {
  return stored == static_cast<int>(curves)
             ? "stored wear_depth_mm"
             : (stored == 0 ? "normal depth against step 0"
                            : fmt::format("stored for {} of {} steps, else normal depth against "
                                          "step 0",
                                          stored, curves));
}

// One depth panel: `title` over the curves of one rail written to `file`.
void DepthPanel(std::ostringstream& g, const std::string& title, bool empty, const fs::path& file) {
  g << "set title " << GnuplotQuote(title) << "\n";
  if (empty) {
    g << "unset colorbox\nset label 1 'no wear steps yet' at graph 0.5, 0.5 center\n"
      << "plot [0:1][0:1] NaN notitle\n";
  } else {
    g << "plot " << GnuplotQuote(file.string()) << " using 1:2:3 with lines lc palette lw 1.5 "
      << "notitle\n";
  }
}

std::string DepthScript(const std::string& run, const std::vector<StepRecord>& steps,
                        const std::vector<DepthCurve>& curves,
                        const std::vector<DepthCurve>* low_curves, const fs::path& dir,
                        const std::string& png) {
  const fs::path file = dir / "depth.dat";
  int stored = WriteDepthData(curves, file);
  if (low_curves != nullptr) {
    const fs::path low_file = dir / "depth_low.dat";
    const int low_stored = WriteDepthData(*low_curves, low_file);
    std::ostringstream g;
    g << GnuplotPngTerminal(1000, 1000) << "set output " << GnuplotQuote(png) << "\n";
    g << "set multiplot layout 2,1\n";
    g << "set xlabel 's [mm] along the step-0 profile (from its first point)'\n";
    g << "set ylabel 'wear depth [mm]'\nset cblabel 'MGT'\nset palette rgb 33,13,10\nset grid\n";
    g << CbRange(steps);
    DepthPanel(g,
               fmt::format("run {}: high rail wear depth ({})", run,
                           DepthSourceText(stored, curves.size())),
               curves.empty(), file);
    DepthPanel(g,
               fmt::format("run {}: low rail wear depth ({})", run,
                           DepthSourceText(low_stored, low_curves->size())),
               low_curves->empty(), low_file);
    g << "unset multiplot\n";
    return g.str();
  }
  const std::string source = DepthSourceText(stored, curves.size());
  std::ostringstream g;
  g << GnuplotPngTerminal(1000, 600) << "set output " << GnuplotQuote(png) << "\n";
  g << "set title " << GnuplotQuote(fmt::format("run {}: wear depth ({})", run, source)) << "\n";
  g << "set xlabel 's [mm] along the step-0 profile (from its first point)'\n";
  g << "set ylabel 'wear depth [mm]'\nset cblabel 'MGT'\nset palette rgb 33,13,10\nset grid\n";
  g << CbRange(steps);
  if (curves.empty()) {
    g << "unset colorbox\nset label 1 'no wear steps yet' at graph 0.5, 0.5 center\n"
      << "plot [0:1][0:1] NaN notitle\n";
  } else {
    g << "plot " << GnuplotQuote(file.string()) << " using 1:2:3 with lines lc palette lw 1.5 "
      << "notitle\n";
  }
  return g.str();
}

// The wearing wheels' depth (co-evolution): one panel per wheel, its curves written to files in
// `dir`.
std::string WheelsScript(const std::string& run, const std::vector<StepRecord>& steps,
                         const std::vector<WheelDepthCurves>& wheels, const fs::path& dir,
                         const std::string& png) {
  std::ostringstream g;
  const int n = static_cast<int>(wheels.size());
  g << GnuplotPngTerminal(1000, 400 + 400 * n) << "set output " << GnuplotQuote(png) << "\n";
  g << fmt::format("set multiplot layout {},1\n", n);
  g << "set xlabel 's [mm] along the unworn wheel profile (from its first point)'\n";
  g << "set ylabel 'wear depth [mm]'\nset cblabel 'MGT'\nset palette rgb 33,13,10\nset grid\n";
  g << CbRange(steps);
  for (int k = 0; k < n; ++k) {
    const fs::path file = dir / fmt::format("wheel{}.dat", k);
    WriteDepthData(wheels[k].curves, file);
    DepthPanel(g,
               fmt::format("run {}: wheel of '{}' (traffic entry {}), normal depth against step 0",
                           run, wheels[k].name, wheels[k].traffic_index),
               wheels[k].curves.empty(), file);
  }
  g << "unset multiplot\n";
  return g.str();
}

std::string MeasuresScript(const std::string& run, const std::vector<StepRecord>& steps,
                           const std::vector<StepRecord>& low_steps, const fs::path& dir,
                           const std::string& png) {
  std::string data;
  for (size_t k = 0; k < steps.size(); ++k) {
    const StepRecord& s = steps[k];
    data += fmt::format("{:.9g} {:.9g} {:.9g} {:.9g}", s.mgt, s.w1_mm, s.w2_mm, s.w3_mm);
    if (!low_steps.empty()) {
      const StepRecord& l = low_steps[k];
      data += fmt::format(" {:.9g} {:.9g} {:.9g}", l.w1_mm, l.w2_mm, l.w3_mm);
    }
    data += "\n";
  }
  const fs::path file = dir / "measures.dat";
  WriteFile(file, data);
  const std::string q = GnuplotQuote(file.string());
  if (!low_steps.empty()) {
    std::ostringstream g;
    g << GnuplotPngTerminal(900, 600) << "set output " << GnuplotQuote(png) << "\n";
    g << "set title " << GnuplotQuote(fmt::format("run {}: wear measures, both rails", run))
      << "\n";
    g << "set xlabel 'traffic [MGT]'\nset ylabel 'wear [mm]'\nset grid\nset key top left\n";
    if (steps.size() < 2) g << "set xrange [*:*] noextend\nset offsets 0.5, 0.5, 0, 0\n";
    g << "plot " << q << " using 1:2 with linespoints lc 1 title 'high W1 vertical', \\\n"
      << "     " << q << " using 1:3 with linespoints lc 2 title 'high W2 side', \\\n"
      << "     " << q << " using 1:4 with linespoints lc 3 title 'high W3 45 degrees', \\\n"
      << "     " << q << " using 1:5 with linespoints dt 2 lc 1 title 'low W1 vertical', \\\n"
      << "     " << q << " using 1:6 with linespoints dt 2 lc 2 title 'low W2 side', \\\n"
      << "     " << q << " using 1:7 with linespoints dt 2 lc 3 title 'low W3 45 degrees'\n";
    return g.str();
  }
  std::ostringstream g;
  g << GnuplotPngTerminal(900, 600) << "set output " << GnuplotQuote(png) << "\n";
  g << "set title " << GnuplotQuote(fmt::format("run {}: wear measures", run)) << "\n";
  g << "set xlabel 'traffic [MGT]'\nset ylabel 'wear [mm]'\nset grid\nset key top left\n";
  if (steps.size() < 2) g << "set xrange [*:*] noextend\nset offsets 0.5, 0.5, 0, 0\n";
  g << "plot " << q << " using 1:2 with linespoints title 'W1 vertical (centre line)', \\\n"
    << "     " << q << " using 1:3 with linespoints title 'W2 side (14 mm below top)', \\\n"
    << "     " << q << " using 1:4 with linespoints title 'W3 45 degrees (gauge corner)'\n";
  return g.str();
}

}  // namespace

std::vector<StepRecord> LowRailSteps(const std::vector<StepRecord>& steps) {
  std::vector<StepRecord> out;
  if (steps.empty() || !steps.front().low_rail) return out;
  for (const StepRecord& s : steps) {
    StepRecord r;
    r.step = s.step;
    r.passes = s.passes;
    r.mgt = s.mgt;
    r.created_utc = s.created_utc;
    if (s.low_rail) {
      const RailStepRecord& l = *s.low_rail;
      r.worn_area_mm2 = l.worn_area_mm2;
      r.max_depth_mm = l.max_depth_mm;
      r.max_depth_y_mm = l.max_depth_y_mm;
      r.w1_mm = l.w1_mm;
      r.w2_mm = l.w2_mm;
      r.w3_mm = l.w3_mm;
      r.smoothing_area_error = l.smoothing_area_error;
      r.profile = l.profile;
      r.distributions = l.distributions;
    }
    out.push_back(std::move(r));
  }
  return out;
}

WearRates RatesBetween(const StepRecord& a, const StepRecord& b) {
  const double mgt = b.mgt - a.mgt;
  if (!(mgt > 0.0)) return {std::nan(""), std::nan("")};
  return {(b.w2_mm - a.w2_mm) / mgt, (b.w3_mm - a.w3_mm) / mgt};
}

WearRates LastHalfRates(const std::vector<StepRecord>& steps) {
  StepRecord half;
  half.mgt = 0.5 * steps.back().mgt;
  for (size_t k = 1; k < steps.size(); ++k) {
    const StepRecord &a = steps[k - 1], &b = steps[k];
    if (b.mgt < half.mgt || !(b.mgt > a.mgt)) continue;
    const double t = (half.mgt - a.mgt) / (b.mgt - a.mgt);
    half.w2_mm = a.w2_mm + t * (b.w2_mm - a.w2_mm);
    half.w3_mm = a.w3_mm + t * (b.w3_mm - a.w3_mm);
    break;
  }
  return RatesBetween(half, steps.back());
}

std::vector<DepthCurve> WearDepthCurves(const std::vector<StepRecord>& steps) {
  std::vector<DepthCurve> curves;
  if (steps.size() < 2) return curves;
  const Profile& unworn = steps.front().profile;
  WearMeasureOptions options;
  bool gauge_made = false;
  for (size_t k = 1; k < steps.size(); ++k) {
    const StepRecord& step = steps[k];
    DepthCurve c;
    c.step = step.step;
    c.mgt = step.mgt;
    const Distribution* d = FindDistribution(step, kWearDepthKind);
    if (d != nullptr && !d->s_m.empty()) {
      c.source = DepthSource::kStoredWithS;
      for (size_t i = 0; i < d->s_m.size(); ++i) {
        c.s_mm.push_back(d->s_m[i] * kToMm);
        c.depth_mm.push_back(d->value[i]);
      }
    } else {
      if (!gauge_made) {  // one gauge for every step, built on the unworn profile
        options.gauge = MakeWearGauge(unworn, options.side_wear_depth_m);
        gauge_made = true;
      }
      const WearMeasures m = CompareProfiles(unworn, step.profile, options);
      c.source = DepthSource::kFromProfiles;
      for (size_t i = 0; i < m.s_m.size(); ++i) {
        c.s_mm.push_back(m.s_m[i] * kToMm);
        c.depth_mm.push_back(m.depth_m[i] * kToMm);
      }
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

std::vector<WheelDepthCurves> WheelDepthCurvesOf(const std::vector<StepRecord>& steps) {
  std::vector<WheelDepthCurves> out;
  if (steps.empty()) return out;
  for (const WheelStepRecord& unworn : steps.front().wheels) {
    WheelDepthCurves w;
    w.traffic_index = unworn.traffic_index;
    w.name = unworn.name;
    for (size_t k = 1; k < steps.size(); ++k) {
      for (const WheelStepRecord& now : steps[k].wheels) {
        if (now.traffic_index != unworn.traffic_index || now.wheel != unworn.wheel) continue;
        const WearMeasures m = CompareWheelWithUnworn(unworn.profile, now.profile);
        DepthCurve c;
        c.step = steps[k].step;
        c.mgt = steps[k].mgt;
        for (size_t i = 0; i < m.s_m.size(); ++i) {
          c.s_mm.push_back(m.s_m[i] * kToMm);
          c.depth_mm.push_back(m.depth_m[i] * kToMm);
        }
        w.curves.push_back(std::move(c));
      }
    }
    out.push_back(std::move(w));
  }
  return out;
}

std::vector<std::string> PlotHistory(const std::string& run_name,
                                     const std::vector<StepRecord>& steps,
                                     const std::string& prefix) {
  RequireGnuplotFor("history plot", "use `history profile` / `history sql` for the numbers");
  if (steps.empty()) {
    throw std::runtime_error(fmt::format("run '{}' has no steps to plot", run_name));
  }
  const WearGauge gauge = MakeWearGauge(steps.front().profile);  // InputError: not a rail head
  const std::vector<DepthCurve> curves = WearDepthCurves(steps);
  const std::vector<StepRecord> low_steps = LowRailSteps(steps);
  std::vector<DepthCurve> low_curves;
  if (!low_steps.empty()) low_curves = WearDepthCurves(low_steps);
  const ScopedTempDir tmp("railwear-plot");
  const std::vector<std::string> outputs = {fs::absolute(prefix + "_profiles.png").string(),
                                            fs::absolute(prefix + "_depth.png").string(),
                                            fs::absolute(prefix + "_measures.png").string()};
  std::string script = ProfilesScript(run_name, steps, gauge, tmp.path(), outputs[0]);
  script +=
      "reset\n" + DepthScript(run_name, steps, curves, low_steps.empty() ? nullptr : &low_curves,
                              tmp.path(), outputs[1]);
  script += "reset\n" + MeasuresScript(run_name, steps, low_steps, tmp.path(), outputs[2]);
  std::vector<std::string> written = {prefix + "_profiles.png", prefix + "_depth.png",
                                      prefix + "_measures.png"};
  std::vector<std::string> expected = outputs;
  const std::vector<WheelDepthCurves> wheels = WheelDepthCurvesOf(steps);
  if (!wheels.empty()) {  // co-evolution: a fourth PNG, the wheels' depth
    expected.push_back(fs::absolute(prefix + "_wheels.png").string());
    script += "reset\n" + WheelsScript(run_name, steps, wheels, tmp.path(), expected.back());
    written.push_back(prefix + "_wheels.png");
  }
  RunGnuplot(script, tmp, expected);
  return written;
}

}  // namespace railwear::app
