// SPDX-License-Identifier: MIT
// Scene mistakes that used to pass silently or come back as exit 3 at t = 0 without a line (issue 20, item 6):
// factory and fluid regions outside the domain, [initial_state] spheres cut by walls, end_time < dt, a time
// step near the Rayleigh time, --threads 0 or negative.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "model/scene.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"
#include "base/units.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

using model::test::error_of;
using model::test::kBase;
using model::test::kSphere;

std::string factory(const std::string& shape_lines) {
  return "[[factory]]\nmaterial = \"rock\"\nmass = 0.001\n" + shape_lines +
         "[[factory.psd]]\nd_min = 2e-3\nd_max = 3e-3\nfraction = 1.0\n";
}

}  // namespace

TEST_CASE("scene checks: a factory region reaching outside the domain is an input error at its table") {
  // Lines 17-21: [[factory]], material, mass, shape, min; max on line 22.
  const std::string e = error_of(kBase + factory("shape = \"box\"\nmin = [-0.1, -0.1, 0.9]\nmax = [0.1, 0.1, 1.2]\n"));
  CHECK(e.find("bad.toml:22: key 'max': the box region (-0.1, -0.1, 0.9) to (0.1, 0.1, 1.2) m reaches outside the "
               "[domain] box") == 0);
  const std::string c =
      error_of(kBase + factory("shape = \"cylinder\"\ncenter = [0.95, 0]\nradius = 0.1\nz_min = 0\nz_max = 0.2\n"));
  CHECK(c.find("bad.toml:22: key 'radius': the cylinder region") == 0);
  CHECK(error_of(kBase + factory("shape = \"box\"\nmin = [-0.1, -0.1, 0.1]\nmax = [0.1, 0.1, 0.3]\n")).empty());
}

TEST_CASE("scene checks: a fluid region outside or partly outside the domain is an input error") {
  const std::string fluid = "[[fluid]]\nx = [-0.5, 1.5]\ny = [-0.5, 0.5]\nbottom = -0.5\nsurface = 0.5\n"
                            "density = 1000\nrheology = \"newtonian\"\nviscosity = 1e-3\n";
  const std::string e = error_of(kBase + fluid + kSphere);
  CHECK(e.find("bad.toml:18: key 'x': x = [-0.5, 1.5] m reaches outside the [domain] box (x from -1 to 1 m)") == 0);
  std::string below = fluid;
  below.replace(below.find("x = [-0.5, 1.5]"), 15, "x = [-0.5, 0.5]");
  below.replace(below.find("bottom = -0.5"), 13, "bottom = -3");
  CHECK(error_of(kBase + below + kSphere).find("bad.toml:20: key 'bottom'") == 0);
  std::string above = fluid;
  above.replace(above.find("x = [-0.5, 1.5]"), 15, "x = [-0.5, 0.5]");
  above.replace(above.find("surface = 0.5"), 13, "surface = 2");
  CHECK(error_of(kBase + above + kSphere).find("bad.toml:21: key 'surface'") == 0);
  std::string inside = fluid;
  inside.replace(inside.find("x = [-0.5, 1.5]"), 15, "x = [-0.5, 0.5]");
  CHECK(error_of(kBase + inside + kSphere).empty());
}

