// SPDX-License-Identifier: MIT
// The [stop] rule (model/stop_rule.h): a pour ends when its rock is at rest; reaching end_time first warns.
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "model/run.h"
#include "tests/model/scene_text.h"

using namespace pastemix;
using namespace pastemix::model;
using namespace pastemix::model::test;

namespace {

// Nine 5 mm spheres dropped 2-4 cm onto the floor of a box (E reduced to 1e7 Pa: dt = 5e-5 s is ~11 % of the
// Rayleigh time). They bounce, roll and stop in well under a second.
std::string drop_scene(double end_time, const std::string& stop) {
  std::string t = fmt::format("seed = 1\ntime_step = 5e-5\nend_time = {}\n", end_time);
  t += "[domain]\nmin = [-0.05, -0.05, -0.01]\nmax = [0.15, 0.15, 0.3]\n";
  t += "[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"elastic_plastic\"\n";
  t += "[output]\ninterval = 0.25\n";
  t += stop;
  t += material("rock", 2760, 1e7, 0.19);
  t += interaction("rock/rock", 0.5, 0.5, 0.1);
  t += "[[wall]]\nname = \"box\"\ntype = \"box\"\nmaterial = \"rock\"\nmin = [0, 0, 0]\nmax = [0.1, 0.1, 0.2]\n";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      t += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = 0.005\nposition = [{}, {}, {}]\nvelocity = [0.1, 0, 0]\n",
                       0.03 + 0.02 * i, 0.03 + 0.02 * j, 0.025 + 0.005 * (i + j));
  return t;
}

const std::string kAtRest = "[stop]\nrule = \"at_rest\"\nstart = 0.05\ncheck_interval = 0.01\n";

RunSummary run_text(const std::string& text, const std::string& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir + "/drop.toml");
    f << text;
  }
  RunOptions ro;
  ro.progress = false;
  return run_scene(load_scene(dir + "/drop.toml"), dir, ro);
}

}  // namespace

TEST_CASE("stop rule: a pour ends at rest before its maximum time, with the moving mass below the limit") {
  const RunSummary r = run_text(drop_scene(3.0, kAtRest), "model_stop_rest_out");
  REQUIRE(r.stop.rule_at_rest);
  CHECK(r.stop.fired);
  CHECK(!r.failed_to_rest());
  CHECK(r.stop.time < 2.0);
  CHECK(r.stop.time > 0.05);
  CHECK(r.stop.last.moving_mass <= 1e-3);
  CHECK(r.steps == std::lround(r.stop.time / 5e-5));
  CHECK(r.stop.line().find("at rest at t = ") != std::string::npos);
  // The result file records the rule, the time it fired, the census, and ends with a snapshot at that time.
  H5Reader h5("model_stop_rest_out/drop.h5");
  CHECK(h5.attribute_string("/", "stop_rule") == "at_rest");
  CHECK(h5.attribute_int("/", "stop_fired") == 1);
  CHECK(h5.attribute_double("/", "stop_time_s") == doctest::Approx(r.stop.time));
  CHECK(h5.attribute_double("/", "moving_mass_kg") <= 1e-3);
  const auto times = h5.read_doubles("/snapshots/time");
  CHECK(times.back() == doctest::Approx(r.stop.time));
}

TEST_CASE("stop rule: a run that reaches its maximum time before rest warns with the moving mass") {
  const RunSummary r = run_text(drop_scene(0.06, "[stop]\nrule = \"at_rest\"\nstart = 0.01\n"), "model_stop_limit_out");
  CHECK(r.failed_to_rest());
  CHECK(r.stop.time == doctest::Approx(0.06));
  CHECK(r.stop.last.moving_mass > 1e-3);
  const std::string line = r.stop.line();
  CHECK(line.find("WARNING: end_time 0.06 s reached before the rock came to rest") != std::string::npos);
  CHECK(line.find(fmt::format("{:.4g} g moving", 1e3 * r.stop.last.moving_mass)) != std::string::npos);
  H5Reader h5("model_stop_limit_out/drop.h5");
  CHECK(h5.attribute_int("/", "stop_fired") == 0);
}

TEST_CASE("stop rule: without [stop] a run ends at end_time, as before") {
  const RunSummary r = run_text(drop_scene(0.02, ""), "model_stop_none_out");
  CHECK(!r.stop.rule_at_rest);
  CHECK(!r.failed_to_rest());
  CHECK(r.steps == 400);
}

TEST_CASE("stop rule: bad [stop] tables are input errors with the line") {
  auto err = [](const std::string& stop, double end = 1.0) {
    try {
      parse_scene(drop_scene(end, stop), "bad.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(err("[stop]\nrule = \"at_rest\"\nhold = 0\n").find("hold") != std::string::npos);
  CHECK(err("[stop]\nspeed = 0.01\n").find("only with rule = \"at_rest\"") != std::string::npos);
  CHECK(err("[stop]\nrule = \"at_rst\"\n").find("bad.toml:") != std::string::npos);
  CHECK(err("[stop]\nrule = \"at_rest\"\nspeed = -1\n").find("speed") != std::string::npos);
}
