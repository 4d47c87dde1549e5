// SPDX-License-Identifier: MIT
// The pair pass's filter and staging (model/contacts.cpp). The filter finds which candidate pairs of a chunk
// touch: it keeps each touching pair's list entry, separation x_j - x_i (m), squared distance (m^2) and
// R_i + R_j (m) in pair order, sets the pairs' touching flags and zeroes the springs of the contacts that
// just opened. stage8 loads eight touching pairs' state into a batch kernel's lanes. With AVX-512 both take
// eight pairs at a time (gathers, one compare, compressed stores); one at a time, the filter was about half
// of the pair pass's samples in chapter-7 test 1 (perf, 2 threads; three candidates in four do not touch)
// and the loads of both spheres' radii, velocities and spins a third of the settled bed's. Interleaved A/B
// against the one-at-a-time build (issue 19, bench/README.md): bench bed, 1 thread, contact stage 1.53 ->
// 1.16 s. Both forms give the same bits: the same subtractions, squares and sums per pair, the same entries in
// the same order (tests/model/pair_filter_test.cpp, scripts/bitwise_check.sh).
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/contacts.h"

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

namespace pastemix::model {

#if defined(__AVX512F__) && defined(__AVX512VL__)
// 3 i per lane (the Vec3 arrays' double index): a shift and an add, not a 10-cycle multiply.
inline __m256i times3(__m256i i) { return _mm256_add_epi32(i, _mm256_slli_epi32(i, 1)); }
// Gathers of all eight lanes (the masked forms: the plain ones start from an undefined register, which GCC 12
// warns of).
inline __m512d gather_pd(__m256i at, const double* base) {
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xff, at, base, 8);
}
inline __m256i gather_u32(__m256i at, const std::uint32_t* base) {
  return _mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), 0xff, at, base, 4);
}
// The three components of the Vec3 array `v` (as doubles) at the lanes' indices times 3, into x, y, z + l0.
inline void gather_vec3(__m256i at3, const double* v, double* x, double* y, double* z, int l0) {
  _mm512_storeu_pd(x + l0, gather_pd(at3, v));
  _mm512_storeu_pd(y + l0, gather_pd(at3, v + 1));
  _mm512_storeu_pd(z + l0, gather_pd(at3, v + 2));
}

// Where a group of eight pairs has cross pairs (lanes cm): those lanes read both particles' state from the
// ghost copies of buffer `cur` (PairList::Ghost: x, v, w, nine doubles), the others from the store.
struct Ghosts {
  static_assert(sizeof(PairList::Ghost) == 9 * sizeof(double));
  const double* G;
  __mmask8 cm;
  __m256i ga9, gb9;  // 9 x ghost slot of the lanes' i and j (cross lanes only)
  Ghosts(const PairList& L, int cur, unsigned cross_lanes, __m256i a, __m256i b)
      : G(reinterpret_cast<const double*>(L.ghost[cur].data())), cm(static_cast<__mmask8>(cross_lanes)) {
    const auto nine = [](__m256i g) { return _mm256_add_epi32(_mm256_slli_epi32(g, 3), g); };
    ga9 = nine(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), cm, a, L.ghost_of.data(), 4));
    gb9 = nine(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), cm, b, L.ghost_of.data(), 4));
  }
  // Component `off` of the Ghost (0-2 x, 3-5 v, 6-8 w) of i (or j) in the cross lanes, base[at3] elsewhere.
  __m512d pick(bool of_j, __m256i at3, const double* base, int off) const {
    const __m512d here = _mm512_mask_i32gather_pd(_mm512_setzero_pd(), static_cast<__mmask8>(~cm), at3, base, 8);
    return _mm512_mask_i32gather_pd(here, cm, of_j ? gb9 : ga9, G + off, 8);
  }
  __m512d a_or(__m256i a3, const double* base, int off) const { return pick(false, a3, base, off); }
  __m512d b_or(__m256i b3, const double* base, int off) const { return pick(true, b3, base, off); }
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

