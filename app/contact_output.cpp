// Summary, JSON and CSV output of `railwear contact`.
#include "app/contact_output.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "app/influence_constants_file.h"
#include "core/contact/contact_forces.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace {

std::vector<PressureSample> GridSamples(const PatchResult& patch, int patch_number) {
  const PatchGrid& g = patch.grid;
  if (patch.pressure_Pa.size() != g.cells() || static_cast<int>(g.point_yz_m.size()) != g.ns) {
    throw std::runtime_error(
        fmt::format("patch {}: pressure field has {} values for a grid of {} x {} cells",
                    patch_number, patch.pressure_Pa.size(), g.nx, g.ns));
  }
  std::vector<PressureSample> out;
  out.reserve(g.cells());
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      out.push_back({patch_number, i, j, g.X(i) * kToMm, g.S(j) * kToMm,
                     g.point_yz_m[j].x() * kToMm, g.point_yz_m[j].y() * kToMm,
                     patch.pressure_Pa[g.Index(i, j)] * kToMPa});
    }
  }
  return out;
}

// p = p0 sqrt(1 - (x/a)^2 - (s/b)^2) on a regular grid over [-a, a] x [-b, b].
std::vector<PressureSample> HertzSamples(const PatchResult& patch, int patch_number) {
  const HertzSolution& h = *patch.hertz;
  const double a = h.semi_axis_x_m, b = h.semi_axis_y_m;
  const Eigen::Vector2d t(std::cos(patch.contact_angle_rad), std::sin(patch.contact_angle_rad));
  std::vector<PressureSample> out;
  out.reserve(kHertzSamples * kHertzSamples);
  for (int j = 0; j < kHertzSamples; ++j) {
    const double s = -b + 2.0 * b * j / (kHertzSamples - 1);
    const Eigen::Vector2d yz = patch.contact_point_yz_m + s * t;
    for (int i = 0; i < kHertzSamples; ++i) {
      const double x = -a + 2.0 * a * i / (kHertzSamples - 1);
      const double r2 = (a > 0 && b > 0) ? (x / a) * (x / a) + (s / b) * (s / b) : 1.0;
      const double p = r2 < 1.0 ? h.p0_Pa * std::sqrt(1.0 - r2) : 0.0;
      out.push_back(
          {patch_number, i, j, x * kToMm, s * kToMm, yz.x() * kToMm, yz.y() * kToMm, p * kToMPa});
    }
  }
  return out;
}

// Creep forces are those of the rail on the wheel: x along the rolling direction, y along the
// patch's lateral arc (its s tangent), and the latter also as rail-frame (y, z) components.
void AddRollingJson(const RollingPatch& r, nlohmann::json* j) {
  const TangentialSolution& t = r.tangential;
  (*j)["tangential_status"] = ToString(t.status);
  if (r.choice.automatic) {
    // tangential = "auto": the solver it chose for this patch, its indicators and the rule.
    (*j)["tangential_method"] = ToString(r.choice.method);
    (*j)["tangential_reason"] = r.choice.reason;
    (*j)["tangential_spin_share"] = r.choice.spin_share;
    (*j)["tangential_a_over_b"] = r.choice.a_over_b;
    (*j)["tangential_creepage_residual"] = r.choice.creepage_residual;
  }
  (*j)["creep_force_N"] = {{"x", t.force_x_N}, {"y", t.force_s_N}};
  (*j)[contact_json::kCreepForceYzN] = {{"y", t.force_s_yz_N.x()}, {"z", t.force_s_yz_N.y()}};
  (*j)["spin_moment_Nmm"] = t.spin_moment_Nm * 1e3;
  (*j)["creepage"] = {{"xi", r.creepage.xi},
                      {"eta", r.creepage.eta},
                      {"spin_per_mm", r.creepage.spin_per_m * 1e-3}};
  (*j)["stick_area_mm2"] = t.stick_area_m2 * kToMm2;
  (*j)["slip_area_mm2"] = t.slip_area_m2 * kToMm2;
  (*j)["frictional_power_W"] = t.frictional_power_W;
  if (r.damage) {
    const PatchDamage& d = *r.damage;
    (*j)["damage"] = {{"t_gamma_J_per_m", d.t_gamma_N},
                      {"spin_work_J_per_m", d.spin_work_N},
                      {"spin_share", d.spin_share},
                      {"wlrm_rcf_damage_per_axle", d.wlrm_damage},
                      {"traction_coefficient", d.traction_coefficient},
                      {"fi_surf", d.fi_surf},
                      {"shakedown",
                       {{"load_factor_p_max_over_k", d.shakedown.load_factor},
                        {"elastic_limit", d.shakedown.elastic_limit},
                        {"shakedown_limit", d.shakedown.shakedown_limit},
                        {"margin", d.shakedown.margin},
                        {"regime", ToString(d.shakedown.regime)}}}};
  }
}

