// gnuplot runner: PATH lookup, quoting, `gnuplot script > log 2>&1` in a temporary directory.
#include "app/gnuplot.h"
#include "core/numerics/text_file.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

// A path inside single quotes for /bin/sh.
std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void RequireGnuplotFor(const std::string& needed_by, const std::string& alternative) {
  const char* path_env = std::getenv("PATH");
  std::stringstream dirs(path_env != nullptr ? path_env : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    std::error_code ec;
    if (fs::is_regular_file(fs::path(dir) / "gnuplot", ec)) return;
  }
  throw std::runtime_error(fmt::format(
      "{} needs the program 'gnuplot', which is not on PATH; install gnuplot (e.g. apt-get "
      "install gnuplot-nox) or {}",
      needed_by, alternative));
}

std::string GnuplotQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string GnuplotPngTerminal(int width_px, int height_px) {
  return fmt::format(
      "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {{ set terminal pngcairo size {},{} "
      "noenhanced }} else {{ set terminal png size {},{} noenhanced }}\n",
      width_px, height_px, width_px, height_px);
}

void RunGnuplot(const std::string& script, const ScopedTempDir& dir,
                const std::vector<std::string>& outputs) {
  const fs::path script_file = dir.path() / "plot.gp";
  const fs::path log = dir.path() / "gnuplot.log";
  {
    std::ofstream out(script_file);
    out << script;
    if (!out) {
      throw std::runtime_error("cannot write the gnuplot script to " + script_file.string());
    }
  }
  const std::string command = fmt::format("gnuplot {} > {} 2>&1", ShellQuote(script_file.string()),
                                          ShellQuote(log.string()));
  const int rc = std::system(command.c_str());
  if (rc != 0) {
    throw std::runtime_error(fmt::format("gnuplot failed (status {}) writing {}:\n{}", rc,
                                         fmt::join(outputs, ", "),
                                         ReadTextFile(log.string()).value_or("")));
  }
  for (const auto& file : outputs) {
    if (!fs::exists(file)) {
      throw std::runtime_error(
          fmt::format("gnuplot wrote no {}:\n{}", file, ReadTextFile(log.string()).value_or("")));
    }
  }
}

}  // namespace railwear::app
