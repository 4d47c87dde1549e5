// SPDX-License-Identifier: MIT
// Distances of up to eight (sphere centre, surface of revolution) candidates at once, for the wall force pass
// (contacts.h, wall_forces_block). A funnel's cone and exit tube are surfaces of revolution; their distance
// (two square roots, three divisions, a clamp) one candidate after another was most of the wall pass, itself
// ~8 % of case 3 of the main job on one thread while its rock runs through the funnel (perf, issue 19:
// wall_distance 3.1 %, the pass around it 3.8 %, the contact law 0.6 %). With AVX-512 the eight lanes take
// revolution_distance's operations in its order (IEEE square roots and divisions, no fused multiply-add:
// the build's -ffp-contract=off), so each lane gives its bits (four lanes at a time with AVX2 alone); elsewhere
// one at a time by
// revolution_distance itself. tests/model/wall_batch_test.cpp holds both to wall_distance.
#pragma once

#include "model/walls.h"

#include "model/simd_avx2.h"

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace pastemix::model {

// The lanes' inputs (centre p, shifted origin o, the meridian segment) and outputs (distance, unit vector
// towards the wall).
struct RevolutionLanes {
  static constexpr int kLanes = 8;
  alignas(64) double px[kLanes], py[kLanes], pz[kLanes], ox[kLanes], oy[kLanes], oz[kLanes];
  alignas(64) double r0[kLanes], z0[kLanes], r1[kLanes], z1[kLanes];
  alignas(64) double dist[kLanes], nx[kLanes], ny[kLanes], nz[kLanes];
  // Lane l: centre p of a sphere against wall w at shifted origin o.
  void set(int l, const Wall& w, const Vec3& o, const Vec3& p) {
    px[l] = p.x, py[l] = p.y, pz[l] = p.z, ox[l] = o.x, oy[l] = o.y, oz[l] = o.z;
    r0[l] = w.r0, z0[l] = w.z0, r1[l] = w.r1, z1[l] = w.z1;
  }
};

// dist, nx, ny, nz of lanes 0 .. n - 1 (n <= 8; the other lanes' outputs are unspecified).
inline void revolution_distances(RevolutionLanes& b, int n) {
#if defined(__AVX512F__)
  // Lanes past n repeat lane 0 (computed, never read): no lane computes on values never written.
  for (int l = n; l < RevolutionLanes::kLanes; ++l) {
    b.px[l] = b.px[0], b.py[l] = b.py[0], b.pz[l] = b.pz[0], b.ox[l] = b.ox[0], b.oy[l] = b.oy[0], b.oz[l] = b.oz[0];
    b.r0[l] = b.r0[0], b.z0[l] = b.z0[0], b.r1[l] = b.r1[0], b.z1[l] = b.z1[0];
  }
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
  // (maskz_sqrt: GCC 12's plain _mm512_sqrt_pd starts from an undefined register and warns.)
  const auto ld = [](const double* v) { return _mm512_load_pd(v); };
  const __m512d dx = _mm512_sub_pd(ld(b.px), ld(b.ox)), dy = _mm512_sub_pd(ld(b.py), ld(b.oy));
  const __m512d rho = _mm512_maskz_sqrt_pd(0xff, _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)));
  const __m512d z = _mm512_sub_pd(ld(b.pz), ld(b.oz));
  const __m512d r0 = ld(b.r0), z0 = ld(b.z0);
  const __m512d ar = _mm512_sub_pd(ld(b.r1), r0), az = _mm512_sub_pd(ld(b.z1), z0);
  const __m512d l2 = _mm512_add_pd(_mm512_mul_pd(ar, ar), _mm512_mul_pd(az, az));
  const __m512d num = _mm512_add_pd(_mm512_mul_pd(_mm512_sub_pd(rho, r0), ar), _mm512_mul_pd(_mm512_sub_pd(z, z0), az));
  // s = l2 > 0 ? num / l2 : 0, then std::max(s, 0) = (s < 0 ? 0 : s) and std::min(s, 1) = (1 < s ? 1 : s).
  __m512d s = _mm512_maskz_div_pd(_mm512_cmp_pd_mask(l2, zero, _CMP_GT_OQ), num, l2);
  s = _mm512_mask_mov_pd(s, _mm512_cmp_pd_mask(s, zero, _CMP_LT_OQ), zero);
  s = _mm512_mask_mov_pd(s, _mm512_cmp_pd_mask(one, s, _CMP_LT_OQ), one);
  const __m512d er = _mm512_sub_pd(_mm512_add_pd(r0, _mm512_mul_pd(s, ar)), rho);
  const __m512d ez = _mm512_sub_pd(_mm512_add_pd(z0, _mm512_mul_pd(s, az)), z);
  const __m512d len = _mm512_maskz_sqrt_pd(0xff, _mm512_add_pd(_mm512_mul_pd(er, er), _mm512_mul_pd(ez, ez)));
  const __mmask8 radial = _mm512_cmp_pd_mask(rho, zero, _CMP_GT_OQ);
  const __m512d ux = _mm512_mask_div_pd(one, radial, dx, rho), uy = _mm512_maskz_div_pd(radial, dy, rho);
  const __mmask8 apart = _mm512_cmp_pd_mask(len, zero, _CMP_GT_OQ);
  _mm512_store_pd(b.dist, len);
  _mm512_store_pd(b.nx, _mm512_maskz_div_pd(apart, _mm512_mul_pd(ux, er), len));
  _mm512_store_pd(b.ny, _mm512_maskz_div_pd(apart, _mm512_mul_pd(uy, er), len));
  _mm512_store_pd(b.nz, _mm512_mask_div_pd(_mm512_set1_pd(-1.0), apart, ez, len));
