// End-to-end tests of SolveContact: Hertz cases through the whole pipeline (placement, search,
// grid, influence, solve), properties, conformal grooves, two-point contact, no contact.
#include "core/contact/contact_solver.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "core/profile/profile_io.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

struct HertzCase {
  const char* name;
  double force_N, R_rail_m, nu, area_mm2, p0_MPa;
};
// Reference README §1, computed cases (E = 210 GPa; wheel R = 460 mm, laterally flat).
const HertzCase kHertzCases[] = {
    {"H1", 100e3, 0.300, 0.30, 121.21, 1237.6},
    {"H2", 125e3, 0.300, 0.30, 140.65, 1333.1},
    {"H3", 100e3, 0.080, 0.30, 72.48, 2069.6},
    {"H4", 10e3, 0.300, 0.28, 26.33, 569.6},
};

ContactProblem HertzProblem(const HertzCase& c, ModelKind kind, AccuracyPreset accuracy) {
  ContactProblem p;
  p.rail_profile = testing::ArcProfile(c.R_rail_m, +1.0, 0.06 / c.R_rail_m * 0.9, 1201);
  p.wheel_profile = testing::FunctionProfile([](double) { return 0.0; }, -0.04, 0.04, 161);
  p.wheel_material = {210e9, c.nu};
  p.rail_material = {210e9, c.nu};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = c.force_N;
  p.model = MakeModelOptions(kind);
  p.model.accuracy = accuracy;
  return p;
}

double RelErr(double value, double reference) { return std::abs(value / reference - 1.0); }

TEST(SolveContact, AccuracyPresetsReachTheirErrorsOnHertzCases) {
  // Issue 2: presets are defined by the error they reach on H1-H4 (about 5 %, 1 %, 0.2 %), and
  // `halfspace` must be within 1 % at standard and 0.3 % at reference. The measured errors are
  // printed (the README quotes them): ctest -R AccuracyPresets --verbose
  struct Bound {
    AccuracyPreset preset;
    double tolerance;
  };
  const Bound bounds[] = {{AccuracyPreset::kDraft, 0.05},
                          {AccuracyPreset::kStandard, 0.01},
                          {AccuracyPreset::kReference, 0.003},
                          {AccuracyPreset::kFine, 0.003}};
  for (const auto& [preset, tol] : bounds) {
    double worst_area = 0.0, worst_p0 = 0.0, time_ms = 0.0;
    for (const auto& c : kHertzCases) {
      const ContactResult r = SolveContact(HertzProblem(c, ModelKind::kHalfspace, preset));
      ASSERT_EQ(r.status, SolverStatus::kConverged) << c.name << " " << r.message;
      ASSERT_EQ(r.patches.size(), 1u);
      const double ea = RelErr(r.area_m2 * 1e6, c.area_mm2);
      const double ep = RelErr(r.p_max_Pa * 1e-6, c.p0_MPa);
      EXPECT_LT(ea, tol) << c.name << " " << ToString(preset) << " area " << r.area_m2 * 1e6;
      EXPECT_LT(ep, tol) << c.name << " " << ToString(preset) << " p0 " << r.p_max_Pa * 1e-6;
      EXPECT_NEAR(r.vertical_force_N, c.force_N, 1e-8 * c.force_N) << c.name;  // load balance
      worst_area = std::max(worst_area, ea);
      worst_p0 = std::max(worst_p0, ep);
      time_ms += r.time_s * 1e3 / std::size(kHertzCases);
    }
    std::printf(
        "[ measured ] halfspace %-9s worst over H1-H4: area %.3f %%, p0 %.3f %%, "
        "mean time %.0f ms\n",
        std::string(ToString(preset)).c_str(), 100 * worst_area, 100 * worst_p0, time_ms);
  }
}

TEST(SolveContact, HertzModelIsAnalytic) {
  for (const auto& c : kHertzCases) {
    const ContactResult r =
        SolveContact(HertzProblem(c, ModelKind::kHertz, AccuracyPreset::kStandard));
    ASSERT_EQ(r.status, SolverStatus::kConverged);
    ASSERT_EQ(r.patches.size(), 1u);
    // The table's 5 significant figures.
    EXPECT_LT(RelErr(r.area_m2 * 1e6, c.area_mm2), 2e-4) << c.name;
    EXPECT_LT(RelErr(r.p_max_Pa * 1e-6, c.p0_MPa), 2e-4) << c.name;
  }
}

