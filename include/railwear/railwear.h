/* railwear C API: conformal wheel-rail contact for vehicle-dynamics codes (issue 20).
 *
 * One opaque handle per problem (a single wheel on its rail, or a wheelset on a track); no global
 * state, so independent handles may be used from different threads at the same time (one handle
 * must not be used by two threads at once). Every function returns a status (RW_OK = 0 or an
 * error code); after an error, rw_last_error(handle) gives its text. No C++ exception crosses
 * this boundary.
 *
 * Input structs are versioned: their first member `struct_size` must be set to sizeof(the
 * struct) and the rest filled with the defaults by the rw_init_* functions.
 * Output structs likewise: the caller sets struct_size, the library fills the struct.
 *
 * Units are SI throughout: metres, radians, newtons, pascals, seconds.
 *
 * Call sequence (docs/library.md):
 *   rw_create -> setup (profiles required; materials, model, influence constants, friction,
 *   geometry, wear optional) -> per step: rw_set_state, rw_calculate, queries (and
 *   rw_accumulate for wear) -> rw_destroy.
 *
 * Frames (core/notation.md): rail frame R: x forward (rolling direction), y lateral toward the
 * rail's field side, z down. Track frame: x forward, Y to the right, z down. A wheelset's left
 * wheel reports its results in the left rail's own frame (y toward its field side).
 *
 * The header compiles as C99 and as C++.
 */
#ifndef RAILWEAR_RAILWEAR_H
#define RAILWEAR_RAILWEAR_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define RW_API __declspec(dllimport)
#elif defined(__GNUC__)
#define RW_API __attribute__((visibility("default")))
#else
#define RW_API
#endif
#if defined(RAILWEAR_BUILDING_LIBRARY) && defined(_WIN32)
#undef RW_API
#define RW_API __declspec(dllexport)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Versions ---------------------------------------------------------------------------- */

/* The API version of this header. A library of the same major version accepts every struct
 * size this header writes. rw_api_version() gives the library's (major * 10000 + minor * 100 +
 * patch), for a check at run time. */
#define RW_API_VERSION_MAJOR 1
#define RW_API_VERSION_MINOR 5
#define RW_API_VERSION_PATCH 0
#define RW_API_VERSION \
  (RW_API_VERSION_MAJOR * 10000 + RW_API_VERSION_MINOR * 100 + RW_API_VERSION_PATCH)

RW_API int rw_api_version(void);

/* ---- Status codes ------------------------------------------------------------------------ */

typedef int rw_status;
enum {
  RW_OK = 0,
  RW_ERROR_NULL_ARGUMENT = 1,   /* a required pointer is NULL */
  RW_ERROR_STRUCT_SIZE = 2,     /* struct_size is not a size this library knows */
  RW_ERROR_INVALID_VALUE = 3,   /* NaN, infinite, negative load, out-of-range value */
  RW_ERROR_UNKNOWN_FLAG = 4,    /* an enum value or flag bit this library does not know */
  RW_ERROR_CALL_ORDER = 5,      /* e.g. calculate before the profiles or the state are set */
  RW_ERROR_BUFFER_TOO_SMALL = 6,/* a caller buffer holds fewer elements than the size query */
  RW_ERROR_INDEX = 7,           /* a patch index outside [0, patch count) */
  RW_ERROR_INPUT = 8,           /* bad input found by the engine (profile file, profile points,
                                   inconsistent set-up): the message names it */
  RW_ERROR_NOT_CONVERGED = 9,   /* the solve ran but did not converge; results are readable */
  RW_ERROR_NO_CONTACT = 10,     /* the bodies do not touch; results are readable (no patch) */
  RW_ERROR_INTERNAL = 11,       /* an unexpected failure inside the engine (a bug): a failed
                                   internal check ("internal check failed: EXPR (FILE:LINE)") or
                                   another unexpected exception. The handle stays usable: its
                                   results are cleared and its reuse cache dropped, its set-up,
                                   state and depth field kept (docs/library.md) */
  RW_ERROR_OUT_OF_MEMORY = 12,
  RW_ERROR_WRONG_KIND = 13      /* a wheelset-only call on a single-wheel handle or back */
};

/* The constant's name ("RW_OK", ...); "unknown status" for other values. Never NULL. */
RW_API const char* rw_status_name(rw_status status);

