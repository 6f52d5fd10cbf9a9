// The Python module `railwear` (issue 20 point 2): the C API of include/railwear/railwear.h with
// the same names (rw_set_state -> Problem.set_state), NumPy arrays in and out, and every error
// status raised as railwear.Error (status and the handle's message). The module only translates:
// every number comes from librailwear, so Python and C give the same results.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "railwear/railwear.h"

namespace py = pybind11;

namespace {

// railwear.Error (a RuntimeError) with `status` (the rw_status) and `status_name`. The type lives
// as long as the interpreter (a plain pointer: no destructor runs after Python's finalization).
PyObject* error_type = nullptr;

py::object ErrorType() { return py::reinterpret_borrow<py::object>(error_type); }

// Raises railwear.Error for a status other than RW_OK, with the handle's message (calls without
// a handle, rw_create and rw_init_*, have the status only).
void Check(const rw_problem* p, rw_status s) {
  if (s == RW_OK) return;
  std::string message = rw_status_name(s);
  if (p != nullptr) message += std::string(": ") + rw_last_error(p);
  py::object error = ErrorType()(message);
  error.attr("status") = s;
  error.attr("status_name") = rw_status_name(s);
  PyErr_SetObject(ErrorType().ptr(), error.ptr());
  throw py::error_already_set();
}

// Keyword arguments onto a C struct's fields, by the fields' C names; an unknown name is a
// TypeError naming it and the known ones.
template <class S>
struct Fields {
  std::vector<std::pair<const char*, double S::*>> doubles;
  std::vector<std::pair<const char*, int S::*>> ints;
  std::vector<std::pair<const char*, uint32_t S::*>> flags;

