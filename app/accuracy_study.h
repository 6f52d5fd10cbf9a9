// The measurement of `railwear accuracy` on a contact scene: the scene's contact problem solved
// with each model at each accuracy level; per run the median time per solve, the peak memory the
// solve adds, and the errors of contact area, peak pressure, total force and (when rolling) creep
// force against a reference: the finest solution of the reference model, Richardson-extrapolated
// where the levels allow, or a JSON file as `railwear contact --json` writes it (its keys are
// those of contact_output.h). Nothing here prints.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/accuracy_config.h"
#include "app/scene.h"
#include "core/contact/contact_solver.h"

namespace railwear::app {

// The quantities compared, totals over all patches. Creep forces only with rolling contact.
struct AccuracyQuantities {
  double area_m2 = 0.0;
  double p_max_Pa = 0.0;
  double vertical_force_N = 0.0;
  double lateral_force_N = 0.0;
  std::optional<double> creep_x_N;  // sum of the patches' longitudinal creep forces
  std::optional<double> creep_y_N;  // sum of their lateral creep forces (rail frame y)
};

// One model at one level.
struct AccuracyRow {
  std::string model;                 // as in kAccuracyModels
  std::string level;                 // preset name, "analytic" for Hertz
  std::string tangential;            // rolling: the tangential method asked for; else ""
  std::string tangential_choices;    // rolling: the solver each patch ran, ";"-joined
  double cells_per_semi_axis = 0.0;  // 0 for Hertz
  SolverStatus status = SolverStatus::kNotConverged;
  std::string message;
  int repeats = 0;
  double time_median_s = 0.0, time_min_s = 0.0, time_max_s = 0.0;
  // Peak resident memory the solve added [bytes], median over the repeats; NaN where the
  // platform cannot tell (it needs Linux's /proc/self/clear_refs).
  double memory_bytes = 0.0;
  int cells = 0, cells_in_contact = 0, patches = 0, iterations = 0;
  AccuracyQuantities q;
  std::string patch_models;  // the patches' models, ";"-joined (tells what auto chose)
  // Relative errors against the reference; NaN where the reference lacks the quantity.
  double err_area = 0.0, err_p_max = 0.0, err_force = 0.0, err_creep = 0.0;
  // With more than one tangential method: |F - F_exact| / |F_exact| of the creep force (x, y)
  // against the exact solver's on the same model and level; NaN otherwise.
  double err_creep_vs_exact = 0.0;
};

struct AccuracyReference {
  std::string source;  // "conformal+boussinesq, Richardson ..." or the file's path
  AccuracyQuantities q;
  bool has_area = false, has_p_max = false, has_force = false, has_creep = false;
  // For each quantity, how it was obtained ("extrapolated, order 1.93", "fine level", "file").
  std::vector<std::pair<std::string, std::string>> how;
};

struct AccuracyStudy {
  std::string scene_name, scene_path;
  bool rolling = false;
  bool compare_tangential = false;  // rolling, and more than one tangential method asked for
  // per model in the order asked, levels coarse to fine, tangential methods in the order asked
  std::vector<AccuracyRow> rows;
  AccuracyReference reference;
  std::vector<std::string> notes;  // e.g. models left out and why
};

// Runs the study. `progress` (may be empty) receives one line per run. Throws InputError for
// an unknown model or level, repeats < 1, a wheelset scene, or a bad reference file.
AccuracyStudy RunAccuracyStudy(const Scene& scene, const AccuracyOptions& options,
                               const std::function<void(const std::string&)>& progress = {});

// Richardson extrapolation of f(h) = f0 + C h^p from three values at h1 > h2 > h3 > 0: the
// order p in [1, 6] and f0 when the differences shrink monotonically (same sign, |f2 - f3| <
// |f1 - f2|) and such an order exists; nullopt otherwise.
struct Richardson {
  double value = 0.0;
  double order = 0.0;
};
std::optional<Richardson> ExtrapolateRichardson(double h1, double f1, double h2, double f2,
                                                double h3, double f3);

}  // namespace railwear::app
