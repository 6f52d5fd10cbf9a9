// CalculiX decks: the text the writer produces, and the whole chain gmsh -> FemMesh -> deck ->
// ccx -> .frd on a patch test (a uniformly compressed cube, whose exact solution is linear and
// which quadratic tetrahedra reproduce to the output's precision). The pressure is applied on
// an element-face *SURFACE, so the test also checks the face numbering.
#include "calibration/fem/ccx_deck.h"

#include <cmath>

#include <gtest/gtest.h>

#include "calibration/fem/fem_programs.h"
#include "calibration/fem/frd_file.h"
#include "core/numerics/input_error.h"
#include "tests/calibration/fem/fem_test_support.h"

namespace railwear {
namespace {

using test::TempDirTest;

class CcxDeckTest : public TempDirTest {};

TEST_F(CcxDeckTest, BuilderWritesKeywordLines) {
  CcxDeck deck;
  deck.Comment("unit test")
      .Include("mesh.inp")
      .ElasticMaterial("STEEL", 210000.0, 0.28)
      .SolidSection("EALL", "STEEL")
      .Boundary("SYMX", 1, 1)
      .Boundary("TOP", 3, 3, -0.5)
      .BeginStaticStep()
      .Cload("7", 3, -0.25)
      .NodeFile()
      .Raw("*EL FILE\nS")
      .EndStep()
      .BeginStaticStep("NLGEOM, INC=100", "0.1, 1.")
      .EndStep();
  EXPECT_EQ(deck.Text(),
            "** unit test\n"
            "*INCLUDE, INPUT=mesh.inp\n"
            "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.28\n"
            "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
            "*BOUNDARY\nSYMX, 1, 1, 0\n"
            "*BOUNDARY\nTOP, 3, 3, -0.5\n"
            "*STEP\n*STATIC\n"
            "*CLOAD\n7, 3, -0.25\n"
            "*NODE FILE\nU\n"
            "*EL FILE\nS\n"
            "*END STEP\n"
            "*STEP, NLGEOM, INC=100\n*STATIC\n0.1, 1.\n*END STEP\n");
}

TEST_F(CcxDeckTest, MeshTextHasSolidsSetsAndSurfaces) {
  FemMesh mesh;
  mesh.AddNode(1, {0, 0, 0});
  mesh.AddNode(2, {1.0 / 3.0, 0, 0});
  mesh.AddNode(3, {0, 1, -9.086986490380866e-05});
  mesh.AddNode(4, {0, 0, 1});
  mesh.AddGroup({"BOTTOM", 2, 2});
  mesh.AddGroup({"BODY", 3, 1});
  mesh.AddElement({10, MeshElementType::kTriangle3, 2, {1, 3, 2}});  // not written as element
  mesh.AddElement({11, MeshElementType::kTet4, 1, {1, 2, 3, 4}});
  CcxMeshSets sets;
  sets.node_sets.push_back({"MANY", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}});
  sets.element_sets.push_back({"WHEEL", ElementIds(mesh, "BODY")});
  EXPECT_TRUE(ElementIds(mesh, "BOTTOM").empty());  // no solids in a surface group
  sets.surfaces.push_back({"BOT", mesh.FaceSurface("BOTTOM")});
  EXPECT_EQ(CcxMeshText(mesh, sets),
            "*NODE\n1, 0, 0, 0\n2, 0.333333333333, 0, 0\n3, 0, 1, -9.08698649038e-05\n4, 0, 0, 1\n"
            "*ELEMENT, TYPE=C3D4, ELSET=EALL\n11, 1, 2, 3, 4\n"
            "*NSET, NSET=MANY\n1, 2, 3, 4, 5, 6, 7, 8, 9, 10,\n11, 12,\n"
            "*ELSET, ELSET=WHEEL\n11,\n"
            "*SURFACE, NAME=BOT, TYPE=ELEMENT\n11, S1\n");
}

// A cube 0 <= x, y, z <= 10 mm on rollers at x = 0, y = 0, z = 0 under a pressure p on z = 10:
// sigma_zz = -p, so u_z = -p z / E, u_x = nu p x / E, u_y = nu p y / E exactly.
TEST_F(CcxDeckTest, PatchTestThroughGmshAndCcx) {
  const std::string missing = test::MissingFemPrograms();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const std::string work = dir_.string();
  const FemPrograms programs = FindFemPrograms(work);
  EXPECT_NE(programs.ccx_version, "unknown");
  EXPECT_NE(programs.gmsh_version, "unknown");
  Write("cube.geo",
        "SetFactory(\"OpenCASCADE\");\n"
        "Box(1) = {0, 0, 0, 10, 10, 10};\n"
        "Physical Volume(\"BODY\") = {1};\n"
        "Physical Surface(\"X0\") = {1};\n"
        "Physical Surface(\"Y0\") = {3};\n"
        "Physical Surface(\"Z0\") = {5};\n"
        "Physical Surface(\"Z1\") = {6};\n"
        "Mesh.MeshSizeMax = 4;\n"
        "Mesh.ElementOrder = 2;\n");
  RunGmsh(programs.gmsh, work, "cube.geo", "cube.msh", 1);
  const FemMesh mesh = ReadGmshMesh((dir_ / "cube.msh").string());
  ASSERT_GT(mesh.SolidElements().size(), 10u);

  CcxMeshSets sets;
  for (const char* name : {"X0", "Y0", "Z0"}) sets.node_sets.push_back({name, mesh.NodeSet(name)});
  const std::vector<ElementFace> top = mesh.FaceSurface("Z1");
  EXPECT_EQ(top.size(), mesh.GroupElements("Z1").size());
  sets.surfaces.push_back({"TOPS", top});
  WriteWorkFile((dir_ / "mesh.inp").string(), CcxMeshText(mesh, sets));

  constexpr double kE = 210000.0, kNu = 0.3, kP = 100.0;  // MPa
  CcxDeck deck;
  deck.Include("mesh.inp")
      .ElasticMaterial("STEEL", kE, kNu)
      .SolidSection("EALL", "STEEL")
      .Boundary("X0", 1, 1)
      .Boundary("Y0", 2, 2)
      .Boundary("Z0", 3, 3)
      .BeginStaticStep()
      .Raw("*DSLOAD\nTOPS, P, 100")  // kP
      .NodeFile("U")
      .EndStep();
  WriteWorkFile((dir_ / "job.inp").string(), deck.Text());
  RunCcx(programs.ccx, work, "job", 1);

  const FrdFile frd = ReadFrd((dir_ / "job.frd").string());
  const FrdResultBlock* disp = frd.Find("DISP", 1);
  ASSERT_NE(disp, nullptr);
  EXPECT_EQ(disp->node_ids.size(), mesh.NumNodes());
  // frd values have 6 significant digits: 1e-5 of the largest displacement (p 10 / E).
  const double tolerance = 1e-5 * kP * 10.0 / kE;
  for (int id : mesh.node_ids()) {
    const Eigen::Vector3d p = mesh.Position_mm(id);
    const Eigen::Vector3d exact(kNu * kP * p.x() / kE, kNu * kP * p.y() / kE, -kP * p.z() / kE);
    const Eigen::Vector3d u = FrdDisplacement(*disp, id);
    ASSERT_LT((u - exact).lpNorm<Eigen::Infinity>(), tolerance) << "node " << id;
  }
}

TEST_F(CcxDeckTest, CcxFailureQuotesItsLog) {
  const std::string missing = test::MissingFemPrograms();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const std::string ccx = FindProgram(CcxProgram());
  Write("bad.inp", "*NODE\n1, 0, 0, 0\n*STEP\n*STATIC\n*CLOAD\n7, 3, 1.\n*END STEP\n");
  try {
    RunCcx(ccx, dir_.string(), "bad", 1);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(test::Contains(e.what(), "ccx (CalculiX) failed"));
    EXPECT_TRUE(test::Contains(e.what(), (dir_ / "bad.log").string()));
    EXPECT_TRUE(test::Contains(e.what(), "*ERROR"));
  }
  // ccx exits with 0 when its input does not exist: the missing .frd gives it away.
  try {
    RunCcx(ccx, dir_.string(), "nonexistent", 1);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(test::Contains(e.what(), "ccx (CalculiX) failed"));
  }
}

}  // namespace
}  // namespace railwear
