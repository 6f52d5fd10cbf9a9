// The fixture of the `railwear fem-reference` tests: the CLI fixture, the message a config
// file's reading throws, and whether gmsh and ccx are installed.
#pragma once

#include <string>

#include "app/fem_reference_command.h"
#include "core/numerics/input_error.h"
#include "tests/app/cli_runner.h"
#include "tests/calibration/fem/fem_test_support.h"

namespace railwear::test {

class FemReferenceFixture : public CliFixture {
 protected:
  // The InputError message of reading config text ("" when it reads).
  std::string ConfigError(const std::string& text) const {
    Write("bad.toml", text);
    try {
      railwear::app::ReadFemReferenceConfig((dir_ / "bad.toml").string(), "");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

}  // namespace railwear::test
