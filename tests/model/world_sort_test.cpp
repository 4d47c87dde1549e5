// SPDX-License-Identifier: MIT
// The spatial sort of the particle store at neighbour rebuilds ([neighbor] sort_every, model/world.cpp):
// every array moves with its particle, the pair springs are carried through the renaming (negated where a
// pair's ends swap), the bits do not depend on the thread count, and a sorted run ends within round-off
// growth of the unsorted one (the sort changes the order of the force sums, not the physics).
#include "model/world.h"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "base/h5.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

// ~700 spheres of 4-6 mm thrown down at 1.5 m/s into a cylinder on a floor: impacts, lasting contacts with
// their springs (both rolling laws: the elastic-plastic one keeps a rolling spring too), frequent rebuilds.
std::string heap_scene(const std::string& rolling, long sort_every) {
  return fmt::format(
             "seed = 5\ntime_step = 4e-6\nend_time = 1.0\n[domain]\nmin = [-0.5, -0.5, -0.05]\nmax = [0.5, 0.5, 1.0]\n"
             "[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"{}\"\n[neighbor]\nskin = 1e-3\nsort_every = {}\n",
             rolling, sort_every) +
         model::test::material("rock", 2760, 4.68e7, 0.19) + model::test::interaction("rock/rock", 0.79, 0.466, 0.15) +
         model::test::kThrownHeap;
}

struct End {
  std::map<std::int64_t, Vec3> x, v, w;  // by id
  long sorts = 0, rebuilds = 0;
  bool reordered = false;  // the dense order at the end is not the id order
  std::vector<Vec3> dense_x;
};

End run(const std::string& rolling, long sort_every, int threads, long steps) {
  omp_set_num_threads(threads);
  Scene scene = model::test::scene_from(heap_scene(rolling, sort_every));
  scene.config.parallel_min_items = 0;  // the parallel paths even for this small scene
  World w = make_world(scene);
  for (long k = 0; k < steps; k += 50) w.advance(50);
  omp_set_num_threads(omp_get_num_procs());
  End e;
  const Particles& p = w.particles();
  for (std::size_t a = 0; a < p.size(); ++a) {
    e.x[p.id[a]] = p.x[a], e.v[p.id[a]] = p.v[a], e.w[p.id[a]] = p.omega[a];
    e.reordered = e.reordered || p.id[a] != static_cast<std::int64_t>(a);
  }
  e.dense_x = p.x;
  e.sorts = w.profile().sorts;
  e.rebuilds = w.profile().rebuilds;
  return e;
}

double max_diff(const std::map<std::int64_t, Vec3>& a, const std::map<std::int64_t, Vec3>& b) {
  double m = 0.0;
  for (const auto& [id, q] : a) m = std::max(m, norm(q - b.at(id)));
  return m;
}

}  // namespace

TEST_CASE("spatial sort: apply_map moves every array of a particle, rotation included and remove_if is its compaction") {
  Particles p;
  p.enable_rotation();
  for (int k = 0; k < 5; ++k)
    p.add(k % 2, 0.001 * (k + 1), 2760, {1.0 * k, 0, 0}, {0, 1.0 * k, 0}, {0, 0, 1.0 * k});
  for (int k = 0; k < 5; ++k) p.f[k] = {0, 0, 10.0 * k}, p.torque[k] = {100.0 * k, 0, 0}, p.rolling_capacity[k] = k;
  const Particles before = p;
  const std::vector<std::uint32_t> map{3, 0, 4, 1, 2};  // old -> new
  p.apply_map(map, 5);
  for (std::size_t a = 0; a < 5; ++a) {
    const std::size_t b = map[a];
    CHECK(p.id[b] == before.id[a]);
    CHECK(p.material[b] == before.material[a]);
    CHECK(p.radius[b] == before.radius[a]);
    CHECK(p.mass[b] == before.mass[a]);
    CHECK(p.inv_mass[b] == before.inv_mass[a]);
    CHECK(p.x[b].x == before.x[a].x);
    CHECK(p.v[b].y == before.v[a].y);
    CHECK(p.f[b].z == before.f[a].z);
    CHECK(p.omega[b].z == before.omega[a].z);
    CHECK(p.torque[b].x == before.torque[a].x);
    CHECK(p.inv_inertia[b] == before.inv_inertia[a]);
    CHECK(p.rolling_capacity[b] == before.rolling_capacity[a]);
  }
  Particles q = before;
  const auto kept = q.remove_if({0, 1, 0, 1, 0});
  CHECK(kept == std::vector<std::uint32_t>{0, Particles::kGone, 1, Particles::kGone, 2});
  CHECK(q.id == std::vector<std::int64_t>{0, 2, 4});
  CHECK(q.omega.size() == 3);
}

TEST_CASE("spatial sort: a pair whose ends swap keeps (lower, higher) and its springs, negated") {
  PairList L;
  L.width = 6;
  L.i = {0, 1};
  L.j = {2, 2};
  L.r_star = {1, 2}, L.m_star = {3, 4}, L.rsum = {5, 6}, L.law_index = {0, 0}, L.touching = {1, 0};
  L.history = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  L.rename({2, 0, 1}, 3);  // 0 -> 2, 1 -> 0, 2 -> 1: pair (0, 2) becomes (2, 1) -> (1, 2), pair (1, 2) -> (0, 1)
  CHECK(L.i == std::vector<std::uint32_t>{1, 0});
  CHECK(L.j == std::vector<std::uint32_t>{2, 1});
  CHECK(L.history == std::vector<double>{-1, -2, -3, -4, -5, -6, 7, 8, 9, 10, 11, 12});
  CHECK(L.touching == std::vector<std::uint32_t>{1, 0});
  CHECK(L.r_star == std::vector<double>{1, 2});
  CHECK(L.rsum == std::vector<double>{5, 6});
  // The CSR by first particle the carry-over reads: particle 0 has pair 1, particle 1 pair 0.
  CHECK(L.start == std::vector<std::uint32_t>{0, 1, 2, 2});
  CHECK(L.entry == std::vector<std::uint32_t>{1, 0});
}

