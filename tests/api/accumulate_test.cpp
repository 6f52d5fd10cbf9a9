// Wear for co-simulation (rw_accumulate): the depth a co-simulation accumulates over steps of a
// fixed state equals the per-pass depth `railwear wear` computes for that state
// (wear/pass_depth.h CalcPatchPassDepth summed over the patches, as the wear loop's load case
// does, on the contact the CLI solves), times the passes; the field is per rail and starts again
// when the rail, its cant or the law changes.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/contact_command.h"
#include "app/scene.h"
#include "railwear/railwear.h"
#include "tests/api/scene_to_api.h"
#include "wear/pass_depth.h"

namespace railwear::test {
namespace {

namespace fs = std::filesystem;

// Ten steps of 0.1 pass against one pass: the sum of ten products rounds differently from the
// one product by a few ulps of the largest bin; 1e-12 of the largest depth bounds that with a
// wide margin (the parity tolerance).
constexpr double kAccumulateRelTol = 1e-12;

rw_wear DefaultWear() {
  rw_wear w{};
  w.struct_size = sizeof w;
  rw_init_wear(&w);
  return w;
}

std::vector<double> Depth(rw_problem* p, int rail) {
  size_t n = 0;
  EXPECT_EQ(rw_get_depth_count(p, rail, &n), RW_OK) << rw_last_error(p);
  std::vector<double> d(n);
  EXPECT_EQ(rw_get_depth(p, rail, n, nullptr, d.data()), RW_OK) << rw_last_error(p);
  return d;
}

double MaxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// The wear loop's per-pass depth of a converged contact: every patch's CalcPatchPassDepth on
// the rail it was solved on, summed (wear/wear_simulation.cpp, friction-zone factor 1).
std::vector<double> WearCommandPassDepth(const ContactResult& r, const Profile& rail,
                                         double hardness_Pa, double speed_m_s) {
  const WearGrid grid = WearGrid::ForProfile(rail, 1e-4);
  std::vector<double> out(static_cast<size_t>(grid.n), 0.0);
  for (const PatchResult& patch : r.patches) {
    const std::vector<double> d =
        CalcPatchPassDepth(patch, rail, WearLaw{}, hardness_Pa, speed_m_s, grid);
    for (size_t b = 0; b < d.size(); ++b) out[b] += d[b];
  }
  return out;
}

TEST(ApiAccumulate, TenStepsOfATenthEqualTheWearCommandsPerPassDepth) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / "rolling_gauge_corner.toml";
  const app::Scene scene = app::LoadScene(path.string());
  const ContactCaseResult cli = SolveContactCase(app::ToContactCase(scene));
  ASSERT_EQ(cli.wheel.status, SolverStatus::kConverged);
  const std::vector<double> expected =
      WearCommandPassDepth(cli.wheel, scene.problem.rail_profile,
                           scene.problem.rail_material.hardness_Pa, *scene.speed_m_s);
  ASSERT_GT(MaxAbs(expected), 0.0);

  rw_problem* p = nullptr;
  ASSERT_EQ(rw_create(RW_PROBLEM_WHEEL, &p), RW_OK);
  SetUpFromScene(p, scene);
  const rw_wear wear = DefaultWear();
  ASSERT_EQ(rw_set_wear(p, &wear), RW_OK) << rw_last_error(p);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);

  // One pass: bit for bit.
  ASSERT_EQ(rw_accumulate(p, 1.0), RW_OK) << rw_last_error(p);
  const std::vector<double> one = Depth(p, 0);
  ASSERT_EQ(one.size(), expected.size());
  for (size_t b = 0; b < one.size(); ++b) ASSERT_EQ(one[b], expected[b]) << "bin " << b;

  // Ten steps of a tenth of a pass, each with its own calculate of the same state.
  ASSERT_EQ(rw_reset_depth(p), RW_OK);
  for (int step = 0; step < 10; ++step) {
    ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
    ASSERT_EQ(rw_accumulate(p, 0.1), RW_OK) << rw_last_error(p);
  }
  const std::vector<double> ten = Depth(p, 0);
  const double scale = MaxAbs(expected);
  for (size_t b = 0; b < ten.size(); ++b) {
    ASSERT_NEAR(ten[b], expected[b], kAccumulateRelTol * scale) << "bin " << b;
  }
  // The bins' centres: arc length from the rail profile's first point.
  std::vector<double> s(ten.size());
  ASSERT_EQ(rw_get_depth(p, 0, s.size(), s.data(), nullptr), RW_OK);
  EXPECT_DOUBLE_EQ(s[0], 0.5e-4);
  EXPECT_DOUBLE_EQ(s[1] - s[0], 1e-4);
  // The single wheel has no left rail's wear.
  EXPECT_EQ(MaxAbs(Depth(p, 1)), 0.0);
  rw_destroy(p);
}

