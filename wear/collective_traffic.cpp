// Imported load collectives as wear traffic (see collective_traffic.h).
#include "wear/collective_traffic.h"

#include <stdexcept>

#include <fmt/format.h>

#include "core/contact/wheelset_contact.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "wear/vehicle_traffic.h"
#include "wear/wear_simulation.h"

namespace railwear {

double CollectiveAxleLoad_t(const LoadCollective& collective) {
  double sum[2] = {0.0, 0.0}, share[2] = {0.0, 0.0};
  for (const LoadCollectiveEntry& e : collective.entries) {
    const int r = static_cast<int>(e.rail);
    sum[r] += e.share * e.axle_load_t;
    share[r] += e.share;
  }
  double total = 0.0;
  int rails = 0;
  for (int r = 0; r < 2; ++r) {
    if (share[r] <= 0.0) continue;
    total += sum[r] / share[r];
    ++rails;
  }
  return rails > 0 ? total / rails : 0.0;
}

double RigidContactRadius(const Profile& wheel, const Profile& rail_track, const WheelPose& pose) {
  const WheelRailGeometry geometry(wheel, rail_track, pose);
  // First contact has a gap of 0; a micrometre keeps only its neighbourhood (and a second point
  // touching within it, of which the smaller gap wins).
  const std::vector<ContactCandidate> candidates =
      geometry.has_overlap() ? geometry.FindCandidates(1e-6) : std::vector<ContactCandidate>{};
  if (candidates.empty()) {
    throw std::runtime_error(fmt::format(
        "the wheel at lateral shift {:.3f} mm does not reach the rail: no contact point",
        pose.lateral_shift_m * 1e3));
  }
  const ContactCandidate* best = &candidates.front();
  for (const ContactCandidate& c : candidates) {
    if (c.gap_m < best->gap_m) best = &c;
  }
  return best->wheel_radius_m;
}

double PitchVelocityForCreepage(double xi, double wheel_speed_m_s, double contact_radius_m) {
  return -(1.0 - xi) * wheel_speed_m_s / contact_radius_m;
}

double CreepageForPitchVelocity(double pitch_velocity_rad_s, double wheel_speed_m_s,
                                double contact_radius_m) {
  return 1.0 + pitch_velocity_rad_s * contact_radius_m / wheel_speed_m_s;
}

std::vector<LoadCase> CollectiveLoadCases(const WearStudy& study, int traffic_index) {
  const TrafficCase& c = study.traffic[traffic_index];
  const CollectiveTraffic& ct = *c.collective;
  const std::array<double, 2> totals = RailShareTotals(study.traffic);
  const RailGaugePoints gauge_points = UnwornGaugePoints(study);
  const double kappa = study.curve.curvature_per_m();
  // The unworn rails in the track frame, for the rigid contact radius of bins with xi.
  std::optional<Profile> rails[2];
  std::vector<LoadCase> cases;
  cases.reserve(ct.collective.entries.size());
  for (const LoadCollectiveEntry& e : ct.collective.entries) {
    const bool high = e.rail == RailSide::kHigh;
    WheelsetSpec ws;
    ws.flange_back_distance_m = ct.flange_back_distance_m;
    ws.flange_back_position_m = ct.flange_back_position_m;
    ws.rolling_radius_m = c.rolling_radius_m;
    ws.lateral_displacement_m = e.wheelset_y_m;
    ws.yaw_rad = e.yaw_rad;
    ws.roll_rad = e.roll_rad;
    const WheelsetPlacement placed = PlaceWheelsetAt(gauge_points, study.track, ws);
    WheelMotion axle;
    axle.speed_m_s = e.speed_m_s;
    const WheelMotions motions = CurveWheelMotions(axle, placed, kappa, c.rolling_radius_m);
    const WheelPose& pose = high ? placed.right : placed.left;
    LoadCase lc;
    lc.traffic_index = traffic_index;
    lc.rail = e.rail;
    lc.placement = {pose.lateral_shift_m, pose.roll_rad, pose.rolling_radius_m, pose.yaw_rad};
    lc.vertical_force_N = e.vertical_force_N;
    lc.motion = high ? motions.right : motions.left;
    if (e.creepage_x) {
      std::optional<Profile>& rail = rails[static_cast<int>(e.rail)];
      if (!rail) {
        const Profile& unworn = high ? study.rail_profile : *study.low_rail_profile;
        rail = RailInTrack(study, unworn, unworn);
      }
      double r_c = 0.0;
      try {
        r_c = RigidContactRadius(c.wheel_profile, *rail, pose);
      } catch (const std::runtime_error& err) {
        throw std::runtime_error(fmt::format("wear: {}: bin '{}' on the {} rail: {}", c.name,
                                             e.name, ToString(e.rail), err.what()));
      }
      lc.motion.pitch_velocity_rad_s =
          PitchVelocityForCreepage(*e.creepage_x, lc.motion.speed_m_s, r_c);
    }
    lc.friction = e.friction.value_or(c.friction);
    lc.weight = c.share / totals[static_cast<int>(e.rail)] * e.share;
    cases.push_back(lc);
  }
  return cases;
}

}  // namespace railwear
