// Wear measures of a worn rail profile against an original one: the normal wear depth along the
// original profile, the worn area, the largest depth and where it is, and the three rail-head
// wear measures W1 (vertical), W2 (side) and W3 (45 degrees) of track-maintenance practice.
//
// Frame: both profiles in the rail's own frame R, uncanted (core/notation.md): y lateral, positive
// toward the field side, so the gauge side is at negative y; z vertical, positive downward (into
// the rail); metres. The built-in UIC60 has its crown at the origin (y = 0 is the rail centre
// line) and its gauge face at y = -36 mm.
//
// Sign: every depth is positive where material was removed, i.e. where the worn profile lies
// inside the original (below it on the crown, +z; toward the field side on the gauge face, +y).
//
// Definitions (railwear's statement of the EN 13674-1 / UIC 714 practice; the standards define
// W1 and W2 on the measured head, railwear measures all three along fixed lines of a "wear gauge"
// built once on the unworn rail, MakeWearGauge):
//   normal depth d(s)  at arc length s of the original profile: the distance from the original
//                      point C(s), along the original's inward unit normal, to the worn profile
//                      (the crossing of that normal line with the worn profile nearest to C(s)).
//   W1, vertical wear  along the vertical line y = 0 (the rail centre line): z of the worn
//                      surface minus z of the original surface.
//   W2, side wear      along the horizontal line z = z_top + 14 mm, z_top being the unworn top of
//                      rail at y = 0 ("14 mm below the top of the rail", the gauge-measuring
//                      height of EN 13848-1 and UIC 714): y of the worn gauge face minus y of the
//                      original gauge face (positive when the gauge face moved toward the field).
//   W3, 45-degree wear along the line through the gauge-corner point P45 of the unworn profile
//                      whose outward normal points at 45 degrees between up (-z) and the gauge
//                      side (-y), in the direction of the inward normal (+1, +1)/sqrt(2): the
//                      distance from the original to the worn profile along that line. On UIC60
//                      P45 lies on the R13 arc at (-32.208, 5.757) mm and the line passes through
//                      the arc's centre. (Often approximated in practice as W3 ~ W2 + W1/2.)
//   worn area          the signed area between the curves, material removed positive:
//                      A = integral of (d - kappa d^2 / 2) ds over the original, kappa the
//                      original's curvature (positive where it is convex, centre of curvature on
//                      the material side). This is exact for a worn curve C(s) + d(s) nu(s)
//                      (nu the inward normal) while |d kappa| < 1; the midpoint rule integrates it.
//
// Because W1/W2/W3 are measured along lines fixed on the unworn rail, they are additive over
// steps: measured with the gauge of step 0, W(A -> B) = W(0 -> B) - W(0 -> A).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/profile/profile.h"

namespace railwear {

// A straight measuring line: a point on the unworn rail surface and the unit direction into the
// rail material along which wear is measured.
struct MeasuringLine {
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();     // (y, z) [m], rail frame
  Eigen::Vector2d direction = Eigen::Vector2d::UnitY();  // unit (dy, dz), into the material
};

// The three measuring lines of W1, W2, W3 (definitions above), fixed on an unworn profile.
struct WearGauge {
  MeasuringLine vertical;  // W1: point at (0, z_top), direction (0, 1)
  MeasuringLine side;      // W2: point on the gauge face at z_top + side depth, direction (1, 0)
  MeasuringLine corner45;  // W3: point P45, direction (1, 1)/sqrt(2)
};

// Builds the wear gauge on `unworn` (rail frame, gauge side at -y). side_wear_depth_m is the depth
// of the W2 line below the top of rail (EN 13674 / UIC 714: 14 mm). Throws InputError naming the
// profile's source when it is not a rail head these lines can be drawn on: no surface at y = 0, no
// gauge face at that depth, or no gauge-corner point with a 45-degree normal.
WearGauge MakeWearGauge(const Profile& unworn, double side_wear_depth_m = 14e-3);

struct WearMeasureOptions {
  // Sampling step of the depth along the original's arc length [m]; the samples are the centres
  // of equal cells no longer than this. Range [1e-6, 1e-3], default 0.1 mm.
  double step_m = 1e-4;
  // Depth of the W2 line below the top of rail [m] when the gauge is built here. Default 14 mm.
  double side_wear_depth_m = 14e-3;
  // A crossing farther than this from the original along a normal or measuring line is not the
  // worn surface (it is the far side of the head): such samples count as unmatched [m]. > 0,
  // default 20 mm.
  double max_normal_distance_m = 20e-3;
  // The wear gauge to measure W1/W2/W3 with. Empty: built from the original profile. Give the
  // gauge of the run's unworn (step-0) profile to compare two worn steps on the same lines.
  std::optional<WearGauge> gauge;