std::string RollingTable(const ContactResult& r) {
  std::string out = fmt::format(
      "{:>5} {:>10} {:>10} {:>11} {:>10} {:>10} {:>12} {:>9} {:>9} {:>9}\n", "patch", "Fx_N",
      "Fy_N", "Mspin_Nmm", "xi", "eta", "phi_per_mm", "stick_mm2", "slip_mm2", "power_W");
  for (size_t k = 0; k < r.patches.size(); ++k) {
    if (!r.patches[k].rolling) continue;
    const RollingPatch& rp = *r.patches[k].rolling;
    const TangentialSolution& t = rp.tangential;
    out += fmt::format(
        "{:>5} {:>10.1f} {:>10.1f} {:>11.1f} {:>10.6f} {:>10.6f} {:>12.7f} "
        "{:>9.2f} {:>9.2f} {:>9.1f}\n",
        k + 1, t.force_x_N, t.force_s_N, t.spin_moment_Nm * 1e3, rp.creepage.xi, rp.creepage.eta,
        rp.creepage.spin_per_m * 1e-3, t.stick_area_m2 * kToMm2, t.slip_area_m2 * kToMm2,
        t.frictional_power_W);
    if (rp.choice.automatic) out += fmt::format("      tangential auto: {}\n", rp.choice.reason);
    if (rp.damage) {
      const PatchDamage& d = *rp.damage;
      out += fmt::format(
          "      damage: T-gamma {:.1f} J/m (spin {:.1f} J/m more, {:.0f} % of the frictional "
          "work), WLRM RCF {:.3g} per axle, FI_surf {:.3f}, p_max/k {:.2f} at mu_eff {:.3f} ({}, "
          "margin {:.2f})\n",
          d.t_gamma_N, d.spin_work_N, 100.0 * d.spin_share, d.wlrm_damage, d.fi_surf,
          d.shakedown.load_factor, d.traction_coefficient, ToString(d.shakedown.regime),
          d.shakedown.margin);
    }
  }
  return out;
}

nlohmann::json PatchJson(const PatchResult& p) {
  nlohmann::json j;
  j["area_mm2"] = p.area_m2 * kToMm2;
  j["p_max_MPa"] = p.p_max_Pa * kToMPa;
  j["normal_force_N"] = p.normal_force_N;
  j["vertical_force_N"] = p.vertical_force_N;
  j["lateral_force_N"] = p.lateral_force_N;
  j["contact_x_mm"] = p.contact_x_m * kToMm;
  j["contact_y_mm"] = p.contact_point_yz_m.x() * kToMm;
  j["contact_z_mm"] = p.contact_point_yz_m.y() * kToMm;
  j["contact_angle_deg"] = p.contact_angle_rad * kToDeg;
  j["cells"] = p.cells;
  j["cells_in_contact"] = p.cells_in_contact;
  // The model the patch was solved with; with kind = auto also why it was chosen.
  if (!p.model.empty()) j["model"] = p.model;
  if (!p.model_reason.empty()) j["model_reason"] = p.model_reason;
  if (p.grid.cells() > 0) {
    j["cell_mm"] = {p.grid.dx_m * kToMm, p.grid.ds_m * kToMm};
  } else {
    j["cell_mm"] = nullptr;  // Hertz: analytic, no grid
  }
  if (p.hertz) {
    j["hertz"] = {{"semi_axis_x_mm", p.hertz->semi_axis_x_m * kToMm},
                  {"semi_axis_y_mm", p.hertz->semi_axis_y_m * kToMm}};
  }
  if (p.rolling) AddRollingJson(*p.rolling, &j);
  return j;
}

