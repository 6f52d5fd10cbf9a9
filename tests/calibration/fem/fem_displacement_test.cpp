// The FEM displacement experiment: option checks and the .geo it writes (no programs needed),
// then coarse real runs (gmsh + ccx, about a second each; skipped when they are not installed):
// a flat block against Boussinesq and Cerruti with the support offset removed, the offset's
// 1/size decay, the circumferential load's (anti)symmetry, and convex against concave.
#include "calibration/fem/fem_displacement.h"

#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "calibration/curve_comparison.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"
#include "tests/calibration/fem/fem_test_support.h"

namespace railwear {
namespace {

using test::TempDirTest;

constexpr double kNmPerN = 1e-9;

// The range for the half-space comparison: about 1 to 10 mm from the load.
constexpr double kFrom = 1e-3, kTo = 10e-3;

class FemDisplacementTest : public TempDirTest {
 protected:
  // A coarse mesh (h0 0.2 mm, growth 0.3, elements up to 100 mm: 2.6k nodes, under a second
  // per solve). On the 200 mm block it is within 0.8 % of Boussinesq from 1 to 10 mm once the
  // offset is removed and within 2.8 % of Cerruti (the default mesh: 0.1 % and 0.4 %; README).
  FemDisplacementOptions Coarse(CurveBody body, double radius_mm = 0.0) const {
    FemDisplacementOptions o;
    o.body = body;
    o.radius_m = radius_mm * kMm;
    o.mesh_size_at_load_m = 0.2e-3;
    o.mesh_growth = 0.3;
    o.max_element_m = 100e-3;
    o.max_distance_m = 12e-3;
    o.work_dir = dir_.string();
    return o;
  }
  std::string ErrorOf(const FemDisplacementOptions& o) const {
    std::string error;
    EXPECT_FALSE(o.IsValid(&error));
    return error;
  }
};

const CurveComparison* Find(const std::vector<CurveComparison>& all, CurveLoad load,
                            CurvePath path) {
  for (const CurveComparison& c : all) {
    if (c.load == load && c.path == path) return &c;
  }
  return nullptr;
}

TEST_F(FemDisplacementTest, OptionsAreChecked) {
  FemDisplacementOptions o = Coarse(CurveBody::kFlat);
  std::string error;
  EXPECT_TRUE(o.IsValid(&error)) << error;

  FemDisplacementOptions bad = Coarse(CurveBody::kConvex);
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "radius 0 mm: expected a radius > 0 for a convex body"));
  bad = o;
  bad.loads = {CurveLoad::kNormal, CurveLoad::kNormal};
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "loads: 'normal' given twice"));
  bad = o;
  bad.loads.clear();
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "loads: expected at least one"));
  bad = o;
  bad.material.poisson_ratio = 0.5;
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "nu 0.5: expected a number in [0, 0.5)"));
  bad = o;
  bad.max_element_m = 0.1e-3;
  EXPECT_TRUE(test::Contains(ErrorOf(bad),
                             "largest element 0.1 mm: expected at least the mesh "
                             "size at the load (0.2 mm)"));
  bad = o;
  bad.min_distance_m = 20e-3;
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "expected 0 < min_distance < max_distance"));
  bad = o;
  bad.length_m = 40e-3;
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "body length 40 mm: expected at least 4 max_distance"));
  bad = Coarse(CurveBody::kConcave, 15.1);
  bad.width_m = 30e-3;
  EXPECT_TRUE(test::Contains(ErrorOf(bad),
                             "body width 30 mm: expected more than the groove's "
                             "width 2R = 30.2 mm"));
  bad = Coarse(CurveBody::kConvex, 15);
  bad.depth_m = 15e-3;
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "body depth 15 mm: expected more than R = 15 mm"));
  bad = o;
  bad.work_dir = (dir_ / "missing").string();
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "expected an existing folder"));
  bad = o;
  bad.jobs = 0;
  EXPECT_TRUE(test::Contains(ErrorOf(bad), "jobs 0"));

  EXPECT_THROW(RunFemDisplacement(bad, FemPrograms{}), InputError);
}

