// SPDX-License-Identifier: MIT
// The repose-angle QoI refuses an unfinished pile: spheres still in the funnel are a failure, not an angle.
#include "app/study/qoi.h"

#include <doctest/doctest.h>

#include <string>

#include "app/study/sweep.h"
#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::app::study;

TEST_CASE("repose_angle fails while spheres are still inside the funnel, naming the wall and the time") {
  auto d = model::SceneDoc::parse_file(test::source_path("datasets/scenes/funnel_lift.toml"));
  d.set("end_time", "0.001");  // 200 steps: the plate is still in, every sphere is in the funnel
  std::string what;
  try {
    run_once(d, "repose_angle");
  } catch (const RuntimeFailure& e) {
    what = e.what();
  }
  CHECK(what.find("still inside wall 'funnel'") != std::string::npos);
  CHECK(what.find("t = 0.001 s") != std::string::npos);
}