/* ---- Handle ------------------------------------------------------------------------------ */

typedef struct rw_problem rw_problem; /* opaque */

typedef int rw_problem_kind;
enum {
  RW_PROBLEM_WHEEL = 0,    /* one wheel on one rail (the rail's frame) */
  RW_PROBLEM_WHEELSET = 1  /* a wheelset on a track: both wheels, each on its rail */
};

/* Creates a handle; *out is NULL on error. */
RW_API rw_status rw_create(rw_problem_kind kind, rw_problem** out);
/* Frees the handle and everything it holds; NULL is ignored. */
RW_API void rw_destroy(rw_problem* problem);
/* The text of the last error on this handle ("" after a successful call). Valid until the next
 * call on the handle. For a NULL handle a fixed text. Never NULL. */
RW_API const char* rw_last_error(const rw_problem* problem);

/* ---- Set-up ------------------------------------------------------------------------------ */

typedef int rw_body;
enum {
  RW_BODY_WHEEL = 0,
  RW_BODY_RAIL = 1,      /* the (right) rail, before cant */
  RW_BODY_LEFT_RAIL = 2  /* wheelset only: a different left rail, in its own frame */
};

/* A profile from a file (.csv, MiniProf .ban/.whl, SIMPACK .prr/.prw) or a built-in spec
 * ("builtin:S1002", "builtin:UIC60", "circle:R_mm", "groove:R_mm"). Relative paths are taken
 * from the current directory. */
RW_API rw_status rw_set_profile_file(rw_problem* problem, rw_body body, const char* path);
/* A profile from n points (y, z) in metres, interleaved: yz_m[2 i] = y_i, yz_m[2 i + 1] = z_i,
 * ordered with y increasing (the profile frame of core/notation.md), n >= 4. */
RW_API rw_status rw_set_profile_points(rw_problem* problem, rw_body body, const double* yz_m,
                                       size_t n_points);

typedef struct rw_material {
  size_t struct_size;
  double youngs_modulus_Pa; /* > 0; default 210e9 */
  double poisson_ratio;     /* [0, 0.5); default 0.28 */
  double hardness_Pa;       /* > 0, or NaN (not given; the default) */
  double shear_yield_Pa;    /* > 0, or NaN (not given; the default). The rail's is needed for
                               RW_EFFECT_DAMAGE */
} rw_material;

RW_API rw_status rw_init_material(rw_material* material);
RW_API rw_status rw_set_materials(rw_problem* problem, const rw_material* wheel,
                                  const rw_material* rail);

typedef int rw_model_kind;
enum {
  RW_MODEL_HERTZ = 0,     /* analytic, no grid; since 1.3 with RW_EFFECT_TANGENTIAL (a single
                             wheel; since 1.4 a wheelset too, both wheels or neither): the fast
                             tread path, Hertz's ellipse and FASTSIM on it, where the contact
                             is one Hertzian patch, else RW_MODEL_AUTO (rw_get_patch_model
                             says which and why; docs/library.md) */
  RW_MODEL_HALFSPACE = 1, /* planar grid, Boussinesq kernel */
  RW_MODEL_CONFORMAL = 2, /* conformal grid, the seed's kernel (eq. 4); the default */
  RW_MODEL_CUSTOM = 3,    /* the given geometry and kernel */
  RW_MODEL_AUTO = 4       /* per patch, the cheapest model within the accuracy */
};
/* RW_*_DEFAULT: the kind's own (RW_MODEL_CUSTOM needs both given). */
typedef int rw_geometry_model;
enum { RW_GEOMETRY_DEFAULT = -1, RW_GEOMETRY_PLANAR = 0, RW_GEOMETRY_CONFORMAL = 1 };
typedef int rw_kernel;
enum { RW_KERNEL_DEFAULT = -1, RW_KERNEL_BOUSSINESQ = 0, RW_KERNEL_GOLUBENKO = 1 };
typedef int rw_accuracy;
enum { RW_ACCURACY_DRAFT = 0, RW_ACCURACY_STANDARD = 1, RW_ACCURACY_REFERENCE = 2,
       RW_ACCURACY_FINE = 3 };
typedef int rw_tangential;
enum { RW_TANGENTIAL_FASTSIM = 0, RW_TANGENTIAL_EXACT = 1, RW_TANGENTIAL_AUTO = 2 };

