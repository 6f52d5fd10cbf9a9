// `railwear contact SCENE.toml`: solve the normal contact of one wheel on one rail and report it.
#pragma once

#include <optional>
#include <string>

#include "core/contact/contact_case.h"

namespace CLI {
class App;
}

namespace railwear::app {

struct Scene;  // app/scene.h

struct ContactOptions {
  std::string scene_path;
  std::optional<std::string> model;     // --model hertz|halfspace|conformal: replaces [model] kind
  std::optional<std::string> accuracy;  // --accuracy draft|standard|reference|fine (drops cell_mm)
  // --kernel boussinesq|golubenko: replaces the influence kernel (after --model), keeping the
  // geometry; e.g. conformal geometry + boussinesq, the half-space kernel on the curved grid.
  std::optional<std::string> kernel;
  // --constants fem|paper: replaces the scene's influence constants by a named set.
  std::optional<std::string> constants;
  std::optional<std::string> json;  // --json FILE, "-" = stdout (then nothing else there)
  std::optional<std::string> csv;   // --csv FILE, "-" = stdout: pressure field per cell
  std::optional<std::string> plot;  // --plot PNG (needs gnuplot)
};

void SetupContact(CLI::App& app);

// A contact scene (not a wear scene) as the one contact case both front ends solve
// (core/contact/contact_case.h; the C API of include/railwear/railwear.h builds the same from its
// calls): the problem, the wheelset's track and placement, and the friction.
ContactCase ToContactCase(const Scene& scene);

// Throws InputError for bad input (exit 2) and std::runtime_error for failures (exit 1),
// including a solve that did not converge or found no contact (after writing the outputs).
void RunContact(const ContactOptions& options);

}  // namespace railwear::app
