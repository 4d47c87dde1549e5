// SPDX-License-Identifier: MIT
// [[fluid]] dynamics (model/fluid/fluid_scene.h): "at_rest" is the default and reads nothing more; "flow" needs
// a grid that tiles the region, a top inside the domain, a kernel width at or above its minimum, a coupling
// interval >= 1, a regularisation with a yield stress, no collective rule and no second region. Every error
// names the scene file, its line and key.
#include <array>
#include <cmath>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "model/scene.h"
#include "model/scene_doc.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;
namespace fs = std::filesystem;

namespace {

struct Dir {
  fs::path path = fs::temp_directory_path() / fmt::format("pastemix_dynamics_{}", static_cast<long>(::getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() { fs::remove_all(path); }
};

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// The tiny mixing scene (domain z up to 0.35 m, region 6 x 6 cm, surface 6 cm) with the paste's values typed in.
std::string tiny_scene() {
  std::ifstream in(test::source_path("tests/app/study/data/rheology_tiny.toml"));
  std::stringstream s;
  s << in.rdbuf();
  return with(with(s.str(), "rheology_from = \"../../../../out/lab/parameters.toml\"",
                   "density = 1789.4\nyield_stress = 46.0\nplastic_viscosity = 0.2"),
              "solids_fraction = 0.725", "solids_fraction = 0.725\n#DYN");
}

std::string error_of(const Dir& d, const std::string& text) {
  std::ofstream(d.path / "scene.toml") << text;
  try {
    load_scene(d.path / "scene.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The error names the scene and a line, and says `what`.
void says(const std::string& e, const std::string& what) {
  CHECK_MESSAGE(std::regex_search(e, std::regex("scene\\.toml:[0-9]+")), e);
  CHECK_MESSAGE(e.find(what) != std::string::npos, e);
}

}  // namespace

TEST_CASE("fluid scene: dynamics is at_rest by default and when named, and reads no flow keys then") {
  Dir d;
  CHECK(error_of(d, tiny_scene()).empty());
  CHECK(error_of(d, with(tiny_scene(), "#DYN", "dynamics = \"at_rest\"")).empty());
  says(error_of(d, with(tiny_scene(), "#DYN", "cell = 0.005")), "is a key of dynamics = \"flow\"");
  says(error_of(d, with(tiny_scene(), "#DYN", "dynamics = \"moving\"")), "dynamics");
}

TEST_CASE("fluid scene: dynamics = flow without a grid, with a kernel below its minimum, or not fitting the domain") {
  Dir d;
  auto flow = [&](const std::string& keys) { return error_of(d, with(tiny_scene(), "#DYN", "dynamics = \"flow\"\n" + keys)); };
  says(flow(""), "needs the flow grid, one of: cell = SIZE");
  says(flow("cell = 0.005\ncells = [12, 12, 30]"), "needs the flow grid, one of");
  says(flow("cell = 0.005\nkernel_width = 1.0"), "kernel_width = 1 is below its minimum 1.2091");
  says(flow("cell = 0.005\ntop = 0.4"), "top = 0.4 m is above the [domain] box");
  says(flow("cell = 0.005\ntop = 0.05"), "must lie above the surface");
  says(flow("cell = 0.007"), "x extent (0.06 m) is not a whole number of 0.007 m cells");
  says(flow("cell = 0.005\ntop = 0.1525"), "height from bottom to top (0.1525 m) is not a whole number");
  // The region itself reaching outside the domain (the existing check, which "flow" relies on).
  says(error_of(d, with(with(tiny_scene(), "#DYN", "dynamics = \"flow\"\ncell = 0.005"), "x = [0.0, 0.06]",
                        "x = [0.0, 0.1]")),
       "reaches outside the [domain] box");
}

TEST_CASE("fluid scene: a valid dynamics = flow region is the flow pass's, with its interval and regularisation") {
  Dir d;
  auto flow = [&](const std::string& keys) { return error_of(d, with(tiny_scene(), "#DYN", "dynamics = \"flow\"\n" + keys)); };
  const std::string grid = "cell = 0.005\ntop = 0.15\nkernel_width = 2.5\n";
  // A yield-stress paste in the flow solver is regularised, and m is never defaulted.
  says(flow(grid), "needs regularisation = m");
  says(flow(grid + "regularisation = 100\ncoupling_interval = 0"), "coupling_interval = 0 must be >= 1");
  says(flow(grid + "regularisation = 100\ncollective = \"bearing_capacity\""), "is for dynamics = \"at_rest\" only");
  says(error_of(d, with(tiny_scene(), "#DYN", "regularisation = 100")), "is a key of dynamics = \"flow\"");
  // A second region beside a flow region (either order).
  const std::string second = "[[fluid]]\nname = \"second\"\nx = [0.0, 0.06]\ny = [0.0, 0.06]\nbottom = 0.0\n"
                             "surface = 0.01\ndensity = 1000\nrheology = \"newtonian\"\nviscosity = 0.001\n";
  says(error_of(d, with(tiny_scene(), "#DYN", "dynamics = \"flow\"\n" + grid + "regularisation = 100\n" + second)),
       "has that one [[fluid]] region only");
  CHECK(error_of(d, with(tiny_scene(), "#DYN", "dynamics = \"flow\"\n" + grid + "regularisation = 100\ncoupling_interval = 20")).empty());
  std::ofstream(d.path / "scene.toml")
      << with(tiny_scene(), "#DYN", "dynamics = \"flow\"\n" + grid + "regularisation = 100\ncoupling_interval = 20");
  const Scene s = load_scene(d.path / "scene.toml");
  CHECK(s.plan.flow);
  CHECK_FALSE(s.plan.fluid);  // the at-rest field never sees it
  REQUIRE(s.fluid.size() == 1);
  CHECK(s.fluid[0].flow);
  CHECK(s.fluid[0].coupling_interval == 20);
  CHECK(s.fluid[0].regularisation == 100.0);
  CHECK(s.fluid[0].kernel_width == 2.5);
  CHECK(s.fluid[0].flow_cells == std::array<int, 3>{12, 12, 30});  // 0.06 x 0.06 x 0.15 m in 5 mm cells
  CHECK(s.fluid[0].flow_time_step == 0.0);  // the solver's default
}

TEST_CASE("fluid scene: flow_time_step caps the flow's sub-step in a cycle, positive, a key of flow only") {
  Dir d;
  const std::string flow = "dynamics = \"flow\"\ncell = 0.005\ntop = 0.15\nregularisation = 100\n";
  says(error_of(d, with(tiny_scene(), "#DYN", flow + "flow_time_step = 0")), "flow_time_step");
  says(error_of(d, with(tiny_scene(), "#DYN", flow + "flow_time_step = -1e-3")), "flow_time_step");
  says(error_of(d, with(tiny_scene(), "#DYN", "flow_time_step = 1e-3")), "is a key of dynamics = \"flow\"");
  std::ofstream(d.path / "scene.toml") << with(tiny_scene(), "#DYN", flow + "flow_time_step = 1e-3");
  CHECK(load_scene(d.path / "scene.toml").fluid[0].flow_time_step == 1e-3);
}

TEST_CASE("fluid scene: cells = [nx, ny, nz] sets a nearly cubic grid that need not divide by one size") {
  Dir d;
  auto scene = [&](const std::string& keys) {
    return with(tiny_scene(), "#DYN", "dynamics = \"flow\"\nregularisation = 100\ntop = 0.15\n" + keys);
  };
  auto flow = [&](const std::string& keys) { return error_of(d, scene(keys)); };
  says(flow("cells = [6, 6]"), "cells");
  says(flow("cells = [6, 0, 15]"), "must be whole numbers >= 1 (axis 1: 0)");
  says(flow("cells = [6, 6.5, 15]"), "must be whole numbers >= 1 (axis 1: 6.5)");
  says(flow("cells = [6, 4, 15]"), "more than 1.2 apart");  // 1 cm x 1.5 cm x 1 cm
  // 0.06 x 0.06 x 0.15 m in 6 x 5 x 15 cells: 1 cm x 1.2 cm x 1 cm, at the limit, is allowed.
  std::ofstream(d.path / "scene.toml") << scene("cells = [6, 5, 15]");
  const Scene s = load_scene(d.path / "scene.toml");
  REQUIRE(s.fluid.size() == 1);
  CHECK(s.fluid[0].flow_cells == std::array<int, 3>{6, 5, 15});
  CHECK(s.fluid[0].flow_cell == doctest::Approx(std::cbrt(0.01 * 0.012 * 0.01)).epsilon(1e-12));
}

TEST_CASE("fluid scene: implicit_stick is off by default, a boolean, and a key of flow only") {
  Dir d;
  const std::string flow = "dynamics = \"flow\"\ncell = 0.005\ntop = 0.15\nregularisation = 100\n";
  says(error_of(d, with(tiny_scene(), "#DYN", flow + "implicit_stick = 1.5")), "implicit_stick");
  says(error_of(d, with(tiny_scene(), "#DYN", "implicit_stick = true")), "is a key of dynamics = \"flow\"");
  std::ofstream(d.path / "scene.toml") << with(tiny_scene(), "#DYN", flow);
  CHECK_FALSE(load_scene(d.path / "scene.toml").fluid[0].implicit_stick);
  std::ofstream(d.path / "scene.toml") << with(tiny_scene(), "#DYN", flow + "implicit_stick = true");
  CHECK(load_scene(d.path / "scene.toml").fluid[0].implicit_stick);
}

// A region at rest may carry its flow variant's numerics in a [fluid.flow] sub-table (the mixing scenes' frozen
// numerics, issue 22): they are checked as for "flow" (file and line of the sub-table's key) but unused until
// dynamics = "flow" is set; the same key in the region and the sub-table, or a flow key in the region of a
// region at rest, is an error.
TEST_CASE("fluid scene: a [fluid.flow] sub-table holds the flow numerics, checked at rest and used with dynamics = flow") {
  Dir d;
  const std::string numerics = "[fluid.flow]\ncells = [6, 6, 15]\ntop = 0.15\nkernel_width = 2.0\nregularisation = 100.0\n"
                               "coupling_interval = 50\nimplicit_stick = true\n\n[[factory]]";
  // dynamics written out, so that an override can switch it (overrides replace keys the scene has).
  const std::string at_rest = with(with(tiny_scene(), "[[factory]]", numerics), "#DYN", "dynamics = \"at_rest\"\n#DYN");
  CHECK(error_of(d, at_rest).empty());
  std::ofstream(d.path / "scene.toml") << at_rest;
  const Scene rest = load_scene(d.path / "scene.toml");
  CHECK_FALSE(rest.fluid[0].flow);
  CHECK(rest.plan.fluid);
  CHECK_FALSE(rest.plan.flow);
  const Scene flow = model::load_scene(d.path / "scene.toml", std::vector<std::string>{"fluid.0.dynamics=\"flow\""});
  CHECK(flow.plan.flow);
  CHECK(flow.fluid[0].flow);
  CHECK(flow.fluid[0].flow_cells == std::array<int, 3>{6, 6, 15});
  CHECK(flow.fluid[0].coupling_interval == 50);
  CHECK(flow.fluid[0].regularisation == 100.0);
  CHECK(flow.fluid[0].implicit_stick);
  // Checked while at rest, with the sub-table's line; an unknown key there is named too.
  says(error_of(d, with(at_rest, "cells = [6, 6, 15]", "cells = [6, 4, 15]")), "more than 1.2 apart");
  says(error_of(d, with(at_rest, "coupling_interval = 50", "coupling_interval = 50\ncoupling_intervall = 5")),
       "coupling_intervall");
  says(error_of(d, with(at_rest, "#DYN", "top = 0.15")), "set both here and in the region's [fluid.flow] table");
  says(error_of(d, with(tiny_scene(), "#DYN", "top = 0.15")), "keeps its flow numerics in a [fluid.flow] sub-table");
  // The collective rule of the region at rest must be switched off with it.
  const std::string collective = with(at_rest, "#DYN", "collective = \"bearing_capacity\"");
  CHECK(error_of(d, collective).empty());
  std::ofstream(d.path / "scene.toml") << collective;
  try {
    model::load_scene(d.path / "scene.toml", std::vector<std::string>{"fluid.0.dynamics=\"flow\""});
    FAIL("the collective rule was accepted with dynamics = flow");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("set collective = \"none\"") != std::string::npos);
  }
  CHECK(model::load_scene(d.path / "scene.toml", std::vector<std::string>{"fluid.0.dynamics=\"flow\"", "fluid.0.collective=\"none\""}).fluid[0].flow);
}

// The shipped flow variant of the mixing scenes (issue 22's frozen numerics): every case takes the overrides file
// (its keys are added to the one [[fluid]] region); case 3, whose paste is typed in, loads as a flow region
// with them, and without the file as the at-rest scene it was. (The other cases read their paste from the lab
// store, out/lab/parameters.toml, made by the main job.)
TEST_CASE("fluid scene: the mixing scenes with mixing_flow.overrides.toml are flow regions with the frozen numerics") {
  const fs::path overrides = test::source_path("datasets/scenes/mixing_flow.overrides.toml");
  for (int c = 1; c <= 7; ++c) {
    CAPTURE(c);
    SceneDoc d = SceneDoc::parse_file(test::source_path(fmt::format("datasets/scenes/mixing_case{}.toml", c)));
    CHECK_FALSE(d.has("fluid.0.dynamics"));
    d.apply_file(overrides);
    CHECK(d.string("fluid.0.dynamics") == "flow");
    CHECK(d.string("fluid.0.collective") == "none");
    CHECK(d.number("time_step") == 2e-5);
  }
  SceneDoc c3 = SceneDoc::parse_file(test::source_path("datasets/scenes/mixing_case3.toml"));
  CHECK_FALSE(c3.load().fluid[0].flow);
  c3.apply_file(overrides);
  const Scene s = c3.load();
  REQUIRE(s.fluid.size() == 1);
  const fluid::FluidRegion& r = s.fluid[0];
  CHECK(r.flow);
  CHECK_FALSE(r.collective);
  CHECK(r.flow_cells == std::array<int, 3>{20, 16, 15});
  CHECK(r.flow_top == 0.15);
  CHECK(r.kernel_width == 2.0);
  CHECK(r.regularisation == 100.0);
  CHECK(r.coupling_interval == 50);
  CHECK(r.implicit_stick);
  CHECK(s.end_time == 10.0);
}

// Chapter-7 test 3 with the paste moving: the overrides carry the frozen numerics' lengths and times over (1 cm
// cells over the 36 x 36 cm box to its 20 cm walls, kernel 2, m = 100 s, a ~1 ms cycle at 9e-6 s, the stick) and
// judge rest by the displacement measure.
TEST_CASE("fluid scene: pour_ch7_test3 with pour_ch7_flow.overrides.toml is a flow region of 1 cm cells and 1 ms cycles") {
  SceneDoc d = SceneDoc::parse_file(test::source_path("datasets/scenes/pour_ch7_test3.toml"));
  CHECK_FALSE(d.load().fluid[0].flow);
  d.apply_file(test::source_path("datasets/scenes/pour_ch7_flow.overrides.toml"));
  const Scene s = d.load();
  REQUIRE(s.fluid.size() == 1);
  const fluid::FluidRegion& r = s.fluid[0];
  CHECK(r.flow);
  CHECK_FALSE(r.collective);
  CHECK(r.flow_cells == std::array<int, 3>{36, 36, 20});
  CHECK(r.flow_top == 0.20);
  CHECK(r.kernel_width == 2.0);
  CHECK(r.regularisation == 100.0);
  CHECK(r.implicit_stick);
  CHECK(s.config.dt == 9e-6);
  CHECK(static_cast<double>(r.coupling_interval) * s.config.dt == doctest::Approx(1e-3).epsilon(2e-3));  // the chapter-3 cycle, 1 ms
  // Rest judged by each rock's mean speed between checks (case 7's cycle-locked oscillation never rests by velocity).
  CHECK(s.stop.measure == RestMeasure::displacement);
}