TEST(SolveContact, SymmetricCaseGivesSymmetricPressureAndComplementarity) {
  const ContactProblem p =
      HertzProblem(kHertzCases[0], ModelKind::kHalfspace, AccuracyPreset::kDraft);
  const ContactResult r = SolveContact(p);
  ASSERT_EQ(r.status, SolverStatus::kConverged);
  const PatchGrid& g = r.patches[0].grid;
  const Eigen::VectorXd& pr = r.patches[0].pressure_Pa;
  const double pmax = pr.maxCoeff();
  double sum_w = 0.0;
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double v = pr[g.Index(i, j)];
      EXPECT_GE(v, 0.0);
      EXPECT_NEAR(v, pr[g.Index(g.nx - 1 - i, j)], 1e-6 * pmax);  // mirror in x
      sum_w += v * g.CellArea() * (-g.normal_yz[j].y());
    }
  }
  EXPECT_NEAR(sum_w, kHertzCases[0].force_N, 1e-8 * kHertzCases[0].force_N);
  // Mirror in s about the contact point (the crown is symmetric and the wheel flat).
  const int j0 = static_cast<int>(std::lround(-g.s0_m / g.ds_m));
  for (int dj = 1; j0 - dj >= 0 && j0 + dj < g.ns; ++dj) {
    for (int i = 0; i < g.nx; ++i) {
      EXPECT_NEAR(pr[g.Index(i, j0 - dj)], pr[g.Index(i, j0 + dj)], 1e-6 * pmax);
    }
  }
}

ContactProblem GrooveProblem(double groove_R_m, KernelModel kernel, double force_N = 10e3) {
  ContactProblem p;
  p.wheel_profile = MakeCircle(0.010, BodyRole::kWheel);
  p.rail_profile = MakeGroove(groove_R_m, BodyRole::kRail);
  p.wheel_material = {210e9, 0.28};
  p.rail_material = {210e9, 0.28};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = force_N;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.kernel = kernel;
  p.model.accuracy = AccuracyPreset::kDraft;
  return p;
}

TEST(SolveContact, ConformalGroovePatchIsCurvedAndGrowsWithConformity) {
  // Issue 2: a 10 mm wheel in 10.25 and 10.02 mm grooves: the patch is found and curved; its
  // area grows and its peak pressure falls as the groove gets closer in radius; the seed's
  // kernel gives a smaller area and a higher peak than Boussinesq on the same curved grid.
  ContactResult r[2][2];
  const double radii[2] = {0.01025, 0.01002};
  const KernelModel kernels[2] = {KernelModel::kGolubenko, KernelModel::kBoussinesq};
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      r[a][b] = SolveContact(GrooveProblem(radii[a], kernels[b]));
      ASSERT_EQ(r[a][b].status, SolverStatus::kConverged) << r[a][b].message;
      ASSERT_EQ(r[a][b].patches.size(), 1u);
      // Curved: the surface normal turns by more than 10 degrees across the contact.
      const PatchResult& pr = r[a][b].patches[0];
      double n_lo = 1e9, n_hi = -1e9;
      for (int j = 0; j < pr.grid.ns; ++j) {
        bool any = false;
        for (int i = 0; i < pr.grid.nx; ++i) any |= pr.pressure_Pa[pr.grid.Index(i, j)] > 0;
        if (!any) continue;
        const double ang = std::atan2(pr.grid.normal_yz[j].x(), -pr.grid.normal_yz[j].y());
        n_lo = std::min(n_lo, ang);
        n_hi = std::max(n_hi, ang);
      }
      EXPECT_GT(n_hi - n_lo, 10.0 * M_PI / 180.0) << radii[a];
    }
  }
  for (int b = 0; b < 2; ++b) {
    EXPECT_GT(r[1][b].area_m2, r[0][b].area_m2);
    EXPECT_LT(r[1][b].p_max_Pa, r[0][b].p_max_Pa);
  }
  for (int a = 0; a < 2; ++a) {
    EXPECT_LT(r[a][0].area_m2, r[a][1].area_m2);
    EXPECT_GT(r[a][0].p_max_Pa, r[a][1].p_max_Pa);
  }
}

