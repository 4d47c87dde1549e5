// SPDX-License-Identifier: MIT
// The pair pass's filter and staging (model/contacts.cpp). The filter finds which candidate pairs of a chunk
// touch: it keeps each touching pair's list entry, separation x_j - x_i (m), squared distance (m^2) and
// R_i + R_j (m) in pair order, sets the pairs' touching flags and zeroes the springs of the contacts that
// just opened. stage8 loads eight touching pairs' state into a batch kernel's lanes. With AVX-512 both take
// eight pairs at a time (the spheres' state by loads and a transpose, rows8; one compare, compressed stores);
// one at a time, the filter was about half of the pair pass's samples in chapter-7 test 1 (perf, 2 threads;
// three candidates in four do not touch) and the loads of both spheres' radii, velocities and spins a third of
// the settled bed's. Interleaved A/B against the one-at-a-time build (issue 19, bench/README.md): bench bed, 1
// thread, contact stage 1.53 -> 1.16 s; with gathers replaced by loads (rows8, load8_pd, session 32) 0.78 s.
// Both forms give the same bits: the same subtractions, squares and sums per pair, the same entries in the same
// order (tests/model/pair_filter_test.cpp, scripts/bitwise_check.sh).
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/contacts.h"
#include "model/simd_avx2.h"

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

namespace pastemix::model {

// Where a group of W pairs has cross pairs (lanes cm): those lanes read both particles' state from the ghost
// copies of buffer `cur` (PairList::Ghost: x, v, w, nine doubles), the others from the store. The lanes'
// addresses, shared by the eight-lane (Ghosts) and four-lane (Ghosts4) loads.
template <int W>
struct GhostLanes {
  static_assert(sizeof(PairList::Ghost) == 9 * sizeof(double));
  const double* G;
  unsigned cm;
  const std::uint32_t *a, *b;  // the lanes' i and j
  std::uint32_t ga[W], gb[W];  // 9 x ghost slot of the lanes' i and j (cross lanes only)
  GhostLanes(const PairList& L, int cur, unsigned cross_lanes, const std::uint32_t* ia, const std::uint32_t* ib)
      : G(reinterpret_cast<const double*>(L.ghost[cur].data())), cm(cross_lanes), a(ia), b(ib) {
    for (int l = 0; l < W; ++l) {
      const bool cross = (cm >> l) & 1u;
      ga[l] = cross ? 9 * L.ghost_of[a[l]] : 0;
      gb[l] = cross ? 9 * L.ghost_of[b[l]] : 0;
    }
  }
  // Row l at `off` of the Ghost (0 x, 3 v, 6 w) of i (of_j false) or j in a cross lane, of the Vec3 array
  // `base` elsewhere.
  [[gnu::always_inline]] const double* row(bool of_j, const double* base, int off, int l) const {
    const std::uint32_t* id = of_j ? b : a;
    const std::uint32_t* g = of_j ? gb : ga;
    return ((cm >> l) & 1u) ? G + g[l] + off : base + 3 * static_cast<std::size_t>(id[l]);
  }
};

#if defined(__AVX512F__) && defined(__AVX512VL__)
// Eight rows of three doubles (row l at at(l): a Vec3 array's element, a ghost copy's x, v or w, a pair's
// spring) as one register per component: eight masked 256-bit loads (three lanes each, so never past a row's
// end) and a transpose. On this project's Zen 5 VM the loads and shuffles take about half the time of the
// gathers (bench/gather_probe, both spheres' positions and radii of a 65k-sphere list: 4.21 -> 1.82 ns per
// pair). Data movement only: the values three gathers would give.
// Always inlined, with its lambdas: called out of line (as GCC 12 chose once stage8's cross lanes used it too)
// its outputs went through memory, and the settled bed's contact stage was ~12 % slower.
template <class At>
[[gnu::always_inline]] inline void rows8(const At& at, __m512d& x, __m512d& y, __m512d& z) {
  const auto two = [&](int l) __attribute__((always_inline)) {
    return _mm512_maskz_insertf64x4(0xff, _mm512_maskz_loadu_pd(0x7, at(l)), _mm256_maskz_loadu_pd(0x7, at(l + 4)), 1);
  };
  // t_l = [row l | row l+4] (x y z 0 x y z 0); unpacks pair rows l and l+1 per 128-bit lane. (The maskz forms:
  // GCC 12's plain ones start from an undefined register and warn.)
  const __m512d t0 = two(0), t1 = two(1), t2 = two(2), t3 = two(3);
  const __m512d xz01 = _mm512_maskz_unpacklo_pd(0xff, t0, t1), y01 = _mm512_maskz_unpackhi_pd(0xff, t0, t1);
  const __m512d xz23 = _mm512_maskz_unpacklo_pd(0xff, t2, t3), y23 = _mm512_maskz_unpackhi_pd(0xff, t2, t3);
  const __m512i lo = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), hi = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  x = _mm512_permutex2var_pd(xz01, lo, xz23);
  y = _mm512_permutex2var_pd(y01, lo, y23);
  z = _mm512_permutex2var_pd(xz01, hi, xz23);
}
// Rows base + 3 id[l] (a Vec3 array, or a width-3 spring array).
[[gnu::always_inline]] inline void load_rows8(const double* base, const std::uint32_t* id, __m512d& x, __m512d& y,
                                              __m512d& z) {
  const auto at = [&](int l) __attribute__((always_inline)) { return base + 3 * static_cast<std::size_t>(id[l]); };
  rows8(at, x, y, z);
}
// Eight doubles base[id[l]] by scalar loads and inserts (a third less than one gather on the same probe).
[[gnu::always_inline]] inline __m512d load8_pd(const double* base, const std::uint32_t* id) {
  const auto two = [&](int l) __attribute__((always_inline)) {
    return _mm_loadh_pd(_mm_load_sd(base + id[l]), base + id[l + 1]);
  };
  const __m256d lo = _mm256_insertf128_pd(_mm256_castpd128_pd256(two(0)), two(2), 1);
  const __m256d hi = _mm256_insertf128_pd(_mm256_castpd128_pd256(two(4)), two(6), 1);
  return _mm512_maskz_insertf64x4(0xff, _mm512_castpd256_pd512(lo), hi, 1);
}

