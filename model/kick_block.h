// SPDX-License-Identifier: MIT
// The blocked kick of world.cpp (World::close_kicks_blocked): the spins of a block of particles in one vector
// loop (spin_block), and, where the build has AVX-512, eight consecutive particles' closing and opening
// velocity kicks, spin inputs, drift, domain check and displacement since the last build at a time (velocity8,
// spins8, drift8): their Vec3 arrays loaded as three registers and transposed (model/simd_vec3.h), not one sphere's
// x, y, z at a time. One sphere at a time this was ~20 % of the bench pour's samples on one thread (perf).
// With AVX2 alone (no AVX-512: AMD Zen 2-3, Intel client cores), the same four at a time (velocity4, spins4,
// drift4; session 38). The arithmetic per component and its order are the scalar code's (World::kick_velocity_twice, drift_one,
// Lane::add_moves), so the bits are the same (scripts/bitwise_check.sh, tests/model/kick_block_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "model/particles.h"
#include "model/simd_avx2.h"
#include "model/simd_vec3.h"

namespace pastemix::model::kick {

constexpr int kBlock = 64;  // particles per block (its arrays stay in L1)

// One sphere's closing and next opening half kicks of omega under the non-reversing rolling friction (w + dw,
// then |w| shrinks by stop = h M / I (rad/s) or w stops), or w + dw + dw without a rolling contact (held =
// false: M = 0). Both sides of each choice are computed and one selected, so that spin_block's loop over a
// block of spheres is one vector loop (no trapping math in this target): one sphere at a time chained two
// square roots and two divisions through unpredictable branches (about 40 % of the pour's kick stage, issue 19).
inline void spin_twice(double& wx, double& wy, double& wz, double dx, double dy, double dz, double stop, bool held) {
  const double fx = (wx + dx) + dx, fy = (wy + dy) + dy, fz = (wz + dz) + dz;
  double x = wx, y = wy, z = wz;
  for (int k = 0; k < 2; ++k) {
    x = x + dx, y = y + dy, z = z + dz;
    const double len = std::sqrt(x * x + y * y + z * z);
    const double keep = 1.0 - stop / len;
    const bool halt = len <= stop;
    x = halt ? 0.0 : x * keep;
    y = halt ? 0.0 : y * keep;
    z = halt ? 0.0 : z * keep;
  }
  wx = held ? x : fx;
  wy = held ? y : fy;
  wz = held ? z : fz;
}

// Spins of a block of particles, one lane each: omega (in and out), the half kick's dw = h tau / I, the
// friction's stop = h M / I (rad/s) and the rolling capacity M (N.m).
struct SpinBlock {
  double wx[kBlock], wy[kBlock], wz[kBlock], dx[kBlock], dy[kBlock], dz[kBlock];
  double stop[kBlock], cap[kBlock];
};

// Lanes 0 .. m-1: spin_twice of each (the block's spheres in one vector loop).
inline void spin_block(SpinBlock& b, int m) {
  for (int e = 0; e < m; ++e) spin_twice(b.wx[e], b.wy[e], b.wz[e], b.dx[e], b.dy[e], b.dz[e], b.stop[e], b.cap[e] > 0.0);
}

// Lanes 0 .. m-1 without a rolling friction: w + dw + dw, as kick_twice (its spin_twice(held = false) side).
inline void spin_free(SpinBlock& b, int m) {
  for (int e = 0; e < m; ++e) {
    b.wx[e] = (b.wx[e] + b.dx[e]) + b.dx[e];
    b.wy[e] = (b.wy[e] + b.dy[e]) + b.dy[e];
    b.wz[e] = (b.wz[e] + b.dz[e]) + b.dz[e];
  }
}

#if defined(__AVX512F__)
constexpr bool kEight = true;
constexpr int kLanes = 8;

// Particles a0 .. a0 + 7 (none kicked by a kick pass): v += dv twice with dv = (f / m + g) h (World::
// kick_velocity_twice).
inline void velocity8(Particles& p, const Vec3& g, double h, long a0) {
  using namespace simd;
  const __m512d hv = _mm512_set1_pd(h);
  const Aos8 im = spread(_mm512_loadu_pd(&p.inv_mass[a0])), f = load_aos8(&p.f[a0]), G = repeat(g);
  const Aos8 v = load_aos8(&p.v[a0]);
  const auto twice = [&](__m512d vv, __m512d ff, __m512d m, __m512d gg) {
    const __m512d dv = _mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(ff, m), gg), hv);
    return _mm512_add_pd(_mm512_add_pd(vv, dv), dv);
  };
  store_aos8(&p.v[a0], {twice(v.f0, f.f0, im.f0, G.f0), twice(v.f1, f.f1, im.f1, G.f1), twice(v.f2, f.f2, im.f2, G.f2)});
}

