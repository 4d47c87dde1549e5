// SPDX-License-Identifier: MIT
// The vCPU probe (issue 19, bench/README.md session 37): how fast each CPU this process may run on is right
// now, one at a time, pinned there. On this project's 2-vCPU VMs the two vCPUs are not alike and not steady:
// at 02:58 UTC on 2026-12-07 random reads over 8 MB took 0.074-0.096 s per 100 M on vCPU 0 and 0.157-0.287 s
// on vCPU 1 (up to 3.7x), a multiply-add loop 2.22 against 2.63 s; ten minutes later both read at 0.09-0.14 s. A
// 2-thread run always has a thread on the slower one, and a 1-thread run is as fast as the vCPU it lands on,
// so a timing means little without the state of the vCPUs beside it: bench/run.sh runs this probe before and
// after its runs and keeps what it prints.
//
// Per CPU, best of --reps trials each:
//   read   ns per random 8-byte read from a buffer of --mb MB (independent reads, an index list made by a
//          seeded LCG: the memory-level parallelism of the pair filter's loads of both spheres' state);
//   chase  ns per dependent read (a random cycle through the same buffer: the latency of one miss);
//   arith  ns per multiply and add in 8 independent chains (the arithmetic units, no memory).
// Then the slowest CPU's figure over the fastest's for each. Prints nothing random: the buffers' contents and
// orders are seeded, and the sums are printed so that no loop is optimised away.
//
// Usage: pastemix_vcpu_probe [--mb MB] [--reps R]   (defaults 8 MB, 3 trials)
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Makes v's value depend on everything before and matter to everything after: the compiler may not move the
// arithmetic on it across the clock reads (without this, GCC 12 moved the whole arith loop before them).
template <class T>
void pin_down(T& v) {
  asm volatile("" : "+m"(v) : : "memory");
}

// A 64-bit LCG (Knuth's MMIX constants): the same indices on every machine.
struct Lcg {
  std::uint64_t s;
  std::uint64_t next() { return s = s * 6364136223846793005ull + 1442695040888963407ull; }
};

struct Buffers {
  std::vector<double> data;          // read by `read`
  std::vector<std::uint32_t> index;  // `read`'s random indices
  std::vector<std::uint32_t> next;   // `chase`: one random cycle through every slot
};

Buffers make_buffers(std::size_t n) {
  Buffers b;
  b.data.resize(n);
  for (std::size_t k = 0; k < n; ++k) b.data[k] = 1.0 + static_cast<double>(k % 7);
  Lcg g{20261207};
  b.index.resize(1u << 20);
  for (auto& v : b.index) v = static_cast<std::uint32_t>((g.next() >> 33) % n);
  // Sattolo's shuffle: a single cycle, so the chase visits every slot before it repeats.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  for (std::size_t k = n - 1; k > 0; --k) std::swap(order[k], order[(g.next() >> 33) % k]);
  b.next.resize(n);
  for (std::size_t k = 0; k < n; ++k) b.next[order[k]] = order[(k + 1) % n];
  return b;
}

struct Rates {
  double read_ns = 1e300, chase_ns = 1e300, arith_ns = 1e300;
  double sum = 0.0;  // printed: keeps every loop's result alive
};

void trial(const Buffers& b, Rates& r) {
  constexpr int kPasses = 8;
  auto t0 = Clock::now();
  double acc = 0.0;
  for (int pass = 0; pass < kPasses; ++pass)
    for (std::uint32_t i : b.index) acc += b.data[i];
  r.read_ns = std::min(r.read_ns, seconds_since(t0) * 1e9 / (kPasses * static_cast<double>(b.index.size())));
  r.sum += acc;

  const std::size_t steps = std::min<std::size_t>(4u << 20, 4 * b.next.size());
  t0 = Clock::now();
  std::uint32_t at = 0;
  for (std::size_t k = 0; k < steps; ++k) at = b.next[at];
  r.chase_ns = std::min(r.chase_ns, seconds_since(t0) * 1e9 / static_cast<double>(steps));
  r.sum += at;

  constexpr long kIters = 20'000'000;
  double c[8];
  for (int l = 0; l < 8; ++l) c[l] = 1.0 + l * 1e-9;
  const double m = 0.999999999, a = 1e-9;
  t0 = Clock::now();
  pin_down(c);
  for (long k = 0; k < kIters; ++k)
    for (double& x : c) x = x * m + a;
  pin_down(c);
  r.arith_ns = std::min(r.arith_ns, seconds_since(t0) * 1e9 / (8.0 * kIters));
  for (double x : c) r.sum += x;
}

}  // namespace

int main(int argc, char** argv) {
  long mb = 8, reps = 3;
  if (argc % 2 == 0) {
    std::fprintf(stderr, "usage: pastemix_vcpu_probe [--mb MB] [--reps R]\n");
    return 2;
  }
  for (int k = 1; k + 1 < argc; k += 2) {
    const long v = std::atol(argv[k + 1]);
    if (std::strcmp(argv[k], "--mb") == 0) mb = v;
    else if (std::strcmp(argv[k], "--reps") == 0) reps = v;
    else {
      std::fprintf(stderr, "vcpu_probe: unknown option %s\n", argv[k]);
      return 2;
    }
  }
  if (mb < 1 || mb > 4096 || reps < 1) {
    std::fprintf(stderr, "vcpu_probe: --mb takes 1-4096, --reps a positive integer\n");
    return 2;
  }
  cpu_set_t allowed;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) {
    std::perror("vcpu_probe: sched_getaffinity");
    return 1;
  }
  const Buffers b = make_buffers(static_cast<std::size_t>(mb) * 1024 * 1024 / sizeof(double));
  std::vector<int> cpus;
  std::vector<Rates> rates;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &allowed)) continue;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    if (sched_setaffinity(0, sizeof one, &one) != 0) continue;
    Rates r;
    for (long t = 0; t < reps; ++t) trial(b, r);
    cpus.push_back(cpu), rates.push_back(r);
  }
  sched_setaffinity(0, sizeof allowed, &allowed);
  if (cpus.empty()) {
    std::fprintf(stderr, "vcpu_probe: could not run on any CPU\n");
    return 1;
  }
  for (std::size_t k = 0; k < cpus.size(); ++k)
    std::printf("vcpu %d: read %.3f ns, chase %.2f ns, arith %.4f ns (%d MB, best of %ld; sum %.6g)\n", cpus[k],
                rates[k].read_ns, rates[k].chase_ns, rates[k].arith_ns, static_cast<int>(mb), reps, rates[k].sum);
  const auto spread = [&](double Rates::*f) {
    double lo = 1e300, hi = 0.0;
    for (const Rates& r : rates) lo = std::min(lo, r.*f), hi = std::max(hi, r.*f);
    return hi / lo;
  };
  std::printf("vcpu spread (slowest / fastest): read %.2fx, chase %.2fx, arith %.2fx\n", spread(&Rates::read_ns),
              spread(&Rates::chase_ns), spread(&Rates::arith_ns));
  return 0;
}
