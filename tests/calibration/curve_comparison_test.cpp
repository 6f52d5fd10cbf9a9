// Comparing displacement curves with a reference: the fitted offset, the raw and offset-removed
// errors, points near a zero crossing, and the log-distance interpolation of reference curves.
#include "calibration/curve_comparison.h"

#include <cmath>

#include <gtest/gtest.h>

namespace railwear {
namespace {

constexpr double kNm = 1e-9;

DisplacementCurves Curves(const std::vector<std::pair<double, double>>& d_w,
                          CurveLoad load = CurveLoad::kNormal, CurvePath path = CurvePath::kArc) {
  DisplacementCurves c;
  for (const auto& [d, w] : d_w) {
    DisplacementPoint p;
    p.load = load;
    p.path = path;
    p.distance_m = d;
    p.w_m_per_N = w;
    c.points.push_back(p);
  }
  return c;
}

TEST(CurveComparisonTest, HalfSpaceReferenceIsBoussinesqAndCerruti) {
  const Material steel;
  const auto ref = HalfSpaceReference(steel);
  EXPECT_DOUBLE_EQ(*ref(CurveLoad::kNormal, CurvePath::kAxis, 2e-3),
                   HalfSpaceDisplacement(steel, CurveLoad::kNormal, 2e-3));
  EXPECT_DOUBLE_EQ(*ref(CurveLoad::kAxial, CurvePath::kAxis, 2e-3),
                   HalfSpaceDisplacement(steel, CurveLoad::kAxial, 2e-3));
}

// A curve that is the reference plus a constant: the offset is that constant, the
// offset-removed error zero and the raw error the constant over the smallest reference.
TEST(CurveComparisonTest, ConstantOffsetIsFittedExactly) {
  const Material steel;
  const double c = -0.02 * kNm;
  std::vector<std::pair<double, double>> d_w;
  for (double d_mm : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0}) {
    const double d = d_mm * 1e-3;
    d_w.push_back({d, HalfSpaceDisplacement(steel, CurveLoad::kNormal, d) + c});
  }
  const auto cmp = CompareCurves(Curves(d_w), HalfSpaceReference(steel), 1e-3, 10e-3);
  ASSERT_EQ(cmp.size(), 1u);
  EXPECT_EQ(cmp[0].points.size(), 4u);  // 1, 2, 5, 10 mm
  EXPECT_NEAR(cmp[0].offset_m_per_N, c, 1e-25);
  EXPECT_LT(cmp[0].max_corrected_error, 1e-12);
  const double w10 = HalfSpaceDisplacement(steel, CurveLoad::kNormal, 10e-3);
  EXPECT_NEAR(cmp[0].max_raw_error, std::abs(c) / w10, 1e-12);
  EXPECT_EQ(cmp[0].num_skipped, 0u);
}

TEST(CurveComparisonTest, PointsNearAZeroCrossingAreLeftOutOfTheErrors) {
  // A reference that crosses zero between 2 and 4: its value at 3 is 1 % of the largest.
  DisplacementCurves reference = Curves({{1, 1.0}, {2, 0.5}, {3, 0.01}, {4, -0.5}});
  DisplacementCurves curves = Curves({{1, 1.01}, {2, 0.505}, {3, 0.02}, {4, -0.505}});
  const auto cmp = CompareCurves(curves, CurvesReference(reference), 0.5, 5);
  ASSERT_EQ(cmp.size(), 1u);
  EXPECT_EQ(cmp[0].num_skipped, 1u);
  EXPECT_NEAR(cmp[0].max_raw_error, 0.01, 1e-12);  // not the 100 % at the crossing
}

TEST(CurveComparisonTest, CurvesReferenceInterpolatesInLogDistance) {
  // w = a / d is reproduced exactly between its points.
  const double a = 3.0;
  DisplacementCurves ref = Curves({{1.0, a / 1.0}, {2.0, a / 2.0}, {5.0, a / 5.0}});
  const auto f = CurvesReference(ref);
  EXPECT_NEAR(*f(CurveLoad::kNormal, CurvePath::kArc, 3.3), a / 3.3, 1e-12);
  EXPECT_NEAR(*f(CurveLoad::kNormal, CurvePath::kArc, 2.0), a / 2.0, 1e-12);
  EXPECT_FALSE(f(CurveLoad::kNormal, CurvePath::kArc, 0.5).has_value());  // outside
  EXPECT_FALSE(f(CurveLoad::kNormal, CurvePath::kArc, 6.0).has_value());
  EXPECT_FALSE(f(CurveLoad::kNormal, CurvePath::kAxis, 2.0).has_value());  // no such curve
  // Comparing a curve with itself: no offset, no error.
  const auto self = CompareCurves(ref, f, 0.0, 10.0);
  ASSERT_EQ(self.size(), 1u);
  EXPECT_EQ(self[0].points.size(), 3u);
  EXPECT_NEAR(self[0].offset_m_per_N, 0.0, 1e-15);
  EXPECT_NEAR(self[0].max_raw_error, 0.0, 1e-15);
}

TEST(CurveComparisonTest, OneComparisonPerCurveInFirstAppearanceOrder) {
  DisplacementCurves c = Curves({{1e-3, 1e-9}, {2e-3, 5e-10}}, CurveLoad::kAxial, CurvePath::kAxis);
  const DisplacementCurves n = Curves({{1e-3, 2e-9}}, CurveLoad::kNormal, CurvePath::kArc);
  c.points.insert(c.points.end(), n.points.begin(), n.points.end());
  const auto cmp = CompareCurves(c, HalfSpaceReference(Material{}), 0.0, 1.0);
  ASSERT_EQ(cmp.size(), 2u);
  EXPECT_EQ(cmp[0].load, CurveLoad::kAxial);
  EXPECT_EQ(cmp[1].load, CurveLoad::kNormal);
  EXPECT_TRUE(CompareCurves(c, HalfSpaceReference(Material{}), 5e-3, 1.0).empty());
}

}  // namespace
}  // namespace railwear
