// Tests of the influence-constant fit (calibration/influence_fit.h): recovery of known
// constants from synthetic curves (eq. 4 plus noise and offsets) within two standard errors, the
// standard errors against the scatter of replicates, separate convex/concave sets, the per-curve
// offset, the conditioning reports (undetermined constants, correlated pairs, rank-deficient
// covariance), a contact target recovered through SolveContact, and bad input.
//
// Figures quoted in the README: ctest --test-dir build -R InfluenceFit --verbose | grep figure
#include "calibration/influence_fit.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "core/profile/builtin_profiles.h"
#include "tests/calibration/synthetic_curves.h"

namespace railwear {
namespace {

using testing::MakeSyntheticCurves;
using testing::SyntheticCurveSpec;

// The constants the synthetic data are made with (the example).
const InfluenceConstants kTruth{1.05, 0.6, 0.3};

bool Contains(const std::vector<std::string>& warnings, const std::string& part) {
  for (const auto& w : warnings) {
    if (w.find(part) != std::string::npos) return true;
  }
  return false;
}

std::string Joined(const std::vector<std::string>& warnings) {
  std::string out;
  for (const auto& w : warnings) out += w + "\n";
  return out;
}

// A convex R 15 and a concave R 15.5 body, all four curves each, 40 points from 0.5 to 20 mm,
// noise and offsets relative to each curve's RMS.
InfluenceFitData PaperExperiment(const InfluenceConstants& truth, double noise, double offset,
                                 unsigned seed, double step_mm = 0.5) {
  InfluenceFitData data;
  SyntheticCurveSpec convex;
  convex.noise = noise;
  convex.offset = offset;
  convex.distance_step_mm = step_mm;
  SyntheticCurveSpec concave = convex;
  concave.body = CurveBody::kConcave;
  concave.radius_mm = 15.5;
  data.curves.push_back({MakeSyntheticCurves(truth, convex, seed, "r15_convex.csv")});
  data.curves.push_back({MakeSyntheticCurves(truth, concave, seed + 1000, "r15_5_concave.csv")});
  return data;
}

const FittedConstant& Named(const InfluenceFitSummary& s, const std::string& name) {
  for (const auto& c : s.constants) {
    if (c.name == name) return c;
  }
  ADD_FAILURE() << "no constant " << name;
  return s.constants.front();
}

TEST(InfluenceFit, RecoversKnownConstantsWithinTwoStandardErrors) {
  const InfluenceFitData data = PaperExperiment(kTruth, 0.01, 0.05, 1);
  const InfluenceFitSummary s = FitInfluenceConstants(data, InfluenceFitOptions{});
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged) << s.message;
  EXPECT_TRUE(s.well_conditioned) << Joined(s.warnings);
  ASSERT_TRUE(s.covariance_available) << s.covariance_message;
  const double truth[3] = {kTruth.c_f, kTruth.c_z, kTruth.c_s};
  ASSERT_EQ(s.constants.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const FittedConstant& c = s.constants[k];
    ASSERT_TRUE(std::isfinite(c.standard_error) && c.standard_error > 0) << c.name;
    EXPECT_LT(std::abs(c.value - truth[k]), 2.0 * c.standard_error)
        << c.name << " " << c.value << " +- " << c.standard_error << " truth " << truth[k];
    std::printf(
        "[ figure ] recovery (1 %% noise, 5 %% offsets, 320 points): %s = %.4f +- %.4f "
        "(truth %.2f)\n",
        c.name.c_str(), c.value, c.standard_error, truth[k]);
  }
  // The correlation matrix: symmetric, unit diagonal, entries in [-1, 1].
  ASSERT_EQ(s.correlation.rows(), 3);
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(s.correlation(a, a), 1.0);
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(s.correlation(a, b), s.correlation(b, a), 1e-12);
      EXPECT_LE(std::abs(s.correlation(a, b)), 1.0 + 1e-12);
    }
  }
  std::printf(
      "[ figure ] recovery correlations: c_f,c_z %.3f  c_f,c_s %.3f  c_z,c_s %.3f; "
      "condition number %.3g\n",
      s.correlation(0, 1), s.correlation(0, 2), s.correlation(1, 2), s.condition_number);
  // s^2 estimates the noise: residuals are relative to each curve's RMS, noise 1 % of it.
  EXPECT_NEAR(std::sqrt(s.residual_variance), 0.01, 0.0015);
  // Every point is reported, before and after; the fit removed the starting misfit.
  int points = 0;
  for (const auto& c : s.curves) points += static_cast<int>(c.points.size());
  EXPECT_EQ(points, 320);
  EXPECT_EQ(s.num_residuals, 320);
  EXPECT_EQ(s.num_free_parameters, 3 + 8);
  EXPECT_GT(s.cost_before, 100 * s.cost_after);
  for (const auto& c : s.curves) EXPECT_LT(c.rms_after, 0.015) << c.Name();
  EXPECT_FALSE(s.ceres_brief_report.empty());
  EXPECT_NE(s.ceres_full_report.find("Termination"), std::string::npos);
}

