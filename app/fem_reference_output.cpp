// The text `railwear fem-reference` prints: comparisons of curves, experiment summaries, the
// lines of --report-only. See fem_reference_output.h.
#include "app/fem_reference_output.h"
#include "core/numerics/units.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace railwear::app {
namespace {

constexpr double kMPa = 1e6;
constexpr double kNmPerN = 1e-9;
// Distances [mm] whose nearest curve points the comparison tables show.
constexpr double kTableDistances_mm[] = {0.5, 1.0, 2.0, 5.0, 10.0, 20.0};

// The point nearest (in log distance, within 15 %) to `distance_m` on one curve, or nullptr.
const ComparedPoint* Nearest(const std::vector<ComparedPoint>& points, double distance_m) {
  const ComparedPoint* best = nullptr;
  for (const ComparedPoint& p : points) {
    if (best == nullptr || std::abs(std::log(p.distance_m / distance_m)) <
                               std::abs(std::log(best->distance_m / distance_m))) {
      best = &p;
    }
  }
  if (best == nullptr || std::abs(std::log(best->distance_m / distance_m)) > std::log(1.15)) {
    return nullptr;
  }
  return best;
}

}  // namespace

// Comparison of `curves` with `reference`: per curve the offset fitted over the compare range
// and the largest raw and offset-removed errors there, then a table at a few distances (taken
// from all points the reference covers, with the same offset).
std::string FemComparisonText(const FemExperiment& e, const DisplacementCurves& curves,
                              const CurveReference& reference, const std::string& title,
                              const std::string& ref_name) {
  const double from = e.compare_from_m, to = e.compare_to_m;
  const auto in_range = CompareCurves(curves, reference, from, to);
  const auto all = CompareCurves(curves, reference, 0.0, 1e9);
  std::string out = fmt::format("  {} from {:g} to {:g} mm; offset = mean({} - {}) there:\n", title,
                                from / kMm, to / kMm, "w", ref_name);
  out += fmt::format("    {:<16} {:<5} {:>6} {:>16} {:>14} {:>22}\n", "load", "path", "points",
                     "offset_nm_per_N", "max_error_%", "max_error_no_offset_%");
  size_t skipped = 0;
  for (const CurveComparison& c : in_range) {
    out += fmt::format("    {:<16} {:<5} {:>6} {:>16.5f} {:>14.2f} {:>22.2f}\n", ToString(c.load),
                       ToString(c.path), c.points.size(), c.offset_m_per_N / kNmPerN,
                       100.0 * c.max_raw_error, 100.0 * c.max_corrected_error);
    skipped += c.num_skipped;
  }
  if (skipped > 0) {
    out += fmt::format(
        "    ({} point(s) near a zero crossing, where |{}| < {:g} % of its largest, "
        "are left out of the errors)\n",
        skipped, ref_name, 100.0 * kSmallReferenceFraction);
  }
  for (const CurveComparison& c : in_range) {
    const auto full = std::find_if(all.begin(), all.end(), [&](const CurveComparison& a) {
      return a.load == c.load && a.path == c.path;
    });
    out += fmt::format("    {} load, {} path:\n", ToString(c.load), ToString(c.path));
    out += fmt::format("      {:>11} {:>13} {:>13} {:>8} {:>17}\n", "distance_mm", "w_nm_per_N",
                       ref_name + "_nm_per_N", "ratio", "ratio_no_offset");
    for (double d : kTableDistances_mm) {
      const ComparedPoint* p = Nearest(full->points, d * kMm);
      if (p == nullptr) continue;
      out += fmt::format("      {:>11.3f} {:>13.6f} {:>13.6f} {:>8.4f} {:>17.4f}\n",
                         p->distance_m / kMm, p->w_m_per_N / kNmPerN,
                         p->reference_m_per_N / kNmPerN, c.RawRatio(*p), c.CorrectedRatio(*p));
    }
  }
  return out;
}

