// `railwear contact --kernel boussinesq|golubenko`: replaces the influence kernel after --model,
// keeping the geometry (the README's "half-space kernel on the curved grid" row is
// `--kernel boussinesq` on a conformal scene); it matches a scene that sets geometry and kernel
// explicitly, and is refused with the analytic Hertz model.
#include <string>

#include <gtest/gtest.h>

#include "tests/app/cli_runner.h"

namespace {

using railwear::test::Contains;
using railwear::test::Outcome;

class ContactKernelOptionTest : public railwear::test::CliFixture {};

// The scene's "total" summary line (area, p_max, forces).
std::string TotalLine(const std::string& out) {
  const size_t at = out.find("\ntotal");
  if (at == std::string::npos) return "";
  return out.substr(at + 1, out.find('\n', at + 1) - at - 1);
}

TEST_F(ContactKernelOptionTest, KernelOptionMatchesTheSceneKeys) {
  const std::string scene = std::string(RAILWEAR_SOURCE_DIR) + "/examples/fem/wheel_in_groove.toml";
  const Outcome option = Run("contact '" + scene + "' --accuracy draft --kernel boussinesq");
  ASSERT_EQ(option.exit_code, 0) << option.err;
  EXPECT_TRUE(Contains(option.out, "model       custom (geometry conformal, kernel boussinesq)"));
  Write("explicit.toml",
        "[scene]\nname = \"explicit\"\neffects = [\"normal\"]\n"
        "[model]\ngeometry = \"conformal\"\nkernel = \"boussinesq\"\naccuracy = \"draft\"\n"
        "[wheel]\nprofile = \"circle:10\"\nrolling_radius_mm = 460\n"
        "[rail]\nprofile = \"groove:10.1\"\n[load]\nvertical_N = 10000\n");
  const Outcome keys = Run("contact explicit.toml");
  ASSERT_EQ(keys.exit_code, 0) << keys.err;
  EXPECT_FALSE(TotalLine(option.out).empty());
  EXPECT_EQ(TotalLine(option.out), TotalLine(keys.out));
  // The paper's kernel (the scene's own) gives another answer.
  const Outcome paper = Run("contact '" + scene + "' --accuracy draft");
  EXPECT_NE(TotalLine(paper.out), TotalLine(option.out));
  // --model halfspace --kernel golubenko: planar geometry, the paper's kernel.
  const Outcome planar =
      Run("contact '" + scene + "' --accuracy draft --model halfspace --kernel golubenko");
  ASSERT_EQ(planar.exit_code, 0) << planar.err;
  EXPECT_TRUE(Contains(planar.out, "custom (geometry planar, kernel golubenko)"));
  // --kernel golubenko on the conformal scene is the conformal shorthand again.
  const Outcome same = Run("contact '" + scene + "' --accuracy draft --kernel golubenko");
  EXPECT_TRUE(Contains(same.out, "model       conformal (geometry conformal, kernel golubenko)"));
}

TEST_F(ContactKernelOptionTest, RefusedWithHertzAndUnknownKernels) {
  const std::string scene = std::string(RAILWEAR_SOURCE_DIR) + "/examples/fem/wheel_in_groove.toml";
  const Outcome hertz = Run("contact '" + scene + "' --model hertz --kernel boussinesq");
  EXPECT_EQ(hertz.exit_code, 2);
  EXPECT_TRUE(
      Contains(hertz.err, "--kernel boussinesq: expected a model with an influence kernel"));
  const Outcome unknown = Run("contact '" + scene + "' --kernel love");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(Contains(unknown.err, "--kernel"));
}

}  // namespace