// The spins' inputs of particles a0 .. a0 + 7 into lanes e .. e + 7 of b: omega, dw = tau (h / I),
// stop = h M / I, M.
inline void spins8(const Particles& p, double h, SpinBlock& b, int e, long a0) {
  using namespace simd;
  const __m512d hv = _mm512_set1_pd(h);
  const __m512d ii = _mm512_loadu_pd(&p.inv_inertia[a0]), cap = _mm512_loadu_pd(&p.rolling_capacity[a0]);
  const __m512d k = _mm512_mul_pd(hv, ii);  // h / I
  const Soa8 t = to_soa(load_aos8(&p.torque[a0])), w = to_soa(load_aos8(&p.omega[a0]));
  _mm512_storeu_pd(b.wx + e, w.x), _mm512_storeu_pd(b.wy + e, w.y), _mm512_storeu_pd(b.wz + e, w.z);
  _mm512_storeu_pd(b.dx + e, _mm512_mul_pd(t.x, k));
  _mm512_storeu_pd(b.dy + e, _mm512_mul_pd(t.y, k));
  _mm512_storeu_pd(b.dz + e, _mm512_mul_pd(t.z, k));
  _mm512_storeu_pd(b.stop + e, _mm512_mul_pd(_mm512_mul_pd(hv, cap), ii));
  _mm512_storeu_pd(b.cap + e, cap);
}

// Where the block's displacements go: refining, |dx|^2 and |dx - u|^2 into a2, b2 (lanes e .. e + 7);
// otherwise only their largest |dx|^2, into amax (a NaN displacement is skipped, as std::max(a2max, NaN)).
struct Moves {
  bool refine = false;
  Vec3 u;
  double* a2 = nullptr;
  double* b2 = nullptr;
  __m512d amax = _mm512_setzero_pd();
  // The largest of amax's lanes (none is NaN).
  double largest() const {
    alignas(64) double l[8];
    _mm512_store_pd(l, amax);
    return *std::max_element(l, l + 8);
  }
};

