// Accuracy presets (see grid_resolution.h).
#include "core/contact/grid_resolution.h"

namespace railwear {

double CellsPerSemiAxis(AccuracyPreset preset) {
  switch (preset) {
    case AccuracyPreset::kDraft:
      return 4.0;  // H1-H4: area and p0 within about 0.7 %
    case AccuracyPreset::kStandard:
      return 10.0;  // within about 0.3 %
    case AccuracyPreset::kReference:
      return 24.0;  // within about 0.2 %
    case AccuracyPreset::kFine:
      return 40.0;  // p0 within 0.01 %, area 0.2 % (estimator)
  }
  return 10.0;
}

double CreepForceTolerance(AccuracyPreset preset) {
  switch (preset) {
    case AccuracyPreset::kDraft:
      return 0.15;
    case AccuracyPreset::kStandard:
      return 0.10;
    case AccuracyPreset::kReference:
      return 0.04;
    case AccuracyPreset::kFine:
      return 0.02;
  }
  return 0.10;
}

CellSize ChooseCellSize(const ModelOptions& options, double semi_axis_x_m, double semi_axis_s_m) {
  const double n = CellsPerSemiAxis(options.accuracy);
  CellSize c{semi_axis_x_m / n, semi_axis_s_m / n};
  if (options.cell_dx_m) c.dx_m = *options.cell_dx_m;
  if (options.cell_ds_m) c.ds_m = *options.cell_ds_m;
  return c;
}

}  // namespace railwear
