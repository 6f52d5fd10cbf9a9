// Scene texts shared by the CLI tests of wear studies (wear_command_test, wear_accuracy_test,
// curving_command_test, accuracy_command_test).
#pragma once

namespace railwear::test {

// Draft accuracy, one traffic entry at three nodes: a step takes a few tens of milliseconds.
inline const char* const kSmallWearStudy = R"([scene]
name = "small study"
effects = ["wear", "damage"]
[model]
geometry = "conformal"
kernel = "boussinesq"
accuracy = "draft"
[materials]
wheel = { E_MPa = 210000, nu = 0.28 }
rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600, shear_yield_MPa = 350 }
[rail]
profile = "builtin:UIC60"
cant = "1:40"
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[wear]
law = "archard"
k = 1e-4
total_passes = 4e5
max_depth_per_step_mm = 0.05
quadrature_points = 3
[[traffic]]
vertical_N = 80000
axle_load_t = 16
lateral_shift_mm = { mean = -4.5, std = 1.0 }
yaw_mrad = 4.0
friction = 0.4
speed_m_s = 20.0
)";

// Both rails (issue 15), draft accuracy, no spread: the high rail loaded near its gauge corner,
// the low rail on its crown; two steps of at most 0.1 mm (the high rail's case sets them).
inline const char* const kTwoRailWearStudy = R"([scene]
name = "two rails"
effects = ["wear", "damage"]
[model]
geometry = "conformal"
kernel = "boussinesq"
accuracy = "draft"
[materials]
wheel = { E_MPa = 210000, nu = 0.28 }
rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600, shear_yield_MPa = 350 }
[track]
high_rail = "builtin:UIC60"
inclination = "1:40"
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[wear]
law = "archard"
k = 1e-4
total_passes = 2e4
max_depth_per_step_mm = 0.1
quadrature_points = 1
[[traffic]]
name = "outer wheel"
vertical_N = 80000
axle_load_t = 16
lateral_shift_mm = -4.5
yaw_mrad = 4.0
friction = 0.4
speed_m_s = 20.0
[[traffic]]
name = "inner wheel"
rail = "low"
vertical_N = 80000
axle_load_t = 16
lateral_shift_mm = -8.0
yaw_mrad = 4.0
friction = 0.4
speed_m_s = 20.0
)";

// Vehicle traffic: one free S1002 wheelset (16 t) on UIC60 1:40, R 1500 m without cant, draft
// accuracy: its curving takes about a second.
inline const char* const kWheelsetCurveScene = R"([scene]
name = "wheelset on R1500"
effects = ["wear"]
[model]
kind = "auto"
accuracy = "draft"
[materials]
wheel = { E_MPa = 210000, nu = 0.28 }
rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600 }
[track]
high_rail = "builtin:UIC60"
inclination = "1:40"
radius_m = 1500
cant_mm = 0
[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460
[wear]
law = "archard"
k = 1e-4
total_passes = 1e5
[[vehicle]]
name = "wheelset"
source = "a test"
kind = "wheelset"
axle_load_t = 16
[[traffic]]
vehicle = "wheelset"
speed_m_s = 25
friction = 0.3
)";

}  // namespace railwear::test
