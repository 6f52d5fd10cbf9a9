#include "calibration/displacement_curves.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "core/numerics/input_error.h"
#include "tests/test_support.h"

namespace railwear {
namespace {

namespace fs = std::filesystem;

class DisplacementCurvesTest : public test::TempDirTest {
 protected:
  // The message of the InputError reading `text` throws ("" when it does not throw).
  std::string ErrorOf(const std::string& text) const {
    const std::string path = Write("bad.csv", text);
    try {
      ReadDisplacementCurves(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

constexpr const char* kHeader =
    "# railwear displacement curves v1\n"
    "# body = convex\n"
    "# radius_mm = 15\n"
    "# E_MPa = 210000\n"
    "# nu = 0.28\n";

TEST_F(DisplacementCurvesTest, WriteThenReadRoundTrips) {
  DisplacementCurves c;
  c.body = CurveBody::kConcave;
  c.radius_m = 15.1e-3;
  c.material.youngs_modulus_Pa = 205e9;
  c.material.poisson_ratio = 0.3;
  c.metadata = {{"source", "synthetic"}, {"supports", "clamped bottom face, 45 mm below"}};
  c.points = {{CurveLoad::kNormal, CurvePath::kArc, 0.5e-3, 2.713e-9, 0},
              {CurveLoad::kNormal, CurvePath::kAxis, 1.25e-3, 1.1e-9, 0},
              {CurveLoad::kAxial, CurvePath::kAxis, 2e-3, 0.2e-9, 0},
              {CurveLoad::kCircumferential, CurvePath::kArc, 3e-3, -0.01e-9, 0}};
  const std::string path = (dir_ / "c.csv").string();
  WriteDisplacementCurves(c, path);
  const DisplacementCurves r = ReadDisplacementCurves(path);
  EXPECT_EQ(r.path, path);
  EXPECT_EQ(r.body, CurveBody::kConcave);
  EXPECT_DOUBLE_EQ(r.radius_m, 15.1e-3);
  EXPECT_DOUBLE_EQ(r.material.youngs_modulus_Pa, 205e9);
  EXPECT_DOUBLE_EQ(r.material.poisson_ratio, 0.3);
  EXPECT_EQ(r.metadata, c.metadata);
  ASSERT_EQ(r.points.size(), c.points.size());
  for (size_t i = 0; i < c.points.size(); ++i) {
    EXPECT_EQ(r.points[i].load, c.points[i].load);
    EXPECT_EQ(r.points[i].path, c.points[i].path);
    EXPECT_NEAR(r.points[i].distance_m, c.points[i].distance_m, 1e-15);
    EXPECT_NEAR(r.points[i].w_m_per_N, c.points[i].w_m_per_N, 1e-20);
    EXPECT_EQ(r.points[i].line, static_cast<int>(9 + i));  // 7 metadata lines, the header
  }
}

TEST_F(DisplacementCurvesTest, ColumnsInAnyOrderWithExtrasAndComments) {
  const std::string path = Write("ok.csv", std::string(kHeader) +
                                               "# plain comment without a value\n"
                                               "node,w_nm_per_N,distance_mm,path,load\n"
                                               "17,1.5,2.0,axis,normal\n"
                                               "# a comment among the rows\n"
                                               "18,0.7,4.0,axis,normal\n");
  const DisplacementCurves r = ReadDisplacementCurves(path);
  ASSERT_EQ(r.points.size(), 2u);
  EXPECT_DOUBLE_EQ(r.points[1].distance_m, 4e-3);
  EXPECT_DOUBLE_EQ(r.points[1].w_m_per_N, 0.7e-9);
  EXPECT_EQ(r.points[1].line, 10);
}

TEST_F(DisplacementCurvesTest, BadFilesNameLineValueAndExpectation) {
  const std::string rows = "load,path,distance_mm,w_nm_per_N\n";
  struct Case {
    std::string text, expected_fragment;
  };
  const std::vector<Case> cases = {
      {"", ":1: the file is empty; expected '# railwear displacement curves v1'"},
      {"load,path\n", ":1: first line is 'load,path'; expected '# railwear displacement"},
      {std::string(kHeader) + "load,path,w_nm_per_N\nnormal,arc,1\n",
       ":6: header 'load,path,w_nm_per_N' has no column 'distance_mm'"},
      {std::string(kHeader) + rows + "normal,arc,-1,2\n",
       ":7: column 'distance_mm' is -1: expected a positive distance"},
      {std::string(kHeader) + rows + "normal,arc,0,2\n",
       ":7: column 'distance_mm' is 0: expected a positive distance"},
      {std::string(kHeader) + rows + "normal,arc,1,nan\n",
       ":7: column 'w_nm_per_N' is 'nan': expected a finite number in nm/N"},
      {std::string(kHeader) + rows + "normal,arc,1,inf\n", "column 'w_nm_per_N' is 'inf'"},
      {std::string(kHeader) + rows + "normal,arc,1x,2\n", "column 'distance_mm' is '1x'"},
      {std::string(kHeader) + rows + "normal,arc,1\n", ":7: 'normal,arc,1' has 3 column(s)"},
      {std::string(kHeader) + rows + "shear,arc,1,2\n",
       ":7: column 'load' is 'shear': expected normal, axial or circumferential"},
      {std::string(kHeader) + rows + "normal,line,1,2\n", "column 'path' is 'line'"},
      {std::string(kHeader) + rows + "axial,arc,1,2\n", ":7: load axial seen on path arc"},
      {std::string(kHeader) + rows + "circumferential,axis,1,2\n",
       "load circumferential seen on path axis"},
      {std::string(kHeader) + rows + "normal,arc,48,2\n",
       "expected an arc length of at most half the circumference"},
      {std::string(kHeader) + rows, ":6: no data rows after the header"},
      {std::string(kHeader), "no header line"},
      {"# railwear displacement curves v1\n# radius_mm = 15\n# E_MPa = 1\n# nu = 0.3\n" + rows,
       ":5: metadata 'body' is missing"},
      {"# railwear displacement curves v1\n# body = convex\n# E_MPa = 1\n# nu = 0.3\n" + rows,
       "metadata 'radius_mm' is missing"},
      {"# railwear displacement curves v1\n# body = flat\n# nu = 0.3\n" + rows,
       "metadata 'E_MPa' is missing"},
      {"# railwear displacement curves v1\n# body = round\n",
       ":2: metadata 'body' = 'round': expected flat, convex or concave"},
      {"# railwear displacement curves v1\n# body = flat\n# nu = 0.5\n",
       ":3: metadata 'nu' = '0.5': expected Poisson's ratio in [0, 0.5)"},
      {"# railwear displacement curves v1\n# body = flat\n# body = flat\n",
       ":3: metadata 'body' given twice"},
  };
  for (const Case& c : cases) {
    const std::string message = ErrorOf(c.text);
    EXPECT_NE(message.find(c.expected_fragment), std::string::npos)
        << "text:\n"
        << c.text << "message: " << message;
    EXPECT_NE(message.find("bad.csv"), std::string::npos) << message;
  }
  // A flat body needs no radius.
  EXPECT_EQ(ErrorOf("# railwear displacement curves v1\n# body = flat\n# E_MPa = 1\n# nu = 0\n" +
                    rows + "normal,axis,1,2\n"),
            "");
}

TEST_F(DisplacementCurvesTest, MissingFileAndDirectoryAreInputErrors) {
  EXPECT_THROW(ReadDisplacementCurves((dir_ / "none.csv").string()), InputError);
  EXPECT_THROW(ReadDisplacementCurves(dir_.string()), InputError);
}

// Exact: eq. 4 with the half-space-equivalent constants is Boussinesq / Cerruti on a flat body.
constexpr double kExact = 1e-12;

TEST(SeedKernelDisplacement, FlatBodyWithEquivalentConstantsIsHalfSpace) {
  for (double nu : {0.0, 0.28, 0.3, 0.45}) {
    Material m;
    m.poisson_ratio = nu;
    InfluenceConstants c;
    c.c_f = HalfSpaceEquivalentCf(nu);
    c.c_s = 0.7;  // no effect on a flat body: c_t = 1 there
    for (double d : {0.5e-3, 3e-3, 20e-3}) {
      for (CurvePath path : {CurvePath::kArc, CurvePath::kAxis}) {
        const double w =
            SeedKernelDisplacement(c, CurveBody::kFlat, 0.0, m, CurveLoad::kNormal, path, d);
        const double b = HalfSpaceDisplacement(m, CurveLoad::kNormal, d);
        EXPECT_NEAR(w / b, 1.0, kExact);
      }
      // Tangential: c_t k_d / d against (1 - 2 nu)/(4 pi G d).
      const double w_t = HalfSpaceEquivalentCt(nu) *
                         SeedKernelDisplacement(InfluenceConstants{}, CurveBody::kFlat, 0.0, m,
                                                CurveLoad::kAxial, CurvePath::kAxis, d);
      EXPECT_NEAR(w_t / HalfSpaceDisplacement(m, CurveLoad::kAxial, d), 1.0, kExact);
    }
  }
  // The figures quoted in the header and the reference README (1.47x stiffer seed kernel).
  EXPECT_NEAR(HalfSpaceEquivalentCf(0.28), 1.103, 5e-4);
  EXPECT_NEAR(HalfSpaceEquivalentCt(0.28), 0.634, 5e-4);
  EXPECT_NEAR(0.75 / HalfSpaceEquivalentCf(0.28), 0.680, 5e-4);
}

TEST(SeedKernelDisplacement, ArcGeometryMatchesTheVectorDefinition) {
  // Load point O at the top of a circle of radius R centred at (0, -R) (convex) in the (y, z)
  // cross-section, z up; a field point at angle theta along the arc.
  const double r = 15e-3;
  Material m;
  const InfluenceConstants c{0.8, 1.3, 0.2};
  for (CurveBody body : {CurveBody::kConvex, CurveBody::kConcave}) {
    for (double s : {0.2e-3, 5e-3, 20e-3, 40e-3}) {
      const double theta = s / r;
      const double sign = body == CurveBody::kConvex ? 1.0 : -1.0;  // concave: centre above
      const Eigen::Vector2d o(0.0, 0.0);
      const Eigen::Vector2d centre(0.0, -sign * r);
      const Eigen::Vector2d p =
          centre + r * Eigen::Vector2d(std::sin(theta), sign * std::cos(theta));
      const Eigen::Vector2d n_o(0.0, 1.0);  // normal at O (either sense: dn is squared)
      const Eigen::Vector2d t_o(1.0, 0.0);  // tangent at O toward the field points
      const Eigen::Vector2d d = p - o;
      const double rho = d.norm(), dn = d.dot(n_o), dt = d.dot(t_o);
      const double k_d =
          1.0 / (8.0 * std::numbers::pi * (1.0 - m.poisson_ratio) * m.ShearModulus());
      const double k_f = (3.0 - 4.0 * m.poisson_ratio) * k_d;
      const double normal = (c.c_f * k_f + c.c_z * k_d * dn * dn / (rho * rho)) / rho;
      const double c_t = 1.0 + c.c_s * (body == CurveBody::kConcave ? 1.0 : -1.0);
      const double tangential = c_t * k_d * dt / (rho * rho);
      EXPECT_NEAR(
          SeedKernelDisplacement(c, body, r, m, CurveLoad::kNormal, CurvePath::kArc, s) / normal,
          1.0, kExact);
      EXPECT_NEAR(
          SeedKernelDisplacement(c, body, r, m, CurveLoad::kCircumferential, CurvePath::kArc, s) /
              tangential,
          1.0, kExact);
    }
  }
}

TEST(SeedKernelDisplacement, AxisIsFlatAndSmallArcsTendToIt) {
  const double r = 80e-3;
  Material m;
  const InfluenceConstants c;
  for (double d : {0.1e-3, 1e-3}) {
    const double axis = SeedKernelDisplacement(c, CurveBody::kConvex, r, m, CurveLoad::kNormal,
                                               CurvePath::kAxis, d);
    EXPECT_NEAR(axis / SeedKernelDisplacement(c, CurveBody::kFlat, 0.0, m, CurveLoad::kNormal,
                                              CurvePath::kAxis, d),
                1.0, kExact);
    // On the arc the curvature enters at order (d/R)^2: 1/rho grows by (d/R)^2/24 and the dn
    // term adds c_z k_d (d/2R)^2 / (c_f k_f).
    const double arc =
        SeedKernelDisplacement(c, CurveBody::kConvex, r, m, CurveLoad::kNormal, CurvePath::kArc, d);
    EXPECT_NEAR(arc / axis - 1.0, 0.0, 2.0 * (d / r) * (d / r));
  }
}

}  // namespace
}  // namespace railwear
