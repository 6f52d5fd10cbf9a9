// Finding and running external programs: PATH lookup, environment overrides, the messages for
// a missing program, exit codes, logs, environment, work directory and timeouts.
#include "calibration/fem/external_program.h"

#include <cstdlib>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "tests/calibration/fem/fem_test_support.h"

namespace railwear {
namespace {

using test::TempDirTest;
namespace fs = std::filesystem;

class ExternalProgramTest : public TempDirTest {};

// Sets an environment variable for the test's lifetime (the tests of this file are the only
// code running at that point).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }

 private:
  std::string name_;
  std::optional<std::string> old_;
};

ProgramSpec NoSuchProgram() {
  return {"railwear-no-such-program", "RAILWEAR_TEST_NO_SUCH", "the test program",
          "install it from nowhere"};
}

std::string ErrorOf(const ProgramSpec& spec) {
  try {
    FindProgram(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(ExternalProgramTest, FindsProgramsOnPath) {
  const std::string sh = FindOnPath("sh");
  ASSERT_FALSE(sh.empty());
  EXPECT_EQ(sh.back(), 'h');
  EXPECT_EQ(FindOnPath("railwear-no-such-program"), "");
  EXPECT_EQ(FindOnPath(sh), sh);  // a path is taken as it is
  EXPECT_EQ(FindOnPath("/nonexistent/sh"), "");
  EXPECT_EQ(FindOnPath((dir_).string()), "");  // a directory is no program
}

TEST_F(ExternalProgramTest, MissingProgramIsBadInputWithInstallHint) {
  const std::string message = ErrorOf(NoSuchProgram());
  EXPECT_TRUE(test::Contains(message, "the test program is not installed or not on PATH"));
  EXPECT_TRUE(test::Contains(message, "install it from nowhere"));
  EXPECT_TRUE(test::Contains(message, "RAILWEAR_TEST_NO_SUCH"));

  const std::string ccx = ErrorOf({"railwear-no-such-ccx", "RAILWEAR_TEST_NO_SUCH",
                                   CcxProgram().description, CcxProgram().install_hint});
  EXPECT_TRUE(test::Contains(ccx,
                             "ccx (CalculiX) is not installed or not on PATH: install the "
                             "Debian package calculix-ccx (bash .ci/install-deps.sh)"));
}

TEST_F(ExternalProgramTest, EnvironmentOverrideWinsAndIsChecked) {
  ProgramSpec spec = NoSuchProgram();
  {
    ScopedEnv env("RAILWEAR_TEST_NO_SUCH", "sh");  // a name looked up on PATH
    EXPECT_EQ(FindProgram(spec), FindOnPath("sh"));
  }
  {
    ScopedEnv env("RAILWEAR_TEST_NO_SUCH", "/nonexistent/ccx");
    const std::string message = ErrorOf(spec);
    EXPECT_TRUE(test::Contains(message,
                               "RAILWEAR_TEST_NO_SUCH = '/nonexistent/ccx' is not an "
                               "executable file"));
  }
  {
    ScopedEnv env("RAILWEAR_TEST_NO_SUCH", "");  // empty: as if unset
    EXPECT_TRUE(test::Contains(ErrorOf(spec), "is not installed or not on PATH"));
  }
}

TEST_F(ExternalProgramTest, TrueSucceedsFalseFails) {
  ProgramRun run;
  run.argv = {"true"};
  run.work_dir = dir_.string();
  const ProgramResult ok = RunProgram(run);
  EXPECT_TRUE(ok.Succeeded());
  EXPECT_EQ(ok.exit_code, 0);
  EXPECT_GE(ok.wall_time_s, 0.0);
  EXPECT_EQ(ok.log_path, (dir_ / "program.log").string());
  EXPECT_TRUE(fs::exists(ok.log_path));

  run.argv = {"false"};
  const ProgramResult bad = RunProgram(run);
  EXPECT_FALSE(bad.Succeeded());
  EXPECT_EQ(bad.status, ProgramResult::Status::kExited);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.Describe(), "exit code 1");
}

TEST_F(ExternalProgramTest, OutputGoesToTheLogAndRunsInTheWorkDir) {
  fs::create_directories(dir_ / "work");
  ProgramRun run;
  // The test uses sh to produce output on both streams; the runner itself uses no shell.
  run.argv = {"sh", "-c", "echo out-line; echo err-line >&2; pwd; echo \"$RAILWEAR_TEST_VAR\""};
  run.work_dir = (dir_ / "work").string();
  run.log_path = "run.log";
  run.environment = {{"RAILWEAR_TEST_VAR", "value-42"}};
  const ProgramResult r = RunProgram(run);
  ASSERT_TRUE(r.Succeeded()) << r.Describe();
  const std::string log = test::ReadFile(dir_ / "work" / "run.log");
  EXPECT_TRUE(test::Contains(log, "out-line"));
  EXPECT_TRUE(test::Contains(log, "err-line"));
  EXPECT_TRUE(test::Contains(log, fs::canonical(dir_ / "work").string()));
  EXPECT_TRUE(test::Contains(log, "value-42"));
}

TEST_F(ExternalProgramTest, ArgumentsArePassedVerbatimWithoutAShell) {
  ProgramRun run;
  run.argv = {"printf", "%s|", "a b", "$HOME", "*"};
  run.work_dir = dir_.string();
  ASSERT_TRUE(RunProgram(run).Succeeded());
  EXPECT_EQ(test::ReadFile(dir_ / "program.log"), "a b|$HOME|*|");
}

TEST_F(ExternalProgramTest, MissingExecutableExitsWith127AndSaysWhy) {
  ProgramRun run;
  run.argv = {"/nonexistent/ccx", "-i", "job"};
  run.work_dir = dir_.string();
  const ProgramResult r = RunProgram(run);
  EXPECT_EQ(r.exit_code, 127);
  EXPECT_EQ(r.Describe(), "exit code 127 (could not be executed)");
  EXPECT_TRUE(test::Contains(test::ReadFile(r.log_path), "cannot execute /nonexistent/ccx"));
}

TEST_F(ExternalProgramTest, FailureMessageQuotesTheLogTail) {
  ProgramRun run;
  run.argv = {"sh", "-c",
              "for i in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do echo "
              "line$i; done; echo '*ERROR in job'; exit 201"};
  run.work_dir = dir_.string();
  try {
    RunProgramOrThrow(run, "ccx (CalculiX)");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_TRUE(test::Contains(m, "ccx (CalculiX) failed (exit code 201)"));
    EXPECT_TRUE(test::Contains(m, (dir_ / "program.log").string()));
    EXPECT_TRUE(test::Contains(m, "*ERROR in job"));
    EXPECT_TRUE(test::Contains(m, "line20"));
    EXPECT_FALSE(test::Contains(m, "line5\n"));  // only the tail (15 lines)
  }
}

TEST_F(ExternalProgramTest, TimeoutKillsTheProgram) {
  ProgramRun run;
  run.argv = {"sleep", "10"};
  run.work_dir = dir_.string();
  run.timeout_s = 0.2;
  const ProgramResult r = RunProgram(run);
  EXPECT_EQ(r.status, ProgramResult::Status::kTimedOut);
  EXPECT_LT(r.wall_time_s, 5.0);
  EXPECT_TRUE(test::Contains(r.Describe(), "timed out after"));
}

TEST_F(ExternalProgramTest, TwoProgramsRunAtOnceFromTwoThreads) {
  ProgramResult a, b;
  ProgramRun run_a, run_b;
  run_a.argv = {"sh", "-c", "sleep 0.3; echo A"};
  run_b.argv = {"sh", "-c", "sleep 0.3; echo B"};
  run_a.work_dir = run_b.work_dir = dir_.string();
  run_a.log_path = "a.log";
  run_b.log_path = "b.log";
  std::thread ta([&] { a = RunProgram(run_a); });
  std::thread tb([&] { b = RunProgram(run_b); });
  ta.join();
  tb.join();
  EXPECT_TRUE(a.Succeeded());
  EXPECT_TRUE(b.Succeeded());
  EXPECT_EQ(test::ReadFile(dir_ / "a.log"), "A\n");
  EXPECT_EQ(test::ReadFile(dir_ / "b.log"), "B\n");
}

TEST_F(ExternalProgramTest, LogTailKeepsTheLastLines) {
  std::string text;
  for (int i = 1; i <= 100; ++i) text += "row " + std::to_string(i) + "\n";
  const std::string path = Write("long.log", text);
  EXPECT_EQ(LogTail(path, 3), "row 98\nrow 99\nrow 100\n");
  EXPECT_EQ(LogTail((dir_ / "missing.log").string(), 3), "");
}

}  // namespace
}  // namespace railwear
