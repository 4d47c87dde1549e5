// SPDX-License-Identifier: MIT
// The gather probe (issue 19, bench/README.md session 32): what the pair filter's loads of both spheres'
// positions cost per candidate pair, as 8-lane AVX-512 gathers (six per eight pairs: x, y, z of i and of j)
// and as model/pair_filter.h's load_rows8 (eight masked row loads and a transpose per sphere side), and one
// double per sphere (the radii) by two gathers or by load8_pd. The list is a chapter-7-like one: n spheres in
// index order, 3.8 candidates per sphere (Poisson), partners a few hundred indices on (|normal| n / 40); the
// positions uniform in a unit box. Each form's touching count is printed: both must agree (the same values).
//
// Usage: pastemix_gather_probe [--n N] [--reps R]   (defaults 65000 spheres, 200 passes; three trials each)
#include <immintrin.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "model/pair_filter.h"

namespace {

using Clock = std::chrono::steady_clock;
using pastemix::model::load8_pd;
using pastemix::model::load_rows8;

__m512d gather(__m256i at, const double* base) {
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xff, at, base, 8);
}
__m256i times3(__m256i i) { return _mm256_add_epi32(i, _mm256_slli_epi32(i, 1)); }

struct List {
  std::vector<double> x, r;  // 3 n positions, n radii
  std::vector<std::uint32_t> i, j;
};

List make_list(long n) {
  std::mt19937 g(20261206);
  List L;
  L.x.resize(3 * static_cast<std::size_t>(n));
  L.r.resize(static_cast<std::size_t>(n));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double& v : L.x) v = u(g);
  for (double& v : L.r) v = 0.05 + 0.05 * u(g);
  std::poisson_distribution<int> count(3.8);
  std::normal_distribution<double> reach(0.0, static_cast<double>(n) / 40.0);
  for (long a = 0; a < n; ++a)
    for (int c = count(g); c > 0; --c) {
      const long b = std::min(n - 1, a + 1 + static_cast<long>(std::fabs(reach(g))));
      L.i.push_back(static_cast<std::uint32_t>(a));
      L.j.push_back(static_cast<std::uint32_t>(b));
    }
  const std::size_t m = L.i.size() / 8 * 8;
  L.i.resize(m), L.j.resize(m);
  return L;
}

// Touching pairs of the list (|x_j - x_i| < r_i + r_j), the spheres' state loaded by `form`: 0 gathers, 1 loads.
long pass(const List& L, int form) {
  long hits = 0;
  const double* X = L.x.data();
  const double* R = L.r.data();
  for (std::size_t q = 0; q < L.i.size(); q += 8) {
    __m512d ax, ay, az, bx, by, bz, ra, rb;
    if (form == 0) {
      const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(L.i.data() + q));
      const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(L.j.data() + q));
      const __m256i a3 = times3(a), b3 = times3(b);
      ax = gather(a3, X), ay = gather(a3, X + 1), az = gather(a3, X + 2);
      bx = gather(b3, X), by = gather(b3, X + 1), bz = gather(b3, X + 2);
      ra = gather(a, R), rb = gather(b, R);
    } else {
      load_rows8(X, L.i.data() + q, ax, ay, az);
      load_rows8(X, L.j.data() + q, bx, by, bz);
      ra = load8_pd(R, L.i.data() + q), rb = load8_pd(R, L.j.data() + q);
    }
    const __m512d dx = _mm512_sub_pd(bx, ax), dy = _mm512_sub_pd(by, ay), dz = _mm512_sub_pd(bz, az);
    const __m512d d2 =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
    const __m512d rs = _mm512_add_pd(ra, rb);
    hits += __builtin_popcount(_mm512_cmp_pd_mask(d2, _mm512_mul_pd(rs, rs), _CMP_LT_OQ));
  }
  return hits;
}

}  // namespace

int main(int argc, char** argv) {
  long n = 65000;
  int reps = 200;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (std::strcmp(argv[k], "--n") == 0) n = std::atol(argv[k + 1]);
    else if (std::strcmp(argv[k], "--reps") == 0) reps = std::atoi(argv[k + 1]);
    else {
      std::fprintf(stderr, "usage: pastemix_gather_probe [--n N] [--reps R]\n");
      return 2;
    }
  }
  if (n < 16 || reps < 1) {
    std::fprintf(stderr, "pastemix_gather_probe: --n must be >= 16 and --reps >= 1\n");
    return 2;
  }
  const List L = make_list(n);
  const auto pairs = static_cast<double>(L.i.size());
  std::printf("%ld spheres, %.0f candidate pairs (%.2f per sphere), %d passes per trial\n", n, pairs,
              pairs / static_cast<double>(n), reps);
  const char* names[2] = {"gathers (6 + 2 per 8 pairs)", "rows8 + load8_pd"};
  double best[2] = {1e300, 1e300};
  long hits[2] = {0, 0};
  for (int trial = 0; trial < 3; ++trial)
    for (int form = 0; form < 2; ++form) {  // interleaved: the machine's state drifts
      const auto t0 = Clock::now();
      long h = 0;
      for (int r = 0; r < reps; ++r) h += pass(L, form);
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      best[form] = std::min(best[form], s / reps / pairs * 1e9);
      hits[form] = h;
    }
  for (int form = 0; form < 2; ++form)
    std::printf("%-28s %.3f ns per pair (best of 3), %ld touching\n", names[form], best[form], hits[form]);
  std::printf("ratio loads / gathers: %.3f\n", best[1] / best[0]);
  return hits[0] == hits[1] ? 0 : 1;
}
