// SPDX-License-Identifier: MIT
// PairList::partition (model/contacts_partition.cpp): the threads' shares of the cost, index slabs as index
// ranges, and lists that hold every pair once per thread that needs it.
#include "model/contacts.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "model/neighbor.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

// n spheres of 1 mm radius uniform in a 10 x 3 x 2 cm box, in no spatial order, into p; their pair list
// (skin 0.5 mm).
PairList cloud_list(std::uint64_t seed, int n, Particles& p) {
  Rng rng(seed);
  for (int k = 0; k < n; ++k)
    p.add(0, 1e-3, 2760, {rng.uniform(0, 0.1), rng.uniform(0, 0.03), rng.uniform(0, 0.02)}, {}, {});
  CandidatePairs c = build_pairs(p.x, p.radius, 5e-4);
  PairList L;
  L.rebuild(c, p, 1, 1);
  return L;
}

}  // namespace

TEST_CASE("contacts: the partition gives each thread its share of the cost") {
  Rng rng(4);
  Particles p;
  for (int k = 0; k < 2000; ++k)
    p.add(0, 1e-3, 2760, {rng.uniform(0, 0.1), rng.uniform(0, 0.03), rng.uniform(0, 0.02)}, {}, {});
  NeighborSearch search;
  CandidatePairs c;
  search.build(p.x, p.radius, 5e-4, c, 1);
  PairList L;
  L.rebuild(c, p, 1, 1);
  for (const std::vector<double>& share : {std::vector<double>{0.5, 0.5}, {0.2, 0.8}, {0.1, 0.3, 0.6}}) {
    // With the search's bounding box of the same positions (as the rebuild passes it): the same partition.
    PairList B = L;
    B.partition(static_cast<int>(share.size()), p.x, nullptr, &share, &search.box());
    L.partition(static_cast<int>(share.size()), p.x, nullptr, &share);
    CHECK(B.owner == L.owner);
    CHECK(B.mine == L.mine);
    CHECK(B.work == L.work);
    double total = 0.0;
    for (double w : L.work) total += w;
    for (std::size_t t = 0; t < share.size(); ++t) {
      CAPTURE(t);
      CHECK(L.work[t] / total == doctest::Approx(share[t]).epsilon(0.02));
      CHECK(!L.own[t].empty());
    }
  }
}

// Slabs::index (a store in spatial order): each thread owns one range of the dense index, the ranges in
// thread order, each with its share of the cost, whatever the positions (here in no order at all, where
// Slabs::space would interleave the owners along the index).
TEST_CASE("contacts: index slabs are index ranges, each with its share of the cost") {
  Particles p;
  PairList L = cloud_list(5, 2000, p);
  L.slabs = PairList::Slabs::index;
  for (const std::vector<double>& share : {std::vector<double>{0.5, 0.5}, {0.2, 0.8}, {0.1, 0.3, 0.6}}) {
    L.partition(static_cast<int>(share.size()), p.x, nullptr, &share);
    double total = 0.0;
    for (double w : L.work) total += w;
    std::uint32_t next = 0;
    for (std::size_t t = 0; t < share.size(); ++t) {
      CAPTURE(t);
      REQUIRE(!L.own[t].empty());
      CHECK(L.own[t].front() == next);
      CHECK(L.own[t].back() - L.own[t].front() + 1 == L.own[t].size());
      next = L.own[t].back() + 1;
      CHECK(L.work[t] / total == doctest::Approx(share[t]).epsilon(0.02));
    }
    CHECK(next == p.size());
  }
}