#elif defined(PASTEMIX_AVX2_LANES)
  // Four lanes at a time (AVX2 alone): the same operations, the masked forms as selects (blendv / and).
  for (int l = n; l < RevolutionLanes::kLanes; ++l) {
    b.px[l] = b.px[0], b.py[l] = b.py[0], b.pz[l] = b.pz[0], b.ox[l] = b.ox[0], b.oy[l] = b.oy[0], b.oz[l] = b.oz[0];
    b.r0[l] = b.r0[0], b.z0[l] = b.z0[0], b.r1[l] = b.r1[0], b.z1[l] = b.z1[0];
  }
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  for (int q = 0; q < n; q += 4) {
    const auto ld = [q](const double* v) { return _mm256_load_pd(v + q); };
    const __m256d dx = _mm256_sub_pd(ld(b.px), ld(b.ox)), dy = _mm256_sub_pd(ld(b.py), ld(b.oy));
    const __m256d rho = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
    const __m256d z = _mm256_sub_pd(ld(b.pz), ld(b.oz));
    const __m256d r0 = ld(b.r0), z0 = ld(b.z0);
    const __m256d ar = _mm256_sub_pd(ld(b.r1), r0), az = _mm256_sub_pd(ld(b.z1), z0);
    const __m256d l2 = _mm256_add_pd(_mm256_mul_pd(ar, ar), _mm256_mul_pd(az, az));
    const __m256d num =
        _mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(rho, r0), ar), _mm256_mul_pd(_mm256_sub_pd(z, z0), az));
    __m256d s = _mm256_and_pd(_mm256_cmp_pd(l2, zero, _CMP_GT_OQ), _mm256_div_pd(num, l2));
    s = _mm256_blendv_pd(s, zero, _mm256_cmp_pd(s, zero, _CMP_LT_OQ));
    s = _mm256_blendv_pd(s, one, _mm256_cmp_pd(one, s, _CMP_LT_OQ));
    const __m256d er = _mm256_sub_pd(_mm256_add_pd(r0, _mm256_mul_pd(s, ar)), rho);
    const __m256d ez = _mm256_sub_pd(_mm256_add_pd(z0, _mm256_mul_pd(s, az)), z);
    const __m256d len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(er, er), _mm256_mul_pd(ez, ez)));
    const __m256d radial = _mm256_cmp_pd(rho, zero, _CMP_GT_OQ);
    const __m256d ux = _mm256_blendv_pd(one, _mm256_div_pd(dx, rho), radial);
    const __m256d uy = _mm256_and_pd(radial, _mm256_div_pd(dy, rho));
    const __m256d apart = _mm256_cmp_pd(len, zero, _CMP_GT_OQ);
    _mm256_store_pd(b.dist + q, len);
    _mm256_store_pd(b.nx + q, _mm256_and_pd(apart, _mm256_div_pd(_mm256_mul_pd(ux, er), len)));
    _mm256_store_pd(b.ny + q, _mm256_and_pd(apart, _mm256_div_pd(_mm256_mul_pd(uy, er), len)));
    _mm256_store_pd(b.nz + q, _mm256_blendv_pd(_mm256_set1_pd(-1.0), _mm256_div_pd(ez, len), apart));
  }
#else
  Wall w;
  for (int l = 0; l < n; ++l) {
    w.r0 = b.r0[l], w.z0 = b.z0[l], w.r1 = b.r1[l], w.z1 = b.z1[l];
    Vec3 nv;
    b.dist[l] = revolution_distance(w, {b.ox[l], b.oy[l], b.oz[l]}, {b.px[l], b.py[l], b.pz[l]}, &nv);
    b.nx[l] = nv.x, b.ny[l] = nv.y, b.nz[l] = nv.z;
  }
#endif
}

}  // namespace pastemix::model