// A group of eight pairs' ghost rows (GhostLanes above).
struct Ghosts : GhostLanes<8> {
  using GhostLanes<8>::GhostLanes;
  // Component rows at `off` of the Ghost (0 x, 3 v, 6 w) of i (of_j false) or j in the cross lanes, the Vec3
  // array `base` elsewhere.
  [[gnu::always_inline]] void rows(bool of_j, const double* base, int off, __m512d& x, __m512d& y,
                                   __m512d& z) const {
    const auto at = [&](int l) __attribute__((always_inline)) { return row(of_j, base, off, l); };
    rows8(at, x, y, z);
  }
};
#elif defined(PASTEMIX_AVX2_LANES)
// Ghosts for a group of four pairs (AVX2): as Ghosts above, four lanes.
struct Ghosts4 : GhostLanes<4> {
  using GhostLanes<4>::GhostLanes;
  [[gnu::always_inline]] void rows(bool of_j, const double* base, int off, __m256d& x, __m256d& y,
                                   __m256d& z) const {
    const auto at = [&](int l) __attribute__((always_inline)) { return row(of_j, base, off, l); };
    avx2::rows4(at, x, y, z);
  }
};
#endif

// The separation vectors x_j - x_i (m) of a chunk's touching candidates, one array per axis (not
// Vec3[kChunk]: its zero-initialisation was a 6 kB memset per chunk, ~2 % of the bed).
template <long N>
struct Separations {
  double x[N], y[N], z[N];
};

// Entries of the chunk's touching pairs, in pair order (out), kept by PairFilter, with both particles of each
// (the filter has them in hand: the staging and the force sums then read them here, not from the pair list by
// index).
template <long N>
struct FilterOut {
  std::uint32_t idx[N];
  std::uint32_t ia[N], ib[N];
  Separations<N> sep;
  double sep2[N], rsums[N];
  long m = 0;
};

// Part = true: the entries are ks[q] (pair index, kCrossBit for a cross pair, whose positions come from the
// ghost copies and whose touching flag and spring only the owner of i writes); false: pair q itself.
template <bool Part>
struct PairFilter {
  const Particles& p;
  PairList& L;
  const std::uint32_t* ks;
  int me, cur;