// Whatever the slabs: thread t's list holds, ascending, every pair whose first particle it owns and every
// cross pair (owners differ) of a particle it owns, tagged kCrossBit; cross[k] names the cross slot of such a
// pair, cross_pairs the pair of each slot, and every particle of a cross pair has a ghost slot; each thread's
// particles are listed once, ascending, and every particle by its owner.
TEST_CASE("contacts: the threads' lists hold every pair where it is needed, once, in order") {
  Particles p;
  PairList L = cloud_list(6, 3000, p);
  REQUIRE(L.size() > 3000);
  for (PairList::Slabs slabs : {PairList::Slabs::space, PairList::Slabs::index})
    for (int threads : {2, 3}) {
      CAPTURE(threads);
      L.slabs = slabs;
      L.partition(threads, p.x);
      std::vector<std::vector<std::uint32_t>> expect(static_cast<std::size_t>(threads));
      std::size_t n_cross = 0;
      for (std::uint32_t k = 0; k < L.size(); ++k) {
        const int oi = L.owner[L.i[k]], oj = L.owner[L.j[k]];
        if (oi == oj) {
          expect[static_cast<std::size_t>(oi)].push_back(k);
          CHECK(L.cross[k] == PairList::kNone);
          continue;
        }
        expect[static_cast<std::size_t>(oi)].push_back(k | PairList::kCrossBit);
        expect[static_cast<std::size_t>(oj)].push_back(k | PairList::kCrossBit);
        REQUIRE(L.cross[k] < L.cross_pairs.size());
        CHECK(L.cross_pairs[L.cross[k]] == k);
        CHECK(L.ghost_of[L.i[k]] != PairList::kNone);
        CHECK(L.ghost_of[L.j[k]] != PairList::kNone);
        ++n_cross;
      }
      CHECK(n_cross > 0);
      CHECK(L.cross_pairs.size() == n_cross);
      std::size_t listed = 0;
      for (int t = 0; t < threads; ++t) {
        CAPTURE(t);
        CHECK(L.mine[static_cast<std::size_t>(t)] == expect[static_cast<std::size_t>(t)]);
        const auto& own = L.own[static_cast<std::size_t>(t)];
        CHECK(std::is_sorted(own.begin(), own.end()));
        for (std::uint32_t a : own) CHECK(L.owner[a] == t);
        listed += own.size();
      }
      CHECK(listed == p.size());
    }
}

// The segments of each thread's list (PairList::Segment) cover it in order, without gaps; a run is at least
// kMinRun consecutive pair indices without a cross pair; no run of kMinRun such entries is left inside a
// stretch that is not a run. With index slabs over a cloud in spatial order most of a list is runs.
TEST_CASE("contacts: a thread's list is cut into runs of consecutive own pairs and the stretches between") {
  // The cloud of cloud_list, its particles in order along the 10 cm side (as after the World's spatial sort,
  // whose slowest axis the index slabs cut across).
  Particles p;
  {
    Rng rng(7);
    std::vector<Vec3> x(3000);
    for (Vec3& q : x) q = {rng.uniform(0, 0.1), rng.uniform(0, 0.03), rng.uniform(0, 0.02)};
    std::sort(x.begin(), x.end(), [](const Vec3& a, const Vec3& b) { return a.x < b.x; });
    for (const Vec3& q : x) p.add(0, 1e-3, 2760, q, {}, {});
  }
  CandidatePairs c = build_pairs(p.x, p.radius, 5e-4);
  PairList L;
  L.rebuild(c, p, 1, 1);
  const auto longest_run = [](const std::vector<std::uint32_t>& ks, std::uint32_t q0, std::uint32_t q1) {
    std::uint32_t best = 0, len = 0;
    for (std::uint32_t q = q0; q < q1; ++q) {
      const bool plain = (ks[q] & PairList::kCrossBit) == 0;
      len = plain && len > 0 && ks[q] == ks[q - 1] + 1 ? len + 1 : (plain ? 1 : 0);
      best = std::max(best, len);
    }
    return best;
  };
  for (PairList::Slabs slabs : {PairList::Slabs::space, PairList::Slabs::index})
    for (int threads : {2, 3}) {
      CAPTURE(threads);
      L.slabs = slabs;
      L.partition(threads, p.x);
      REQUIRE(L.segments.size() == static_cast<std::size_t>(threads));
      std::size_t in_runs = 0, total = 0;
      for (int t = 0; t < threads; ++t) {
        CAPTURE(t);
        const auto& ks = L.mine[static_cast<std::size_t>(t)];
        std::uint32_t at = 0;
        for (const PairList::Segment& s : L.segments[static_cast<std::size_t>(t)]) {
          CHECK(s.q0 == at);
          CHECK(s.q1 > s.q0);
          at = s.q1;
          if (s.run) {
            CHECK(s.q1 - s.q0 >= PairList::kMinRun);
            CHECK(longest_run(ks, s.q0, s.q1) == s.q1 - s.q0);
            in_runs += s.q1 - s.q0;
          } else {
            CHECK(longest_run(ks, s.q0, s.q1) < PairList::kMinRun);
          }
        }
        CHECK(at == ks.size());
        total += ks.size();
      }
      MESSAGE((slabs == PairList::Slabs::index ? "index" : "space") << " slabs, " << threads << " threads: "
                                                                     << in_runs << " of " << total << " entries in runs");
      if (slabs == PairList::Slabs::index) CHECK(in_runs > total / 2);
    }
}