/* Effects beyond normal contact (flags, OR-ed). Damage and coupling imply tangential. */
#define RW_EFFECT_TANGENTIAL 0x1u /* rolling contact: creepages, tractions, creep forces */
#define RW_EFFECT_DAMAGE 0x2u     /* T-gamma, WLRM, FI_surf per patch */
#define RW_EFFECT_COUPLING 0x4u   /* normal-tangential coupling iteration */

/* Since 1.5. The normal solver's stopping rule, a scene's [model] normal_criterion (docs/speed.md
 * "The 4-digit defaults"). */
typedef int rw_normal_criterion;
enum {
  RW_NORMAL_PRESSURE_UPDATE = 0, /* "pressure-update", the default: the last step changed the
                                    pressures by at most the tolerance of their RMS and left the
                                    contact set as it was (1e-4: 4 significant digits) */
  RW_NORMAL_GAP_RESIDUAL = 1     /* "gap-residual", the strict setting: the deformed gap's
                                    residual within the tolerance (1e-10) of the largest elastic
                                    displacement */
};

typedef struct rw_model {
  size_t struct_size;
  rw_model_kind kind;         /* default RW_MODEL_CONFORMAL */
  rw_geometry_model geometry; /* RW_MODEL_CUSTOM only; default RW_GEOMETRY_DEFAULT */
  rw_kernel kernel;           /* RW_MODEL_CUSTOM, and RW_MODEL_AUTO (its conformal patches;
                                 default Boussinesq); default RW_KERNEL_DEFAULT */
  rw_accuracy accuracy;       /* default RW_ACCURACY_STANDARD */
  rw_tangential tangential;   /* default RW_TANGENTIAL_FASTSIM */
  uint32_t effects;           /* RW_EFFECT_* flags; default 0: normal contact only */
  double cell_dx_m;           /* explicit cell size along x and s [m] > 0, replacing the */
  double cell_ds_m;           /* accuracy preset; 0 (the default): from the preset */
  /* Since 1.5 (a caller of 1.4 passes struct_size = RW_MODEL_SIZE_1_4 and gets the defaults): */
  rw_normal_criterion normal_criterion; /* default RW_NORMAL_PRESSURE_UPDATE */
  double normal_tolerance;    /* the criterion's tolerance in [1e-13, 1e-2] (a scene's [model]
                                 normal_tolerance), or 0 (the default): the criterion's own,
                                 1e-4 or 1e-10 */
  double tangential_tolerance; /* the exact tangential solver's stop, relative to mu p_max, in
                                  [1e-10, 1e-2] (a scene's [model] tangential_tolerance), or 0
                                  (the default): 1e-6. FASTSIM ignores it */
} rw_model;

/* rw_model's size in API 1.0 to 1.4 (before the normal solver's stopping rule), still accepted
 * by rw_init_model and rw_set_model. */
#define RW_MODEL_SIZE_1_4 offsetof(rw_model, normal_criterion)

RW_API rw_status rw_init_model(rw_model* model);
RW_API rw_status rw_set_model(rw_problem* problem, const rw_model* model);

/* The constants of the seed's eq. 4 (dimensionless). With `separate` nonzero, convex and
 * concave bodies use their own sets and c_f, c_z, c_s are unused. rw_init_influence_constants
 * fills the default of a new handle, as of a scene: the FEM-calibrated convex and concave sets
 * (separate = 1; the scene reader's constants = "fem"), and as the one set the seed's 0.75, 1,
 * 0.25 ("paper"), which separate = 0 selects. */
typedef struct rw_influence_constants {
  size_t struct_size;
  double c_f, c_z, c_s;                         /* the seed's: 0.75, 1, 0.25 */
  int separate;                                 /* 0 (default) or 1 */
  double convex_c_f, convex_c_z, convex_c_s;    /* with separate */
  double concave_c_f, concave_c_z, concave_c_s; /* with separate */
} rw_influence_constants;

RW_API rw_status rw_init_influence_constants(rw_influence_constants* constants);
RW_API rw_status rw_set_influence_constants(rw_problem* problem,
                                            const rw_influence_constants* constants);

/* The friction coefficient mu in (0, 2]. Needed for RW_EFFECT_TANGENTIAL; with normal contact
 * only it sets Nadal's limit of the flange-climb check. */