std::string StagesLine(const ContactResult& r) {
  std::string out;
  for (const auto& s : r.stages) {
    out += fmt::format("{}{} {:.1f} ms", out.empty() ? "" : ", ", s.name, s.seconds * kToMs);
  }
  return out.empty() ? std::string() : fmt::format(" ({})", out);
}

// The plastic share (cells at the pressure limit) of one patch or of the total, when the scene
// set a limit: cells, their share of the cells in contact, area and normal load.
nlohmann::json PlasticJson(int cells, int cells_in_contact, double area_m2, double force_N,
                           double normal_force_N) {
  return {{"cells", cells},
          {"cell_share", cells_in_contact > 0 ? double(cells) / cells_in_contact : 0.0},
          {"area_mm2", area_m2 * kToMm2},
          {"normal_force_N", force_N},
          {"force_share", normal_force_N > 0.0 ? force_N / normal_force_N : 0.0}};
}

std::string PlasticText(int cells, int cells_in_contact, double area_m2, double force_N,
                        double normal_force_N) {
  return fmt::format(
      "{} of {} cells in contact ({:.1f} %), area {:.2f} mm2, load {:.1f} N ({:.1f} % "
      "of the normal load)",
      cells, cells_in_contact, cells_in_contact > 0 ? 100.0 * cells / cells_in_contact : 0.0,
      area_m2 * kToMm2, force_N, normal_force_N > 0.0 ? 100.0 * force_N / normal_force_N : 0.0);
}

// Sums over the patches of the cells in contact and the normal force [N].
std::pair<int, double> ContactCellsAndNormalForce(const ContactResult& r) {
  int cells = 0;
  double normal = 0.0;
  for (const PatchResult& p : r.patches) {
    cells += p.cells_in_contact;
    normal += p.normal_force_N;
  }
  return {cells, normal};
}

std::string PlasticLines(const ContactResult& r) {
  if (!r.pressure_limit_Pa) return "";
  const auto [cells, normal] = ContactCellsAndNormalForce(r);
  std::string out = fmt::format(
      "plastic     pressure limit {:.1f} MPa: {}\n", *r.pressure_limit_Pa * kToMPa,
      PlasticText(r.plastic_cells, cells, r.plastic_area_m2, r.plastic_force_N, normal));
  if (r.patches.size() > 1) {
    for (size_t k = 0; k < r.patches.size(); ++k) {
      const PatchResult& p = r.patches[k];
      out += fmt::format("            patch {}: {}\n", k + 1,
                         PlasticText(p.plastic_cells, p.cells_in_contact, p.plastic_area_m2,
                                     p.plastic_force_N, p.normal_force_N));
    }
  }
  return out;
}

std::string PatchTable(const ContactResult& r) {
  std::string out =
      fmt::format("{:>5} {:>10} {:>10} {:>11} {:>9} {:>9} {:>9} {:>15}\n", "patch", "area_mm2",
                  "p_max_MPa", "normal_N", "y_mm", "z_mm", "angle_deg", "cells_contact");
  for (size_t k = 0; k < r.patches.size(); ++k) {
    const PatchResult& p = r.patches[k];
    const std::string cells =
        p.cells > 0 ? fmt::format("{}/{}", p.cells_in_contact, p.cells) : "analytic";
    out += fmt::format("{:>5} {:>10.2f} {:>10.1f} {:>11.1f} {:>9.3f} {:>9.3f} {:>9.2f} {:>15}\n",
                       k + 1, p.area_m2 * kToMm2, p.p_max_Pa * kToMPa, p.normal_force_N,
                       p.contact_point_yz_m.x() * kToMm, p.contact_point_yz_m.y() * kToMm,
                       p.contact_angle_rad * kToDeg, cells);
  }
  return out;
}

nlohmann::json XyzJson(const Eigen::Vector3d& f) {
  return {{"x", f.x()}, {"y", f.y()}, {"z", f.z()}};
}

nlohmann::json PatchAxesJson(const Eigen::Vector3d& f) {
  return {{"normal", f.x()}, {"longitudinal", f.y()}, {"lateral", f.z()}};
}

