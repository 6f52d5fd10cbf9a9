// Plots of `railwear contact --plot`, drawn by gnuplot (an external program): per wheel a
// cross-section (the rail and wheel profiles, the patches on the rail, the contact points and
// their angles) beside the pressure maps of its patches.
#pragma once

#include <string>
#include <vector>

#include "app/scene.h"
#include "core/contact/contact_solver.h"
#include "core/geometry/wheel_rail_geometry.h"

namespace railwear::app {

// Throws std::runtime_error naming 'gnuplot' when it is not on PATH (checked before solving).
void RequireGnuplot();

// One wheel of the plot: its name ("wheel", "right wheel", "left wheel"), its result, its pose
// and the profiles (rail frame R of its own rail: y toward the field side, z down).
struct PlotWheel {
  std::string name;
  const ContactResult* result = nullptr;
  WheelPose pose;
  const Profile* wheel_profile = nullptr;
  const Profile* rail_profile = nullptr;
};

// The gnuplot script of the plot, self-contained (inline data blocks, no data files): one row per
// wheel; in each row the cross-section, then one pressure map per patch (with rolling contact
// also the traction |q| and the slip velocity). Every panel has equal aspect (`set size ratio
// -1`) and ranges fitted to its data:
//   cross-section: data blocks $rail_K and $wheel_K (K = 1, 2, ... the wheel's row: the wheel
//     placed by WheelRailGeometry at first contact, the elastic approach not drawn), $patch_K
//     (the cross-section points of the cells in contact, on the rail) and $contact_K (per patch
//     the contact point y z and its contact angle in degrees), an arrow per patch along the
//     force on the rail (the contact angle against the vertical) and a label "N: ANGLE deg";
//     z axis reversed (down, as the rail frame).
//   pressure map: data block $map_K_P (P = the patch, 1-based): s [mm] (lateral arc) across,
//     x [mm] (rolling) up, p [MPa] (and |q|, |v_slip|) as colour.
std::string ContactPlotScript(const Scene& scene, const std::vector<PlotWheel>& wheels,
                              const std::string& png_path);

// Writes a PNG of ContactPlotScript. Terminal pngcairo when gnuplot has it, png otherwise.
// Throws std::runtime_error when gnuplot fails (with its messages).
void PlotContact(const Scene& scene, const std::vector<PlotWheel>& wheels,
                 const std::string& png_path);

}  // namespace railwear::app
