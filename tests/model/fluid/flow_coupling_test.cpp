// SPDX-License-Identifier: MIT
// The moving paste in the engine ([[fluid]] dynamics = "flow", model/fluid/flow_coupling.h, the flow pass
// forces/flow_forces.h): a sphere in a Bingham paste held by the yield part only with the paste's pressure
// force (-V_p grad p, the buoyancy counted once) and sinking below the yield threshold; the same bits at 1 and
// 2 threads and in batches, with contacts, walls and the exchange's velocity changes on cross pairs.
#include "model/fluid/flow_coupling.h"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <tuple>

#include "base/units.h"
#include "model/flow/solver.h"
#include "model/world.h"
#include "tests/model/fluid/flow_scene.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

// One 10 mm rock sphere at rest 2 cm below the surface of a Bingham paste (Stokes curve) of yield number
// Y = tau_y / (g d (rho_s - rho_f)), in the 6 x 6 cm box with 1 cm cells; run for `time` s.
struct Held {
  double drop = 0.0, speed = 0.0;  // m (downwards), m/s at the end
  long cycles = 0;
};
Held sphere_in_paste(double Y, double time) {
  const double d = 0.01, rho_f = 1800.0;
  const double tau_y = Y * 9.81 * d * (2760.0 - rho_f);
  const std::string paste = fmt::format(
      "density = {}\nrheology = \"bingham\"\nyield_stress = {}\nplastic_viscosity = 0.5\ncurve = \"stokes\"\n"
      "regularisation = 100.0\n",
      rho_f, tau_y);
  const std::string text = model::test::flow_box(1e-4, 0.04, paste, "coupling_interval = 10\n") +
                           "[[particle]]\nmaterial = \"rock\"\nradius = 0.005\nposition = [0.031, 0.029, 0.02]\n";
  World w = make_world(model::test::scene_from(text));
  REQUIRE(w.flow() != nullptr);
  REQUIRE(w.fluid() == nullptr);  // the at-rest field never sees a flow region
  w.advance(std::lround(time / 1e-4));
  Held h;
  h.drop = 0.02 - w.particles().x[0].z;
  h.speed = norm(w.particles().v[0]);
  h.cycles = w.flow()->cycles();
  return h;
}

}  // namespace

TEST_CASE("flow pass: a sphere at Y = 0.08 is held by the yield part with the paste's pressure force, and at Y = 0.02 it sinks") {
  // The law's own threshold (Stokes curve): (pi^2/4 + 3 pi) d^2 tau_y = (rho_s - rho_f) g pi d^3 / 6 at
  // Y = (pi / 6) / (pi^2/4 + 3 pi) = 0.0440. At Y = 0.08 the yield part holds 1.82 times the buoyant weight but
  // only 0.63 times the full weight (rho_s / (rho_s - rho_f) = 2.875): it stays only if the pressure force
  // carries the buoyancy. Before the first flow interval (no pending pressure yet) the sphere creeps for one
  // cycle; then it stops.
  const Held held = sphere_in_paste(0.08, 0.2);
  const Held sinks = sphere_in_paste(0.02, 0.2);
  MESSAGE(fmt::format("Y = 0.08: drop {:.3g} mm, |v| {:.3g} m/s after {} cycles; Y = 0.02: drop {:.3g} mm, |v| {:.3g} m/s",
                      1e3 * held.drop, held.speed, held.cycles, 1e3 * sinks.drop, sinks.speed));
  CHECK(held.cycles == 200);
  // Held: what is left is the regularised plug's creep (m = 100 s: ~1e-5 m/s here), a thousand times slower
  // than the sphere below the threshold.
  CHECK(std::abs(held.drop) < 2e-5);  // m: 0.002 of the diameter
  CHECK(held.speed < 1e-4);
  CHECK(sinks.speed > 1e-2);
  CHECK(sinks.drop > 1e-3);
}

