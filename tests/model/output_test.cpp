// SPDX-License-Identifier: MIT
// `pastemix run` end to end: the HDF5 holds what the schema says, and every dataset the XDMF file
// references exists in the HDF5 with the declared dimensions.
#include "model/output.h"

#include <doctest/doctest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "base/h5.h"
#include "model/scene.h"
#include "tests/fresh_dir.h"
#include "tests/run_command.h"

using namespace pastemix;

TEST_CASE("output: pastemix run writes HDF5 + XDMF that agree, with scene, seed and profile") {
  const std::string dir = pastemix::test::fresh_dir("model_output_test_out").string();
  // The demo pour, shortened: 0.02 s, snapshots every 0.01 s.
  std::ifstream in(pastemix::test::source_path("datasets/scenes/pour_box.toml"));
  std::stringstream buf;
  buf << in.rdbuf();
  std::string text = buf.str();
  text = std::regex_replace(text, std::regex("end_time = [0-9.e-]+"), "end_time = 0.02");
  text = std::regex_replace(text, std::regex("\ninterval = [0-9.e-]+"), "\ninterval = 0.01");
  text = std::regex_replace(text, std::regex("mass = [0-9.e-]+ "), "mass = 0.01 ");
  {
    std::ofstream f(dir + "/pour.toml");
    f << text;
  }
  const auto r = pastemix::test::run_pastemix("run " + dir + "/pour.toml --out " + dir + " --quiet --threads 2");
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("stage profile") != std::string::npos);
  CHECK(r.output.find("contact_forces") != std::string::npos);

  H5Reader h5(dir + "/pour.h5");
  CHECK(h5.attribute_string("/", "scene_text") == text);
  CHECK(h5.attribute_int("/", "seed") == 1);
  CHECK(h5.attribute_string("/", "scene_hash") == model::scene_hash(text));
  CHECK(h5.read_doubles("/snapshots/time").size() == 3);
  CHECK(h5.read_strings("/profile/stage").size() == model::Profile::count);
  CHECK(h5.attribute_int("/profile", "steps") == 4000);
  const auto ke = h5.read_doubles("/timeseries/kinetic");
  CHECK(ke.size() == h5.read_doubles("/timeseries/time").size());
  CHECK(ke.back() > 0.0);

  std::ifstream xf(dir + "/pour.xmf");
  std::stringstream xs;
  xs << xf.rdbuf();
  const std::string xmf = xs.str();
  CHECK(xmf.find("TopologyType=\"Polyvertex\"") != std::string::npos);
  CHECK(xmf.find("CollectionType=\"Temporal\"") != std::string::npos);
  // Every HDF DataItem: Dimensions="..." ... >file.h5:/path</DataItem>
  const std::regex item("<DataItem Dimensions=\"([0-9 ]+)\"[^>]*Format=\"HDF\">([^<:]+):([^<]+)</DataItem>");
  int checked = 0;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item); it != std::sregex_iterator(); ++it) {
    const std::string dims = (*it)[1], file = (*it)[2], path = (*it)[3];
    CAPTURE(path);
    CHECK(file == "pour.h5");
    REQUIRE(h5.exists(path));
    std::string actual;
    for (auto d : h5.dims(path)) {
      if (!actual.empty()) actual.push_back(' ');
      actual.append(std::to_string(d));
    }
    CHECK(actual == dims);
    ++checked;
  }
  CHECK(checked == 3 * 5);  // 3 snapshots x (position, radius, id, velocity, angular_velocity)

  // [initial_state]: a scene starting from the last snapshot (how a settled bed is reused) gets exactly
  // those spheres.
  std::string again = text.substr(0, text.find("\n[[factory]]") + 1);
  again += "[initial_state]\nfile = \"pour.h5\"\n";
  const model::Scene s = model::parse_scene(again, dir + "/again.toml");
  const auto x = h5.read_doubles("/snapshots/000002/position");
  REQUIRE(s.particles.size() * 3 == x.size());
  CHECK(s.particles.x.back().z == x.back());
  CHECK(s.particles.v.size() == s.particles.size());
}

TEST_CASE("output: a run that fails (particle leaves the domain) exits 3 naming the particle, and writes nothing") {
  const std::string dir = pastemix::test::fresh_dir("model_output_fail_out").string();
  {
    std::ofstream f(dir + "/fall.toml");
    f << "time_step = 1e-4\nend_time = 1.0\n[domain]\nmin = [-1, -1, -0.1]\nmax = [1, 1, 1]\n"
         "[contact]\nlaw = \"hertz_mindlin\"\n"
         "[[material]]\nname = \"rock\"\ndensity = 2760\nyoungs_modulus = 4.68e7\npoisson_ratio = 0.19\n"
         "[[interaction]]\nmaterials = \"rock/rock\"\nrestitution = 0.5\n"
         "[[particle]]\nmaterial = \"rock\"\nradius = 0.005\nposition = [0, 0, 0]\n";
  }
  const auto r = pastemix::test::run_pastemix("run " + dir + "/fall.toml --out " + dir + " --quiet");
  CHECK(r.exit_code == 3);
  CHECK(r.output.find("particle id 0 at t = ") != std::string::npos);
  CHECK(r.output.find("left the domain") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir + "/fall.h5"));
  CHECK_FALSE(std::filesystem::exists(dir + "/fall.xmf"));
}
