// Wear for co-simulation (rw_accumulate): the depth a co-simulation accumulates over steps of a
// fixed state equals the per-pass depth `railwear wear` computes for that state, times the
// passes: against the `wear` command itself (a one-load-case wear scene run by the CLI, its
// stored per-pass depth read back from the database) and against the wear loop's own sum
// (wear/pass_depth.h CalcPatchPassDepth summed over the patches, on the contact the CLI
// solves); the field is per rail and starts again when the rail, its cant or the law changes.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/contact_command.h"
#include "app/scene.h"
#include "profiles_db/profile_store.h"
#include "railwear/railwear.h"
#include "tests/app/cli_runner.h"
#include "tests/api/rolling_wheel.h"
#include "tests/api/scene_to_api.h"
#include "wear/pass_depth.h"

namespace railwear::test {
namespace {

namespace fs = std::filesystem;

// Ten steps of 0.1 pass against one pass: the sum of ten products rounds differently from the
// one product by a few ulps of the largest bin; 1e-12 of the largest depth bounds that with a
// wide margin (the issue's parity tolerance).
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

// The `wear` command against N passes accumulated through the C API: a wear scene with one load
// case (the rolling_gauge_corner example's wheel, rail, materials, position, yaw, load, speed and
// friction as one [[traffic]] entry without a lateral spread, at draft accuracy, Archard's law)
// run one step by the CLI into a database; its stored per-pass depth (`depth_per_pass_nm`, the
// step's weighted mean depth per pass before smoothing) against the depth the handle
// accumulates over N calculate + accumulate(1 pass) steps of the same state, divided by N. The
// handle's rail is the run's stored step-0 rail (the wear loop resamples the unworn rail at
// its profile spacing before the first step), set as points with the same cant.
class ApiAccumulateCli : public CliFixture {};

// Per bin, relative to the bin's own depth: the stored depth went through nm (x 1e9, a rounding
// of 1 ulp each way) and N additions round by at most N ulps, some 1e-15 relative for N = 4;
// 1e-12 is the issue's parity tolerance. Zero bins must be zero in both.
constexpr double kCliParityRelTol = 1e-12;
constexpr int kPasses = 4;

TEST_F(ApiAccumulateCli, NPassesOfAFixedStateEqualTheWearCommandsStoredPerPassDepth) {
  const std::string scene = Write("one_case.toml", R"([scene]
name = "accumulate parity"
effects = ["normal", "tangential", "wear"]

[model]
kind = "conformal"
accuracy = "draft"
tangential = "fastsim"

[materials]
wheel = { E_MPa = 210000, nu = 0.28 }
rail = { E_MPa = 210000, nu = 0.28, hardness_MPa = 2600 }

[wheel]
profile = "builtin:S1002"
rolling_radius_mm = 460

[rail]
profile = "builtin:UIC60"
cant = "1:40"

[wear]
law = "archard"
max_depth_per_step_mm = 0.1
total_passes = 1e6
threads = 1

[[traffic]]
name = "one load case"
vertical_N = 100000
lateral_shift_mm = -4.0
yaw_mrad = 5.0
friction = 0.3
speed_m_s = 20.0
)");
  const Outcome run = Run("wear one_case.toml --db wear.sqlite --steps 1");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "wear.sqlite").string());
  const std::vector<RunInfo> runs = store.Runs();
  ASSERT_EQ(runs.size(), 1u);
  const StepRecord step = store.LoadStep(runs[0].id, 1);
  ASSERT_EQ(step.load_cases_json.size(), 1u);  // one load case: its weight is 1
  const Distribution* stored = nullptr;
  for (const Distribution& d : step.distributions) {
    if (d.kind == "depth_per_pass_nm") stored = &d;
  }
  ASSERT_NE(stored, nullptr);
  const Profile rail = store.LoadProfile(runs[0].id, 0);

  // The scene's wheel, rail, cant (1:40), radius (the default 460 mm), steel, model and friction
  // (tests/api/rolling_wheel.h), then the run's step-0 rail in place of the built-in and the
  // rail's hardness.
  rw_problem* p = MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_DRAFT);
  ASSERT_NE(p, nullptr);
  std::vector<double> yz;
  for (const Eigen::Vector2d& q : rail.points()) yz.insert(yz.end(), {q.x(), q.y()});
  RW_EXPECT_OK(p, rw_set_profile_points(p, RW_BODY_RAIL, yz.data(), rail.points().size()));
  rw_material steel{};
  steel.struct_size = sizeof steel;
  rw_init_material(&steel);  // 210 GPa, 0.28: the scene's
  rw_material rail_steel = steel;
  rail_steel.hardness_Pa = 2600e6;
  RW_EXPECT_OK(p, rw_set_materials(p, &steel, &rail_steel));
  const rw_wear wear = DefaultWear();  // Archard at the scene's default k, 0.1 mm bins
  RW_EXPECT_OK(p, rw_set_wear(p, &wear));
  rw_state s{};
  s.struct_size = sizeof s;
  rw_init_state(&s);
  s.lateral_m = -4e-3;
  s.yaw_rad = 5e-3;
  s.vertical_force_N = 100e3;
  s.speed_m_s = 20.0;
  for (int pass = 0; pass < kPasses; ++pass) {
    RW_EXPECT_OK(p, rw_set_state(p, &s));
    ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
    ASSERT_EQ(rw_accumulate(p, 1.0), RW_OK) << rw_last_error(p);
  }
  const std::vector<double> depth = Depth(p, 0);
  std::vector<double> centre(depth.size());
  ASSERT_EQ(rw_get_depth(p, 0, centre.size(), centre.data(), nullptr), RW_OK);
  rw_destroy(p);

  ASSERT_EQ(depth.size(), stored->value.size());
  int worn_bins = 0;
  for (size_t b = 0; b < depth.size(); ++b) {
    const double want = stored->value[b] * 1e-9;  // nm -> m
    const double got = depth[b] / kPasses;
    EXPECT_NEAR(got, want, kCliParityRelTol * std::abs(want)) << "bin " << b;
    if (want > 0.0) ++worn_bins;
    // The same bins: the stored centre is clipped to the profile's length (the last bin).
    if (stored->s_m[b] == centre[b] || b + 1 < depth.size()) {
      EXPECT_DOUBLE_EQ(stored->s_m[b], centre[b]) << "bin " << b;
    }
  }
  EXPECT_GT(worn_bins, 20);  // the patch spans a few millimetres of rail: tens of bins
}

}  // namespace
}  // namespace railwear::test