// Normal (pressure), creep and net parts of a force on the rail in the rail and track frames.
nlohmann::json FramesJson(const ForceParts& f, bool left_wheel) {
  return {
      {"rail",
       {{"normal", XyzJson(f.normal_N)}, {"creep", XyzJson(f.creep_N)}, {"net", XyzJson(f.Net())}}},
      {"track",
       {{"normal", XyzJson(RailToTrackFrame(f.normal_N, left_wheel))},
        {"creep", XyzJson(RailToTrackFrame(f.creep_N, left_wheel))},
        {"net", XyzJson(RailToTrackFrame(f.Net(), left_wheel))}}}};
}

// The labelled forces of DESIGN.md §8 (issue 14): on the rail, in the rail, track and (per
// patch) patch frames, as pressure ("normal"), creep and net parts.
nlohmann::json ForcesJson(const ContactResult& r, bool left_wheel) {
  nlohmann::json j;
  j["on"] = "rail";
  j["unit"] = "N";
  j["frames"] = {
      {"rail", "rail profile frame R: x forward, y toward this rail's field side, z down"},
      {"track", left_wheel ? "track frame T: x forward, Y right, z down (left wheel: R mirrored)"
                           : "track frame T: x forward, Y right, z down (right wheel: = R)"},
      {"patch",
       "normal (into the rail, along the patch's pressure resultant), longitudinal (x), lateral "
       "(tangent plane, toward the field side)"}};
  j["total"] = FramesJson(TotalForcesOnRail(r), left_wheel);
  j["patches"] = nlohmann::json::array();
  for (const PatchResult& p : r.patches) {
    const ForceParts f = PatchForcesOnRail(p);
    nlohmann::json pj = FramesJson(f, left_wheel);
    pj["patch"] = {{"normal", PatchAxesJson(RailToPatchFrame(f.normal_N, p.contact_angle_rad))},
                   {"creep", PatchAxesJson(RailToPatchFrame(f.creep_N, p.contact_angle_rad))},
                   {"net", PatchAxesJson(RailToPatchFrame(f.Net(), p.contact_angle_rad))}};
    pj["contact_angle_deg"] = p.contact_angle_rad * kToDeg;
    j["patches"].push_back(std::move(pj));
  }
  return j;
}

nlohmann::json OptionalNumber(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// L/V, Nadal's limit and its verdict.
nlohmann::json ClimbJson(const FlangeClimbCheck& c) {
  return {{"l_over_v", c.l_over_v},
          {"contact_angle_deg", c.contact_angle_rad * kToDeg},
          {"friction", OptionalNumber(c.friction)},
          {"nadal_limit", OptionalNumber(c.nadal_limit)},
          {"exceeded", c.exceeded}};
}

std::string ClimbLine(const FlangeClimbCheck& c) {
  std::string limit;
  if (!c.friction) {
    limit = "no Nadal limit (normal contact, no friction)";
  } else if (!c.nadal_limit) {
    limit = fmt::format(
        "no Nadal limit (steepest contact angle {:.1f} deg <= atan(mu) = {:.1f} deg: no climb)",
        c.contact_angle_rad * kToDeg, std::atan(*c.friction) * kToDeg);
  } else {
    limit = fmt::format("Nadal's limit {:.3f} at {:.1f} deg, mu {:.3g}{}", *c.nadal_limit,
                        c.contact_angle_rad * kToDeg, *c.friction, c.exceeded ? ": EXCEEDED" : "");
  }
  return fmt::format("L/V         {:.3f} (net forces on the rail, rail frame); {}\n", c.l_over_v,
                     limit);
}

// Per patch: the forces on the rail, rail frame, pressure / creep / net.
std::string ForceTable(const ContactResult& r) {
  std::string out = fmt::format("{:>5} {:>8} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11}\n", "patch",
                                "part", "x_N", "y_N", "z_N", "normal_N", "long_N", "lat_N");
  for (size_t k = 0; k < r.patches.size(); ++k) {
    const ForceParts f = PatchForcesOnRail(r.patches[k]);
    const double g = r.patches[k].contact_angle_rad;
    const std::pair<const char*, Eigen::Vector3d> parts[] = {
        {"pressure", f.normal_N}, {"creep", f.creep_N}, {"net", f.Net()}};
    for (const auto& [name, v] : parts) {
      const Eigen::Vector3d pf = RailToPatchFrame(v, g);
      out +=
          fmt::format("{:>5} {:>8} {:>11.1f} {:>11.1f} {:>11.1f} {:>11.1f} {:>11.1f} {:>11.1f}\n",
                      k + 1, name, v.x(), v.y(), v.z(), pf.x(), pf.y(), pf.z());
    }
  }
  return out;
}

}  // namespace

