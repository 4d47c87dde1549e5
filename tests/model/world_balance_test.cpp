// SPDX-License-Identifier: MIT
// The threads' load balance (model/world_balance.cpp): any partition gives the 1-thread bits, the measured
// shares stay bounded, and the share update moves towards the measured speeds.
#include "model/world.h"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <omp.h>

#include <cstring>

#include "tests/model/scene_text.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

// ~100 spheres of 5-8 mm thrown down at 1.5 m/s onto a floor, constant-torque rolling: impacts, lasting
// contacts and rebuilds within the 0.02 s the tests run.
std::string thrown_pile() {
  return "seed = 3\ntime_step = 4e-6\nend_time = 1\n[domain]\nmin = [-0.5, -0.5, -0.05]\nmax = [0.5, 0.5, 1.0]\n"
         "[physics]\ngravity = [0, 0, -9.81]\nrotation = true\n[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"constant_torque\"\n" +
         model::test::material("rock", 2760, 4.68e7, 0.19) + model::test::interaction("rock/rock", 0.79, 0.466, 0.15) +
         "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
         "[[factory]]\nmaterial = \"rock\"\nmass = 0.02\nshape = \"cylinder\"\ncenter = [0, 0]\nradius = 0.025\n"
         "z_min = 0.002\nz_max = 0.06\nvelocity = [0, 0, -1.5]\n[[factory.psd]]\nd_min = 5e-3\nd_max = 8e-3\nfraction = 1.0\n";
}

}  // namespace

TEST_CASE("load balance: any thread shares give the same bits, and measured shares stay within bounds") {
  auto run = [](int threads, std::vector<double> shares) {
    omp_set_num_threads(threads);
    Scene scene = model::test::scene_from(thrown_pile());
    scene.config.parallel_min_items = 0;  // force the parallel paths even for this small scene
    World w = make_world(scene);
    if (!shares.empty()) w.fix_thread_shares(shares);
    for (long k = 0; k < 5000; k += 500) w.advance(500);
    omp_set_num_threads(omp_get_num_procs());
    if (threads > 1 && shares.empty()) {  // measured: a partition of the cost, none starved
      double sum = 0.0;
      for (double s : w.thread_shares()) {
        CHECK(s >= 0.25 - 1e-12);
        CHECK(s <= 0.75 + 1e-12);
        sum += s;
      }
      CHECK(sum == doctest::Approx(1.0));
    }
    return w.particles().x;
  };
  const auto one = run(1, {}), skewed = run(2, {0.15, 0.85}), other = run(2, {0.7, 0.3}), measured = run(2, {});
  REQUIRE(one.size() == skewed.size());
  CHECK(std::memcmp(one.data(), skewed.data(), one.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(one.data(), other.data(), one.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(one.data(), measured.data(), one.size() * sizeof(Vec3)) == 0);
}

TEST_CASE("load balance: the shares move halfway towards the measured speeds, bounded, summing to 1") {
  // Thread 1 took twice as long for the same cost: speeds 2:1, so 0.5 -> halfway to 2/3.
  auto s = balanced_shares({0.5, 0.5}, {100.0, 100.0}, {1.0, 2.0});
  CHECK(s[0] == doctest::Approx(0.5 * 0.5 + 0.5 * 2.0 / 3.0));
  CHECK(s[0] + s[1] == doctest::Approx(1.0));
  // Repeated on the same speeds: converges to the speeds' shares.
  for (int k = 0; k < 40; ++k) s = balanced_shares(s, {200.0 * s[0], 200.0 * s[1]}, {200.0 * s[0] / 2.0, 200.0 * s[1]});
  CHECK(s[0] == doctest::Approx(2.0 / 3.0).epsilon(1e-6));
  // A thread that did no work in its time cannot be starved below half an equal share.
  s = balanced_shares({0.75, 0.25}, {100.0, 100.0}, {1.0, 1e9});
  CHECK(s[1] == doctest::Approx(0.25));
  CHECK(s[0] == doctest::Approx(0.75));
  // No time measured: unchanged.
  s = balanced_shares({0.6, 0.4}, {1.0, 1.0}, {0.0, 0.0});
  CHECK(s[0] == 0.6);
}