TEST_F(FemDisplacementTest, DefaultBodySizes) {
  const FemBodySize flat = DefaultFemBodySize(CurveBody::kFlat, 0.0);
  EXPECT_DOUBLE_EQ(flat.length_m, 0.2);
  EXPECT_DOUBLE_EQ(flat.width_m, 0.2);
  EXPECT_DOUBLE_EQ(flat.depth_m, 0.1);
  const FemBodySize convex = DefaultFemBodySize(CurveBody::kConvex, 15e-3);
  EXPECT_DOUBLE_EQ(convex.width_m, 30e-3);  // the rail head: 2R
  EXPECT_DOUBLE_EQ(convex.depth_m, 30e-3);
  const FemBodySize concave = DefaultFemBodySize(CurveBody::kConcave, 80.1e-3);
  EXPECT_NEAR(concave.width_m, 0.2602, 1e-12);  // 100 mm wider than the groove
  EXPECT_DOUBLE_EQ(concave.depth_m, 0.1);
}

// The node estimate made before meshing (issue 17) against gmsh's node counts of the meshes
// docs/fem_reference.md documents (quarter models, C3D10, measured by `railwear fem-reference`):
// the paper experiment's four bodies at the default mesh, the R 15 head at h0 and growth halved,
// the flat block at the default mesh and at a coarse one. Tolerance: a factor 1.5 either way,
// the spread of the fit (0.68-1.33: the estimate's box ignores the curved faces and their 12
// elements per circle); the estimate guards against meshes 10-100x too large, not a count.
TEST_F(FemDisplacementTest, NodeEstimateIsWithinAFactorOneAndAHalfOfTheDocumentedMeshes) {
  struct Mesh {
    CurveBody body;
    double radius_mm, h0_mm, growth, max_mm, nodes;
  };
  const std::vector<Mesh> meshes = {
      {CurveBody::kConvex, 15.0, 0.1, 0.12, 20.0, 14458},
      {CurveBody::kConvex, 15.0, 0.05, 0.06, 20.0, 96209},
      {CurveBody::kConcave, 15.1, 0.1, 0.12, 20.0, 28830},
      {CurveBody::kConvex, 80.0, 0.1, 0.12, 20.0, 22955},
      {CurveBody::kConcave, 80.1, 0.1, 0.12, 20.0, 28107},
      {CurveBody::kFlat, 0.0, 0.1, 0.12, 20.0, 24711},
      {CurveBody::kFlat, 0.0, 0.2, 0.3, 100.0, 2591},
  };
  constexpr double kFactor = 1.5;
  for (const Mesh& m : meshes) {
    FemDisplacementOptions o;
    o.body = m.body;
    o.radius_m = m.radius_mm * kMm;
    o.mesh_size_at_load_m = m.h0_mm * kMm;
    o.mesh_growth = m.growth;
    o.max_element_m = m.max_mm * kMm;
    const double estimate = EstimateFemDisplacementNodes(o);
    EXPECT_GT(estimate, m.nodes / kFactor) << m.radius_mm << " " << m.h0_mm;
    EXPECT_LT(estimate, m.nodes * kFactor) << m.radius_mm << " " << m.h0_mm;
  }
  // A mesh far too fine shows as such: h0 1 um and growth 0.01 give over 1e7 nodes.
  FemDisplacementOptions fine;
  fine.body = CurveBody::kFlat;
  fine.mesh_size_at_load_m = 1e-6;
  fine.mesh_growth = 0.01;
  EXPECT_GT(EstimateFemDisplacementNodes(fine), 1e7);
}

TEST_F(FemDisplacementTest, GeoNamesEveryGroup) {
  const FemDisplacementOptions o = Coarse(CurveBody::kConcave, 15.1);
  const std::string geo = FemDisplacementGeo(o, DefaultFemBodySize(o.body, o.radius_m));
  for (const char* group : {"\"BODY\"", "\"LOAD\"", "\"SYMX\"", "\"END\"", "\"TOP\"", "\"TOPFLAT\"",
                            "\"SIDE\"", "\"BOTTOM\"", "\"SYMY\""}) {
    EXPECT_TRUE(test::Contains(geo, group));
  }
  EXPECT_TRUE(test::Contains(geo, "R = 15.1; W2 = 100; D = 100; L2 = 100;"));
  EXPECT_TRUE(test::Contains(geo, "Field[1].F = \"0.2 + 0.3 * Sqrt(x * x + y * y + z * z)\""));
  EXPECT_TRUE(test::Contains(geo, "Mesh.ElementOrder = 2;"));
}