#if defined(__AVX512F__) && defined(__AVX512VL__)
  // The touching flags and springs of a group's cross pairs (lanes cm; pair k, first particle a), as one()
  // sets them: by the owner of i only.
  void cross_flags(unsigned cm, unsigned touch, __m256i k, __m256i a) const {
    alignas(32) std::uint32_t k8[8], a8[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(k8), k);
    _mm256_store_si256(reinterpret_cast<__m256i*>(a8), a);
    const std::size_t ws = static_cast<std::size_t>(L.width);
    for (unsigned m = cm & 0xffu; m != 0; m &= m - 1) {
      const int l = __builtin_ctz(m);
      if (L.owner[a8[l]] != me) continue;
      const std::uint32_t t = (touch >> l) & 1u;
      if (t == 0) std::fill_n(&L.cross_hist[cur ^ 1][L.cross[k8[l]] * ws], L.width, 0.0);
      L.touching[k8[l]] = t;
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
          a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(L.i.data() + k0));
          b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(L.j.data() + k0));
          rsum = _mm512_loadu_pd(L.rsum.data() + k0);
        } else {
          a = gather_u32(k, L.i.data());
          b = gather_u32(k, L.j.data());
          rsum = gather_pd(k, L.rsum.data());
        }
      } else {
        e = k = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(q)), lane);
        a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(L.i.data() + q));
        b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(L.j.data() + q));
        rsum = _mm512_loadu_pd(L.rsum.data() + q);
      }
      const __m256i a3 = times3(a), b3 = times3(b);
      __m512d dx, dy, dz;
      if (cm == 0) {
        dx = _mm512_sub_pd(gather_pd(b3, X), gather_pd(a3, X));
        dy = _mm512_sub_pd(gather_pd(b3, X + 1), gather_pd(a3, X + 1));
        dz = _mm512_sub_pd(gather_pd(b3, X + 2), gather_pd(a3, X + 2));
      } else {
        // A cross pair's two positions from their ghost copies (Ghost: x, v, w, nine doubles), as one() reads
        // them; the other lanes' from the store.
        const Ghosts g{L, cur, cm, a, b};
        dx = _mm512_sub_pd(g.b_or(b3, X, 0), g.a_or(a3, X, 0));
        dy = _mm512_sub_pd(g.b_or(b3, X + 1, 1), g.a_or(a3, X + 1, 1));
        dz = _mm512_sub_pd(g.b_or(b3, X + 2, 2), g.a_or(a3, X + 2, 2));
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
      __m256i was;
      std::uint32_t* T = L.touching.data();
      if (consecutive) {
        was = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(T + k0));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(T + k0), now);
      } else {
        // The other lanes' flags here; a cross pair's below, by the owner of its i only.
        const __mmask8 here = static_cast<__mmask8>(~cm);
        was = _mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), here, k, T, 4);
        _mm256_mask_i32scatter_epi32(reinterpret_cast<int*>(T), here, k, now, 4);
      }
      if (cm != 0) cross_flags(cm, touch, k, a);
      const unsigned opened = _mm256_test_epi32_mask(was, was) & ~static_cast<unsigned>(touch) & ~cm & 0xffu;
      if (opened != 0) {
        alignas(32) std::uint32_t ks8[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(ks8), k);
        const std::size_t ws = static_cast<std::size_t>(L.width);
        for (int l = 0; l < 8; ++l)
          if ((opened >> l) & 1u) std::fill_n(&L.history[ks8[l] * ws], L.width, 0.0);
      }
    }
#endif
    scalar(q, q1, o);
  }
};