nlohmann::json ModelJson(const ModelOptions& m) {
  nlohmann::json j;
  j["kind"] = ToString(m.kind);
  const bool hertz = m.kind == ModelKind::kHertz;
  // auto: the geometry is chosen per patch (patches[].model); kernel is that of its conformal
  // patches.
  const bool per_patch = hertz || m.kind == ModelKind::kAuto;
  j["geometry"] = per_patch ? nlohmann::json(nullptr) : nlohmann::json(ToString(m.geometry));
  j["kernel"] = hertz ? nlohmann::json(nullptr) : nlohmann::json(ToString(m.kernel));
  j["accuracy"] = ToString(m.accuracy);
  j["influence_constants"] = InfluenceConstantsJson(m.constants);
  // Which set (issue 17): "fem" (the default), "paper" or "custom"; Hertz uses none.
  j["constants"] = hertz ? nlohmann::json(nullptr) : nlohmann::json(ConstantsSetName(m.constants));
  return j;
}

std::string ModelLine(const ModelOptions& m) {
  if (m.kind == ModelKind::kHertz) {
    return fmt::format("hertz (analytic), accuracy {}", ToString(m.accuracy));
  }
  if (m.kind == ModelKind::kAuto) {
    return fmt::format("auto (per patch: hertz, halfspace or conformal+{}), accuracy {}, {}",
                       ToString(m.kernel), ToString(m.accuracy),
                       InfluenceConstantsLine(m.constants));
  }
  return fmt::format("{} (geometry {}, kernel {}), accuracy {}, {}", ToString(m.kind),
                     ToString(m.geometry), ToString(m.kernel), ToString(m.accuracy),
                     InfluenceConstantsLine(m.constants));
}

std::vector<PressureSample> PressureSamples(const PatchResult& patch, int patch_number) {
  if (patch.grid.cells() == 0 && patch.hertz) return HertzSamples(patch, patch_number);
  return GridSamples(patch, patch_number);
}

std::optional<std::string> HardnessWarning(const Material& wheel_material, const Material& rail,
                                           double p_max_Pa, const std::string& wheel) {
  // The softer body of those whose hardness is given.
  const bool rail_softer = rail.hardness_Pa > 0 && !(wheel_material.hardness_Pa > 0 &&
                                                     wheel_material.hardness_Pa < rail.hardness_Pa);
  const double hardness_Pa = rail_softer ? rail.hardness_Pa : wheel_material.hardness_Pa;
  // A pressure limit at the hardness holds p_max at it: only a clear excess is reported.
  constexpr double kHardnessMargin = 1e-6;  // relative; far above the limit's rounding
  if (!(hardness_Pa > 0 && p_max_Pa > hardness_Pa * (1.0 + kHardnessMargin))) return std::nullopt;
  return fmt::format(
      "{}p_max {:.0f} MPa exceeds the {}'s hardness {:.0f} MPa: the elastic solution is beyond "
      "yield there (pressure_limit = \"hardness\" bounds it)",
      wheel.empty() ? "" : wheel + ": ", p_max_Pa * kToMPa, rail_softer ? "rail" : "wheel",
      hardness_Pa * kToMPa);
}

std::vector<std::string> ContactWarnings(const Scene& scene, const ContactResult& r,
                                         const std::string& wheel) {
  std::vector<std::string> out;
  if (r.climb.exceeded) out.push_back(FlangeClimbWarning(r.climb, wheel));
  if (auto w = HardnessWarning(scene.problem.wheel_material, scene.problem.rail_material,
                               r.p_max_Pa, wheel)) {
    out.push_back(std::move(*w));
  }
  return out;
}

// The placement of a wheel placed from the centred wheelset ([load] lateral_mm).
std::string CentredPlacementLine(const Scene& scene) {
  if (!scene.centred) return {};
  const Scene::CentredPlacement& c = *scene.centred;
  return fmt::format(
      "placement   lateral {:.3f} mm from the centred wheelset (gauge {:.1f} mm at {:.1f} mm "
      "below the top of rail, flange backs {:.1f} mm apart, flange back at y = {:.1f} mm): wheel "
      "origin at {:.3f} mm from the rail's ({:.3f} mm when centred)\n",
      c.lateral_m * kToMm, c.track.gauge_m * kToMm, c.track.gauge_height_m * kToMm,
      c.wheelset.flange_back_distance_m * kToMm, c.wheelset.flange_back_position_m * kToMm,
      scene.problem.placement.lateral_shift_m * kToMm, c.centred_shift_m * kToMm);
}