  void Apply(const py::kwargs& kwargs, S* s, const char* what) const {
    for (const auto& [key, value] : kwargs) {
      const std::string name = py::str(key);
      bool found = false;
      for (const auto& [n, m] : doubles) {
        if (name == n) {
          s->*m = py::cast<double>(value);
          found = true;
        }
      }
      for (const auto& [n, m] : ints) {
        if (name == n) {
          s->*m = py::cast<int>(value);
          found = true;
        }
      }
      for (const auto& [n, m] : flags) {
        if (name == n) {
          s->*m = py::cast<uint32_t>(value);
          found = true;
        }
      }
      if (!found) {
        std::string known;
        for (const auto& f : doubles) known += std::string(known.empty() ? "" : ", ") + f.first;
        for (const auto& f : ints) known += std::string(known.empty() ? "" : ", ") + f.first;
        for (const auto& f : flags) known += std::string(known.empty() ? "" : ", ") + f.first;
        throw py::type_error(std::string(what) + ": unknown field '" + name + "' (known: " + known +
                             ")");
      }
    }
  }
  py::dict ToDict(const S& s) const {
    py::dict d;
    for (const auto& [n, m] : doubles) d[n] = s.*m;
    for (const auto& [n, m] : ints) d[n] = s.*m;
    for (const auto& [n, m] : flags) d[n] = s.*m;
    return d;
  }
};

template <class S>
S Init(rw_status (*init)(S*)) {
  S s{};
  s.struct_size = sizeof s;
  Check(nullptr, init(&s));
  return s;
}

const Fields<rw_material> kMaterial{{{"youngs_modulus_Pa", &rw_material::youngs_modulus_Pa},
                                     {"poisson_ratio", &rw_material::poisson_ratio},
                                     {"hardness_Pa", &rw_material::hardness_Pa},
                                     {"shear_yield_Pa", &rw_material::shear_yield_Pa}},
                                    {},
                                    {}};
const Fields<rw_model> kModel{{{"cell_dx_m", &rw_model::cell_dx_m},
                               {"cell_ds_m", &rw_model::cell_ds_m},
                               {"normal_tolerance", &rw_model::normal_tolerance},
                               {"tangential_tolerance", &rw_model::tangential_tolerance}},
                              {{"kind", &rw_model::kind},
                               {"geometry", &rw_model::geometry},
                               {"kernel", &rw_model::kernel},
                               {"accuracy", &rw_model::accuracy},
                               {"tangential", &rw_model::tangential},
                               {"normal_criterion", &rw_model::normal_criterion}},
                              {{"effects", &rw_model::effects}}};
const Fields<rw_influence_constants> kConstants{
    {{"c_f", &rw_influence_constants::c_f},
     {"c_z", &rw_influence_constants::c_z},
     {"c_s", &rw_influence_constants::c_s},
     {"convex_c_f", &rw_influence_constants::convex_c_f},
     {"convex_c_z", &rw_influence_constants::convex_c_z},
     {"convex_c_s", &rw_influence_constants::convex_c_s},
     {"concave_c_f", &rw_influence_constants::concave_c_f},
     {"concave_c_z", &rw_influence_constants::concave_c_z},
     {"concave_c_s", &rw_influence_constants::concave_c_s}},
    {{"separate", &rw_influence_constants::separate}},
    {}};
const Fields<rw_geometry> kGeometry{
    {{"rolling_radius_m", &rw_geometry::rolling_radius_m},
     {"rail_cant", &rw_geometry::rail_cant},
     {"gauge_m", &rw_geometry::gauge_m},
     {"gauge_height_m", &rw_geometry::gauge_height_m},
     {"flange_back_distance_m", &rw_geometry::flange_back_distance_m},
     {"flange_back_position_m", &rw_geometry::flange_back_position_m}},
    {},
    {}};
const Fields<rw_state> kState{{{"lateral_m", &rw_state::lateral_m},
                               {"yaw_rad", &rw_state::yaw_rad},
                               {"roll_rad", &rw_state::roll_rad},
                               {"vertical_force_N", &rw_state::vertical_force_N},
                               {"approach_m", &rw_state::approach_m},
                               {"left_vertical_force_N", &rw_state::left_vertical_force_N},
                               {"speed_m_s", &rw_state::speed_m_s},
                               {"pitch_velocity_rad_s", &rw_state::pitch_velocity_rad_s},
                               {"lateral_velocity_m_s", &rw_state::lateral_velocity_m_s},
                               {"yaw_velocity_rad_s", &rw_state::yaw_velocity_rad_s},
                               {"longitudinal_force_N", &rw_state::longitudinal_force_N},
                               {"curvature_per_m", &rw_state::curvature_per_m},
                               {"creepage_xi", &rw_state::creepage_xi},
                               {"creepage_eta", &rw_state::creepage_eta},
                               {"creepage_spin_per_m", &rw_state::creepage_spin_per_m}},
                              {},
                              {{"flags", &rw_state::flags}}};
const Fields<rw_wear> kWear{
    {{"archard_k", &rw_wear::archard_k}, {"bin_m", &rw_wear::bin_m}}, {{"law", &rw_wear::law}}, {}};
const Fields<rw_summary> kSummary{
    {{"pitch_velocity_rad_s", &rw_summary::pitch_velocity_rad_s},
     {"wheelset_lateral_m", &rw_summary::wheelset_lateral_m},
     {"right_rail_origin_Y_m", &rw_summary::right_rail_origin_Y_m},
     {"left_rail_origin_Y_m", &rw_summary::left_rail_origin_Y_m},
     {"time_s", &rw_summary::time_s}},
    {{"status", &rw_summary::status}, {"patches", &rw_summary::patches}},
    {}};
const Fields<rw_patch> kPatch{{{"contact_x_m", &rw_patch::contact_x_m},
                               {"contact_y_m", &rw_patch::contact_y_m},
                               {"contact_z_m", &rw_patch::contact_z_m},
                               {"contact_track_Y_m", &rw_patch::contact_track_Y_m},
                               {"contact_angle_rad", &rw_patch::contact_angle_rad},
                               {"area_m2", &rw_patch::area_m2},
                               {"p_max_Pa", &rw_patch::p_max_Pa},
                               {"normal_force_N", &rw_patch::normal_force_N},
                               {"creepage_xi", &rw_patch::creepage_xi},
                               {"creepage_eta", &rw_patch::creepage_eta},
                               {"creepage_spin_per_m", &rw_patch::creepage_spin_per_m},
                               {"creep_force_x_N", &rw_patch::creep_force_x_N},
                               {"creep_force_s_N", &rw_patch::creep_force_s_N},
                               {"spin_moment_Nm", &rw_patch::spin_moment_Nm},
                               {"t_gamma_N", &rw_patch::t_gamma_N},
                               {"wlrm_damage", &rw_patch::wlrm_damage},
                               {"fi_surf", &rw_patch::fi_surf},
                               {"contact_wheel_x_m", &rw_patch::contact_wheel_x_m},
                               {"contact_wheel_y_m", &rw_patch::contact_wheel_y_m},
                               {"contact_wheel_z_m", &rw_patch::contact_wheel_z_m}},
                              {{"wheel", &rw_patch::wheel},
                               {"cells", &rw_patch::cells},
                               {"cells_in_contact", &rw_patch::cells_in_contact}},
                              {}};

// One handle; freed with the object.
class Problem {
 public:
  explicit Problem(int kind) { Check(nullptr, rw_create(kind, &p_)); }
  ~Problem() { rw_destroy(p_); }
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  void set_profile_file(int body, const std::string& spec) {
    Check(p_, rw_set_profile_file(p_, body, spec.c_str()));
  }
  void set_profile_points(int body,
                          py::array_t<double, py::array::c_style | py::array::forcecast> yz) {
    if (yz.ndim() != 2 || yz.shape(1) != 2) {
      throw py::value_error("yz_m: expected an array of shape (n, 2) of (y, z) in metres");
    }
    Check(p_, rw_set_profile_points(p_, body, yz.data(), static_cast<size_t>(yz.shape(0))));
  }
  void set_materials(const py::dict& wheel, const py::dict& rail) {
    rw_material w = Init(&rw_init_material), r = Init(&rw_init_material);
    kMaterial.Apply(py::kwargs(wheel), &w, "wheel");
    kMaterial.Apply(py::kwargs(rail), &r, "rail");
    Check(p_, rw_set_materials(p_, &w, &r));
  }
  void set_model(const py::kwargs& kwargs) {
    rw_model m = Init(&rw_init_model);
    kModel.Apply(kwargs, &m, "set_model");
    Check(p_, rw_set_model(p_, &m));
  }
  void set_influence_constants(const py::kwargs& kwargs) {
    rw_influence_constants c = Init(&rw_init_influence_constants);
    kConstants.Apply(kwargs, &c, "set_influence_constants");
    Check(p_, rw_set_influence_constants(p_, &c));
  }
  void set_friction(double mu) { Check(p_, rw_set_friction(p_, mu)); }
  void set_warm_start(bool enable) { Check(p_, rw_set_warm_start(p_, enable ? 1 : 0)); }
  void set_pressure_limit(int kind, double value_Pa) {
    Check(p_, rw_set_pressure_limit(p_, kind, value_Pa));
  }
  void set_geometry(const py::kwargs& kwargs) {
    rw_geometry g = Init(&rw_init_geometry);
    kGeometry.Apply(kwargs, &g, "set_geometry");
    Check(p_, rw_set_geometry(p_, &g));
  }
  void set_state(const py::kwargs& kwargs) {
    rw_state s = Init(&rw_init_state);
    kState.Apply(kwargs, &s, "set_state");
    Check(p_, rw_set_state(p_, &s));
  }
  // RW_OK, or RW_ERROR_NOT_CONVERGED / RW_ERROR_NO_CONTACT (results readable); raises otherwise.
  int calculate() {
    rw_status s;
    {
      py::gil_scoped_release release;  // other Python threads run during the solve
      s = rw_calculate(p_);
    }
    if (s != RW_ERROR_NOT_CONVERGED && s != RW_ERROR_NO_CONTACT) Check(p_, s);
    return s;
  }
  py::dict get_summary() {
    rw_summary s{};
    s.struct_size = sizeof s;
    Check(p_, rw_get_summary(p_, &s));
    py::dict d = kSummary.ToDict(s);
    d["approach_m"] = py::make_tuple(s.approach_m[0], s.approach_m[1]);
    d["l_over_v"] = py::make_tuple(s.l_over_v[0], s.l_over_v[1]);
    d["nadal_limit"] = py::make_tuple(s.nadal_limit[0], s.nadal_limit[1]);
    return d;
  }
  int get_patch_count() {
    int n = 0;
    Check(p_, rw_get_patch_count(p_, &n));
    return n;
  }
  py::dict get_patch(int index) {
    rw_patch q{};
    q.struct_size = sizeof q;
    Check(p_, rw_get_patch(p_, index, &q));
    py::dict d = kPatch.ToDict(q);
    d["force_on_rail_N"] =
        py::make_tuple(q.force_on_rail_N[0], q.force_on_rail_N[1], q.force_on_rail_N[2]);
    return d;
  }
  // (model, reason) of a patch (rw_get_patch_model, since 1.3).
  py::tuple get_patch_model(int index) {
    const char* model = nullptr;
    const char* reason = nullptr;
    Check(p_, rw_get_patch_model(p_, index, &model, &reason));
    return py::make_tuple(std::string(model), std::string(reason));
  }
  // The size query and the buffers in one: a dict of NumPy arrays, one value per cell.
  py::dict get_cells(int index) {
    size_t n = 0;
    Check(p_, rw_get_cell_count(p_, index, &n));
    const char* names[7] = {"x_m",           "s_m",        "pressure_Pa", "traction_x_Pa",
                            "traction_s_Pa", "slip_x_m_s", "slip_s_m_s"};
    std::vector<py::array_t<double>> a;
    for (int i = 0; i < 7; ++i) a.emplace_back(static_cast<py::ssize_t>(n));
    Check(p_, rw_get_cells(p_, index, n, a[0].mutable_data(), a[1].mutable_data(),
                           a[2].mutable_data(), a[3].mutable_data(), a[4].mutable_data(),
                           a[5].mutable_data(), a[6].mutable_data()));
    py::dict d;
    for (int i = 0; i < 7; ++i) d[names[i]] = a[static_cast<size_t>(i)];
    return d;
  }
  void set_wear(const py::kwargs& kwargs) {
    rw_wear w = Init(&rw_init_wear);
    kWear.Apply(kwargs, &w, "set_wear");
    Check(p_, rw_set_wear(p_, &w));
  }
  void accumulate(double passes) { Check(p_, rw_accumulate(p_, passes)); }
  // (s_m, depth_m) of rail 0 (single or right) or 1 (left).
  py::tuple get_depth(int rail) {
    size_t n = 0;
    Check(p_, rw_get_depth_count(p_, rail, &n));
    py::array_t<double> s(static_cast<py::ssize_t>(n)), d(static_cast<py::ssize_t>(n));
    Check(p_, rw_get_depth(p_, rail, n, s.mutable_data(), d.mutable_data()));
    return py::make_tuple(s, d);
  }
  void reset_depth() { Check(p_, rw_reset_depth(p_)); }

