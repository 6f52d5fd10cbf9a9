// A rail vehicle for steady-state curving: a single wheelset, or a car body on two bogies of two
// wheelsets each, with linear primary and secondary suspension.
//
// Layout (track frame T, x forward): a bogie vehicle's bogie centres are at x = +-L (L half the
// bogie spacing), each bogie's wheelsets at +-a from its centre (a half the wheelbase); the
// wheelsets are numbered from the front: 0, 1 in the leading bogie, 2, 3 in the trailing one.
// Primary: per axlebox a longitudinal stiffness kx and a lateral stiffness ky, the two axleboxes
// of a wheelset b1 to either side of its centre, so a wheelset is held by the lateral stiffness
// 2 ky and the yaw stiffness 2 kx b1^2 against its bogie frame. Secondary, per bogie: a lateral
// stiffness and a yaw stiffness against the car body (air springs or a centre bowl's friction
// taken as an equivalent stiffness). Vertical loads are quasi-static: the axle load and, in a
// curve, the load transfer of the unbalanced lateral force at the centre of gravity's height.
#pragma once

#include <array>
#include <string>

#include "core/geometry/wheelset.h"
#include "core/numerics/enum_names.h"
#include "core/profile/profile.h"

namespace railwear {

enum class VehicleKind { kWheelset, kBogie };

inline constexpr std::array<EnumName<VehicleKind>, 2> kVehicleKindNames = {{
    {VehicleKind::kWheelset, "wheelset"},
    {VehicleKind::kBogie, "bogie"},
}};

struct VehicleSpec {
  std::string name;
  std::string source;  // where the parameters come from
  VehicleKind kind = VehicleKind::kBogie;
  double axle_load_N = 0.0;  // static vertical load of one axle, > 0 (wheel load is half)
  Profile wheel_profile;     // wheel profile frame (core/notation.md)
  double rolling_radius_m = 0.46;
  double flange_back_distance_m = 1.360;
  double flange_back_position_m = -0.070;  // y of the flange back in the wheel profile frame
  // Bogie vehicles only:
  double wheelbase_m = 2.5;             // of a bogie (2a)
  double bogie_spacing_m = 19.0;        // between the bogie centres (2L)
  double primary_kx_N_m = 1.2e7;        // longitudinal, per axlebox
  double primary_ky_N_m = 5.0e6;        // lateral, per axlebox
  double primary_semi_spacing_m = 1.0;  // b1: axlebox spring to wheelset centre, lateral
  double secondary_ky_N_m = 3.0e5;      // lateral, per bogie
  double secondary_yaw_Nm_rad = 3.0e5;  // yaw, per bogie
  // Height of the centre of gravity above the rail for the load transfer [m], >= 0.
  double cg_height_m = 1.5;
  // Longitudinal force of every axle on the vehicle [N]: > 0 traction, < 0 braking, 0 free
  // rolling.
  double traction_N_per_axle = 0.0;

  int wheelsets() const { return kind == VehicleKind::kBogie ? 4 : 1; }
  // One of its wheelsets at a state: y toward the high rail [m], yaw and roll [rad].
  WheelsetSpec WheelsetAt(double y_m, double yaw_rad, double roll_rad) const {
    WheelsetSpec ws;
    ws.flange_back_distance_m = flange_back_distance_m;
    ws.flange_back_position_m = flange_back_position_m;
    ws.rolling_radius_m = rolling_radius_m;
    ws.lateral_displacement_m = y_m;
    ws.yaw_rad = yaw_rad;
    ws.roll_rad = roll_rad;
    return ws;
  }
  int bogies() const { return kind == VehicleKind::kBogie ? 2 : 0; }
};

inline std::string_view ToString(VehicleKind kind) { return EnumToString(kVehicleKindNames, kind); }

// Throws InputError naming `where` (e.g. "vehicle \"coach\"") and the scene key for a missing
// profile, non-positive loads, radii, lengths or stiffnesses (the secondary ones of a bogie
// vehicle must be > 0 to hold the car body), a wheelbase not below the bogie spacing, or a
// traction force above the axle load.
void ValidateVehicle(const VehicleSpec& vehicle, const std::string& where);

}  // namespace railwear
