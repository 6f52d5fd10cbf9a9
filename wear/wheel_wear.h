// The wheel's wear (issue 16 point 6, co-evolution): the depth one pass of a traffic entry
// removes from its own wheel, from the same contact solution as the rail's.
//
// The rail (wear/pass_depth.h): a rail point passes under the patch once per wheel pass, taking
// dx / V in each cell, so a pass removes dz_j = sum_i (dz/dL)_i dx at patch column j.
//
// The wheel: a wheel material point passes through the patch once per wheel revolution. Column j
// touches the wheel on its circle of radius r_j (the wheel radius where column j meets the wheel
// profile); a point of that circle crosses a cell of length dx in dx / (Omega r_j), Omega the
// wheel's angular velocity. Per metre the wheel rolls it makes Omega / (2 pi V) revolutions. So
// per metre rolled a point of circle j loses
//     dz_j(wheel) * V / (Omega r_j) * Omega / (2 pi V) = dz_j(wheel) / (2 pi r_j)
// where dz_j(wheel) = sum_i (dz/dL)_i dx is the rail's column sum taken with the wheel's material
// (its hardness H_w for Archard and KTH). Over the distance L the wheel rolls per pass of its
// traffic entry (TrafficCase::wheel_wear):
//     depth per pass on circle j = dz_j(wheel) * L / (2 pi r_j)                       (*)
// Omega (the creepage) drops out. This is the usual treatment of wheel wear in wheel-profile
// prediction: the wear computed in the contact patch is spread over the wheel's circumference
// 2 pi r (Enblom & Berg, "Simulation of railway wheel profile development due to wear -
// influence of disc braking and contact environment", Wear 258 (2005) 1055-1063; Pombo et al.,
// "A study on wear evaluation of railway wheels based on multibody dynamics and wear
// computation", Multibody System Dynamics 24 (2010) 347-366; and, with the rail's wear averaged
// over the track length next to the wheel's over its circumference, Ignesti, Marini, Meli & Rindi,
// "Development of a model for the simultaneous analysis of wheel and rail wear in railway
// systems", Multibody System Dynamics 31 (2014) 191-240; review: Bosso, Magelli & Zampieri,
// "Simulation of wheel and rail profile wear: a review of numerical models", Railway Engineering
// Science 30(4) (2022)). Those are the sources of the approach; their equations were not checked
// line by line here. railwear writes it per column with the column's own radius r_j (the papers
// use the nominal radius), which makes the volumes exact:
//     wheel volume per pass = sum_j (*) ds 2 pi r_j = L sum_j dz_j(wheel) ds
//     rail volume over L    = L sum_j dz_j(rail) ds
// so their ratio is the law's: H_rail / H_wheel for Archard (V = k N s / H: both bodies slide
// the same distance under the same load), 1 for USFD at equal density, and the KTH map's k
// ratio cell by cell (its seizure boundary p = 0.8 H is each body's own).
//
// Mapping: the columns' edge points (on the reference surface, rail frame) are projected onto
// the wheel profile placed as the contact placed it (lateral shift, roll, at first contact:
// WheelRailGeometry; yaw, milliradians, is left out of this projection) and binned along the
// wheel profile's arc length like the rail's (area conserved per column). A point off the
// wheel's undeformed surface by the approach (tens of micrometres) along the normal projects to
// the same arc length to first order.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/contact/contact_problem.h"
#include "core/contact/contact_result.h"
#include "core/geometry/curve_locator.h"
#include "core/profile/profile.h"
#include "wear/pass_depth.h"
#include "wear/wear_law.h"

namespace railwear {

// A wheel profile placed in the rail frame of a contact (for mapping its patches' columns).
struct PlacedWheel {
  const Profile* wheel = nullptr;  // wheel profile frame (the radius at a point is r0 + z)
  double rolling_radius_m = 0.0;   // r0, at the wheel profile's z = 0
  // The same points in the rail frame (on the heap: `locator` points to it, the struct moves).
  std::unique_ptr<const Profile> in_rail;
  std::optional<CurveLocator> locator;  // on *in_rail, material toward -z (the wheel is above)
  // The wheel radius at arc length s of the wheel profile [m].
  double RadiusAt(double s) const { return rolling_radius_m + wheel->Position(s).y(); }
};

// `wheel` (wheel profile frame; must outlive the result) placed on `rail_track` (the rail profile
// the contact was solved on) as `placement` places it, at first contact.
PlacedWheel PlaceWheelProfile(const Profile& wheel, const Profile& rail_track,
                              const WheelPlacement& placement);

// Per-pass wear depth [m] of one patch on the wheel's bins (wear_grid on the wheel profile's arc
// length), formula (*) above: law and wheel_hardness_Pa as CalcColumnPassDepth (the wheel's
// hardness), speed_m_s the rolling speed V of the solution, distance_per_pass_m = L > 0.
// Volume-conserving: sum_b depth_b h 2 pi r(s_b) equals L sum_j dz_j ds to the variation of r
// within a bin. Throws as CalcColumnPassDepth.
std::vector<double> CalcPatchWheelPassDepth(const PatchResult& patch, const PlacedWheel& wheel,
                                            const WearLaw& law, double wheel_hardness_Pa,
                                            double speed_m_s, double distance_per_pass_m,
                                            const WearGrid& wear_grid);

// The wear volume per pass [m^3] of a depth field on the wheel's bins (depth_b h 2 pi r at the
// bin centre); `wheel` and `rolling_radius_m` as PlacedWheel's.
double WheelWornVolume(const std::vector<double>& depth_m, const WearGrid& wear_grid,
                       const Profile& wheel, double rolling_radius_m);

}  // namespace railwear
