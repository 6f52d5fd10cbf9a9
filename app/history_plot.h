// The PNG plots of `railwear history plot RUN`, drawn by gnuplot (app/gnuplot.h):
//   PREFIX_profiles.png  the rail profile after every step, coloured by MGT, zoomed on the gauge
//                        corner (equal axes, z downward as in the rail frame);
//   PREFIX_depth.png     wear depth against the arc length s along the step-0 profile, one curve
//                        per step coloured by MGT;
//   PREFIX_measures.png  W1, W2, W3 (wear/wear_measures.h) against MGT;
//   PREFIX_wheels.png    only for a run whose wheels wear (co-evolution, issue 16): each
//                        wearing wheel's depth against the arc length of its unworn profile.
// A two-rail run (issue 15) gets the low rail next to the high one in the depth plot (a second
// panel) and the measures plot (dashed curves); the profile plot shows the high rail.
//
// Also the wear rates both `railwear wear` and `history steps` print: W2 and W3 in mm/MGT.
#pragma once

#include <string>
#include <vector>

#include "profiles_db/profile_store.h"

namespace railwear::app {

// The low rail of a two-rail run as a run of its own: each step's low_rail moved into the
// StepRecord fields (measures, profile, distributions), passes and MGT kept. Empty when the run
// has no low rail (steps[0].low_rail absent).
std::vector<StepRecord> LowRailSteps(const std::vector<StepRecord>& steps);

// W2 (side) and W3 (45 degree) wear rates [mm/MGT] from step a to step b of one rail's steps:
// (W(b) - W(a)) / (MGT(b) - MGT(a)); NaN when no traffic passed between them.
struct WearRates {
  double w2_mm_per_mgt = 0.0;
  double w3_mm_per_mgt = 0.0;
};
WearRates RatesBetween(const StepRecord& a, const StepRecord& b);

// W2 and W3 rates [mm/MGT] over the last half of a run (by MGT): from half the final MGT, where
// W2 and W3 are interpolated linearly between the stored steps around it, to the last step.
// NaN when the run has no traffic. `steps` in step order (one rail's), not empty.
WearRates LastHalfRates(const std::vector<StepRecord>& steps);

// Where a step's wear-depth curve came from.
enum class DepthSource {
  kStoredWithS,   // the step's "wear_depth_mm" distribution, which carries s
  kFromProfiles,  // CompareProfiles(step 0, step) — the distribution is missing or has no s
};

// One step's wear depth against the arc length along the step-0 profile.
struct DepthCurve {
  int step = 0;
  double mgt = 0.0;
  DepthSource source = DepthSource::kFromProfiles;
  std::vector<double> s_mm, depth_mm;  // shape [n] each; NaN depths are gaps
};

// The depth curve of every step after step 0. `steps` are LoadStep results of one run (profiles
// and distributions filled), in step order, steps[0] the unworn profile. Throws InputError when
// steps[0] is not a rail head CompareProfiles can measure (wear/wear_measures.h).
std::vector<DepthCurve> WearDepthCurves(const std::vector<StepRecord>& steps);

// Co-evolution: each wearing wheel's depth curves, the normal depth of its profile at every step
// after step 0 against its step-0 profile (CompareWheelWithUnworn), s along that profile.
struct WheelDepthCurves {
  int traffic_index = 0;
  std::string name;
  std::vector<DepthCurve> curves;
};
// One per wheel of steps[0] (LoadStep results, in step order); empty for a run without them.
std::vector<WheelDepthCurves> WheelDepthCurvesOf(const std::vector<StepRecord>& steps);

// Writes the three PNGs for the run (and PREFIX_wheels.png, one depth panel per wearing wheel,
// when the run's wheels wear) and returns their paths. Throws std::runtime_error when gnuplot
// is missing (checked first) or fails; InputError when steps[0] is not a rail head on which
// MakeWearGauge can find the gauge corner (the profile plot is zoomed on it).
std::vector<std::string> PlotHistory(const std::string& run_name,
                                     const std::vector<StepRecord>& steps,
                                     const std::string& prefix);

}  // namespace railwear::app
