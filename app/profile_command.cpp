// `railwear profile show|convert`: what a profile file holds, and conversion between formats.
#include "app/profile_command.h"

#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/profile/profile_io.h"

namespace railwear::app {
namespace {

constexpr double kToMm = 1e3;

nlohmann::json ProfileJson(const std::string& path, const ProfileFile& file) {
  const Profile::Bounds b = file.profile.bounds();
  return {{"file", path},
          {"source", file.profile.source()},
          {"format", ToString(file.format)},
          {"notes", file.notes},
          {"points", file.profile.size()},
          {"y_range_mm", {b.y_min * kToMm, b.y_max * kToMm}},
          {"z_range_mm", {b.z_min * kToMm, b.z_max * kToMm}},
          {"arc_length_mm", file.profile.Length() * kToMm}};
}

std::string ProfileText(const std::string& path, const ProfileFile& file) {
  const Profile::Bounds b = file.profile.bounds();
  std::string out;
  out += fmt::format("file        {}\n", path);
  out += fmt::format("source      {}\n", file.profile.source());
  out += fmt::format("format      {}\n", ToString(file.format));
  out += fmt::format("points      {}\n", file.profile.size());
  out += fmt::format("y range     {:.3f} .. {:.3f} mm\n", b.y_min * kToMm, b.y_max * kToMm);
  out += fmt::format("z range     {:.3f} .. {:.3f} mm\n", b.z_min * kToMm, b.z_max * kToMm);
  out += fmt::format("arc length  {:.3f} mm\n", file.profile.Length() * kToMm);
  for (const auto& note : file.notes) out += fmt::format("note        {}\n", note);
  return out;
}

}  // namespace

void SetupProfile(CLI::App& app) {
  CLI::App* profile = app.add_subcommand("profile", "Inspect and convert profile files");
  profile->require_subcommand(1);

  auto show = std::make_shared<ProfileShowOptions>();
  CLI::App* show_cmd = profile->add_subcommand("show", "What was read from a profile file");
  show_cmd->add_option("file", show->path, "Profile file (.csv, .ban, .whl, .prr, .prw)")
      ->required();
  show_cmd->add_flag("--json", show->json, "One JSON object on stdout");
  show_cmd->callback([show]() { RunProfileShow(*show); });

  auto convert = std::make_shared<ProfileConvertOptions>();
  CLI::App* convert_cmd = profile->add_subcommand("convert", "Convert a profile file");
  convert_cmd->add_option("in", convert->input, "Profile file to read")->required();
  convert_cmd->add_option("out", convert->output, "File to write (.csv or .ban)")->required();
  convert_cmd->callback([convert]() { RunProfileConvert(*convert); });
}

void RunProfileShow(const ProfileShowOptions& o) {
  const ProfileFile file = ReadProfileFile(o.path);
  if (o.json) {
    std::cout << ProfileJson(o.path, file).dump(2) << "\n";
  } else {
    std::cout << ProfileText(o.path, file);
  }
}

void RunProfileConvert(const ProfileConvertOptions& o) {
  const ProfileFile file = ReadProfileFile(o.input);
  WriteProfileFile(file.profile, o.output);
  std::cerr << fmt::format("railwear: wrote {} ({} points, read as {}) from {}\n", o.output,
                           file.profile.size(), ToString(file.format), o.input);
}

}  // namespace railwear::app
