// The potential-area stage of SolveContact: the grids of the patches, and whether they fit the
// solution. The potential contact area is not known before the solve. It starts from a Hertz
// estimate of the approach at the first contact point and is corrected from the solution: the
// grid grows when pressure reaches its edge, takes in further candidates (two-point contact)
// when the approach passes their gap, and is re-gridded when the patch turns out larger or
// smaller than estimated, so that every accuracy preset keeps its number of cells per
// semi-axis. A planar grid is the tangent plane at its candidate's smallest gap at first; when
// the solved patch's pressure centre lies more than half a cell from that point, the plane is
// moved to the rail point under the pressure centre and the patch solved again (at most
// kMaxRecentres times). On a worn, nearly conformal tread the smallest gap can lie at one end of
// a 25 mm wide patch and jump to the other as the wheel moves by micrometres; the plane's angle
// (and so the spin and the creep forces) jumped with it (a Y25 wagon's low wheel on a 6 MGT
// worn rail: 1.7 to 0.7 degrees, F_x 14.0 to 16.7 kN within 7 um of y). The pressure centre
// moves continuously. Internal to SolveContact.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/contact/grid_resolution.h"
#include "core/contact/hertz_estimate.h"
#include "core/contact/influence_operator.h"
#include "core/contact/model_selection.h"
#include "core/contact/normal_solver.h"
#include "core/contact/patch_model_memory.h"
#include "core/geometry/patch_builder.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// The cell size of a patch, found again by position (the candidate's interval [y_lo, y_hi]),
// and for a planar grid the lateral position of its tangent plane once re-centred on the solved
// pressure centre (with how many times it was moved).
struct CellMemory {
  double y_lo_m, y_hi_m;
  CellSize cell;
  std::optional<double> plane_y_m;
  int recentred = 0;
};

// A grid of a warm start's last call (contact_warm_start.h), kept with its influence operator
// for the next call: when that call's wheel has moved by at most kMaxKeptGridMove of a cell
// from where the grid was built, and its candidate is found again with the same cell size and
// model, the grid is used again with its gaps projected anew (UpdateConformalGaps) and so is its
// operator (the same cells: the same operator).
struct KeptGrid {
  PatchBuild build;           // conformal; the gaps are recomputed
  double y_lo_m, y_hi_m;      // the candidate's interval when the grid was built
  PatchModelChoice choice;    // its geometry, kernel and labels
  int wheel_sign, rail_sign;  // the operator's curvature signs
  std::shared_ptr<const InfluenceOperator> op;
  // Where the wheel was when the grid was built: the wheel-frame points under the first and
  // last rows' points and those points in the rail frame, and the pose's yaw.
  Eigen::Vector2d wheel_first_W, wheel_last_W, rail_first_R, rail_last_R;
  double yaw_rad, rolling_radius_m;
};
// The largest move of the wheel, in cells (of the smaller side), for which a kept grid is used
// again: its cells then lie within a tenth of a cell (and its reference cross-section, the
// intermediate surface of seed eq. 2, within K of that) of where a grid built at the new pose
// would put them, a tenth of the grid placement's own variation between a warm call and a
// cold one (a warm attempt's grid is placed from the last call's measurement of the patch),
// and the gaps are computed exactly for those cells. Measured in docs/library.md, "Warm start".
inline constexpr double kMaxKeptGridMove = 0.1;

// The grids of one attempt, one entry per usable candidate.
struct PatchBuilds {
  std::vector<PatchBuild> builds;
  std::vector<CellMemory> cells;
  std::vector<ContactCandidate> cands;
  std::vector<PatchModelChoice> choices;
  // Candidates whose cell size no earlier attempt (or, warm, no earlier call) measured: they
  // start from the first estimate's cells.
  int unremembered = 0;
  // Per build: the kept grid (an index of the KeptGrids Build was given) it reuses, or -1.
  std::vector<int> kept;
};

// How the grids of an attempt fit its solution.
struct AreaReview {
  bool grow = false;             // pressure reaches the edge of a grid
  bool regrid = false;           // a patch needs another cell size
  bool switched = false;         // auto: a planar patch turned conformal on its solved extent
  bool more_candidates = false;  // the approach passes the threshold: more candidates may touch
  bool outgrew_trim = false;     // the approach passed the one the grids were cropped for
  bool recentre = false;         // a planar grid's plane lies off its solved pressure centre
  bool Again() const {
    return grow || regrid || more_candidates || switched || outgrew_trim || recentre;
  }
};

class PotentialArea {
 public:
  // Memory one patch's influence operator may take (the curved one holds about 2 nx ns^2
  // doubles with its preconditioner, the planar one a few FFT buffers of the padded grid).
  static constexpr double kMaxOperatorBytes = 4e9;
  // Cells one patch's grid may have: the time estimate (every cell is a gap projection and an
  // unknown of each normal and tangential iteration). 16 times the finest preset's patch of
  // about 250 x 250 cells; the re-gridding keeps within 300 across. Only an explicit cell_mm
  // can ask for more (issue 17: 1 um along x gave 19 000 columns).
  static constexpr double kMaxGridCells = 1e6;
  // ... and at most this many along either axis: the curved operator's construction holds an
  // nx x nx cosine table, and its kernel takes nx ns^2 evaluations (4000: 128 MB, and 13 times
  // the re-gridding's 300 across).
  static constexpr int kMaxCellsAlongAxis = 4000;

  // From the first estimate of the approach and patch size; stiffness_ratio_K of seed eq. 1.
  PotentialArea(const ContactProblem& problem, const FirstContactEstimate& first,
                double stiffness_ratio_K);