RW_API rw_status rw_set_friction(rw_problem* problem, double friction);

/* Since 1.1. The elastic-perfectly-plastic pressure limit of the normal solve (a scene's [model]
 * pressure_limit / pressure_limit_MPa, docs/contact_plasticity.md): every cell's pressure is
 * bounded by p_lim and the patch grows until it carries the load. RW_PRESSURE_LIMIT_NONE (the
 * default, elastic; value_Pa NaN), RW_PRESSURE_LIMIT_HARDNESS (p_lim = the smaller hardness_Pa
 * given to rw_set_materials; value_Pa NaN), RW_PRESSURE_LIMIT_VALUE (p_lim = value_Pa in
 * [1e6, 1e12] Pa, the scene's 1 MPa to 1e6 MPa). The Hertz model has no cells to limit:
 * rw_calculate then returns RW_ERROR_INPUT with the engine's message. */
typedef int rw_pressure_limit;
enum {
  RW_PRESSURE_LIMIT_NONE = 0,
  RW_PRESSURE_LIMIT_HARDNESS = 1,
  RW_PRESSURE_LIMIT_VALUE = 2
};
RW_API rw_status rw_set_pressure_limit(rw_problem* problem, rw_pressure_limit kind,
                                       double value_Pa);

/* Wheel and track geometry. */
typedef struct rw_geometry {
  size_t struct_size;
  double rolling_radius_m;       /* wheel radius at the wheel profile's z = 0; default 0.46 */
  double rail_cant;              /* rail inclination as a ratio (1:40 -> 0.025); default 0 */
  /* Wheelset only: */
  double gauge_m;                /* default 1.435 */
  double gauge_height_m;         /* default 0.014 */
  double flange_back_distance_m; /* default 1.360 */
  double flange_back_position_m; /* flange back in the wheel profile frame; default -0.070 */
} rw_geometry;

RW_API rw_status rw_init_geometry(rw_geometry* geometry);
RW_API rw_status rw_set_geometry(rw_problem* problem, const rw_geometry* geometry);

/* ---- Per step ---------------------------------------------------------------------------- */

#define RW_STATE_CREEPAGE 0x1u /* prescribed creepages (xi, eta, spin) instead of the motion */

typedef struct rw_state {
  size_t struct_size;
  /* Position. Single wheel: the wheel profile origin's y in the rail frame. Wheelset: the
   * wheelset's lateral displacement toward +Y (flange contact on the right wheel). [m] */
  double lateral_m;
  double yaw_rad;  /* about +z (down): positive turns the nose toward +y; |yaw| <= 0.1 */
  double roll_rad; /* about +x; |roll| <= 0.5 */
  /* Load: exactly one of the two is finite (the other NaN). Wheelset: per wheel. */
  double vertical_force_N; /* > 0 */
  double approach_m;       /* > 0; single wheel only */
  /* Wheelset only: the left wheel's load when it differs (NaN: the same). */
  double left_vertical_force_N;
  /* Motion (with RW_EFFECT_TANGENTIAL). */
  double speed_m_s;            /* > 0 */
  double pitch_velocity_rad_s; /* NaN: pure rolling at the nominal radius */
  double lateral_velocity_m_s; /* toward +y (wheelset: +Y of the track; mirrored for the left) */
  double yaw_velocity_rad_s;   /* about +z (wheelset: against the curve's own -V curvature) */
  double longitudinal_force_N; /* NaN, or a prescribed total F_x instead of the pitch velocity */
  double curvature_per_m;      /* wheelset only: track curvature 1/R >= 0, curve to the left */
  /* Prescribed creepages with RW_STATE_CREEPAGE. */
  double creepage_xi, creepage_eta, creepage_spin_per_m;
  uint32_t flags; /* RW_STATE_* */
} rw_state;

/* Defaults: positions, velocities, curvature and creepages 0; speed 1 m/s; the loads, the
 * pitch velocity and the longitudinal force NaN (the caller must give a load). */
RW_API rw_status rw_init_state(rw_state* state);
RW_API rw_status rw_set_state(rw_problem* problem, const rw_state* state);

