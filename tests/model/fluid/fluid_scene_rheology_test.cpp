// SPDX-License-Identifier: MIT
// [[fluid]] rheology_from (model/fluid/fluid_scene.h): a scene takes tau_y, eta_B and the density of its solids
// content from the lab parameter store, and every way of getting that wrong is an InputError naming it.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "model/fluid/fluid_scene.h"
#include "model/scene.h"
#include "tests/run_command.h"
#include "tests/input_error.h"

using namespace pastemix;
using namespace pastemix::model;
namespace fs = std::filesystem;

namespace {

// A store as `lab reduce` writes it, cut down to what the reader needs (the contract of the keys).
const char* kStore = R"STORE([paste_rheology.model.curve]
text = "published_4_19"
[paste_rheology.cw_72_5.solids_fraction]
value = 0.725
[paste_rheology.cw_72_5.yield_stress]
value = 45.99
method = "model exponential, shape parameter at its prior (prior)"
[paste_rheology.cw_72_5.plastic_viscosity]
value = 0.202
[paste_rheology.cw_72_5.density]
value = 1789.4
[paste_rheology.cw_72_5.minus_sd.yield_stress]
value = 57.0
[paste_rheology.cw_72_5.minus_sd.plastic_viscosity]
value = 0.26
[paste_rheology.cw_72_5.plus_sd.yield_stress]
value = 37.0
[paste_rheology.cw_72_5.plus_sd.plastic_viscosity]
value = 0.16
[paste_rheology.cw_70.solids_fraction]
value = 0.7
)STORE";

struct Dir {
  fs::path path = fs::temp_directory_path() / fmt::format("pastemix_rheofrom_{}", static_cast<long>(::getpid()));
  Dir() {
    fs::create_directories(path);
    std::ofstream(path / "parameters.toml") << kStore;
  }
  ~Dir() { fs::remove_all(path); }
};

std::string tiny_scene() {
  std::ifstream in(test::source_path("tests/app/study/data/rheology_tiny.toml"));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

Scene load_in(const Dir& d, const std::string& text) {
  std::ofstream(d.path / "scene.toml") << text;
  return load_scene(d.path / "scene.toml");
}

std::string error_of(const Dir& d, const std::string& text) {
  return pastemix::test::input_error_of([&] { load_in(d, text); });
}

const std::string kFrom = "rheology_from = \"../../../../out/lab/parameters.toml\"";

}  // namespace

TEST_CASE("fluid scene: rheology_from takes the store's values at the scene's solids content") {
  Dir d;
  const Scene s = load_in(d, with(tiny_scene(), kFrom, "rheology_from = \"parameters.toml\""));
  REQUIRE(s.fluid.size() == 1);
  CHECK(s.fluid[0].yield_stress() == 45.99);
  CHECK(std::get<BinghamDedegil::Params>(s.fluid[0].law).plastic_viscosity == 0.202);
  CHECK(s.fluid[0].density() == 1789.4);
  CHECK(s.fluid[0].solids_fraction == 0.725);
  // The band: the same paste with the shape parameter at +1 sd (tau_y and eta_B together), one key of the scene.
  const std::string at = with(tiny_scene(), kFrom, "rheology_from = \"parameters.toml\"\nrheology_at = \"plus_sd\"");
  const Scene plus = load_in(d, at);
  CHECK(plus.fluid[0].yield_stress() == 37.0);
  CHECK(std::get<BinghamDedegil::Params>(plus.fluid[0].law).plastic_viscosity == 0.16);
  CHECK(plus.fluid[0].density() == 1789.4);
  const auto r = fluid::read_store_rheology((d.path / "parameters.toml").string(), 0.725);
  CHECK(r.key == "paste_rheology.cw_72_5");
  CHECK(r.provenance.find("(prior)") != std::string::npos);
}

TEST_CASE("fluid scene: rheology_from errors name the scene, the key and what to do") {
  Dir d;
  const std::string base = with(tiny_scene(), kFrom, "rheology_from = \"parameters.toml\"");
  auto has = [](const std::string& e, const std::string& what) {
    CHECK_MESSAGE(e.find(what) != std::string::npos, e);
    CHECK_MESSAGE(e.find("scene.toml") != std::string::npos, e);
  };
  has(error_of(d, with(base, "\"parameters.toml\"", "\"missing.toml\"")), "no such parameter store");
  has(error_of(d, with(base, "\"parameters.toml\"", "\"missing.toml\"")), "pastemix lab reduce");
  has(error_of(d, with(base, "solids_fraction = 0.725", "solids_fraction = 0.74")), "no entry for solids content 0.74");
  has(error_of(d, with(base, "solids_fraction = 0.725", "")), "needs solids_fraction");
  has(error_of(d, with(base, "curve = \"published_4_19\"", "curve = \"stokes\"")), "belongs to drag curve published_4_19");
  has(error_of(d, with(base, "rheology = \"bingham\"", "rheology = \"bingham\"\nyield_stress = 69.0")),
      "give either rheology_from or yield_stress");
  has(error_of(d, with(base, "rheology = \"bingham\"", "rheology = \"newtonian\"")), "set rheology = \"bingham\"");
  has(error_of(d, with(base, "solids_fraction = 0.725", "solids_fraction = 0.725\nrheology_at = \"high\"")),
      "rheology_at");
  has(error_of(d, with(tiny_scene(), kFrom, "density = 1789.4\nyield_stress = 46.0\nplastic_viscosity = 0.2\n"
                                            "rheology_at = \"plus_sd\"")),
      "needs rheology_from");
  std::ofstream(d.path / "parameters.toml") << "[paste.yield_stress]\nvalue = 138.0\n";
  const std::string old = error_of(d, base);  // names the store (the file that lacks the model)
  CHECK(old.find("parameters.toml") != std::string::npos);
  CHECK(old.find("no paste-rheology model") != std::string::npos);
}
