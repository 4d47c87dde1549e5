// SPDX-License-Identifier: MIT
// `pastemix validate coupling` (app/cmd_coupling.cpp): the Bingham sphere prints its figures and holds, a box
// that is not a whole number of cells is bad input (exit 2, naming the options).
#include <doctest/doctest.h>

#include <string>

#include "tests/run_command.h"

namespace pastemix {

TEST_CASE("pastemix validate coupling sphere: Bingham Y = 0.08 holds, and a box of 8 / 3 cells is exit 2") {
  const auto held = test::run_pastemix("validate coupling sphere --yield-number 0.08");
  CHECK(held.exit_code == 0);
  CHECK(held.output.find("sphere Bingham Y = 0.08") != std::string::npos);
  const auto bad = test::run_pastemix("validate coupling sphere --cell-over-d 3");
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("--cell-over-d 3 / --box-over-d 8") != std::string::npos);
  CHECK(bad.output.find("whole number") != std::string::npos);
}

}  // namespace pastemix