  // True when all values are in range; otherwise false with a reason in *error.
  bool IsValid(std::string* error) const;
};

struct WearMeasures {
  double worn_area_m2 = 0.0;   // signed area between original and worn, removed positive [m^2]
  double max_depth_m = 0.0;    // largest normal depth d(s) over the samples [m]
  double max_depth_s_m = 0.0;  // arc length on the original where it occurs [m]
  double max_depth_y_m = 0.0;  // position on the original profile where it occurs [m]
  double max_depth_z_m = 0.0;
  double vertical_wear_m = 0.0;  // W1 [m]
  double side_wear_m = 0.0;      // W2 [m]
  double wear_45_m = 0.0;        // W3 [m]
  // Normal depth d along the original profile: s_m[i] is the arc length from the original's
  // first point, depth_m[i] the depth there [m], shape [n] each. NaN where the normal misses the
  // worn profile within max_normal_distance_m (then counted in unmatched_samples and left out of
  // the area and the maximum).
  std::vector<double> s_m, depth_m;
  int unmatched_samples = 0;
  // W1/W2/W3 are NaN when their line misses the original or the worn profile within
  // max_normal_distance_m of the line's point.
};

// Compares `worn` with `original` (both rail-frame profiles of the same rail). Throws InputError
// for invalid options (naming the option, its value and the range) and, when options.gauge is
// empty, for an original on which MakeWearGauge cannot draw its lines.
WearMeasures CompareProfiles(const Profile& original, const Profile& worn,
                             const WearMeasureOptions& options = {});

// The same for a wheel (issue 16, co-evolution): both profiles in the wheel profile frame
// (material toward -z), the normal depth along the original wheel profile, the worn area and the
// largest depth (removed material positive); W1/W2/W3 are rail measures and NaN here, and
// options.gauge is not used. Throws InputError for invalid options.
WearMeasures CompareWheelProfiles(const Profile& original, const Profile& worn,
                                  const WearMeasureOptions& options = {});

// The flange measures of a wheel profile (EN 15313 / UIC 510-2 practice, railwear's statement):
// in the wheel profile frame (core/notation.md: origin on the taping line, 70 mm from the flange
// back; y toward the field side, the flange at negative y; z toward the rail, so the flange tip
// has the largest z), metres:
//   Sh, flange height    z of the flange tip (the largest z at y < 0) minus z of the tread at
//                        y = 0 (the taping line);
//   Sd, flange thickness y of the flange's tread-side flank where z = z(0) + 10 mm, minus y of
//                        the flange back (flange_back_y_m, -70 mm);
//   qR, flange slope     y of that flank point minus y of the flank where z = z_tip - 2 mm.
// Measured on the profile itself, so a worn tread (z(0) moving up) raises Sh as the standard's
// measure does. New S1002: Sh 28, Sd 32.5, qR 10.8 mm (tested). NaN where a line misses the
// profile (no tread at y = 0, no flank at a height).
struct WheelFlangeMeasures {
  double flange_height_m = 0.0;     // Sh
  double flange_thickness_m = 0.0;  // Sd
  double flange_slope_m = 0.0;      // qR
};
WheelFlangeMeasures MeasureWheelFlange(const Profile& wheel, double flange_back_y_m = -70e-3);

}  // namespace railwear
