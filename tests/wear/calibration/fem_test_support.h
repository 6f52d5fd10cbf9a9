// Test support for the FEM pipeline tests: a temporary folder per test, and whether gmsh and
// ccx are installed (tests that need them skip with a message saying how to install them).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/numerics/input_error.h"
#include "wear/calibration/external_program.h"

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

// A fixture with a fresh folder dir_ per test, removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("railwear_" + std::string(info->test_suite_name()) + "_" +
                                        info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  fs::path dir_;
};

// The message why gmsh or ccx cannot be used ("" when both are found).
inline std::string MissingFemPrograms() {
  try {
    FindProgram(GmshProgram());
    FindProgram(CcxProgram());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace railwear::test