// The standard errors are honest: over replicates with fresh noise the fitted constants scatter
// as the standard errors say (z = (fit - truth) / SE has an RMS near 1 and |z| < 2 about 95 % of
// the time).
TEST(InfluenceFit, StandardErrorsMatchTheScatterOfReplicates) {
  constexpr int kReplicates = 40;
  double sum_z2[3] = {0, 0, 0};
  int within[3] = {0, 0, 0};
  const double truth[3] = {kTruth.c_f, kTruth.c_z, kTruth.c_s};
  for (int r = 0; r < kReplicates; ++r) {
    const InfluenceFitSummary s =
        FitInfluenceConstants(PaperExperiment(kTruth, 0.02, 0.05, 100 + r), {});
    ASSERT_EQ(s.status, InfluenceFitStatus::kConverged);
    for (int k = 0; k < 3; ++k) {
      const double z = (s.constants[k].value - truth[k]) / s.constants[k].standard_error;
      sum_z2[k] += z * z;
      within[k] += std::abs(z) < 2.0;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const double rms_z = std::sqrt(sum_z2[k] / kReplicates);
    std::printf(
        "[ figure ] %d replicates (2 %% noise): %s RMS of (fit - truth)/SE %.2f, "
        "within 2 SE %d/%d\n",
        kReplicates, std::string(ToString(static_cast<InfluenceConstantName>(k))).c_str(), rms_z,
        within[k], kReplicates);
    // 40 samples: the RMS of z has a standard deviation of ~0.11 around 1.
    EXPECT_GT(rms_z, 0.7);
    EXPECT_LT(rms_z, 1.35);
    EXPECT_GE(within[k], 34);  // 95 % expected; 34 of 40 is 2.4 sigma below
  }
}

TEST(InfluenceFit, StandardErrorsShrinkWithLessNoiseAndMoreData) {
  const InfluenceFitSummary base = FitInfluenceConstants(PaperExperiment(kTruth, 0.02, 0.0, 7), {});
  const InfluenceFitSummary quiet =
      FitInfluenceConstants(PaperExperiment(kTruth, 0.01, 0.0, 7), {});
  const InfluenceFitSummary dense =
      FitInfluenceConstants(PaperExperiment(kTruth, 0.02, 0.0, 7, 0.125), {});
  for (int k = 0; k < 3; ++k) {
    const double se = base.constants[k].standard_error;
    // Half the noise: half the standard error (same seed, so the same noise pattern scaled).
    EXPECT_NEAR(quiet.constants[k].standard_error / se, 0.5, 0.02) << base.constants[k].name;
    // Four times the points over the same range: about half (the design is not exactly
    // replicated, so 0.4-0.6).
    const double ratio = dense.constants[k].standard_error / se;
    EXPECT_GT(ratio, 0.4) << base.constants[k].name;
    EXPECT_LT(ratio, 0.6) << base.constants[k].name;
    std::printf(
        "[ figure ] SE of %s: %.4f (2 %% noise, 320 points), %.4f (1 %%), %.4f (1256 "
        "points)\n",
        base.constants[k].name.c_str(), se, quiet.constants[k].standard_error,
        dense.constants[k].standard_error);
  }
}

TEST(InfluenceFit, SeparateSetsRecoveredFromConvexAndConcaveCurves) {
  InfluenceConstants truth;
  truth.separate = SeparateInfluenceConstants{{1.1, 0.7, 0.2}, {0.95, 0.5, 0.4}};
  const InfluenceFitData data = PaperExperiment(truth, 0.01, 0.05, 3);
  InfluenceFitOptions o;
  o.separate_bodies = true;
  const InfluenceFitSummary s = FitInfluenceConstants(data, o);
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged) << s.message;
  ASSERT_TRUE(s.fitted.IsSeparate());
  EXPECT_TRUE(s.well_conditioned) << Joined(s.warnings);
  ASSERT_EQ(s.constants.size(), 6u);
  const double want[6] = {1.1, 0.7, 0.2, 0.95, 0.5, 0.4};
  const char* names[6] = {"convex.c_f",  "convex.c_z",  "convex.c_s",
                          "concave.c_f", "concave.c_z", "concave.c_s"};
  for (int k = 0; k < 6; ++k) {
    const FittedConstant& c = Named(s, names[k]);
    EXPECT_LT(std::abs(c.value - want[k]), 2.0 * c.standard_error)
        << c.name << " " << c.value << " +- " << c.standard_error;
  }
  EXPECT_NEAR(s.fitted.separate->convex.c_f, 1.1, 0.02);
  EXPECT_NEAR(s.fitted.separate->concave.c_s, 0.4, 0.02);
  // The two sets come from different curves: no correlation between them.
  EXPECT_NEAR(s.correlation(0, 3), 0.0, 1e-6);
}

