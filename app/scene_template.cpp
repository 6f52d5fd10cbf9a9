// Text of the `railwear init` scene template (kept in step with scene.cpp; a test loads it).
#include "app/scene_template.h"

namespace railwear::app {

std::string_view SceneTemplate() {
  return R"toml(# railwear scene: one wheel on one rail (or a wheelset on a track).
# Run it with:   railwear contact THIS_FILE.toml [--json -] [--csv p.csv] [--plot p.png]
#
# Units are in the key names (mm, N, MPa, rad, m/s). Frames (core/notation.md): y lateral,
# positive toward the field side; z vertical, positive downward (into the rail).
# Unknown keys, missing required keys, wrong types and out-of-range values are errors.

[scene]
name = "S1002 on UIC60"       # optional; default: the file name without extension
effects = ["normal"]          # optional; "normal" is implied. Add "tangential" for rolling
                              # contact (creep forces, slip; needs [load] friction and
                              # speed_m_s) and "damage" (T-gamma, WLRM RCF damage, FI_surf,
                              # shakedown; implies "tangential", needs the rail's
                              # shear_yield_MPa) and "coupling" (tractions change the normal
                              # gap, seed eq. 4 cross terms; implies "tangential").
                              # "wear" makes this a wear scene for `railwear wear`: it
                              # needs [wear] and [[traffic]] (below) instead of [load].

[model]                       # optional table
kind = "conformal"            # "hertz" | "halfspace" (planar + boussinesq)
                              # | "conformal" (conformal + golubenko); default "conformal"
                              # | "auto": per patch the cheapest model within the accuracy
                              #   (Hertz or half-space on non-conformal patches, conformal
                              #   geometry where the curvature changes across the patch;
                              #   the choice and its reason are reported per patch)
# geometry = "conformal"      # "planar" | "conformal"; overrides kind (not with "hertz")
# kernel = "golubenko"        # "boussinesq" | "golubenko"; overrides kind (not with "hertz")
constants = "fem"             # the named set of seed eq. 4's constants: "fem" (fitted to
                              # CalculiX, within 2 % of the FEM contact cases; default) |
                              # "paper" (the seed's c_f 0.75, c_z 1, c_s 0.25: ~29 % high
                              # on peak pressure against FEM; docs/models.md)
# influence_constants = { c_f = 0.75, c_z = 1.0, c_s = 0.25 }
                              # instead of constants: the constants themselves, seed eq. 4;
                              # each optional (the paper's values shown);
                              # c_f, c_z > 0, c_s any finite number. One set for both
                              # bodies, or a set for each curvature sign (each body of a
                              # patch uses the set of its lateral curvature there):
                              #   { convex = { c_f = 0.9, c_z = 1.0, c_s = 0.25 },
                              #     concave = { c_f = 0.8, c_z = 1.0, c_s = 0.25 } }
                              # Or the path (relative to this file) of a TOML file with an
                              # [influence_constants] table of either form, such as the one
                              # `railwear calibrate` writes.
accuracy = "standard"         # "draft" | "standard" | "reference" | "fine"; default "standard"
# cell_mm = [0.2, 0.2]        # explicit cell size [dx, ds] in mm (> 0); overrides accuracy
tangential = "fastsim"        # "fastsim" | "exact" | "auto"; default "fastsim": the tangential
                              # solver of the "tangential" effect (kind = "hertz": on the
                              # fast tread path's ellipse, one wheel or a wheelset's both,
                              # docs/library.md);
                              # "auto": per patch exact where spin or the patch's shape takes
                              # FASTSIM beyond the accuracy's creep-force tolerance
                              # (docs/rolling_contact.md)
# pressure_limit = "hardness" # "none" | "hardness"; default "none" (elastic). "hardness":
                              # elastic-perfectly-plastic contact, p <= the softer body's
                              # hardness_MPa (docs/contact_plasticity.md; not with "hertz")
# pressure_limit_MPa = 2600   # or the limit itself, in [1, 1e6] MPa (not with pressure_limit)
# normal_criterion = "pressure-update"  # or "gap-residual" (the strict one); default
                              # "pressure-update": the normal solver stops when its last step
                              # changed the pressures by at most normal_tolerance of their RMS
                              # and left the contact set unchanged (CONTACT's criterion; about
                              # that relative error in p_max and F_n). "gap-residual": when the
                              # deformed gap's residual is within normal_tolerance of the
                              # largest elastic displacement (docs/speed.md)
# normal_tolerance = 1e-4     # in [1e-13, 1e-2]; default 1e-4 (4 significant digits with
                              # margin) for "pressure-update", 1e-10 for "gap-residual"
# tangential_tolerance = 1e-6 # in [1e-10, 1e-2]; default 1e-6: the exact tangential solver
                              # stops when one more local solve would change no cell's traction
                              # by more than this times mu p_max (4 significant digits of the
                              # creep forces with margin; docs/speed.md). FASTSIM ignores it

[materials]                   # optional table; without it both bodies are steel,
                              # E_MPa = 210000 and nu = 0.28. With it, give both bodies.
wheel = { E_MPa = 210000, nu = 0.28 }          # E_MPa > 0, 0 <= nu < 0.5
rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600, shear_yield_MPa = 350 }
                              # hardness_MPa, shear_yield_MPa optional (> 0), for wear/damage;
                              # the wheel may give hardness_MPa too (for pressure_limit)
# rail = { grade = "R260" }   # or a rail grade: "R200" | "R260" | "R350HT" (EN 13674-1) presets
                              # E, nu, hardness and shear yield; keys beside it override them
# wheel = { grade = "R8" }    # or a wheel grade: "R7" | "R8" (EN 13262) presets E, nu and the
                              # rim's minimum hardness (the wheel's, when its wheel wears)

[wheel]                       # required
profile = "builtin:S1002"     # "builtin:S1002", "circle:R_mm", or a file (.csv, .whl, .prw,
                              # .ban) relative to this scene file
rolling_radius_mm = 460       # required, [50, 2000]: wheel radius at the profile's z = 0
# mirror_y = false            # true: mirror the profile (y -> -y) after reading it

[rail]                        # required
profile = "builtin:UIC60"     # "builtin:UIC60", "groove:R_mm", or a file (.csv, .ban, .prr)
cant = "1:40"                 # "1:N" or "0"; default "0" (no cant)
# mirror_y = false            # true: mirror the profile (before the cant is applied)

[load]                        # required; one wheel on one rail
vertical_N = 100000           # give exactly one of vertical_N ([1, 1e6]) ...
# approach_mm = 0.05          # ... and approach_mm ([1e-6, 1], from first contact)
lateral_mm = 0.0              # lateral position of the wheel toward the field side, from where
                              # the right wheel of a centred wheelset stands on this rail: 0 is
                              # a tread contact. The reference (optional; defaults shown):
# gauge_mm = 1435             # track gauge between the gauge faces, [1000, 1700]
# gauge_height_mm = 14        # below the top of rail, where the gauge is measured
# flange_back_distance_mm = 1360  # between the wheels' flange backs
# flange_back_position_mm = -70   # y of the flange back in the wheel profile (S1002: -70)
# lateral_shift_mm = -10.53   # or (not with lateral_mm) the wheel profile's origin relative to
                              # the rail's, toward the field side, [-100, 100]; default 0 when
                              # neither is given
roll_rad = 0.0                # roll of the wheel, |roll_rad| < 0.5; default 0
friction = 0.3                # in (0, 2]; needed by the "tangential" effect
speed_m_s = 20.0              # (0, 150]; needed by the "tangential" effect
# yaw_mrad = 0.0              # yaw of the wheel (positive turns its nose to the field side)
# pitch_velocity_rad_s = -43.5  # about the axle; default pure rolling, -speed / rolling radius
# longitudinal_force_N = 10000  # or a total longitudinal creep force on the wheel (> 0
                              # traction, < 0 braking): the pitch velocity is solved for it
# creepage = { xi = -0.004, eta = 0.0, spin_per_mm = 0.0 }
                              # prescribed creepages about the patch's pressure centre, instead
                              # of the wheel's motion (not with yaw_mrad/pitch_velocity_rad_s)

# A wheelset on a track instead of the single wheel of [load] (then [load] holds only friction
# and creepage); left wheel and rail are the mirror images of the profiles above:
# [track]
# gauge_mm = 1435             # between the gauge faces
# gauge_height_mm = 14        # below the top of rail
# [wheelset]
# flange_back_distance_mm = 1360
# flange_back_position_mm = -70   # y of the flange back in the wheel profile (S1002: -70)
# lateral_displacement_mm = 5.0   # toward the right: right-wheel flange contact
# yaw_mrad = 12.0
# roll_rad = -0.0006
# vertical_load_per_wheel_N = 10000
# speed_m_s = 2.0
# pitch_velocity_rad_s = -4.33   # default pure rolling
# longitudinal_force_N = 5000    # or the axle's total longitudinal force (sets the pitch velocity)

# A wear scene (effects = ["wear"], or ["wear", "damage"]; run with `railwear wear`) replaces
# [load] by [wear] and one [[traffic]] table per kind of wheel; [wheel] is then optional and gives
# the entries their default wheel profile and rolling radius. The rail needs hardness_MPa (not
# for law "usfd"), and shear_yield_MPa with "damage".
# [wear]
# law = "kth-continuous"       # "archard" | "kth" | "kth-continuous" | "usfd"
# k = 1.0e-4                   # Archard coefficient, only with law = "archard"
# # kth_k_seizure = 350e-4, kth_k_mild_low = 5.5e-4, kth_k_severe = 35e-4, kth_k_mild_high = 5.5e-4,
# # kth_v1_m_s = 0.2, kth_v2_m_s = 0.7, kth_pressure_ratio = 0.8     (KTH map, law "kth*")
# # kth_velocity_band = 0.25, kth_pressure_band = 0.05              (law "kth-continuous")
# # density_kg_m3 = 7850                                             (law "usfd")
# max_depth_per_step_mm = 0.1  # step control: the deepest wear of one step, in (0, 1]
# time_step = "euler"          # "euler" | "heun" (second order, twice the load cases a step;
#                              # not with wheel_wear): docs/wear.md "A second-order step"
# total_MGT = 10.0             # or total_passes = 1e6 (exactly one)
# integration_tolerance = 0.005  # spreads: adaptive nodes until the step's worn area is within
#                              # this relative tolerance, [0.0001, 0.1] (the default rule)
# quadrature_points = 5        # or fixed Gauss-Hermite nodes per spread, 1-81 (not both)
# spread_rule = "adaptive"     # "adaptive" | "gauss_hermite" | "piecewise_linear" (default: by
#                              # the key given above; each rule takes only its own key)
# spread_nodes = 128           # "piecewise_linear": m nodes within +-3 std, m/8 more per tail
#                              # to +-5 std; a multiple of 8 from 8 to 512 (the curve's reference)
# smoothing_mm = 1.0           # smoothing length of the per-pass depth (lambda = l^4)
# bin_mm = 0.1                 # arc-length bins the depth is collected on
# profile_spacing_mm = 0.2     # point spacing of the updated rail profile
# damage_layer_mm = 0.5        # opt-in: the old removal of RCF damage by wear (counts it twice)
# threads = 0                  # load cases in parallel; 0 = all cores
# gauge_face_angle_deg = 15    # patches steeper than this are on the gauge face, (0, 90)
# [wear.conditions.lubricated] # override a friction condition ("dry", "wet", "lubricated",
# friction = 0.1               # "friction_modified"): mu in (0, 2] and the factors on each
# archard_factor = 0.1         # law's wear coefficient, in (0, 10]; defaults and sources in
# kth_factor = 0.1             # docs/wear.md
# usfd_factor = 0.1
# db = "wear.sqlite"           # relative to this file; --db overrides
#
# [[traffic]]                  # one per kind of wheel; at least one
# name = "freight"             # optional
# wheel_profile = "builtin:S1002"  # default: [wheel] profile (mirror_y = true mirrors it)
# rolling_radius_mm = 460      # default: [wheel] rolling_radius_mm
# vertical_N = 110000          # wheel load on this rail, [1, 1e6]
# axle_load_t = 22.5           # for the MGT count; default twice the wheel load
# lateral_shift_mm = { mean = -4.5, std = 1.0 }   # or a number (no spread)
# roll_rad = 0.0
# yaw_mrad = 4.0               # angle of attack, |yaw| < 100 mrad
# friction = 0.35              # (0, 2]; required unless a condition gives it
# condition = "dry"            # top of rail: "dry" | "wet" | "lubricated" | "friction_modified"
# gauge_face_condition = "lubricated"  # gauge corner and face (default: the top of rail's)
# speed_m_s = 22.0             # required, > 0
# share = 0.4                  # relative share of passes, > 0
# wheel_wear = { distance_per_pass_m = 500 }  # co-evolution: this entry's wheel wears too;
#                              # the distance it rolls on track like this one per pass of the
#                              # entry, (0, 1e7] m; grade = "R7" | "R8" or hardness_MPa set its
#                              # hardness (default: materials.wheel's); on a vehicle entry
#                              # both wheels of every wheelset wear, each its own
# wheel_population = [ { profile = "worn.whl", weight = 3, name = "worn" },
#                      { profile = "builtin:S1002", weight = 1 } ]
#                              # or a TOML file of [[wheel]] tables with these keys: one load
#                              # case per wheel, weighted by share x weight / sum of weights
#                              # (instead of wheel_profile; rolling_radius_mm per wheel or the
#                              # entry's; not on vehicle entries)
)toml";
}

}  // namespace railwear::app
