// SPDX-License-Identifier: MIT
// A small roofline probe for the Hertz-Mindlin contact kernel (issue 19): how fast could a contact be on
// this CPU, and how close does the engine come?
//
// It measures, with the engine's own compiler flags (x86-64-v3 = AVX2, no FMA contraction, no trapping
// math), on 1 and on N threads:
//   1. the peak rate of independent double-precision adds and multiplies (4-wide AVX2 vectors),
//   2. the throughput of 4-wide square roots and divisions (the kernel needs 5 and 4 per contact),
//   3. the memory bandwidth (STREAM-style triad a = b + s c over arrays far larger than the caches),
//   4. HertzMindlin::force_batch itself on in-cache staged contacts (the vector kernel, no gather/scatter).
// From the operation counts of one contact (counted from the source of force_batch, below) it prints the
// compute roof (time per contact = the largest of adds+muls / rate, sqrt / rate, div / rate: the add, multiply
// and divide/sqrt units work in parallel, so no code can beat it), a no-overlap estimate (the sum of the
// three: what a kernel whose units never overlap reaches) and the memory roof for the bytes a contact streams
// from memory in the engine's pair pass. bench/README.md compares the
// engine's measured contact rate on the bed scene with these.
//
// Usage: pastemix_roofline [--threads N] [--quick]
#include <immintrin.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "model/laws/hertz_mindlin.h"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Operations of one contact in HertzMindlin::force_batch, counted from its source (each line of the loop
// body; selects and compares are not counted as flops). Mixing the pair's parameters and gathering the
// particles (the staging) are not in it.
constexpr double kAddMulPerContact = 123.0;
constexpr double kSqrtPerContact = 5.0;  // |d|, sqrt(R* delta), sqrt(S_n m*), the spring rescale, |F_t|
constexpr double kDivPerContact = 4.0;   // 1/|d|, |xi|^2/|xi_t|^2, F_max/|F_t|, 1/S_t
// Bytes a contact streams in the pair pass that cannot stay in cache for a large pile: its two indices
// (2 x 4 B), the tangential spring read and written (2 x 24 B), and the partner's state (position,
// velocity, angular velocity 3 x 24 B, radius and inverse mass 2 x 8 B) once per contact. A lower bound on
// traffic for a pile that does not fit the caches; at 13k spheres everything fits in L2 and this roof
// does not bind.
constexpr double kBytesPerContact = 8.0 + 48.0 + 88.0;

using v4d = __m256d;

// Peak add+mul rate: 16 independent chains (8 adds, 8 multiplies) so latency never limits; flops/s.
double peak_addmul(int threads, double target_s) {
  double best = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : best)
  {
    v4d a[8], m[8];
    for (int k = 0; k < 8; ++k) a[k] = _mm256_set1_pd(1.0 + 1e-9 * k), m[k] = _mm256_set1_pd(1.0 - 1e-9 * k);
    const v4d inc = _mm256_set1_pd(1e-12), mul = _mm256_set1_pd(1.0 + 1e-15);
    long iters = 0;
    const auto t0 = Clock::now();
    double t = 0.0;
    do {
      for (int r = 0; r < 10000; ++r) {
        for (int k = 0; k < 8; ++k) a[k] = _mm256_add_pd(a[k], inc), m[k] = _mm256_mul_pd(m[k], mul);
      }
      iters += 10000;
      t = seconds_since(t0);
    } while (t < target_s);
    double sink = 0.0;
    for (int k = 0; k < 8; ++k) sink += a[k][0] + m[k][0];
    if (sink == 42.0) std::puts("");  // keeps the chains alive
    best = double(iters) * 16.0 * 4.0 / t;  // 16 vector ops of 4 doubles per iteration
  }
  return best;
}

// Throughput of 4-wide sqrt (div = false) or division (div = true): results/s summed over threads.
double peak_sqrt_div(int threads, bool div, double target_s) {
  double total = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : total)
  {
    v4d x[8];
    for (int k = 0; k < 8; ++k) x[k] = _mm256_set1_pd(2.0 + k);
    const v4d one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0);
    long iters = 0;
    const auto t0 = Clock::now();
    double t = 0.0;
    do {
      for (int r = 0; r < 2000; ++r) {
        // x -> sqrt(x) + 1 or 2 / x + 1 stays in [1, 3]: no denormals, no overflow.
        for (int k = 0; k < 8; ++k)
          x[k] = div ? _mm256_add_pd(_mm256_div_pd(two, x[k]), one) : _mm256_add_pd(_mm256_sqrt_pd(x[k]), one);
      }
      iters += 2000;
      t = seconds_since(t0);
    } while (t < target_s);
    double sink = 0.0;
    for (int k = 0; k < 8; ++k) sink += x[k][0];
    if (sink == 42.0) std::puts("");
    total = double(iters) * 8.0 * 4.0 / t;
  }
  return total;
}

// Triad a = b + s c over 3 arrays of n doubles, best of reps; bytes/s counting 3 x 8 B per element (the
// write-allocate read of a not counted, as STREAM does).
double triad_bandwidth(int threads, std::size_t n, int reps) {
  std::vector<double> a(n), b(n), c(n);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (long i = 0; i < long(n); ++i) a[i] = 0.0, b[i] = 1.0 + 1e-9 * double(i % 7), c[i] = 2.0;
  double best = 1e30;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    const double s = 1.0 + 1e-6 * r;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long i = 0; i < long(n); ++i) a[i] = b[i] + s * c[i];
    best = std::min(best, seconds_since(t0));
  }
  if (a[n / 2] == 42.0) std::puts("");
  return 3.0 * 8.0 * double(n) / best;
}

