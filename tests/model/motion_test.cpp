// SPDX-License-Identifier: MIT
// The Verlet lists' rebuild test (model/motion.h, World::rebuild_due): its bound covers every pair's relative
// displacement for any common displacement, is never looser than the usual 2 max|dx|, lets a coherent stream
// keep its lists about twice as long, and a World that uses it never misses a touching pair.
#include "model/motion.h"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "model/world.h"
#include "tests/model/scene_text.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

Motion motion_of(const std::vector<Vec3>& dx, const Vec3& u) {
  Motion m;
  for (const Vec3& d : dx) m.add(norm2(d), norm2(d - u));
  return m;
}

double largest_relative(const std::vector<Vec3>& dx) {
  double worst = 0.0;
  for (std::size_t i = 0; i < dx.size(); ++i)
    for (std::size_t j = i + 1; j < dx.size(); ++j) worst = std::max(worst, norm(dx[i] - dx[j]));
  return worst;
}

// n displacements (m): a resting pile (jitter), a stream moving `stream` with spread, and a few bouncers.
std::vector<Vec3> pile_and_stream(std::mt19937_64& rng, int n, const Vec3& stream, double spread) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> dx;
  for (int k = 0; k < n; ++k) {
    const Vec3 noise{g(rng), g(rng), g(rng)};
    if (k % 3 == 0) dx.push_back(noise * (0.02 * norm(stream)));           // resting
    else if (k % 17 == 0) dx.push_back(noise * (0.5 * norm(stream) / norm(noise)));  // bouncing: half its move
    else dx.push_back(stream + noise * spread);                            // falling
  }
  return dx;
}

}  // namespace

TEST_CASE("motion: the bound covers every pair's relative displacement, whatever the common displacement") {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Vec3 stream{0.1 * g(rng), 0.1 * g(rng), -1e-3 * (1.0 + trial % 5)};
    const auto dx = pile_and_stream(rng, 150, stream, 1e-5 * (trial % 7));
    const double exact = largest_relative(dx);
    // A good common displacement, none, a wrong one and a random one: each must bound every pair.
    for (const Vec3& u : {stream, Vec3{}, stream * -1.0, Vec3{g(rng), g(rng), g(rng)} * 1e-3}) {
      const Motion m = motion_of(dx, u);
      CHECK(m.pair_bound() >= exact * (1.0 - 1e-12));
      // Never looser than the usual test, 2 max|dx|.
      CHECK(m.pair_bound() <= 2.0 * std::sqrt(m.max2()) * (1.0 + 1e-12));
      ++checked;
    }
  }
  CHECK(checked == 240);
}

TEST_CASE("motion: a stream falling onto a resting pile is bounded by its own move, not twice it") {
  std::mt19937_64 rng(11);
  const Vec3 stream{0, 0, -1e-3};  // m
  const auto dx = pile_and_stream(rng, 600, stream, 2e-6);
  const Motion good = motion_of(dx, stream);
  const Motion none = motion_of(dx, Vec3{});
  const double d = std::sqrt(good.max2());
  CHECK(none.pair_bound() <= 2.0 * d);  // u = 0: the usual test (its two largest moves)
  CHECK(none.pair_bound() > 1.9 * d);
  // The bouncers (half the stream's move) are the still side's largest: stream + bouncer, ~1.5 of the move.
  CHECK(good.pair_bound() < 1.6 * norm(stream));
  CHECK(good.pair_bound() > 1.0 * norm(stream));
  CHECK(Motion::within(4e-6).pair_bound() == doctest::Approx(4e-3));
}

TEST_CASE("motion: the lanes' merged result is the scalar adds' result, padding zeros change nothing") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> r(0.0, 1e-6);
  for (int n : {8, 24, 64}) {
    std::vector<double> a2(static_cast<std::size_t>(n)), b2(static_cast<std::size_t>(n));
    Motion scalar;
    for (int e = 0; e < n; ++e) {
      a2[static_cast<std::size_t>(e)] = e < n - 5 ? r(rng) : 0.0;  // the last five: padding
      b2[static_cast<std::size_t>(e)] = e < n - 5 ? r(rng) : 0.0;
      scalar.add(a2[static_cast<std::size_t>(e)], b2[static_cast<std::size_t>(e)]);
    }
    MotionLanes lanes;
    lanes.add(a2.data(), b2.data(), n);
    const Motion merged = lanes.total();
    CHECK(merged.still1 == scalar.still1);
    CHECK(merged.still2 == scalar.still2);
    CHECK(merged.moving1 == scalar.moving1);
    CHECK(merged.moving2 == scalar.moving2);
    CHECK(merged.moving_a == scalar.moving_a);
    CHECK(merged.still_b == scalar.still_b);
  }
}