  std::uint32_t entry(long q) const { return Part ? ks[q] : static_cast<std::uint32_t>(q); }

  // One candidate (the reference form).
  template <long N>
  void one(long q, FilterOut<N>& o) const {
    const std::uint32_t e = entry(q);
    const std::uint32_t k = e & ~PairList::kCrossBit;
    const std::uint32_t a = L.i[k], b = L.j[k];
    // A cross pair reads the other thread's particle from its ghost copy (that thread may already be
    // kicking and drifting the original).
    const bool cross_pair = Part && (e & PairList::kCrossBit) != 0;
    const Vec3 d = cross_pair ? L.state(b, cur).x - L.state(a, cur).x : p.x[b] - p.x[a];
    const double rsum = L.rsum[k];
    const double dist2 = norm2(d);
    const bool touch = !(dist2 >= rsum * rsum);
    const long m = o.m;
    o.idx[m] = e;
    o.ia[m] = a, o.ib[m] = b;
    o.sep.x[m] = d.x, o.sep.y[m] = d.y, o.sep.z[m] = d.z;
    o.sep2[m] = dist2;
    o.rsums[m] = rsum;
    o.m = m + touch;
    // Not touching: forget the springs (a new contact starts from zero displacement). Branch only on the
    // rare contact that just opened; "touching?" itself is unpredictable.
    const std::size_t ws = static_cast<std::size_t>(L.width);
    if (cross_pair) {
      if (L.owner[a] == me) {
        if (!touch) std::fill_n(&L.cross_hist[cur ^ 1][L.cross[k] * ws], L.width, 0.0);
        L.touching[k] = touch;
      }
    } else {
      // One branch, on "just opened" (was touching, is not): rare and predictable. Written as `!touch &&
      // touching[k]`, the compiler branched on `touch` first, a mispredicted branch on ~40 % of a settled
      // bed's candidates (issue 19).
      const std::uint32_t was = L.touching[k];
      L.touching[k] = touch;
      if ((was & static_cast<std::uint32_t>(!touch)) != 0) std::fill_n(&L.history[k * ws], L.width, 0.0);
    }
  }