// A large constant offset (as a clamped FE body gives): fitted exactly with offsets, and a bias
// on the constants without them.
TEST(InfluenceFit, OffsetIsFittedExactlyWhenOnAndBiasesTheConstantsWhenOff) {
  const InfluenceFitData data = PaperExperiment(kTruth, 0.0, 0.3, 1);
  const InfluenceFitSummary on = FitInfluenceConstants(data, {});
  ASSERT_EQ(on.status, InfluenceFitStatus::kConverged) << on.message;
  EXPECT_NEAR(on.fitted.c_f, kTruth.c_f, 1e-7);
  EXPECT_NEAR(on.fitted.c_z, kTruth.c_z, 1e-7);
  EXPECT_NEAR(on.fitted.c_s, kTruth.c_s, 1e-7);
  // The offsets found are the ones added: the difference to the same curves without them.
  const InfluenceFitData clean = PaperExperiment(kTruth, 0.0, 0.0, 1);
  ASSERT_EQ(on.curves.size(), 8u);
  for (int c = 0; c < 8; ++c) {
    const auto& points = clean.curves[c / 4].curves.points;
    const double added =
        data.curves[c / 4].curves.points[(c % 4) * 40].w_m_per_N - points[(c % 4) * 40].w_m_per_N;
    EXPECT_NEAR(on.curves[c].offset_after_m_per_N, added, 1e-7 * std::abs(added))
        << on.curves[c].Name();
    EXPECT_LT(on.curves[c].max_after, 1e-7) << on.curves[c].Name();
  }
  InfluenceFitOptions off;
  off.fit_offsets = false;
  const InfluenceFitSummary biased = FitInfluenceConstants(data, off);
  ASSERT_EQ(biased.status, InfluenceFitStatus::kConverged) << biased.message;
  const double bias = biased.fitted.c_f / kTruth.c_f - 1.0;
  std::printf(
      "[ figure ] offsets of 30 %% of each curve's RMS: c_f %.6f with offsets, %.4f "
      "(%+.1f %%) without\n",
      on.fitted.c_f, biased.fitted.c_f, 100 * bias);
  EXPECT_GT(std::abs(bias), 0.05);
  for (const auto& c : biased.curves) EXPECT_EQ(c.offset_after_m_per_N, 0.0);
}