// Particles a0 .. a0 + 7 after the block's spins: omega from lanes e .. e + 7 of b, x += v dt, the domain
// check (first_bad: the lowest index outside [lo, hi] or NaN) and x - x_build into `moves`.
inline void drift8(Particles& p, const Vec3* x_build, const SpinBlock& b, int e, long a0, double dt, const Vec3& lo,
                   const Vec3& hi, long& first_bad, Moves& moves) {
  using namespace simd;
  store_aos8(&p.omega[a0], to_aos({_mm512_loadu_pd(b.wx + e), _mm512_loadu_pd(b.wy + e), _mm512_loadu_pd(b.wz + e)}));
  const __m512d dtv = _mm512_set1_pd(dt);
  const Aos8 v = load_aos8(&p.v[a0]), x0 = load_aos8(&p.x[a0]);
  const Aos8 x{_mm512_add_pd(x0.f0, _mm512_mul_pd(v.f0, dtv)), _mm512_add_pd(x0.f1, _mm512_mul_pd(v.f1, dtv)),
               _mm512_add_pd(x0.f2, _mm512_mul_pd(v.f2, dtv))};
  store_aos8(&p.x[a0], x);
  const Aos8 L = repeat(lo), H = repeat(hi);
  const auto inside = [](__m512d c, __m512d l, __m512d u) {
    return static_cast<unsigned>(_mm512_cmp_pd_mask(c, l, _CMP_GE_OQ) & _mm512_cmp_pd_mask(c, u, _CMP_LE_OQ));
  };
  if ((inside(x.f0, L.f0, H.f0) & inside(x.f1, L.f1, H.f1) & inside(x.f2, L.f2, H.f2)) != 0xffu)
    for (long a = a0; a < a0 + 8; ++a) {
      const Vec3& q = p.x[a];
      if (!(q.x >= lo.x && q.x <= hi.x && q.y >= lo.y && q.y <= hi.y && q.z >= lo.z && q.z <= hi.z))
        first_bad = std::min(first_bad, a);
    }
  const Aos8 r = load_aos8(x_build + a0);
  const Soa8 d = to_soa({_mm512_sub_pd(x.f0, r.f0), _mm512_sub_pd(x.f1, r.f1), _mm512_sub_pd(x.f2, r.f2)});
  const auto norm2 = [](__m512d cx, __m512d cy, __m512d cz) {
    return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(cx, cx), _mm512_mul_pd(cy, cy)), _mm512_mul_pd(cz, cz));
  };
  const __m512d a2 = norm2(d.x, d.y, d.z);
  if (!moves.refine) {
    moves.amax = _mm512_maskz_max_pd(0xff, a2, moves.amax);  // NaN in a2: the second operand
    return;
  }
  _mm512_storeu_pd(moves.a2 + e, a2);
  _mm512_storeu_pd(moves.b2 + e, norm2(_mm512_sub_pd(d.x, _mm512_set1_pd(moves.u.x)), _mm512_sub_pd(d.y, _mm512_set1_pd(moves.u.y)),
                                       _mm512_sub_pd(d.z, _mm512_set1_pd(moves.u.z))));
}
#elif defined(PASTEMIX_AVX2_LANES)
constexpr bool kEight = false;
constexpr int kLanes = 4;

// velocity8, spins8, Moves and drift8 with four lanes (AVX2, model/simd_avx2.h): the same operations.
inline void velocity4(Particles& p, const Vec3& g, double h, long a0) {
  using namespace avx2;
  const __m256d hv = _mm256_set1_pd(h);
  const Aos4 im = spread(_mm256_loadu_pd(&p.inv_mass[a0])), f = load_aos4(&p.f[a0].x), G = repeat(g.x, g.y, g.z);
  const Aos4 v = load_aos4(&p.v[a0].x);
  const auto twice = [&](__m256d vv, __m256d ff, __m256d m, __m256d gg) {
    const __m256d dv = _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(ff, m), gg), hv);
    return _mm256_add_pd(_mm256_add_pd(vv, dv), dv);
  };
  store_aos4(&p.v[a0].x, {twice(v.f0, f.f0, im.f0, G.f0), twice(v.f1, f.f1, im.f1, G.f1), twice(v.f2, f.f2, im.f2, G.f2)});
}

inline void spins4(const Particles& p, double h, SpinBlock& b, int e, long a0) {
  using namespace avx2;
  const __m256d hv = _mm256_set1_pd(h);
  const __m256d ii = _mm256_loadu_pd(&p.inv_inertia[a0]), cap = _mm256_loadu_pd(&p.rolling_capacity[a0]);
  const __m256d k = _mm256_mul_pd(hv, ii);  // h / I
  const Soa4 t = to_soa(load_aos4(&p.torque[a0].x)), w = to_soa(load_aos4(&p.omega[a0].x));
  _mm256_storeu_pd(b.wx + e, w.x), _mm256_storeu_pd(b.wy + e, w.y), _mm256_storeu_pd(b.wz + e, w.z);
  _mm256_storeu_pd(b.dx + e, _mm256_mul_pd(t.x, k));
  _mm256_storeu_pd(b.dy + e, _mm256_mul_pd(t.y, k));
  _mm256_storeu_pd(b.dz + e, _mm256_mul_pd(t.z, k));
  _mm256_storeu_pd(b.stop + e, _mm256_mul_pd(_mm256_mul_pd(hv, cap), ii));
  _mm256_storeu_pd(b.cap + e, cap);
}