  // The touching flags and springs of a group's cross pairs (lanes cm; pair k, first particle a), as one()
  // sets them: by the owner of i only.
  void cross_flags(unsigned cm, unsigned touch, const std::uint32_t* k8, const std::uint32_t* a8) const {
    const std::size_t ws = static_cast<std::size_t>(L.width);
    for (unsigned m = cm & 0xffu; m != 0; m &= m - 1) {
      const int l = __builtin_ctz(m);
      if (L.owner[a8[l]] != me) continue;
      const std::uint32_t t = (touch >> l) & 1u;
      if (t == 0) std::fill_n(&L.cross_hist[cur ^ 1][L.cross[k8[l]] * ws], L.width, 0.0);
      L.touching[k8[l]] = t;
    }
  }

#if defined(PASTEMIX_AVX2_LANES)
  // Candidates q .. q + 3 into o (AVX2, four lanes): run()'s AVX-512 group of eight with four lanes, the
  // compress by a table (simd_avx2.h). The same values, entries and flags in the same order as one().
  template <long N>
  [[gnu::always_inline]] void group4(long q, const double* X, FilterOut<N>& o) const {
    __m128i e, k, a, b;
    __m256d rsum;
    unsigned cm = 0;  // the cross pairs' lanes
    std::uint32_t k0 = static_cast<std::uint32_t>(q);
    alignas(16) std::uint32_t k4[4], a4[4], b4[4];
    const std::uint32_t *ia = nullptr, *ib = nullptr;
    bool consecutive = true;  // pairs k0 .. k0 + 3, none crossing
    if constexpr (Part) {
      e = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ks + q));
      cm = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(e)));  // kCrossBit is the sign bit
      k = _mm_and_si128(e, _mm_set1_epi32(static_cast<int>(~PairList::kCrossBit)));
      k0 = static_cast<std::uint32_t>(_mm_cvtsi128_si32(e));
      consecutive = cm == 0 && static_cast<std::uint32_t>(_mm_extract_epi32(e, 3)) == k0 + 3;
      if (consecutive) {
        ia = L.i.data() + k0, ib = L.j.data() + k0;
        rsum = _mm256_loadu_pd(L.rsum.data() + k0);
      } else {
        _mm_store_si128(reinterpret_cast<__m128i*>(k4), k);
        for (int l = 0; l < 4; ++l) a4[l] = L.i[k4[l]], b4[l] = L.j[k4[l]];
        ia = a4, ib = b4;
        rsum = avx2::load4_pd(L.rsum.data(), k4);
      }
    } else {
      e = k = _mm_add_epi32(_mm_set1_epi32(static_cast<int>(q)), _mm_setr_epi32(0, 1, 2, 3));
      ia = L.i.data() + q, ib = L.j.data() + q;
      rsum = _mm256_loadu_pd(L.rsum.data() + q);
    }
    a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ia));
    b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ib));
    __m256d xa, ya, za, xb, yb, zb;
    if (cm == 0) {
      avx2::load_rows4(X, ia, xa, ya, za);
      avx2::load_rows4(X, ib, xb, yb, zb);
    } else {
      const Ghosts4 g{L, cur, cm, ia, ib};
      g.rows(false, X, 0, xa, ya, za);
      g.rows(true, X, 0, xb, yb, zb);
    }
    const __m256d dx = _mm256_sub_pd(xb, xa), dy = _mm256_sub_pd(yb, ya), dz = _mm256_sub_pd(zb, za);
    const __m256d dist2 = avx2::norm2(dx, dy, dz);
    // touch = !(dist2 >= rsum^2), true for NaN as the scalar form.
    const unsigned touch =
        static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(dist2, _mm256_mul_pd(rsum, rsum), _CMP_NGE_UQ)));
    const long m = o.m;  // (m + 4 <= N: at most q - q0 pairs kept so far)
    _mm_storeu_si128(reinterpret_cast<__m128i*>(o.idx + m), avx2::compress_epi32(touch, e));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(o.ia + m), avx2::compress_epi32(touch, a));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(o.ib + m), avx2::compress_epi32(touch, b));
    _mm256_storeu_pd(o.sep.x + m, avx2::compress_pd(touch, dx));
    _mm256_storeu_pd(o.sep.y + m, avx2::compress_pd(touch, dy));
    _mm256_storeu_pd(o.sep.z + m, avx2::compress_pd(touch, dz));
    _mm256_storeu_pd(o.sep2 + m, avx2::compress_pd(touch, dist2));
    _mm256_storeu_pd(o.rsums + m, avx2::compress_pd(touch, rsum));
    o.m = m + __builtin_popcount(touch);
    unsigned was = 0;  // the lanes that were touching
    std::uint32_t* T = L.touching.data();
    if (consecutive) {
      const __m128i now =
          _mm_and_si128(_mm_srlv_epi32(_mm_set1_epi32(static_cast<int>(touch)), _mm_setr_epi32(0, 1, 2, 3)),
                        _mm_set1_epi32(1));
      const __m128i w = _mm_loadu_si128(reinterpret_cast<const __m128i*>(T + k0));
      was = ~static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(w, _mm_setzero_si128())))) & 0xfu;
      _mm_storeu_si128(reinterpret_cast<__m128i*>(T + k0), now);
    } else {
      for (unsigned here = ~cm & 0xfu; here != 0; here &= here - 1) {
        const int l = __builtin_ctz(here);
        was |= static_cast<unsigned>(T[k4[l]] != 0) << l;
        T[k4[l]] = (touch >> l) & 1u;
      }
    }
    if (cm != 0) cross_flags(cm, touch, k4, ia);
    const unsigned opened = was & ~touch & ~cm & 0xfu;
    if (opened != 0) {
      alignas(16) std::uint32_t ks4[4];
      _mm_store_si128(reinterpret_cast<__m128i*>(ks4), k);
      const std::size_t ws = static_cast<std::size_t>(L.width);
      for (int l = 0; l < 4; ++l)
        if ((opened >> l) & 1u) std::fill_n(&L.history[ks4[l] * ws], L.width, 0.0);
    }
  }