TEST(InfluenceFit, CsWithoutTangentialCurvesIsReportedNotDetermined) {
  SyntheticCurveSpec spec;
  spec.curves = {{CurveLoad::kNormal, CurvePath::kArc}, {CurveLoad::kNormal, CurvePath::kAxis}};
  spec.noise = 0.01;
  InfluenceFitData data;
  data.curves.push_back({MakeSyntheticCurves(kTruth, spec, 5, "normal_only.csv")});
  const InfluenceFitSummary s = FitInfluenceConstants(data, {});
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged) << s.message;
  EXPECT_FALSE(s.well_conditioned);
  EXPECT_TRUE(Contains(s.warnings, "c_s is not determined by these data: no tangential-load curve"))
      << Joined(s.warnings);
  const FittedConstant& cs = Named(s, "c_s");
  EXPECT_FALSE(cs.determined);
  EXPECT_EQ(cs.value, 0.25);  // held at its start
  EXPECT_TRUE(std::isnan(cs.standard_error));
  // The others are still fitted, with standard errors.
  EXPECT_TRUE(s.covariance_available) << s.covariance_message;
  EXPECT_LT(std::abs(Named(s, "c_f").value - kTruth.c_f), 2 * Named(s, "c_f").standard_error);
  EXPECT_TRUE(std::isnan(s.correlation(0, 2)));
}

TEST(InfluenceFit, CzWithAxisOnlyDataIsReportedNotDetermined) {
  SyntheticCurveSpec spec;
  spec.curves = {{CurveLoad::kNormal, CurvePath::kAxis}, {CurveLoad::kAxial, CurvePath::kAxis}};
  InfluenceFitData data;
  data.curves.push_back({MakeSyntheticCurves(kTruth, spec, 1, "axis_only.csv")});
  const InfluenceFitSummary s = FitInfluenceConstants(data, {});
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged) << s.message;
  EXPECT_TRUE(Contains(s.warnings,
                       "c_z is not determined by these data: no normal-load curve "
                       "with out-of-plane offsets"))
      << Joined(s.warnings);
  EXPECT_TRUE(Contains(s.warnings, "axis-only"));
  EXPECT_FALSE(Named(s, "c_z").determined);
  EXPECT_NEAR(Named(s, "c_f").value, kTruth.c_f, 1e-7);  // exact data: exact recovery
  EXPECT_NEAR(Named(s, "c_s").value, kTruth.c_s, 1e-7);
}

// c_z seen only through dn^2/rho^2 ~ s^2/(4 R^2) on a large radius, over a short stretch, with
// an offset: the c_z term is almost linear in s there, and 1/s, 1 and s are nearly collinear on
// [10, 20] mm. The fit still runs; the correlation is reported.
TEST(InfluenceFit, StronglyCorrelatedPairIsReported) {
  SyntheticCurveSpec spec;
  spec.radius_mm = 80.0;
  spec.curves = {{CurveLoad::kNormal, CurvePath::kArc}};
  spec.distance_min_mm = 10.0;
  spec.noise = 1e-4;
  InfluenceFitData data;
  data.curves.push_back({MakeSyntheticCurves(kTruth, spec, 9, "r80_arc.csv")});
  InfluenceFitOptions o;
  o.fit = {InfluenceConstantName::kCf, InfluenceConstantName::kCz};
  const InfluenceFitSummary s = FitInfluenceConstants(data, o);
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged) << s.message;
  EXPECT_FALSE(s.well_conditioned);
  EXPECT_TRUE(Contains(s.warnings, "strongly correlated")) << Joined(s.warnings);
  EXPECT_GT(s.condition_number, 100.0);
  std::printf(
      "[ figure ] R80 arc, 10-20 mm, offset fitted: condition number %.3g, c_z = %.3f "
      "+- %.3f; %s\n",
      s.condition_number, Named(s, "c_z").value, Named(s, "c_z").standard_error,
      Joined(s.warnings).c_str());
}

