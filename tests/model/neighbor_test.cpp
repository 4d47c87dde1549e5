// SPDX-License-Identifier: MIT
#include "model/neighbor.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <utility>

#include "base/rng.h"

using namespace pastemix;
using namespace pastemix::model;

TEST_CASE("neighbor: the cell-list pairs equal brute force, for a 42:1 size ratio too") {
  for (double ratio : {1.0, 2.0, 42.0}) {
    CAPTURE(ratio);
    Rng rng(11);
    std::vector<Vec3> x;
    std::vector<double> r;
    for (int k = 0; k < 600; ++k) {
      x.push_back({rng.uniform(0, 0.1), rng.uniform(0, 0.1), rng.uniform(0, 0.05)});
      r.push_back(k % 50 == 0 ? 0.5e-3 * ratio : 0.5e-3 * rng.uniform(1.0, 1.5));
    }
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
