// model.kind = "auto" (issue 6): the conformity measures against closed forms, the choice on a
// tread contact (not conformal) and a gauge-corner contact (conformal), Hertz only where the
// patch is Hertzian and no grid is needed, never the seed's kernel on a planar patch, and the
// check on the solved patch that catches a patch the estimate misses.
#include "core/contact/model_selection.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/contact_solver.h"
#include "core/profile/builtin_profiles.h"
#include "tests/core/geometry/geometry_test_util.h"

namespace railwear {
namespace {

const Material kSteel{210e9, 0.28};

// examples/tread.toml and examples/gauge_corner.toml: S1002 on UIC60 1:40, 100 kN, standard.
ContactProblem S1002OnUic60(double lateral_shift_mm, ModelKind kind) {
  static const Profile wheel = MakeS1002();
  static const Profile rail = ApplyCant(MakeUic60(), 1.0 / 40.0);
  ContactProblem p;
  p.wheel_profile = wheel;
  p.rail_profile = rail;
  p.wheel_material = p.rail_material = kSteel;
  p.placement.lateral_shift_m = lateral_shift_mm * 1e-3;
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 100e3;
  p.model = MakeModelOptions(kind);
  p.model.accuracy = AccuracyPreset::kStandard;
  return p;
}

// A laterally flat wheel on a circular crown of radius R: Hertzian (reference README §1).
ContactProblem CrownProblem(double R_m) {
  ContactProblem p;
  p.rail_profile = testing::ArcProfile(R_m, +1.0, 0.06 / R_m * 0.9, 1201);
  p.wheel_profile = testing::FunctionProfile([](double) { return 0.0; }, -0.04, 0.04, 161);
  p.wheel_material = p.rail_material = kSteel;
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 100e3;
  p.model = MakeModelOptions(ModelKind::kAuto);
  p.model.accuracy = AccuracyPreset::kStandard;
  return p;
}

bool StartsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(ModelSelection, ConformityOfACrownUnderAFlatWheelMatchesClosedForms) {
  // Crown R = 30 mm, flat wheel, K = 1/2: the intermediate normal bisects the rail normal (angle
  // t/R) and the vertical, so it turns by b/R over t in [-b, b]; cos(theta) drops to
  // cos(b/(2R)); the gap R(1 - cos(t/R)) departs from t^2/(2R) by b^4/(24 R^3) at t = b, i.e.
  // b^2/(12 R^2) of B0 b^2.
  const double R = 0.030, b = 0.003;
  const ContactProblem p = CrownProblem(R);
  const WheelRailGeometry geom(p.wheel_profile, p.rail_profile, {0.0, 0.0, 0.46});
  const auto cands = geom.FindCandidates(1e-6);
  ASSERT_EQ(cands.size(), 1u);
  const PatchConformity c = MeasureConformity(geom, cands[0], -b, b, 0.5);
  // The profiles are splines through 1201 and 161 points: curvature and normals to ~1e-5.
  constexpr double kSplineTolerance = 1e-4;
  EXPECT_NEAR(c.normal_turn_rad, b / R, kSplineTolerance * b / R);
  EXPECT_NEAR(c.approach_weight_change, 1.0 - std::cos(b / (2 * R)), 1e-3 * (b / R) * (b / R));
  EXPECT_NEAR(c.gap_deviation, b * b / (12 * R * R), 0.02 * b * b / (12 * R * R));
  EXPECT_NEAR(c.normal_angle_rad, 0.0, 1e-6);
  EXPECT_NEAR(c.lateral_radius_m, R, 1e-4 * R);
  EXPECT_FALSE(c.measured);
}

TEST(ModelSelection, LimitsTightenWithTheAccuracyPreset) {
  const AccuracyPreset order[] = {AccuracyPreset::kDraft, AccuracyPreset::kStandard,
                                  AccuracyPreset::kReference, AccuracyPreset::kFine};
  for (int k = 1; k < 4; ++k) {
    EXPECT_LE(MaxPlanarNormalTurn(order[k]), MaxPlanarNormalTurn(order[k - 1]));
    EXPECT_LE(MaxPlanarApproachWeightChange(order[k]), MaxPlanarApproachWeightChange(order[k - 1]));
    EXPECT_LE(MaxHertzGapDeviation(order[k]), MaxHertzGapDeviation(order[k - 1]));
  }
  // A patch between the standard and the draft limits is conformal at standard, planar at draft.
  PatchConformity c;
  c.t_lo_m = -2e-3;
  c.t_hi_m = 2e-3;
  c.normal_turn_rad = 0.5 * (MaxPlanarNormalTurn(AccuracyPreset::kDraft) +
                             MaxPlanarNormalTurn(AccuracyPreset::kStandard));
  c.gap_deviation = 1.0;
  ModelOptions o = MakeModelOptions(ModelKind::kAuto);
  o.accuracy = AccuracyPreset::kStandard;
  EXPECT_EQ(ChoosePatchModel(c, o, "").model, PatchModel::kConformal);
  o.accuracy = AccuracyPreset::kDraft;
  EXPECT_EQ(ChoosePatchModel(c, o, "").model, PatchModel::kHalfspace);
  // Explicit cells count as standard.
  o.cell_dx_m = o.cell_ds_m = 0.2e-3;
  EXPECT_EQ(ChoosePatchModel(c, o, "").model, PatchModel::kConformal);
}

TEST(ModelSelection, TreadContactIsNotConformal) {
  // examples/tread.toml: the centred wheel, tread on the rail crown.
  const ContactResult r = SolveContact(S1002OnUic60(-10.4, ModelKind::kAuto));
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  ASSERT_FALSE(r.patches.empty());
  for (const auto& p : r.patches) {
    EXPECT_NE(p.model.find("halfspace"), std::string::npos) << p.model;
    EXPECT_TRUE(StartsWith(p.model_reason, "halfspace: over the solved patch")) << p.model_reason;
    // The tread patch spans the rail's R300/R80 arcs: not Hertzian, said so.
    EXPECT_NE(p.model_reason.find("not Hertz: the gap departs"), std::string::npos)
        << p.model_reason;
  }
  // Same solution as the halfspace model (the choice adds no approximation of its own).
  const ContactResult h = SolveContact(S1002OnUic60(-10.4, ModelKind::kHalfspace));
  EXPECT_NEAR(r.area_m2, h.area_m2, 1e-9 * h.area_m2);
  EXPECT_NEAR(r.p_max_Pa, h.p_max_Pa, 1e-9 * h.p_max_Pa);
}

TEST(ModelSelection, GaugeCornerContactIsConformalWithTheBoussinesqKernel) {
  // examples/gauge_corner.toml: flange root on gauge corner, the normal turns by ~29 degrees.
  const ContactResult r = SolveContact(S1002OnUic60(-4.0, ModelKind::kAuto));
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].model, "conformal+boussinesq");
  EXPECT_TRUE(StartsWith(r.patches[0].model_reason, "conformal: over the estimated patch"))
      << r.patches[0].model_reason;
  ContactProblem cb = S1002OnUic60(-4.0, ModelKind::kConformal);
  cb.model.kernel = KernelModel::kBoussinesq;
  const ContactResult c = SolveContact(cb);
  EXPECT_NEAR(r.area_m2, c.area_m2, 1e-9 * c.area_m2);
  EXPECT_NEAR(r.p_max_Pa, c.p_max_Pa, 1e-9 * c.p_max_Pa);
}

