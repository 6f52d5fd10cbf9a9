// Validation of a vehicle's parameters (see vehicle.h).
#include "core/vehicle/vehicle.h"

#include <cmath>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

namespace railwear {

namespace {
void RequirePositive(const std::string& where, const char* key, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("{}: {} = {}: expected a finite number > 0", where, key, value));
  }
}
}  // namespace

void ValidateVehicle(const VehicleSpec& v, const std::string& where) {
  if (v.wheel_profile.size() < 2) {
    throw InputError(fmt::format("{}: wheel_profile is missing: expected a wheel profile", where));
  }
  RequirePositive(where, "axle_load_t", v.axle_load_N);
  RequirePositive(where, "rolling_radius_mm", v.rolling_radius_m);
  RequirePositive(where, "flange_back_distance_mm", v.flange_back_distance_m);
  if (!(v.cg_height_m >= 0.0) || !std::isfinite(v.cg_height_m)) {
    throw InputError(
        fmt::format("{}: cg_height_m = {}: expected a finite height >= 0", where, v.cg_height_m));
  }
  if (!std::isfinite(v.traction_N_per_axle) || std::abs(v.traction_N_per_axle) > v.axle_load_N) {
    throw InputError(fmt::format(
        "{}: traction_N_per_axle = {}: expected |traction| below the axle load {} N (no rail "
        "friction carries more)",
        where, v.traction_N_per_axle, v.axle_load_N));
  }
  if (v.kind != VehicleKind::kBogie) return;
  RequirePositive(where, "wheelbase_m", v.wheelbase_m);
  RequirePositive(where, "bogie_spacing_m", v.bogie_spacing_m);
  RequirePositive(where, "primary_kx_N_m", v.primary_kx_N_m);
  RequirePositive(where, "primary_ky_N_m", v.primary_ky_N_m);
  RequirePositive(where, "primary_semi_spacing_m", v.primary_semi_spacing_m);
  RequirePositive(where, "secondary_ky_N_m", v.secondary_ky_N_m);
  RequirePositive(where, "secondary_yaw_Nm_rad", v.secondary_yaw_Nm_rad);
  if (!(v.wheelbase_m < v.bogie_spacing_m)) {
    throw InputError(fmt::format(
        "{}: wheelbase_m = {}: expected less than bogie_spacing_m = {} (the bogies would overlap)",
        where, v.wheelbase_m, v.bogie_spacing_m));
  }
}

}  // namespace railwear