#endif

  // Candidates q0 .. q1 (at most N) into o, one at a time.
  template <long N>
  void scalar(long q0, long q1, FilterOut<N>& o) const {
    for (long q = q0; q < q1; ++q) one(q, o);
  }

  // The same, eight at a time where the build has AVX-512 (a cross pair's lanes read the ghost copies).
  template <long N>
  void run(long q0, long q1, FilterOut<N>& o) const {
    long q = q0;
#if defined(__AVX512F__) && defined(__AVX512VL__)
    static_assert(sizeof(Vec3) == 3 * sizeof(double));
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const double* X = p.x.empty() ? nullptr : &p.x[0].x;
    for (; q + 8 <= q1; q += 8) {
      __m256i e, k, a, b;
      __m512d rsum;
      unsigned cm = 0;  // the cross pairs' lanes
      std::uint32_t k0 = static_cast<std::uint32_t>(q);
      // The lanes' pairs and particles: in the list where the eight are consecutive, else copied here.
      alignas(32) std::uint32_t k8[8], a8[8], b8[8];
      const std::uint32_t *ia = nullptr, *ib = nullptr;
      bool consecutive = true;  // pairs k0 .. k0 + 7, none crossing (a single thread's list: always)
      if constexpr (Part) {
        e = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ks + q));
        cm = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(e)));  // kCrossBit is the sign bit
        k = _mm256_and_si256(e, _mm256_set1_epi32(static_cast<int>(~PairList::kCrossBit)));
        k0 = static_cast<std::uint32_t>(_mm256_extract_epi32(e, 0));
        consecutive = cm == 0 && static_cast<std::uint32_t>(_mm256_extract_epi32(e, 7)) == k0 + 7;
        if (consecutive) {
          // Eight consecutive pairs (a thread's list ascends, and most of it is runs): loads, not gathers
          // (bench bed, 2 threads, 4 interleaved pairs: contact stage 0.658 -> 0.625 s, min of each).
          ia = L.i.data() + k0, ib = L.j.data() + k0;
          a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ia));
          b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ib));
          rsum = _mm512_loadu_pd(L.rsum.data() + k0);
        } else {
          // Scalar loads, not gathers (bench/gather_probe: a gather costs about twice the loads here).
          _mm256_store_si256(reinterpret_cast<__m256i*>(k8), k);
          for (int l = 0; l < 8; ++l) a8[l] = L.i[k8[l]], b8[l] = L.j[k8[l]];
          ia = a8, ib = b8;
          a = _mm256_load_si256(reinterpret_cast<const __m256i*>(a8));
          b = _mm256_load_si256(reinterpret_cast<const __m256i*>(b8));
          rsum = load8_pd(L.rsum.data(), k8);
        }
      } else {
        e = k = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(q)), lane);
        ia = L.i.data() + q, ib = L.j.data() + q;
        a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ia));
        b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ib));
        rsum = _mm512_loadu_pd(L.rsum.data() + q);
      }
      __m512d dx, dy, dz;
      if (cm == 0) {
        // Both positions by loads and a transpose (load_rows8).
        __m512d xa, ya, za, xb, yb, zb;
        load_rows8(X, ia, xa, ya, za);
        load_rows8(X, ib, xb, yb, zb);
        dx = _mm512_sub_pd(xb, xa), dy = _mm512_sub_pd(yb, ya), dz = _mm512_sub_pd(zb, za);
      } else {
        // A cross pair's two positions from their ghost copies (Ghost: x, v, w, nine doubles), as one() reads
        // them; the other lanes' from the store.
        const Ghosts g{L, cur, cm, ia, ib};
        __m512d xa, ya, za, xb, yb, zb;
        g.rows(false, X, 0, xa, ya, za);
        g.rows(true, X, 0, xb, yb, zb);
        dx = _mm512_sub_pd(xb, xa), dy = _mm512_sub_pd(yb, ya), dz = _mm512_sub_pd(zb, za);
      }
      // norm2: (dx dx + dy dy) + dz dz, no fused multiply-add (the build's -ffp-contract=off).
      const __m512d dist2 =
          _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
      // touch = !(dist2 >= rsum^2): "not greater or equal", true for NaN as the scalar form.
      const __mmask8 touch = _mm512_cmp_pd_mask(dist2, _mm512_mul_pd(rsum, rsum), _CMP_NGE_UQ);
      const long m = o.m;
      // Compressed in registers and stored whole (the lanes past the touching ones are overwritten by the
      // next group or never read; m + 8 <= N): a compressing store to memory is microcoded on Intel cores,
      // and was ~20 % of the filter's samples on the bench bed.
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o.idx + m), _mm256_maskz_compress_epi32(touch, e));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o.ia + m), _mm256_maskz_compress_epi32(touch, a));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o.ib + m), _mm256_maskz_compress_epi32(touch, b));
      _mm512_storeu_pd(o.sep.x + m, _mm512_maskz_compress_pd(touch, dx));
      _mm512_storeu_pd(o.sep.y + m, _mm512_maskz_compress_pd(touch, dy));
      _mm512_storeu_pd(o.sep.z + m, _mm512_maskz_compress_pd(touch, dz));
      _mm512_storeu_pd(o.sep2 + m, _mm512_maskz_compress_pd(touch, dist2));
      _mm512_storeu_pd(o.rsums + m, _mm512_maskz_compress_pd(touch, rsum));
      o.m = m + __builtin_popcount(touch);
      // The touching flags (0/1) of the eight pairs; their previous values give the contacts just opened.
      const __m256i now = _mm256_maskz_mov_epi32(touch, _mm256_set1_epi32(1));
      unsigned was = 0;  // the lanes that were touching
      std::uint32_t* T = L.touching.data();
      if (consecutive) {
        const __m256i w = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(T + k0));
        was = _mm256_test_epi32_mask(w, w);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(T + k0), now);
      } else {
        // The other lanes' flags here, one at a time; a cross pair's below, by the owner of its i only.
        for (unsigned here = ~cm & 0xffu; here != 0; here &= here - 1) {
          const int l = __builtin_ctz(here);
          was |= static_cast<unsigned>(T[k8[l]] != 0) << l;
          T[k8[l]] = (touch >> l) & 1u;
        }
      }
      if (cm != 0) cross_flags(cm, touch, k8, ia);
      const unsigned opened = was & ~static_cast<unsigned>(touch) & ~cm & 0xffu;
      if (opened != 0) {
        alignas(32) std::uint32_t ks8[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(ks8), k);
        const std::size_t ws = static_cast<std::size_t>(L.width);
        for (int l = 0; l < 8; ++l)
          if ((opened >> l) & 1u) std::fill_n(&L.history[ks8[l] * ws], L.width, 0.0);
      }
    }