// The groove example at draft accuracy: targets computed with c_f = 0.95 are recovered from
// c_f = 0.75 through SolveContact with numeric derivatives.
ContactProblem Groove() {
  ContactProblem p;
  p.wheel_profile = MakeCircle(10e-3, BodyRole::kWheel);
  p.rail_profile = MakeGroove(10.25e-3, BodyRole::kRail);
  p.placement.rolling_radius_m = 0.46;
  p.load.vertical_force_N = 10000;
  p.model = MakeModelOptions(ModelKind::kConformal);
  p.model.accuracy = AccuracyPreset::kDraft;
  return p;
}

TEST(InfluenceFit, ContactTargetRecoveredThroughSolveContact) {
  ContactProblem truth_problem = Groove();
  truth_problem.model.constants.c_f = 0.95;
  const ContactResult truth = SolveContact(truth_problem);
  ASSERT_EQ(truth.status, SolverStatus::kConverged);
  InfluenceFitData data;
  data.contacts.push_back({"groove", Groove(), truth.area_m2, truth.p_max_Pa, 1.0});
  InfluenceFitOptions o;
  o.fit = {InfluenceConstantName::kCf};
  const InfluenceFitSummary s = FitInfluenceConstants(data, o);
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged) << s.message;
  std::printf(
      "[ figure ] groove (draft): c_f %.4f recovered as %.4f in %d iterations, %d "
      "solves, %.2f s\n",
      0.95, s.fitted.c_f, s.iterations, s.contact_solves, s.time_s);
  // The area is piecewise constant on a scale of ~1e-3 in c_f (influence_fit.h); p_max is
  // smooth, so the minimum is pinned by p_max to well within that.
  EXPECT_NEAR(s.fitted.c_f, 0.95, 2e-3);
  ASSERT_EQ(s.contacts.size(), 1u);
  const ContactFitReport& r = s.contacts[0];
  EXPECT_GT(r.area_before_m2 / r.target_area_m2 - 1.0, -0.5);
  EXPECT_LT(r.area_before_m2, r.target_area_m2);    // the stiffer start: smaller area ...
  EXPECT_GT(r.p_max_before_Pa, r.target_p_max_Pa);  // ... and a higher peak
  EXPECT_NEAR(r.p_max_after_Pa / r.target_p_max_Pa, 1.0, 2e-3);
  EXPECT_NEAR(r.area_after_m2 / r.target_area_m2, 1.0, 5e-3);
  // Near the solution the area residual is locally flat while its 1 % difference quotient is
  // not, so Levenberg-Marquardt converges linearly (cost x ~0.5 per step) rather than
  // quadratically: about 35 iterations of 3 solves here.
  EXPECT_LT(s.contact_solves, 150) << s.ceres_full_report;
}

