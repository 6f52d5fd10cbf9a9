// Reading a study database that already exists (see stored_study.h).
#include "app/stored_study.h"

#include <filesystem>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "core/numerics/input_error.h"

namespace railwear::app {

ProfileStore OpenExistingStudy(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw InputError(fmt::format(
        "database '{}': no such file; expected an existing railwear profile-history database "
        "(--db FILE; `railwear wear` creates one, reading commands never do)",
        path));
  }
  if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) == 0) {
    throw InputError(
        fmt::format("database '{}': empty file; expected a railwear "
                    "profile-history database",
                    path));
  }
  return ProfileStore::OpenReadOnly(path);  // never writes, migrates or recovers the file
}

RunInfo FindRunOrThrow(const ProfileStore& db, const std::string& name) {
  if (auto run = db.FindRun(name)) return *run;
  std::string known;
  for (const auto& r : db.Runs()) known += (known.empty() ? "" : ", ") + ("'" + r.name + "'");
  throw InputError(
      fmt::format("database '{}': no run named '{}'; expected {}", db.path(), name,
                  known.empty() ? "a run name, but the database has no runs" : "one of " + known));
}

WearState StateFromStore(const ProfileStore& store, int64_t run, int step) {
  const StepRecord r = store.LoadStep(run, step);
  WearState state;
  state.step = r.step;
  state.passes = r.passes;
  state.mgt = r.mgt;
  state.rail = r.profile;
  for (const Distribution& d : r.distributions) {
    if (d.kind == "rcf_damage") state.damage = d.value;
  }
  if (r.low_rail) {
    state.low_rail = r.low_rail->profile;
    for (const Distribution& d : r.low_rail->distributions) {
      if (d.kind == "rcf_damage") state.low_damage = d.value;
    }
  }
  // Each vehicle entry's curving solution: where the next step starts (bit-identical resume).
  for (const CurvingStartRecord& c : r.curving_starts) {
    if (c.traffic_index >= static_cast<int>(state.curving.size())) {
      state.curving.resize(c.traffic_index + 1);
    }
    CurvingStart& start = state.curving[c.traffic_index];
    const auto n = static_cast<Eigen::Index>(c.state.size());
    start.state = Eigen::Map<const Eigen::VectorXd>(c.state.data(), n);
    if (!c.jacobian.empty())
      start.jacobian = Eigen::Map<const Eigen::MatrixXd>(c.jacobian.data(), n, n);
  }
  // Each wearing wheel's profile (co-evolution): the next step's contacts run it.
  for (const WheelStepRecord& w : r.wheels) {
    StateWheelSlot(&state, w.traffic_index, w.wheel) = w.profile;
  }
  return state;
}

}  // namespace railwear::app