namespace {

std::string scene_text(const std::string& body) {
  return "seed = 5\ntime_step = 4e-6\nend_time = 1.0\n[domain]\nmin = [-0.5, -0.5, -0.05]\nmax = [0.5, 0.5, 1.0]\n"
         "[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"constant_torque\"\n[neighbor]\nskin = 1e-3\n" +
         model::test::material("rock", 2760, 4.68e7, 0.19) + model::test::interaction("rock/rock", 0.79, 0.466, 0.15) +
         body;
}

// Every pair closer than r_i + r_j (touching) is in the pair list.
long missed_contacts(const World& w) {
  const Particles& p = w.particles();
  std::set<std::pair<std::uint32_t, std::uint32_t>> listed;
  const PairList& L = w.pairs();
  for (std::size_t k = 0; k < L.size(); ++k) listed.insert({L.i[k], L.j[k]});
  long missed = 0;
  for (std::uint32_t a = 0; a < p.size(); ++a)
    for (std::uint32_t b = a + 1; b < p.size(); ++b)
      if (norm(p.x[a] - p.x[b]) < p.radius[a] + p.radius[b] && !listed.count({a, b})) ++missed;
  return missed;
}

}  // namespace

TEST_CASE("motion: a cloud falling as one keeps its lists twice as long as 2 max|dx| would") {
  // 300 spheres of 4 mm falling at 2 m/s through empty space: every sphere moves alike, so only the wall and
  // fluid lists' limit (a move of one skin) calls a rebuild: every ~125 steps of 4 us instead of every ~62.
  std::string body = "[[factory]]\nmaterial = \"rock\"\nmass = 0.03\nshape = \"box\"\nmin = [-0.03, -0.03, 0.5]\n"
                     "max = [0.03, 0.03, 0.56]\nvelocity = [0, 0, -2]\n[[factory.psd]]\nd_min = 3.9e-3\nd_max = 4.1e-3\n"
                     "fraction = 1.0\n";
  Scene scene = model::test::scene_from(scene_text(body));
  World w = make_world(scene);
  w.advance(1000);
  INFO("rebuilds: " << w.profile().rebuilds);
  CHECK(w.particles().size() > 250);
  CHECK(w.profile().rebuilds <= 10);  // the usual test: 17 (1 + 1000 / 62)
  CHECK(w.profile().rebuilds >= 8);
}

TEST_CASE("motion: two layers closing at 2.8 m/s are listed before they touch") {
  // 25 spheres of 4 mm moving at +2 m/s in x towards 25 at -0.8 m/s, 1.2 mm apart (more than the 1 mm skin:
  // not listed at the first build). The common displacement is the fast layer's, so each layer alone looks
  // still; only the bound across the classes (still + moving) sees them close at 2.8 m/s. Without it the
  // lists would be rebuilt at a move of one skin (0.5 ms, 125 steps), after the layers touch (107 steps).
  std::string body;
  for (int k = 0; k < 25; ++k) {
    const double y = 0.005 * (k % 5), z = 0.3 + 0.005 * (k / 5);
    body += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = 0.002\nposition = [0, {}, {}]\nvelocity = [2, 0, 0]\n", y, z);
    body += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = 0.002\nposition = [0.0052, {}, {}]\n"
                        "velocity = [-0.8, 0, 0]\n", y, z);
  }
  Scene scene = model::test::scene_from(scene_text(body));
  World w = make_world(scene);
  long missed = 0, touching_steps = 0;
  for (int step = 0; step < 200; ++step) {
    w.advance(1);
    missed += missed_contacts(w);
    const Particles& p = w.particles();
    touching_steps += norm(p.x[0] - p.x[1]) < p.radius[0] + p.radius[1];
  }
  INFO("rebuilds " << w.profile().rebuilds);
  CHECK(touching_steps > 20);  // the layers did collide
  CHECK(missed == 0);
}

TEST_CASE("motion: a stream thrown into a tube onto a floor never has a touching pair missing from its list") {
  // ~700 spheres of 4-6 mm thrown down at 1.5 m/s into a cylinder: impacts, bouncers, a resting heap under
  // a falling cloud, at 1 and 2 threads; the list is checked against brute force after every step.
  const std::string body = model::test::kThrownHeap;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Scene scene = model::test::scene_from(scene_text(body));
    scene.config.parallel_min_items = 0;
    World w = make_world(scene);
    long missed = 0;
    for (int step = 0; step < 1500; ++step) {
      w.advance(1);
      if (step % 3 == 0) missed += missed_contacts(w);
    }
    INFO("threads " << threads << ", rebuilds " << w.profile().rebuilds);
    CHECK(missed == 0);
    CHECK(w.profile().rebuilds > 5);
  }
  omp_set_num_threads(omp_get_num_procs());
}