TEST(ModelSelection, TheSeedKernelNeverReachesAPlanarPatch) {
  // DESIGN.md §1: Model B's constants do not tend to Hertz on flat patches. With the seed's
  // kernel asked for, auto keeps it for conformal patches only.
  ContactProblem tread = S1002OnUic60(-10.4, ModelKind::kAuto);
  tread.model.kernel = KernelModel::kGolubenko;
  const ContactResult t = SolveContact(tread);
  ASSERT_EQ(t.status, SolverStatus::kConverged);
  for (const auto& p : t.patches) EXPECT_EQ(p.model, "halfspace");
  ContactProblem corner = S1002OnUic60(-4.0, ModelKind::kAuto);
  corner.model.kernel = KernelModel::kGolubenko;
  const ContactResult c = SolveContact(corner);
  ASSERT_EQ(c.status, SolverStatus::kConverged);
  EXPECT_EQ(c.patches[0].model, "conformal+golubenko");
}

TEST(ModelSelection, HertzOnlyOnAHertzianPatchWithoutRolling) {
  // R 300 mm crown, flat wheel: the gap is Hertz's quadratic to 1e-4 over the patch.
  const ContactResult r = SolveContact(CrownProblem(0.300));
  ASSERT_EQ(r.status, SolverStatus::kConverged);
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].model, "hertz");
  EXPECT_TRUE(r.patches[0].hertz.has_value());
  EXPECT_TRUE(StartsWith(r.patches[0].model_reason, "hertz:")) << r.patches[0].model_reason;
  // Reference README §1, case H1 (nu = 0.3; ours 0.28): within Hertz's own change with nu.
  EXPECT_NEAR(r.area_m2 * 1e6, 121.21, 0.02 * 121.21);

  ContactProblem rolling = CrownProblem(0.300);
  RollingOptions o;
  o.motion.speed_m_s = 10.0;
  rolling.rolling = o;
  const ContactResult g = SolveContact(rolling);
  ASSERT_EQ(g.status, SolverStatus::kConverged) << g.message;
  EXPECT_EQ(g.patches[0].model, "halfspace");
  EXPECT_NE(g.patches[0].model_reason.find("rolling contact needs a grid"), std::string::npos)
      << g.patches[0].model_reason;
  EXPECT_TRUE(g.patches[0].rolling.has_value());
}

