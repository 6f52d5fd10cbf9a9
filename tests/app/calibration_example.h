// The synthetic reference data of examples/calibration/: displacement curves made from eq. 4
// with known constants, 1 % Gaussian noise and a +5 % offset per curve (both relative to the
// curve's RMS). calibrate_command_test.cpp checks that the committed CSVs are exactly these.
#pragma once

#include <string>
#include <vector>

#include "tests/calibration/synthetic_curves.h"

namespace railwear::testing {

// The constants the example data are made with (issue 5's example).
inline const InfluenceConstants kCalibrationExampleTruth{1.05, 0.6, 0.3};

struct CalibrationExampleFile {
  std::string name;  // in examples/calibration/
  DisplacementCurves curves;
};

inline std::vector<CalibrationExampleFile> CalibrationExampleFiles() {
  std::vector<CalibrationExampleFile> out;
  struct Body {
    const char* name;
    CurveBody body;
    double radius_mm;
    unsigned seed;
  };
  for (const Body& b : {Body{"synthetic_r15_convex.csv", CurveBody::kConvex, 15.0, 1},
                        Body{"synthetic_r15_5_concave.csv", CurveBody::kConcave, 15.5, 2}}) {
    SyntheticCurveSpec spec;
    spec.body = b.body;
    spec.radius_mm = b.radius_mm;
    spec.noise = 0.01;
    spec.offset = 0.05;
    DisplacementCurves c = MakeSyntheticCurves(kCalibrationExampleTruth, spec, b.seed);
    c.metadata = {{"source",
                   "synthetic: eq. 4 with c_f = 1.05, c_z = 0.6, c_s = 0.3, 1 % "
                   "Gaussian noise and a +5 % offset per curve (of its RMS), seed " +
                       std::to_string(b.seed)},
                  {"generator", "tests/app/calibration_example.h"}};
    out.push_back({b.name, std::move(c)});
  }
  return out;
}

}  // namespace railwear::testing
