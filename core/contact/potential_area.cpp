// The potential-area stage of SolveContact (potential_area.h).
#include "core/contact/potential_area.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/contact/influence_operator.h"
#include "core/contact/patch_results.h"
#include "core/contact/stage_timer.h"

namespace railwear::internal {

namespace {

// Floors keep a degenerate estimate (no Hertz solution, a zero approach) from producing an
// empty grid; the re-gridding below corrects the cell size from the first solution.
constexpr double kMinSemiAxis_m = 1e-5, kMinThreshold_m = 1e-8;
// Initial overlap a cell may show from the first-contact search's tolerance and the gap
// projections' rounding (both ~1e-10 m) before it counts as a failed gap computation.
constexpr double kMaxInitialOverlap_m = 1e-7;
// Re-gridding never makes a patch finer than this many cells across its potential area (the
// fine preset's patches need about 250).
constexpr double kMaxCellsAlong = 300.0;
// Patches carrying at least this share of the load get the preset's cells per semi-axis.
constexpr double kFullShare = 0.1;
// ... and at most kMaxCellsAlong scaled alike, but never fewer than this many across.
constexpr double kMinCellsAlong = 40.0;
// The crop follows the solved approach with this margin.
constexpr double kTrimFactor = 1.2;
// A patch is re-gridded when its target cells differ from its cells by more than this share.
constexpr double kRegridBand = 0.3;
// The measuring attempts' cells per semi-axis (potential_area.h, measure_cell_): the draft
// preset's.
double MeasureCellsPerSemiAxis() { return CellsPerSemiAxis(AccuracyPreset::kDraft); }
bool Regrids(const CellSize& now, const CellSize& target) {
  return std::abs(target.dx_m / now.dx_m - 1.0) > kRegridBand ||
         std::abs(target.ds_m / now.ds_m - 1.0) > kRegridBand;
}

}  // namespace

PotentialArea::PotentialArea(const ContactProblem& problem, const FirstContactEstimate& first,
                             double stiffness_ratio_K)
    : problem_(problem),
      stiffness_ratio_K_(stiffness_ratio_K),
      cell_(ChooseCellSize(problem.model, std::max(first.semi_axis_x_m, kMinSemiAxis_m),
                           std::max(first.semi_axis_s_m, kMinSemiAxis_m))),
      threshold_(std::max(2.0 * first.delta, kMinThreshold_m)),
      n_per_axis_(CellsPerSemiAxis(problem.model.accuracy)),
      cell_fixed_(problem.model.cell_dx_m.has_value() || problem.model.cell_ds_m.has_value()),
      measure_cell_{std::max(first.semi_axis_x_m, kMinSemiAxis_m) / MeasureCellsPerSemiAxis(),
                    std::max(first.semi_axis_s_m, kMinSemiAxis_m) / MeasureCellsPerSemiAxis()},
      measuring_(problem.model.accuracy != AccuracyPreset::kDraft && !problem.model.cell_dx_m &&
                 !problem.model.cell_ds_m) {}

namespace {

// Whether the kept grid kg applies to candidate c (model `choice`, cells cc) on geom: the same
// candidate (its interval then held c's smallest gap), model, kernel and cells, and the wheel
// moved by at most kMaxKeptGridMove of a cell at the grid's first and last rows (the yaw's move
// at its ends in x included).
bool KeptGridApplies(const KeptGrid& kg, const WheelRailGeometry& geom, const ContactCandidate& c,
                     const PatchModelChoice& choice, const CellSize& cc) {
  const PatchGrid& g = kg.build.grid;
  if (choice.geometry != GeometryModel::kConformal || g.planar ||
      kg.choice.geometry != GeometryModel::kConformal || choice.kernel != kg.choice.kernel ||
      choice.label != kg.choice.label || cc.dx_m != g.dx_m || cc.ds_m != g.ds_m ||
      c.y_m < kg.y_lo_m || c.y_m > kg.y_hi_m ||
      BodyCurvatureSign(c.wheel_lateral_curvature) != kg.wheel_sign ||
      BodyCurvatureSign(c.rail_lateral_curvature) != kg.rail_sign ||
      geom.pose().rolling_radius_m != kg.rolling_radius_m) {
    return false;
  }
  const double half_length = 0.5 * g.nx * g.dx_m + std::abs(g.XCentre());
  const double move = std::max((geom.WheelToRail(kg.wheel_first_W) - kg.rail_first_R).norm(),
                               (geom.WheelToRail(kg.wheel_last_W) - kg.rail_last_R).norm()) +
                      std::abs(geom.pose().yaw_rad - kg.yaw_rad) * half_length;
  return move <= kMaxKeptGridMove * std::min(g.dx_m, g.ds_m);
}

}  // namespace

KeptGrid KeepGrid(const WheelRailGeometry& geom, const PatchBuilds& builds, size_t k,
                  std::shared_ptr<const InfluenceOperator> op) {
  const PatchBuild& b = builds.builds[k];
  const PatchGrid& g = b.grid;
  KeptGrid kg{b,
              builds.cands[k].y_lo_m,
              builds.cands[k].y_hi_m,
              builds.choices[k],
              BodyCurvatureSign(builds.cands[k].wheel_lateral_curvature),
              BodyCurvatureSign(builds.cands[k].rail_lateral_curvature),
              std::move(op),
              geom.RailToWheel(g.point_yz_m.front()),
              geom.RailToWheel(g.point_yz_m.back()),
              g.point_yz_m.front(),
              g.point_yz_m.back(),
              geom.pose().yaw_rad,
              geom.pose().rolling_radius_m};
  return kg;
}

bool PotentialArea::Build(const WheelRailGeometry& geom, PatchModelMemory* models,
                          double approach_now, PatchBuilds* out, ContactResult* result,
                          const std::vector<KeptGrid>* kept) const {
  const auto t0 = Clock::now();
  const std::vector<ContactCandidate> cands = geom.FindCandidates(threshold_);
  std::vector<bool> kept_used(kept ? kept->size() : 0, false);  // (each grid serves one patch)
  for (const auto& found : cands) {
    CellMemory memory{found.y_lo_m, found.y_hi_m, measuring_ ? measure_cell_ : cell_, std::nullopt,
                      0};
    bool remembered = false;
    for (const auto& m : cell_memory_) {
      if (found.y_m >= m.y_lo_m && found.y_m <= m.y_hi_m) {
        memory = m;
        remembered = true;
      }
    }
    const CellSize cc = memory.cell;
    PatchModelChoice choice = models->ChooseFor(found, approach_now);
    // A planar grid re-centred on its solved pressure centre (Review).
    const ContactCandidate c = choice.geometry == GeometryModel::kPlanar && memory.plane_y_m
                                   ? geom.CandidateAt(found, *memory.plane_y_m)
                                   : found;
    PatchGridOptions o;
    o.geometry = choice.geometry;
    o.cell_dx_m = cc.dx_m;
    o.cell_ds_m = cc.ds_m;
    o.threshold_m = threshold_;
    o.stiffness_ratio_K = stiffness_ratio_K_;
    o.trim_approach_m = trim_approach_;
    o.walks = &walks_;
    o.size_accepted = [](const PatchGrid& sized) {
      return !(EstimateOperatorBytes(sized.nx, sized.ns, sized.planar) > kMaxOperatorBytes) &&
             !(static_cast<double>(sized.nx) * sized.ns > kMaxGridCells) &&
             sized.nx <= kMaxCellsAlongAxis && sized.ns <= kMaxCellsAlongAxis;
    };
    // A warm start's kept grid of this candidate: the same cells, gaps projected anew.
    int kept_index = -1;
    for (size_t k = 0; kept && k < kept->size(); ++k) {
      if (!kept_used[k] && KeptGridApplies((*kept)[k], geom, c, choice, cc)) {
        kept_index = static_cast<int>(k);
        kept_used[k] = true;
        break;
      }
    }
    PatchBuild b;
    if (kept_index >= 0) {
      b = (*kept)[kept_index].build;
      UpdateConformalGaps(geom, &b);
    } else {
      b = BuildPatchGrid(geom, c, o);
    }
    if (b.too_large) {
      // A status, not std::bad_alloc, when a grid outgrows memory (the cell rules of the
      // re-gridding below keep within it; an explicit cell_mm may not).
      result->status = SolverStatus::kNotConverged;
      result->message = fmt::format(
          "the potential contact area needs at least a {} x {} grid ({:.3g} cells; at most {} "
          "along each axis and {:.0g} in all), whose influence operator would take {:.1f} GB "
          "(at most {:.0f} GB): choose a coarser model.accuracy or a larger model.cell_mm",
          b.grid.nx, b.grid.ns, static_cast<double>(b.grid.nx) * b.grid.ns, kMaxCellsAlongAxis,
          kMaxGridCells, EstimateOperatorBytes(b.grid.nx, b.grid.ns, b.grid.planar) / 1e9,
          kMaxOperatorBytes / 1e9);
      return false;
    }
    if (b.valid) {
      if (!remembered) ++out->unremembered;
      out->builds.push_back(std::move(b));
      out->cells.push_back({c.y_lo_m, c.y_hi_m, cc, memory.plane_y_m, memory.recentred});
      out->cands.push_back(c);
      out->choices.push_back(std::move(choice));
      out->kept.push_back(kept_index);
    }
  }
  AddStage(&result->stages, "grid", SecondsSince(t0));
  if (out->builds.empty()) {
    result->status = SolverStatus::kNoContact;
    result->message = "no usable contact patch (surfaces too steep for a vertical approach)";
    return false;
  }
  for (const PatchBuild& b : out->builds) {
    // The wheel was lowered to first contact, so no cell may start inside the rail: a
    // negative initial separation is a geometry failure (a projection that found the wrong
    // branch), and a solve on it "converges" to nonsense (a lifted wheel on a few cells).
    if (const double g = b.grid.gap_m.minCoeff(); g < -kMaxInitialOverlap_m) {
      result->status = SolverStatus::kNotConverged;
      result->message = fmt::format(
          "the initial separation is negative ({:.4g} um) in a cell of the potential contact "
          "area: the gap computation failed there; try the other geometry model",
          g * 1e6);
      return false;
    }
  }
  return true;
}

AreaReview PotentialArea::Review(PatchBuilds* builds, const NormalSolution& sol,
                                 const Eigen::VectorXd& cell_area_m2, PatchModelMemory* models) {
  // Decide whether the grid fits the solution (and, for auto, whether a planar patch still
  // qualifies for the planar grid on its solved extent).
  AreaReview review;
  std::vector<CellMemory> next_memory;
  // While measuring: each patch's (an index of next_memory) cells at the preset.
  std::vector<std::pair<size_t, CellSize>> preset_targets;
  const double total_load = sol.pressure_Pa.dot(cell_area_m2);
  int offset = 0;
  for (size_t k = 0; k < builds->builds.size(); ++k) {
    const PatchBuild& b = builds->builds[k];
    CellMemory mem = builds->cells[k];
    const auto p_k = sol.pressure_Pa.segment(offset, b.grid.cells());
    const Extent e = MeasureExtent(b.grid, p_k);
    const double share = total_load > 0.0 ? p_k.sum() * b.grid.CellArea() / total_load : 1.0;
    offset += b.grid.cells();
    if (e.cells == 0) continue;
    if (models->is_auto() && builds->choices[k].model != PatchModel::kConformal &&
        sol.status == SolverStatus::kConverged) {
      const bool switched = models->Recheck(builds->cands[k], e, &builds->choices[k]);
      review.switched = review.switched || switched;
    }
    if (e.touches_x_edge || (e.touches_s_edge && !b.lateral_limited)) review.grow = true;
    // The planar grid's plane onto the rail point under the solved pressure centre.
    if (b.grid.planar && sol.status == SolverStatus::kConverged && mem.recentred < kMaxRecentres &&
        builds->choices[k].geometry == GeometryModel::kPlanar) {
      double weight = 0.0, y = 0.0;
      for (int j = 0; j < b.grid.ns; ++j) {
        const double column = p_k.segment(b.grid.Index(0, j), b.grid.nx).sum();
        weight += column;
        y += column * b.grid.point_yz_m[j].x();
      }
      if (weight > 0.0) {
        y /= weight;
        if (std::abs(y - builds->cands[k].rail_point_m.x()) > 0.5 * b.grid.ds_m) {
          mem.plane_y_m = y;
          ++mem.recentred;
          review.recentre = true;
        }
      }
    }
    if (!cell_fixed_) {
      // The preset's cells per semi-axis for every patch that carries at least
      // kFullShare of the load. A patch that barely touches (a third candidate on a worn
      // rail: 0.03 mm2 beside 126 mm2) would otherwise be re-gridded into millions of tiny
      // cells over its potential area, and the curved operator's nx ns^2 memory with them;
      // its force error is its share times its relative error, so it keeps
      // n sqrt(share / kFullShare) cells per semi-axis (at least the draft preset's), and
      // never more than kMaxCellsAlong (scaled alike, at least kMinCellsAlong) across its
      // potential area. While measuring, the draft preset's cells per semi-axis.
      const double weight = std::sqrt(std::min(1.0, share / kFullShare));
      const double along = std::max(kMinCellsAlong, kMaxCellsAlong * weight);
      const double min_dx = b.grid.nx * b.grid.dx_m / along,
                   min_ds = b.grid.ns * b.grid.ds_m / along;
      auto target_at = [&, half_x = e.half_x, half_s = e.half_s](double n_per_axis) {
        const double n_patch =
            std::max(CellsPerSemiAxis(AccuracyPreset::kDraft), n_per_axis * weight);
        return CellSize{std::max(half_x / n_patch, min_dx), std::max(half_s / n_patch, min_ds)};
      };
      // The preset's cells from a measurement on the measuring cells. The extent counts whole
      // cells, so it lies half a cell beyond the patch's edge on average: the patch's
      // semi-axis is about half - dx / 2, and the target is the cell size whose own measurement
      // (half a target cell beyond the edge) gives n_patch cells per semi-axis,
      // (half - dx / 2) / (n_patch - 1/2). Without it the preset's cells follow the coarse
      // cells' larger overshoot (the Hertz cases' areas at standard were 1.7 % off, the
      // preset's 1 % exceeded, SolveContact.AccuracyPresetsReachTheirErrorsOnHertzCases).
      auto preset_target = [&, half_x = e.half_x, half_s = e.half_s]() {
        const double n_patch =
            std::max(CellsPerSemiAxis(AccuracyPreset::kDraft), n_per_axis_ * weight);
        return CellSize{std::max((half_x - 0.5 * b.grid.dx_m) / (n_patch - 0.5), min_dx),
                        std::max((half_s - 0.5 * b.grid.ds_m) / (n_patch - 0.5), min_ds)};
      };
      if (measuring_ ? measure_regrids_ < 3 : regrids_ < 3) {
        const CellSize target = target_at(measuring_ ? MeasureCellsPerSemiAxis() : n_per_axis_);
        if (Regrids(mem.cell, target)) {
          review.regrid = true;
          mem.cell = target;
        }
      }
      if (measuring_) preset_targets.push_back({next_memory.size(), preset_target()});
    }
    next_memory.push_back(mem);
  }
  const bool converged = sol.status == SolverStatus::kConverged;
  review.more_candidates = converged && sol.approach_m > 0.7 * threshold_;
  // The crop is exact only while the approach stays below the one it was made for.
  review.outgrew_trim = converged && sol.approach_m > trim_approach_;
  if (measuring_) {
    // The patch measured (it fits, on its measuring cells): every patch onto the preset's cells
    // on its measured extent, or onto the first estimate's preset cells (cell_, the cells the
    // first attempt would have had without measuring) where those are within kRegridBand of
    // it, as a review at the preset keeps them (on the Hertz cases the estimate is exact).
    if (converged && !review.grow && !review.more_candidates && !review.switched &&
        !review.outgrew_trim && !review.recentre) {
      review.regrid = false;
      for (const auto& [index, target] : preset_targets) {
        const CellSize cells = Regrids(cell_, target) ? target : cell_;
        if (Regrids(next_memory[index].cell, cells)) {
          review.regrid = true;
          next_memory[index].cell = cells;
        }
      }
      measuring_ = false;
    } else if (review.regrid) {
      ++measure_regrids_;
    }
  } else if (review.regrid) {
    ++regrids_;
  }
  cell_memory_ = std::move(next_memory);
  if (converged) trim_approach_ = kTrimFactor * sol.approach_m;
  return review;
}

void PotentialArea::Widen(const AreaReview& review, const NormalSolution& sol) {
  if (review.grow) threshold_ *= 1.8;
  if (review.more_candidates) threshold_ = std::max(threshold_, 2.0 * sol.approach_m);
  if (review.regrid) threshold_ = std::max(threshold_, 2.0 * sol.approach_m);
}

}  // namespace railwear::internal
