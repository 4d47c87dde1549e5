// SPDX-License-Identifier: MIT
// The blocked kick's eight-at-a-time forms (model/kick_block.h, model/simd_vec3.h; four at a time with AVX2
// alone, model/simd_avx2.h): the transposes move every
// value unchanged, and velocity8, spins8 and drift8 give, bit for bit, what the one-sphere-at-a-time kick gives
// (World::kick_velocity_twice, drift_one, the displacements' squares), with a stray and a NaN particle caught.
#include "model/kick_block.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace pastemix;
using namespace pastemix::model;

namespace {

// (maybe_unused: a build without vector lanes runs none of the tests that use these.)
[[maybe_unused]] bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
[[maybe_unused]] bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

[[maybe_unused]] Particles random_particles(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles p;
  p.enable_rotation();
  for (int a = 0; a < n; ++a) {
    p.add(0, 1e-3 * (1.5 + u(rng)), 2650.0, {0.05 + 0.02 * u(rng), 0.05 + 0.02 * u(rng), 0.05 + 0.02 * u(rng)},
          {u(rng), u(rng), u(rng)}, {50 * u(rng), 50 * u(rng), 50 * u(rng)});
    p.f[a] = {1e-3 * u(rng), 1e-3 * u(rng), 1e-3 * u(rng)};
    p.torque[a] = {1e-7 * u(rng), 1e-7 * u(rng), 1e-7 * u(rng)};
    p.rolling_capacity[a] = a % 3 == 0 ? 0.0 : 1e-8 * (1.0 + u(rng));
  }
  return p;
}

}  // namespace

#if defined(__AVX512F__)
constexpr int kW = 8;  // the blocked kick's lanes
void velocity_w(Particles& p, const Vec3& g, double h, long a0) { kick::velocity8(p, g, h, a0); }
void spins_w(const Particles& p, double h, kick::SpinBlock& b, int e, long a0) { kick::spins8(p, h, b, e, a0); }
void drift_w(Particles& p, const Vec3* xb, const kick::SpinBlock& b, int e, long a0, double dt, const Vec3& lo,
             const Vec3& hi, long& bad, kick::Moves& m) {
  kick::drift8(p, xb, b, e, a0, dt, lo, hi, bad, m);
}
#elif defined(PASTEMIX_AVX2_LANES)
constexpr int kW = 4;
void velocity_w(Particles& p, const Vec3& g, double h, long a0) { kick::velocity4(p, g, h, a0); }
void spins_w(const Particles& p, double h, kick::SpinBlock& b, int e, long a0) { kick::spins4(p, h, b, e, a0); }
void drift_w(Particles& p, const Vec3* xb, const kick::SpinBlock& b, int e, long a0, double dt, const Vec3& lo,
             const Vec3& hi, long& bad, kick::Moves& m) {
  kick::drift4(p, xb, b, e, a0, dt, lo, hi, bad, m);
}

TEST_CASE("kick block: the four-lane transposes and layouts move every value unchanged") {
  std::vector<Vec3> v(4), back(4);
  for (int a = 0; a < 4; ++a) v[a] = {a + 0.125, -a - 0.25, 100.0 * a + 0.5};
  const avx2::Soa4 s = avx2::to_soa(avx2::load_aos4(&v[0].x));
  alignas(32) double x[4], y[4], z[4];
  _mm256_store_pd(x, s.x), _mm256_store_pd(y, s.y), _mm256_store_pd(z, s.z);
  for (int a = 0; a < 4; ++a) {
    CHECK(x[a] == v[a].x);
    CHECK(y[a] == v[a].y);
    CHECK(z[a] == v[a].z);
  }
  avx2::store_aos4(&back[0].x, avx2::to_aos(s));
  for (int a = 0; a < 4; ++a) CHECK(same_bits(back[a], v[a]));
  std::vector<Vec3> spv(4), rpv(4);
  avx2::store_aos4(&spv[0].x, avx2::spread(_mm256_setr_pd(0, 1, 2, 3)));
  avx2::store_aos4(&rpv[0].x, avx2::repeat(1.5, 2.5, 3.5));
  for (int a = 0; a < 4; ++a) {
    CHECK(same_bits(spv[a], Vec3{double(a), double(a), double(a)}));
    CHECK(same_bits(rpv[a], Vec3{1.5, 2.5, 3.5}));
  }
}
#endif

