// SPDX-License-Identifier: MIT
#include "model/neighbor.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <utility>

#include "base/rng.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

// n spheres uniform in the box [0, size]: radii 0.5-0.75 mm, every 50th of radius 0.5 mm x ratio.
void cloud(std::uint64_t seed, int n, const Vec3& size, double ratio, std::vector<Vec3>& x, std::vector<double>& r) {
  Rng rng(seed);
  for (int k = 0; k < n; ++k) {
    x.push_back({rng.uniform(0, size.x), rng.uniform(0, size.y), rng.uniform(0, size.z)});
    r.push_back(k % 50 == 0 ? 0.5e-3 * ratio : 0.5e-3 * rng.uniform(1.0, 1.5));
  }
}

}  // namespace

TEST_CASE("neighbor: the cell-list pairs equal brute force, for a 42:1 size ratio too") {
  for (double ratio : {1.0, 2.0, 42.0}) {
    CAPTURE(ratio);
    std::vector<Vec3> x;
    std::vector<double> r;
    cloud(11, 600, {0.1, 0.1, 0.05}, ratio, x, r);
    const double skin = 0.4e-3;
    auto as_set = [](const CandidatePairs& c) {
      std::vector<std::pair<std::uint32_t, std::uint32_t>> v;
      for (std::size_t k = 0; k < c.i.size(); ++k) v.emplace_back(c.i[k], c.j[k]);
      std::sort(v.begin(), v.end());
      return v;
    };
    const auto fast = as_set(build_pairs(x, r, skin));
    const auto slow = as_set(brute_force_pairs(x, r, skin));
    CHECK(fast.size() > 0);
    CHECK(fast == slow);
  }
}

TEST_CASE("neighbor: the list and its order do not depend on the thread count, nor on the buffers of a last build") {
  for (double ratio : {1.0, 42.0}) {
    CAPTURE(ratio);
    std::vector<Vec3> x;
    std::vector<double> r;
    cloud(12, 3000, {0.03, 0.03, 0.02}, ratio, x, r);
    const double skin = 0.4e-3;
    CandidatePairs one, reused;
    NeighborSearch fresh, kept;
    fresh.build(x, r, skin, one, 1);
    CHECK(one.i.size() > 1000);
    // A build with other positions first, then this one, on 2 and 3 threads: the same pairs in the same order.
    std::vector<Vec3> moved = x;
    for (Vec3& q : moved) q.z += 0.01;
    for (int threads : {2, 3}) {
      CAPTURE(threads);
      kept.build(moved, r, skin, reused, threads);
      kept.build(x, r, skin, reused, threads);
      CHECK(reused.i == one.i);
      CHECK(reused.j == one.j);
    }
  }
}
