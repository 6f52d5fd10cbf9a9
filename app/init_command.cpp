// `railwear init`: the scene template, to a new file or stdout.
#include "app/init_command.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/scene_template.h"
#include "core/numerics/input_error.h"

namespace railwear::app {

void SetupInit(CLI::App& app) {
  auto options = std::make_shared<InitOptions>();
  CLI::App* sub = app.add_subcommand("init", "Write a commented scene template");
  sub->add_option("file", options->path, "Scene file to create (stdout when omitted)");
  sub->callback([options]() { RunInit(*options); });
}

void RunInit(const InitOptions& o) {
  if (!o.path) {
    std::cout << SceneTemplate();
    return;
  }
  if (std::filesystem::exists(*o.path)) {
    throw InputError(
        fmt::format("{}: file exists; railwear init never overwrites a file "
                    "(remove it or choose another name)",
                    *o.path));
  }
  std::ofstream out(*o.path);
  out << SceneTemplate();
  if (!out) throw InputError(fmt::format("{}: cannot write the scene template", *o.path));
  std::cerr << fmt::format("railwear: wrote scene template {}\n", *o.path);
}

}  // namespace railwear::app
