// Wall-clock timing of SolveContact's stages (ContactResult::stages): internal to the stages.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "core/contact/contact_result.h"

namespace railwear::internal {

using Clock = std::chrono::steady_clock;

inline double SecondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Adds `seconds` to the stage `name` (appended on its first use, so stages keep their order).
inline void AddStage(std::vector<StageTime>* stages, const std::string& name, double seconds) {
  for (auto& s : *stages) {
    if (s.name == name) {
      s.seconds += seconds;
      return;
    }
  }
  stages->push_back({name, seconds});
}

}  // namespace railwear::internal
