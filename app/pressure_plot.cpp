// Pressure maps via gnuplot: data files and a script in a temporary directory, then `gnuplot`.
#include "app/pressure_plot.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "app/contact_output.h"
#include "app/gnuplot.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

// One data file per patch: x_mm s_mm p_MPa, and with rolling contact also |q|_MPa and
// |v_slip|_mm_s; a blank line after each s row.
std::string WritePatchData(const PatchResult& patch, int number, const fs::path& dir) {
  const fs::path file = dir / fmt::format("patch{}.dat", number);
  std::ofstream out(file);
  int row = -1;
  for (const auto& s : PressureSamples(patch, number)) {
    if (row >= 0 && s.js != row) out << "\n";
    row = s.js;
    out << fmt::format("{:.6f} {:.6f} {:.6f}", s.x_mm, s.s_mm, s.p_MPa);
    if (patch.rolling) {
      const TangentialSolution& t = patch.rolling->tangential;
      const int c = patch.grid.Index(s.ix, s.js);
      out << fmt::format(" {:.6f} {:.6g}",
                         std::hypot(t.traction_x_Pa[c], t.traction_s_Pa[c]) * 1e-6,
                         std::hypot(t.slip_x_m_s[c], t.slip_s_m_s[c]) * 1e3);
    }
    out << "\n";
  }
  if (!out) throw std::runtime_error("cannot write plot data to " + file.string());
  return file.string();
}

std::string Title(const Scene& scene, const ContactResult& r) {
  return fmt::format("{} - {} model, {} accuracy", scene.name, ToString(r.model.kind),
                     ToString(r.model.accuracy));
}

std::string PatchTitle(const PatchResult& p, int number) {
  return fmt::format("patch {}: area {:.1f} mm^2, p_max {:.0f} MPa, angle {:.1f} deg", number,
                     p.area_m2 * 1e6, p.p_max_Pa * 1e-6, p.contact_angle_rad * 180.0 / M_PI);
}

std::string Script(const Scene& scene, const ContactResult& r, const fs::path& dir,
                   const std::string& png_path) {
  const int n = static_cast<int>(r.patches.size());
  const int height = (n > 0 && r.patches[0].rolling) ? 1500 : 600;
  std::ostringstream s;
  s << GnuplotPngTerminal(500 * std::max(n, 2), height);
  s << "set output " << GnuplotQuote(png_path) << "\n";
  s << "set xlabel 'x [mm] (rolling)'\nset ylabel 's [mm] (lateral arc)'\n";
  s << "set cblabel 'p [MPa]'\nset size ratio -1\nset palette rgb 33,13,10\n";
  // With rolling contact: a second and third row of maps, traction |q| and slip velocity.
  const bool rolling = n > 0 && r.patches[0].rolling.has_value();
  s << fmt::format("set multiplot layout {},{} columnsfirst title {}\n", rolling ? 3 : 1,
                   std::max(n, 1), GnuplotQuote(Title(scene, r)));
  for (int k = 0; k < n; ++k) {
    const std::string data = WritePatchData(r.patches[k], k + 1, dir);
    s << "set cblabel 'p [MPa]'\n";
    s << "set title " << GnuplotQuote(PatchTitle(r.patches[k], k + 1)) << "\n";
    s << "plot " << GnuplotQuote(data) << " using 1:2:3 with image notitle\n";
    if (rolling) {
      s << "set cblabel '|q| [MPa]'\nset title "
        << GnuplotQuote(fmt::format("patch {}: traction", k + 1)) << "\n";
      s << "plot " << GnuplotQuote(data) << " using 1:2:4 with image notitle\n";
      s << "set cblabel '|v_slip| [mm/s]'\nset title "
        << GnuplotQuote(fmt::format("patch {}: slip velocity (0 = stick)", k + 1)) << "\n";
      s << "plot " << GnuplotQuote(data) << " using 1:2:5 with image notitle\n";
    }
  }
  if (n == 0) s << "set title 'no contact'\nunset colorbox\nplot [-1:1][-1:1] NaN notitle\n";
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace

void RequireGnuplot() { RequireGnuplotFor("--plot", "leave out --plot"); }

void PlotPressure(const Scene& scene, const ContactResult& result, const std::string& png_path) {
  RequireGnuplot();
  const ScopedTempDir tmp("railwear-plot");
  const std::string png = fs::absolute(png_path).string();
  RunGnuplot(Script(scene, result, tmp.path(), png), tmp, {png});
}

}  // namespace railwear::app