  // The grids at the current threshold, each candidate with its remembered cell size and its
  // model from *models. false (status and message in *result) when a grid outgrows memory,
  // no candidate gives a usable grid, or a cell starts inside the rail.
  // kept (optional): a warm start's last grids, reused where they apply (KeptGrid).
  bool Build(const WheelRailGeometry& geom, PatchModelMemory* models, double approach_now,
             PatchBuilds* out, ContactResult* result,
             const std::vector<KeptGrid>* kept = nullptr) const;

  // Checks the grids against the solution sol (cell_area_m2 per cell of all grids, as in the
  // NormalProblem), remembers each patch's cell size, rechecks auto's planar patches and moves
  // the crop to the solved approach.
  AreaReview Review(PatchBuilds* builds, const NormalSolution& sol,
                    const Eigen::VectorXd& cell_area_m2, PatchModelMemory* models);

  // Widens the threshold for the next attempt after a review that asks for one.
  void Widen(const AreaReview& review, const NormalSolution& sol);

  // Whether the grids are still on the measuring cells (measure_cell_ below), and an end to it
  // after a solve on them that did not converge (the next attempt then starts on the preset's
  // cells, as without measuring).
  bool measuring() const { return measuring_; }
  void StopMeasuring() {
    measuring_ = false;
    cell_memory_.clear();
  }

  // What the attempts have measured (the threshold, each patch's cell size and plane, the crop),
  // and the same taken over by a new PotentialArea of the next call at a nearby position
  // (warm start, contact_warm_start.h): its first attempt is then the last call's final one,
  // on the grids of the new position.
  struct Measured {
    double threshold_m;
    std::vector<CellMemory> cells;
    double trim_approach_m;
  };
  Measured measured() const { return {threshold_, cell_memory_, trim_approach_}; }
  // A planar patch's plane stays where the last call re-centred it, and its count of
  // re-centrings starts again, so that the review checks it against this call's pressure centre
  // (and the warm attempt falls back when the contact has moved by more than half a cell).
  void TakeOver(const Measured& m) {
    threshold_ = m.threshold_m;
    cell_memory_ = m.cells;
    for (CellMemory& c : cell_memory_) c.recentred = 0;
    trim_approach_ = m.trim_approach_m;
    measuring_ = false;
  }

 private:
  const ContactProblem& problem_;
  double stiffness_ratio_K_;
  CellSize cell_;      // the first estimate's cell size at the preset's cells per semi-axis
  double threshold_;   // vertical-gap threshold bounding the potential area [m]
  double n_per_axis_;  // the preset's cells per semi-axis
  bool cell_fixed_;    // an explicit cell size: never re-gridded
  // At presets finer than draft the first attempts only measure the patch (its extent, the
  // approach, the candidates it touches) and run on the draft preset's cells per semi-axis of
  // the first estimate (measure_cell_; at standard (4/10)^3, some 15 times, fewer cell integrals
  // per operator) until the potential area fits; that review re-grids every patch to the
  // preset's cells on its measured extent, and the attempts from there on are the preset's, as
  // before. A patch first found after that starts on cell_. Draft is unchanged (its measuring
  // cells are its own); an explicit cell size is never re-gridded, so it never measures.
  CellSize measure_cell_;
  bool measuring_;
  int measure_regrids_ = 0;  // re-griddings on the measuring cells (at most 3, as regrids_)
  // Each patch keeps its own cell size once it has been measured (two-point contact: a small
  // flange patch must not shrink the cells of a large tread patch), found again by position.
  std::vector<CellMemory> cell_memory_;
  int regrids_ = 0;
  // Re-centrings of one planar patch's plane (after it, the last plane is kept).
  static constexpr int kMaxRecentres = 2;
  // Grids are cropped to the cells an approach of trim_approach could close (patch_builder.h):
  // unbounded until a solve has measured the approach, then kTrimFactor times the last one.
  double trim_approach_ = std::numeric_limits<double>::infinity();
  // The candidates' lateral walks (LateralWalkCache), kept across the attempts of this solve:
  // every attempt grids the same placed geometry, most of them the same candidates at other
  // cells or thresholds. The grids are the same bit for bit; a cache, hence mutable.
  mutable LateralWalkCache walks_;
};

// A wheel's contact as the last call left it, for the next call's warm start
// (contact_warm_start.h): its potential area as measured, the candidates it gridded, its
// approach, and under a prescribed load with a vertical balance the load Q and the pressure's
// balanced target T.
struct WarmStartState {
  PotentialArea::Measured area;
  int candidates = 0;
  double approach_m = 0.0;
  std::optional<double> load_N, target_N;
  // The last call's patches in contact: their grids (without the gaps) and final pressures,
  // the warm attempt's first pressures once interpolated onto its grids (WarmPressureStart).
  std::vector<PatchGrid> grids;
  std::vector<Eigen::VectorXd> pressures_Pa;
  // Every grid of the last call's final attempt, with its operator (KeptGrid).
  std::vector<KeptGrid> kept_grids;
};

// A KeptGrid of build k of `builds` on `geom`, with its operator.
KeptGrid KeepGrid(const WheelRailGeometry& geom, const PatchBuilds& builds, size_t k,
                  std::shared_ptr<const InfluenceOperator> op);

// The warm attempt's starting pressures on the grids of `builds` (cells in the NormalProblem's
// order): the last call's pressures (`state`) interpolated bilinearly, in x between columns and
// along the cross-section between the rail-frame points of the last grids' rows, onto each new
// cell centre; cells off every last grid (more than half a cell beyond its ends, or farther than
// a cell from its cross-section) start at 0. Only a starting point: the solve (SolveNormal's
// `start`, scaled to the load) converges to the same solution to its tolerance.
Eigen::VectorXd WarmPressureStart(const WarmStartState& state, const PatchBuilds& builds);

}  // namespace railwear::internal
