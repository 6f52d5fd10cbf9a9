// Built-in profiles: S1002 wheel (EN 13715, exact piecewise definition), UIC60 (60E1) rail head
// (arc construction), and circular test profiles; profile specs; rail cant.
// Definitions and check values: ../shared/reference/README.md §5.
// All built-ins order their points with y increasing (as the file readers do).
#pragma once

#include <string>

#include "core/profile/profile.h"

namespace railwear {

enum class BodyRole { kWheel, kRail };

// S1002 wheel in the profile frame: y = S (toward the field side), z = F(S) (radius increase,
// toward the rail), S from -70 (flange back) to +60 mm. `step_m` is the point spacing in S.
Profile MakeS1002(double step_m = 0.1e-3);
// F(S) of the S1002 definition, millimetres in and out (for tests and the generator).
double S1002RadiusIncrease_mm(double S_mm);

// UIC60 rail head, uncanted, symmetric about y = 0, crown at the origin, z downward; R300, R80,
// R13 arcs then the 1:20 flank down to the bottom of the head. `step_m` is the arc spacing.
Profile MakeUic60(double step_m = 0.1e-3);

// Circular profiles of radius R for tests. Role decides which way they face:
//   circle, wheel: convex wheel (bottom point at the origin, z = -(R - sqrt(R^2 - y^2)))
//   circle, rail:  convex rail crown (top at the origin, z = R - sqrt(R^2 - y^2))
//   groove, rail:  concave rail groove (bottom at the origin, z = -(R - sqrt(R^2 - y^2)))
//   groove, wheel: concave wheel groove (z = R - sqrt(R^2 - y^2))
Profile MakeCircle(double radius_m, BodyRole role);
Profile MakeGroove(double radius_m, BodyRole role);

// Rail cant: rotates the rail profile so that its head leans toward the gauge side (-y) by
// atan(ratio) (1:40 -> ratio = 0.025), then moves the origin to the new highest point (minimum z
// of the spline). UIC60 canted 1:40: its old crown lands at y = -7.4977 mm.
Profile ApplyCant(const Profile& rail, double ratio);
// The rigid motion ApplyCant performs: ApplyCant(rail, ratio) == rail.Transformed(angle_rad,
// shift_m). A wear run computes it once on the unworn rail and applies the same motion to every
// worn profile, so the track frame does not follow the rail's changing highest point.
struct CantTransform {
  double angle_rad = 0.0;
  Eigen::Vector2d shift_m = Eigen::Vector2d::Zero();
};
CantTransform CalcCantTransform(const Profile& rail, double ratio);
// Parses "1:40" -> 0.025, "0" -> 0. Throws InputError otherwise.
double ParseCant(const std::string& text);

// A profile spec from a scene: "builtin:S1002", "builtin:UIC60", "circle:R", "groove:R" (R in
// mm), or a file path (relative paths are taken relative to base_dir). Throws InputError.
// source() of the result is the spec for built-ins/circles/grooves, the resolved path for files.
// Circles and grooves: half-angle 80 degrees for R <= 50 mm, else half-width 50 mm; arc only.
Profile LoadProfileSpec(const std::string& spec, BodyRole role, const std::string& base_dir);

}  // namespace railwear
