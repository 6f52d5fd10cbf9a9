// Accuracy presets -> cell sizes. A preset fixes the number of cells per estimated contact
// semi-axis in each direction; tests/core/contact/accuracy_preset_test.cpp measures the errors
// they reach on the Hertz cases of the reference README (draft about 5 %, standard about 1 %,
// reference about 0.2 % on area and peak pressure).
#pragma once

#include "core/contact/contact_types.h"

namespace railwear {

// Cells per contact semi-axis for a preset.
double CellsPerSemiAxis(AccuracyPreset preset);

// The creep-force error a preset bounds (issue 16): the relative error of the linear-theory
// creep forces (pure xi, eta and spin) of a Hertzian patch against Kalker's (C11, C22, C23),
// for FASTSIM and the exact solver alike, and the tolerance to which `tangential = "auto"`
// keeps FASTSIM against the exact solver (tangential_method.h). Draft 15 %, standard 10 %,
// reference 4 %, fine 2 %; measured worst over H1, H3, H4 (exact solver / FASTSIM): draft
// 12.3 / 5.1 %, standard 7.4 / 5.3 %, reference 2.9 / 1.6 %, fine 1.7 / 0.9 % (the exact
// solver's first-order upwind difference; FASTSIM's from the patch size counted in cells).
// tests/core/contact/tangential_method_test.cpp checks it.
double CreepForceTolerance(AccuracyPreset preset);

struct CellSize {
  double dx_m = 0.0;
  double ds_m = 0.0;
};
// Cell size for estimated semi-axes a (along x) and b (along s), honouring the explicit
// override in `options` when given.
CellSize ChooseCellSize(const ModelOptions& options, double semi_axis_x_m, double semi_axis_s_m);

}  // namespace railwear
