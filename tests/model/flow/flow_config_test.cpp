// SPDX-License-Identifier: MIT
// Reading a [flow] case: the shipped cases load; bad values are errors naming file:line and the key.
#include "model/flow/flow_config.h"

#include <doctest/doctest.h>

#include <string>

#include "base/error.h"
#include "tests/run_command.h"
#include "tests/input_error.h"

using namespace pastemix;
using namespace pastemix::flow;

namespace {
const char* kGood = R"([flow]
name = "t"
box = [0.20, 0.165, 0.25]
cell = 0.005
cfl = 0.3
end_time = 0.1
[flow.boundary]
x = "no_slip"
z_hi = "open"
[flow.paste]
density = 1850.0
viscosity = 2.0
[flow.initial]
paste_below = 0.10
)";

FlowCase parse(const std::string& text) {
  const Params file = Params::parse(text, "case.toml");
  FlowCase c = read_flow_case(file.table("flow"));
  file.finish();
  return c;
}

std::string error_of(const std::string& text) {
  return pastemix::test::input_error_of([&] { parse(text); });
}

using pastemix::test::replace;
}  // namespace

TEST_CASE("flow config: a good case gives the grid, the boundaries and the paste") {
  const FlowCase c = parse(kGood);
  CHECK(c.grid.n == std::array<int, 3>{40, 33, 50});
  CHECK(c.grid.h[1] == doctest::Approx(0.005));
  CHECK(c.grid.bc[5].type == BoundaryType::open);
  CHECK(c.grid.bc[4].type == BoundaryType::no_slip);
  CHECK(c.phases.paste->viscosity(3.0) == 2.0);
  REQUIRE(c.paste.size() == 1);
  const FlowSolver s = make_solver(c);
  CHECK(s.paste_volume() == doctest::Approx(0.20 * 0.165 * 0.10).epsilon(1e-12));
}

TEST_CASE("flow config: negative viscosity, a grid that does not fit, a CFL above 1/2: errors with file:line") {
  std::string e = error_of(replace(kGood, "viscosity = 2.0", "viscosity = -2.0"));
  CHECK(e.find("case.toml:12") != std::string::npos);
  CHECK(e.find("viscosity") != std::string::npos);
  e = error_of(replace(kGood, "cell = 0.005", "cell = 0.01"));
  CHECK(e.find("case.toml:4") != std::string::npos);
  CHECK(e.find("does not fit the box") != std::string::npos);
  CHECK(e.find("16.5 cells") != std::string::npos);
  e = error_of(replace(kGood, "cfl = 0.3", "cfl = 0.7"));
  CHECK(e.find("case.toml:5") != std::string::npos);
  CHECK(e.find("above its bound 0.5") != std::string::npos);
  e = error_of(replace(kGood, "z_hi = \"open\"", "z_hi = \"periodic\""));
  CHECK(e.find("periodic on one z side only") != std::string::npos);
  e = error_of(replace(kGood, "end_time = 0.1", "end_time = 0.1\nendtime = 3"));
  CHECK(e.find("endtime") != std::string::npos);
  e = error_of(replace(kGood, "density = 1850.0", "density = nan"));
  CHECK(e.find("case.toml:11") != std::string::npos);
}

TEST_CASE("flow config: the shipped mixing-box cases load") {
  for (const char* f : {"datasets/scenes/flow_box_still.toml", "datasets/scenes/flow_box_still_1cm.toml"}) {
    const FlowCase c = load_flow_case(pastemix::test::source_path(f));
    CHECK(c.grid.cell_count() > 0);
  }
  const auto r = pastemix::test::run_pastemix("flow run " + pastemix::test::source_path("tests/model/flow/data/bad_cfl.toml"));
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("bad_cfl.toml:6") != std::string::npos);
}
