// SPDX-License-Identifier: MIT
// The moving paste in the result file and the checkpoint (model/output.h's /flow, model/checkpoint.cpp with
// FlowCoupling::save/restore): a flow run stopped mid-cycle and resumed from its checkpoint in a fresh World
// gives the bits of the run that went on (particles and the flow's fields), and `pastemix run` writes the flow
// fields of every snapshot.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "model/checkpoint.h"
#include "model/flow/solver.h"
#include "model/fluid/flow_coupling.h"
#include "model/output.h"
#include "model/stop_rule.h"
#include "model/world.h"
#include "tests/model/fluid/flow_scene.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;
namespace fs = std::filesystem;

using model::test::same_bits;

namespace {
void resume_mid_cycle(bool stick) {
  CAPTURE(stick);
  const fs::path dir = fs::absolute(fmt::format("flow_checkpoint_{}", ::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Rocks just above and in the paste: contacts, the exchange and the pending pressure impulses all in use; with
  // the implicit stick also the cycle's stuck flags (saved with the start).
  std::string text = model::test::flow_drop_scene(0.3, 20, "0.05", "0.11");
  if (stick) text.replace(text.find("coupling_interval"), 0, "implicit_stick = true\n");
  const Scene scene = model::test::scene_from(text);
  World a = make_world(scene);
  a.advance(2510);  // 125 cycles of 20 steps and 10 steps into the next
  REQUIRE(a.flow()->cycles() == 125);
  {
    RunOutput out(dir / "a.h5.part", "a.h5", scene);
    out.snapshot(a);
    const RestMonitor rest(scene.stop, scene.config.dt, 10000);
    write_checkpoint(dir / "a.checkpoint.h5", out, a, rest, 0.0, "test");
  }
  World b = make_world(scene);
  RestMonitor rest_b(scene.stop, scene.config.dt, 10000);
  RunOutput out_b(dir / "b.h5.part", "b.h5", scene);
  const CheckpointInfo info = resume_from_checkpoint(dir / "a.checkpoint.h5", scene, b, rest_b, out_b, dir / "b.h5.part");
  CHECK(info.step == 2510);
  a.advance(1490);
  b.advance(1490);
  CHECK(b.flow()->cycles() == a.flow()->cycles());
  CHECK(same_bits(a.particles().x, b.particles().x));
  CHECK(same_bits(a.particles().v, b.particles().v));
  const flow::FlowSolver& fa = a.flow()->solver();
  const flow::FlowSolver& fb = b.flow()->solver();
  for (int c = 0; c < 3; ++c) CHECK(same_bits(fa.velocity()[c], fb.velocity()[c]));
  CHECK(same_bits(fa.pressure(), fb.pressure()));
  CHECK(same_bits(fa.alpha(), fb.alpha()));
  CHECK(same_bits(fa.fluid_fraction(), fb.fluid_fraction()));
  fs::remove_all(dir);
}
}  // namespace

TEST_CASE("flow checkpoint: resumed mid-cycle in a fresh World, the run goes on with the same bits") {
  resume_mid_cycle(false);
  resume_mid_cycle(true);
}

// The flow state's raw structs are tagged by size (flow_coupling.cpp flow_sizes_tag): a checkpoint of a build
// whose cycle stats had another field (session 15: one double added) says so, instead of "damaged".
TEST_CASE("flow checkpoint: a flow state of another build is named as another version, not read") {
  const Scene scene = model::test::scene_from(model::test::flow_drop_scene(0.3, 20, "0.05", "0.11"));
  World a = make_world(scene);
  a.advance(30);
  std::vector<char> bytes = a.flow()->save();
  const std::string tag = "flow state: CycleStats ";
  const auto it = std::search(bytes.begin(), bytes.end(), tag.begin(), tag.end());
  REQUIRE(it != bytes.end());
  char& digit = *(it + static_cast<long>(tag.size()));
  digit = digit == '9' ? '8' : '9';  // another size of CycleStats
  World b = make_world(scene);
  b.advance(30);
  auto& flow = const_cast<fluid::FlowCoupling&>(*b.flow());  // the test's way in: World keeps it const
  try {
    flow.restore(bytes, b.particles());
    FAIL("restored a flow state of another build");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("flow state written by another version of pastemix") != std::string::npos);
  }
  CHECK_NOTHROW(flow.restore(a.flow()->save(), b.particles()));
}

// The .xmf beside a flow result: a "paste" collection on the 7 x 7 x 13 corner nodes of the 6 x 6 x 12 cells of
// 1 cm from the origin (0, 0, 0), and every HDF DataItem (particles and paste) names a dataset of the .h5 whose
// dimensions are the ones stated, so ParaView reads what is there.
static void check_xdmf(const fs::path& xmf, const H5Reader& h) {
  std::ifstream in(xmf);
  const std::string x((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(x.find("<Grid Name=\"paste\" GridType=\"Collection\" CollectionType=\"Temporal\">") != std::string::npos);
  CHECK(x.find("TopologyType=\"3DCoRectMesh\" Dimensions=\"13 7 7\"") != std::string::npos);
  CHECK(x.find("Format=\"XML\">0 0 0</DataItem>") != std::string::npos);
  CHECK(x.find("Format=\"XML\">0.01 0.01 0.01</DataItem>") != std::string::npos);
  const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">flow_drop\.h5:([^<]+)</DataItem>)re");
  int items = 0, flow_items = 0;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), item); it != std::sregex_iterator(); ++it, ++items) {
    std::istringstream dims((*it)[1].str());
    std::vector<std::uint64_t> want;
    for (std::uint64_t d; dims >> d;) want.push_back(d);
    const std::string path = (*it)[2].str();
    flow_items += path.rfind("/flow/", 0) == 0 ? 1 : 0;
    CHECK_MESSAGE(h.dims(path) == want, path);
  }
  const auto snaps = h.read_doubles("/snapshots/time").size();
  CHECK(flow_items == static_cast<int>(4 * snaps));  // paste and fluid fractions, pressure, velocity
  CHECK(items > flow_items);
}

