// Test helper: runs the built railwear binary (RAILWEAR_BINARY) in a fresh temporary directory
// per test, with stdout and stderr captured.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace railwear::test {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

// Each test gets its own working directory; the binary runs there.
class CliFixture : public TempDirTest {
 protected:
  // The shell command that runs `ENV railwear ARGS` in dir_ (without redirections).
  std::string Command(const std::string& args, const std::string& env = "") const {
    return "cd '" + dir_.string() + "' && " + env + " '" RAILWEAR_BINARY "' " + args;
  }
  // Runs `ENV railwear ARGS` in dir_ with stdout and stderr captured.
  Outcome Run(const std::string& args, const std::string& env = "") const {
    return Shell(env + " '" RAILWEAR_BINARY "' " + args);
  }
  // Runs the shell command `command` in dir_ with stdout and stderr captured.
  Outcome Shell(const std::string& command) const {
    const std::string full =
        "cd '" + dir_.string() + "' && " + command + " > stdout.txt 2> stderr.txt";
    const int status = std::system(full.c_str());
    Outcome o;
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.out = ReadFile(dir_ / "stdout.txt");
    o.err = ReadFile(dir_ / "stderr.txt");
    return o;
  }
};

}  // namespace railwear::test
