// `railwear profile show|convert|fit`: what a profile file holds, conversion between formats,
// and a smoothing-spline fit of measured points (wear/profile_fit.h).
#include "app/profile_command.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "core/profile/profile_io.h"
#include "wear/profile_fit.h"

namespace railwear::app {
namespace {

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

// The fit report: figures in mm, point numbers 1-based as in the readers' messages.
std::string FitText(const std::string& path, const ProfileFile& file, const ProfileFit& fit) {
  const Profile& raw = file.profile;
  const SmoothingSplineSummary& s = fit.summary;
  std::string out;
  out += fmt::format("file            {}\n", path);
  out += fmt::format(
      "points          {} ({} rejected as gross outliers, {} down-weighted by the "
      "{} loss)\n",
      raw.size(), fit.num_rejected, fit.num_downweighted, ToString(s.loss));
  if (!fit.rejected_points.empty()) {
    std::string list;
    for (std::size_t k = 0; k < fit.rejected_points.size(); ++k) {
      if (k == 10) {
        list += fmt::format(" ... ({} more)", fit.rejected_points.size() - 10);
        break;
      }
      list += fmt::format("{}{}", k == 0 ? "" : " ", fit.rejected_points[k] + 1);
    }
    out += fmt::format("rejected        points {}\n", list);
  }
  out += fmt::format("smoothing       length {:.4f} mm, lambda {:.4g} m^4 ({})\n",
                     fit.smoothing_length_m * kToMm, fit.lambda_m4,
                     s.lambda_from_gcv ? "GCV" : "given");
  out += fmt::format(
      "RMS residual    {:.5f} mm normal distance ({:.5f} mm without rejected "
      "points)\n",
      fit.rms_distance_m * kToMm, fit.rms_inlier_distance_m * kToMm);
  const Eigen::Vector2d& worst = raw.points()[fit.max_distance_index];
  out += fmt::format("max residual    {:.5f} mm at point {} (y = {:.3f}, z = {:.3f} mm)\n",
                     fit.max_distance_m * kToMm, fit.max_distance_index + 1, worst.x() * kToMm,
                     worst.y() * kToMm);
  out += fmt::format(
      "noise           {:.5f} mm estimated from the points, {:.5f} mm implied by "
      "the fit\n",
      fit.noise_estimate_m * kToMm, fit.fit_noise_m * kToMm);
  out += fmt::format(
      "curvature       {:.4f} 1/mm at (y, z) = ({:.3f}, {:.3f}) mm .. {:.4f} 1/mm "
      "at ({:.3f}, {:.3f}) mm\n",
      fit.curvature_min_per_m / kToMm, fit.curvature_min_at_m.x() * kToMm,
      fit.curvature_min_at_m.y() * kToMm, fit.curvature_max_per_m / kToMm,
      fit.curvature_max_at_m.x() * kToMm, fit.curvature_max_at_m.y() * kToMm);
  out += fmt::format(
      "fit             {}, {} B-spline coefficients (knots every {:.3f} mm), "
      "{:.1f} degrees of freedom, {:.1f} ms\n",
      ToString(s.status), s.num_coefficients, s.knot_spacing * kToMm, s.effective_dof,
      s.time_s * 1e3);
  return out;
}

}  // namespace

std::optional<double> ParseSmoothingLength(const std::string& text) {
  std::string lower;
  for (char c : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "auto") return std::nullopt;
  std::size_t used = 0;
  double mm = 0.0;
  try {
    mm = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(mm) || !(mm > 0.0)) {
    throw InputError(
        fmt::format("--smoothing '{}': expected AUTO or a smoothing length in mm "
                    "greater than 0 (e.g. 0.5)",
                    text));
  }
  return mm / kToMm;
}

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

  auto fit = std::make_shared<ProfileFitCommandOptions>();
  CLI::App* fit_cmd = profile->add_subcommand(
      "fit", "Fit a smoothing spline to a (measured) profile: residuals, outliers, curvature");
  fit_cmd->add_option("file", fit->path, "Profile file (.csv, .ban, .whl, .prr, .prw)")->required();
  fit_cmd
      ->add_option("--smoothing", fit->smoothing,
                   "AUTO (generalised cross-validation) or a smoothing length in mm: "
                   "wavelengths below 2 pi times it are damped (lambda = length^4)")
      ->default_val("auto");
  fit_cmd->add_option("--out", fit->output,
                      "Write the fitted profile, resampled every 0.1 mm (.csv or .ban)");
  fit_cmd->callback([fit]() { RunProfileFit(*fit); });
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

void RunProfileFit(const ProfileFitCommandOptions& o) {
  ProfileFitOptions options;
  if (const std::optional<double> length = ParseSmoothingLength(o.smoothing)) {
    options.spline.lambda = std::pow(*length, 4);
  }
  if (!o.output.empty()) {
    std::string extension = std::filesystem::path(o.output).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".csv" && extension != ".ban") {
      throw InputError(
          fmt::format("--out '{}': expected a file name ending in .csv or .ban", o.output));
    }
  }
  const ProfileFile file = ReadProfileFile(o.path);
  const ProfileFit fit = FitProfile(file.profile, options);
  if (fit.summary.status == SmoothingSplineStatus::kFailure) {
    throw std::runtime_error(
        fmt::format("profile fit of {} failed: {}", o.path, fit.summary.message));
  }
  std::cout << FitText(o.path, file, fit);
  if (fit.summary.status == SmoothingSplineStatus::kNoConvergence) {
    std::cerr << fmt::format(
        "railwear: warning: the fit did not converge ({}); figures are for "
        "the last iterate\n",
        fit.summary.message);
  }
  if (!o.output.empty()) {
    WriteProfileFile(fit.profile, o.output);
    std::cerr << fmt::format("railwear: wrote {} ({} points every {:.3f} mm) fitted to {}\n",
                             o.output, fit.profile.size(),
                             fit.profile.Length() / (fit.profile.size() - 1) * kToMm, o.path);
  }
}

}  // namespace railwear::app
