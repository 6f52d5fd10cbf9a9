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

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

// A path inside single quotes for /bin/sh.
std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A string inside gnuplot single quotes ('' stands for ').
std::string GnuplotQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Removes the temporary directory however the plot ends.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "railwear-plot-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("cannot create a temporary directory for the plot");
    }
    path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

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
      out << fmt::format(" {:.6f} {:.6g}", std::hypot(t.traction_x_Pa[c], t.traction_s_Pa[c]) * 1e-6,
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
  s << fmt::format(
      "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {{ set terminal pngcairo size {},{} "
      "noenhanced }} else {{ set terminal png size {},{} noenhanced }}\n",
      500 * std::max(n, 2), height, 500 * std::max(n, 2), height);
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
      s << "set cblabel '|q| [MPa]'\nset title " << GnuplotQuote(fmt::format("patch {}: traction", k + 1)) << "\n";
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

std::string ReadAll(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace

void RequireGnuplot() {
  const char* path_env = std::getenv("PATH");
  std::stringstream dirs(path_env != nullptr ? path_env : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    std::error_code ec;
    if (fs::is_regular_file(fs::path(dir) / "gnuplot", ec)) return;
  }
  throw std::runtime_error(
      "--plot needs the program 'gnuplot', which is not on PATH; install gnuplot (e.g. "
      "apt-get install gnuplot-nox) or leave out --plot");
}

void PlotPressure(const Scene& scene, const ContactResult& result, const std::string& png_path) {
  RequireGnuplot();
  const TempDir tmp;
  const fs::path script = tmp.path / "pressure.gp";
  const fs::path log = tmp.path / "gnuplot.log";
  {
    std::ofstream out(script);
    out << Script(scene, result, tmp.path, fs::absolute(png_path).string());
    if (!out) throw std::runtime_error("cannot write the gnuplot script to " + script.string());
  }
  const std::string command = fmt::format("gnuplot {} > {} 2>&1", ShellQuote(script.string()),
                                          ShellQuote(log.string()));
  const int rc = std::system(command.c_str());
  if (rc != 0) {
    throw std::runtime_error(
        fmt::format("gnuplot failed (status {}) writing {}:\n{}", rc, png_path, ReadAll(log)));
  }
  if (!fs::exists(png_path)) {
    throw std::runtime_error(fmt::format("gnuplot wrote no {}:\n{}", png_path, ReadAll(log)));
  }
}

}  // namespace railwear::app
