// SPDX-License-Identifier: MIT
// Contact history survives neighbour-list rebuilds (it is keyed by the particle-id pair).
#include "model/contacts.h"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "model/world.h"
#include "tests/model/scene_text.h"

using namespace pastemix;
using namespace pastemix::model;

TEST_CASE("contacts: the tangential spring survives neighbour rebuilds (rebuild every step = never)") {
  // An oblique impact: the tangential spring carries the whole contact. With a 1 nm skin the pair list is
  // rebuilt at nearly every step; with 1 mm, never during the contact. Same bits if the history is carried.
  auto run = [](double skin, long* rebuilds) {
    const std::string text = fmt::format(
        "time_step = 1e-7\nend_time = 1\n[domain]\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\n[physics]\ngravity = [0, 0, 0]\n"
        "[contact]\nlaw = \"hertz_mindlin\"\n[neighbor]\nskin = {}\n{}{}"
        "[[particle]]\nmaterial = \"m\"\nradius = 0.01\nposition = [-0.01, 0, 0]\nvelocity = [1, 0.3, 0]\n"
        "[[particle]]\nmaterial = \"m\"\nradius = 0.01\nposition = [0.01, 0, 0]\nvelocity = [-1, -0.3, 0]\n",
        skin, model::test::material("m", 2800, 4.8e10, 0.2), model::test::interaction("m/m", 0.8, 0.5));
    World w = make_world(model::test::scene_from(text));
    for (int k = 0; k < 2000; ++k) w.step();
    *rebuilds = w.profile().rebuilds;
    return std::pair{w.particles().v[0], w.particles().omega[0]};
  };
  long many = 0, few = 0;
  const auto [v_many, w_many] = run(1e-9, &many);
  const auto [v_few, w_few] = run(1e-3, &few);
  MESSAGE("rebuilds: " << many << " (1 nm skin) vs " << few << " (1 mm skin); spin after impact " << w_few.z << " rad/s");
  CHECK(many > 1000);
  CHECK(few == 1);
  CHECK(std::abs(w_few.z) > 1.0);  // the tangential force did act
  CHECK(v_many.x == v_few.x);
  CHECK(v_many.y == v_few.y);
  CHECK(w_many.z == w_few.z);
}
