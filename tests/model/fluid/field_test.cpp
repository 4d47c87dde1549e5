// SPDX-License-Identifier: MIT
// FluidField's threads' lanes (model/fluid/field.*): begin_batch / update_part / end_batch, run here on one
// thread lane after lane, against update() on the same particles. The World's slabs are contiguous index
// ranges after its spatial sort; here each lane owns every third particle, the case where the surface sums
// must really merge the lanes' lists into ascending order.
#include "model/fluid/field.h"

#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <vector>

using namespace pastemix::model;
using namespace pastemix::model::fluid;

namespace {

// 600 spheres of 2-4 mm over a 10 x 10 cm paste box (surface 5 cm), from below the bottom to 10 cm up.
Particles falling_rock() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Particles p;
  for (int k = 0; k < 600; ++k)
    p.add(0, 0.002 + 0.002 * u(rng), 2700, {0.11 * u(rng) - 0.005, 0.11 * u(rng) - 0.005, 0.11 * u(rng) - 0.01}, {},
          {});
  return p;
}

FluidRegion paste() {
  FluidRegion reg;
  reg.x_min = reg.y_min = 0, reg.x_max = reg.y_max = 0.1, reg.z_bottom = 0, reg.z_surface0 = 0.05;
  reg.law = BinghamDedegil::Params{1843, 20, 0.7};
  reg.curve = {pastemix::drag::CurveId::published_4_19, {}};
  return reg;
}

// Bitwise: every flag, volume and the kick of every particle under one force.
void check_same(const FluidField& one, const FluidField& lanes, const Particles& p, double dt) {
  CHECK(one.surface_z(0) == lanes.surface_z(0));
  CHECK(one.members() == lanes.members());
  const Vec3 g{0, 0, -9.81}, v{0.01, -0.02, -0.3}, f{0, 0, -1e-3};
  int differ = 0;
  for (std::size_t a = 0; a < p.size(); ++a) {
    const long i = static_cast<long>(a);
    differ += one.region_of(i) != lanes.region_of(i) || one.submerged_volume(i) != lanes.submerged_volume(i);
    if (!one.inside(i)) continue;
    const Vec3 k1 = one.kick(i, v, f, p.mass[a], p.radius[a], 0.5 * dt, g);
    const Vec3 k2 = lanes.kick(i, v, f, p.mass[a], p.radius[a], 0.5 * dt, g);
    differ += k1.x != k2.x || k1.y != k2.y || k1.z != k2.z;
  }
  CHECK(differ == 0);
}

}  // namespace

namespace {

// 40 batches of 25 steps, the rock sinking, on 3 lanes whose particles are every third one (interleaved: the
// lanes' member lists must be merged) or three index ranges (contiguous: the World's slabs after its sort,
// where the surface's sum continues lane 0's own), against update() on one lane.
void lanes_against_one(bool contiguous) {
  Particles p = falling_rock();
  const double dt = 2e-5;
  FluidField one({paste()}), lanes({paste()});
  for (FluidField* f : {&one, &lanes}) f->set_candidate_margin(1.25e-3), f->set_step(dt, {0, 0, -9.81});
  std::vector<std::vector<std::uint32_t>> own(3);
  long stamp = 0;
  for (int batch = 0; batch < 40; ++batch) {
    // A new partition every fourth batch (the lanes are made anew, the last members cleared by begin_batch).
    if (batch % 4 == 0) {
      ++stamp;
      for (auto& list : own) list.clear();
      for (std::uint32_t a = 0; a < p.size(); ++a) {
        const std::uint32_t third = static_cast<std::uint32_t>(p.size() + 2) / 3;
        own[contiguous ? (a + static_cast<std::uint32_t>(batch)) % p.size() / third % 3 : (a + batch) % 3].push_back(a);
      }
    }
    lanes.begin_batch(p, 3, stamp);
    for (int s = 0; s < 25; ++s) {
      for (std::size_t a = 0; a < p.size(); ++a) p.x[a].z -= 1e-5;  // the rock sinks 0.25 mm per batch
      one.update(p);
      for (int t = 2; t >= 0; --t) lanes.update_part(p, t, &own[static_cast<std::size_t>(t)]);  // any order
    }
    lanes.end_batch();
    check_same(one, lanes, p, dt);
    // A pair-list rebuild every other batch, before any sphere has moved half the margin: the candidates anew.
    if (batch % 2 == 1) lanes.mark_stale(), one.mark_stale();
  }
  const double risen = one.surface_z(0) - 0.05;
  INFO("members " << one.members().size() << ", candidates " << lanes.candidate_count() << ", rise " << risen);
  CHECK(one.members().size() > 200);
  CHECK(risen > 0.0);
  CHECK(lanes.candidate_count() < p.size());
}

}  // namespace

TEST_CASE("fluid field: 3 lanes over interleaved particles give update()'s bits (members, volumes, surface, kicks)") {
  lanes_against_one(false);
}

TEST_CASE("fluid field: 3 lanes over index ranges give update()'s bits (the surface's sum continued lane by lane)") {
  lanes_against_one(true);
}

// update() skips a sphere's constants while it stays in its region with the same wetted volume (field.cpp): a
// new step or gravity (set_step) must still make them anew, as a field that never saw the old step does.
TEST_CASE("fluid field: a resting sphere's kick follows a new step, as a fresh field's") {
  Particles p = falling_rock();
  FluidRegion rock_paste = paste(), water = paste();
  rock_paste.surface_rise = water.surface_rise = false;  // the same surface after any number of updates
  water.law = NewtonianStokes::Params{1000, 1e-3};  // Stokes drag (linear): its kick factors depend on the step
  water.curve = FluidRegion{}.curve;
  // Slow enough for the paste's affine branch (its kept factors also depend on the step).
  const Vec3 g{0, 0, -9.81}, v{1e-4, -2e-4, -3e-4}, f{0, 0, -1e-4};
  for (bool linear : {true, false}) {
    FluidField moved({linear ? water : rock_paste}), fresh({linear ? water : rock_paste});
    moved.set_step(2e-5, g);
    moved.update(p), moved.update(p);  // the second update keeps every sphere's constants
    moved.set_step(5e-5, g), fresh.set_step(5e-5, g);
    moved.update(p), fresh.update(p);  // nothing moved: the same volumes, the new step's constants
    int inside = 0, differ = 0;
    for (long a = 0; a < static_cast<long>(p.size()); ++a) {
      if (!fresh.inside(a)) continue;
      ++inside;
      const auto i = static_cast<std::size_t>(a);
      const Vec3 k1 = moved.kick(a, v, f, p.mass[i], p.radius[i], 2.5e-5, g);
      const Vec3 k2 = fresh.kick(a, v, f, p.mass[i], p.radius[i], 2.5e-5, g);
      differ += k1.x != k2.x || k1.y != k2.y || k1.z != k2.z;
    }
    CHECK(inside > 100);
    CHECK(differ == 0);
  }
}
