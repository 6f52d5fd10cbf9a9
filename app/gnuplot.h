// Running gnuplot, an external program, for the PNG plots of `contact --plot` and `history plot`:
// the PATH check with the message users see when it is missing, quoting, the PNG terminal, and
// running a script (data files beside it in a ScopedTempDir) with gnuplot's messages on failure.
#pragma once

#include <string>
#include <vector>

#include "app/paths.h"

namespace railwear::app {

// Throws std::runtime_error "<needed_by> needs the program 'gnuplot', which is not on PATH;
// install gnuplot (e.g. apt-get install gnuplot-nox) or <alternative>" when it is not on PATH.
void RequireGnuplotFor(const std::string& needed_by, const std::string& alternative);

// `s` inside gnuplot single quotes ('' stands for ').
std::string GnuplotQuote(const std::string& s);

// The first line of every railwear plot script: pngcairo when gnuplot has it, png otherwise,
// width x height pixels, no enhanced text (names with _ print as they are).
std::string GnuplotPngTerminal(int width_px, int height_px);

// Writes `script` into `dir` and runs gnuplot on it. Throws std::runtime_error with gnuplot's
// messages when gnuplot fails or does not write every file in `outputs`.
void RunGnuplot(const std::string& script, const ScopedTempDir& dir,
                const std::vector<std::string>& outputs);

}  // namespace railwear::app
