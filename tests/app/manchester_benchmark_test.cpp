// The Manchester contact benchmark, case A-2.2 (examples/manchester/, inputs in
// ../shared/reference/README.md §5b): the trend of the 21 cases with yaw in the contact geometry.
// Skipped with a message when ../shared (the benchmark's profile files) is absent.
#include <cmath>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app/scene.h"
#include "core/contact/wheelset_contact.h"

namespace railwear::app {
namespace {

std::string CaseFile(int n) {
  return fmt::format("{}/examples/manchester/case_{:02d}.toml", RAILWEAR_SOURCE_DIR, n);
}

bool SharedProfilesPresent() {
  return std::filesystem::exists(std::string(RAILWEAR_SHARED_DIR) +
                                 "/data/profiles/MBench_S1002_v3.prw");
}

// The right wheel's patch carrying the largest normal force.
const PatchResult& MainPatch(const ContactResult& r) {
  const PatchResult* best = &r.patches.at(0);
  for (const auto& p : r.patches) {
    if (p.normal_force_N > best->normal_force_N) best = &p;
  }
  return *best;
}

struct Solved {
  Scene scene;
  WheelsetResult result;
};
Solved Solve(int n) {
  Solved s{LoadScene(CaseFile(n)), {}};
  WheelsetProblem problem;
  problem.wheel_rail = s.scene.problem;
  problem.track = *s.scene.track;
  problem.wheelset = *s.scene.wheelset;
  s.result = SolveWheelset(problem);
  EXPECT_EQ(s.result.right.status, SolverStatus::kConverged) << "case " << n;
  EXPECT_EQ(s.result.left.status, SolverStatus::kConverged) << "case " << n;
  return s;
}

TEST(ManchesterBenchmark, ContactMovesFromTreadToGaugeCornerToFlange) {
  if (!SharedProfilesPresent()) {
    GTEST_SKIP() << "../shared/data/profiles/ is absent: the benchmark's profile files are read "
                    "from there, never copied into the repository";
  }
  // The right wheel's main contact angle: tread (a few degrees) at y_ws = 0, the gauge corner
  // (15-45 degrees) at 5.5-6 mm, the flange (55-75 degrees) from 6.5 mm on, as the benchmark's
  // reference solution has it; at the largest shifts the flange carries the whole vertical load.
  const double tread = MainPatch(Solve(1).result.right).contact_angle_rad * 180 / M_PI;
  EXPECT_LT(std::abs(tread), 5.0);
  const double corner = MainPatch(Solve(12).result.right).contact_angle_rad * 180 / M_PI;
  EXPECT_GT(corner, 15.0);
  EXPECT_LT(corner, 45.0);
  for (int n : {14, 21}) {
    const Solved s = Solve(n);
    const ContactResult& right = s.result.right;
    const PatchResult& flange = MainPatch(right);
    const double angle = flange.contact_angle_rad * 180 / M_PI;
    EXPECT_GT(angle, 55.0) << "case " << n;
    EXPECT_LT(angle, 75.0) << "case " << n;
    EXPECT_NEAR(flange.vertical_force_N, right.vertical_force_N, 0.01 * right.vertical_force_N)
        << "case " << n << ": the flange carries the load";
  }
}

TEST(ManchesterBenchmark, FlangeContactLeadsTheAxleByTheClosedForm) {
  if (!SharedProfilesPresent()) {
    GTEST_SKIP() << "../shared/data/profiles/ is absent: the benchmark's profile files are read "
                    "from there, never copied into the repository";
  }
  // The pressure centre's lead over the axle line through it, against r tan(gamma) tan(psi) /
  // cos(psi) with the patch's contact angle gamma and the wheel radius at the contact point
  // (yawed_wheel.h). 3 %: the pressure centre averages the lead over a patch whose angle varies
  // by a few degrees across it (the closed form is exact at a point).
  for (int n : {14, 17, 21}) {
    const Solved s = Solve(n);
    const double psi = s.scene.wheelset->yaw_rad;
    const PatchResult& flange = MainPatch(s.result.right);
    const WheelPose& pose = s.result.placement.right;
    const WheelRailGeometry geom(s.scene.problem.wheel_profile, s.scene.problem.rail_profile, pose);
    double radius = 0.0, closest = 1e300;  // the wheel radius at the candidate nearest the patch
    for (const auto& c : geom.FindCandidates(1e-4)) {
      const double d = std::abs(c.y_m - flange.contact_point_yz_m.x());
      if (d < closest) {
        closest = d;
        radius = c.wheel_radius_m;
      }
    }
    const double y_w = flange.contact_point_yz_m.x() - pose.lateral_shift_m;
    const double lead = flange.contact_x_m + y_w * std::tan(psi);
    const double closed =
        radius * std::tan(flange.contact_angle_rad) * std::tan(psi) / std::cos(psi);
    EXPECT_NEAR(lead, closed, 0.03 * closed) << "case " << n;
    std::printf("[ measured ] case %d: lead %.2f mm, closed form %.2f mm at %.1f deg\n", n,
                lead * 1e3, closed * 1e3, flange.contact_angle_rad * 180 / M_PI);
  }
}

}  // namespace
}  // namespace railwear::app
