// SPDX-License-Identifier: MIT
// When to run a loop in parallel. Below a few hundred items an OpenMP fork/join costs more than the loop
// (and on a loaded machine a barrier can wait for a descheduled thread), so small loops stay serial. The
// threshold belongs to the World (WorldConfig::parallel_min_items; tests set 0 to exercise the parallel
// paths on small scenes), which hands each list build its thread count. The result does not depend on it:
// every loop writes outputs indexed by its own variable only.
#pragma once

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <thread>

#include <omp.h>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace pastemix::model {

// Loops with fewer items than this run on one thread (the default of WorldConfig::parallel_min_items).
inline constexpr long kParallelMinItems = 512;

// The threads for a loop over n items: one below min_items, else OpenMP's maximum.
inline int threads_for(long n, long min_items) { return n >= min_items ? omp_get_max_threads() : 1; }

// A barrier for the threads of one parallel region that waits by polling and yielding the core
// (sched_yield; after a 20 us spin) instead of sleeping: the way MPI ranks wait with mpi_yield_when_idle. On
// this project's 2-vCPU VMs a thread that sleeps in an OpenMP barrier (OMP_WAIT_POLICY=passive) takes tens of
// us to wake, at every step; a pure spin is as fast but starves another process sharing the core, while a
// yield hands the core over whenever something else is runnable. After kSleepAfter of waiting it sleeps in short
// naps, so a long wait (a thread descheduled for a while) does not burn a core.
class YieldBarrier {
 public:
  YieldBarrier() = default;
  // A copy or move (of the World that holds it, between runs: no thread is waiting) starts fresh.
  YieldBarrier(const YieldBarrier&) {}
  YieldBarrier& operator=(const YieldBarrier&) { return *this; }
  // Every one of `threads` threads calls wait(); none returns before all have called it. Writes before
  // wait() in any thread are visible after it in every thread (acquire/release on the counter and the
  // generation).
  void wait(int threads) {
    const unsigned g = gen_.load(std::memory_order_acquire);
    if (count_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads) {
      count_.store(0, std::memory_order_relaxed);
      gen_.store(g + 1, std::memory_order_release);
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    // First a short spin (kSpinFor): on this project's Firecracker VM each sched_yield is a system call through
    // the hypervisor (perf: pvm_irq_enable, 8 % of a 2-thread bed's samples), so a thread that yields at once
    // notices the last arrival up to a call later. Bench, 2 threads, interleaved (min of 4 and of 6 pairs): pour
    // 0.422 -> 0.407 and 0.660 -> 0.592 s, bed 0.669 -> 0.661 and 0.843 -> 0.792 s; chapter-7 test 1 segment
    // unchanged (3 pairs).
    for (int k = 0; gen_.load(std::memory_order_acquire) == g; ++k) {
#if defined(__x86_64__) || defined(__i386__)
      _mm_pause();
#endif
      if ((k & 63) == 63 && std::chrono::steady_clock::now() - start >= kSpinFor) break;
    }
    for (int k = 0; gen_.load(std::memory_order_acquire) == g; ++k) {
      if ((k & 63) != 63 || std::chrono::steady_clock::now() - start < kSleepAfter)
        sched_yield();
      else
        std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
  }

 private:
  static constexpr std::chrono::milliseconds kSleepAfter{2};
  static constexpr std::chrono::microseconds kSpinFor{20};
  alignas(64) std::atomic<int> count_{0};
  alignas(64) std::atomic<unsigned> gen_{0};
};

// One thread's view of a team that runs a multi-phase job inside one parallel region (the neighbour
// rebuild: search, pair list, wall lists), its phases separated by sync() on a YieldBarrier instead of
// libgomp regions and barriers (each of which sleeps and wakes under OMP_WAIT_POLICY=passive, issue 19).
// A one-thread team never waits.
struct Team {
  int me = 0;
  int size = 1;
  YieldBarrier* barrier = nullptr;
  void sync() const {
    if (size > 1) barrier->wait(size);
  }
  // This thread's share [lo, hi) of n items: contiguous, in thread order (as OpenMP's static schedule).
  void range(long n, long& lo, long& hi) const {
    const long per = n / size, extra = n % size;
    lo = me * per + std::min<long>(me, extra);
    hi = lo + per + (me < extra ? 1 : 0);
  }
};

// Work items 0 .. n-1 shared by a team, each thread starting on its own contiguous range (Team::range)
// from the front and, once that is done, taking items from the back of the other threads' ranges. So a
// thread works on neighbouring items (the neighbour search's chunks: neighbouring particles, whose cells
// stay in its cache) and a slower thread's remainder is taken over. Why (issue 19): the chunks dealt
// round-robin made both threads read every region of the grid, and the 2-thread pour's search took 38 %
// more CPU time than on one thread, with one thread waiting at the end. Which thread takes an item never
// changes its result (each item has its own output).
class WorkQueue {
 public:
  // Before the team starts taking (one thread, then a sync).
  void reset(long n, int threads) {
    if (threads_ != threads) ranges_.reset(new Range[static_cast<std::size_t>(threads)]), threads_ = threads;
    for (int t = 0; t < threads; ++t) {
      long lo = 0, hi = 0;
      Team{t, threads, nullptr}.range(n, lo, hi);
      ranges_[static_cast<std::size_t>(t)].state.store(pack(lo, hi), std::memory_order_relaxed);
    }
  }
  // The next item for thread me, or -1 when every item is taken.
  long next(int me) {
    if (const long k = take(me, true); k >= 0) return k;
    for (int d = 1; d < threads_; ++d)
      if (const long k = take((me + d) % threads_, false); k >= 0) return k;
    return -1;
  }

 private:
  struct alignas(64) Range {
    std::atomic<std::uint64_t> state{0};  // front (low 32 bits) and back (high 32 bits): items [front, back)
  };
  static std::uint64_t pack(long front, long back) {
    return static_cast<std::uint64_t>(front) | (static_cast<std::uint64_t>(back) << 32);
  }
  // An item of range t, from its front (its owner) or its back (another thread): -1 if it is empty.
  long take(int t, bool front) {
    std::atomic<std::uint64_t>& st = ranges_[static_cast<std::size_t>(t)].state;
    std::uint64_t s = st.load(std::memory_order_relaxed);
    for (;;) {
      const long f = static_cast<long>(s & 0xffffffffu), b = static_cast<long>(s >> 32);
      if (f >= b) return -1;
      const std::uint64_t next = front ? pack(f + 1, b) : pack(f, b - 1);
      if (st.compare_exchange_weak(s, next, std::memory_order_acq_rel, std::memory_order_relaxed))
        return front ? f : b - 1;
    }
  }
  std::unique_ptr<Range[]> ranges_;
  int threads_ = 0;
};

// Runs job(team) on `threads` threads in one parallel region (the whole team waits on `barrier`).
template <class Job>
void run_team(int threads, YieldBarrier& barrier, Job&& job) {
  if (threads <= 1) {
    job(Team{});
    return;
  }
#pragma omp parallel num_threads(threads)
  job(Team{omp_get_thread_num(), omp_get_num_threads(), &barrier});
}

}  // namespace pastemix::model