TEST_CASE("flow pass: the same bits at 1 and 2 threads and in batches (contacts, walls, the exchange's velocity changes)") {
  // 8 g of 5-6 mm rocks in a Newtonian paste (0.05 Pa s) of the 6 x 6 cm box, and three stacks of two touching
  // spheres in the middle, the bottom one on the floor: contacts (pairs and walls) across the threads' slabs
  // while the exchange changes velocities at every cycle's end (every 10 steps). One more sphere starts 0.5 mm
  // above the flow box's top (z = 0.12 m) and falls into it after ~500 steps, inside a batch of 300: the members
  // change between two partitions, so a thread's own list of members (forces/flow_forces.h) must follow them.
  std::string text =
      model::test::flow_box(2e-5, 0.06, "density = 1800\nrheology = \"newtonian\"\nviscosity = 0.05\ncurve = \"stokes\"\n",
                            "coupling_interval = 10\n") +
      "[[factory]]\nmaterial = \"rock\"\nmass = 0.008\nshape = \"box\"\nmin = [0.004, 0.004, 0.012]\n"
      "max = [0.056, 0.056, 0.04]\n[[factory.psd]]\nd_min = 5e-3\nd_max = 6e-3\nfraction = 1.0\n";
  for (double y : {0.015, 0.03, 0.045})
    for (double z : {0.00275, 0.008251})
      text += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = 0.00275\nposition = [0.03, {}, {}]\n", y, z);
  text += "[[particle]]\nmaterial = \"rock\"\nradius = 0.00275\nposition = [0.03, 0.03, 0.1205]\n";
  auto run = [&](int threads, long batch) {
    omp_set_num_threads(threads);
    Scene scene = model::test::scene_from(text);
    scene.config.parallel_min_items = 0;  // the parallel paths even for this small scene
    World w = make_world(scene);
    long contacts = 0;  // the most pair + wall contacts at a batch's end
    std::size_t members_first = 0;  // the flow's members after the first batch
    for (long k = 0; k < 1000; k += batch) {
      w.advance(std::min(batch, 1000 - k));
      const Energies e = w.energies();
      contacts = std::max(contacts, e.pair_contacts + e.wall_contacts);
      if (k == 0) members_first = w.flow()->members().size();
    }
    omp_set_num_threads(omp_get_num_procs());
    return std::make_tuple(w.particles().x, w.particles().v, w.flow()->solver().velocity()[2], contacts,
                           w.flow()->cycles(), members_first, w.flow()->members().size());
  };
  const auto [xa, va, ua, pairs, cycles, first, last] = run(1, 1);
  const auto [xb, vb, ub, pairs_b, cycles_b, first_b, last_b] = run(2, 1);
  const auto [xc, vc, uc, pairs_c, cycles_c, first_c, last_c] = run(2, 300);
  const auto [xd, vd, ud, pairs_d, cycles_d, first_d, last_d] = run(1, 300);
  MESSAGE(fmt::format("{} spheres, at most {} contacts (pairs and walls), {} cycles, {} then {} members", xa.size(),
                      pairs, cycles, first, last));
  CHECK(cycles == 100);
  CHECK(pairs > 0);
  CHECK(last == first + 1);  // the falling sphere joined the members
  for (const auto* x : {&xb, &xc, &xd}) CHECK(model::test::same_bits(xa, *x));
  for (const auto* v : {&vb, &vc, &vd}) CHECK(model::test::same_bits(va, *v));
  for (const auto* u : {&ub, &uc, &ud}) CHECK(model::test::same_bits(ua, *u));
}


TEST_CASE("flow pass: a failure inside the World's parallel region reaches the caller instead of aborting") {
  // A 12 mm sphere's kernel (c = 2.5: half-width 15 mm) is longer than the 1 cm wide box: the kernel refuses it
  // in the first step's flow start, inside the region; the World rethrows it after the region.
  const std::string text =
      "seed = 1\ntime_step = 1e-4\nend_time = 0.01\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [0.02, 0.07, 0.13]\n"
      "[contact]\nlaw = \"hertz_mindlin\"\n" + model::test::material("rock", 2760, 4.68e7, 0.19) +
      model::test::interaction("rock/rock", 0.5, 0.5) +
      "[[fluid]]\nname = \"paste\"\nx = [0.0, 0.01]\ny = [0.0, 0.06]\nbottom = 0.0\nsurface = 0.04\ndensity = 1800\n"
      "rheology = \"newtonian\"\nviscosity = 0.5\ncurve = \"stokes\"\ndynamics = \"flow\"\ncell = 0.01\ntop = 0.12\n"
      "kernel_width = 2.5\n[[particle]]\nmaterial = \"rock\"\nradius = 0.006\nposition = [0.005, 0.03, 0.02]\n";
  World w = make_world(model::test::scene_from(text));
  CHECK_THROWS_WITH_AS(w.advance(10), doctest::Contains("longer than the box"), std::invalid_argument);
}
