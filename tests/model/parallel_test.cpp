// SPDX-License-Identifier: MIT
#include "model/parallel.h"

#include <doctest/doctest.h>

#include <atomic>
#include <thread>
#include <vector>

using namespace pastemix::model;

TEST_CASE("parallel: no thread leaves the yield barrier before every thread has reached it") {
  // Each round, every thread writes the round number into its slot (a plain write: the barrier must make
  // it visible), waits, checks every slot, waits again (nobody may overwrite a slot still being read).
  for (int threads : {2, 3, 4}) {
    CAPTURE(threads);
    YieldBarrier barrier;
    std::vector<int> slot(static_cast<std::size_t>(threads), -1);
    std::atomic<int> wrong{0};
    constexpr int kRounds = 2000;
    std::vector<std::thread> team;
    for (int t = 0; t < threads; ++t)
      team.emplace_back([&, t] {
        for (int r = 0; r < kRounds; ++r) {
          slot[static_cast<std::size_t>(t)] = r;
          barrier.wait(threads);
          for (int u = 0; u < threads; ++u)
            if (slot[static_cast<std::size_t>(u)] != r) wrong.fetch_add(1);
          barrier.wait(threads);
        }
      });
    for (auto& th : team) th.join();
    CHECK(wrong.load() == 0);
  }
}

TEST_CASE("parallel: one thread passes the yield barrier at once, and a late thread is waited for") {
  YieldBarrier barrier;
  barrier.wait(1);  // returns
  // A thread that arrives 5 ms late (past the barrier's switch from yielding to naps) is still waited for.
  std::atomic<bool> late_done{false};
  std::thread late([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    late_done = true;
    barrier.wait(2);
  });
  barrier.wait(2);
  CHECK(late_done.load());
  late.join();
}

// A team's shares must cover every item once, in thread order, as even as possible: the rebuild's loops
// (search bounding box, pair list, wall lists) each write outputs indexed by the item only.
TEST_CASE("parallel: a team's ranges cover the items once, contiguous and in thread order") {
  for (int size : {1, 2, 3, 7})
    for (long n : {0L, 1L, 5L, 64L, 1001L}) {
      long next = 0;
      for (int me = 0; me < size; ++me) {
        long lo = -1, hi = -1;
        Team{me, size, nullptr}.range(n, lo, hi);
        CHECK(lo == next);
        CHECK(hi >= lo);
        CHECK(hi - lo <= n / size + 1);
        CHECK(hi - lo >= n / size);
        next = hi;
      }
      CHECK(next == n);
    }
}

// run_team: every thread of the region runs the job with its own rank, and sync() holds each phase until
// all have finished the one before (the rebuild's phases read what other threads wrote).
TEST_CASE("parallel: run_team gives each thread its rank and its syncs separate the phases") {
  for (int threads : {1, 2, 3}) {
    YieldBarrier barrier;
    std::vector<int> seen(8, 0), phase(8, -1);
    std::atomic<int> wrong{0}, size_seen{0};
    run_team(threads, barrier, [&](const Team& t) {
      size_seen = t.size;
      for (int p = 0; p < 200; ++p) {
        phase[static_cast<std::size_t>(t.me)] = p;
        t.sync();
        for (int u = 0; u < t.size; ++u)
          if (phase[static_cast<std::size_t>(u)] != p) wrong.fetch_add(1);
        t.sync();
      }
      ++seen[static_cast<std::size_t>(t.me)];
    });
    CHECK(wrong.load() == 0);
    for (int me = 0; me < size_seen.load(); ++me) CHECK(seen[static_cast<std::size_t>(me)] == 1);
    CHECK(size_seen.load() >= 1);
    CHECK(size_seen.load() <= threads);
  }
}

TEST_CASE("parallel: the work queue gives each item once, own range first, then the others' from the back") {
  // One thread at a time (a fixed interleaving): thread 0 alone takes its range 0 .. 4 in order, then thread
  // 1's from the back (9, 8, ...) while thread 1 takes its own from the front (5, 6, ...).
  WorkQueue q;
  q.reset(10, 2);
  std::vector<long> got0, got1;
  for (int k = 0; k < 5; ++k) got0.push_back(q.next(0));
  CHECK(got0 == std::vector<long>{0, 1, 2, 3, 4});
  got1.push_back(q.next(1));
  got0.push_back(q.next(0));
  got0.push_back(q.next(0));
  got1.push_back(q.next(1));
  got1.push_back(q.next(1));
  CHECK(got1 == std::vector<long>{5, 6, 7});
  CHECK(got0 == std::vector<long>{0, 1, 2, 3, 4, 9, 8});
  CHECK(q.next(0) == -1);
  CHECK(q.next(1) == -1);
  // Reused with another count and team; an empty queue; one thread takes everything in order.
  q.reset(0, 3);
  CHECK(q.next(2) == -1);
  q.reset(4, 1);
  for (long k = 0; k < 4; ++k) CHECK(q.next(0) == k);
  CHECK(q.next(0) == -1);
  // Real threads, one of them slowed: every item exactly once.
  for (int threads : {2, 3, 4}) {
    CAPTURE(threads);
    constexpr long kItems = 5000;
    q.reset(kItems, threads);
    std::vector<std::atomic<int>> seen(kItems);
    std::vector<std::thread> team;
    for (int t = 0; t < threads; ++t)
      team.emplace_back([&, t] {
        for (long k = q.next(t); k >= 0; k = q.next(t)) {
          seen[static_cast<std::size_t>(k)].fetch_add(1);
          if (t == 0) std::this_thread::yield();
        }
      });
    for (auto& th : team) th.join();
    long once = 0;
    for (const auto& s : seen) once += s.load() == 1;
    CHECK(once == kItems);
  }
}
