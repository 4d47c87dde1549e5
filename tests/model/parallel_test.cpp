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
