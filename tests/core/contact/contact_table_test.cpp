// ContactTable: the tabulated rigid contact geometry of a wheelset against the placed geometry at
// its nodes, its forces between nodes against a finer table's node there, and its creep forces
// against Kalker's linear theory in the linear range.
#include "core/contact/contact_table.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/contact/hertz.h"
#include "core/contact/kalker_coefficients.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"

namespace railwear {
namespace {

// An S1002 wheelset on UIC60 rails inclined 1:40, both sides alike.
ContactTableGeometry S1002OnUic60() {
  ContactTableGeometry g;
  g.high_wheel = MakeS1002();
  g.low_wheel = g.high_wheel;
  g.high_rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  g.low_rail = g.high_rail;
  const double y_g = RailGaugePoint(g.high_rail, g.track.gauge_height_m).x();
  g.gauge_points = {y_g, y_g};
  return g;
}

ContactTableLoad Load() {
  ContactTableLoad l;
  l.high_load_N = 60e3;
  l.low_load_N = 60e3;
  l.speed_m_s = 20.0;
  l.friction = 0.35;
  return l;
}

TEST(ContactTable, NodesAreThePlacedGeometrysAtTheNodesRoll) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions o;
  o.half_range_m = 8e-3;
  o.node_spacing_m = 2e-3;
  const ContactTable table(g, o);
  ASSERT_EQ(table.size(), 9);
  for (int i = 0; i < table.size(); ++i) {
    const ContactTable::Node& n = table.node(i);
    EXPECT_NEAR(n.y_m, -8e-3 + 2e-3 * i, 1e-15);
    // The placed geometry at the node's y and roll, at the contact solver's default sampling
    // (20 um, five times finer than the table's): the same first contact point (refined on the
    // splines, so the sampling moves it by far less than the 1 um allowed), angle and radius.
    WheelsetSpec ws = g.wheelset;
    ws.lateral_displacement_m = n.y_m;
    ws.roll_rad = n.roll_rad;
    const WheelsetPlacement placed = PlaceWheelsetAt(g.gauge_points, g.track, ws);
    const WheelRailGeometry high(g.high_wheel, g.high_rail, placed.right);
    const WheelRailGeometry low(g.low_wheel, g.low_rail, placed.left);
    // Both wheels touch their rails at the node's roll: the heights agree to a micrometre (two
    // fixed-point steps of a contraction of about 0.05 from a roll of 0).
    const double half_span = 0.5 * ws.flange_back_distance_m - ws.flange_back_position_m;
    EXPECT_NEAR(std::asin((high.dz_m() - low.dz_m()) / (2.0 * half_span)), n.roll_rad,
                1e-6 / half_span)
        << i;
    for (const auto& [placed_geometry, wheel] :
         {std::pair{&high, &n.high}, std::pair{&low, &n.low}}) {
      ASSERT_TRUE(wheel->contact) << i;
      const std::vector<ContactCandidate> c = placed_geometry->FindCandidates(1e-6);
      ASSERT_FALSE(c.empty());
      // The table's candidate of zero gap.
      const ContactCandidate* first = nullptr;
      for (const ContactCandidate& t : wheel->candidates) {
        if (t.gap_m < 1e-9) first = &t;
      }
      ASSERT_NE(first, nullptr) << i;
      EXPECT_NEAR(first->rail_point_m.x(), c[0].rail_point_m.x(), 1e-6) << i;
      EXPECT_NEAR(first->rail_point_m.y(), c[0].rail_point_m.y(), 1e-6) << i;
      EXPECT_NEAR(first->wheel_radius_m, c[0].wheel_radius_m, 1e-6) << i;
      EXPECT_NEAR(std::atan2(first->normal.x(), -first->normal.y()),
                  std::atan2(c[0].normal.x(), -c[0].normal.y()), 1e-3)
          << i;
    }
  }
}

// Between nodes the forces are blended linearly: against a table with half the spacing, whose
// odd nodes lie midway, the error is that of linear interpolation, h^2/8 |F''|, small on the
// tread and large only where a second point (the flange) takes load within one spacing.
TEST(ContactTable, ForcesBetweenNodesWithinTheInterpolationBound) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions coarse, fine;
  coarse.half_range_m = fine.half_range_m = 10e-3;
  coarse.node_spacing_m = 2e-4;
  fine.node_spacing_m = 1e-4;
  const ContactTable a(g, coarse), b(g, fine);
  ContactTableLoad load = Load();
  load.curvature_per_m = 1.0 / 600.0;
  const double yaw = 2e-3;
  double tread = 0.0, anywhere = 0.0;
  for (int k = 1; k < b.size(); k += 2) {
    const double y = b.node(k).y_m;
    const ContactTableForces mid = a.Evaluate(y, yaw, load);
    const ContactTableForces at = b.EvaluateNode(k, yaw, load);
    ASSERT_TRUE(mid.valid && at.valid) << y;
    const double e = std::abs(mid.force_N.y() - at.force_N.y());
    anywhere = std::max(anywhere, e);
    if (at.high.largest_contact_angle_rad < 0.5 && at.low.largest_contact_angle_rad < 0.5) {
      tread = std::max(tread, e);
    }
  }
  std::printf("lateral force between nodes 0.2 mm apart: largest error %.0f N on the tread, "
              "%.0f N anywhere (of a 60 kN wheel load)\n",
              tread, anywhere);
  // On the tread the lateral force's curvature in y is that of the contact angle's and the
  // creep forces' smooth variation: within 1 % of the wheel load.
  EXPECT_LT(tread, 0.01 * load.high_load_N);
  // At the flange the force turns from the tread's to the flange's within about 0.1 mm: the
  // blend's error is bounded by the force's change over one spacing, below the wheel load.
  EXPECT_LT(anywhere, load.high_load_N);
}

