// `railwear sweep --slurm` past Slurm's MaxArraySize (issue 19): a plan of more lines than one
// job array may hold is submitted in slices, each task running line RAILWEAR_SWEEP_OFFSET +
// SLURM_ARRAY_TASK_ID. submit.sh is run against a stand-in `sbatch` on PATH that records its
// arguments (the slices, their offsets and the merge job's dependency on all of them), and the
// array script is run as Slurm runs a task of the last slice.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/app/cli_runner.h"
#include "tests/app/sweep_test_support.h"

namespace railwear::test {
namespace {

// Five lines: the wear coefficient at five values.
const char* const kFiveLinePlan = R"([sweep]
scene = "base.toml"
out_dir = "runs"

[[axis]]
key = "wear.k"
values = [1.0e-4, 1.2e-4, 1.4e-4, 1.6e-4, 1.8e-4]
)";

// A stand-in sbatch: appends its arguments to sbatch.log and prints a job id (101, 102, ...).
const char* const kFakeSbatch = R"(#!/bin/bash
echo "$*" >> "$(dirname "$0")/../sbatch.log"
echo $((100 + $(wc -l < "$(dirname "$0")/../sbatch.log")))
)";

class SweepSlurmSliceTest : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    Write("base.toml", SmallStudyOfPasses("3e4"));
    Write("plan.toml", kFiveLinePlan);
    fs::create_directories(dir_ / "bin");
    Write("bin/sbatch", kFakeSbatch);
    fs::permissions(dir_ / "bin/sbatch", fs::perms::owner_all);
  }
  std::vector<std::string> SbatchCalls() const {
    std::vector<std::string> calls;
    std::istringstream in(ReadFile(dir_ / "sbatch.log"));
    for (std::string line; std::getline(in, line);) calls.push_back(line);
    return calls;
  }
};

TEST_F(SweepSlurmSliceTest, APlanPastMaxArraySizeIsSubmittedInSlicesWithTheirOffsets) {
  const Outcome o = Run("sweep plan.toml --slurm --max-array-size 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.out, "5 lines in 3 slices of at most 2 task(s)")) << o.out;
  const std::string array = ReadFile(dir_ / "runs/sweep.sbatch");
  EXPECT_TRUE(Contains(array, "#SBATCH --array=0-1\n")) << array;
  EXPECT_TRUE(Contains(array, "--index \"$((${RAILWEAR_SWEEP_OFFSET:-0} + SLURM_ARRAY_TASK_ID))\"\n"))
      << array;

  // Every slice submitted with its offset, the merge job after all of them.
  const std::string runs = fs::weakly_canonical(dir_ / "runs").string();
  const Outcome submit = Shell("PATH=\"$PWD/bin:$PATH\" runs/submit.sh");
  ASSERT_EQ(submit.exit_code, 0) << submit.err;
  std::vector<std::string> calls = SbatchCalls();
  ASSERT_EQ(calls.size(), 4u) << submit.out;
  EXPECT_EQ(calls[0], "--parsable --export=ALL,RAILWEAR_SWEEP_OFFSET=0 --array=0-1 " + runs +
                          "/sweep.sbatch");
  EXPECT_EQ(calls[1], "--parsable --export=ALL,RAILWEAR_SWEEP_OFFSET=2 --array=0-1 " + runs +
                          "/sweep.sbatch");
  EXPECT_EQ(calls[2], "--parsable --export=ALL,RAILWEAR_SWEEP_OFFSET=4 --array=0-0 " + runs +
                          "/sweep.sbatch");
  EXPECT_EQ(calls[3], "--parsable --dependency=afterok:101:102:103 " + runs + "/merge.sbatch");
  EXPECT_TRUE(Contains(submit.out, "job array(s) 101:102:103")) << submit.out;

  // Resubmitting one line of the last slice by its offset and task id.
  const Outcome again =
      Shell("RAILWEAR_SWEEP_OFFSET=4 PATH=\"$PWD/bin:$PATH\" runs/submit.sh --array=0");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  calls = SbatchCalls();
  ASSERT_EQ(calls.size(), 6u);
  EXPECT_EQ(calls[4], "--parsable --export=ALL,RAILWEAR_SWEEP_OFFSET=4 --array=0 " + runs +
                          "/sweep.sbatch");
  EXPECT_EQ(calls[5], "--parsable --dependency=afterok:105 " + runs + "/merge.sbatch");

  // Task 0 of the last slice runs line 4, and only it.
  const Outcome ids = Run("sweep plan.toml --list");
  ASSERT_EQ(ids.exit_code, 0) << ids.err;
  const std::vector<std::string> manifest = ManifestIds(ids.out);
  ASSERT_EQ(manifest.size(), 5u);
  const Outcome task = Shell("RAILWEAR_SWEEP_OFFSET=4 SLURM_ARRAY_TASK_ID=0 bash runs/sweep.sbatch");
  ASSERT_EQ(task.exit_code, 0) << task.err;
  for (size_t i = 0; i < manifest.size(); ++i) {
    EXPECT_EQ(fs::exists(dir_ / "runs" / (manifest[i] + ".sqlite")), i == 4) << i;
  }
  // The merge job refuses and says how to resubmit the missing lines, slice by slice.
  EXPECT_TRUE(Contains(ReadFile(dir_ / "runs/merge.sbatch"), " --max-array-size 2\n"));
  const Outcome merge = Shell("bash runs/merge.sbatch");
  EXPECT_EQ(merge.exit_code, 2) << merge.err;
  EXPECT_TRUE(Contains(merge.err, "(not run: 0-3; started, not complete: none)")) << merge.err;
  EXPECT_TRUE(Contains(merge.err, "`RAILWEAR_SWEEP_OFFSET=0 " + runs +
                                      "/submit.sh --array=0-1`, `RAILWEAR_SWEEP_OFFSET=2 " + runs +
                                      "/submit.sh --array=0-1`"))
      << merge.err;
}

TEST_F(SweepSlurmSliceTest, APlanThatFitsOneArrayHasNoOffsetAndBadSizesAreRefused) {
  ASSERT_EQ(Run("sweep plan.toml --slurm --max-array-size 5").exit_code, 0);
  const std::string array = ReadFile(dir_ / "runs/sweep.sbatch");
  EXPECT_TRUE(Contains(array, "#SBATCH --array=0-4\n"));
  EXPECT_TRUE(Contains(array, "--index \"$SLURM_ARRAY_TASK_ID\"\n")) << array;
  EXPECT_FALSE(Contains(ReadFile(dir_ / "runs/submit.sh"), "RAILWEAR_SWEEP_OFFSET"));
  const Outcome zero = Run("sweep plan.toml --slurm --max-array-size 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_TRUE(Contains(zero.err, "--max-array-size 0: expected the cluster's MaxArraySize"))
      << zero.err;
  const Outcome alone = Run("sweep plan.toml --max-array-size 2");  // needs --slurm or --merge
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_TRUE(Contains(alone.err, "expected --slurm or --merge")) << alone.err;
}

}  // namespace
}  // namespace railwear::test
