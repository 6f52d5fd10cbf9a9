// SweepLineCost (app/sweep_plan.h), the order in which `sweep --mpi` hands out lines: its
// documented product, total MGT x load cases per step x cells per patch, on the small study.
#include <string>

#include <gtest/gtest.h>

#include "app/scene.h"
#include "app/sweep_plan.h"
#include "tests/app/sweep_test_support.h"

namespace railwear::test {
namespace {

// The small study with `from` replaced by `to`, read by the scene reader.
double CostWith(const std::string& from, const std::string& to) {
  std::string text = SmallStudyOfPasses("4e5");
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  return app::SweepLineCost(app::ParseScene(text, "<small study>"));
}

// Exact arithmetic on small integers and one decimal: only rounding in the last bit.
constexpr double kRelative = 1e-12;

TEST(SweepLineCost, IsTotalMgtTimesLoadCasesTimesCellsPerPatch) {
  // 4e5 passes of 16 t axles = 6.4 MGT; 3 spread nodes; draft: 4 cells per semi-axis, 16.
  const double base = CostWith("", "");
  EXPECT_NEAR(base, 6.4 * 3 * 16, kRelative * base);
  // Twice the passes, twice the cost.
  EXPECT_NEAR(CostWith("total_passes = 4e5", "total_passes = 8e5"), 2 * base, kRelative * base);
  // Standard accuracy: 10 cells per semi-axis instead of 4.
  EXPECT_NEAR(CostWith("accuracy = \"draft\"", "accuracy = \"standard\""), base * 100 / 16,
              kRelative * base * 7);
  // One spread node instead of three; no spread: one load case whatever the rule.
  EXPECT_NEAR(CostWith("quadrature_points = 3", "quadrature_points = 1"), base / 3,
              kRelative * base);
  EXPECT_NEAR(CostWith("std = 1.0", "std = 0.0"), base / 3, kRelative * base);
  // The adaptive rule (no quadrature_points): its typical 11 nodes.
  EXPECT_NEAR(CostWith("quadrature_points = 3\n", ""), base * 11 / 3, kRelative * base * 11 / 3);
  // The wear coefficient is not in it (documented: the estimate leaves out the wear rate).
  EXPECT_EQ(CostWith("k = 1e-4", "k = 3e-4"), base);
}

}  // namespace
}  // namespace railwear::test
