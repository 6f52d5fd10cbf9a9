// The CalculiX .frd reader on hand-written files in ccx's fixed-column layout: nodes, result
// blocks by name and step, stored and computed components, continuation rows, the short format,
// and the messages for malformed files.
#include "calibration/fem/frd_file.h"

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "tests/calibration/fem/fem_test_support.h"

namespace railwear {
namespace {

using test::TempDirTest;

class FrdFileTest : public TempDirTest {
 protected:
  std::string ErrorOf(const std::string& text) const {
    const std::string path = Write("bad.frd", text);
    try {
      ReadFrd(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

// As ccx 2.20 writes it (two nodes, an element block, two steps of DISP and one STRESS block).
constexpr const char* kTwoSteps =
    "    1C\n"
    "    1UUSER\n"
    "    1UPGM               CalculiX\n"
    "    2C                             2                                     1\n"
    " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1        17 1.00000E+00-2.50000E+00 3.00000E+01\n"
    " -3\n"
    "    3C                             1                                     1\n"
    " -1         1    1    0    1\n"
    " -2         1        17\n"
    " -3\n"
    "    1PSTEP                         1           1           1          \n"
    "  100CL  101 1.000000000           2                     0    1           1\n"
    " -4  DISP        4    1\n"
    " -5  D1          1    2    1    0\n"
    " -5  D2          1    2    2    0\n"
    " -5  D3          1    2    3    0\n"
    " -5  ALL         1    2    0    0    1ALL\n"
    " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1        17-3.50903E-04 2.00000E-18-1.76287E-03\n"
    " -3\n"
    "    1PSTEP                         2           1           1          \n"
    "  100CL  101 1.000000000           2                     0    1           1\n"
    " -4  STRESS      6    1\n"
    " -5  SXX         1    4    1    1\n"
    " -5  SYY         1    4    2    2\n"
    " -5  SZZ         1    4    3    3\n"
    " -5  SXY         1    4    1    2\n"
    " -5  SYZ         1    4    2    3\n"
    " -5  SZX         1    4    3    1\n"
    " -1         1-1.84047E+02-1.84047E+02-4.73255E+02-1.32805E-15-2.87849E+01-2.87849E+01\n"
    " -1        17 7.76337E+01 7.76337E+01-3.26713E+02-1.85857E-14-2.87849E+01-2.87849E+01\n"
    " -3\n"
    "    1PSTEP                         3           1           2          \n"
    "  100CL  102 2.000000000           2                     0    2           1\n"
    " -4  DISP        4    1\n"
    " -5  D1          1    2    1    0\n"
    " -5  D2          1    2    2    0\n"
    " -5  D3          1    2    3    0\n"
    " -5  ALL         1    2    0    0    1ALL\n"
    " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1        17 8.52958E-04 7.71067E-05 3.65339E-04\n"
    " -3\n"
    " 9999\n";

TEST_F(FrdFileTest, ReadsNodesAndBlocksByNameAndStep) {
  const FrdFile frd = ReadFrd(Write("job.frd", kTwoSteps));
  ASSERT_EQ(frd.node_ids, std::vector<int>({1, 17}));
  EXPECT_EQ(frd.positions[1], Eigen::Vector3d(1.0, -2.5, 30.0));
  ASSERT_EQ(frd.blocks.size(), 3u);

  const FrdResultBlock* d1 = frd.Find("DISP", 1);
  ASSERT_NE(d1, nullptr);
  EXPECT_EQ(d1->step, 1);
  EXPECT_EQ(d1->increment, 1);
  EXPECT_DOUBLE_EQ(d1->time, 1.0);
  EXPECT_EQ(d1->components, std::vector<std::string>({"D1", "D2", "D3"}));  // ALL is not stored
  EXPECT_EQ(FrdDisplacement(*d1, 17), Eigen::Vector3d(-3.50903e-4, 2.0e-18, -1.76287e-3));

  const FrdResultBlock* last = frd.Find("DISP");  // the last step that has one
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->step, 2);
  EXPECT_DOUBLE_EQ(last->time, 2.0);
  EXPECT_DOUBLE_EQ(FrdDisplacement(*last, 17).x(), 8.52958e-4);

  const FrdResultBlock* s = frd.Find("STRESS", 1);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->NumComponents(), 6u);
  EXPECT_EQ(s->ComponentIndex("SZZ"), 2);
  EXPECT_EQ(s->ComponentIndex("S11"), -1);
  EXPECT_DOUBLE_EQ(s->Value(s->Row(17), s->ComponentIndex("SZX")), -2.87849e1);
  EXPECT_EQ(s->Row(99), -1);
  EXPECT_EQ(frd.Find("STRESS", 2), nullptr);
  EXPECT_EQ(frd.Find("CONTACT"), nullptr);
  EXPECT_THROW(FrdDisplacement(*s, 17), std::runtime_error);   // no D1..D3
  EXPECT_THROW(FrdDisplacement(*d1, 99), std::runtime_error);  // no such node
}

// A block with more than six components continues its rows on " -2" lines; the short format
// (FORMAT 0) has 5-column ids.
TEST_F(FrdFileTest, ContinuationRowsAndShortFormat) {
  const std::string text =
      "    2C                             1                                     0\n"
      " -1    3 1.00000E+00 2.00000E+00 3.00000E+00\n"
      " -3\n"
      "    1PSTEP                         1           1           1\n"
      "  100CL  101 5.000000000           1                     0    1           0\n"
      " -4  MANY        8    1\n"
      " -5  C1          1    1    0    0\n -5  C2          1    1    0    0\n"
      " -5  C3          1    1    0    0\n -5  C4          1    1    0    0\n"
      " -5  C5          1    1    0    0\n -5  C6          1    1    0    0\n"
      " -5  C7          1    1    0    0\n -5  C8          1    1    0    0\n"
      " -1    3 1.00000E+00 2.00000E+00 3.00000E+00 4.00000E+00 5.00000E+00 6.00000E+00\n"
      " -2      7.00000E+00 8.00000E+00\n"
      " -3\n"
      " 9999\n";
  const FrdFile frd = ReadFrd(Write("short.frd", text));
  ASSERT_EQ(frd.node_ids, std::vector<int>({3}));
  EXPECT_EQ(frd.positions[0], Eigen::Vector3d(1, 2, 3));
  const FrdResultBlock* b = frd.Find("MANY");
  ASSERT_NE(b, nullptr);
  EXPECT_DOUBLE_EQ(b->time, 5.0);
  ASSERT_EQ(b->NumComponents(), 8u);
  EXPECT_DOUBLE_EQ(b->Value(0, 7), 8.0);
}

TEST_F(FrdFileTest, MalformedFilesNameTheLine) {
  const std::string head =
      "    2C                             1                                     1\n"
      " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
      " -3\n"
      "  100CL  101 1.000000000           1                     0    1           1\n"
      " -4  DISP        4    1\n"
      " -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n"
      " -5  D3          1    2    3    0\n";
  EXPECT_TRUE(
      test::Contains(ErrorOf(head + " -1         1         nan 0.00000E+00 0.00000E+00\n -3\n"),
                     "bad.frd:9: 'nan' is not a finite number"));
  EXPECT_TRUE(test::Contains(ErrorOf(head + " -1         1 1.00000E+00 0.00000E+00\n -3\n"),
                             "bad.frd:10: node 1 of block DISP has 2 value(s); expected 3"));
  EXPECT_TRUE(test::Contains(ErrorOf(head + " -1         1 1.00000E+00 0.00000E+00 0.00000E+00\n"),
                             "the file ends inside a block"));
  EXPECT_TRUE(test::Contains(
      ErrorOf("    2C                             1                                     2\n"),
      "bad.frd:1: block header"));
  EXPECT_TRUE(test::Contains(ErrorOf("    2C                             1          "
                                     "                           1\n -1         1 1.0\n -3\n"),
                             "node 1 has 1 coordinate(s); expected 3"));
  try {
    ReadFrd((dir_ / "missing.frd").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_TRUE(test::Contains(e.what(), "missing.frd: cannot open the CalculiX result file"));
  }
}

}  // namespace
}  // namespace railwear
