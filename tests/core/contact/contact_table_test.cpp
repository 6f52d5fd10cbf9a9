// ContactTable: the tabulated rigid contact geometry of a wheelset against the placed geometry at
// its nodes, its forces between nodes against a finer table's node there, and its creep forces
// against Kalker's linear theory in the linear range.
#include "core/contact/contact_table.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "core/contact/hertz.h"
#include "core/contact/hertz_estimate.h"
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

// The default table's options over +-half_range with nodes `spacing` apart [m].
ContactTableOptions Nodes(double half_range_m, double spacing_m) {
  ContactTableOptions o;
  o.half_range_m = half_range_m;
  o.node_spacing_m = spacing_m;
  return o;
}

TEST(ContactTable, NodesAreThePlacedGeometrysAtTheNodesRoll) {
  const ContactTableGeometry g = S1002OnUic60();
  const ContactTableOptions o = Nodes(8e-3, 1e-3);
  const ContactTable table(g, o);
  ASSERT_EQ(table.size(), 17);
  double d_point = 0.0, d_radius = 0.0, d_angle = 0.0;
  for (int i = 0; i < table.size(); ++i) {
    const ContactTable::Node& n = table.node(i);
    EXPECT_NEAR(n.y_m, -8e-3 + 1e-3 * i, 1e-15);
    WheelsetSpec ws = g.wheelset;
    ws.lateral_displacement_m = n.y_m;
    ws.roll_rad = n.roll_rad;
    const WheelsetPlacement placed = PlaceWheelsetAt(g.gauge_points, g.track, ws);
    // At the table's own sampling: the node is the placed geometry, candidate for candidate.
    const WheelRailGeometry high(g.high_wheel, g.high_rail, placed.right, o.sampling_m);
    const WheelRailGeometry low(g.low_wheel, g.low_rail, placed.left, o.sampling_m);
    // Both wheels touch their rails at the node's roll: the roll from their heights there is
    // the node's within 1e-5 rad (two fixed-point steps of a contraction of about 0.05 from a
    // roll of 0, as the curving's kinematic roll takes them; 1e-5 rad is 7.5 um of height at a
    // wheel, a tenth of a wheel load's approach).
    const double half_span = 0.5 * ws.flange_back_distance_m - ws.flange_back_position_m;
    EXPECT_NEAR(std::asin((high.dz_m() - low.dz_m()) / (2.0 * half_span)), n.roll_rad, 1e-5) << i;
    // At the contact solver's default sampling (20 um): the first contact point and its radius
    // and angle, within what the table's 0.2 mm sampling of the gap moves them (printed).
    const WheelRailGeometry high_fine(g.high_wheel, g.high_rail, placed.right);
    const WheelRailGeometry low_fine(g.low_wheel, g.low_rail, placed.left);
    for (const auto& [geometry, fine, wheel] :
         {std::tuple{&high, &high_fine, &n.high}, std::tuple{&low, &low_fine, &n.low}}) {
      ASSERT_TRUE(wheel->contact) << i;
      const std::vector<ContactCandidate> c = geometry->FindCandidates(o.candidate_threshold_m);
      ASSERT_EQ(c.size(), wheel->candidates.size()) << i;
      for (size_t k = 0; k < c.size(); ++k) {
        EXPECT_EQ(c[k].rail_point_m, wheel->candidates[k].rail_point_m) << i;
        EXPECT_EQ(c[k].gap_m, wheel->candidates[k].gap_m) << i;
        EXPECT_EQ(c[k].wheel_radius_m, wheel->candidates[k].wheel_radius_m) << i;
      }
      const std::vector<ContactCandidate> f = fine->FindCandidates(1e-6);
      ASSERT_FALSE(f.empty());
      const ContactCandidate* first = nullptr;
      for (const ContactCandidate& t : wheel->candidates) {
        if (!first || t.gap_m < first->gap_m) first = &t;
      }
      d_point = std::max(d_point, (first->rail_point_m - f[0].rail_point_m).norm());
      d_radius = std::max(d_radius, std::abs(first->wheel_radius_m - f[0].wheel_radius_m));
      d_angle = std::max(d_angle, std::abs(std::atan2(first->normal.x(), -first->normal.y()) -
                                           std::atan2(f[0].normal.x(), -f[0].normal.y())));
    }
  }
  std::printf(
      "table nodes (%.2f mm sampling) against the 20 um placed geometry: first contact "
      "point within %.3f mm, rolling radius %.2f um, contact angle %.3f mrad\n",
      o.sampling_m * 1e3, d_point * 1e3, d_radius * 1e6, d_angle * 1e3);
  // Within 1.5 samples of the gap in position (measured 0.101 mm at 0.1 mm sampling, at the
  // flange root where two candidates' gaps nearly tie); the radius follows the point along the
  // flange's slope (tan 70 deg = 2.7: 0.1 mm of point is 0.27 mm of radius; measured 95 um).
  EXPECT_LT(d_point, 1.5 * o.sampling_m);
  EXPECT_LT(d_radius, 1.5 * o.sampling_m * std::tan(70.0 * M_PI / 180.0));
  EXPECT_LT(d_angle, 0.05);
}