#elif defined(PASTEMIX_AVX2_LANES)
    const double* X = p.x.empty() ? nullptr : &p.x[0].x;
    for (; q + 4 <= q1; q += 4) group4(q, X, o);
#endif
    scalar(q, q1, o);
  }
};

#if defined(PASTEMIX_AVX2_LANES)
// stage8's four-lane form (AVX2): pairs q .. q + 3 into lanes l0 .. l0 + 3, the same values.
template <class Batch, long N>
[[gnu::always_inline]] inline void stage4(Batch& B, int l0, const std::uint32_t* e4, const std::uint32_t* a4,
                                          const std::uint32_t* b4, const Separations<N>& sep, const double* sep2,
                                          const double* rsums, long q, const Particles& p, const PairList& L,
                                          int cur) {
  const __m128i e = _mm_loadu_si128(reinterpret_cast<const __m128i*>(e4));
  const unsigned cm = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(e)));  // kCrossBit: sign bit
  _mm256_storeu_pd(B.dx + l0, _mm256_loadu_pd(sep.x + q));
  _mm256_storeu_pd(B.dy + l0, _mm256_loadu_pd(sep.y + q));
  _mm256_storeu_pd(B.dz + l0, _mm256_loadu_pd(sep.z + q));
  _mm256_storeu_pd(B.dist2 + l0, _mm256_loadu_pd(sep2 + q));
  _mm256_storeu_pd(B.rsum + l0, _mm256_loadu_pd(rsums + q));
  _mm256_storeu_pd(B.ra + l0, avx2::load4_pd(p.radius.data(), a4));
  _mm256_storeu_pd(B.rb + l0, avx2::load4_pd(p.radius.data(), b4));
  const double* V = &p.v[0].x;
  const double* W = &p.omega[0].x;
  const double* H = L.history.data();
  const auto store = [&](double* x, double* y, double* z, const __m256d& rx, const __m256d& ry, const __m256d& rz) {
    _mm256_storeu_pd(x + l0, rx), _mm256_storeu_pd(y + l0, ry), _mm256_storeu_pd(z + l0, rz);
  };
  __m256d rx, ry, rz;
  if (cm == 0) {
    _mm256_storeu_pd(B.r_star + l0, avx2::load4_pd(L.r_star.data(), e4));
    _mm256_storeu_pd(B.m_star + l0, avx2::load4_pd(L.m_star.data(), e4));
    avx2::load_rows4(V, a4, rx, ry, rz), store(B.vax, B.vay, B.vaz, rx, ry, rz);
    avx2::load_rows4(V, b4, rx, ry, rz), store(B.vbx, B.vby, B.vbz, rx, ry, rz);
    avx2::load_rows4(W, a4, rx, ry, rz), store(B.wax, B.way, B.waz, rx, ry, rz);
    avx2::load_rows4(W, b4, rx, ry, rz), store(B.wbx, B.wby, B.wbz, rx, ry, rz);
    avx2::load_rows4(H, e4, rx, ry, rz), store(B.hx, B.hy, B.hz, rx, ry, rz);
    return;
  }
  alignas(16) std::uint32_t k4[4];  // the pair indices
  _mm_store_si128(reinterpret_cast<__m128i*>(k4), _mm_and_si128(e, _mm_set1_epi32(static_cast<int>(~PairList::kCrossBit))));
  _mm256_storeu_pd(B.r_star + l0, avx2::load4_pd(L.r_star.data(), k4));
  _mm256_storeu_pd(B.m_star + l0, avx2::load4_pd(L.m_star.data(), k4));
  const Ghosts4 g{L, cur, cm, a4, b4};
  g.rows(false, V, 3, rx, ry, rz), store(B.vax, B.vay, B.vaz, rx, ry, rz);
  g.rows(true, V, 3, rx, ry, rz), store(B.vbx, B.vby, B.vbz, rx, ry, rz);
  g.rows(false, W, 6, rx, ry, rz), store(B.wax, B.way, B.waz, rx, ry, rz);
  g.rows(true, W, 6, rx, ry, rz), store(B.wbx, B.wby, B.wbz, rx, ry, rz);
  const double* CH = L.cross_hist[cur].data();
  const auto spring = [&](int l) __attribute__((always_inline)) {
    const std::size_t kk = k4[l];
    return ((cm >> l) & 1u) ? CH + 3 * static_cast<std::size_t>(L.cross[kk]) : H + 3 * kk;
  };
  avx2::rows4(spring, rx, ry, rz), store(B.hx, B.hy, B.hz, rx, ry, rz);
}
#endif

