// SPDX-License-Identifier: MIT
// Scene overrides (--set key.path=value): values reach the scene, bad paths and types fail with the file.
#include "model/scene_override.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

const std::string kScene =
    "seed = 3\n"                    // 1
    "time_step = 1e-6\n"            // 2
    "end_time = 0.01\n"             // 3
    "[domain]\n"                    // 4
    "min = [-1, -1, -1]\n"          // 5
    "max = [1, 1, 1]\n"             // 6
    "[contact]\n"                   // 7
    "law = \"hertz_mindlin\"\n"     // 8
    "rolling = \"none\"\n"          // 9
    "[[material]]\n"                // 10
    "name = \"rock\"\n"             // 11
    "density = 2760\n"              // 12
    "youngs_modulus = 4.68e7\n"     // 13
    "poisson_ratio = 0.19\n"        // 14
    "[[interaction]]\n"             // 15
    "materials = \"rock/rock\"\n"   // 16
    "restitution = 0.79\n"          // 17
    "friction = 0.466\n"            // 18
    "[[particle]]\n"                // 19
    "material = \"rock\"\n"         // 20
    "radius = 0.01\n"               // 21
    "position = [0, 0, 0.5]\n";     // 22

InputError error_of(const std::string& assignment) {
  SceneDoc d = SceneDoc::parse(kScene, "s.toml");
  try {
    d.apply(assignment);
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError for " << assignment);
  return InputError("", 0, "", "");
}

}  // namespace

TEST_CASE("overrides reach the scene: top-level, nested, array element by name and by index") {
  SceneDoc d = SceneDoc::parse(kScene, "s.toml");
  d.apply("time_step=2.5e-7");
  d.apply("material.rock.youngs_modulus=1e9");
  d.apply("interaction.rock/rock.friction=0.3");
  d.apply("particle.0.position=[0, 0, 0.25]");
  d.apply("domain.max.2=2");        // an array element; integer into a float array
  d.apply("contact.rolling=constant_torque");  // bare word for a string key
  d.apply("seed=9");
  const Scene s = d.load();
  CHECK(s.config.dt == 2.5e-7);
  CHECK(s.materials[0].youngs_modulus == 1e9);
  CHECK(s.pairs[0].friction == 0.3);
  CHECK(s.particles.x[0].z == 0.25);
  CHECK(s.config.domain_max.z == 2.0);
  CHECK(s.seed == 9u);
  CHECK(s.path == "s.toml");
}

TEST_CASE("override errors name the file, the line and the path") {
  const InputError unknown = error_of("material.rock.youngs_modulu=1e9");
  CHECK(unknown.file() == "s.toml");
  CHECK(unknown.line() == 10);  // the [[material]] table that was found
  CHECK(unknown.field() == "material.rock.youngs_modulu");
  CHECK(error_of("material.granite.density=1").field() == "material.granite.density");
  const InputError type = error_of("time_step=\"fast\"");
  CHECK(type.line() == 2);
  CHECK(std::string(type.what()).find("expects a float, got a string") != std::string::npos);
  CHECK(std::string(error_of("seed=1.5").what()).find("expects an integer, got a float") != std::string::npos);
  CHECK(std::string(error_of("domain=1").what()).find("is a table") != std::string::npos);
  CHECK(std::string(error_of("time_step").what()).find("key.path=value") != std::string::npos);
}

TEST_CASE("pastemix run --set: exit 2 with the scene file for an unknown path or a wrong type") {
  const auto dir = std::filesystem::temp_directory_path() / "pastemix_override_test";
  std::filesystem::create_directories(dir);
  const auto scene = dir / "s.toml";
  std::ofstream(scene) << kScene;
  const auto unknown = test::run_pastemix("run '" + scene.string() + "' --quiet --out '" + dir.string() +
                                          "' --set physics.gravity=[0,0,0]");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.output.find("s.toml") != std::string::npos);
  CHECK(unknown.output.find("physics.gravity: unknown key path") != std::string::npos);
  const auto type = test::run_pastemix("run '" + scene.string() + "' --quiet --out '" + dir.string() +
                                       "' --set end_time=true");
  CHECK(type.exit_code == 2);
  CHECK(type.output.find("s.toml:3: end_time: expects a float, got a boolean") != std::string::npos);
  // An override file as `pastemix sweep` writes it; a malformed line names its line.
  std::ofstream(dir / "bad_overrides.toml") << "# chosen\ntime_step = 1e-6\nnot an assignment\n";
  const auto bad = test::run_pastemix("run '" + scene.string() + "' --quiet --out '" + dir.string() +
                                      "' --overrides '" + (dir / "bad_overrides.toml").string() + "'");
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("bad_overrides.toml:3:") != std::string::npos);
  std::filesystem::remove_all(dir);
}