// Between nodes the forces are blended linearly: against a table with half the spacing, whose
// odd nodes lie midway, the error is that of linear interpolation: h^2/8 |F''| where the force is
// smooth, and where it is monotone across the interval (a second point, the flange, taking load
// within one spacing) at most half its change across the interval.
TEST(ContactTable, ForcesBetweenNodesWithinTheInterpolationBound) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions coarse, fine;
  coarse.half_range_m = fine.half_range_m = 10e-3;
  fine.node_spacing_m = 0.5 * coarse.node_spacing_m;
  const ContactTable a(g, coarse), b(g, fine);
  ContactTableLoad load = Load();
  load.curvature_per_m = 1.0 / 600.0;
  const double yaw = 2e-3;
  double tread = 0.0, anywhere = 0.0;
  for (int k = 1; k + 1 < b.size(); k += 2) {
    const double y = b.node(k).y_m;
    const ContactTableForces mid = a.Evaluate(y, yaw, load);
    const ContactTableForces at = b.EvaluateNode(k, yaw, load);
    const ContactTableForces lo = b.EvaluateNode(k - 1, yaw, load);
    const ContactTableForces hi = b.EvaluateNode(k + 1, yaw, load);
    ASSERT_TRUE(mid.valid && at.valid && lo.valid && hi.valid) << y;
    const double e = std::abs(mid.force_N.y() - at.force_N.y());
    anywhere = std::max(anywhere, e);
    if (std::abs(y) < 3e-3) tread = std::max(tread, e);
    const double f0 = lo.force_N.y(), f1 = at.force_N.y(), f2 = hi.force_N.y();
    if ((f1 - f0) * (f2 - f1) >= 0.0) {  // monotone across the interval
      EXPECT_LE(e, 0.5 * std::abs(f2 - f0) + 1.0) << "y " << y * 1e3 << " mm";
    }
  }
  std::printf(
      "lateral force between nodes %.2f mm apart: largest error %.0f N within 3 mm of "
      "the centre, %.0f N anywhere in +-10 mm (wheel load 60 kN)\n",
      coarse.node_spacing_m * 1e3, tread, anywhere);
  // Within 3 mm of the centre (the tread) within 2 % of the wheel load: measured 838 N, 1.4 %,
  // where the S1002 tread's contact point moves fast as the profiles' curvatures nearly match.
  EXPECT_LT(tread, 0.02 * load.high_load_N);
}

// At the centre of a symmetric wheelset, rolling freely on tangent track with a small yaw, the
// lateral creep force of each wheel is Kalker's linear -G c^2 C22 eta (spin aside), eta = -psi
// sec(gamma): the table's sum against both wheels' linear forces within 2 % (cos^2 of the tread's
// contact angle of about 2 degrees, the lead). A friction of 1000 keeps the saturation out (the
// tread's conicity spins each patch, whose C23 force would otherwise take the patch to u of
// about 0.1 of the adhesion limit, and Shen-Hedrick-Elkins' slope there is 1 - 2u/3).
TEST(ContactTable, SmallYawGivesKalkersLinearLateralForce) {
  const ContactTableGeometry g = S1002OnUic60();
  const ContactTable table(g, Nodes(1e-3, 1e-3));
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
    const HertzSolution h =
        SolveHertz(A, B, ContactModulus(load.wheel_material, load.rail_material), 60e3 / cos_gamma);
    const double G = 210e9 / (2.0 * 1.28);
    const LinearCreepForces f = CalcLinearCreepForces(h.semi_axis_x_m, h.semi_axis_y_m, G, 0.28,
                                                      0.0, -yaw / cos_gamma, 0.0);
    expected += f.force_y_N * cos_gamma;  // the lateral tangent's Y part
  }
  const double got = at.force_N.y() - at0.force_N.y();
  std::printf("yaw 0.1 mrad at the centre: lateral creep force %.1f N, Kalker linear %.1f N\n", got,
              expected);
  EXPECT_NEAR(got, expected, 0.02 * std::abs(expected));
}

TEST(ContactTable, OutsideTheTableIsNotValidAndBadOptionsThrow) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions o = Nodes(1e-3, 5e-4);
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

