// Contact plots via gnuplot: a self-contained script (inline data blocks), then `gnuplot`.
#include "app/pressure_plot.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "app/contact_output.h"
#include "app/gnuplot.h"
#include "app/influence_constants_file.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

// The bounding box of points, for panel ranges.
struct Box {
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x;
  double lo_y = lo_x, hi_y = -lo_x;
  void Add(double x, double y) {
    lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x);
    lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
  }
  bool empty() const { return !(lo_x <= hi_x); }
};

// "set xrange [..]; set yrange [..]" around `b`, widened by `margin` (a share of the larger
// side, at least `min_mm`); with `reverse_y` the y axis points down (rail frame z).
std::string Ranges(const Box& b, double margin, double min_mm, bool reverse_y) {
  const double pad = std::max(min_mm, margin * std::max(b.hi_x - b.lo_x, b.hi_y - b.lo_y));
  // gnuplot ignores `reverse` on an explicit range: a downward axis is the range high to low.
  const double y0 = b.lo_y - pad, y1 = b.hi_y + pad;
  return fmt::format("set xrange [{:.4f}:{:.4f}]\nset yrange [{:.4f}:{:.4f}]\n", b.lo_x - pad,
                     b.hi_x + pad, reverse_y ? y1 : y0, reverse_y ? y0 : y1);
}

std::string DataBlockStart(const std::string& name) { return "$" + name + " << EOD\n"; }
constexpr char kDataBlockEnd[] = "EOD\n";

// The pressure map of one patch: s across, x up; with rolling also |q| and |v_slip|.
std::string MapBlock(const PatchResult& patch, int number, const std::string& name, Box* box) {
  std::string out = DataBlockStart(name);
  int row = -1;
  for (const PressureSample& s : PressureSamples(patch, number)) {
    if (row >= 0 && s.js != row) out += "\n";  // a blank line after each s row
    row = s.js;
    if (s.p_MPa > 0.0) box->Add(s.s_mm, s.x_mm);  // the window: the cells in contact
    out += fmt::format("{:.6f} {:.6f} {:.6f}", s.s_mm, s.x_mm, s.p_MPa);
    if (patch.rolling) {
      const TangentialSolution& t = patch.rolling->tangential;
      const int c = patch.grid.Index(s.ix, s.js);
      out += fmt::format(" {:.6f} {:.6g}", std::hypot(t.traction_x_Pa[c], t.traction_s_Pa[c]) * 1e-6,
                         std::hypot(t.slip_x_m_s[c], t.slip_s_m_s[c]) * 1e3);
    }
    out += "\n";
  }
  return out + kDataBlockEnd;
}

std::string PatchTitle(const std::string& wheel, const PatchResult& p, int number) {
  return fmt::format("{}patch {}: area {:.1f} mm^2, p_max {:.0f} MPa, angle {:.1f} deg",
                     wheel.empty() ? "" : wheel + ", ", number, p.area_m2 * 1e6,
                     p.p_max_Pa * 1e-6, p.contact_angle_rad * kToDeg);
}

// The cross-section panel of wheel row `k`: data blocks and the plot command.
std::string CrossSection(const PlotWheel& w, int k) {
  const ContactResult& r = *w.result;
  std::string out;
  // The rail and the wheel at first contact, in the rail frame.
  out += DataBlockStart(fmt::format("rail_{}", k));
  for (const Eigen::Vector2d& p : w.rail_profile->points()) {
    out += fmt::format("{:.5f} {:.5f}\n", p.x() * kToMm, p.y() * kToMm);
  }
  out += kDataBlockEnd;
  const WheelRailGeometry geometry(*w.wheel_profile, *w.rail_profile, w.pose);
  out += DataBlockStart(fmt::format("wheel_{}", k));
  if (geometry.has_overlap()) {
    for (const Eigen::Vector2d& p : w.wheel_profile->points()) {
      const Eigen::Vector2d q = geometry.WheelToRail(p);
      out += fmt::format("{:.5f} {:.5f}\n", q.x() * kToMm, q.y() * kToMm);
    }
  }
  out += kDataBlockEnd;
  // The patches on the rail: the cross-section points of the cells in contact (one per lateral
  // index), a blank line between patches.
  Box box;
  out += DataBlockStart(fmt::format("patch_{}", k));
  for (size_t n = 0; n < r.patches.size(); ++n) {
    std::vector<std::pair<int, Eigen::Vector2d>> points;
    for (const PressureSample& s : PressureSamples(r.patches[n], static_cast<int>(n) + 1)) {
      if (s.p_MPa <= 0.0) continue;
      if (std::none_of(points.begin(), points.end(), [&](const auto& q) { return q.first == s.js; }))
        points.push_back({s.js, {s.y_mm, s.z_mm}});
    }
    std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [js, p] : points) {
      out += fmt::format("{:.5f} {:.5f}\n", p.x(), p.y());
      box.Add(p.x(), p.y());
    }
    out += "\n";
  }
  out += kDataBlockEnd;
  out += DataBlockStart(fmt::format("contact_{}", k));
  for (const PatchResult& p : r.patches) {
    const Eigen::Vector2d c = p.contact_point_yz_m * kToMm;
    out += fmt::format("{:.5f} {:.5f} {:.3f}\n", c.x(), c.y(), p.contact_angle_rad * kToDeg);
    box.Add(c.x(), c.y());
  }
  out += kDataBlockEnd;

  // The window: the patches and contact points with 12 mm around them (the wheel's flange and
  // the rail's head in view); without contact the rail's top.
  if (box.empty()) {  // the rail's head: its points within 15 mm of its top
    double top = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& p : w.rail_profile->points()) top = std::min(top, p.y());
    for (const Eigen::Vector2d& p : w.rail_profile->points()) {
      if (p.y() < top + 15e-3) box.Add(p.x() * kToMm, p.y() * kToMm);
    }
  }
  out += "set size ratio -1\nunset colorbox\n";
  out += Ranges(box, 0.25, 15.0, /*reverse_y=*/true);
  out += "set xlabel 'y [mm] (rail frame, toward the field side)'\nset ylabel 'z [mm] (down)'\n";
  out += fmt::format("set title {}\n", GnuplotQuote(fmt::format(
                                           "{}: cross-section at first contact, {} patch{}",
                                           w.name, r.patches.size(), r.patches.size() == 1 ? "" : "es")));
  // The force on the rail at each contact point: an arrow of 6 mm along the contact angle
  // (against the vertical, toward +y for a positive angle) ending at the point.
  out += "unset arrow\nunset label\n";
  for (size_t n = 0; n < r.patches.size(); ++n) {
    const PatchResult& p = r.patches[n];
    const Eigen::Vector2d c = p.contact_point_yz_m * kToMm;
    const Eigen::Vector2d d(std::sin(p.contact_angle_rad), std::cos(p.contact_angle_rad));
    const Eigen::Vector2d from = c - 6.0 * d;
    out += fmt::format("set arrow {} from {:.4f},{:.4f} to {:.4f},{:.4f} lw 2 lc rgb 'black'\n",
                       n + 1, from.x(), from.y(), c.x(), c.y());
    out += fmt::format("set label {} {} at {:.4f},{:.4f} offset 1,-1\n", n + 1,
                       GnuplotQuote(fmt::format("{}: {:.1f} deg", n + 1, p.contact_angle_rad * kToDeg)),
                       from.x(), from.y());
  }
  out += fmt::format(
      "plot $rail_{0} using 1:2 with lines lw 2 lc rgb '#404040' title 'rail', "
      "$wheel_{0} using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'wheel', "
      "$patch_{0} using 1:2 with lines lw 6 lc rgb '#d62728' title 'patch', "
      "$contact_{0} using 1:2 with points pt 7 ps 1.2 lc rgb 'black' title 'contact point'\n",
      k);
  out += "unset arrow\nunset label\n";
  return out;
}

}  // namespace

