// Imported load collectives as wear traffic: each bin's load case is its wheelset state placed
// on the unworn rails; the weights of each rail sum to 1 with the other entries; a synthetic MBS
// CSV written from steady-curving solutions imports to the same states and gives the same load
// cases as the vehicle traffic of those solutions; a one-step wear run on collective traffic
// wears both rails.
#include "wear/collective_traffic.h"

#include <cmath>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/contact/wheelset_contact.h"
#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "wear/vehicle_traffic.h"
#include "wear/wear_simulation.h"
#include "tests/wear/default_study.h"

namespace railwear {
namespace {

// A free S1002 wheelset on UIC60 1:40 rails of a 1500 m curve, at two speeds (shares 3 and 1):
// the fixture of tests/wear/vehicle_traffic_test.cpp with a second entry.
WearStudy VehicleStudy() {
  WearStudy study = VehicleCurveStudy(1500.0, VehicleKind::kWheelset, 0.3, 25.0);
  VehicleSpec& v = study.vehicles[0];
  v.cg_height_m = 1.5;
  const TrafficCase one = study.traffic[0];
  study.traffic.clear();
  for (const auto& [speed, share] : {std::pair{25.0, 3.0}, std::pair{15.0, 1.0}}) {
    TrafficCase c = one;
    c.name = fmt::format("wheelset at {} m/s", speed);
    c.rolling_radius_m = v.rolling_radius_m;
    c.speed_m_s = speed;
    c.share = share;
    study.traffic.push_back(c);
  }
  study.options.quadrature_points = 1;
  return study;
}

// The study with its traffic replaced by one collective entry (the vehicle's wheel).
WearStudy CollectiveStudy(const WearStudy& vehicles, const LoadCollective& collective) {
  WearStudy study = vehicles;
  const VehicleSpec& v = vehicles.vehicles[0];
  auto ct = std::make_shared<CollectiveTraffic>();
  ct->collective = collective;
  ct->flange_back_distance_m = v.flange_back_distance_m;
  ct->flange_back_position_m = v.flange_back_position_m;
  TrafficCase c;
  c.name = "collective";
  c.wheel_profile = v.wheel_profile;
  c.rolling_radius_m = v.rolling_radius_m;
  c.friction = 0.25;  // the bins' mu wins
  c.share = 1.0;
  c.axle_load_t = CollectiveAxleLoad_t(collective);
  c.collective = ct;
  study.traffic = {c};
  study.vehicles.clear();
  return study;
}

Profile HighTrack(const WearStudy& s) { return RailInTrack(s, s.rail_profile, s.rail_profile); }
Profile LowTrack(const WearStudy& s) {
  return RailInTrack(s, *s.low_rail_profile, *s.low_rail_profile);
}

// A synthetic MBS CSV (weight in passes) from each vehicle entry's curving solution: both wheels'
// rows per wheelset, the entry's share as weight, and each wheel's xi at its rigid contact point
// from the solved pitch velocity (collective_traffic.h).
std::string CsvFromCurving(const WearStudy& study, const std::vector<CurvingResult>& solutions) {
  std::string csv =
      "# synthetic: railwear's steady curving of a free wheelset\n"
      "weight_passes,side,V_m_s,y_mm,yaw_mrad,roll_mrad,Q_N,xi,mu\n";
  const Profile high = HighTrack(study), low = LowTrack(study);
  for (int t = 0; t < static_cast<int>(study.traffic.size()); ++t) {
    const TrafficCase& c = study.traffic[t];
    const CurvingResult& r = solutions[t];
    const VehicleSpec& v = study.vehicles[c.vehicle];
    for (const CurvedWheelset& w : r.wheelsets) {
      const WheelsetSpec ws = v.WheelsetAt(w.lateral_m, w.yaw_rad, w.roll_rad);
      const WheelsetPlacement placed = PlaceWheelsetAt(UnwornGaugePoints(study), study.track, ws);
      WheelMotion axle;
      axle.speed_m_s = c.speed_m_s;
      const WheelMotions m =
          CurveWheelMotions(axle, placed, study.curve.curvature_per_m(), v.rolling_radius_m);
      for (const RailSide side : {RailSide::kHigh, RailSide::kLow}) {
        const bool is_high = side == RailSide::kHigh;
        const double r_c = RigidContactRadius(v.wheel_profile, is_high ? high : low,
                                              is_high ? placed.right : placed.left);
        const double v_w = (is_high ? m.right : m.left).speed_m_s;
        csv += fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", c.share,
                           ToString(side), c.speed_m_s, w.lateral_m * 1e3, w.yaw_rad * 1e3,
                           w.roll_rad * 1e3, is_high ? w.high_load_N : w.low_load_N,
                           CreepageForPitchVelocity(w.pitch_velocity_rad_s, v_w, r_c), c.friction);
      }
    }
  }
  return csv;
}

WheelMotion Axle(double speed_m_s) {
  WheelMotion m;
  m.speed_m_s = speed_m_s;
  return m;
}

void ExpectRelNear(double a, double b, double rel, const std::string& what) {
  EXPECT_LE(std::abs(a - b), rel * std::max(std::abs(b), 1e-300))
      << what << ": " << a << " vs " << b;
}

TEST(CollectiveTrafficTest, CreepageAndPitchVelocityAreInverse) {
  // Pure rolling at the contact radius is xi = 0; a faster-turning wheel (traction) has xi < 0.
  EXPECT_DOUBLE_EQ(CreepageForPitchVelocity(-20.0 / 0.45, 20.0, 0.45), 0.0);
  EXPECT_LT(CreepageForPitchVelocity(-20.0 / 0.44, 20.0, 0.45), 0.0);
  EXPECT_DOUBLE_EQ(PitchVelocityForCreepage(0.002, 20.0, 0.46), -0.998 * 20.0 / 0.46);
  EXPECT_NEAR(CreepageForPitchVelocity(PitchVelocityForCreepage(-0.003, 21.0, 0.455), 21.0, 0.455),
              -0.003, 1e-15);
  // The right wheel of a centred S1002 wheelset on UIC60 1:40 touches near its taping line
  // (r0 = 0.46 m); shifted 6 mm toward it, it touches at its flange root, a larger radius.
  const Profile rail = ApplyCant(MakeUic60(), 0.025);
  WheelsetSpec ws;
  const double centred =
      RigidContactRadius(MakeS1002(), rail, PlaceWheelset(rail, TrackSpec{}, ws).right);
  EXPECT_NEAR(centred, 0.46, 2e-3);
  ws.lateral_displacement_m = 6e-3;
  const double shifted =
      RigidContactRadius(MakeS1002(), rail, PlaceWheelset(rail, TrackSpec{}, ws).right);
  EXPECT_GT(shifted, centred + 2e-3);
}

// Each bin's case is the placement PlaceWheelsetAt gives its state (high: right wheel, low: the
// left wheel in its mirrored frame); weights sum to 1 per rail together with a prescribed entry.
TEST(CollectiveTrafficTest, BinsArePlacedWheelsetsAndWeightsSumToOnePerRail) {
  const std::string csv =
      "weight_passes,side,V_m_s,y_mm,yaw_mrad,roll_mrad,Q_N\n"
      "3,high,20,4.2,1.5,0.8,90000\n"
      "3,low,20,4.2,1.5,0.8,70000\n"
      "1,high,20,-1.0,-0.5,-0.2,78000\n"
      "1,low,20,-1.0,-0.5,-0.2,80000\n"
      "2,high,22,1.0,0.0,0.0,80000\n";
  const LoadCollective lc = BinLoadCollective(ParseMbsTimeHistory(csv, "x.csv"), {});
  WearStudy study = CollectiveStudy(VehicleStudy(), lc);
  study.curve.radius_m = 600.0;
  TrafficCase prescribed = VehicleStudy().traffic[0];
  prescribed.vehicle = -1;
  prescribed.name = "prescribed low";
  prescribed.rail = RailSide::kLow;
  prescribed.lateral_shift_mean_m = -5e-3;
  prescribed.vertical_force_N = 80e3;
  prescribed.share = 1.0;
  study.traffic[0].share = 3.0;
  study.traffic.push_back(prescribed);
  ValidateWearStudy(study);

  const std::vector<LoadCase> cases = CollectiveLoadCases(study, 0);
  ASSERT_EQ(cases.size(), lc.entries.size());
  const RailGaugePoints gauge = UnwornGaugePoints(study);
  for (size_t i = 0; i < cases.size(); ++i) {
    const LoadCollectiveEntry& e = lc.entries[i];
    const LoadCase& c = cases[i];
    SCOPED_TRACE(e.name);
    WheelsetSpec ws;
    ws.lateral_displacement_m = e.wheelset_y_m;
    ws.yaw_rad = e.yaw_rad;
    ws.roll_rad = e.roll_rad;
    ws.rolling_radius_m = study.traffic[0].rolling_radius_m;
    const WheelsetPlacement p = PlaceWheelsetAt(gauge, study.track, ws);
    const WheelPose& pose = e.rail == RailSide::kHigh ? p.right : p.left;
    EXPECT_EQ(c.rail, e.rail);
    EXPECT_EQ(c.placement.lateral_shift_m, pose.lateral_shift_m);
    EXPECT_EQ(c.placement.yaw_rad, pose.yaw_rad);
    EXPECT_EQ(c.placement.roll_rad, pose.roll_rad);
    EXPECT_EQ(c.placement.rolling_radius_m, pose.rolling_radius_m);
    EXPECT_EQ(c.vertical_force_N, e.vertical_force_N);
    EXPECT_EQ(c.friction, 0.25);  // no mu in the CSV: the entry's
    // On the curve each wheel runs at its own speed; without xi the axle rolls at -V/r0.
    const WheelMotions m = CurveWheelMotions(Axle(e.speed_m_s), p, 1.0 / 600.0, 0.46);
    const WheelMotion& wm = e.rail == RailSide::kHigh ? m.right : m.left;
    EXPECT_EQ(c.motion.speed_m_s, wm.speed_m_s);
    EXPECT_EQ(c.motion.yaw_velocity_rad_s, wm.yaw_velocity_rad_s);
    ASSERT_TRUE(c.motion.pitch_velocity_rad_s);
    EXPECT_EQ(*c.motion.pitch_velocity_rad_s, -e.speed_m_s / 0.46);
  }
  // The high rail: the collective alone; the low rail: 3/4 collective, 1/4 prescribed.
  const std::vector<LoadCase> all =
      internal::StepLoadCases(study, HighTrack(study), LowTrack(study));
  double sums[2] = {0.0, 0.0}, collective_low = 0.0;
  for (const LoadCase& c : all) {
    sums[static_cast<int>(c.rail)] += c.weight;
    if (c.rail == RailSide::kLow && c.traffic_index == 0) collective_low += c.weight;
  }
  EXPECT_NEAR(sums[0], 1.0, 1e-14);
  EXPECT_NEAR(sums[1], 1.0, 1e-14);
  EXPECT_NEAR(collective_low, 0.75, 1e-14);
  // One axle pass: the collective's axle load (both rails' mean Q over g) counts on the high rail.
  EXPECT_NEAR(MgtPerPass(study.traffic) * 1e6, CollectiveAxleLoad_t(lc), 1e-12);
}

TEST(CollectiveTrafficTest, CollectiveNeedsALowRail) {
  const LoadCollective lc = BinLoadCollective(
      ParseMbsTimeHistory("weight_passes,side,V_m_s,y_mm,yaw_mrad,Q_N\n1,high,20,0,0,80000\n", "x"),
      {});
  WearStudy study = CollectiveStudy(VehicleStudy(), lc);
  study.low_rail_profile.reset();
  EXPECT_THROW(ValidateWearStudy(study), InputError);
}

// The must-show round trip: curving solutions -> MBS CSV -> load collective -> load cases equal
// to the vehicle traffic's of the same solutions. The CSV carries each wheel's xi, so the pitch
// velocity is the solved one (without xi the collective would roll each axle at -V/r0).
TEST(CollectiveTrafficTest, CsvFromCurvingRoundTripsToTheVehicleLoadCases) {
  const WearStudy vehicles = VehicleStudy();
  ValidateWearStudy(vehicles);
  const Profile high = HighTrack(vehicles), low = LowTrack(vehicles);
  std::vector<CurvingResult> solutions;
  for (int t = 0; t < 2; ++t) {
    solutions.push_back(SolveCurving(VehicleCurvingProblem(vehicles, t, high, low)));
    ASSERT_EQ(solutions.back().status, CurvingStatus::kConverged) << solutions.back().message;
  }
  const std::string csv = CsvFromCurving(vehicles, solutions);
  const LoadCollective lc = BinLoadCollective(ParseMbsTimeHistory(csv, "curving.csv"), {});

  // The states come back, one bin per wheel, with the entries' shares per rail.
  std::vector<LoadCase> expected;
  for (int t = 0; t < 2; ++t) {
    const std::vector<LoadCase> more = VehicleLoadCases(vehicles, t, high, low);
    expected.insert(expected.end(), more.begin(), more.end());
  }
  ASSERT_EQ(lc.entries.size(), 4u);
  ASSERT_EQ(expected.size(), 4u);
  const WearStudy study = CollectiveStudy(vehicles, lc);
  ValidateWearStudy(study);
  const std::vector<LoadCase> got = internal::StepLoadCases(study, high, low);
  ASSERT_EQ(got.size(), 4u);
  // Collective order is by bin; match each bin to the vehicle case of its speed and rail.
  for (size_t i = 0; i < got.size(); ++i) {
    const LoadCollectiveEntry& e = lc.entries[i];
    const int t = e.speed_m_s > 20.0 ? 0 : 1;
    const LoadCase* want = nullptr;
    for (const LoadCase& c : expected) {
      if (c.traffic_index == t && c.rail == e.rail) want = &c;
    }
    ASSERT_NE(want, nullptr);
    const LoadCase& c = got[i];
    SCOPED_TRACE(e.name);
    // The binned state (one row per bin: its mean is the row) and its share on the rail.
    const CurvedWheelset& w = solutions[t].wheelsets[0];
    const bool is_high = e.rail == RailSide::kHigh;
    constexpr double kRel = 1e-12;
    ExpectRelNear(e.wheelset_y_m, w.lateral_m, kRel, "y");
    ExpectRelNear(e.yaw_rad, w.yaw_rad, kRel, "yaw");
    ExpectRelNear(e.roll_rad, w.roll_rad, kRel, "roll");
    ExpectRelNear(e.vertical_force_N, is_high ? w.high_load_N : w.low_load_N, kRel, "Q");
    EXPECT_EQ(e.speed_m_s, vehicles.traffic[t].speed_m_s);
    EXPECT_EQ(e.share, t == 0 ? 0.75 : 0.25);
    // The load case.
    EXPECT_EQ(c.rail, want->rail);
    ExpectRelNear(c.placement.lateral_shift_m, want->placement.lateral_shift_m, kRel, "shift");
    ExpectRelNear(c.placement.yaw_rad, want->placement.yaw_rad, kRel, "placed yaw");
    ExpectRelNear(c.placement.roll_rad, want->placement.roll_rad, kRel, "placed roll");
    EXPECT_EQ(c.placement.rolling_radius_m, want->placement.rolling_radius_m);
    ExpectRelNear(c.vertical_force_N, want->vertical_force_N, kRel, "load");
    ExpectRelNear(c.motion.speed_m_s, want->motion.speed_m_s, kRel, "wheel speed");
    EXPECT_EQ(c.motion.yaw_velocity_rad_s, want->motion.yaw_velocity_rad_s);
    EXPECT_EQ(c.motion.lateral_velocity_m_s, want->motion.lateral_velocity_m_s);
    ASSERT_TRUE(c.motion.pitch_velocity_rad_s && want->motion.pitch_velocity_rad_s);
    ExpectRelNear(*c.motion.pitch_velocity_rad_s, *want->motion.pitch_velocity_rad_s, kRel,
                  "pitch velocity");
    EXPECT_EQ(c.friction, want->friction);
    ExpectRelNear(c.weight, want->weight, 1e-15, "weight");
  }
}

// A one-step two-rail wear run on collective traffic wears both rails, and counts MGT by the
// collective's axle load.
TEST(CollectiveTrafficTest, OneStepWearsBothRails) {
  const std::string csv =
      "weight_m,side,V_m_s,y_mm,yaw_mrad,roll_mrad,Q_N,xi,mu\n"
      "0.2,high,20,5.0,2.0,-1.5,85000,-0.001,0.35\n"
      "0.2,low,20,5.0,2.0,-1.5,75000,0.001,0.35\n"
      "0.2,high,20,1.0,-1.0,-0.3,80000,0.0,0.35\n"
      "0.2,low,20,1.0,-1.0,-0.3,80000,0.0,0.35\n";
  const LoadCollective lc = BinLoadCollective(ParseMbsTimeHistory(csv, "x.csv"), {});
  WearStudy study = CollectiveStudy(VehicleStudy(), lc);
  study.curve.radius_m = 600.0;
  const WearState s0 = MakeInitialState(study);
  const StepResult step = RunWearStep(study, UnwornRails::Of(s0), s0, 1e6);
  ASSERT_EQ(step.cases.size(), 4u);
  ASSERT_TRUE(step.low_rail);
  EXPECT_GT(step.measures.worn_area_m2, 0.0);
  EXPECT_GT(step.low_rail->measures.worn_area_m2, 0.0);
  EXPECT_GT(step.step_passes, 0.0);
  ExpectRelNear(step.state.mgt, step.step_passes * 160000.0 / kGravity_m_s2 / 1e9, 1e-12, "MGT");
}

}  // namespace
}  // namespace railwear
