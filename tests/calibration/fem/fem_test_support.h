// Test support for the FEM pipeline tests: whether gmsh and ccx are installed (tests that need
// them skip with a message saying how to install them), and the shared test support.
#pragma once

#include <string>

#include "calibration/fem/external_program.h"
#include "core/numerics/input_error.h"
#include "tests/test_support.h"

namespace railwear::test {

namespace fs = std::filesystem;

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