// At the centre of a symmetric wheelset, rolling freely on tangent track with a small yaw, the
// lateral creep force of each wheel is Kalker's linear -G c^2 C22 eta (spin aside), eta = -psi
// sec(gamma): the table's sum against both wheels' linear forces within 2 % (cos^2 of the tread's
// contact angle of about 2 degrees, the lead). A friction of 1000 keeps the saturation out (the
// tread's conicity spins each patch, whose C23 force would otherwise take the patch to u of
// about 0.1 of the adhesion limit, and Shen-Hedrick-Elkins' slope there is 1 - 2u/3).
TEST(ContactTable, SmallYawGivesKalkersLinearLateralForce) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions o;
  o.half_range_m = 1e-3;
  o.node_spacing_m = 1e-3;
  const ContactTable table(g, o);
  ContactTableLoad load = Load();
  load.friction = 1e3;
  const double yaw = 1e-4;
  const ContactTableForces at0 = table.EvaluateNode(1, 0.0, load);
  const ContactTableForces at = table.EvaluateNode(1, yaw, load);
  ASSERT_TRUE(at.valid && at0.valid);
  EXPECT_NEAR(at0.force_N.y(), 0.0, 1.0);  // symmetric
  // Kalker's linear force on each wheel's single candidate, at its Hertz ellipse.
  double expected = 0.0;
  for (const ContactTable::Wheel* w : {&table.node(1).high, &table.node(1).low}) {
    ASSERT_EQ(w->candidates.size(), 1u);
    const ContactCandidate& c = w->candidates[0];
    const double cos_gamma = -c.normal.y();
    const double A = cos_gamma / (2.0 * c.wheel_radius_m);
    const double B = 0.5 * (c.rail_lateral_curvature + c.wheel_lateral_curvature);
    const HertzSolution h = SolveHertz(A, B, ContactModulus(load.wheel_material, load.rail_material),
                                       60e3 / cos_gamma);
    const double G = 210e9 / (2.0 * 1.28);
    const LinearCreepForces f =
        CalcLinearCreepForces(h.semi_axis_x_m, h.semi_axis_y_m, G, 0.28, 0.0, -yaw / cos_gamma, 0.0);
    expected += f.force_y_N * cos_gamma;  // the lateral tangent's Y part
  }
  const double got = at.force_N.y() - at0.force_N.y();
  std::printf("yaw 0.1 mrad at the centre: lateral creep force %.1f N, Kalker linear %.1f N\n",
              got, expected);
  EXPECT_NEAR(got, expected, 0.02 * std::abs(expected));
}

TEST(ContactTable, OutsideTheTableIsNotValidAndBadOptionsThrow) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions o;
  o.half_range_m = 1e-3;
  o.node_spacing_m = 5e-4;
  const ContactTable table(g, o);
  const ContactTableForces f = table.Evaluate(1.5e-3, 0.0, Load());
  EXPECT_FALSE(f.valid);
  EXPECT_NE(f.why_not.find("outside the contact table"), std::string::npos) << f.why_not;
  o.node_spacing_m = 0.0;
  EXPECT_THROW(ContactTable(g, o), InputError);
  o.node_spacing_m = 1e-3;
  o.half_range_m = 1e-4;
  EXPECT_THROW(ContactTable(g, o), InputError);
}

}  // namespace
}  // namespace railwear