std::string FemDisplacementSummaryText(const FemExperiment& e, const FemDisplacementResult& r,
                                       int jobs) {
  const FemDisplacementOptions& o = e.options;
  const FemDisplacementSummary& s = r.summary;
  std::string out = fmt::format("{}: {} body", e.name, ToString(o.body));
  if (o.body != CurveBody::kFlat) out += fmt::format(" R = {:g} mm", o.radius_m / kMm);
  out += fmt::format(", E = {:g} MPa, nu = {:g}\n", o.material.youngs_modulus_Pa / kMPa,
                     o.material.poisson_ratio);
  out += fmt::format("  body      {:g} x {:g} x {:g} mm (length x width x depth), supports {}\n",
                     s.body_size.length_m / kMm, s.body_size.width_m / kMm,
                     s.body_size.depth_m / kMm, ToString(o.supports));
  out += fmt::format(
      "  mesh      {} nodes, {} C3D10 elements (quarter model; h0 {:g} mm, growth "
      "{:g}, max {:g} mm), gmsh {:.1f} s\n",
      s.nodes, s.elements, o.mesh_size_at_load_m / kMm, o.mesh_growth, o.max_element_m / kMm,
      s.mesh_time_s);
  std::string solves;
  for (const auto& [load, t] : s.solve_time_s) {
    solves += fmt::format("{}{} {:.1f} s", solves.empty() ? "" : ", ", ToString(load), t);
  }
  out += fmt::format("  solves    {} (ccx, {} at a time)\n", solves, jobs);
  out += fmt::format("  points    {} written to {}\n", s.points, e.output);
  out += fmt::format("  time      {:.1f} s\n", s.wall_time_s);
  return out;
}

std::string FemContactSummaryText(const FemExperiment& e, const FemContactResult& r) {
  const FemContactOptions& o = r.options;
  std::string out = fmt::format(
      "{}: contact case {}, convex R {:g} mm in groove R {:g} mm, rolling radius {:g} mm, load "
      "{:g} N, E = {:g} MPa, nu = {:g}\n",
      e.name, ToString(o.contact_case), o.convex_radius_m / kMm, o.groove_radius_m / kMm,
      o.rolling_radius_m / kMm, o.load_N, o.material.youngs_modulus_Pa / kMPa,
      o.material.poisson_ratio);
  out += fmt::format(
      "  model     quarter; bodies {:g} x {:g} x {:g} mm (length x width x depth); zone {:g} x "
      "{:g} x {:g} mm; penalty {:g} MPa/mm; C3D10, growth {:g}\n",
      o.length_m / kMm, o.width_m / kMm, o.depth_m / kMm, o.zone_x_m / kMm, o.zone_s_m / kMm,
      o.zone_depth_m / kMm, o.penalty_Pa_per_m / kMPa * kMm, o.mesh_growth);
  out += fmt::format(
      "  {:>6} {:>7} {:>6} {:>7} {:>8} {:>5} {:>9} {:>10} {:>8} {:>8} {:>9} {:>8} "
      "{:>10}  {}\n",
      "h_mm", "nodes", "faces", "mesh_s", "solve_s", "iter", "area_mm2", "p_max_MPa", "a_x_mm",
      "b_s_mm", "force_N", "force_%", "area_nd_mm2", "status");
  for (const FemContactLevel& L : r.levels) {
    const FemContactPatch& p = L.patch;
    out += fmt::format(
        "  {:>6.3f} {:>7} {:>6} {:>7.1f} {:>8.1f} {:>5} {:>9.3f} {:>10.2f} {:>8.3f} {:>8.3f} "
        "{:>9.1f} {:>8.2f} {:>10.3f}  {}\n",
        L.mesh_size_m / kMm, L.nodes, L.slave_faces, L.mesh_time_s, L.solve_time_s, L.iterations,
        p.area_m2 / (kMm * kMm), p.p_max_Pa / kMPa, p.half_length_x_m / kMm, p.half_width_s_m / kMm,
        p.vertical_force_N, 100.0 * (p.vertical_force_N / o.load_N - 1.0),
        p.area_nodes_m2 / (kMm * kMm), ToString(p.status));
    if (!p.message.empty()) out += "         " + p.message + "\n";
  }
  out += fmt::format("  result    written to {}\n  time      {:.1f} s\n", e.output, r.wall_time_s);
  return out;
}

std::string FemContactTargetText(const FemExperiment& e, const FemContactTarget& t) {
  return fmt::format(
      "{}: area {:.2f} mm2, p_max {:.1f} MPa, half-length x {:.3f} mm, half-width s {:.3f} "
      "mm, pressure resultant {:.1f} N of {:g} N ({} mesh levels), read from {}\n",
      e.name, t.area_mm2, t.p_max_MPa, t.half_length_x_mm, t.half_width_s_mm, t.total_force_N,
      t.load_N, t.levels, e.output);
}

}  // namespace railwear::app
