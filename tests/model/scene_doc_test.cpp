// SPDX-License-Identifier: MIT
// Scene overrides (--set key.path=value): values reach the scene, bad paths and types fail with the file.
#include "model/scene_doc.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

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

TEST_CASE("an override adds a key the scene lacks to a table it has, checked by the loader like any key") {
  SceneDoc d = SceneDoc::parse(kScene, "s.toml");
  d.apply("contact.rolling_model=\"x\"");
  CHECK(d.has("contact.rolling_model"));
  CHECK_THROWS_WITH_AS(d.load(), doctest::Contains("unknown key"), InputError);
  SceneDoc e = SceneDoc::parse(kScene, "s.toml");
  e.apply("particle.0.velocity=[0, 0, -1]");  // a key the loader knows, absent from the scene
  CHECK(e.load().particles.v[0].z == -1.0);
}

TEST_CASE("override errors name the file, the line and the path") {
  // A misspelt key is added to its table and refused by the loader, at the table's line, with the --set.
  SceneDoc misspelt = SceneDoc::parse(kScene, "s.toml");
  misspelt.apply("material.rock.youngs_modulu=1e9");
  CHECK_THROWS_WITH_AS(misspelt.load(),
                       doctest::Contains("s.toml:10: key 'youngs_modulu' (--set material.rock.youngs_modulu=1e9): "
                                         "unknown key (did you mean 'youngs_modulus'?)"),
                       InputError);
  // A table or array element the scene lacks is an error of the override itself.
  const InputError unknown = error_of("material.granite.density=1");
  CHECK(unknown.file() == "s.toml");
  CHECK(unknown.field() == "material.granite.density");
  CHECK(std::string(unknown.what()).find("unknown key path") != std::string::npos);
  CHECK(error_of("particle.3.radius=1").field() == "particle.3.radius");
  CHECK(std::string(error_of("domain.size=[1, 2, banana]").what()).find("is not a TOML value") != std::string::npos);
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

namespace {

// Runs `pastemix run` on kScene with extra arguments in a fresh folder; returns the result.
test::CommandResult run_scene_with(const std::string& scene_text, const std::string& args,
                                   const std::string& overrides_text = "") {
  // One folder per process: ctest runs the test cases as parallel processes, and two of them call this.
  const auto dir = std::filesystem::temp_directory_path() / ("pastemix_scene_doc_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "s.toml") << scene_text;
  if (!overrides_text.empty()) std::ofstream(dir / "o.toml") << overrides_text;
  std::string a = args;  // "{dir}" stands for the folder
  for (auto at = a.find("{dir}"); at != std::string::npos; at = a.find("{dir}")) a.replace(at, 5, dir.string());
  const auto r = test::run_pastemix("run '" + (dir / "s.toml").string() + "' --quiet --out '" + dir.string() + "' " + a);
  std::filesystem::remove_all(dir);
  return r;
}

std::string with_line(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

}  // namespace

TEST_CASE("a scene error under --set names the line the user wrote, not a re-serialised copy") {
  // restitution (line 17) is wrong in the file; --set edits another key. The loader reads the document as
  // parsed, so the error keeps line 17 (the toml++ re-serialisation sorts keys: another line there).
  const std::string bad = with_line(kScene, "restitution = 0.79", "restitution = 1.5");
  SceneDoc d = SceneDoc::parse(bad, "s.toml");
  d.apply("time_step=2e-6");
  try {
    (void)d.load();
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(e.file() == "s.toml");
    CHECK(e.line() == 17);
    CHECK(e.field() == "key 'restitution'");
  }
  // The same through the command, and a value --set wrote: the key's line, the --set named after the key.
  const auto cli = run_scene_with(bad, "--set time_step=2e-6");
  CHECK(cli.exit_code == 2);
  CHECK(cli.output.find("s.toml:17: key 'restitution': expected a value in (0, 1]") != std::string::npos);
  const auto set = run_scene_with(kScene, "--set material.rock.density=-5");
  CHECK(set.exit_code == 2);
  CHECK(set.output.find("s.toml:12: key 'density' (--set material.rock.density=-5): expected a positive number") !=
        std::string::npos);
}

TEST_CASE("a scene error under --overrides names the scene's line, or the overrides file's line for its values") {
  // An error in the scene file (line 17) while an overrides file edits another key.
  const std::string bad = with_line(kScene, "restitution = 0.79", "restitution = 1.5");
  const auto scene_err = run_scene_with(bad, "--overrides {dir}/o.toml", "time_step = 2e-6\n");
  CHECK(scene_err.exit_code == 2);
  CHECK(scene_err.output.find("s.toml:17: key 'restitution'") != std::string::npos);
  // An error inside the overrides file: a value the loader refuses names the overrides file and its line.
  const std::string ov = "# chosen by a study\ntime_step = 2e-6\nmaterial.rock.poisson_ratio = 0.7\n";
  const auto dir = std::filesystem::temp_directory_path() / ("pastemix_scene_doc_ov_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "o.toml") << ov;
  SceneDoc d = SceneDoc::parse(kScene, "s.toml");
  d.apply_file(dir / "o.toml");
  try {
    (void)d.load();
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(e.file() == (dir / "o.toml").string());
    CHECK(e.line() == 3);
    CHECK(e.field() == "key 'poisson_ratio'");
  }
  // A path the scene does not have, and a wrong type, at their overrides-file lines.
  std::ofstream(dir / "o.toml") << "time_step = 2e-6\n\nphysics.gravity = [0, 0, 0]\n";
  SceneDoc u = SceneDoc::parse(kScene, "s.toml");
  try {
    u.apply_file(dir / "o.toml");
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(e.file() == (dir / "o.toml").string());
    CHECK(e.line() == 3);
    CHECK(std::string(e.what()).find("unknown key path") != std::string::npos);
    CHECK(std::string(e.what()).find("in the scene s.toml") != std::string::npos);
  }
  std::ofstream(dir / "o.toml") << "end_time = true\n";
  SceneDoc t = SceneDoc::parse(kScene, "s.toml");
  CHECK_THROWS_WITH_AS(t.apply_file(dir / "o.toml"), doctest::Contains("o.toml:1: end_time: expects a float"),
                       InputError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a copy of an edited document edits on its own and keeps the user's lines") {
  SceneDoc base = SceneDoc::parse(kScene, "s.toml");
  base.apply("time_step=2e-6");
  SceneDoc copy = base;
  copy.set("interaction.rock/rock.restitution", "1.5");  // the copy rebuilds its tree from the text
  CHECK(base.number("interaction.rock/rock.restitution") == 0.79);
  CHECK(copy.number("time_step") == 2e-6);
  try {
    (void)copy.load();
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(e.line() == 17);  // the key's line in s.toml, where the set value sits
  }
  CHECK(base.load().config.dt == 2e-6);
}

TEST_CASE("text(): the file as read when unedited, the toml++ serialisation once edited") {
  SceneDoc d = SceneDoc::parse(kScene, "s.toml");
  CHECK(d.text() == kScene);
  CHECK(d.load().text == kScene);
  d.set_number("material.rock.density", 2700.5);
  d.erase("interaction.0.friction");
  d.add_number("interaction.0", "friction", 0.25);
  const Scene s = d.load();
  CHECK(s.text == d.text());
  CHECK(s.text.find("density = 2700.5") != std::string::npos);
  CHECK(s.materials[0].density == 2700.5);
  CHECK(s.pairs[0].friction == 0.25);
  CHECK_THROWS_AS(d.add_number("interaction.0", "friction", 0.3), InputError);  // exists
  CHECK_THROWS_AS(d.erase("material.granite"), InputError);
  CHECK(d.size("material") == 1);
  CHECK(d.size("nothing") == 0);
  CHECK(d.string("contact.law") == "hertz_mindlin");
  CHECK(d.line_of("contact.law") == 8);
}
