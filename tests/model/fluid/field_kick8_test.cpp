// SPDX-License-Identifier: MIT
// FluidField's eight-at-a-time kicks (kick8_linear, kick8_affine; kick4_* with AVX2 alone; the blocked kick of
// world.cpp): both half
// kicks of eight particles give, bit for bit, what kick() gives each one at a time, in a Newtonian fluid (the
// linear branch) and in a Bingham paste at rest and sliding (the affine branch, its rest resistance holding
// some spheres); a group with a sphere outside, on another branch or too fast for the affine one is declined
// and left unchanged.
#include "model/fluid/field.h"

#include <doctest/doctest.h>

#include <cstring>
#include <random>
#include <vector>

using namespace pastemix::model;
using namespace pastemix::model::fluid;

namespace {

// (maybe_unused: a build without vector lanes runs none of the tests that use these.)
[[maybe_unused]] bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// 64 spheres of 2-4 mm inside a 10 x 10 x 5 cm region (the first and the last eight of them from `out`:
// above it).
[[maybe_unused]] Particles rock(std::uint64_t seed, double speed, double force) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles p;
  for (int k = 0; k < 64; ++k) {
    const double z = k >= 56 ? 0.08 : 0.025 + 0.015 * u(rng);
    p.add(0, 0.003 + 0.001 * u(rng), 2700, {0.05 + 0.04 * u(rng), 0.05 + 0.04 * u(rng), z},
          {speed * u(rng), speed * u(rng), speed * u(rng)}, {});
    p.f[static_cast<std::size_t>(k)] = {force * u(rng), force * u(rng), force * u(rng)};
  }
  return p;
}

[[maybe_unused]] FluidRegion region(bool paste) {
  FluidRegion reg;
  reg.x_min = reg.y_min = 0, reg.x_max = reg.y_max = 0.1, reg.z_bottom = 0, reg.z_surface0 = 0.05;
  if (paste) {
    reg.law = BinghamDedegil::Params{1843, 20, 0.7};
    reg.curve = {pastemix::drag::CurveId::published_4_19, {}};
  } else {
    reg.law = NewtonianStokes::Params{1000, 1e-3};
  }
  return reg;
}

#if defined(__AVX512F__)
constexpr int kW = 8;  // the field's lanes
bool lanes_linear(const FluidField& f, long a0, Particles& q, const Vec3& g, double h) { return f.kick8_linear(a0, q, g, h); }
bool lanes_affine(const FluidField& f, long a0, Particles& q, const Vec3& g, double h) { return f.kick8_affine(a0, q, g, h); }
#elif defined(PASTEMIX_AVX2_LANES)
constexpr int kW = 4;
bool lanes_linear(const FluidField& f, long a0, Particles& q, const Vec3& g, double h) { return f.kick4_linear(a0, q, g, h); }
bool lanes_affine(const FluidField& f, long a0, Particles& q, const Vec3& g, double h) { return f.kick4_affine(a0, q, g, h); }
#endif

#if defined(__AVX512F__) || defined(PASTEMIX_AVX2_LANES)
// Groups of kW (eight, or four with AVX2 alone): the field's linear or affine form against kick() twice per
// sphere. Returns how many groups were kicked at once.
int check(bool paste, double speed, double force) {
  const double dt = 2e-5, h = 0.5 * dt;
  const Vec3 g{0, 0, -9.81};
  Particles p = rock(paste ? 3 : 4, speed, force);
  FluidField field({region(paste)});
  field.set_step(dt, g);
  field.update(p);
  int eight = 0;
  for (long a0 = 0; a0 < 64; a0 += kW) {
    Particles q = p;
    const bool done = paste ? lanes_affine(field, a0, q, g, h) : lanes_linear(field, a0, q, g, h);
    // The other form declines a group that is not its own.
    Particles r = p;
    CHECK_FALSE((paste ? lanes_linear(field, a0, r, g, h) : lanes_affine(field, a0, r, g, h)));
    for (long a = a0; a < a0 + kW; ++a) {
      const auto i = static_cast<std::size_t>(a);
      CHECK(same_bits(r.v[i], p.v[i]));
      if (!done) {
        CHECK(same_bits(q.v[i], p.v[i]));  // declined: unchanged
        continue;
      }
      REQUIRE(field.inside(a));
      const Vec3 F = p.f[i] + g * p.mass[i];
      const Vec3 v1 = field.kick(a, p.v[i], F, p.mass[i], p.radius[i], h, g);
      const Vec3 v2 = field.kick(a, v1, F, p.mass[i], p.radius[i], h, g);
      CHECK(same_bits(q.v[i], v2));
    }
    eight += done;
  }
  return eight;
}

#endif

}  // namespace

#if defined(__AVX512F__) || defined(PASTEMIX_AVX2_LANES)
TEST_CASE("fluid field: eight (four) spheres' kicks at once give kick()'s bits, and a mixed group is declined") {
  const int inside = 56 / kW;  // groups wholly inside (spheres 56 .. 63 are above the region)
  // Newtonian: every group inside is linear (the last ones are above the region: declined).
  CHECK(check(false, 0.3, 1e-3) == inside);
  // Paste at rest under small forces (the rest resistance holds most) and sliding slowly: affine.
  CHECK(check(true, 0.0, 1e-4) == inside);
  CHECK(check(true, 0.01, 1e-3) == inside);
  // Too fast for the affine branch, before the kick or after it (a large force from rest): every group
  // declined (kick() takes its general branch).
  CHECK(check(true, 3.0, 1e-3) == 0);
  CHECK(check(true, 0.0, 30.0) == 0);
}
#endif
