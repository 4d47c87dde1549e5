// SPDX-License-Identifier: MIT
#include "model/neighbor.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// The pairs of c as a sorted set (the search's order is its scan's).
std::vector<std::pair<std::uint32_t, std::uint32_t>> as_set(const CandidatePairs& c) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> v;
  for (std::size_t k = 0; k < c.i.size(); ++k) v.emplace_back(c.i[k], c.j[k]);
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

TEST_CASE("neighbor: the cell-list pairs equal brute force, for a 42:1 size ratio too") {
  for (double ratio : {1.0, 2.0, 42.0}) {
    CAPTURE(ratio);
    std::vector<Vec3> x;
    std::vector<double> r;
    cloud(11, 600, {0.1, 0.1, 0.05}, ratio, x, r);
    const double skin = 0.4e-3;
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
    // A build of other spheres (other count and sizes: other levels), one with other positions, then this
    // one, on 2 and 3 threads (each thread sorts its share into the cells): the same pairs in the same order.
    std::vector<Vec3> moved = x, other_x;
    std::vector<double> other_r;
    for (Vec3& q : moved) q.z += 0.01;
    cloud(13, 2000, {0.03, 0.03, 0.02}, 43.0 - ratio, other_x, other_r);
    for (int threads : {2, 3}) {
      CAPTURE(threads);
      kept.build(other_x, other_r, skin, reused, threads);
      kept.build(moved, r, skin, reused, threads);
      kept.build(x, r, skin, reused, threads);
      CHECK(reused.i == one.i);
      CHECK(reused.j == one.j);
    }
  }
}

// The threads share the counting sort's cells by ranges of all levels' cells (model/neighbor.cpp: cell_sum,
// place_cells), so a range may begin inside one level and end several levels further on. Radii 0.5-12 mm
// (most small) make five size levels, at least four of them filled: on 2 and 3 threads the same pairs in the
// same order as on one, each level's cells starting where the one-thread sort starts them, and the pairs
// those of brute force.
TEST_CASE("neighbor: cells shared by ranges across five size levels give the one-thread list") {
  Rng rng(41);
  std::vector<Vec3> x;
  std::vector<double> r;
  for (int k = 0; k < 4000; ++k) {
    x.push_back({rng.uniform(0, 0.2), rng.uniform(0, 0.2), rng.uniform(0, 0.1)});
    r.push_back(0.5e-3 * std::pow(24.0, std::pow(rng.uniform(0, 1), 2.0)));  // most small, some up to 12 mm
  }
  const double skin = 0.4e-3;
  NeighborSearch one;
  CandidatePairs ref;
  one.build(x, r, skin, ref, 1);
  long filled = 0;
  for (const auto& level : one.levels()) filled += level.count > 0;
  REQUIRE(filled >= 4);
  CHECK(as_set(ref) == as_set(brute_force_pairs(x, r, skin)));
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    NeighborSearch many;
    CandidatePairs out;
    many.build(x, r, skin, out, threads);
    CHECK(out.i == ref.i);
    CHECK(out.j == ref.j);
    REQUIRE(many.levels().size() == one.levels().size());
    for (std::size_t l = 0; l < one.levels().size(); ++l) {
      CHECK(many.levels()[l].start == one.levels()[l].start);
      CHECK(many.levels()[l].sorted == one.levels()[l].sorted);
    }
  }
}

TEST_CASE("neighbor: the candidate scan gives the scalar loop's pairs in its order, boundary distances too") {
  // 40 candidates around a finder at the origin (so d is exact): random ones, and every fifth on the
  // cut-off along x (d^2 == cut^2: not a pair) or a hair inside it. Every range s0 .. s1 of them (lengths
  // 0-40: every vector tail), with the finder's index below, among and above the candidates' ids.
  Rng rng(20261205);
  const int n = 40;
  std::vector<double> xs(n), ys(n), zs(n), rs(n);
  std::vector<std::uint32_t> sorted(n);
  const Vec3 xa{0.0, 0.0, 0.0};
  const double ra = 1.2e-3;
  for (int s = 0; s < n; ++s) {
    rs[s] = rng.uniform(0.5e-3, 1.0e-3);
    sorted[s] = static_cast<std::uint32_t>(100 + 3 * s);
    if (s % 5 == 0) {
      const double cut = ra + rs[s];
      xs[s] = s % 10 == 0 ? cut : cut * (1.0 - 1e-12), ys[s] = 0.0, zs[s] = 0.0;
    } else {
      xs[s] = rng.uniform(-3e-3, 3e-3), ys[s] = rng.uniform(-3e-3, 3e-3), zs[s] = rng.uniform(-3e-3, 3e-3);
    }
  }
  MESSAGE("candidate scan vectorized: ", detail::scan_is_vectorized());
  int hits = 0;
  for (std::uint32_t a : {7u, 150u, 1000u})
    for (std::uint32_t s0 = 0; s0 <= n; ++s0)
      for (std::uint32_t s1 = s0; s1 <= n; ++s1) {
        std::vector<std::uint32_t> pi(2 * n + 16, 0), pj(2 * n + 16, 0), qi(2 * n + 16, 0), qj(2 * n + 16, 0);
        // Both start after 3 pairs already in the buffers.
        const std::size_t m = detail::scan_candidates(xs.data(), ys.data(), zs.data(), rs.data(), sorted.data(), s0,
                                                      s1, a, xa, ra, pi.data(), pj.data(), 3);
        const std::size_t ms = detail::scan_candidates_scalar(xs.data(), ys.data(), zs.data(), rs.data(),
                                                              sorted.data(), s0, s1, a, xa, ra, qi.data(), qj.data(), 3);
        REQUIRE(m == ms);
        for (std::size_t k = 3; k < m; ++k) {
          REQUIRE(pi[k] == qi[k]);
          REQUIRE(pj[k] == qj[k]);
          REQUIRE(pi[k] < pj[k]);
          REQUIRE((pi[k] == a || pj[k] == a));
        }
        hits += static_cast<int>(m - 3);
      }
  CHECK(hits > 0);
  // The finder against all 40: the candidates on the cut-off are out, those a hair inside are in.
  std::vector<std::uint32_t> pi(n + 16), pj(n + 16);
  const std::size_t m = detail::scan_candidates(xs.data(), ys.data(), zs.data(), rs.data(), sorted.data(), 0, n, 7,
                                                xa, ra, pi.data(), pj.data(), 0);
  const auto end = pj.begin() + static_cast<long>(m);
  for (int s = 0; s < n; s += 5) CHECK((std::find(pj.begin(), end, sorted[s]) != end) == (s % 10 != 0));
}

