// The patch-results stage of SolveContact: a solved grid's pressure or a Hertz ellipse turned
// into a PatchResult (area, peak, forces, pressure centre on the rail), and the measured extent
// of the contact that the potential-area stage checks its grid against. Internal to SolveContact.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/contact/contact_result.h"
#include "core/contact/hertz.h"
#include "core/geometry/patch_grid.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::internal {

// Measured extent of the contact on a grid: half-lengths along x and s of the cells with p > 0.
struct Extent {
  double half_x = 0.0, half_s = 0.0;
  double s_lo = 0.0, s_hi = 0.0;  // s range of the cells in contact, cell edges included
  bool touches_x_edge = false, touches_s_edge = false;
  int cells = 0;
};
// p: pressure per cell [Pa], shape [g.cells()].
Extent MeasureExtent(const PatchGrid& g, const Eigen::Ref<const Eigen::VectorXd>& p);

// Contact area [m^2] with the edge located inside the boundary cells (a level-set estimate of
// the zero of p^2; see the .cpp). p: pressure per cell [Pa], shape [g.cells()].
double SubCellArea(const PatchGrid& g, const Eigen::Ref<const Eigen::VectorXd>& p);

// SubCellArea's sub-samples per side of a square between four cell centres.
inline constexpr int kSubSamples = 24;
// How many of the kSubSamples x kSubSamples points (r, t) = ((u + 0.5), (v + 0.5)) / kSubSamples
// of a square have a positive bilinear interpolant of its corner values a (r = 0, t = 0),
// b (1, 0), c (0, 1), d (1, 1), evaluated sample by sample as
// (1 - r) (1 - t) a + r (1 - t) b + (1 - r) t c + r t d.
int SubSampledHits(double a, double b, double c, double d);

// When a grid patch's sub-cell area is computed: with its other results, or deferred (area_m2
// NaN) until FillDeferredAreas. The vertical balance's intermediate solves replace their patches
// by the next solve's, and nothing before the result's end reads the area, so SubCellArea (a
// tenth of a warm gauge-corner call, docs/library.md) runs only on the patches reported.
enum class PatchArea { kNow, kDeferred };

// A grid patch's result from its pressure p [Pa] (shape [grid.cells()]): forces, peak, the
// sub-cell area (when `area` is kNow) and the pressure centre projected onto the rail profile of
// `geom`; with a pressure limit p_lim [Pa] also the plastic cells (p >= p_lim), their area and
// load.
PatchResult NumericalPatch(const WheelRailGeometry& geom, PatchGrid grid,
                           const Eigen::Ref<const Eigen::VectorXd>& p,
                           std::optional<double> pressure_limit_Pa = std::nullopt,
                           PatchArea area = PatchArea::kNow);

// The sub-cell area of every patch whose area NumericalPatch deferred (the same value it would
// have computed).
void FillDeferredAreas(std::vector<PatchResult>* patches);

// The Hertz model's patch at candidate c with ellipse h.
PatchResult HertzPatch(const ContactCandidate& c, const HertzSolution& h);

// The result with its totals over its patches (area, peak, forces) and its run time time_s [s].
ContactResult FinishResult(ContactResult r, double time_s);

}  // namespace railwear::internal
