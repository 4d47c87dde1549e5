// SPDX-License-Identifier: MIT
// asin(x) by a polynomial, in a scalar, an 8-lane AVX-512 and a 4-lane AVX2 form that run the same operations
// (the same bits).
//
// Why (issue 19): the collective rule's footprint (collective.cpp, strip_lengths) evaluates the integral of a
// disc's chord at every strip boundary it crosses, t sqrt(r^2 - t^2) + r^2 asin(t / r): ~640k per update of
// the bench bed, one libm asin each, and that pass was half of the fluid hook's "cluster" variant. The scalar
// libm call cannot be vectorised with the rest (libmvec's asin is another function with other bits on each ISA
// level), so the project owns one function with one result on every build.
//
// Method: |x| <= 1/2: asin(x) = x + x z P(z), z = x^2, P of degree 14 fitted (least squares on 80 Chebyshev
// nodes of z in [0, 1/4], 40-digit arithmetic, coefficients rounded to double) to 2.6e-18 relative error in
// exact arithmetic; |x| > 1/2: asin(x) = pi/2 - 2 asin(s), s = sqrt((1 - |x|) / 2) <= 1/2 (1 - |x| and the
// halving are exact there). In double arithmetic within 2 ulp of the correctly rounded asin
// (tests/model/fluid/asin_poly_test.cpp: against std::asin over [-1, 1]). Odd: asin(-x) = -asin(x).
#pragma once

#include <cmath>

#if defined(__AVX512F__) || (defined(__AVX2__) && defined(__FMA__))
#include <immintrin.h>
#endif

namespace pastemix::model::fluid {

// P(z) of asin(x) = x + x z P(z) on z = x^2 in [0, 1/4], lowest degree first.
inline constexpr double kAsinP[15] = {
    0.16666666666666666,    0.0749999999999999,     0.04464285714288483,   0.030381944441216887,
    0.022372159287575737,   0.017352757223830194,   0.013965015221404711,  0.011549011895900822,
    0.009793486386035298,   0.00813073858378954,    0.008819738782820177,  0.00029837978129833786,
    0.022733346235747326,   -0.024251252161814167,  0.030850913031892038};
inline constexpr double kPio2Hi = 1.5707963267948966;     // pi/2 rounded to double
inline constexpr double kPio2Lo = 6.123233995736766e-17;  // pi/2 - kPio2Hi

// asin(x) for x in [-1, 1] (NaN for NaN; |x| > 1 is the caller's to clamp).
inline double asin_poly(double x) {
  const double a = std::fabs(x);
  const bool big = a > 0.5;
  const double s = big ? std::sqrt(0.5 * (1.0 - a)) : a;
  const double z = s * s;
  double p = kAsinP[14];
  for (int k = 13; k >= 0; --k) p = std::fma(p, z, kAsinP[k]);
  const double core = std::fma(s * z, p, s);
  const double r = big ? kPio2Hi - (2.0 * core - kPio2Lo) : core;
  return std::copysign(r, x);
}

#if defined(__AVX512F__)
// asin_poly of eight lanes: the same operations per lane.
inline __m512d asin8(__m512d x) {
  const __m512i sign = _mm512_set1_epi64(static_cast<long long>(0x8000000000000000ull));
  const __m512i xi = _mm512_castpd_si512(x);
  const __m512d a = _mm512_castsi512_pd(_mm512_maskz_andnot_epi64(0xff, sign, xi));
  const __mmask8 big = _mm512_cmp_pd_mask(a, _mm512_set1_pd(0.5), _CMP_GT_OQ);
  const __m512d half_gap = _mm512_mul_pd(_mm512_set1_pd(0.5), _mm512_sub_pd(_mm512_set1_pd(1.0), a));
  const __m512d from_top = _mm512_maskz_sqrt_pd(0xff, half_gap);
  const __m512d s = _mm512_mask_blend_pd(big, a, from_top);
  const __m512d z = _mm512_mul_pd(s, s);
  __m512d p = _mm512_set1_pd(kAsinP[14]);
  for (int k = 13; k >= 0; --k) p = _mm512_fmadd_pd(p, z, _mm512_set1_pd(kAsinP[k]));
  const __m512d core = _mm512_fmadd_pd(_mm512_mul_pd(s, z), p, s);
  const __m512d top = _mm512_sub_pd(_mm512_set1_pd(kPio2Hi),
                                    _mm512_sub_pd(_mm512_mul_pd(_mm512_set1_pd(2.0), core), _mm512_set1_pd(kPio2Lo)));
  const __m512d r = _mm512_mask_blend_pd(big, core, top);
  const __m512i ri = _mm512_castpd_si512(r);  // copysign(r, x):
  return _mm512_castsi512_pd(_mm512_or_si512(_mm512_maskz_andnot_epi64(0xff, sign, ri), _mm512_and_si512(sign, xi)));
}
#elif defined(__AVX2__) && defined(__FMA__)
// asin_poly of four lanes (AVX2 alone): the same operations per lane.
inline __m256d asin4(__m256d x) {
  const __m256d sign = _mm256_set1_pd(-0.0);
  const __m256d a = _mm256_andnot_pd(sign, x);
  const __m256d big = _mm256_cmp_pd(a, _mm256_set1_pd(0.5), _CMP_GT_OQ);
  const __m256d half_gap = _mm256_mul_pd(_mm256_set1_pd(0.5), _mm256_sub_pd(_mm256_set1_pd(1.0), a));
  const __m256d s = _mm256_blendv_pd(a, _mm256_sqrt_pd(half_gap), big);
  const __m256d z = _mm256_mul_pd(s, s);
  __m256d p = _mm256_set1_pd(kAsinP[14]);
  for (int k = 13; k >= 0; --k) p = _mm256_fmadd_pd(p, z, _mm256_set1_pd(kAsinP[k]));
  const __m256d core = _mm256_fmadd_pd(_mm256_mul_pd(s, z), p, s);
  const __m256d top = _mm256_sub_pd(_mm256_set1_pd(kPio2Hi),
                                    _mm256_sub_pd(_mm256_mul_pd(_mm256_set1_pd(2.0), core), _mm256_set1_pd(kPio2Lo)));
  const __m256d r = _mm256_blendv_pd(core, top, big);
  return _mm256_or_pd(_mm256_andnot_pd(sign, r), _mm256_and_pd(sign, x));  // copysign(r, x)
}
#endif

}  // namespace pastemix::model::fluid
