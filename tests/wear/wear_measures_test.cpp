// Tests of the wear measures: identical profiles give zeros; a uniform inward offset of UIC60 gives
// its depth everywhere, W1/W3 equal to it, W2 and the area as computed by hand for offset arcs; a
// local wear bump at the gauge corner gives the hand-calculated W2/W3 and an area equal to a
// shoelace reference; material added counts negative; the measures are additive over steps
// when measured with the step-0 gauge; bad options and non-rail profiles are refused.
#include "wear/wear_measures.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/geometry/curve_locator.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "core/profile/builtin_profiles.h"

namespace railwear {
namespace {

// UIC60 head geometry, reference README §5 (mm): R13 arc centre on the field side (mirrored to
// -y on the gauge side), the gauge point 14 mm below the crown.
constexpr double kR13CentreY_mm = 23.016030, kR13CentreZ_mm = 14.949147, kR13_mm = 13.0;
constexpr double kGaugePointY_mm = 35.981335;
// The built-in UIC60 is a C2 spline through arc points 0.1 mm apart, and a worn profile below is
// a spline through offset points 0.05 mm apart, so depths and crossings differ from the exact
// arcs and offsets by spline interpolation error. Measured: 4e-10 m for the uniform offset and
// the UIC60 gauge point, 5e-8 m where the bump's cos^2 tapers and the arc joints (curvature
// jumps) meet; the tolerance keeps a factor 4 above the largest.
constexpr double kSplineTol_m = 2e-7;
// Depth on one and the same spline: crossings are refined to CurveLocator::kParameterTolerance_m
// (1e-12 m); the normal line meets the curve at the start point, so any error is rounding.
constexpr double kSameCurveTol_m = 1e-10;
// Worn area (midpoint rule on 0.1 mm cells) against exact and shoelace references. The integrand
// d - kappa d^2/2 jumps where UIC60's curvature does (1/13 mm^-1 to 0 at the R13/flank joint),
// which the midpoint rule integrates to O(h): at most h kappa d^2/2 per joint (1.5e-8 m^2 for
// d = 2 mm), less since the spline smooths the jump. Measured: 5e-8 relative for the uniform
// 0.5 mm offset, 1.6e-5 for the 2 mm bump against the shoelace polygon; tolerance 1e-4.
constexpr double kAreaRelTol = 1e-4;

// The worn profile C(s) + depth(s) * inward normal, sampled every `step_m` along the original.
Profile OffsetProfile(const Profile& original, const std::function<double(double)>& depth,
                      double step_m = 0.05 * kMm) {
  const CurveLocator locator(original, true);
  const int n = static_cast<int>(std::ceil(original.Length() / step_m));
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k <= n; ++k) {
    const double s = original.Length() * k / n;
    points.push_back(original.Position(s) - depth(s) * locator.OutwardNormal(s));
  }
  return Profile(std::move(points), "offset");
}

// Total turning angle of the tangent from the first to the last point [rad].
double TurningAngle(const Profile& p) {
  const Eigen::Vector2d t0 = p.Tangent(0.0), t1 = p.Tangent(p.Length());
  return std::atan2(t0.x() * t1.y() - t0.y() * t1.x(), t0.dot(t1));
}

// Signed area of a closed polygon (shoelace), (y, z) as (x, y).
double Shoelace(const std::vector<Eigen::Vector2d>& poly) {
  double twice = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

// Arc length on UIC60 of the gauge-side R13 point at angle `deg` from the vertical (0 = top of
// the arc, 90 = the gauge face).
double R13Arc(const Profile& uic60, double deg) {
  const double a = deg * M_PI / 180.0;
  const Eigen::Vector2d q(-(kR13CentreY_mm + kR13_mm * std::sin(a)) * kMm,
                          (kR13CentreZ_mm - kR13_mm * std::cos(a)) * kMm);
  return CurveLocator(uic60, true).Project(q).s;
}

// y of the gauge-side point of a circle concentric with R13, radius r, at depth z [mm].
double ConcentricGaugeY_mm(double r_mm, double z_mm) {
  const double dz = kR13CentreZ_mm - z_mm;
  return -(kR13CentreY_mm + std::sqrt(r_mm * r_mm - dz * dz));
}

TEST(WearGauge, UIC60LinesSitWhereTheReferenceSays) {
  const WearGauge g = MakeWearGauge(MakeUic60());
  EXPECT_NEAR(g.vertical.point_m.x(), 0.0, kSameCurveTol_m);
  EXPECT_NEAR(g.vertical.point_m.y(), 0.0, kSplineTol_m);
  EXPECT_EQ(g.vertical.direction, Eigen::Vector2d(0.0, 1.0));
  EXPECT_NEAR(g.side.point_m.x(), -kGaugePointY_mm * kMm, kSplineTol_m);
  EXPECT_NEAR(g.side.point_m.y(), 14.0 * kMm, kSameCurveTol_m);
  EXPECT_EQ(g.side.direction, Eigen::Vector2d(1.0, 0.0));
  // P45 = R13 centre + 13 mm * (-1, -1)/sqrt(2) = (-32.208418, 5.756759) mm.
  const double r = kR13_mm / std::sqrt(2.0);
  EXPECT_NEAR(g.corner45.point_m.x(), -(kR13CentreY_mm + r) * kMm, kSplineTol_m);
  EXPECT_NEAR(g.corner45.point_m.y(), (kR13CentreZ_mm - r) * kMm, kSplineTol_m);
  EXPECT_NEAR(g.corner45.direction.x(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(g.corner45.direction.y(), std::sqrt(0.5), 1e-15);
}

TEST(WearMeasures, IdenticalProfilesGiveZeros) {
  const Profile rail = MakeUic60();
  const WearMeasures m = CompareProfiles(rail, rail);
  EXPECT_EQ(m.unmatched_samples, 0);
  ASSERT_EQ(m.s_m.size(), m.depth_m.size());
  // Cells of at most 0.1 mm: ceil(L / 0.1 mm) samples.
  EXPECT_EQ(static_cast<int>(m.s_m.size()), static_cast<int>(std::ceil(rail.Length() / 1e-4)));
  for (double d : m.depth_m) ASSERT_NEAR(d, 0.0, kSameCurveTol_m);
  EXPECT_NEAR(m.worn_area_m2, 0.0, kSameCurveTol_m * rail.Length());
  EXPECT_NEAR(m.max_depth_m, 0.0, kSameCurveTol_m);
  EXPECT_NEAR(m.vertical_wear_m, 0.0, kSameCurveTol_m);
  EXPECT_NEAR(m.side_wear_m, 0.0, kSameCurveTol_m);
  EXPECT_NEAR(m.wear_45_m, 0.0, kSameCurveTol_m);
}

TEST(WearMeasures, UniformInwardOffsetOfUIC60) {
  const Profile rail = MakeUic60();
  const double d = 0.5 * kMm;
  const Profile worn = OffsetProfile(rail, [&](double) { return d; });
  const WearMeasures m = CompareProfiles(rail, worn);
  EXPECT_EQ(m.unmatched_samples, 0);
  for (size_t i = 0; i < m.depth_m.size(); ++i) {
    ASSERT_NEAR(m.depth_m[i], d, kSplineTol_m) << "s = " << m.s_m[i];
  }
  EXPECT_NEAR(m.max_depth_m, d, kSplineTol_m);
  EXPECT_NEAR(m.vertical_wear_m, d, kSplineTol_m);  // W1: the crown moved down by d
  EXPECT_NEAR(m.wear_45_m, d, kSplineTol_m);        // W3: along a normal, as the offset
  // W2: the gauge face at z = 14 mm is now the R(13 - 0.5) arc about the same centre.
  EXPECT_NEAR(m.side_wear_m, (ConcentricGaugeY_mm(kR13_mm - 0.5, 14.0) + kGaugePointY_mm) * kMm,
              kSplineTol_m);
  // Area of the band between a curve and its inward offset: d L - d^2/2 * (turning angle).
  // Against d L alone the difference is at most d^2/2 * pi (0.39 mm^2 of 67 mm^2).
  const double theta = std::abs(TurningAngle(rail));
  EXPECT_NEAR(m.worn_area_m2, d * rail.Length(), 0.5 * d * d * M_PI);
  EXPECT_NEAR(m.worn_area_m2, d * rail.Length() - 0.5 * d * d * theta,
              kAreaRelTol * d * rail.Length());
}

TEST(WearMeasures, MaterialAddedCountsNegative) {
  const Profile rail = MakeUic60();
  const double d = -0.3 * kMm;
  const WearMeasures m = CompareProfiles(rail, OffsetProfile(rail, [&](double) { return d; }));
  EXPECT_NEAR(m.max_depth_m, d, kSplineTol_m);
  EXPECT_NEAR(m.vertical_wear_m, d, kSplineTol_m);
  EXPECT_NEAR(m.wear_45_m, d, kSplineTol_m);
  EXPECT_LT(m.side_wear_m, 0.0);
  EXPECT_LT(m.worn_area_m2, 0.0);
}

// A gauge-corner wear bump: depth D over the R13 arc from 30 degrees down onto the flank (3 mm
// past the arc's end), cos^2 tapers 3 mm long on both sides, zero elsewhere. Within the flat part
// the worn surface is the circle of radius 13 - D about the R13 centre.
struct Bump {
  double depth_m, s_begin, s_end;
  static constexpr double kTaper_m = 3e-3;
  double operator()(double s) const {
    if (s >= s_begin && s <= s_end) return depth_m;
    const double off = s < s_begin ? s_begin - s : s - s_end;
    if (off >= kTaper_m) return 0.0;
    const double c = std::cos(0.5 * M_PI * off / kTaper_m);
    return depth_m * c * c;
  }
};

TEST(WearMeasures, GaugeCornerBumpMatchesHandCalculation) {
  const Profile rail = MakeUic60();
  const double depth = 2.0 * kMm;
  // On the gauge side s runs from the flank bottom up to the crown: the flank end of the bump
  // has the smaller s. R13 ends at 87.1 degrees (y = -36 mm, z = 14.30 mm).
  const double s_arc_end = R13Arc(rail, 87.0);
  const Bump bump{depth, s_arc_end - 3e-3, R13Arc(rail, 30.0)};
  const Profile worn = OffsetProfile(rail, bump);
  const WearMeasures m = CompareProfiles(rail, worn);
  EXPECT_EQ(m.unmatched_samples, 0);

  // W1: the crown is untouched.
  EXPECT_NEAR(m.vertical_wear_m, 0.0, kSplineTol_m);
  // W3: the 45-degree line is a normal of the flat part of the bump: W3 = D.
  EXPECT_NEAR(m.wear_45_m, depth, kSplineTol_m);
  // W2 by hand: on z = 14 mm the original gauge face is at y = -35.981335 mm, the worn one on
  // the R11 circle: y = -(23.016030 + sqrt(11^2 - 0.949147^2)) = -33.975004 mm; W2 = 2.006331 mm.
  const double w2_mm = ConcentricGaugeY_mm(kR13_mm - 2.0, 14.0) + kGaugePointY_mm;
  EXPECT_NEAR(w2_mm, 2.006331, 1e-6);
  EXPECT_NEAR(m.side_wear_m, w2_mm * kMm, kSplineTol_m);
  // The largest depth is D, found inside the flat part.
  EXPECT_NEAR(m.max_depth_m, depth, kSplineTol_m);
  EXPECT_GE(m.max_depth_s_m, bump.s_begin);
  EXPECT_LE(m.max_depth_s_m, bump.s_end);
  EXPECT_LT(m.max_depth_y_m, -20.0 * kMm);  // on the gauge side
  // Depth zero away from the bump, D inside.
  for (size_t i = 0; i < m.s_m.size(); ++i) {
    ASSERT_NEAR(m.depth_m[i], bump(m.s_m[i]), kSplineTol_m) << "s = " << m.s_m[i];
  }

  // Worn area against a shoelace reference: the original's own spline sampled every 0.01 mm,
  // then the worn profile's points backwards (its first and last points are the original's end
  // points: the bump is zero there). Removed material is positive.
  std::vector<Eigen::Vector2d> poly;
  const int n = static_cast<int>(std::ceil(rail.Length() / 1e-5));
  for (int k = 0; k <= n; ++k) poly.push_back(rail.Position(rail.Length() * k / n));
  for (int k = worn.size() - 2; k >= 1; --k) poly.push_back(worn.points()[k]);
  const double reference = std::abs(Shoelace(poly));
  EXPECT_GT(reference, 20e-6);  // ~ 2 mm over ~14 mm of arc
  EXPECT_NEAR(m.worn_area_m2, reference, kAreaRelTol * reference);
}

TEST(WearMeasures, AdditiveOverStepsWithTheStepZeroGauge) {
  const Profile rail = MakeUic60();
  const Profile a = OffsetProfile(rail, [](double) { return 0.2e-3; });
  const Bump bump{1.0e-3, R13Arc(rail, 80.0), R13Arc(rail, 20.0)};
  const Profile b = OffsetProfile(rail, [&](double s) { return 0.2e-3 + bump(s); });
  WearMeasureOptions options;
  options.gauge = MakeWearGauge(rail);
  const WearMeasures to_a = CompareProfiles(rail, a, options);
  const WearMeasures to_b = CompareProfiles(rail, b, options);
  const WearMeasures a_to_b = CompareProfiles(a, b, options);
  // Same lines, differences of crossings on the same curves: rounding only.
  EXPECT_NEAR(a_to_b.vertical_wear_m, to_b.vertical_wear_m - to_a.vertical_wear_m, kSameCurveTol_m);
  EXPECT_NEAR(a_to_b.side_wear_m, to_b.side_wear_m - to_a.side_wear_m, kSameCurveTol_m);
  EXPECT_NEAR(a_to_b.wear_45_m, to_b.wear_45_m - to_a.wear_45_m, kSameCurveTol_m);
  EXPECT_NEAR(a_to_b.wear_45_m, 1.0e-3, 2 * kSplineTol_m);
  // The area is additive too (it is the area between the curves), to the integration error.
  EXPECT_NEAR(a_to_b.worn_area_m2, to_b.worn_area_m2 - to_a.worn_area_m2,
              kAreaRelTol * to_b.worn_area_m2);
}

TEST(WearMeasures, RefusesBadOptionsAndProfilesThatAreNoRailHead) {
  const Profile rail = MakeUic60();
  WearMeasureOptions options;
  options.step_m = 0.0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("step_m = 0; expected 1e-6 to 1e-3 m"), std::string::npos) << error;
  try {
    CompareProfiles(rail, rail, options);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("step_m"), std::string::npos) << e.what();
  }
  options = {};
  options.max_normal_distance_m = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_normal_distance_m = -1"), std::string::npos) << error;

  // A 300 mm crown arc 100 mm wide is only 4.2 mm deep: there is no gauge face 14 mm down.
  const Profile crown = MakeCircle(0.3, BodyRole::kRail);
  try {
    MakeWearGauge(crown);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("profile 'circle:300'"), std::string::npos) << what;
    EXPECT_NE(what.find("no gauge face 14 mm below the top of rail"), std::string::npos) << what;
    EXPECT_NE(what.find("expected a rail head"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace railwear
