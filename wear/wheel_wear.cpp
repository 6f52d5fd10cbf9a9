// The wheel's per-pass wear depth (wheel_wear.h).
#include "wear/wheel_wear.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/wheel_rail_geometry.h"
#include "core/numerics/check.h"

namespace railwear {

PlacedWheel PlaceWheelProfile(const Profile& wheel, const Profile& rail_track,
                              const WheelPlacement& placement) {
  const WheelPose pose{placement.lateral_shift_m, placement.roll_rad, placement.rolling_radius_m,
                       placement.yaw_rad};
  const WheelRailGeometry geometry(wheel, rail_track, pose);
  PlacedWheel placed;
  placed.wheel = &wheel;
  placed.rolling_radius_m = placement.rolling_radius_m;
  placed.in_rail = std::make_unique<const Profile>(wheel.Transformed(
      placement.roll_rad, Eigen::Vector2d(placement.lateral_shift_m, geometry.dz_m())));
  placed.locator.emplace(*placed.in_rail, /*material_toward_plus_z=*/false);
  return placed;
}

std::vector<double> CalcPatchWheelPassDepth(const PatchResult& patch, const PlacedWheel& wheel,
                                            const WearLaw& law, double wheel_hardness_Pa,
                                            double speed_m_s, double distance_per_pass_m,
                                            const WearGrid& wear_grid) {
  RAILWEAR_CHECK(distance_per_pass_m > 0.0 && wear_grid.n > 0);
  std::vector<double> dz = CalcColumnPassDepth(patch, law, wheel_hardness_Pa, speed_m_s);
  if (std::all_of(dz.begin(), dz.end(), [](double v) { return v == 0.0; })) {
    return std::vector<double>(wear_grid.n, 0.0);
  }
  // (*): column j's depth spread over its circle, times the revolutions of L.
  const std::vector<double> edges = CalcColumnEdgesOnRail(patch.grid, *wheel.locator);
  for (int j = 0; j < patch.grid.ns; ++j) {
    const double r = wheel.RadiusAt(0.5 * (edges[j] + edges[j + 1]));
    RAILWEAR_CHECK(r > 0.0);
    dz[j] *= distance_per_pass_m / (2.0 * std::numbers::pi * r);
  }
  return MapColumnAmounts(patch.grid, dz, *wheel.locator, wear_grid);
}

double WheelWornVolume(const std::vector<double>& depth_m, const WearGrid& wear_grid,
                       const Profile& wheel, double rolling_radius_m) {
  RAILWEAR_CHECK(static_cast<int>(depth_m.size()) == wear_grid.n);
  double volume = 0.0;
  for (int b = 0; b < wear_grid.n; ++b) {
    if (depth_m[b] == 0.0) continue;
    const double s = std::min(wear_grid.Centre(b), wheel.Length());
    const double r = rolling_radius_m + wheel.Position(s).y();
    volume += depth_m[b] * wear_grid.h_m * 2.0 * std::numbers::pi * r;
  }
  return volume;
}

}  // namespace railwear