TEST(ModelSelection, TheSolvedPatchOverridesAnEstimateThatLooksPlanar) {
  // At -5.5 mm the tread patch spreads toward the gauge corner: estimated, it turns by 5.4
  // degrees (planar at standard); solved as halfspace, by 14 degrees. Auto re-solves it on the
  // conformal geometry.
  const ContactResult r = SolveContact(S1002OnUic60(-5.5, ModelKind::kAuto));
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].model, "conformal+boussinesq");
  EXPECT_TRUE(StartsWith(r.patches[0].model_reason, "conformal: over the solved patch"))
      << r.patches[0].model_reason;
}

TEST(ModelSelection, SteepFlangeContactIsNeverPlanar) {
  // At -3 mm the flange carries the wheel at 70 degrees; a planar grid fails there.
  for (AccuracyPreset a : {AccuracyPreset::kDraft, AccuracyPreset::kStandard}) {
    ContactProblem p = S1002OnUic60(-3.0, ModelKind::kAuto);
    p.model.accuracy = a;
    const ContactResult r = SolveContact(p);
    ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
    for (const auto& patch : r.patches) {
      EXPECT_EQ(patch.model, "conformal+boussinesq");
      EXPECT_NE(patch.model_reason.find("steeper than the 45 deg"), std::string::npos)
          << patch.model_reason;
    }
  }
}

TEST(ModelSelection, FixedModelsLabelTheirPatches) {
  const ContactResult h = SolveContact(S1002OnUic60(-4.0, ModelKind::kHertz));
  ASSERT_FALSE(h.patches.empty());
  EXPECT_EQ(h.patches[0].model, "hertz");
  EXPECT_TRUE(h.patches[0].model_reason.empty());
  const ContactResult c = SolveContact(S1002OnUic60(-4.0, ModelKind::kConformal));
  EXPECT_EQ(c.patches[0].model, "conformal+golubenko");
  EXPECT_TRUE(c.patches[0].model_reason.empty());
}

}  // namespace
}  // namespace railwear