TEST(SolveContact, SharedGrooveFilesGiveTheSamePatchAsBuiltIns) {
  // The conformal case on the shared files themselves: circ_r10.prw in groove_r1025.prr
  // and groove_r1002.prr. Same trend as the built-ins (area up, peak down as the groove closes
  // in), and the same patch as the built-in profiles of the same radii.
  const std::filesystem::path dir = std::filesystem::path(RAILWEAR_SHARED_DIR) / "data/profiles";
  if (!std::filesystem::exists(dir / "groove_r1025.prr")) {
    GTEST_SKIP() << "shared profiles not found at " << dir << " (a bare clone): skipped";
  }
  const struct {
    double radius_m;
    const char* file;
  } grooves[2] = {{0.01025, "groove_r1025.prr"}, {0.01002, "groove_r1002.prr"}};
  ContactResult files[2];
  for (int k = 0; k < 2; ++k) {
    ContactProblem p = GrooveProblem(grooves[k].radius_m, KernelModel::kGolubenko);
    const ContactResult built_in = SolveContact(p);
    p.wheel_profile = ReadProfileFile((dir / "circ_r10.prw").string()).profile;
    p.rail_profile = ReadProfileFile((dir / grooves[k].file).string()).profile;
    files[k] = SolveContact(p);
    ASSERT_EQ(files[k].status, SolverStatus::kConverged) << files[k].message;
    ASSERT_EQ(files[k].patches.size(), 1u);
    // Different point sets and spline fits of the same circles: within 2 %.
    EXPECT_NEAR(files[k].area_m2, built_in.area_m2, 0.02 * built_in.area_m2) << grooves[k].file;
    EXPECT_NEAR(files[k].p_max_Pa, built_in.p_max_Pa, 0.02 * built_in.p_max_Pa) << grooves[k].file;
  }
  EXPECT_GT(files[1].area_m2, files[0].area_m2);
  EXPECT_LT(files[1].p_max_Pa, files[0].p_max_Pa);
}

TEST(SolveContact, NoContactIsAStatusNotAnError) {
  ContactProblem p = HertzProblem(kHertzCases[0], ModelKind::kHalfspace, AccuracyPreset::kDraft);
  p.load = {};
  p.load.approach_m = -1e-4;  // profiles held apart
  const ContactResult r = SolveContact(p);
  EXPECT_EQ(r.status, SolverStatus::kNoContact);
  EXPECT_TRUE(r.patches.empty());
  EXPECT_FALSE(r.message.empty());
  p.placement.lateral_shift_m = 1.0;  // no lateral overlap at all
  p.load.approach_m = 1e-4;
  EXPECT_EQ(SolveContact(p).status, SolverStatus::kNoContact);
}

TEST(SolveContact, PrescribedApproachReproducesTheLoad) {
  const ContactProblem pf =
      HertzProblem(kHertzCases[3], ModelKind::kHalfspace, AccuracyPreset::kStandard);
  const ContactResult rf = SolveContact(pf);
  ContactProblem pa = pf;
  pa.load = {};
  pa.load.approach_m = rf.approach_m;
  const ContactResult ra = SolveContact(pa);
  ASSERT_EQ(ra.status, SolverStatus::kConverged);
  EXPECT_NEAR(ra.vertical_force_N, kHertzCases[3].force_N, 2e-3 * kHertzCases[3].force_N);
  // Hertz: delta = 22.62 um for H4; the discrete half-space solution is within 1 %.
  EXPECT_NEAR(rf.approach_m, 22.62e-6, 0.01 * 22.62e-6);
}

