// SPDX-License-Identifier: MIT
// PLIC geometry against brute-force quadrature of the cube below a plane.
#include "model/flow/plic.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace pastemix::flow;

namespace {
// Midpoint quadrature on an M^3 lattice of the part of [lo, hi] below n . x = a.
double brute(const std::array<double, 3>& n, double a, const std::array<double, 3>& lo, const std::array<double, 3>& hi,
             int M) {
  long in = 0;
  for (int i = 0; i < M; ++i)
    for (int j = 0; j < M; ++j)
      for (int k = 0; k < M; ++k) {
        const double x = lo[0] + (i + 0.5) / M * (hi[0] - lo[0]), y = lo[1] + (j + 0.5) / M * (hi[1] - lo[1]),
                     z = lo[2] + (k + 0.5) / M * (hi[2] - lo[2]);
        in += n[0] * x + n[1] * y + n[2] * z <= a;
      }
  return static_cast<double>(in) / (static_cast<double>(M) * M * M) * (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
}
}  // namespace

TEST_CASE("plic: the closed-form cube volume agrees with quadrature for random planes (all branches)") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 60; ++t) {
    const std::array<double, 3> n{u(rng), u(rng), u(rng)};
    double lo = 0, hi = 0;
    for (double v : n) (v < 0 ? lo : hi) += v;
    const double a = lo + (hi - lo) * (0.5 + 0.5 * u(rng));
    const double exact = plic::box_fraction(n, a, {0, 0, 0}, {1, 1, 1});
    // A 120^3 lattice resolves the volume to ~1/120 of the plane's area: 2e-2 at most.
    CHECK(exact == doctest::Approx(brute(n, a, {0, 0, 0}, {1, 1, 1}, 120)).epsilon(0).scale(1).epsilon(2e-2));
  }
}

TEST_CASE("plic: axis-aligned and degenerate planes are exact") {
  CHECK(plic::cube_fraction({0, 0, 1}, 0.37) == doctest::Approx(0.37).epsilon(1e-15));
  CHECK(plic::cube_fraction({1, 1, 0}, 0.5) == doctest::Approx(0.125).epsilon(1e-14));
  CHECK(plic::cube_fraction({1, 1, 1}, 1.5) == doctest::Approx(0.5).epsilon(1e-14));
  CHECK(plic::cube_fraction({1, 1, 1}, 0.3) == doctest::Approx(0.3 * 0.3 * 0.3 / 6).epsilon(1e-13));
  // A strip of the cell: the plane z = 0.37 (paste below), the top half of the cell holds none of it.
  CHECK(plic::box_fraction({0, 0, 1}, 0.37, {0, 0, 0.5}, {1, 1, 1}) == 0.0);
  CHECK(plic::box_fraction({0, 0, 1}, 0.37, {0, 0, 0}, {1, 1, 0.25}) == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(plic::box_fraction({1e-13, 0, 1}, 0.37, {0.9, 0, 0}, {1, 1, 1}) == doctest::Approx(0.037).epsilon(1e-10));
}

TEST_CASE("plic: plane_constant inverts the volume to round-off") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), f(0.0, 1.0);
  for (int t = 0; t < 500; ++t) {
    const std::array<double, 3> n{u(rng), u(rng), t % 5 == 0 ? 0.0 : u(rng)};
    const double alpha = f(rng);
    const double a = plic::plane_constant(n, alpha);
    CHECK(std::abs(plic::box_fraction(n, a, {0, 0, 0}, {1, 1, 1}) - alpha) < 1e-13);
  }
}
