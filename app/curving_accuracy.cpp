// `railwear accuracy --curving`: steady-state curving at each accuracy level (curving_accuracy.h).
#include "app/curving_accuracy.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <utility>

#include <fmt/format.h>

#include "app/accuracy_config.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "wear/vehicle_traffic.h"

namespace railwear::app {

CurvingAccuracyStudy RunCurvingAccuracyStudy(
    const Scene& scene, const std::vector<std::string>& level_names,
    const std::function<void(const std::string&)>& progress) {
  if (!scene.wear || scene.wear->vehicles.empty()) {
    throw InputError(fmt::format(
        "{}: --curving needs a wear scene with [track], [[vehicle]] tables and [[traffic]] "
        "entries naming a vehicle",
        scene.path));
  }
  const std::vector<AccuracyPreset> presets = ParseAccuracyLevels(level_names);
  const WearStudy& study = *scene.wear;
  const TrackRails rails = UnwornRailsInTrack(study);
  CurvingAccuracyStudy out;
  out.scene_path = scene.path;
  for (AccuracyPreset a : presets) out.levels.emplace_back(ToString(a));
  for (int t = 0; t < static_cast<int>(study.traffic.size()); ++t) {
    const TrafficCase& c = study.traffic[t];
    if (!c.is_vehicle()) continue;
    std::vector<CurvingResult> results;
    // The scene's predictor at every level (absent: each level's default,
    // CurvingOptions::ColdPredictorFor), then the other one at the finest.
    auto own = [&](AccuracyPreset a) {
      CurvingProblem p = VehicleCurvingProblem(study, t, rails.high, rails.low);
      p.contact.model.accuracy = a;
      return p.options.ColdPredictorFor(p.contact.model);
    };
    const CurvingPredictor other = own(presets.back()) == CurvingPredictor::kTable
                                       ? CurvingPredictor::kModel
                                       : CurvingPredictor::kTable;
    std::vector<std::pair<AccuracyPreset, CurvingPredictor>> runs;
    for (AccuracyPreset a : presets) runs.emplace_back(a, own(a));
    runs.emplace_back(presets.back(), other);
    for (const auto& [a, predictor] : runs) {
      CurvingProblem p = VehicleCurvingProblem(study, t, rails.high, rails.low);
      p.contact.model.accuracy = a;
      p.options.cold_predictor = predictor;
      results.push_back(SolveCurving(p));
      const CurvingResult& r = results.back();
      CurvingAccuracyRow row;
      row.traffic = c.name;
      row.level = std::string(ToString(a));
      row.predictor = std::string(ToString(predictor));
      if (r.table_predictor == TablePredictorOutcome::kFellBack) row.predictor += " (fell_back)";
      row.status = std::string(ToString(r.status));
      row.time_s = r.time_s;
      row.solves = r.contact_solves;
      if (!r.wheelsets.empty()) {
        const CurvedWheelset& lead = r.wheelsets.front();
        row.lead_y_mm = lead.lateral_m * kToMm;
        row.lead_psi_mrad = lead.yaw_rad * 1e3;
        row.lead_y_high_kN = lead.high_lateral_N * 1e-3;
        row.lead_l_over_v = lead.high_climb.l_over_v;
      }
      if (progress) {
        progress(fmt::format("{}: {}, {} predictor: {} in {:.1f} s, {} wheelset solves{}", c.name,
                             row.level, row.predictor, row.status, row.time_s, row.solves,
                             predictor == CurvingPredictor::kTable
                                 ? fmt::format(", {} table evaluations, table built in {:.2f} s",
                                               r.table_evaluations, r.table_build_s)
                                 : std::string()));
      }
      out.rows.push_back(row);
    }
    // Against the finest level's solution of this entry with the scene's predictor.
    const CurvingResult& ref = results[presets.size() - 1];
    const size_t first = out.rows.size() - results.size();
    for (size_t k = 0; k < results.size(); ++k) {
      CurvingAccuracyRow& row = out.rows[first + k];
      const CurvingResult& r = results[k];
      for (size_t i = 0; i < std::min(r.wheelsets.size(), ref.wheelsets.size()); ++i) {
        const CurvedWheelset &w = r.wheelsets[i], &v = ref.wheelsets[i];
        row.err_y_mm = std::max(row.err_y_mm, std::abs(w.lateral_m - v.lateral_m) * kToMm);
        row.err_psi_mrad = std::max(row.err_psi_mrad, std::abs(w.yaw_rad - v.yaw_rad) * 1e3);
        row.err_y_high_kN =
            std::max(row.err_y_high_kN, std::abs(w.high_lateral_N - v.high_lateral_N) * 1e-3);
      }
    }
  }
  return out;
}

std::string FormatCurvingAccuracyTable(const CurvingAccuracyStudy& s) {
  std::string t = fmt::format(
      "steady-state curving at each accuracy level: {} (reference: {} with the scene's cold "
      "predictor; the last row of each entry: the other predictor; lead = wheelset 0; "
      "errors: largest over the wheelsets against the reference)\n",
      s.scene_path, s.levels.back());
  t += fmt::format(
      "{:<24} {:<10} {:<18} {:<14} {:>8} {:>7} {:>8} {:>9} {:>9} {:>7} {:>8} {:>9} {:>9}\n",
      "traffic", "level", "predictor", "status", "time_s", "solves", "lead_y", "lead_psi",
      "lead_Yhi", "L/V", "err_y_mm", "err_psi", "err_Y_kN");
  for (const CurvingAccuracyRow& r : s.rows) {
    t += fmt::format(
        "{:<24} {:<10} {:<18} {:<14} {:8.2f} {:7d} {:8.3f} {:9.3f} {:9.2f} {:7.3f} {:8.3f} "
        "{:9.3f} {:9.2f}\n",
        r.traffic.substr(0, 24), r.level, r.predictor, r.status, r.time_s, r.solves, r.lead_y_mm,
        r.lead_psi_mrad, r.lead_y_high_kN, r.lead_l_over_v, r.err_y_mm, r.err_psi_mrad,
        r.err_y_high_kN);
  }
  return t;
}

void WriteCurvingAccuracyCsv(const CurvingAccuracyStudy& s, std::ostream& out) {
  out << "traffic,level,status,time_s,solves,lead_y_mm,lead_psi_mrad,lead_y_high_kN,"
         "lead_l_over_v,err_y_mm,err_psi_mrad,err_y_high_kN,predictor\n";
  for (const CurvingAccuracyRow& r : s.rows) {
    out << fmt::format(
        "\"{}\",{},{},{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},\"{}\"\n",
        r.traffic, r.level, r.status, r.time_s, r.solves, r.lead_y_mm, r.lead_psi_mrad,
        r.lead_y_high_kN, r.lead_l_over_v, r.err_y_mm, r.err_psi_mrad, r.err_y_high_kN,
        r.predictor);
  }
}

}  // namespace railwear::app