TEST(SolveContact, BadLoadIsInputError) {
  ContactProblem p = HertzProblem(kHertzCases[0], ModelKind::kHalfspace, AccuracyPreset::kDraft);
  p.load.approach_m = 1e-4;  // both given
  EXPECT_THROW(SolveContact(p), InputError);
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

TEST(SolveContact, TwoPointContactSharesOneApproach) {
  // A wheel with two lobes 40 mm apart (lateral radii 5 and 16.7 mm) on a flat rail; the second
  // lobe starts 20 um higher. Under 50 kN both carry load: two patches, one rigid approach, the
  // vertical forces add up to the load, and the numerical models agree with Hertz on the share.
  ContactProblem p;
  p.rail_profile = testing::FunctionProfile([](double) { return 0.0; }, -0.05, 0.05, 401);
  auto lobes = [](double y) {
    return -std::min(100.0 * (y + 0.02) * (y + 0.02), 30.0 * (y - 0.02) * (y - 0.02) + 2e-5);
  };
  p.wheel_profile = testing::FunctionProfile(lobes, -0.045, 0.045, 1801);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 50e3;
  ContactResult r[3];
  const ModelKind kinds[3] = {ModelKind::kHertz, ModelKind::kHalfspace, ModelKind::kConformal};
  for (int m = 0; m < 3; ++m) {
    p.model = MakeModelOptions(kinds[m]);
    p.model.kernel =
        KernelModel::kBoussinesq;  // the seed's kernel is stiffer; compare like with like
    r[m] = SolveContact(p);
    ASSERT_EQ(r[m].status, SolverStatus::kConverged) << ToString(kinds[m]) << r[m].message;
    ASSERT_EQ(r[m].patches.size(), 2u) << ToString(kinds[m]);
    EXPECT_NEAR(r[m].patches[0].vertical_force_N + r[m].patches[1].vertical_force_N, 50e3, 1e-6);
    EXPECT_NEAR(r[m].patches[0].contact_point_yz_m.x(), -0.02, 1e-3);
    EXPECT_NEAR(r[m].patches[1].contact_point_yz_m.x(), 0.02, 1e-3);
    EXPECT_GT(r[m].approach_m, 2e-5);  // the second lobe is pressed in
  }
  // Hertz is exact for these quadratic lobes up to discretisation: load share and approach
  // within the standard preset's ~1 %.
  for (int m = 1; m < 3; ++m) {
    EXPECT_NEAR(r[m].patches[1].vertical_force_N, r[0].patches[1].vertical_force_N, 0.02 * 50e3);
    EXPECT_NEAR(r[m].approach_m, r[0].approach_m, 0.02 * r[0].approach_m);
  }
}

}  // namespace
}  // namespace railwear

namespace railwear {
namespace {

// The planar grid's tangent plane at the solved pressure centre (core/contact/potential_area.h).
// A wide, nearly conformal patch over two gap minima 10 mm apart on a 100 mm crown, the one at
// -5 mm or the one at +5 mm the deeper by 0.2 um: the smallest gap, where the first grid is
// placed, jumps by 10 mm between the two, and with it the plane's angle by 2 w / R = 0.1 rad
// (5.7 degrees: what the Y25 wagon's low wheel met on a worn tread, docs/curving.md). The patch
// itself spans both minima and hardly moves. The plane follows the pressure centre, so the two
// solutions' contact angles agree within the re-centring's half-cell rule (ds / 2R), and each
// plane passes within half a cell of its patch's pressure centre.
TEST(SolveContact, PlanarPlaneFollowsThePressureCentreNotTheSmallestGap) {
  const double R = 0.1, w = 0.005, h = 2e-6;
  ContactProblem p;
  p.rail_profile = testing::ArcProfile(R, +1.0, 0.35, 1401);
  p.wheel_material = p.rail_material = {210e9, 0.28};
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 60e3;
  p.model = MakeModelOptions(ModelKind::kHalfspace);
  p.model.accuracy = AccuracyPreset::kStandard;
  double angle[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const double e = k == 0 ? -2e-7 : 2e-7;  // the deeper minimum at -w, then at +w
    auto wheel = [&](double y) {
      const double u = y / w;
      const double gap = h * (u * u - 1.0) * (u * u - 1.0) + e * u;
      return (R - std::sqrt(R * R - y * y)) - gap;
    };
    p.wheel_profile = testing::FunctionProfile(wheel, -0.03, 0.03, 1201);
    const ContactResult r = SolveContact(p);
    ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
    ASSERT_EQ(r.patches.size(), 1u);
    const PatchResult& patch = r.patches[0];
    const PatchGrid& g = patch.grid;
    ASSERT_TRUE(g.planar);
    // The plane's tangent point (s = 0 on the grid) against the pressure centre's lateral place.
    const double plane_y = g.point_yz_m[0].x() - g.S(0) * g.tangent_yz[0].x();
    EXPECT_LE(std::abs(plane_y - patch.contact_point_yz_m.x()), 0.5 * g.ds_m + 1e-9) << k;
    // A patch wider than the two minima: one connected contact, not a patch at one minimum.
    double s_lo = 1.0, s_hi = -1.0;
    for (int j = 0; j < g.ns; ++j) {
      if (patch.pressure_Pa.segment(g.Index(0, j), g.nx).maxCoeff() > 0.0) {
        s_lo = std::min(s_lo, g.S(j));
        s_hi = std::max(s_hi, g.S(j));
      }
    }
    EXPECT_GT(s_hi - s_lo, 2.0 * w) << k;
    angle[k] = patch.contact_angle_rad;
  }
  EXPECT_LT(std::abs(angle[1] - angle[0]), 0.1 * 2.0 * w / R);
}

}  // namespace
}  // namespace railwear