void RequireGnuplot() { RequireGnuplotFor("--plot", "leave out --plot"); }

std::string ContactPlotScript(const Scene& scene, const std::vector<PlotWheel>& wheels,
                              const std::string& png_path) {
  size_t columns = 2;  // the cross-section and at least one map's place
  for (const PlotWheel& w : wheels) {
    size_t panels = 1;
    for (const PatchResult& p : w.result->patches) panels += p.rolling ? 3 : 1;
    columns = std::max(columns, panels);
  }
  const ModelOptions& m = wheels.empty() ? scene.problem.model : wheels[0].result->model;
  std::ostringstream s;
  s << GnuplotPngTerminal(static_cast<int>(620 * columns), static_cast<int>(520 * wheels.size()));
  s << "set output " << GnuplotQuote(png_path) << "\n";
  s << "set palette rgb 33,13,10\nset key bottom right\n";
  s << fmt::format("set multiplot layout {},{} rowsfirst title {}\n", wheels.size(), columns,
                   GnuplotQuote(fmt::format("{} - {} model, {} accuracy{}", scene.name,
                                            ToString(m.kind), ToString(m.accuracy),
                                            m.kind == ModelKind::kHertz
                                                ? std::string()
                                                : ", constants " + ConstantsSetName(m.constants))));
  for (size_t k = 0; k < wheels.size(); ++k) {
    const PlotWheel& w = wheels[k];
    const int row = static_cast<int>(k) + 1;
    s << CrossSection(w, row);
    size_t panels = 1;
    for (size_t n = 0; n < w.result->patches.size(); ++n) {
      const PatchResult& p = w.result->patches[n];
      const int number = static_cast<int>(n) + 1;
      const std::string block = fmt::format("map_{}_{}", row, number);
      Box box;
      s << MapBlock(p, number, block, &box);
      if (box.empty()) box.Add(0.0, 0.0);  // no cell in contact
      s << "set size ratio -1\nset colorbox\nset key off\n" << Ranges(box, 0.08, 0.5, false);
      s << "set xlabel 's [mm] (lateral arc)'\nset ylabel 'x [mm] (rolling)'\n";
      const std::string who = wheels.size() > 1 ? w.name : std::string();
      s << "set cblabel 'p [MPa]'\nset title " << GnuplotQuote(PatchTitle(who, p, number)) << "\n";
      s << "plot $" << block << " using 1:2:3 with image notitle\n";
      ++panels;
      if (p.rolling) {
        s << "set cblabel '|q| [MPa]'\nset title "
          << GnuplotQuote(fmt::format("patch {}: traction", number)) << "\n";
        s << "plot $" << block << " using 1:2:4 with image notitle\n";
        s << "set cblabel '|v_slip| [mm/s]'\nset title "
          << GnuplotQuote(fmt::format("patch {}: slip velocity (0 = stick)", number)) << "\n";
        s << "plot $" << block << " using 1:2:5 with image notitle\n";
        panels += 2;
      }
      s << "set key bottom right\n";
    }
    for (; panels < columns; ++panels) s << "set multiplot next\n";  // a shorter row
  }
  s << "unset multiplot\n";
  return s.str();
}

void PlotContact(const Scene& scene, const std::vector<PlotWheel>& wheels,
                 const std::string& png_path) {
  RequireGnuplot();
  const ScopedTempDir tmp("railwear-plot");
  const std::string png = fs::absolute(png_path).string();
  RunGnuplot(ContactPlotScript(scene, wheels, png), tmp, {png});
}

}  // namespace railwear::app