// force_batch on full batches of touching contacts staged once (in L1/L2): contacts/s per thread summed.
double kernel_rate(int threads, double target_s) {
  using HM = pastemix::model::HertzMindlin;
  double total = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : total)
  {
    constexpr int kBatches = 16;  // 16 x 64 contacts: ~260 kB, in L2
    std::vector<HM::Batch> batches(kBatches);
    std::mt19937_64 rng(20261201 + omp_get_thread_num());
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (auto& b : batches) {
      for (int q = 0; q < HM::kBatch; ++q) {
        // Spheres of 1.25-2.5 mm radius at 0-20 um overlap, moving at up to 0.5 m/s, spinning at up to
        // 50 rad/s, with a spring of up to 1 um: a settled bed's contacts.
        const double ra = 1.875e-3 + 0.625e-3 * u(rng), rb = 1.875e-3 + 0.625e-3 * u(rng);
        const double dist = ra + rb - 1e-5 * (1.0 + u(rng));
        double dx = u(rng), dy = u(rng), dz = u(rng);
        const double len = std::sqrt(dx * dx + dy * dy + dz * dz) + 1e-12;
        dx *= dist / len, dy *= dist / len, dz *= dist / len;
        b.dx[q] = dx, b.dy[q] = dy, b.dz[q] = dz, b.dist2[q] = dx * dx + dy * dy + dz * dz;
        b.rsum[q] = ra + rb, b.ra[q] = ra, b.rb[q] = rb, b.r_star[q] = ra * rb / (ra + rb);
        b.m_star[q] = 2760.0 * 4.18879 * ra * ra * ra / 2.0;
        b.E_star[q] = 2.4e7, b.G_star[q] = 1.0e7, b.damping[q] = 0.14, b.sqrt_st_over_sn[q] = 1.29,
        b.friction[q] = 0.466;
        b.vax[q] = 0.5 * u(rng), b.vay[q] = 0.5 * u(rng), b.vaz[q] = 0.5 * u(rng);
        b.vbx[q] = 0.5 * u(rng), b.vby[q] = 0.5 * u(rng), b.vbz[q] = 0.5 * u(rng);
        b.wax[q] = 50 * u(rng), b.way[q] = 50 * u(rng), b.waz[q] = 50 * u(rng);
        b.wbx[q] = 50 * u(rng), b.wby[q] = 50 * u(rng), b.wbz[q] = 50 * u(rng);
        b.hx[q] = 1e-6 * u(rng), b.hy[q] = 1e-6 * u(rng), b.hz[q] = 1e-6 * u(rng);
      }
    }
    long contacts = 0;
    const auto t0 = Clock::now();
    double t = 0.0;
    do {
      for (int r = 0; r < 100; ++r)
        for (auto& b : batches) HM::force_batch(b, HM::kBatch, 1e-5);
      contacts += 100L * kBatches * HM::kBatch;
      t = seconds_since(t0);
    } while (t < target_s);
    double sink = 0.0;
    for (auto& b : batches) sink += b.fx[0];
    if (sink == 42.0) std::puts("");
    total = double(contacts) / t;
  }
  return total;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 2;
  bool quick = false;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--threads") && k + 1 < argc) threads = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--quick")) quick = true;
    else {
      std::fprintf(stderr, "usage: pastemix_roofline [--threads N] [--quick]\n");
      return 2;
    }
  }
  if (threads < 1) threads = 1;
  const double t_probe = quick ? 0.2 : 1.0;  // s per compute probe
  const std::size_t n_triad = quick ? (std::size_t(1) << 24) : (std::size_t(1) << 26);  // 3 x 128/512 MB
  std::printf("roofline probe: AVX2 (4 doubles), no FMA contraction (the engine's flags); %s\n",
              quick ? "quick" : "full");
  std::printf("per contact (force_batch, counted from its source): %.0f adds+muls, %.0f sqrt, %.0f div; "
              "%.0f B streamed in the pair pass\n", kAddMulPerContact, kSqrtPerContact, kDivPerContact,
              kBytesPerContact);
  std::printf("%8s %12s %12s %12s %12s %14s %14s %14s %14s\n", "threads", "add+mul G/s", "sqrt G/s",
              "div G/s", "triad GB/s", "compute roof", "no overlap", "memory roof", "force_batch");
  for (int t = 1; t <= threads; ++t) {
    const double am = peak_addmul(t, t_probe), sq = peak_sqrt_div(t, false, t_probe),
                 dv = peak_sqrt_div(t, true, t_probe), bw = triad_bandwidth(t, n_triad, quick ? 3 : 5),
                 kr = kernel_rate(t, t_probe);
    const double t_am = kAddMulPerContact / am, t_sq = kSqrtPerContact / sq, t_dv = kDivPerContact / dv;
    const double roof = 1.0 / std::max({t_am, t_sq, t_dv}), serial = 1.0 / (t_am + t_sq + t_dv);
    const double mem_roof = bw / kBytesPerContact;
    std::printf("%8d %12.2f %12.3f %12.3f %12.2f %11.1f M/s %11.1f M/s %11.1f M/s %11.1f M/s\n", t,
                am * 1e-9, sq * 1e-9, dv * 1e-9, bw * 1e-9, roof * 1e-6, serial * 1e-6, mem_roof * 1e-6,
                kr * 1e-6);
  }
  std::printf("contacts per second: compute roof = the slowest unit alone, max(adds+muls/rate, sqrt/rate, "
              "div/rate); no overlap = 1 / (their sum); memory roof = triad bandwidth / bytes per contact; "
              "force_batch = the kernel alone on staged in-cache contacts\n");
  return 0;
}