std::string FormatSummary(const Scene& scene, const ContactResult& r, bool left_wheel) {
  std::string out;
  out += fmt::format("scene       {} ({})\n", scene.name, scene.path);
  out += fmt::format("model       {}\n", ModelLine(r.model));
  out += fmt::format("status      {}\n", ToString(r.status));
  if (!r.message.empty()) out += fmt::format("message     {}\n", r.message);
  out += CentredPlacementLine(scene);
  out += fmt::format("approach    {:.5f} mm\n", r.approach_m * kToMm);
  out += fmt::format("iterations  {}\n", r.iterations);
  out += fmt::format("time        {:.1f} ms{}\n", r.time_s * kToMs, StagesLine(r));
  const ForceParts forces = TotalForcesOnRail(r);
  const Eigen::Vector3d net = forces.Net();
  out += fmt::format(
      "total       area {:.2f} mm2, p_max {:.1f} MPa; net force on the rail (rail frame): "
      "vertical {:.1f} N, lateral {:.1f} N\n",
      r.area_m2 * kToMm2, r.p_max_Pa * kToMPa, net.z(), net.y());
  const bool rolling = !r.patches.empty() && r.patches[0].rolling;
  if (rolling) {
    out += fmt::format(
        "            of which pressure vertical {:.1f} N, lateral {:.1f} N; creep forces "
        "longitudinal {:.1f} N, vertical {:.1f} N, lateral {:.1f} N\n",
        forces.normal_N.z(), forces.normal_N.y(), forces.creep_N.x(), forces.creep_N.z(),
        forces.creep_N.y());
    if (left_wheel) {
      out += fmt::format("            track frame (Y right): lateral {:.1f} N\n",
                         RailToTrackFrame(net, true).y());
    }
  }
  out += PlasticLines(r);
  if (r.balance_iterations > 0) {
    out += fmt::format(
        "balance     {} iterations: pressure and creep forces carry the load to {:.1e}\n",
        r.balance_iterations, r.balance_residual);
  }
  if (!r.patches.empty()) out += ClimbLine(r.climb);
  for (const std::string& w : ContactWarnings(scene, r, "")) {
    out += fmt::format("WARNING     {}\n", w);
  }
  if (r.coupling_iterations > 0) {
    out += fmt::format(
        "coupling    {} normal-tangential iterations: area {:+.3f} %, p_max {:+.3f} %\n",
        r.coupling_iterations, 100.0 * r.coupling_area_change, 100.0 * r.coupling_p_max_change);
  }
  out += fmt::format("patches     {}\n", r.patches.size());
  if (!r.patches.empty()) out += fmt::format("\n{}", PatchTable(r));
  if (r.model.kind == ModelKind::kAuto) {
    out += "\n";
    for (size_t k = 0; k < r.patches.size(); ++k) {
      out += fmt::format("patch {} model: {}\n", k + 1, r.patches[k].model_reason);
    }
  }
  if (rolling) {
    out += fmt::format(
        "\nrolling (creep forces of the rail ON THE WHEEL, patch frame: Fx longitudinal, Fy "
        "lateral along s; pitch velocity {:.4f} rad/s)\n{}",
        r.pitch_velocity_rad_s, RollingTable(r));
    out += fmt::format(
        "\nforces ON THE RAIL per patch: rail frame (x, y toward the field side, z down) and "
        "patch frame (normal, longitudinal, lateral)\n{}",
        ForceTable(r));
  }
  return out;
}