TEST_CASE("neighbor: a pour's tall, mostly empty box keeps cells of 2 r_max + skin, its pairs those of brute force") {
  // A pile 10 x 10 x 2 cm of 20,000 spheres and a stream of 1,000 falling 40 cm above it, 1 cm wide: the box
  // holds ~19 cells of 2 r_max + skin per sphere. Cells grown for the empty box would make every finder
  // scan several times the candidates (chapter-7 test 1: 2.25x the cell, issue 19).
  std::vector<Vec3> x;
  std::vector<double> r;
  cloud(31, 20000, {0.1, 0.1, 0.02}, 1.0, x, r);
  Rng rng(32);
  for (int k = 0; k < 1000; ++k) {
    x.push_back({0.045 + 0.01 * rng.uniform(0, 1), 0.045 + 0.01 * rng.uniform(0, 1), rng.uniform(0.02, 0.42)});
    r.push_back(0.5e-3 * rng.uniform(1.0, 1.5));
  }
  const double skin = 0.4e-3;
  NeighborSearch search;
  CandidatePairs pairs;
  search.build(x, r, skin, pairs, 1);
  REQUIRE(search.levels().size() == 1);
  const auto& level = search.levels()[0];
  CHECK(level.cell == doctest::Approx(2.0 * level.rmax + skin).epsilon(1e-12));
  const double cells = static_cast<double>(level.dim[0]) * level.dim[1] * level.dim[2];
  CHECK(cells > 8.0 * x.size());  // the case this test is for: a sparse box
  CHECK(as_set(pairs) == as_set(brute_force_pairs(x, r, skin)));  // the pairs of the O(N^2) search
}

// One size level (radii within a factor 2) computes the cells in a loop of its own (model/neighbor.cpp): every
// particle lands in the cell clamp_cell gives, ascending index inside a cell (the order the scan's pairs follow),
// the particles on the box's far faces in the last cells and a NaN coordinate in the first cell of its axis,
// as clamp_cell puts it.
TEST_CASE("neighbor: one level's cells are clamp_cell's, a NaN coordinate in the first cell of its axis") {
  std::vector<Vec3> x;
  std::vector<double> r;
  cloud(13, 2000, {0.05, 0.03, 0.02}, 1.0, x, r);
  x[7] = {0.05, 0.03, 0.02};  // the far corner
  x[11] = {NAN, 0.01, 0.01};
  NeighborSearch search;
  CandidatePairs out;
  search.build(x, r, 0.4e-3, out, 1);
  REQUIRE(search.levels().size() == 1);
  const NeighborSearch::Level& L = search.levels()[0];
  // The box's lower corner as the search takes it (the positions' minimum; NaN is skipped by std::min).
  Vec3 lo = x[0];
  for (const Vec3& q : x) lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
  std::vector<std::pair<std::size_t, std::uint32_t>> expected;  // (cell, particle)
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Vec3 rel = x[k] - lo;
    const long cx = std::isnan(rel.x) ? 0 : L.clamp_cell(rel.x, 0);
    expected.emplace_back(L.index(cx, L.clamp_cell(rel.y, 1), L.clamp_cell(rel.z, 2)), static_cast<std::uint32_t>(k));
  }
  std::sort(expected.begin(), expected.end());
  REQUIRE(L.sorted.size() == x.size());
  for (std::size_t s = 0; s < x.size(); ++s) {
    CAPTURE(s);
    REQUIRE(L.sorted[s] == expected[s].second);
    REQUIRE(L.start[expected[s].first] <= s);
    REQUIRE(s < L.start[expected[s].first + 1]);
  }
}
