// Pressure maps of `railwear contact --plot`, drawn by gnuplot (an external program).
#pragma once

#include <string>

#include "app/scene.h"
#include "core/contact/contact_solver.h"

namespace railwear::app {

// Throws std::runtime_error naming 'gnuplot' when it is not on PATH (checked before solving).
void RequireGnuplot();

// Writes a PNG: one panel per patch (multiplot), x_mm (rolling) against s_mm (lateral arc),
// colour = p_MPa; the title gives the model and the totals. Terminal pngcairo when gnuplot has
// it, png otherwise. Data and script go to a temporary directory that is removed afterwards.
// Throws std::runtime_error when gnuplot fails (with its messages).
void PlotPressure(const Scene& scene, const ContactResult& result, const std::string& png_path);

}  // namespace railwear::app