TEST_CASE("spatial sort: a thrown heap ends within round-off growth of the unsorted run and has the same bits at 1 and 2 threads") {
  // 0.02 s (5000 steps): the spheres hit the floor, the tube and each other and keep their contacts with
  // springs across ~100 rebuilds, each one sorting. Sorting changes the order of each particle's force sum,
  // i.e. the last bit of a force, and the chaotic contacts amplify it: measured here max |dx| 3.5e-15 m
  // (constant torque) and 3.4e-16 m (elastic-plastic), |dv| 8.5e-12 / 1.6e-12 m/s (spheres of 2-3 mm radius
  // moving at 1.5 m/s). A spring carried with the wrong sign at a renaming changes a force by up to the
  // Coulomb limit: without the negation in PairList::rename this test measured |dx| 5.3 mm / 2.5 mm and
  // |dv| 1.4 / 1.6 m/s. Tolerance 1e-9 m on positions and 1e-5 m/s on velocities: a millionfold room for
  // round-off growth, still a millionth of what a lost spring does.
  for (const std::string rolling : {"constant_torque", "elastic_plastic"}) {
    CAPTURE(rolling);
    const long steps = 5000;
    const End plain = run(rolling, 0, 1, steps), sorted = run(rolling, 1, 1, steps), sorted2 = run(rolling, 1, 2, steps);
    const double dx = max_diff(plain.x, sorted.x), dv = max_diff(plain.v, sorted.v), dw = max_diff(plain.w, sorted.w);
    MESSAGE(fmt::format("{}: {} spheres, {} rebuilds, {} sorts; sorted - unsorted after {} steps: max |dx| {:.3g} m, "
                        "|dv| {:.3g} m/s, |dw| {:.3g} rad/s",
                        rolling, plain.x.size(), sorted.rebuilds, sorted.sorts, steps, dx, dv, dw));
    CHECK(plain.sorts == 0);
    CHECK(!plain.reordered);
    CHECK(sorted.sorts > 10);
    CHECK(sorted.reordered);
    CHECK(sorted.rebuilds == plain.rebuilds);
    CHECK(dx < 1e-9);
    CHECK(dv < 1e-5);
    // Thread count: the sort is serial and a function of the positions only.
    REQUIRE(sorted.dense_x.size() == sorted2.dense_x.size());
    CHECK(std::memcmp(sorted.dense_x.data(), sorted2.dense_x.data(), sorted.dense_x.size() * sizeof(Vec3)) == 0);
  }
}

TEST_CASE("spatial sort: the snapshots are written in id order, as without the sort") {
  const std::filesystem::path dir = std::filesystem::absolute(fmt::format("model_sort_out_{}", ::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string text = heap_scene("constant_torque", 1);
  text.replace(text.find("end_time = 1.0"), 14, "end_time = 0.01");
  std::ofstream(dir / "heap.toml") << text << "[output]\ninterval = 0.005\n";
  const auto r = pastemix::test::run_pastemix(fmt::format("run '{}' --out '{}' --quiet --threads 1",
                                                          (dir / "heap.toml").string(), dir.string()));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("spatial sorts") != std::string::npos);
  const H5Reader h5(dir / "heap.h5");
  const auto ids = h5.read_ints("/snapshots/000002/id");
  REQUIRE(!ids.empty());
  for (std::size_t k = 0; k < ids.size(); ++k) CHECK(ids[k] == static_cast<std::int64_t>(k));
  CHECK(h5.attribute_int("/profile", "sorts") > 0);
  std::filesystem::remove_all(dir);
}

// The sort's slowest axis is the one the threads' index slabs cut across (World::slab_axes): for a flat
// layer under a tall column, not the longest side (the height, which would cut the layer flat through all
// its spheres) but a side of the layer, so that few pairs cross the two threads' slabs.
TEST_CASE("spatial sort: under a tall column a flat layer is cut across its side, not its height") {
  std::string text = model::test::kBase + "[neighbor]\nskin = 1e-3\nsort_every = 1\n";
  const auto sphere = [&](double x, double y, double z) {
    text += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = 1e-3\nposition = [{}, {}, {}]\n", x, y, z);
  };
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 16; ++j)
      for (int k = 0; k < 4; ++k) sphere(2.1e-3 * i, 2.1e-3 * j, 1e-3 + 2.1e-3 * k);
  for (int k = 0; k < 40; ++k) sphere(25e-3, 16e-3, 12e-3 + 2.1e-3 * k);  // up to 94 mm: the longest side
  omp_set_num_threads(2);
  Scene scene = model::test::scene_from(text);
  scene.config.parallel_min_items = 0;
  World w = make_world(scene);
  w.advance(1);
  omp_set_num_threads(omp_get_num_procs());
  const PairList& L = w.pairs();
  REQUIRE(L.threads == 2);
  REQUIRE(L.size() > 2000);
  CAPTURE(L.size());
  // Measured: 293 of 11,231 pairs cross the cut across the layer's 50 mm side; 1,403 with the longest side
  // slowest (slab_axes returning its input), the cut then running flat through the layer's four rows.
  CHECK(L.cross_pairs.size() < L.size() / 20);
}