/* Since 1.5. Warm start across calls (enable 1; 0, the default, solves every calculate cold).
 * A single wheel's grid solve then starts from the previous calculate's measured contact patch
 * (the cell sizes and extent of its grids, its approach and vertical balance), as an MBS time
 * loop calls at nearby positions: the attempts that only measure the patch are skipped (on the
 * gauge corner at standard accuracy most of a call's work). When that patch does not fit the
 * new position (pressure at its edge, a new contact point, a jump) the call is solved cold,
 * exactly as without the option. A warm result differs from the cold one at the same position
 * by about the accuracy preset's discretization error (docs/library.md, "Warm start"), so
 * results depend on the calls before: leave it off where runs must be reproducible call by
 * call. The first calculate, and the first after any set-up call (every rw_set_* but
 * rw_set_state and rw_set_wear) or rw_set_warm_start itself, is cold. A wheelset's two wheels
 * each start warm from their own last calculate, with an axle force target too (since
 * 2026-11-29: the first solve of each wheel warm, the pitch search's rounds from it). */
RW_API rw_status rw_set_warm_start(rw_problem* problem, int enable);

/* Solves the contact of the current set-up and state. RW_ERROR_NOT_CONVERGED and
 * RW_ERROR_NO_CONTACT leave the results readable; other errors clear them. */
RW_API rw_status rw_calculate(rw_problem* problem);

/* ---- Queries (after rw_calculate) --------------------------------------------------------- */

typedef struct rw_summary {
  size_t struct_size;
  int status;                 /* RW_OK, RW_ERROR_NOT_CONVERGED or RW_ERROR_NO_CONTACT (of the
                                 worse wheel) */
  int patches;                /* both wheels' for a wheelset */
  double approach_m[2];       /* per wheel: [0] the single or right wheel, [1] the left */
  double pitch_velocity_rad_s;/* of the rolling stage (the right wheel's; 0 without) */
  double l_over_v[2];         /* per wheel */
  double nadal_limit[2];      /* per wheel; NaN without friction or below atan(mu) */
  double wheelset_lateral_m;  /* wheelset: the right wheel origin's y in its rail frame */
  double right_rail_origin_Y_m, left_rail_origin_Y_m; /* wheelset: rail origins in the track */
  double time_s;              /* solve time of both wheels [s] */
} rw_summary;

RW_API rw_status rw_get_summary(rw_problem* problem, rw_summary* summary);
RW_API rw_status rw_get_patch_count(rw_problem* problem, int* count);

typedef struct rw_patch {
  size_t struct_size;
  int wheel; /* 0 the single or right wheel, 1 the left wheel (its own rail frame) */
  /* Location: the pressure centre on the rail profile, rail frame [m]; its x from the wheel
   * profile origin's cross-section; Y in the track frame (wheelset; else equal to y). */
  double contact_x_m, contact_y_m, contact_z_m, contact_track_Y_m;
  double contact_angle_rad; /* of the resultant on the rail against the vertical */
  double area_m2, p_max_Pa;
  double normal_force_N;
  /* Forces the wheel exerts on the rail, rail frame (x, y, z) [N]: the pressure's part plus the
   * creep forces' reaction. */
  double force_on_rail_N[3];
  /* Rolling contact (0 without RW_EFFECT_TANGENTIAL): creepages about the pressure centre,
   * creep forces on the wheel along x and s, the spin moment. */
  double creepage_xi, creepage_eta, creepage_spin_per_m;
  double creep_force_x_N, creep_force_s_N, spin_moment_Nm;
  double t_gamma_N; /* with RW_EFFECT_DAMAGE, else 0 */
  double wlrm_damage, fi_surf;
  int cells, cells_in_contact;
  /* Since 1.2: the pressure centre in the wheel's frame [m]. x along the wheel's own rolling
   * direction (its yaw undone) from the wheel profile origin's cross-section, > 0 ahead of the
   * axle; (y, z) the point turned about the axle into that cross-section, in the wheel profile
   * frame W (core/notation.md: y along the axle, z toward the rail, the wheel radius there is
   * rolling_radius_m + z). A wheelset's left wheel in its own (mirrored) profile frame. The
   * wheel is the one of the solve's geometry, placed at first contact (before the approach):
   * (y, z) is the wheel profile's point at the rail-frame pressure centre, off the profile by
   * the initial gap there (at most the approach). A caller of 1.1 passes
   * struct_size = RW_PATCH_SIZE_1_1 and gets the fields above. */
  double contact_wheel_x_m, contact_wheel_y_m, contact_wheel_z_m;
} rw_patch;

