// The labelled forces on the rail and the flange-climb check (contact_forces.h).
#include "core/contact/contact_forces.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace railwear {

ForceParts PatchForcesOnRail(const PatchResult& patch) {
  ForceParts f;
  f.normal_N = Eigen::Vector3d(0.0, patch.lateral_force_N, patch.vertical_force_N);
  if (patch.rolling) {
    // Tractions act on the wheel (tangential_types.h): the rail feels their reaction.
    const TangentialSolution& t = patch.rolling->tangential;
    f.creep_N = -Eigen::Vector3d(t.force_x_N, t.force_s_yz_N.x(), t.force_s_yz_N.y());
  }
  return f;
}

ForceParts TotalForcesOnRail(const ContactResult& result) {
  ForceParts total;
  for (const PatchResult& p : result.patches) {
    const ForceParts f = PatchForcesOnRail(p);
    total.normal_N += f.normal_N;
    total.creep_N += f.creep_N;
  }
  return total;
}

Eigen::Vector3d RailToPatchFrame(const Eigen::Vector3d& f, double contact_angle_rad) {
  const double c = std::cos(contact_angle_rad), s = std::sin(contact_angle_rad);
  return {s * f.y() + c * f.z(), f.x(), c * f.y() - s * f.z()};
}

Eigen::Vector3d RailToTrackFrame(const Eigen::Vector3d& f, bool left_wheel) {
  return left_wheel ? Eigen::Vector3d(f.x(), -f.y(), f.z()) : f;
}

std::optional<double> NadalLimit(double contact_angle_rad, double friction) {
  const double t = std::tan(contact_angle_rad);
  if (t <= friction) return std::nullopt;
  return (t - friction) / (1.0 + friction * t);
}

void SumPatchTotals(ContactResult* r) {
  r->area_m2 = r->p_max_Pa = r->vertical_force_N = r->lateral_force_N = 0.0;
  r->plastic_cells = 0;
  r->plastic_area_m2 = r->plastic_force_N = 0.0;
  for (const PatchResult& p : r->patches) {
    r->area_m2 += p.area_m2;
    r->p_max_Pa = std::max(r->p_max_Pa, p.p_max_Pa);
    r->vertical_force_N += p.vertical_force_N;
    r->lateral_force_N += p.lateral_force_N;
    r->plastic_cells += p.plastic_cells;
    r->plastic_area_m2 += p.plastic_area_m2;
    r->plastic_force_N += p.plastic_force_N;
  }
}

FlangeClimbCheck CheckFlangeClimb(const ContactResult& result, std::optional<double> friction) {
  FlangeClimbCheck c;
  c.friction = friction;
  if (result.patches.empty()) return c;
  const Eigen::Vector3d net = TotalForcesOnRail(result).Net();
  c.l_over_v = net.z() > 0.0 ? std::abs(net.y()) / net.z() : 0.0;
  c.contact_angle_rad = result.patches.front().contact_angle_rad;
  for (const PatchResult& p : result.patches) {
    c.contact_angle_rad = std::max(c.contact_angle_rad, p.contact_angle_rad);
  }
  if (friction) c.nadal_limit = NadalLimit(c.contact_angle_rad, *friction);
  c.exceeded = c.nadal_limit && c.l_over_v > *c.nadal_limit &&
               c.contact_angle_rad >= kFlangeContactAngle_rad;
  return c;
}

FlangeClimbCheck CheckFlangeClimbAtSteepest(const ContactResult& result, double friction) {
  constexpr double kLoadedColumn = 0.05;
  FlangeClimbCheck check = CheckFlangeClimb(result, friction);
  for (const PatchResult& patch : result.patches) {
    check.contact_angle_rad = std::max(check.contact_angle_rad, patch.contact_angle_rad);
    const PatchGrid& g = patch.grid;
    if (g.cells() == 0 || patch.pressure_Pa.size() != g.cells()) continue;
    Eigen::VectorXd column = Eigen::VectorXd::Zero(g.ns);
    for (int j = 0; j < g.ns; ++j) {
      for (int i = 0; i < g.nx; ++i) column[j] += std::max(patch.pressure_Pa[g.Index(i, j)], 0.0);
    }
    const double largest = column.maxCoeff();
    for (int j = 0; j < g.ns && largest > 0.0; ++j) {
      if (column[j] < kLoadedColumn * largest) continue;
      const Eigen::Vector2d& n = g.normal_yz[j];  // out of the rail: the pressure acts along -n
      check.contact_angle_rad = std::max(check.contact_angle_rad, std::atan2(-n.x(), -n.y()));
    }
  }
  check.nadal_limit = NadalLimit(check.contact_angle_rad, friction);
  check.exceeded = check.nadal_limit && check.l_over_v > *check.nadal_limit &&
                   check.contact_angle_rad >= kFlangeContactAngle_rad;
  return check;
}

std::string FlangeClimbWarning(const FlangeClimbCheck& check, const std::string& wheel) {
  return fmt::format(
      "{}L/V {:.3f} exceeds Nadal's limit {:.3f} at contact angle {:.1f} deg, "
      "mu {:.3g}: flange climb possible",
      wheel.empty() ? "" : wheel + ": ", check.l_over_v, check.nadal_limit.value_or(0.0),
      check.contact_angle_rad * 180.0 / std::numbers::pi, check.friction.value_or(0.0));
}

}  // namespace railwear