#if defined(__AVX512F__)
TEST_CASE("kick block: the transposes and layouts move every value unchanged") {
  std::vector<Vec3> v(8), back(8);
  for (int a = 0; a < 8; ++a) v[a] = {a + 0.125, -a - 0.25, 100.0 * a + 0.5};
  const simd::Soa8 s = simd::to_soa(simd::load_aos8(v.data()));
  alignas(64) double x[8], y[8], z[8];
  _mm512_store_pd(x, s.x), _mm512_store_pd(y, s.y), _mm512_store_pd(z, s.z);
  for (int a = 0; a < 8; ++a) {
    CHECK(x[a] == v[a].x);
    CHECK(y[a] == v[a].y);
    CHECK(z[a] == v[a].z);
  }
  simd::store_aos8(back.data(), simd::to_aos(s));
  for (int a = 0; a < 8; ++a) CHECK(same_bits(back[a], v[a]));
  // spread: particle a's scalar at its three components; repeat: the same Vec3 at every particle.
  const simd::Aos8 sp = simd::spread(_mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7));
  const simd::Aos8 rp = simd::repeat({1.5, 2.5, 3.5});
  std::vector<Vec3> spv(8), rpv(8);
  simd::store_aos8(spv.data(), sp);
  simd::store_aos8(rpv.data(), rp);
  for (int a = 0; a < 8; ++a) {
    CHECK(same_bits(spv[a], Vec3{double(a), double(a), double(a)}));
    CHECK(same_bits(rpv[a], Vec3{1.5, 2.5, 3.5}));
  }
}
#endif

#if defined(__AVX512F__) || defined(PASTEMIX_AVX2_LANES)

TEST_CASE("kick block: the blocked lanes (velocity8/4, spins8/4, drift8/4) give the one-at-a-time kick's bits") {
  const Vec3 g{0.0, 0.0, -9.81}, lo{0.02, 0.02, 0.02}, hi{0.08, 0.08, 0.08};
  const double h = 4.5e-6, dt = 9e-6;
  for (bool refine : {false, true}) {
    Particles p = random_particles(refine ? 11 : 12, 24), q = p;
    p.x[13].x = 0.0801 - p.v[13].x * dt;           // leaves the domain in this drift
    if (!refine) p.x[10].y = std::numeric_limits<double>::quiet_NaN();  // a NaN is outside too
    q.x[13] = p.x[13], q.x[10] = p.x[10];
    std::vector<Vec3> x_build(24);
    for (int a = 0; a < 24; ++a) x_build[a] = p.x[a] + Vec3{1e-5 * a, -2e-5, 3e-6};
    x_build[2] = p.x[2] + Vec3{0.0, 0.0, 0.5};  // the largest displacement, in the NaN one's lane (10 = 8 + 2)
    const Vec3 u{1e-5, 0.0, -4e-5};
    kick::SpinBlock b{}, c{};
    double a2[24] = {}, b2[24] = {};
    kick::Moves moves{refine, u, a2, b2};
    long bad = std::numeric_limits<long>::max();
    for (int e = 0; e < 24; e += kW) velocity_w(p, g, h, e), spins_w(p, h, b, e, e);
    for (int e = 0; e < 24; e += kW) drift_w(p, x_build.data(), b, e, e, dt, lo, hi, bad, moves);
    // The same, one sphere at a time, as world.cpp writes it.
    long bad_ref = std::numeric_limits<long>::max();
    double amax_ref = 0.0;
    for (int a = 0; a < 24; ++a) {
      const Vec3 dv = (q.f[a] * q.inv_mass[a] + g) * h;
      Vec3 v = q.v[a];
      v += dv;
      v += dv;
      q.v[a] = v;
      const Vec3 dw = q.torque[a] * (h * q.inv_inertia[a]);
      c.wx[a] = q.omega[a].x, c.wy[a] = q.omega[a].y, c.wz[a] = q.omega[a].z;
      c.dx[a] = dw.x, c.dy[a] = dw.y, c.dz[a] = dw.z;
      c.stop[a] = h * q.rolling_capacity[a] * q.inv_inertia[a];
      c.cap[a] = q.rolling_capacity[a];
      q.omega[a] = {c.wx[a], c.wy[a], c.wz[a]};
      q.x[a] += q.v[a] * dt;
      const Vec3& x = q.x[a];
      if (!(x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z))
        bad_ref = std::min<long>(bad_ref, a);
      const Vec3 dx = x - x_build[a];
      if (refine) {
        CHECK(same_bits(a2[a], norm2(dx)));
        CHECK(same_bits(b2[a], norm2(dx - u)));
      }
      amax_ref = std::max(amax_ref, norm2(dx));
    }
    for (int a = 0; a < 24; ++a) {
      CHECK(same_bits(p.v[a], q.v[a]));
      CHECK(same_bits(p.x[a], q.x[a]));
      CHECK(same_bits(p.omega[a], q.omega[a]));
      CHECK(same_bits(b.dx[a], c.dx[a]));
      CHECK(same_bits(b.dy[a], c.dy[a]));
      CHECK(same_bits(b.dz[a], c.dz[a]));
      CHECK(same_bits(b.stop[a], c.stop[a]));
      CHECK(same_bits(b.cap[a], c.cap[a]));
    }
    CHECK(bad == (refine ? 13 : 10));
    CHECK(bad_ref == bad);
    if (!refine) {
      CHECK(same_bits(moves.largest(), amax_ref));  // the NaN one skipped, as std::max does
      CHECK(amax_ref > 0.2);
    }
  }
}
#else
TEST_CASE("kick block: without AVX2 the kick goes one sphere at a time") { CHECK(kick::kLanes == 0); }
#endif
