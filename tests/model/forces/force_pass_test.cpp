// SPDX-License-Identifier: MIT
// The force passes (model/forces/): what the registered list declares, gravity's bits through the list, and
// each pass timed on its own profile line in a run with walls and a fluid region.
#include "model/forces/registry.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "model/world.h"
#include "tests/model/scene_text.h"

using namespace pastemix;
using namespace pastemix::model;

TEST_CASE("force passes: the registered list, in the order of the step, with their profile lines") {
  CHECK(std::tuple_size_v<ForcePasses> == 4);
  CHECK(std::string(std::tuple_element_t<0, ForcePasses>::info.name) == "gravity");
  CHECK(std::string(std::tuple_element_t<1, ForcePasses>::info.name) == "walls");
  CHECK(std::string(std::tuple_element_t<2, ForcePasses>::info.name) == "fluid");
  CHECK(std::string(std::tuple_element_t<3, ForcePasses>::info.name) == "flow");
  // A pass with a line of its own is named as its line; gravity is a term of the kick (no line of its own).
  CHECK(std::string(Profile::names[WallForces::info.stage]) == WallForces::info.name);
  CHECK(std::string(Profile::names[FluidForces::info.stage]) == FluidForces::info.name);
  CHECK(Gravity::info.stage == Profile::kick);
  // The moving paste's pass (dynamics = "flow") is timed on the fluid line: a scene has one or the other.
  CHECK(FlowForces::info.stage == Profile::fluid);
  CHECK(!FlowForces::info.needs_pairs);
  CHECK((FlowForces::info.adds & adds::kick) != 0);
  // What each declares: only the fluid pass reads the pair list (its collective rule) and owns a kick.
  CHECK(!Gravity::info.needs_pairs);
  CHECK(!WallForces::info.needs_pairs);
  CHECK(FluidForces::info.needs_pairs);
  CHECK((Gravity::info.adds & adds::acceleration) != 0);
  CHECK((WallForces::info.adds & adds::force) != 0);
  CHECK((WallForces::info.adds & adds::kick) == 0);
  CHECK((FluidForces::info.adds & adds::kick) != 0);
  CHECK((FluidForces::info.reads & reads::force) != 0);
}

TEST_CASE("force passes: the body acceleration is gravity's own bits (a -0 component stays -0)") {
  ForcePasses passes;
  std::get<Gravity>(passes).g = Vec3{-0.0, 0.0, -9.81};
  const Vec3 a = body_acceleration(passes);
  CHECK(std::signbit(a.x));
  CHECK(!std::signbit(a.y));
  CHECK(a.z == -9.81);
  // No fluid field: the fluid pass is inactive and claims no particle's kick.
  CHECK(!std::get<FluidForces>(passes).active());
  CHECK(!with_kick_pass(passes, 0, [](const auto&) {}));
}

TEST_CASE("force passes: walls and fluid are timed on their own lines") {
  // Twelve spheres dropped onto a floor into a pool of paste: the wall pass and the fluid pass both work.
  std::string text =
      "seed = 1\ntime_step = 2e-5\nend_time = 1.0\n[domain]\nmin = [-0.05, -0.05, -0.01]\nmax = [0.05, 0.05, 0.2]\n"
      "[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"constant_torque\"\n[neighbor]\nskin = 1e-3\n" +
      model::test::material("rock", 2760, 4.68e7, 0.19) + model::test::interaction("rock/rock", 0.79, 0.466, 0.15) +
      "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
      "[[factory]]\nmaterial = \"rock\"\nmass = 0.004\nshape = \"box\"\nmin = [-0.02, -0.02, 0.004]\n"
      "max = [0.02, 0.02, 0.03]\nvelocity = [0, 0, -0.5]\n[[factory.psd]]\nd_min = 5e-3\nd_max = 6e-3\nfraction = 1.0\n"
      "[[fluid]]\nname = \"paste\"\nx = [-0.04, 0.04]\ny = [-0.04, 0.04]\nbottom = 0.0\nsurface = 0.02\n"
      "density = 1843\nrheology = \"bingham\"\nyield_stress = 0.2\nplastic_viscosity = 0.05\n"
      "curve = \"published_4_19\"\nsolids_fraction = 0.75\n";
  World w = make_world(model::test::scene_from(text));
  REQUIRE(w.fluid() != nullptr);
  w.advance(6000);  // 0.12 s: the spheres reach the floor through the paste
  const Profile& p = w.profile();
  double z_min = 1.0;
  for (const Vec3& x : w.particles().x) z_min = std::min(z_min, x.z);
  MESSAGE(w.particles().size() << " spheres, lowest centre at z = " << z_min << " m");
  // On the floor (radii 2.5-3 mm): the wall pass held them (without it they leave the domain, exit 3).
  CHECK(z_min > 0.0025 * 0.99);
  CHECK(z_min < 0.003);
  CHECK(!w.fluid()->members().empty());
  CHECK(p.seconds[Profile::contact_forces] > 0.0);
  CHECK(p.seconds[Profile::walls] > 0.0);
  CHECK(p.seconds[Profile::kick] > 0.0);
  CHECK(p.seconds[Profile::fluid] > 0.0);
}
