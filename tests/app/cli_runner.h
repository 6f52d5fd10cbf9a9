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

namespace railwear::test {

namespace fs = std::filesystem;

inline ::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n  text:  " << text << "\n  lacks: " << part;
}

inline std::string ReadFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

// Each test gets its own working directory; the binary runs there.
class CliFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("railwear_") + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The shell command that runs `ENV railwear ARGS` in dir_ (without redirections).
  std::string Command(const std::string& args, const std::string& env = "") const {
    return "cd '" + dir_.string() + "' && " + env + " '" RAILWEAR_BINARY "' " + args;
  }
  // Runs `ENV railwear ARGS` in dir_ with stdout and stderr captured.
  Outcome Run(const std::string& args, const std::string& env = "") const {
    const std::string command = Command(args, env) + " > stdout.txt 2> stderr.txt";
    const int status = std::system(command.c_str());
    Outcome o;
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.out = ReadFile(dir_ / "stdout.txt");
    o.err = ReadFile(dir_ / "stderr.txt");
    return o;
  }
  void Write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }
  fs::path dir_;
};

}  // namespace railwear::test
