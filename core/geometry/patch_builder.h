// BuildPatchGrid: the potential contact area of one contact candidate as a PatchGrid.
//
// Planar model (Model A): the cross-section is the tangent line of the first contact point; the
// gap is measured along that line's normal n0, from the rail to the wheel.
// Conformal model (Model B): the cross-section is the intermediate curve of seed eq. 1,
// f = K f_wheel + (1 - K) f_rail with K = k_rail / (k_wheel + k_rail), evaluated in the local
// frame (t0, n0) of the first contact point so that steep gauge-corner surfaces stay
// single-valued; the gap of a cell is the sum of the signed distances of its centre to both
// bodies by orthogonal projection (seed eq. 2): a 1-D search along the prismatic rail's profile,
// and along the wheel profile in the meridian plane through the point (body of revolution).
//
// Both grids are extruded along x. The potential area spans the lateral range where the gap
// along n0 at x = 0 stays below threshold * w0 (w0 = the vertical component of n0) and the
// longitudinal range where the wheel's lift x^2 / (2 r) stays below the threshold.
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/geometry_model.h"
#include "core/geometry/patch_grid.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear {

// Step 1 of BuildPatchGrid, the lateral walk of one candidate's cross-section (the rail and
// wheel crossings of lines along n0, one an eighth of a cell or 20 um apart), kept for the next
// grids of the same candidate on the same placed geometry: the attempts of one contact solve
// walk the same candidate again and again, at other cells and thresholds (the measuring attempt,
// its re-grid to the preset's cells, a grown threshold). A walk's sections depend only on the
// candidate's point, normal and profile parameters and the step, each one on the one before;
// a walk at a higher threshold or for more cells beyond it only goes on further. So a kept walk
// serves any later one of the same key bit for bit, walking on from its last section where the
// later one needs more. Internal to BuildPatchGrid (the members are its).
struct LateralWalkCache {
  struct Section {
    double tau = 0.0;       // offset along t0 from the contact point [m]
    double lambda_r = 0.0;  // rail surface offset along n0
    double lambda_w = 0.0;  // wheel surface offset along n0 (x = 0)
    double rail_s = 0.0, wheel_s = 0.0;
  };
  // The sections walked on one side, in order of increasing |tau|; ended: the next one has no
  // crossing (a geometric limit), so no walk goes beyond them.
  struct Side {
    std::vector<Section> sections;
    bool ended = false;
  };
  struct Walked {
    Eigen::Vector2d rail_point_m, normal;  // the candidate's
    double rail_s_m, wheel_s_m, step_m;
    bool centre_found;
    Section centre;
    Side lo, hi;  // toward -t0 and +t0
  };
  // The geometry the walks were made on: a cache handed a grid on another WheelRailGeometry
  // object is emptied first. A geometry moved in place (a new pose on the same object) must
  // not be given the cache of its old pose.
  const WheelRailGeometry* geometry = nullptr;
  std::vector<Walked> walks;
  int reused = 0;  // walks served from a kept one (for tests)
};

// Half-width [m] of the arc searched for a walk section's rail and wheel crossings about the
// previous section's (a line along n0 one walk step further along t0; the whole profile when
// nothing crosses there). Between sections 20 um apart a crossing moves by step / cos(angle
// between the profile and t0): the window holds it up to 85 degrees, and a steeper profile's
// crossing is found by the whole-profile search. The crossing taken is the one nearest the
// line's base point, so a window only changes it where a nearer crossing lies outside it while
// another lies inside: the profile turning back within a few tenths of a millimetre. It was
// 50 steps + 0.5 mm (1.5 mm) before issue 20's grids; PatchBuilder.
// TheWalksNarrowWindowFindsTheWideWindowsCrossings checks that both find the same crossings
// (within the refinement's tolerance) on the gauge corner and the tread.
inline double LateralWalkWindow(double step_m) { return 8.0 * step_m + 1e-4; }

struct PatchGridOptions {
  GeometryModel geometry = GeometryModel::kConformal;
  double cell_dx_m = 0.0;          // > 0
  double cell_ds_m = 0.0;          // > 0
  double threshold_m = 0.0;        // vertical-gap threshold bounding the potential area (> 0)
  double stiffness_ratio_K = 0.5;  // K = k_rail / (k_wheel + k_rail) of seed eq. 1
  // Cells whose surface normal is steeper than this against the vertical are left out (a
  // vertical approach cannot close them). cos of 85 degrees.
  double min_approach_weight = 0.0872;
  // When finite: the grid is cropped to the cells that a vertical approach of up to this much
  // could close, d_ij <= trim_approach_m * w_j (w_j = the vertical component of the cell's
  // normal), plus kTrimMarginCells around them (x symmetric about 0). This is exact, not an
  // approximation: elastic displacements only open gaps (every influence coefficient is > 0),
  // so no other cell can come into contact while the approach stays below trim_approach_m. The
  // threshold alone can leave a barely touching patch a potential area thousands of times its
  // contact (the threshold is shared by all patches and grows with the largest).
  double trim_approach_m = std::numeric_limits<double>::infinity();
  // When set: asked once the grid is sized (nx, ns, dx_m, ds_m, planar set; no points or gaps
  // yet) whether a grid of that size may be built. The caller decides (the contact stage checks
  // the memory of the grid's influence operator); false: the grid is not built, the result has
  // too_large set and the grid's nx, ns (a lower bound when refused before the walk), but no
  // gaps. Unset: every size is accepted. Also asked before the lateral walk, with the nx the
  // contact point's wheel radius gives and trial ns, to bound the walk (a tiny cell made it take
  // minutes and gigabytes): it must accept every grid no larger in nx and ns than one it
  // accepts.
  std::function<bool(const PatchGrid& sized)> size_accepted;
  // When set: the lateral walk is taken from (and kept in) this cache, LateralWalkCache. The
  // grid is the same bit for bit as without it.
  LateralWalkCache* walks = nullptr;
};

// Cells kept around the closable cells when trimming (so the contact's edge lies inside).
inline constexpr int kTrimMarginCells = 2;

struct PatchBuild {
  PatchGrid grid;
  bool valid = false;            // false when the candidate gives no usable cross-section
  bool lateral_limited = false;  // the lateral range stopped at a profile end or a steep normal
  bool trimmed = false;          // trim_approach_m cropped the grid
  bool too_large = false;        // size_accepted refused it: not built (valid is false)
  // Conformal grids: per row j the rail and wheel profile parameters [m] the gap projections'
  // search windows were centred on, and x of the grid's centre column's contact point, so that
  // UpdateConformalGaps can project the same cells again.
  std::vector<double> rail_s_m, wheel_s_m;
  double x_contact_m = 0.0;
};

PatchBuild BuildPatchGrid(const WheelRailGeometry& geometry, const ContactCandidate& candidate,
                          const PatchGridOptions& options);

// The initial separation of every cell of a valid conformal grid that BuildPatchGrid made,
// computed again on another placed geometry of the same profiles (the wheel moved a little):
// the same cells (reference cross-section, x columns, crop) and the same projections as
// BuildPatchGrid's step 4, their search windows centred on the build's. Only the gaps change,
// so an influence operator made for the grid still applies. false when the build is not a
// conformal one.
bool UpdateConformalGaps(const WheelRailGeometry& geometry, PatchBuild* build);

}  // namespace railwear
