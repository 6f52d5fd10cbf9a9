// Damage carried with the material through a wear step (issue 16, point 7).
//
// A wear step moves every point of the rail profile along its inward normal by the step's depth
// and resamples the moved curve at uniform arc length (wear/wear_simulation.h). The profile's arc
// length changes: a bin at arc length s of the worn profile is not the material that sat at s
// before. The accumulated RCF damage is a property of material points, so it is remapped:
//   1. the material map: the material point at arc length s of the previous profile (a point of
//      it) moves along its normal to a point of the moved curve, which sits at arc length t of
//      the next, resampled profile. The knots (s_i, t_i) of the previous profile's points give a
//      monotone piecewise-linear map s <-> t (MaterialMapOfStep);
//   2. each bin of the next profile, t in [c h, (c+1) h], covers the material interval
//      [s(c h), s((c+1) h)]; its damage is the material-length average of the previous bins'
//      piecewise-constant damage over that interval (RemapDamage).
// The remap conserves the integral of damage over material, sum_c D'_c m'_c = sum_b D_b m_b
// (m: a bin's material length; to rounding), and leaves a uniform damage uniform. Its one cost is
// the averaging of a bin over the (at most two or three) previous bins it overlaps.
#pragma once

#include <vector>

#include "core/profile/profile.h"
#include "wear/pass_depth.h"

namespace railwear {

// The monotone piecewise-linear map between the previous profile's arc length s (the material
// coordinate) and the next profile's arc length t; both knot vectors run from 0 to each
// profile's length and increase strictly.
struct MaterialMap {
  std::vector<double> s_m, t_m;
  double ToNext(double s_m_value) const;      // t(s); clamped to the ends
  double ToPrevious(double t_m_value) const;  // s(t); clamped to the ends
};

// The identity on a profile of length L (a step that wears nothing).
MaterialMap IdentityMaterialMap(double length_m);

// The map of one step: `previous` the profile the step started from, `moved` the same points
// moved along their normals (point i of `previous` is point i of the moved point list; the
// Profile may have subdivided long chords, which are skipped), `next` the moved curve resampled
// (ResampleProfile: point k of `next` is moved.Position(moved.Length() k / m)).
MaterialMap MaterialMapOfStep(const Profile& previous,
                              const std::vector<Eigen::Vector2d>& moved_points,
                              const Profile& moved, const Profile& next);

// Material length of each bin of a grid on the next profile of length `next_length_m` (the
// measure the remapped damage is conserved in): m_c = s(min((c+1) h, L)) - s(c h).
std::vector<double> MaterialBinLengths(const WearGrid& next_grid, double next_length_m,
                                       const MaterialMap& map);

// Damage per bin of `previous_grid` (profile length previous_length_m; shorter vectors are
// padded with zeros) remapped onto `next_grid` (profile length next_length_m) by `map`.
std::vector<double> RemapDamage(const std::vector<double>& damage, const WearGrid& previous_grid,
                                double previous_length_m, const WearGrid& next_grid,
                                double next_length_m, const MaterialMap& map);

}  // namespace railwear