TEST_CASE("scene checks: [initial_state] spheres cut by a wall of the scene, or outside the domain, are refused") {
  const std::string dir = fmt::format("model_scene_checks_{}", ::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  auto snapshot = [&](const std::string& name, std::vector<double> pos) {
    H5Writer h5(dir + "/" + name);
    h5.write_strings("/materials", {"rock"});
    const std::uint64_t n = pos.size() / 3;
    h5.write("/snapshots/time", std::vector<double>{0.0});
    h5.write("/snapshots/000000/position", pos, {n, 3});
    h5.write("/snapshots/000000/velocity", std::vector<double>(pos.size(), 0.0), {n, 3});
    h5.write("/snapshots/000000/radius", std::vector<double>(n, 0.01));
    h5.write("/snapshots/000000/material", std::vector<std::int64_t>(n, 0));
    h5.close();
  };
  snapshot("cut.h5", {0, 0, 0.5, 0.3, 0, 0.005});  // sphere 1 is 5 mm into the floor at z = 0
  snapshot("out.h5", {0, 0, 0.5, 0, 0, 1.5});      // sphere 1 above the domain
  snapshot("ok.h5", {0, 0, 0.5, 0.3, 0, 0.0099});  // sphere 1 resting on the floor (a contact overlap)
  const std::string floor =
      "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";
  auto with = [&](const std::string& file) {
    return error_of(kBase + floor + "[initial_state]\nfile = \"" + file + "\"\n", dir + "/s.toml");
  };
  CHECK(with("cut.h5").find(":24: key 'file': sphere 1 of the snapshot (radius 0.01 m) is cut by wall 'floor' "
                            "(0.005 m deep) at t = 0") != std::string::npos);
  CHECK(with("out.h5").find(":24: key 'file': sphere 1 of the snapshot at (0, 0, 1.5) m is outside the [domain] box") !=
        std::string::npos);
  CHECK(with("ok.h5").empty());
  std::filesystem::remove_all(dir);
}

TEST_CASE("scene checks: end_time shorter than one step is an input error") {
  std::string s = kBase;
  s.replace(s.find("end_time = 0.01"), 15, "end_time = 5e-7");
  CHECK(error_of(s + kSphere).find("bad.toml:2: key 'end_time': end_time 5e-07 s is shorter than one time step") == 0);
}

TEST_CASE("scene checks: a time step at 97.5 % of the Rayleigh time warns, 1e-6 s does not") {
  // T_R = pi r sqrt(rho/G) / (0.8766 + 0.163 nu), r = 0.01 m, rho = 2760, G = 4.68e7 / 2.38, nu = 0.19:
  // 4.1015e-4 s.
  const double t_r = pastemix::units::pi * 0.01 * std::sqrt(2760.0 / (4.68e7 / 2.38)) / (0.8766 + 0.163 * 0.19);
  std::string s = kBase;
  s.replace(s.find("time_step = 1e-6"), 16, fmt::format("time_step = {:.17g}", 0.975 * t_r));
  const Scene fast = parse_scene(s + kSphere, "fast.toml");
  REQUIRE(fast.warnings.size() == 1);
  CHECK(fast.warnings[0].find("fast.toml: time_step") == 0);
  CHECK(fast.warnings[0].find("is 98 % of the Rayleigh time of the smallest sphere (0.00041 s") != std::string::npos);
  CHECK(parse_scene(kBase + kSphere, "slow.toml").warnings.empty());
}

TEST_CASE("scene checks: `pastemix run --threads 0` or a negative count is an input error") {
  const std::string dir = fmt::format("model_threads_{}", ::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/ok.toml") << kBase << kSphere;
  for (const char* n : {"0", "-3"}) {
    const auto r = pastemix::test::run_pastemix(fmt::format("run {}/ok.toml --out {} --quiet --threads {}", dir, dir, n));
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(fmt::format("--threads: expected a thread count >= 1, got {}", n)) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir + "/ok.h5"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("scene checks: a factory mass below one sphere of its PSD is an input error, not a crash (fuzz find)") {
  // fuzz/corpus/scene regression (scene-crash-60ac6f66): d_max = 3.0e43 m drew no sphere at all, and the
  // smallest radius was then read from an empty list (undefined behaviour under UBSan).
  const std::string text = kBase + "[[factory]]\nmaterial = \"rock\"\nmass = 0.002\nshape = \"box\"\n"
                                   "min = [-0.1, -0.1, 0.1]\nmax = [0.1, 0.1, 0.3]\n"
                                   "[[factory.psd]]\nd_min = 2.5e-3\nd_max = 3.0e43\nfraction = 1.0\n";
  const std::string e = error_of(text);
  INFO(e);
  CHECK(e.find("bad.toml:19: key 'mass': 0.002 kg makes not one sphere of this PSD") == 0);
  // A mass too small for one sphere of an ordinary PSD: the same error.
  const std::string small = error_of(kBase + "[[factory]]\nmaterial = \"rock\"\nmass = 1e-9\nshape = \"box\"\n"
                                             "min = [-0.1, -0.1, 0.1]\nmax = [0.1, 0.1, 0.3]\n"
                                             "[[factory.psd]]\nd_min = 2e-3\nd_max = 3e-3\nfraction = 1.0\n");
  CHECK(small.find("key 'mass': 1e-09 kg makes not one sphere") != std::string::npos);
}
