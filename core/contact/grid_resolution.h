// Accuracy presets -> cell sizes. A preset fixes the number of cells per estimated contact
// semi-axis in each direction; tests/core/contact/accuracy_preset_test.cpp measures the errors
// they reach on the Hertz cases of the reference README (draft about 5 %, standard about 1 %,
// reference about 0.2 % on area and peak pressure).
#pragma once

#include "core/contact/contact_types.h"

namespace railwear {

// Cells per contact semi-axis for a preset.
double CellsPerSemiAxis(AccuracyPreset preset);

struct CellSize {
  double dx_m = 0.0;
  double ds_m = 0.0;
};
// Cell size for estimated semi-axes a (along x) and b (along s), honouring the explicit
// override in `options` when given.
CellSize ChooseCellSize(const ModelOptions& options, double semi_axis_x_m, double semi_axis_s_m);

}  // namespace railwear