// The interpenetration patches' options are checked where the table is built, the message
// naming both values and the ranges expected.
TEST(ContactTable, BadInterpenetrationOptionsThrowNamingThem) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions o = Nodes(1e-3, 5e-4);
  o.patch = ContactTableOptions::Patch::kInterpenetration;
  for (const auto& [ratio, spacing] : {std::pair{0.0, 1e-3}, {1.5, 1e-3}, {0.55, 0.0}}) {
    o.penetration_ratio = ratio;
    o.station_spacing_m = spacing;
    try {
      const ContactTable table(g, o);
      ADD_FAILURE() << "no error for ratio " << ratio << ", spacing " << spacing;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("penetration_ratio"), std::string::npos) << what;
      EXPECT_NE(what.find("station_spacing_m"), std::string::npos) << what;
      EXPECT_NE(what.find("expected a ratio in (0, 1] and a spacing > 0"), std::string::npos)
          << what;
    }
  }
}

// Interpenetration patches come from the wheel's whole gap, one per physical region: where the
// gauge corner's gap splits into two candidates (the flange root and the tread's edge) whose
// saddle the wheel's approach overlaps, the two Hertz candidates are one patch carrying both
// their vertical loads, so the patch's contact angle moves steadily from node to node where
// Hertz's largest loaded angle jumps. S1002 on UIC60 1:40, the high wheel at 125 kN (a Y25
// wagon's leading high wheel on R 600 m), nodes 0.1 mm apart from 4.5 to 6.0 mm, below flange
// contact (which starts at 6.6 mm with a real jump of the angle to 69 degrees).
TEST(ContactTable, InterpenetrationRegionsJoinCandidatesAcrossSaddles) {
  const ContactTableGeometry g = S1002OnUic60();
  ContactTableOptions hertz_options = Nodes(6e-3, 1e-4), pen_options = hertz_options;
  pen_options.patch = ContactTableOptions::Patch::kInterpenetration;
  const ContactTable hertz(g, hertz_options), pen(g, pen_options);
  ContactTableLoad load = Load();
  load.high_load_N = 125e3;
  load.low_load_N = 95e3;
  load.curvature_per_m = 1.0 / 600.0;
  const double estar = ContactModulus(load.wheel_material, load.rail_material);
  const double yaw = 1e-3;
  int joined = 0;
  double hertz_step = 0.0, pen_step = 0.0, last_hertz = -1.0, last_pen = -1.0;
  for (int i = 0; i < pen.size(); ++i) {
    const ContactTable::Node& n = pen.node(i);
    if (n.y_m < 4.5e-3 - 1e-9 || n.y_m > 6.0e-3 + 1e-9) continue;
    const ContactTableForces fh = hertz.EvaluateNode(i, yaw, load);
    const ContactTableForces fp = pen.EvaluateNode(i, yaw, load);
    ASSERT_TRUE(fh.valid && fp.valid) << n.y_m;
    // The Hertz candidates the approach loads, and whether the gap between the first two
    // loaded ones' minima stays below the approach (one physical region).
    const std::vector<ContactCandidate>& c = n.high.candidates;
    const double delta =
        internal::HertzApproachForLoad(c, n.high.pose.roll_rad, estar, load.high_load_N);
    std::vector<HertzSolution> hs;
    internal::HertzVerticalLoad(c, n.high.pose.roll_rad, estar, delta, &hs);
    std::vector<double> minima;
    for (size_t k = 0; k < c.size(); ++k) {
      if (hs[k].force_N > 0.0) minima.push_back(c[k].y_m);
    }
    ASSERT_EQ(fh.high.loaded_points, static_cast<int>(minima.size())) << n.y_m;
    if (minima.size() == 2) {
      const ContactTable::Wheel::Samples& s = n.high.samples;
      double saddle = 0.0;
      for (size_t j = 0; j < s.y_m.size(); ++j) {
        if (s.y_m[j] > minima[0] && s.y_m[j] < minima[1]) saddle = std::max(saddle, s.gap_m[j]);
      }
      if (saddle < delta) {
        ++joined;
        EXPECT_EQ(fp.high.loaded_points, 1) << "y " << n.y_m * 1e3 << " mm";
      }
    }
    if (last_pen >= 0.0) {
      hertz_step = std::max(hertz_step, std::abs(fh.high.largest_contact_angle_rad - last_hertz));
      pen_step = std::max(pen_step, std::abs(fp.high.largest_contact_angle_rad - last_pen));
    }
    last_hertz = fh.high.largest_contact_angle_rad;
    last_pen = fp.high.largest_contact_angle_rad;
  }
  std::printf(
      "gauge corner 4.5-6.0 mm: %d nodes with two Hertz candidates in one region; largest "
      "change of the high wheel's contact angle between nodes 0.1 mm apart: Hertz %.1f deg, "
      "interpenetration regions %.1f deg\n",
      joined, hertz_step * 180.0 / M_PI, pen_step * 180.0 / M_PI);
  EXPECT_GE(joined, 2);  // measured 3 (5.0, 5.1 and 5.2 mm)
  // Measured 9.9 deg (Hertz: the flange root's candidate appears) against 3.9 deg.
  EXPECT_LT(pen_step, 0.5 * hertz_step);
}

}  // namespace
}  // namespace railwear
