// SPDX-License-Identifier: MIT
// The rolling-resistance calibration's scene edit (its surrogate: surrogate_test.cpp; the command on a
// tiny pile: study_tasks_test.cpp).
#include "app/study/calibrate.h"

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::app::study;

TEST_CASE("every interaction's rolling_friction is set") {
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/repose_ch5.toml"));
  const auto d = with_rolling_resistance(base, 0.14);
  CHECK(std::stod(d.get("interaction.rock/rock.rolling_friction")) == 0.14);
  CHECK(std::stod(d.get("interaction.rock/steel.rolling_friction")) == 0.14);
  CHECK(d.load().pairs[0].rolling_friction == 0.14);
}