// The validation: a flat block against Boussinesq (normal load) and Cerruti
// (tangential), from 1 to 10 mm, once the support offset (the least-squares constant) is
// removed. The circumferential load on the arc must repeat the axial load on the axis (the
// block is square), which checks its antisymmetric boundary conditions.
TEST_F(FemDisplacementTest, FlatBlockMatchesHalfSpaceAfterTheOffset) {
  const std::string missing = test::MissingFemPrograms();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const FemPrograms programs = FindFemPrograms(dir_.string());
  const FemDisplacementResult r = RunFemDisplacement(Coarse(CurveBody::kFlat), programs);
  EXPECT_GT(r.summary.nodes, 1000u);
  EXPECT_LT(r.summary.nodes, 10000u);

  const auto cmp = CompareCurves(r.curves, HalfSpaceReference(r.curves.material), kFrom, kTo);
  for (const CurveComparison& c : cmp) {
    std::cout << "[ measured ] coarse flat block (" << r.summary.nodes << " nodes), "
              << ToString(c.load) << " load, " << ToString(c.path) << ": offset "
              << c.offset_m_per_N / kNmPerN << " nm/N, largest error 1-10 mm "
              << 100 * c.max_raw_error << " % raw, " << 100 * c.max_corrected_error
              << " % offset removed\n";
  }
  // The issue asks for 5 %. The coarse mesh does 0.8 % (normal) and 2.1-2.8 % (tangential:
  // its far elements are coarser than the defaults', which do 0.1 % and 0.4 %: README); either
  // bound catches a wrong load share or boundary condition (a factor 2 or worse).
  constexpr double kNormalTolerance = 0.02;
  constexpr double kTangentialTolerance = 0.05;
  for (CurvePath path : {CurvePath::kArc, CurvePath::kAxis}) {
    const CurveComparison* c = Find(cmp, CurveLoad::kNormal, path);
    ASSERT_NE(c, nullptr);
    EXPECT_GE(c->points.size(), 8u);
    EXPECT_LT(c->max_corrected_error, kNormalTolerance) << ToString(path);
    // The clamped bottom 100 mm below: about -0.018 nm/N (-1.8e-11 m/N), 12 % of Boussinesq at
    // 10 mm; a support offset is what makes the raw curve differ.
    EXPECT_LT(c->offset_m_per_N, -0.012 * kNmPerN);
    EXPECT_GT(c->offset_m_per_N, -0.025 * kNmPerN);
    EXPECT_GT(c->max_raw_error, 0.08);
  }
  const CurveComparison* axial = Find(cmp, CurveLoad::kAxial, CurvePath::kAxis);
  ASSERT_NE(axial, nullptr);
  EXPECT_LT(axial->max_corrected_error, kTangentialTolerance);
  EXPECT_LT(axial->max_raw_error, kTangentialTolerance);  // no offset to speak of
  const CurveComparison* circ = Find(cmp, CurveLoad::kCircumferential, CurvePath::kArc);
  ASSERT_NE(circ, nullptr);
  EXPECT_LT(circ->max_corrected_error, kTangentialTolerance);
  EXPECT_EQ(Find(cmp, CurveLoad::kAxial, CurvePath::kArc), nullptr);  // zero by antisymmetry

  // The CSV round trip keeps what calibration reads.
  const std::string csv = (dir_ / "flat.csv").string();
  WriteDisplacementCurves(r.curves, csv);
  const DisplacementCurves back = ReadDisplacementCurves(csv);
  EXPECT_EQ(back.points.size(), r.curves.points.size());
  EXPECT_EQ(back.body, CurveBody::kFlat);
  bool has_supports = false;
  for (const auto& [key, value] : back.metadata) has_supports = has_supports || key == "supports";
  EXPECT_TRUE(has_supports);
}