nlohmann::json MakeContactJson(const Scene& scene, const ContactResult& r, bool left_wheel) {
  nlohmann::json j;
  j["status"] = ToString(r.status);
  j["message"] = r.message;
  j["scene"] = scene.name;
  j["scene_file"] = scene.path;
  j["model"] = ModelJson(r.model);
  j["model"]["normal_criterion"] = ToString(scene.problem.solver.criterion);
  j["model"]["normal_tolerance"] = scene.problem.solver.tolerance;
  j["model"]["tangential_tolerance"] = scene.problem.tangential_tolerance;
  j["approach_mm"] = r.approach_m * kToMm;
  j["iterations"] = r.iterations;
  j["time_ms"] = r.time_s * kToMs;
  j["stages"] = nlohmann::json::array();
  for (const auto& s : r.stages)
    j["stages"].push_back({{"name", s.name}, {"time_ms", s.seconds * kToMs}});
  j[contact_json::kTotal] = {{contact_json::kAreaMm2, r.area_m2 * kToMm2},
                             {contact_json::kPMaxMPa, r.p_max_Pa * kToMPa},
                             {contact_json::kVerticalForceN, r.vertical_force_N},
                             {contact_json::kLateralForceN, r.lateral_force_N}};
  j[contact_json::kPatches] = nlohmann::json::array();
  for (const auto& p : r.patches) j[contact_json::kPatches].push_back(PatchJson(p));
  if (r.pressure_limit_Pa) {  // only with a limit: the JSON of elastic scenes is unchanged
    const auto [cells, normal] = ContactCellsAndNormalForce(r);
    nlohmann::json plastic =
        PlasticJson(r.plastic_cells, cells, r.plastic_area_m2, r.plastic_force_N, normal);
    plastic["pressure_limit_MPa"] = *r.pressure_limit_Pa * kToMPa;
    j[contact_json::kTotal]["plastic"] = std::move(plastic);
    for (size_t k = 0; k < r.patches.size(); ++k) {
      const PatchResult& p = r.patches[k];
      j[contact_json::kPatches][k]["plastic"] =
          PlasticJson(p.plastic_cells, p.cells_in_contact, p.plastic_area_m2, p.plastic_force_N,
                      p.normal_force_N);
    }
  }
  if (!r.patches.empty() && r.patches[0].rolling) {
    j["pitch_velocity_rad_s"] = r.pitch_velocity_rad_s;
    double fx = 0.0;
    for (const auto& p : r.patches) fx += p.rolling->tangential.force_x_N;
    j[contact_json::kTotal][contact_json::kCreepForceXN] = fx;
  }
  if (r.coupling_iterations > 0) {
    j["coupling"] = {{"iterations", r.coupling_iterations},
                     {"area_change_percent", 100.0 * r.coupling_area_change},
                     {"p_max_change_percent", 100.0 * r.coupling_p_max_change}};
  }
  // The old keys first: a non-finite value is named where it arises, not in "forces".
  RequireFiniteJson(j, "contact result $");
  if (r.balance_iterations > 0) {
    j["balance"] = {{"iterations", r.balance_iterations},
                    {"residual_relative", r.balance_residual}};
  }
  // total.vertical_force_N and lateral_force_N (and the patches' ones) are the pressure's part
  // on the rail, as always; "forces" labels every part, body and frame.
  j["forces"] = ForcesJson(r, left_wheel);
  j["flange_climb_check"] = ClimbJson(r.climb);
  j["flange_climb"] = r.climb.exceeded;
  j["warnings"] = ContactWarnings(scene, r, "");
  if (scene.centred && !left_wheel) {
    const Scene::CentredPlacement& c = *scene.centred;
    j["placement"] = {{"lateral_mm", c.lateral_m * kToMm},
                      {"lateral_shift_mm", scene.problem.placement.lateral_shift_m * kToMm},
                      {"centred_lateral_shift_mm", c.centred_shift_m * kToMm},
                      {"gauge_mm", c.track.gauge_m * kToMm},
                      {"gauge_height_mm", c.track.gauge_height_m * kToMm},
                      {"flange_back_distance_mm", c.wheelset.flange_back_distance_m * kToMm},
                      {"flange_back_position_mm", c.wheelset.flange_back_position_m * kToMm}};
  }
  RequireFiniteJson(j, "contact result $");
  return j;
}