// The pair pass's staging of eight touching pairs (entries e8[0 .. 8), chunk positions q .. q + 7 of the
// filter's arrays) into lanes l0 .. l0 + 7 of a batch kernel's input B (a Law::Batch with HertzMindlin's
// fields; a8, b8: the pairs' particles, as the filter kept them): separations, radii, R*, m*, both velocities and
// spins, the spring. Gathers, one store per field instead of eight. A cross pair (a thread's part, buffer
// `cur`) takes both particles' velocities and spins from their ghost copies and its spring from cross_hist[cur],
// as the one-at-a-time staging does. False (nothing staged) where the build has no AVX-512: the caller stages
// them one at a time.
template <class Batch, long N>
bool stage8(Batch& B, int l0, const std::uint32_t* e8, const std::uint32_t* a8, const std::uint32_t* b8,
            const Separations<N>& sep, const double* sep2, const double* rsums, long q, const Particles& p,
            const PairList& L, int cur) {
#if defined(__AVX512F__) && defined(__AVX512VL__)
  const __m256i e = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(e8));
  const unsigned cm = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(e)));  // kCrossBit: sign bit
  const __m256i k = _mm256_and_si256(e, _mm256_set1_epi32(static_cast<int>(~PairList::kCrossBit)));
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a8));
  const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b8));
  const __m256i a3 = times3(a), b3 = times3(b), k3 = times3(k);
  _mm512_storeu_pd(B.dx + l0, _mm512_loadu_pd(sep.x + q));
  _mm512_storeu_pd(B.dy + l0, _mm512_loadu_pd(sep.y + q));
  _mm512_storeu_pd(B.dz + l0, _mm512_loadu_pd(sep.z + q));
  _mm512_storeu_pd(B.dist2 + l0, _mm512_loadu_pd(sep2 + q));
  _mm512_storeu_pd(B.rsum + l0, _mm512_loadu_pd(rsums + q));
  _mm512_storeu_pd(B.ra + l0, gather_pd(a, p.radius.data()));
  _mm512_storeu_pd(B.rb + l0, gather_pd(b, p.radius.data()));
  _mm512_storeu_pd(B.r_star + l0, gather_pd(k, L.r_star.data()));
  _mm512_storeu_pd(B.m_star + l0, gather_pd(k, L.m_star.data()));
  const double* V = &p.v[0].x;
  const double* W = &p.omega[0].x;
  const double* H = L.history.data();
  if (cm == 0) {
    gather_vec3(a3, V, B.vax, B.vay, B.vaz, l0);
    gather_vec3(b3, V, B.vbx, B.vby, B.vbz, l0);
    gather_vec3(a3, W, B.wax, B.way, B.waz, l0);
    gather_vec3(b3, W, B.wbx, B.wby, B.wbz, l0);
    gather_vec3(k3, H, B.hx, B.hy, B.hz, l0);
    return true;
  }
  const Ghosts g{L, cur, cm, a, b};
  double* va[3] = {B.vax, B.vay, B.vaz};
  double* vb[3] = {B.vbx, B.vby, B.vbz};
  double* wa[3] = {B.wax, B.way, B.waz};
  double* wb[3] = {B.wbx, B.wby, B.wbz};
  double* hs[3] = {B.hx, B.hy, B.hz};
  // The cross lanes' springs: slot cross[k] of cross_hist[cur], three doubles each.
  const __m256i c3 = times3(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), g.cm, k, L.cross.data(), 4));
  const double* CH = L.cross_hist[cur].data();
  for (int c = 0; c < 3; ++c) {
    _mm512_storeu_pd(va[c] + l0, g.a_or(a3, V + c, 3 + c));
    _mm512_storeu_pd(vb[c] + l0, g.b_or(b3, V + c, 3 + c));
    _mm512_storeu_pd(wa[c] + l0, g.a_or(a3, W + c, 6 + c));
    _mm512_storeu_pd(wb[c] + l0, g.b_or(b3, W + c, 6 + c));
    const __m512d here = _mm512_mask_i32gather_pd(_mm512_setzero_pd(), static_cast<__mmask8>(~g.cm), k3, H + c, 8);
    _mm512_storeu_pd(hs[c] + l0, _mm512_mask_i32gather_pd(here, g.cm, c3, CH + c, 8));
  }
  return true;
#else
  (void)B, (void)l0, (void)e8, (void)a8, (void)b8, (void)sep, (void)sep2, (void)rsums, (void)q, (void)p, (void)L,
      (void)cur;
  return false;
#endif
}

}  // namespace pastemix::model
