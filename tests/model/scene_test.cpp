// SPDX-License-Identifier: MIT
// Scene parsing: the Plan follows the physics named, and bad scenes fail with file:line.
#include "model/scene.h"

#include <doctest/doctest.h>

#include <fstream>

#include "base/error.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

using model::test::error_of;
using model::test::kBase;

}  // namespace

TEST_CASE("scene: the Plan allocates only what the physics needs") {
  const std::string sphere = "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0, 0, 0]\n";
  const Scene with_friction = model::test::scene_from(kBase + sphere);
  CHECK(with_friction.plan.rotation);
  CHECK(with_friction.plan.history_width == 3);
  CHECK(with_friction.particles.omega.size() == 1);
  CHECK_FALSE(with_friction.plan.fluid);

  std::string frictionless = kBase;
  frictionless.replace(frictionless.find("friction = 0.466"), 16, "friction = 0.0");
  const Scene s = model::test::scene_from(frictionless + sphere);
  CHECK_FALSE(s.plan.rotation);
  CHECK(s.plan.history_width == 0);
  CHECK(s.particles.omega.empty());
  CHECK(s.particles.torque.empty());

  std::string epsd = kBase;
  epsd.replace(epsd.find("law = \"hertz_mindlin\""), 21, "law = \"hertz_mindlin\"\nrolling = \"elastic_plastic\"");
  CHECK(model::test::scene_from(epsd + sphere).plan.history_width == 6);
}

TEST_CASE("scene: bad scenes fail with file:line and the field") {
  const std::string sphere = "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0, 0, 0]\n";
  // Unknown key (typo) on line 17.
  CHECK(error_of(kBase + "rolling_frction = 0.1\n" + sphere).find("bad.toml:17: key 'rolling_frction': unknown key") !=
        std::string::npos);
  // Negative radius on line 19.
  CHECK(error_of(kBase + "[[particle]]\nmaterial = \"rock\"\nradius = -0.01\nposition = [0, 0, 0]\n")
            .find("bad.toml:19: key 'radius'") != std::string::npos);
  // Missing material on line 18.
  const std::string missing = error_of(kBase + "[[particle]]\nmaterial = \"steel\"\nradius = 0.01\nposition = [0, 0, 0]\n");
  CHECK(missing.find("bad.toml:18: key 'material': material 'steel' is not defined") != std::string::npos);
  // A wall material without an interaction with the rock.
  const std::string no_pair = error_of(
      kBase + "[[material]]\nname = \"steel\"\ndensity = 7800\nyoungs_modulus = 2e11\npoisson_ratio = 0.3\n" +
      "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"steel\"\npoint = [0, 0, -0.5]\nnormal = [0, 0, 1]\n" + sphere);
  CHECK(no_pair.find("no [[interaction]] for materials 'rock/steel'") != std::string::npos);
  // A particle overlapping a wall (line 24 is its position).
  const std::string floor =
      "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";
  CHECK(error_of(kBase + floor + "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0, 0, 0.005]\n")
            .find("bad.toml:26: key 'position': the particle overlaps wall 'floor'") != std::string::npos);
  // Two overlapping spheres: reported at the second one's position (line 24).
  CHECK(error_of(kBase + sphere + "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0.015, 0, 0]\n")
            .find("bad.toml:24: key 'position': the particle overlaps particle 0") != std::string::npos);
  // A plate across a factory's fill region.
  const std::string plate =
      "[[wall]]\nname = \"plate\"\ntype = \"disk\"\nmaterial = \"rock\"\ncenter = [0, 0, 0.05]\nradius = 0.2\n";
  const std::string factory =
      "[[factory]]\nmaterial = \"rock\"\nmass = 0.01\nshape = \"box\"\nmin = [-0.1, -0.1, 0.0]\nmax = [0.1, 0.1, 0.1]\n"
      "[[factory.psd]]\nd_min = 2e-3\nd_max = 3e-3\nfraction = 1.0\n";
  CHECK(error_of(kBase + plate + factory).find("wall 'plate' passes through the factory region") != std::string::npos);
  // Restitution outside (0, 1].
  std::string e2 = kBase;
  e2.replace(e2.find("restitution = 0.79"), 18, "restitution = 1.5");
  CHECK(error_of(e2 + sphere).find("bad.toml:15: key 'restitution'") != std::string::npos);
  // Rolling friction without a rolling law.
  CHECK(error_of(kBase + "rolling_friction = 0.1\n" + sphere).find("no rolling law is named") != std::string::npos);
}

TEST_CASE("scene: `pastemix run` exits 2 with file:line on a bad scene and writes nothing") {
  const std::string dir = "model_scene_test_out";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir + "/bad.toml");
    f << kBase << "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0, 0, 0]\nvelocty = [1, 0, 0]\n";
  }
  const auto r = pastemix::test::run_pastemix("run " + dir + "/bad.toml --out " + dir + " --quiet");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("bad.toml:21: key 'velocty': unknown key") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir + "/bad.h5"));
}

TEST_CASE("scene: [domain] on_exit = stop by default, remove with max_escaped_fraction, bad values name file:line") {
  const std::string sphere = "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0, 0, 0]\n";
  // Extra [domain] keys go on lines 6, 7, ... (after max on line 5).
  auto with_domain = [&](const std::string& extra) {
    std::string t = kBase;
    t.insert(t.find("[contact]"), extra);
    return t + sphere;
  };
  const Scene plain = model::test::scene_from(kBase + sphere);
  CHECK(plain.config.on_exit == ExitRule::stop);
  const Scene removing = model::test::scene_from(with_domain("on_exit = \"remove\"\n"));
  CHECK(removing.config.on_exit == ExitRule::remove);
  CHECK(removing.config.max_escaped_fraction == 0.05);
  CHECK(model::test::scene_from(with_domain("on_exit = \"remove\"\nmax_escaped_fraction = 0.2\n"))
            .config.max_escaped_fraction == 0.2);
  CHECK(model::test::scene_from(with_domain("on_exit = \"stop\"\n")).config.on_exit == ExitRule::stop);
  const std::string bad = error_of(with_domain("on_exit = \"sideways\"\n"));
  MESSAGE("bad on_exit: " << bad);
  CHECK(bad.find("bad.toml:6: key 'on_exit'") != std::string::npos);
  CHECK(bad.find("remove") != std::string::npos);  // the error lists the choices
  CHECK(error_of(with_domain("on_exit = 1\n")).find("bad.toml:6: key 'on_exit'") != std::string::npos);
  CHECK(error_of(with_domain("on_exit = \"remove\"\nmax_escaped_fraction = 1.5\n"))
            .find("bad.toml:7: key 'max_escaped_fraction'") != std::string::npos);
  // Without "remove" the limit means nothing: an error, not a silently ignored key.
  CHECK(error_of(with_domain("max_escaped_fraction = 0.1\n")).find("bad.toml:6: key 'max_escaped_fraction'") !=
        std::string::npos);
  CHECK(error_of(with_domain("on_exit = \"remove\"\nmax_escape = 0.1\n")).find("bad.toml:7: key 'max_escape': unknown key") !=
        std::string::npos);
}
