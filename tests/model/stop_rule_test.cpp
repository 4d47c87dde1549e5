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
#include "model/scene.h"
#include "model/stop_rule.h"
#include "model/world.h"
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
  CHECK(err("[stop]\nrule = \"at_rest\"\nmeasure = \"displace\"\n").find("bad.toml:") != std::string::npos);
  CHECK(err("[stop]\nmeasure = \"displacement\"\n").find("only with rule = \"at_rest\"") != std::string::npos);
}

// The displacement measure (model/stop_rule.h): a particle's speed at a check is its mean speed over the check
// interval. The world is not stepped here; its state is set between checks: a particle that oscillates in place
// (a velocity at every check, no displacement: the coupling-cycle oscillation of case 7) is at rest by
// displacement and moving by velocity; one that moved with zero velocity at the checks is the converse.
TEST_CASE("stop rule: the displacement measure judges the mean speed over the check interval, not the velocity") {
  const std::string stop = "[stop]\nrule = \"at_rest\"\ncheck_interval = 0.01\nhold = 2\nmoving_mass = 1e-6\n";
  auto rule_of = [&](const std::string& measure) {
    return parse_scene(drop_scene(1.0, stop + "measure = \"" + measure + "\"\n"), "drop.toml").stop;
  };
  CHECK(rule_of("displacement").measure == RestMeasure::displacement);
  CHECK(rule_of("velocity").measure == RestMeasure::velocity);
  const Scene scene = parse_scene(drop_scene(1.0, stop), "drop.toml");
  const long every = std::lround(0.01 / 5e-5);
  SUBCASE("oscillating in place: velocity at every check, no displacement") {
    World w = make_world(scene);
    for (auto& v : w.particles().v) v = Vec3{0, 0, 0};
    RestMonitor by_velocity(rule_of("velocity"), 5e-5, 100000), by_displacement(rule_of("displacement"), 5e-5, 100000);
    for (int k = 0; k < 4; ++k) {
      w.particles().v[3] = Vec3{0, 0, k % 2 ? 0.03 : -0.03};  // 3 cm/s, the sign of the phase
      CHECK_FALSE(by_velocity.check(w, k * every));
      // The first check records; the next two pass (hold = 2): fired at the third.
      CHECK(by_displacement.check(w, k * every) == (k >= 2));
    }
    // Fired at the third check (2 every); a fired monitor checks no more, so 3 every is not a check step.
    const std::vector<double>* s = by_displacement.mean_speeds(w, 2 * every);
    REQUIRE(s);
    for (double v : *s) CHECK(v == 0.0);
    CHECK(by_displacement.mean_speeds(w, 3 * every) == nullptr);
    CHECK(census(w, rule_of("velocity")).moving_count == 1);
  }
  SUBCASE("moved 1 mm between checks with no velocity at them: moving by displacement (0.1 m/s), not by velocity") {
    World w = make_world(scene);
    for (auto& v : w.particles().v) v = Vec3{0, 0, 0};
    RestMonitor by_velocity(rule_of("velocity"), 5e-5, 100000), by_displacement(rule_of("displacement"), 5e-5, 100000);
    for (int k = 0; k < 4; ++k) {
      w.particles().x[5].z += 1e-3;
      by_velocity.check(w, k * every);
      CHECK_FALSE(by_displacement.check(w, k * every));
    }
    CHECK(by_velocity.fired());
    const std::vector<double>* s = by_displacement.mean_speeds(w, 3 * every);
    REQUIRE(s);
    REQUIRE(s->size() == 9);
    CHECK((*s)[5] == doctest::Approx(0.1));
  }
  SUBCASE("a run with the measure writes it and the last snapshot's mean speeds, which the census used") {
    const RunSummary r = run_text(drop_scene(3.0, kAtRest + "measure = \"displacement\"\n"), "model_stop_disp_out");
    CHECK(r.stop.fired);
    CHECK(r.stop.last.moving_mass <= 1e-3);
    H5Reader h5("model_stop_disp_out/drop.h5");
    CHECK(h5.attribute_string("/", "stop_measure") == "displacement");
    const auto n = h5.read_doubles("/snapshots/time").size();
    const auto speeds = h5.read_doubles(fmt::format("/snapshots/{:06d}/mean_speed", n - 1));
    REQUIRE(speeds.size() == 9);
    for (double v : speeds) CHECK(v <= 0.01);
  }
}
