// SPDX-License-Identifier: MIT
// Four-lane (AVX2) forms of the pair pass's data movement, for CPUs without AVX-512 (AMD Zen 2-3, Intel
// client cores): the engine's eight-lane kernels (pair_filter.h, kick_block.h) are AVX-512 only, and on such a
// CPU every one of them fell back to one sphere at a time. Measured on an AMD EPYC (Zen 3) VM without AVX-512
// (session 38, bench/README.md): the pair pass around the kernel was 45 % of the bench bed's samples there.
// Data movement only (loads, shuffles, stores): every value keeps its bits, so the callers' arithmetic, done in
// the scalar code's order, gives the scalar code's bits.
#pragma once

#if defined(__AVX2__) && !defined(__AVX512F__)
#define PASTEMIX_AVX2_LANES 1
#include <immintrin.h>

#include <array>
#include <cstdint>

namespace pastemix::model::avx2 {

// Four rows of three doubles (row l at at(l)) as one register per component: each row's (x, y) by a 128-bit
// load and its z by a scalar one, then two unpacks. Reads exactly the rows' 24 bytes (never past an array).
template <class At>
[[gnu::always_inline]] inline void rows4(const At& at, __m256d& x, __m256d& y, __m256d& z) {
  const auto xy = [&](int l, int m) __attribute__((always_inline)) {  // [x_l y_l | x_m y_m]
    return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(l))), _mm_loadu_pd(at(m)), 1);
  };
  const auto zz = [&](int l, int m) __attribute__((always_inline)) {  // [z_l z_m]
    return _mm_loadh_pd(_mm_load_sd(at(l) + 2), at(m) + 2);
  };
  const __m256d a = xy(0, 2), b = xy(1, 3);
  x = _mm256_unpacklo_pd(a, b);
  y = _mm256_unpackhi_pd(a, b);
  z = _mm256_insertf128_pd(_mm256_castpd128_pd256(zz(0, 1)), zz(2, 3), 1);
}

// Rows base + 3 id[l] (a Vec3 array, or a width-3 spring array).
[[gnu::always_inline]] inline void load_rows4(const double* base, const std::uint32_t* id, __m256d& x, __m256d& y,
                                              __m256d& z) {
  const auto at = [&](int l) __attribute__((always_inline)) { return base + 3 * static_cast<std::size_t>(id[l]); };
  rows4(at, x, y, z);
}

// Four doubles base[id[l]] by scalar loads.
[[gnu::always_inline]] inline __m256d load4_pd(const double* base, const std::uint32_t* id) {
  const __m128d lo = _mm_loadh_pd(_mm_load_sd(base + id[0]), base + id[1]);
  const __m128d hi = _mm_loadh_pd(_mm_load_sd(base + id[2]), base + id[3]);
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(lo), hi, 1);
}

// Compress tables: for a 4-bit lane mask, the selected lanes moved to the front, in order (AVX-512's
// compress). Dword indices for four 32-bit lanes (vpermilps) and for four doubles as eight dwords (vpermps).
struct CompressTables {
  alignas(16) std::int32_t i32[16][4];
  alignas(32) std::int32_t f64[16][8];
};
constexpr CompressTables make_compress_tables() {
  CompressTables t{};
  for (int mask = 0; mask < 16; ++mask) {
    int k = 0;
    for (int l = 0; l < 4; ++l)
      if ((mask >> l) & 1) t.i32[mask][k] = l, t.f64[mask][2 * k] = 2 * l, t.f64[mask][2 * k + 1] = 2 * l + 1, ++k;
  }
  return t;
}
inline constexpr CompressTables kCompress = make_compress_tables();

// The lanes of `mask` of v, moved to the front (the other lanes: whatever the table's zeros pick).
[[gnu::always_inline]] inline __m128i compress_epi32(unsigned mask, __m128i v) {
  const __m128i idx = _mm_load_si128(reinterpret_cast<const __m128i*>(kCompress.i32[mask]));
  return _mm_castps_si128(_mm_permutevar_ps(_mm_castsi128_ps(v), idx));
}
[[gnu::always_inline]] inline __m256d compress_pd(unsigned mask, __m256d v) {
  const __m256i idx = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompress.f64[mask]));
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), idx));
}

// (dx dx + dy dy) + dz dz: norm2's order, no fused multiply-add.
[[gnu::always_inline]] inline __m256d norm2(__m256d x, __m256d y, __m256d z) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)), _mm256_mul_pd(z, z));
}


// Four consecutive Vec3 (12 doubles x0 y0 z0 x1 ... z3, three 256-bit registers) and one register per
// component (simd_vec3.h's Aos8 / Soa8 with four lanes).
struct Soa4 {
  __m256d x, y, z;
};
struct Aos4 {
  __m256d f0, f1, f2;  // flat doubles 0-3, 4-7, 8-11
};
inline Aos4 load_aos4(const double* d) { return {_mm256_loadu_pd(d), _mm256_loadu_pd(d + 4), _mm256_loadu_pd(d + 8)}; }
inline void store_aos4(double* d, const Aos4& a) {
  _mm256_storeu_pd(d, a.f0), _mm256_storeu_pd(d + 4, a.f1), _mm256_storeu_pd(d + 8, a.f2);
}
// f0 = x0 y0 z0 x1, f1 = y1 z1 x2 y2, f2 = z2 x3 y3 z3.
inline Soa4 to_soa(const Aos4& a) {
  const __m256d m03 = _mm256_permute2f128_pd(a.f0, a.f2, 0x21);  // z0 x1 | z2 x3
  const __m256d m12 = _mm256_permute2f128_pd(a.f0, a.f1, 0x30);  // x0 y0 | x2 y2   (f0 lo, f1 hi)
  const __m256d m21 = _mm256_permute2f128_pd(a.f1, a.f2, 0x30);  // y1 z1 | y3 z3   (f1 lo, f2 hi)
  return {_mm256_shuffle_pd(m12, m03, 0b1010),   // x0 x1 | x2 x3
          _mm256_shuffle_pd(m12, m21, 0b0101),   // y0 y1 | y2 y3
          _mm256_shuffle_pd(m03, m21, 0b1010)};  // z0 z1 | z2 z3
}
inline Aos4 to_aos(const Soa4& s) {
  const __m256d xy = _mm256_shuffle_pd(s.x, s.y, 0b0000);  // x0 y0 | x2 y2
  const __m256d zx = _mm256_shuffle_pd(s.z, s.x, 0b1010);  // z0 x1 | z2 x3
  const __m256d yz = _mm256_shuffle_pd(s.y, s.z, 0b1111);  // y1 z1 | y3 z3
  return {_mm256_permute2f128_pd(xy, zx, 0x20), _mm256_permute2f128_pd(yz, xy, 0x30),
          _mm256_permute2f128_pd(zx, yz, 0x31)};
}
// Four per-particle scalars, each repeated for its particle's three components.
inline Aos4 spread(__m256d s) {
  return {_mm256_permute4x64_pd(s, 0b01000000), _mm256_permute4x64_pd(s, 0b10100101),
          _mm256_permute4x64_pd(s, 0b11111110)};
}
// The same Vec3 (cx, cy, cz) for all four particles.
inline Aos4 repeat(double cx, double cy, double cz) {
  return {_mm256_setr_pd(cx, cy, cz, cx), _mm256_setr_pd(cy, cz, cx, cy), _mm256_setr_pd(cz, cx, cy, cz)};
}

}  // namespace pastemix::model::avx2

#endif
