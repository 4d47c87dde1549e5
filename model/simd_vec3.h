// SPDX-License-Identifier: MIT
// Eight consecutive Vec3 (24 doubles: x0 y0 z0 x1 ... z7, three 512-bit registers F0 F1 F2) to one register
// per component and back, and a per-particle scalar or a Vec3 constant laid out as those three registers.
// For loops over the particle store's Vec3 arrays that work eight particles at a time (the blocked kick of
// world.cpp): two two-source permutes per register, no gathers. Data movement only: every value keeps its bits.
#pragma once

#if defined(__AVX512F__)
#include <immintrin.h>

#include "model/vec3.h"

namespace pastemix::model::simd {

struct Soa8 {
  __m512d x, y, z;
};
struct Aos8 {
  __m512d f0, f1, f2;  // flat doubles 0-7, 8-15, 16-23 of the eight Vec3
};

inline Aos8 load_aos8(const Vec3* v) {
  const double* d = &v->x;
  return {_mm512_loadu_pd(d), _mm512_loadu_pd(d + 8), _mm512_loadu_pd(d + 16)};
}
inline void store_aos8(Vec3* v, const Aos8& a) {
  double* d = &v->x;
  _mm512_storeu_pd(d, a.f0), _mm512_storeu_pd(d + 8, a.f1), _mm512_storeu_pd(d + 16, a.f2);
}

// Lane index vectors (a permute's table: 0-7 the first source, 8-15 the second).
inline __m512i lanes(long a, long b, long c, long d, long e, long f, long g, long h) {
  return _mm512_setr_epi64(a, b, c, d, e, f, g, h);
}

inline Soa8 to_soa(const Aos8& a) {
  // x_i is flat 3i, y_i 3i + 1, z_i 3i + 2: the first five or six from f0/f1, the rest from f2.
  const __m512d tx = _mm512_permutex2var_pd(a.f0, lanes(0, 3, 6, 9, 12, 15, 0, 0), a.f1);
  const __m512d ty = _mm512_permutex2var_pd(a.f0, lanes(1, 4, 7, 10, 13, 0, 0, 0), a.f1);
  const __m512d tz = _mm512_permutex2var_pd(a.f0, lanes(2, 5, 8, 11, 14, 0, 0, 0), a.f1);
  return {_mm512_permutex2var_pd(tx, lanes(0, 1, 2, 3, 4, 5, 10, 13), a.f2),
          _mm512_permutex2var_pd(ty, lanes(0, 1, 2, 3, 4, 8, 11, 14), a.f2),
          _mm512_permutex2var_pd(tz, lanes(0, 1, 2, 3, 4, 9, 12, 15), a.f2)};
}

inline Aos8 to_aos(const Soa8& s) {
  const __m512d t0 = _mm512_permutex2var_pd(s.x, lanes(0, 8, 0, 1, 9, 0, 2, 10), s.y);
  const __m512d t1 = _mm512_permutex2var_pd(s.x, lanes(0, 3, 11, 0, 4, 12, 0, 5), s.y);
  const __m512d t2 = _mm512_permutex2var_pd(s.x, lanes(13, 0, 6, 14, 0, 7, 15, 0), s.y);
  return {_mm512_permutex2var_pd(t0, lanes(0, 1, 8, 3, 4, 9, 6, 7), s.z),
          _mm512_permutex2var_pd(t1, lanes(10, 1, 2, 11, 4, 5, 12, 7), s.z),
          _mm512_permutex2var_pd(t2, lanes(0, 13, 2, 3, 14, 5, 6, 15), s.z)};
}

// Eight per-particle scalars s_0 .. s_7, each repeated for its particle's three components.
inline Aos8 spread(__m512d s) {
  // (the masked form: the plain one starts from an undefined register, which GCC 12 warns of)
  return {_mm512_maskz_permutexvar_pd(0xff, lanes(0, 0, 0, 1, 1, 1, 2, 2), s),
          _mm512_maskz_permutexvar_pd(0xff, lanes(2, 3, 3, 3, 4, 4, 4, 5), s),
          _mm512_maskz_permutexvar_pd(0xff, lanes(5, 5, 6, 6, 6, 7, 7, 7), s)};
}

// The same Vec3 c for all eight particles.
inline Aos8 repeat(const Vec3& c) {
  return {_mm512_setr_pd(c.x, c.y, c.z, c.x, c.y, c.z, c.x, c.y),
          _mm512_setr_pd(c.z, c.x, c.y, c.z, c.x, c.y, c.z, c.x),
          _mm512_setr_pd(c.y, c.z, c.x, c.y, c.z, c.x, c.y, c.z)};
}

}  // namespace pastemix::model::simd

#endif