struct Moves {
  bool refine = false;
  Vec3 u;
  double* a2 = nullptr;
  double* b2 = nullptr;
  __m256d amax = _mm256_setzero_pd();
  double largest() const {
    alignas(32) double l[4];
    _mm256_store_pd(l, amax);
    return *std::max_element(l, l + 4);
  }
};

inline void drift4(Particles& p, const Vec3* x_build, const SpinBlock& b, int e, long a0, double dt, const Vec3& lo,
                   const Vec3& hi, long& first_bad, Moves& moves) {
  using namespace avx2;
  store_aos4(&p.omega[a0].x, to_aos({_mm256_loadu_pd(b.wx + e), _mm256_loadu_pd(b.wy + e), _mm256_loadu_pd(b.wz + e)}));
  const __m256d dtv = _mm256_set1_pd(dt);
  const Aos4 v = load_aos4(&p.v[a0].x), x0 = load_aos4(&p.x[a0].x);
  const Aos4 x{_mm256_add_pd(x0.f0, _mm256_mul_pd(v.f0, dtv)), _mm256_add_pd(x0.f1, _mm256_mul_pd(v.f1, dtv)),
               _mm256_add_pd(x0.f2, _mm256_mul_pd(v.f2, dtv))};
  store_aos4(&p.x[a0].x, x);
  const Aos4 L = repeat(lo.x, lo.y, lo.z), H = repeat(hi.x, hi.y, hi.z);
  const auto inside = [](__m256d c, __m256d l, __m256d u) {
    return _mm256_and_pd(_mm256_cmp_pd(c, l, _CMP_GE_OQ), _mm256_cmp_pd(c, u, _CMP_LE_OQ));
  };
  const __m256d in = _mm256_and_pd(_mm256_and_pd(inside(x.f0, L.f0, H.f0), inside(x.f1, L.f1, H.f1)),
                                   inside(x.f2, L.f2, H.f2));
  if (_mm256_movemask_pd(in) != 0xf)
    for (long a = a0; a < a0 + 4; ++a) {
      const Vec3& q = p.x[a];
      if (!(q.x >= lo.x && q.x <= hi.x && q.y >= lo.y && q.y <= hi.y && q.z >= lo.z && q.z <= hi.z))
        first_bad = std::min(first_bad, a);
    }
  const Aos4 r = load_aos4(&x_build[a0].x);
  const Soa4 d = to_soa({_mm256_sub_pd(x.f0, r.f0), _mm256_sub_pd(x.f1, r.f1), _mm256_sub_pd(x.f2, r.f2)});
  const __m256d a2 = avx2::norm2(d.x, d.y, d.z);
  if (!moves.refine) {
    moves.amax = _mm256_max_pd(a2, moves.amax);  // NaN in a2: the second operand
    return;
  }
  _mm256_storeu_pd(moves.a2 + e, a2);
  _mm256_storeu_pd(moves.b2 + e, avx2::norm2(_mm256_sub_pd(d.x, _mm256_set1_pd(moves.u.x)),
                                             _mm256_sub_pd(d.y, _mm256_set1_pd(moves.u.y)),
                                             _mm256_sub_pd(d.z, _mm256_set1_pd(moves.u.z))));
}
#else
constexpr bool kEight = false;
constexpr int kLanes = 0;
#endif

}  // namespace pastemix::model::kick