/* rw_patch's size in API 1.0 and 1.1 (before the wheel-frame location), still accepted. */
#define RW_PATCH_SIZE_1_1 offsetof(rw_patch, contact_wheel_x_m)

RW_API rw_status rw_get_patch(rw_problem* problem, int index, rw_patch* patch);

/* Since 1.3. The model a patch was solved with and why, as `railwear contact` prints them:
 * *model "hertz", "halfspace", "conformal+golubenko", ...; *reason the model selection's reason
 * (RW_MODEL_AUTO; RW_MODEL_HERTZ with rolling contact: "fast tread path: ..." when the fast
 * tread path solved the patch, "fast tread path not valid: <why>; full path: ..." when it did not
 * apply and RW_MODEL_AUTO solved it), "" otherwise. The texts belong to the handle and stay valid
 * until the next call that clears the results. Either pointer may be NULL. */
RW_API rw_status rw_get_patch_model(rw_problem* problem, int index, const char** model,
                                    const char** reason);

/* Number of grid cells of a patch (0 for a Hertz patch of normal contact, which has no grid; the
 * fast tread path's patch has the grid its tangential solution ran on). */
RW_API rw_status rw_get_cell_count(rw_problem* problem, int index, size_t* count);
/* Per cell k = j * nx + i (i along x, j along s): centre x and s [m], pressure [Pa], tractions
 * on the wheel along x and s [Pa], slip velocities along x and s [m/s] (0 without rolling). Any
 * buffer may be NULL (not wanted); every non-NULL one must hold `capacity` >= the cell count. */
RW_API rw_status rw_get_cells(rw_problem* problem, int index, size_t capacity, double* x_m,
                              double* s_m, double* pressure_Pa, double* traction_x_Pa,
                              double* traction_s_Pa, double* slip_x_m_s, double* slip_s_m_s);

/* ---- Wear for co-simulation -------------------------------------------------------------- */

/* The wear law of rw_accumulate (wear/wear_law.h): Archard with a constant coefficient, the KTH
 * map (Jendel 2002) with its published coefficients, its continuous variant, or the USFD law. */
typedef int rw_wear_law;
enum { RW_WEAR_ARCHARD = 0, RW_WEAR_KTH = 1, RW_WEAR_KTH_CONTINUOUS = 2, RW_WEAR_USFD = 3 };

typedef struct rw_wear {
  size_t struct_size;
  rw_wear_law law;  /* default RW_WEAR_ARCHARD */
  double archard_k; /* Archard's coefficient [-] > 0; default 1e-4 */
  double bin_m;     /* width of the depth field's bins of rail arc length [m] > 0; default 1e-4 */
} rw_wear;

RW_API rw_status rw_init_wear(rw_wear* wear);
/* Sets the law and the bins; clears the accumulated depth. Archard and KTH need the rail's
 * hardness_Pa (rw_set_materials). */
RW_API rw_status rw_set_wear(rw_problem* problem, const rw_wear* wear);
/* Adds the last rw_calculate's wear, `passes` times its per-pass depth, to the handle's rail
 * depth field: the depth one wheel pass removes, per bin of rail-profile arc length, computed as
 * `railwear wear` computes it (wear/pass_depth.h), summed over the patches. `passes` >= 0 weights
 * the step: for a time step dt at speed V on a rail section of length L, passes = V dt / L.
 * Needs RW_EFFECT_TANGENTIAL and a converged calculate; rail 0 is the single or right rail, 1 the
 * left rail (its own frame). A new rail profile, cant or rw_set_wear clears the field. */
RW_API rw_status rw_accumulate(rw_problem* problem, double passes);
/* The depth field of rail 0 (single or right) or 1 (left): bin count, then the bins' centres
 * (arc length from the rail profile's first point [m]) and depths [m]; either buffer may be
 * NULL. */
RW_API rw_status rw_get_depth_count(rw_problem* problem, int rail, size_t* count);
RW_API rw_status rw_get_depth(rw_problem* problem, int rail, size_t capacity, double* s_m,
                              double* depth_m);
/* Sets the depth field to zero. */
RW_API rw_status rw_reset_depth(rw_problem* problem);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* RAILWEAR_RAILWEAR_H */
