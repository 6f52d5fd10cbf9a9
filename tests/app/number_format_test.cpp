#include "app/number_format.h"

#include <gtest/gtest.h>

namespace railwear::app {
namespace {

TEST(NumberFormat, ValuesThatRoundToZeroPrintWithoutASign) {
  // history steps printed -0.0000 for a wear measure of -1e-9 mm (issue 17).
  EXPECT_EQ(FixedNoNegativeZero(-1e-9, 4), "0.0000");
  EXPECT_EQ(FixedNoNegativeZero(-0.0, 3), "0.000");
  EXPECT_EQ(FixedNoNegativeZero(-0.00004, 4), "0.0000");
  EXPECT_EQ(FixedNoNegativeZero(-0.00005, 4), "-0.0001");  // a real negative value keeps it
  EXPECT_EQ(FixedNoNegativeZero(-35.008, 3), "-35.008");
  EXPECT_EQ(FixedNoNegativeZero(2.5, 4), "2.5000");
}

}  // namespace
}  // namespace railwear::app