// A block four times larger: the offset shrinks about as 1/size and the raw curve is within
// 5 % of Boussinesq from 1 to 10 mm (offset -0.006 nm/N: 4 % of Boussinesq at 10 mm, plus
// under 1 % of mesh error).
TEST_F(FemDisplacementTest, LargeBlockRawCurveAndOffsetDecay) {
  const std::string missing = test::MissingFemPrograms();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const FemPrograms programs = FindFemPrograms(dir_.string());
  FemDisplacementOptions o = Coarse(CurveBody::kFlat);
  o.loads = {CurveLoad::kNormal};
  const auto small = CompareCurves(RunFemDisplacement(o, programs).curves,
                                   HalfSpaceReference(o.material), kFrom, kTo);
  o.length_m = o.width_m = 0.8;
  o.depth_m = 0.4;
  const auto large = CompareCurves(RunFemDisplacement(o, programs).curves,
                                   HalfSpaceReference(o.material), kFrom, kTo);
  constexpr double kRawTolerance = 0.05;
  for (CurvePath path : {CurvePath::kArc, CurvePath::kAxis}) {
    const CurveComparison* s = Find(small, CurveLoad::kNormal, path);
    const CurveComparison* l = Find(large, CurveLoad::kNormal, path);
    ASSERT_TRUE(s != nullptr && l != nullptr);
    std::cout << "[ measured ] coarse flat block, normal load, " << ToString(path) << ": offset "
              << s->offset_m_per_N / kNmPerN << " nm/N (200 mm) and " << l->offset_m_per_N / kNmPerN
              << " nm/N (800 mm); raw error 1-10 mm on the "
              << "800 mm block " << 100 * l->max_raw_error << " %\n";
    EXPECT_LT(l->max_raw_error, kRawTolerance) << ToString(path);
    const double ratio = l->offset_m_per_N / s->offset_m_per_N;
    EXPECT_GT(ratio, 0.15) << ToString(path);  // 1/4 for an exact 1/size decay
    EXPECT_LT(ratio, 0.45) << ToString(path);
  }
}

// Convex against concave of the same radius, normal load: the convex surface yields more
// (eq. 4's premise), and near the load both look flat (arc and axis agree).
TEST_F(FemDisplacementTest, ConvexYieldsMoreThanConcave) {
  const std::string missing = test::MissingFemPrograms();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const FemPrograms programs = FindFemPrograms(dir_.string());
  FemDisplacementOptions convex = Coarse(CurveBody::kConvex, 15.0);
  convex.loads = {CurveLoad::kNormal};
  FemDisplacementOptions concave = Coarse(CurveBody::kConcave, 15.1);
  concave.loads = {CurveLoad::kNormal};
  const DisplacementCurves vex = RunFemDisplacement(convex, programs).curves;
  const DisplacementCurves cave = RunFemDisplacement(concave, programs).curves;
  EXPECT_EQ(vex.body, CurveBody::kConvex);
  EXPECT_DOUBLE_EQ(cave.radius_m, 15.1e-3);
  const CurveReference cave_ref = CurvesReference(cave);
  const CurveReference vex_ref = CurvesReference(vex);
  for (double d_mm : {2.0, 5.0, 10.0}) {
    const auto a = vex_ref(CurveLoad::kNormal, CurvePath::kArc, d_mm * kMm);
    const auto b = cave_ref(CurveLoad::kNormal, CurvePath::kArc, d_mm * kMm);
    ASSERT_TRUE(a && b);
    EXPECT_GT(*a, *b) << d_mm << " mm";
  }
  // At 1 mm (R / 15) the surface is nearly flat: arc and axis within 5 %.
  const auto arc = vex_ref(CurveLoad::kNormal, CurvePath::kArc, 1e-3);
  const auto axis = vex_ref(CurveLoad::kNormal, CurvePath::kAxis, 1e-3);
  ASSERT_TRUE(arc && axis);
  EXPECT_NEAR(*arc / *axis, 1.0, 0.05);
  // Every arc distance is on the cylinder (at most pi R / 2).
  for (const DisplacementPoint& p : vex.points) {
    if (p.path == CurvePath::kArc) {
      EXPECT_LE(p.distance_m, 0.5 * std::numbers::pi * 15e-3 + 1e-9);
    }
  }
}

}  // namespace
}  // namespace railwear