 private:
  rw_problem* p_ = nullptr;
};

}  // namespace

PYBIND11_MODULE(railwear, m) {
  m.doc() =
      "railwear: conformal wheel-rail contact (the C API of librailwear, docs/library.md). "
      "SI units; the names are the C API's without the rw_ prefix.";
  error_type = PyErr_NewException("railwear.Error", PyExc_RuntimeError, nullptr);
  m.attr("Error") = ErrorType();
  m.attr("API_VERSION") = rw_api_version();
#define RW_CONSTANT(name) m.attr(#name) = static_cast<int>(RW_##name)
  RW_CONSTANT(OK);
  RW_CONSTANT(ERROR_NOT_CONVERGED);
  RW_CONSTANT(ERROR_NO_CONTACT);
  RW_CONSTANT(PROBLEM_WHEEL);
  RW_CONSTANT(PROBLEM_WHEELSET);
  RW_CONSTANT(BODY_WHEEL);
  RW_CONSTANT(BODY_RAIL);
  RW_CONSTANT(BODY_LEFT_RAIL);
  RW_CONSTANT(MODEL_HERTZ);
  RW_CONSTANT(MODEL_HALFSPACE);
  RW_CONSTANT(MODEL_CONFORMAL);
  RW_CONSTANT(MODEL_CUSTOM);
  RW_CONSTANT(MODEL_AUTO);
  RW_CONSTANT(GEOMETRY_PLANAR);
  RW_CONSTANT(GEOMETRY_CONFORMAL);
  RW_CONSTANT(KERNEL_BOUSSINESQ);
  RW_CONSTANT(KERNEL_GOLUBENKO);
  RW_CONSTANT(ACCURACY_DRAFT);
  RW_CONSTANT(ACCURACY_STANDARD);
  RW_CONSTANT(ACCURACY_REFERENCE);
  RW_CONSTANT(ACCURACY_FINE);
  RW_CONSTANT(TANGENTIAL_FASTSIM);
  RW_CONSTANT(TANGENTIAL_EXACT);
  RW_CONSTANT(TANGENTIAL_AUTO);
  RW_CONSTANT(EFFECT_TANGENTIAL);
  RW_CONSTANT(EFFECT_DAMAGE);
  RW_CONSTANT(EFFECT_COUPLING);
  RW_CONSTANT(STATE_CREEPAGE);
  RW_CONSTANT(WEAR_ARCHARD);
  RW_CONSTANT(WEAR_KTH);
  RW_CONSTANT(WEAR_KTH_CONTINUOUS);
  RW_CONSTANT(WEAR_USFD);
  RW_CONSTANT(PRESSURE_LIMIT_NONE);
  RW_CONSTANT(PRESSURE_LIMIT_HARDNESS);
  RW_CONSTANT(PRESSURE_LIMIT_VALUE);
  RW_CONSTANT(NORMAL_PRESSURE_UPDATE);
  RW_CONSTANT(NORMAL_GAP_RESIDUAL);
#undef RW_CONSTANT

  py::class_<Problem>(m, "Problem", "One contact problem (rw_problem): a wheel or a wheelset.")
      .def(py::init<int>(), py::arg("kind") = static_cast<int>(RW_PROBLEM_WHEEL))
      .def("set_profile_file", &Problem::set_profile_file, py::arg("body"), py::arg("spec"),
           "A profile file or built-in spec ('builtin:S1002', 'circle:10', ...).")
      .def("set_profile_points", &Problem::set_profile_points, py::arg("body"), py::arg("yz_m"),
           "A profile from an (n, 2) array of (y, z) points [m], y increasing.")
      .def("set_materials", &Problem::set_materials, py::arg("wheel"), py::arg("rail"),
           "Dicts of rw_material fields: youngs_modulus_Pa, poisson_ratio, hardness_Pa, "
           "shear_yield_Pa.")
      .def("set_model", &Problem::set_model,
           "rw_model fields: kind, geometry, kernel, accuracy, tangential, effects, cell_dx_m, "
           "cell_ds_m, normal_criterion (NORMAL_PRESSURE_UPDATE, the default, or "
           "NORMAL_GAP_RESIDUAL, the strict setting), normal_tolerance (0: the criterion's own), "
           "tangential_tolerance (the exact solver's stop relative to mu p_max; 0: 1e-6).")
      .def("set_influence_constants", &Problem::set_influence_constants,
           "rw_influence_constants fields: c_f, c_z, c_s, separate, convex_*, concave_*.")
      .def("set_friction", &Problem::set_friction, py::arg("friction"))
      .def("set_pressure_limit", &Problem::set_pressure_limit, py::arg("kind"),
           py::arg("value_Pa") = std::numeric_limits<double>::quiet_NaN(),
           "PRESSURE_LIMIT_NONE, _HARDNESS (the smaller hardness), or _VALUE with value_Pa.")
      .def("set_warm_start", &Problem::set_warm_start, py::arg("enable"),
           "rw_set_warm_start: start each calculate from the last one's measured patch.")
      .def("set_geometry", &Problem::set_geometry,
           "rw_geometry fields: rolling_radius_m, rail_cant, gauge_m, gauge_height_m, "
           "flange_back_distance_m, flange_back_position_m.")
      .def("set_state", &Problem::set_state,
           "rw_state fields (per step): lateral_m, yaw_rad, roll_rad, vertical_force_N or "
           "approach_m, speed_m_s, pitch_velocity_rad_s, ... (docs/library.md).")
      .def("calculate", &Problem::calculate,
           "Solves; returns OK, ERROR_NOT_CONVERGED or ERROR_NO_CONTACT, raises Error otherwise.")
      .def("get_summary", &Problem::get_summary)
      .def("get_patch_count", &Problem::get_patch_count)
      .def("get_patch", &Problem::get_patch, py::arg("index"))
      .def("get_patch_model", &Problem::get_patch_model, py::arg("index"),
           "(model, reason) of patch `index`: the model that solved it (\"hertz\", "
           "\"halfspace\", ...) and why (rw_get_patch_model)")
      .def("get_cells", &Problem::get_cells, py::arg("index"),
           "Per cell (NumPy arrays): x_m, s_m, pressure_Pa, traction_x_Pa, traction_s_Pa, "
           "slip_x_m_s, slip_s_m_s.")
      .def("set_wear", &Problem::set_wear, "rw_wear fields: law, archard_k, bin_m.")
      .def("accumulate", &Problem::accumulate, py::arg("passes"))
      .def("get_depth", &Problem::get_depth, py::arg("rail") = 0,
           "(s_m, depth_m) NumPy arrays of the rail's accumulated depth field.")
      .def("reset_depth", &Problem::reset_depth);
}