void WritePressureCsv(const ContactResult& r, std::ostream& out, const std::string& wheel,
                      bool header) {
  const bool rolling = !r.patches.empty() && r.patches[0].rolling.has_value();
  const std::string lead = wheel.empty() ? "" : wheel + ",";
  // The whole table is formatted first and checked, so a non-finite value writes nothing.
  std::string text;
  if (header) {
    text += (wheel.empty() ? "" : "wheel,") + std::string("patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa") +
            (rolling ? ",qx_MPa,qs_MPa,slip_x_m_s,slip_s_m_s,stick\n" : "\n");
  }
  auto finite = [](std::initializer_list<double> values, int patch, int ix, int js) {
    for (double v : values) {
      if (!std::isfinite(v)) {
        throw std::runtime_error(
            fmt::format("the pressure CSV has a non-finite value ({}) at "
                        "patch {} cell ({}, {}); nothing written",
                        v, patch, ix, js));
      }
    }
  };
  for (size_t k = 0; k < r.patches.size(); ++k) {
    const PatchResult& patch = r.patches[k];
    for (const auto& s : PressureSamples(patch, static_cast<int>(k) + 1)) {
      finite({s.x_mm, s.s_mm, s.y_mm, s.z_mm, s.p_MPa}, s.patch, s.ix, s.js);
      text += lead + fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}", s.patch, s.ix, s.js,
                                 s.x_mm, s.s_mm, s.y_mm, s.z_mm, s.p_MPa);
      if (rolling && patch.rolling) {
        // Traction, slip velocity and stick (1) / slip (0) / outside (-1) per cell.
        const TangentialSolution& t = patch.rolling->tangential;
        const int c = patch.grid.Index(s.ix, s.js);
        finite({t.traction_x_Pa[c], t.traction_s_Pa[c], t.slip_x_m_s[c], t.slip_s_m_s[c]}, s.patch,
               s.ix, s.js);
        text +=
            fmt::format(",{:.6f},{:.6f},{:.6g},{:.6g},{}", t.traction_x_Pa[c] * kToMPa,
                        t.traction_s_Pa[c] * kToMPa, t.slip_x_m_s[c], t.slip_s_m_s[c], t.stick[c]);
      }
      text += "\n";
    }
  }
  out << text;
}

nlohmann::json MakeWheelsetJson(const Scene& scene, const WheelsetResult& r) {
  nlohmann::json j;
  const bool ok =
      r.right.status == SolverStatus::kConverged && r.left.status == SolverStatus::kConverged;
  j["status"] = ok ? "converged"
                   : (r.right.status != SolverStatus::kConverged ? ToString(r.right.status)
                                                                 : ToString(r.left.status));
  j["scene"] = scene.name;
  j["scene_file"] = scene.path;
  j["placement"] = {{"right_lateral_shift_mm", r.placement.right.lateral_shift_m * kToMm},
                    {"left_lateral_shift_mm", r.placement.left.lateral_shift_m * kToMm},
                    {"right_roll_rad", r.placement.right.roll_rad},
                    {"left_roll_rad", r.placement.left.roll_rad},
                    {"rail_gauge_point_y_mm", r.placement.rail_gauge_point_y_m * kToMm}};
  j["wheels"] = {{"right", MakeContactJson(scene, r.right, false)},
                 {"left", MakeContactJson(scene, r.left, true)}};
  j["warnings"] = nlohmann::json::array();
  for (const auto& [name, w] : {std::pair{"right wheel", &r.right}, {"left wheel", &r.left}}) {
    for (const std::string& warning : ContactWarnings(scene, *w, name)) {
      j["warnings"].push_back(warning);
    }
  }
  j["flange_climb"] = r.right.climb.exceeded || r.left.climb.exceeded;
  return j;
}

std::string FormatWheelsetSummary(const Scene& scene, const WheelsetResult& r) {
  return fmt::format(
      "wheelset    lateral shift in each rail's frame: right {:.3f} mm, left {:.3f} mm\n\n"
      "== right wheel (right rail's frame) ==\n{}\n== left wheel (left rail's own frame, y "
      "toward its field side) ==\n{}",
      r.placement.right.lateral_shift_m * kToMm, r.placement.left.lateral_shift_m * kToMm,
      FormatSummary(scene, r.right, false), FormatSummary(scene, r.left, true));
}

void RequireFiniteJson(const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    throw std::runtime_error(
        fmt::format("{}: a non-finite value ({}); nothing written", where, j.get<double>()));
  }
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) RequireFiniteJson(value, where + "." + key);
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) RequireFiniteJson(j[i], fmt::format("{}[{}]", where, i));
  }
}

}  // namespace railwear::app
