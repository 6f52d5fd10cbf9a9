// Everything a wear run stored in a study database, as text, bit for bit: shared by the tests
// that interrupt, kill and resume runs (wear_interrupt_test.cpp, wheel_wear_cli_test.cpp) and the
// serial / MPI / Slurm sweeps' merges (sweep_cluster_test.cpp).
#pragma once

#include <ios>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "profiles_db/profile_store.h"
#include "tests/test_support.h"

namespace railwear::test {

// Everything a run stored, bit for bit (doubles as hexfloat), except the creation times: the
// run's scene, wear law and state, and per step its summary, profile, load cases and
// distributions (and the low rail's, and the wearing wheels').
inline std::string RunFingerprint(const fs::path& db, const std::string& name = "small study") {
  const ProfileStore store = ProfileStore::OpenReadOnly(db.string());
  const std::optional<RunInfo> run = store.FindRun(name);
  if (!run) return "no run";
  std::ostringstream os;
  os << std::hexfloat << run->scene_text << '\n'
     << run->wear_law_json << '\n'
     << ToString(run->state) << '\n';
  const auto doubles = [&os](const char* what, const std::vector<double>& v) {
    os << what;
    for (const double x : v) os << ' ' << x;
    os << '\n';
  };
  const auto distributions = [&](const std::vector<Distribution>& all) {
    for (const Distribution& d : all) {
      os << d.kind << '\n';
      doubles("y", d.y_m);
      doubles("value", d.value);
      doubles("s", d.s_m);
    }
  };
  for (const StepRecord& summary : store.Steps(run->id)) {
    const StepRecord s = store.LoadStep(run->id, summary.step);
    os << "step " << s.step << ' ' << s.passes << ' ' << s.mgt << ' ' << s.worn_area_mm2 << ' '
       << s.max_depth_mm << ' ' << s.max_depth_y_mm << ' ' << s.w1_mm << ' ' << s.w2_mm << ' '
       << s.w3_mm << ' ' << s.smoothing_area_error << '\n';
    for (const auto& p : s.profile.points()) os << p.x() << ',' << p.y() << ' ';
    os << '\n';
    for (const std::string& j : s.load_cases_json) os << j << '\n';
    distributions(s.distributions);
    if (s.low_rail) {
      os << "low rail " << s.low_rail->worn_area_mm2 << ' ' << s.low_rail->max_depth_mm << '\n';
      for (const auto& p : s.low_rail->profile.points()) os << p.x() << ',' << p.y() << ' ';
      distributions(s.low_rail->distributions);
    }
    for (const WheelStepRecord& w : s.wheels) {  // co-evolution (issue 16)
      os << "wheel " << w.traffic_index << (w.wheel != 0 ? ":" + std::to_string(w.wheel) : "")
         << ' ' << w.name << ' ' << w.worn_area_mm2 << ' '
         << w.max_depth_mm << ' ' << w.max_depth_y_mm << ' ' << w.smoothing_area_error << ' '
         << w.flange_height_mm.value_or(-1.0) << ' ' << w.flange_thickness_mm.value_or(-1.0) << ' '
         << w.flange_slope_mm.value_or(-1.0) << '\n';
      for (const auto& p : w.profile.points()) os << p.x() << ',' << p.y() << ' ';
      os << '\n';
    }
  }
  return os.str();
}

}  // namespace railwear::test
