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

// The run ids of a manifest (`sweep PLAN --list`'s stdout: "NNNN-HHHHHHHH  values"), in order.
inline std::vector<std::string> ManifestIds(const std::string& manifest) {
  std::vector<std::string> ids;
  std::istringstream in(manifest);
  for (std::string line; std::getline(in, line);) ids.push_back(line.substr(0, 13));
  return ids;
}

}  // namespace railwear::test