// The pair pass's staging of eight touching pairs (entries e8[0 .. 8), chunk positions q .. q + 7 of the
// filter's arrays) into lanes l0 .. l0 + 7 of a batch kernel's input B (a Law::Batch with HertzMindlin's
// fields; a8, b8: the pairs' particles, as the filter kept them): separations, radii, R*, m*, both velocities and
// spins, the spring. Gathers, one store per field instead of eight. A cross pair (a thread's part, buffer
// `cur`) takes both particles' velocities and spins from their ghost copies and its spring from cross_hist[cur],
// as the one-at-a-time staging does. With AVX2 alone, two groups of four (stage4). False (nothing staged)
// where the build has neither: the caller stages them one at a time.
// With AVX2 alone stage8 is inlined into the pair pass (its two stage4s out of line cost the bench bed ~5 % of
// its contact stage on a Zen 3 VM: 5 of 6 interleaved pairs, session 38); the AVX-512 build keeps the
// compiler's choice, as measured there.
#if defined(PASTEMIX_AVX2_LANES)
#define PASTEMIX_STAGE8_INLINE [[gnu::always_inline]] inline
#else
#define PASTEMIX_STAGE8_INLINE
#endif
template <class Batch, long N>
PASTEMIX_STAGE8_INLINE bool stage8(Batch& B, int l0, const std::uint32_t* e8, const std::uint32_t* a8, const std::uint32_t* b8,
            const Separations<N>& sep, const double* sep2, const double* rsums, long q, const Particles& p,
            const PairList& L, int cur) {
#if defined(__AVX512F__) && defined(__AVX512VL__)
  const __m256i e = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(e8));
  const unsigned cm = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(e)));  // kCrossBit: sign bit
  _mm512_storeu_pd(B.dx + l0, _mm512_loadu_pd(sep.x + q));
  _mm512_storeu_pd(B.dy + l0, _mm512_loadu_pd(sep.y + q));
  _mm512_storeu_pd(B.dz + l0, _mm512_loadu_pd(sep.z + q));
  _mm512_storeu_pd(B.dist2 + l0, _mm512_loadu_pd(sep2 + q));
  _mm512_storeu_pd(B.rsum + l0, _mm512_loadu_pd(rsums + q));
  _mm512_storeu_pd(B.ra + l0, load8_pd(p.radius.data(), a8));
  _mm512_storeu_pd(B.rb + l0, load8_pd(p.radius.data(), b8));
  const double* V = &p.v[0].x;
  const double* W = &p.omega[0].x;
  const double* H = L.history.data();
  const auto store = [&](double* x, double* y, double* z, const __m512d& rx, const __m512d& ry, const __m512d& rz) {
    _mm512_storeu_pd(x + l0, rx), _mm512_storeu_pd(y + l0, ry), _mm512_storeu_pd(z + l0, rz);
  };
  __m512d rx, ry, rz;
  if (cm == 0) {
    // No cross pair: the entries are the pair indices.
    _mm512_storeu_pd(B.r_star + l0, load8_pd(L.r_star.data(), e8));
    _mm512_storeu_pd(B.m_star + l0, load8_pd(L.m_star.data(), e8));
    load_rows8(V, a8, rx, ry, rz), store(B.vax, B.vay, B.vaz, rx, ry, rz);
    load_rows8(V, b8, rx, ry, rz), store(B.vbx, B.vby, B.vbz, rx, ry, rz);
    load_rows8(W, a8, rx, ry, rz), store(B.wax, B.way, B.waz, rx, ry, rz);
    load_rows8(W, b8, rx, ry, rz), store(B.wbx, B.wby, B.wbz, rx, ry, rz);
    load_rows8(H, e8, rx, ry, rz), store(B.hx, B.hy, B.hz, rx, ry, rz);
    return true;
  }
  alignas(32) std::uint32_t k8[8];  // the pair indices
  _mm256_store_si256(reinterpret_cast<__m256i*>(k8),
                     _mm256_and_si256(e, _mm256_set1_epi32(static_cast<int>(~PairList::kCrossBit))));
  _mm512_storeu_pd(B.r_star + l0, load8_pd(L.r_star.data(), k8));
  _mm512_storeu_pd(B.m_star + l0, load8_pd(L.m_star.data(), k8));
  const Ghosts g{L, cur, cm, a8, b8};
  g.rows(false, V, 3, rx, ry, rz), store(B.vax, B.vay, B.vaz, rx, ry, rz);
  g.rows(true, V, 3, rx, ry, rz), store(B.vbx, B.vby, B.vbz, rx, ry, rz);
  g.rows(false, W, 6, rx, ry, rz), store(B.wax, B.way, B.waz, rx, ry, rz);
  g.rows(true, W, 6, rx, ry, rz), store(B.wbx, B.wby, B.wbz, rx, ry, rz);
  // The cross lanes' springs: slot cross[k] of cross_hist[cur], three doubles each; the others' in `history`.
  const double* CH = L.cross_hist[cur].data();
  const auto spring = [&](int l) __attribute__((always_inline)) {
    const std::size_t k = k8[l];
    return ((cm >> l) & 1u) ? CH + 3 * static_cast<std::size_t>(L.cross[k]) : H + 3 * k;
  };
  rows8(spring, rx, ry, rz), store(B.hx, B.hy, B.hz, rx, ry, rz);
  return true;
#elif defined(PASTEMIX_AVX2_LANES)
  stage4(B, l0, e8, a8, b8, sep, sep2, rsums, q, p, L, cur);
  stage4(B, l0 + 4, e8 + 4, a8 + 4, b8 + 4, sep, sep2, rsums, q + 4, p, L, cur);
  return true;
#else
  (void)B, (void)l0, (void)e8, (void)a8, (void)b8, (void)sep, (void)sep2, (void)rsums, (void)q, (void)p, (void)L,
      (void)cur;
  return false;
#endif
}

}  // namespace pastemix::model