// Points of a curve all at one distance: the constants' columns are constant there, like the
// offset's, so the Jacobian is exactly rank deficient and ceres::Covariance cannot be computed.
// The fit is still returned and the failure reported, not hidden.
TEST(InfluenceFit, RankDeficientCovarianceIsReportedAndTheFitReturned) {
  SyntheticCurveSpec spec;
  spec.curves = {{CurveLoad::kNormal, CurvePath::kAxis}};
  spec.distance_min_mm = 5.0;
  spec.distance_max_mm = 5.0;
  DisplacementCurves curves = MakeSyntheticCurves(kTruth, spec, 1, "one_distance.csv");
  for (int i = 0; i < 5; ++i) curves.points.push_back(curves.points.front());
  curves.points[1].w_m_per_N *= 1.001;  // repeated measurements that differ a little
  InfluenceFitData data;
  data.curves.push_back({curves});
  InfluenceFitOptions o;
  o.fit = {InfluenceConstantName::kCf};
  const InfluenceFitSummary s = FitInfluenceConstants(data, o);
  ASSERT_NE(s.status, InfluenceFitStatus::kFailure) << s.message;
  EXPECT_FALSE(s.well_conditioned);
  EXPECT_FALSE(s.covariance_available);
  EXPECT_TRUE(Contains(s.warnings,
                       "ceres::Covariance could not be computed: the Jacobian of the "
                       "free parameters is rank deficient"))
      << Joined(s.warnings);
  EXPECT_TRUE(std::isnan(Named(s, "c_f").standard_error));
  EXPECT_EQ(s.correlation.size(), 0);
}

// Separate convex and concave c_f from one contact result: the normal kernel of two steel
// bodies sees only their sum. Reported as badly conditioned; the sum is matched. The pair's
// condition number is set by the contact outputs' rounding-level noise under the fit's 1 %
// central differences, not by the data: 573 on 14c7225, 138 to 258 after each of issue 20's
// rounding-level speed changes alone (the one-pass products, the splines in power form, the
// grids' warm starts), 52 with all three. So the warning's threshold is 20 here (the columns
// parallel to within 1/20), and the default's 100 is not what the test is about; without
// degrees of freedom the fit is reported badly conditioned whatever the number.
TEST(InfluenceFit, SeparateSetsFromAContactResultAloneAreReportedBadlyConditioned) {
  ContactProblem truth_problem = Groove();
  truth_problem.model.constants.separate =
      SeparateInfluenceConstants{{0.9, 1.0, 0.25}, {0.9, 1.0, 0.25}};
  const ContactResult truth = SolveContact(truth_problem);
  ASSERT_EQ(truth.status, SolverStatus::kConverged);
  InfluenceFitData data;
  data.contacts.push_back({"groove", Groove(), truth.area_m2, truth.p_max_Pa, 1.0});
  InfluenceFitOptions o;
  o.fit = {InfluenceConstantName::kCf};
  o.separate_bodies = true;
  o.condition_warning = 20.0;
  const InfluenceFitSummary s = FitInfluenceConstants(data, o);
  ASSERT_NE(s.status, InfluenceFitStatus::kFailure) << s.message;
  EXPECT_FALSE(s.well_conditioned);
  EXPECT_GT(s.condition_number, 20.0);
  EXPECT_TRUE(Contains(s.warnings, "condition number")) << Joined(s.warnings);
  EXPECT_NEAR(s.fitted.separate->convex.c_f + s.fitted.separate->concave.c_f, 1.8, 0.01);
  std::printf(
      "[ figure ] convex and concave c_f from one contact result: condition number "
      "%.3g, sum %.4f (truth 1.8)\n",
      s.condition_number, s.fitted.separate->convex.c_f + s.fitted.separate->concave.c_f);
}

// Contact results alone say nothing of c_s without the coupling effect.
TEST(InfluenceFit, ContactResultsWithoutCouplingLeaveCsUndetermined) {
  const ContactResult start = SolveContact(Groove());
  InfluenceFitData data;
  data.contacts.push_back({"groove", Groove(), start.area_m2 * 1.05, start.p_max_Pa * 0.97, 1.0});
  InfluenceFitOptions o;
  o.fit = {InfluenceConstantName::kCf, InfluenceConstantName::kCs};
  o.max_num_iterations = 5;  // the direction is all this test needs
  const InfluenceFitSummary s = FitInfluenceConstants(data, o);
  EXPECT_TRUE(Contains(s.warnings,
                       "c_s is not determined by these data: no tangential-load "
                       "curve and no contact result with the coupling effect"))
      << Joined(s.warnings);
  EXPECT_GT(s.fitted.c_f, 0.75);  // a larger area and a lower peak want a softer kernel
}

