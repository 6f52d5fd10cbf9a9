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

// A fit of a measured scan: the points as read, the glitches dropped before the fit and the fit
// of the rest (whose point indices run over the kept points).
struct ScanFit {
  ProfilePoints scan;
  CleanedScan cleaned;
  ProfileFit fit;
  int RawIndex(int fitted) const { return cleaned.kept[fitted]; }
};

// "point 151 (line 153)": the 1-based point number in the file and its line.
std::string PointName(const ScanFit& f, int raw) {
  return fmt::format("point {} (line {})", raw + 1, f.scan.lines[raw]);
}

// Up to ten items, then how many more.
std::string ListOf(const std::vector<std::string>& items) {
  std::string list;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (k == 10) {
      list += fmt::format(", ... ({} more)", items.size() - 10);
      break;
    }
    list += (k == 0 ? "" : ", ") + items[k];
  }
  return list;
}

// The fit report: figures in mm, point numbers 1-based as in the readers' messages.
std::string FitText(const std::string& path, const ScanFit& f) {
  const ProfileFit& fit = f.fit;
  const std::vector<Eigen::Vector2d>& raw = f.scan.points_m;
  const SmoothingSplineSummary& s = fit.summary;
  std::string out;
  out += fmt::format("file            {}\n", path);
  const std::string dropped =
      f.cleaned.dropped.empty()
          ? std::string()
          : fmt::format("{} dropped as scan glitches, ", f.cleaned.dropped.size());
  out += fmt::format(
      "points          {} ({}{} rejected as gross outliers, {} down-weighted by the "
      "{} loss)\n",
      raw.size(), dropped, fit.num_rejected, fit.num_downweighted, ToString(s.loss));
  for (const CleanedScan::Dropped& d : f.cleaned.dropped) {
    out +=
        fmt::format("dropped         {} (y = {:.3f}, z = {:.3f} mm): {}\n", PointName(f, d.index),
                    raw[d.index].x() * kToMm, raw[d.index].y() * kToMm, d.reason);
  }
  if (!fit.rejected_points.empty()) {
    std::vector<std::string> points, lines;
    for (const int i : fit.rejected_points) {
      points.push_back(std::to_string(f.RawIndex(i) + 1));
      lines.push_back(std::to_string(f.scan.lines[f.RawIndex(i)]));
    }
    out += fmt::format("rejected        points {} (lines {})\n", ListOf(points), ListOf(lines));
  }
  out += fmt::format("smoothing       length {:.4f} mm, lambda {:.4g} m^4 ({})\n",
                     fit.smoothing_length_m * kToMm, fit.lambda_m4,
                     s.lambda_from_gcv ? "GCV" : "given");
  out += fmt::format(
      "RMS residual    {:.5f} mm normal distance ({:.5f} mm without rejected "
      "points)\n",
      fit.rms_distance_m * kToMm, fit.rms_inlier_distance_m * kToMm);
  const int worst = f.RawIndex(fit.max_distance_index);
  out += fmt::format("max residual    {:.5f} mm at {} (y = {:.3f}, z = {:.3f} mm)\n",
                     fit.max_distance_m * kToMm, PointName(f, worst), raw[worst].x() * kToMm,
                     raw[worst].y() * kToMm);
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

// The same as one JSON object; every point named by its 1-based number and file line.
nlohmann::json FitJson(const std::string& path, const ScanFit& f) {
  const ProfileFit& fit = f.fit;
  const std::vector<Eigen::Vector2d>& raw = f.scan.points_m;
  const auto point = [&](int i) {
    return nlohmann::json{{"point", i + 1},
                          {"line", f.scan.lines[i]},
                          {"y_mm", raw[i].x() * kToMm},
                          {"z_mm", raw[i].y() * kToMm}};
  };
  nlohmann::json dropped = nlohmann::json::array(), rejected = nlohmann::json::array();
  for (const CleanedScan::Dropped& d : f.cleaned.dropped) {
    nlohmann::json j = point(d.index);
    j["reason"] = d.reason;
    dropped.push_back(j);
  }
  for (const int i : fit.rejected_points) {
    nlohmann::json j = point(f.RawIndex(i));
    j["distance_mm"] = fit.distance_m[i] * kToMm;
    rejected.push_back(j);
  }
  nlohmann::json worst = point(f.RawIndex(fit.max_distance_index));
  worst["distance_mm"] = fit.max_distance_m * kToMm;
  return {{"file", path},
          {"format", ToString(f.scan.format)},
          {"notes", f.scan.notes},
          {"points", raw.size()},
          {"dropped", dropped},
          {"rejected", rejected},
          {"num_downweighted", fit.num_downweighted},
          {"loss", ToString(fit.summary.loss)},
          {"smoothing_length_mm", fit.smoothing_length_m * kToMm},
          {"lambda_m4", fit.lambda_m4},
          {"lambda_from_gcv", fit.summary.lambda_from_gcv},
          {"rms_distance_mm", fit.rms_distance_m * kToMm},
          {"rms_inlier_distance_mm", fit.rms_inlier_distance_m * kToMm},
          {"max_distance", worst},
          {"noise_estimate_mm", fit.noise_estimate_m * kToMm},
          {"fit_noise_mm", fit.fit_noise_m * kToMm},
          {"curvature_min_per_mm", fit.curvature_min_per_m / kToMm},
          {"curvature_max_per_mm", fit.curvature_max_per_m / kToMm},
          {"status", ToString(fit.summary.status)}};
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
  fit_cmd->add_flag("--json", fit->json,
                    "One JSON object on stdout (dropped and rejected points with their lines)");
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
  ScanFit f;
  f.scan = ReadProfilePoints(o.path);
  f.cleaned = CleanScan(f.scan.points_m, f.scan.lines, o.path);
  f.fit = FitProfile(f.cleaned.profile, options);
  const ProfileFit& fit = f.fit;
  if (fit.summary.status == SmoothingSplineStatus::kFailure) {
    throw std::runtime_error(
        fmt::format("profile fit of {} failed: {}", o.path, fit.summary.message));
  }
  if (o.json) {
    std::cout << FitJson(o.path, f).dump(2) << "\n";
  } else {
    std::cout << FitText(o.path, f);
  }
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
