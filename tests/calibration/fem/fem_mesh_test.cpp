// The gmsh MSH 2.2 reader on hand-written files: node order conversion to ccx, groups, node
// sets, element faces, and the messages for malformed files.
#include "calibration/fem/fem_mesh.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "tests/calibration/fem/fem_test_support.h"

namespace railwear {
namespace {

using test::TempDirTest;

class FemMeshTest : public TempDirTest {
 protected:
  std::string ErrorOf(const std::string& text) const {
    const std::string path = Write("bad.msh", text);
    try {
      ReadGmshMesh(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

// One 10-node tetrahedron with corners 1 (origin), 2 (x), 3 (y), 4 (z) and its mid-side nodes
// in gmsh's order: 5 (1-2), 6 (2-3), 7 (3-1), 8 (1-4), 9 (3-4), 10 (2-4); the face z = 0 as a
// 6-node triangle of the physical surface "BOTTOM", node 1 as the physical point "LOAD".
constexpr const char* kOneTet =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n3\n0 3 \"LOAD\"\n2 2 \"BOTTOM\"\n3 1 \"BODY\"\n$EndPhysicalNames\n"
    "$Nodes\n10\n"
    "1 0 0 0\n2 2 0 0\n3 0 2 0\n4 0 0 2\n"
    "5 1 0 0\n6 1 1 0\n7 0 1 0\n8 0 0 1\n9 0 1 1\n10 1 0 1\n"
    "$EndNodes\n"
    "$Elements\n3\n"
    "1 15 2 3 1 1\n"
    "2 9 2 2 5 1 3 2 7 6 5\n"
    "3 11 2 1 1 1 2 3 4 5 6 7 8 9 10\n"
    "$EndElements\n";

TEST_F(FemMeshTest, ReadsNodesElementsAndGroups) {
  const FemMesh mesh = ReadGmshMesh(Write("one.msh", kOneTet));
  EXPECT_EQ(mesh.NumNodes(), 10u);
  EXPECT_EQ(mesh.elements().size(), 3u);
  EXPECT_EQ(mesh.groups().size(), 3u);
  ASSERT_NE(mesh.FindGroup("BOTTOM"), nullptr);
  EXPECT_EQ(mesh.FindGroup("BOTTOM")->dimension, 2);
  EXPECT_EQ(mesh.FindGroup("NOPE"), nullptr);
  EXPECT_EQ(mesh.NodeSet("LOAD"), std::vector<int>({1}));
  EXPECT_EQ(mesh.NodeSet("BOTTOM"), std::vector<int>({1, 2, 3, 5, 6, 7}));
  EXPECT_EQ(mesh.NodeSet("BODY").size(), 10u);
  EXPECT_TRUE(mesh.NodeSet("NOPE").empty());
  ASSERT_EQ(mesh.SolidElements().size(), 1u);
  EXPECT_EQ(mesh.SolidElements()[0]->type, MeshElementType::kTet10);
  EXPECT_EQ(mesh.Position_mm(4), Eigen::Vector3d(0, 0, 2));
}

// ccx's C3D10 numbers its edge nodes 0-1, 1-2, 2-0, 0-3, 1-3, 2-3: after the reader's swap every
// mid-side node sits at the middle of its ccx edge.
TEST_F(FemMeshTest, Tet10NodesComeInCcxOrder) {
  const FemMesh mesh = ReadGmshMesh(Write("one.msh", kOneTet));
  const MeshElement& tet = *mesh.SolidElements()[0];
  constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d mid = 0.5 * (mesh.Position_mm(tet.nodes[kEdges[k][0]]) +
                                       mesh.Position_mm(tet.nodes[kEdges[k][1]]));
    EXPECT_EQ(mesh.Position_mm(tet.nodes[4 + k]), mid) << "edge node " << 4 + k;
  }
}

TEST_F(FemMeshTest, SurfaceTrianglesBecomeElementFaces) {
  const FemMesh mesh = ReadGmshMesh(Write("one.msh", kOneTet));
  const std::vector<ElementFace> faces = mesh.FaceSurface("BOTTOM");
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0].element, 3);
  EXPECT_EQ(faces[0].face, 1);  // corners 1, 2, 3: ccx face S1
  // The four faces each leave out a different corner.
  std::vector<int> left_out;
  for (int f = 1; f <= 4; ++f) {
    const auto c = TetFaceCorners(f);
    EXPECT_TRUE(c[0] != c[1] && c[1] != c[2] && c[0] != c[2]);
    left_out.push_back(6 - c[0] - c[1] - c[2]);
  }
  std::sort(left_out.begin(), left_out.end());
  EXPECT_EQ(left_out, std::vector<int>({0, 1, 2, 3}));
  EXPECT_TRUE(mesh.FaceSurface("NOPE").empty());
}

TEST_F(FemMeshTest, SkipsUnusedSections) {
  std::string text = kOneTet;
  text += "$NodeData\n1\n\"x\"\n$EndNodeData\n";
  EXPECT_EQ(ReadGmshMesh(Write("extra.msh", text)).NumNodes(), 10u);
}

TEST_F(FemMeshTest, MalformedFilesNameTheLine) {
  EXPECT_TRUE(test::Contains(ErrorOf("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"),
                             "bad.msh:2: mesh format '4.1 0 8': expected MSH version 2.2 ASCII"));
  EXPECT_TRUE(test::Contains(ErrorOf("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n"),
                             "expected MSH version 2.2 ASCII"));
  EXPECT_TRUE(test::Contains(ErrorOf("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n"),
                             "bad.msh:6: the file ends early; expected a node 'id x y z'"));
  EXPECT_TRUE(test::Contains(
      ErrorOf("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 zero 0\n$EndNodes\n"),
      "bad.msh:6: '1 0 zero 0': expected a node 'id x y z'"));
  EXPECT_TRUE(test::Contains(ErrorOf("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n"
                                     "$EndNodes\n$Elements\n1\n1 5 2 1 1 1 1 1 1 1 1 1 1\n"
                                     "$EndElements\n"),
                             "bad.msh:10: element 1 has gmsh type 5"));
  EXPECT_TRUE(test::Contains(ErrorOf("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n"
                                     "$EndNodes\n$Elements\n1\n1 2 2 1 1 1 1 7\n$EndElements\n"),
                             "element 1 expects 3 existing node ids"));
  EXPECT_TRUE(
      test::Contains(ErrorOf("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"), "the file lacks $Nodes"));
  EXPECT_TRUE(test::Contains(ErrorOf("garbage\n"), "bad.msh:1: 'garbage': expected a section"));
  try {
    ReadGmshMesh((dir_ / "missing.msh").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_TRUE(test::Contains(e.what(), "missing.msh: cannot open the mesh file"));
  }
}

}  // namespace
}  // namespace railwear
