// Test helpers of the sweep tests (sweep_command_test.cpp, sweep_cluster_test.cpp): the small
// wear study at another length, and the run ids of a manifest.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "tests/app/wear_scenes.h"

namespace railwear::test {

// kSmallWearStudy with `total_passes = PASSES` (its own 4e5 is a few seconds a run).
inline std::string SmallStudyOfPasses(const std::string& passes) {
  std::string s = kSmallWearStudy;
  const std::string from = "total_passes = 4e5";
  s.replace(s.find(from), from.size(), "total_passes = " + passes);
  return s;
}

// An ensemble with a real failing sample (issue 19): 3 samples of the wear coefficient and of the
// cell size along the rail's profile, uniform in [0.001, 3.001] mm, seed 115, of a base scene
// FailingSampleBase() written as "fbase.toml". Seed 115 draws one cell of 0.0037 mm, whose run
// fails at once (its grid would need 7300 cells along one axis, more than the solver's 4000),
// and cells of 1.5 and 2.7 mm, whose runs complete in about a second each. Runs in "fail_runs".
inline std::string FailingSampleBase() {
  std::string base = SmallStudyOfPasses("2e4");
  const std::string draft = "accuracy = \"draft\"";
  base.replace(base.find(draft), draft.size(), draft + "\ncell_mm = [2.0, 1.0]");
  return base;
}
inline const char* const kFailingSamplePlan = R"([sweep]
scene = "fbase.toml"
out_dir = "fail_runs"
samples = 3
seed = 115
[[axis]]
key = "wear.k"
distribution = { kind = "lognormal" }
[[axis]]
key = "model.cell_mm[0]"
distribution = { kind = "uniform", min = 0.001, max = 3.001 }
[life]
[[life.limit]]
name = "worn"
measure = "worn_area_mm2"
value = 1e-6
)";

// The run ids of a manifest (`sweep PLAN --list`'s stdout: "NNNN-HHHHHHHH  values"), in order.
inline std::vector<std::string> ManifestIds(const std::string& manifest) {
  std::vector<std::string> ids;
  std::istringstream in(manifest);
  for (std::string line; std::getline(in, line);) ids.push_back(line.substr(0, 13));
  return ids;
}

}  // namespace railwear::test