TEST_CASE("flow output: the shipped flow_drop scene runs and writes the grid, each snapshot's flow fields and the paste volume") {
  const fs::path dir = fs::absolute(fmt::format("flow_output_{}", ::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = pastemix::test::run_pastemix(
      fmt::format("run '{}' --set end_time=0.2 --out '{}' --quiet --threads 1",
                  pastemix::test::source_path("datasets/scenes/flow_drop.toml"), dir.string()));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const H5Reader h(dir / "flow_drop.h5");
  CHECK(h.attribute_string("/flow", "dynamics") == "flow");
  CHECK(h.attribute_int("/flow", "nx") == 6);
  CHECK(h.attribute_int("/flow", "nz") == 12);
  CHECK(h.attribute_int("/flow", "coupling_interval") == 50);
  CHECK(h.attribute_int("/flow", "cycles") == 200);
  // The flow's cost: every cycle solved the pressure (the rocks move the fluid), and it took time.
  CHECK(h.attribute_int("/flow", "pressure_iterations") >= 200);
  CHECK(h.attribute_int("/flow", "viscous_iterations") >= 0);
  CHECK(h.attribute_double("/flow", "solver_seconds") > 0.0);
  const std::vector<double> alpha0 = h.read_doubles("/flow/snapshots/000000/paste_fraction");
  REQUIRE(alpha0.size() == 6 * 6 * 12);
  // 6 cm of paste in 1 cm cells at the start: the lower six layers full, the upper six empty.
  for (std::size_t c = 0; c < alpha0.size(); ++c) CHECK(std::abs(alpha0[c] - (c < 6 * 6 * 6 ? 1.0 : 0.0)) < 1e-12);
  CHECK(h.read_doubles("/flow/snapshots/000002/velocity").size() == 3 * alpha0.size());
  CHECK(h.read_doubles("/flow/snapshots/000002/pressure").size() == alpha0.size());
  // The paste keeps its volume (Weymouth & Yue's transport) while the rocks go in: 0.06^2 x 0.06 m3.
  const std::vector<double> volume = h.read_doubles("/flow/timeseries/paste_volume");
  REQUIRE(!volume.empty());
  for (double v : volume) CHECK(std::abs(v - 0.06 * 0.06 * 0.06) < 1e-12);
  CHECK(h.attribute_double("/", "fluid_solids_fraction") == 0.725);  // the scene's, for the maps' dried paste
  check_xdmf(dir / "flow_drop.xmf", h);
  fs::remove_all(dir);
}