TEST(InfluenceFit, DistanceWindowLeavesPointsOut) {
  InfluenceFitData data = PaperExperiment(kTruth, 0.0, 0.0, 1);
  data.curves[0].min_distance_m = 2e-3;
  data.curves[0].max_distance_m = 10e-3;
  const InfluenceFitSummary s = FitInfluenceConstants(data, {});
  ASSERT_EQ(s.status, InfluenceFitStatus::kConverged);
  for (int c = 0; c < 4; ++c) {  // the convex file's curves: 2, 2.5, ..., 10 mm
    EXPECT_EQ(s.curves[c].points.size(), 17u);
    EXPECT_EQ(s.curves[c].points_left_out, 23);
    EXPECT_GE(s.curves[c].points.front().distance_m, 2e-3 - 1e-12);
  }
  EXPECT_EQ(s.curves[4].points.size(), 40u);
}

template <typename F>
std::string InputErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InfluenceFit, BadInputIsRefusedWithAMessage) {
  const InfluenceFitData good = PaperExperiment(kTruth, 0.0, 0.0, 1);
  InfluenceFitOptions o;
  o.fit = {};
  EXPECT_NE(InputErrorOf([&] { FitInfluenceConstants(good, o); }).find("fit is empty"),
            std::string::npos);
  o.fit = {InfluenceConstantName::kCf, InfluenceConstantName::kCf};
  EXPECT_NE(InputErrorOf([&] { FitInfluenceConstants(good, o); }).find("c_f twice"),
            std::string::npos);
  o = {};
  o.start.c_s = 1.5;
  EXPECT_NE(InputErrorOf([&] {
              FitInfluenceConstants(good, o);
            }).find("start c_s = 1.5: expected a value in [-0.999, 0.999]"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { FitInfluenceConstants({}, {}); }).find("no data"),
            std::string::npos);

  InfluenceFitData flat;
  SyntheticCurveSpec spec;
  spec.body = CurveBody::kFlat;
  spec.curves = {{CurveLoad::kNormal, CurvePath::kAxis}};
  flat.curves.push_back({MakeSyntheticCurves(kTruth, spec, 1, "flat.csv")});
  InfluenceFitOptions separate;
  separate.separate_bodies = true;
  EXPECT_NE(InputErrorOf([&] {
              FitInfluenceConstants(flat, separate);
            }).find("flat.csv: a flat body with separate convex and concave sets"),
            std::string::npos);

  InfluenceFitData window = good;
  window.curves[1].min_distance_m = 30e-3;
  window.curves[1].max_distance_m = 40e-3;
  EXPECT_NE(InputErrorOf([&] {
              FitInfluenceConstants(window, {});
            }).find("r15_5_concave.csv: no point within the distance window [30, 40] mm"),
            std::string::npos);

  InfluenceFitData zero = good;
  for (auto& p : zero.curves[0].curves.points) {
    if (p.load == CurveLoad::kAxial) p.w_m_per_N = 0.0;
  }
  EXPECT_NE(InputErrorOf([&] {
              FitInfluenceConstants(zero, {});
            }).find("r15_convex.csv: the axial load on the axis path has only zero"),
            std::string::npos);

  InfluenceFitData halfspace;
  ContactProblem p = Groove();
  p.model = MakeModelOptions(ModelKind::kHalfspace);
  halfspace.contacts.push_back({"planar.toml", p, 1e-5, 1e9, 1.0});
  EXPECT_NE(InputErrorOf([&] { FitInfluenceConstants(halfspace, {}); })
                .find("contact result 'planar.toml': its model (halfspace, kernel boussinesq) "
                      "does not use the influence constants"),
            std::string::npos);
}

}  // namespace
}  // namespace railwear