TEST(ApiAccumulate, ANewRailOrLawStartsTheFieldAgainAndANewStateKeepsIt) {
  const fs::path path = fs::path(RAILWEAR_SOURCE_DIR) / "examples" / "rolling_gauge_corner.toml";
  const app::Scene scene = app::LoadScene(path.string());
  rw_problem* p = nullptr;
  ASSERT_EQ(rw_create(RW_PROBLEM_WHEEL, &p), RW_OK);
  SetUpFromScene(p, scene);
  rw_model m{};
  m.struct_size = sizeof m;
  rw_init_model(&m);
  m.accuracy = RW_ACCURACY_DRAFT;
  m.effects = RW_EFFECT_TANGENTIAL;
  ASSERT_EQ(rw_set_model(p, &m), RW_OK);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  ASSERT_EQ(rw_accumulate(p, 2.0), RW_OK) << rw_last_error(p);
  const double worn = MaxAbs(Depth(p, 0));
  EXPECT_GT(worn, 0.0);
  rw_state s{};
  s.struct_size = sizeof s;
  rw_init_state(&s);
  s.lateral_m = -4e-3;
  s.vertical_force_N = 100e3;
  s.speed_m_s = 20.0;
  ASSERT_EQ(rw_set_state(p, &s), RW_OK);
  EXPECT_EQ(MaxAbs(Depth(p, 0)), worn);                   // a new state keeps the field
  EXPECT_EQ(rw_accumulate(p, 1.0), RW_ERROR_CALL_ORDER);  // but there is no result to add
  EXPECT_EQ(MaxAbs(Depth(p, 0)), worn);
  rw_geometry g{};
  g.struct_size = sizeof g;
  rw_init_geometry(&g);
  g.rail_cant = 1.0 / 20.0;
  ASSERT_EQ(rw_set_geometry(p, &g), RW_OK);
  EXPECT_EQ(MaxAbs(Depth(p, 0)), 0.0);  // another cant: another rail
  const rw_wear wear = DefaultWear();
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  ASSERT_EQ(rw_accumulate(p, 1.0), RW_OK) << rw_last_error(p);
  EXPECT_GT(MaxAbs(Depth(p, 0)), 0.0);
  ASSERT_EQ(rw_set_wear(p, &wear), RW_OK);
  EXPECT_EQ(MaxAbs(Depth(p, 0)), 0.0);
  rw_destroy(p);
}

TEST(ApiAccumulate, AWheelsetWearsBothRails) {
  rw_problem* p = nullptr;
  ASSERT_EQ(rw_create(RW_PROBLEM_WHEELSET, &p), RW_OK);
  ASSERT_EQ(rw_set_profile_file(p, RW_BODY_WHEEL, "builtin:S1002"), RW_OK);
  ASSERT_EQ(rw_set_profile_file(p, RW_BODY_RAIL, "builtin:UIC60"), RW_OK);
  rw_geometry g{};
  g.struct_size = sizeof g;
  rw_init_geometry(&g);
  g.rail_cant = 1.0 / 40.0;
  ASSERT_EQ(rw_set_geometry(p, &g), RW_OK);
  rw_material steel{};
  steel.struct_size = sizeof steel;
  rw_init_material(&steel);
  rw_material rail = steel;
  rail.hardness_Pa = 2.6e9;
  ASSERT_EQ(rw_set_materials(p, &steel, &rail), RW_OK);
  rw_model m{};
  m.struct_size = sizeof m;
  rw_init_model(&m);
  m.accuracy = RW_ACCURACY_DRAFT;
  m.effects = RW_EFFECT_TANGENTIAL;
  ASSERT_EQ(rw_set_model(p, &m), RW_OK);
  ASSERT_EQ(rw_set_friction(p, 0.3), RW_OK);
  rw_state s{};
  s.struct_size = sizeof s;
  rw_init_state(&s);
  s.lateral_m = 3e-3;
  s.yaw_rad = 4e-3;
  s.vertical_force_N = 60e3;
  s.speed_m_s = 10.0;
  ASSERT_EQ(rw_set_state(p, &s), RW_OK);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  ASSERT_EQ(rw_accumulate(p, 1.0), RW_OK) << rw_last_error(p);
  EXPECT_GT(MaxAbs(Depth(p, 0)), 0.0);
  EXPECT_GT(MaxAbs(Depth(p, 1)), 0.0);
  rw_destroy(p);
}

}  // namespace
}  // namespace railwear::test
