// SPDX-License-Identifier: MIT
#include "base/psd.h"

#include <cmath>
#include <stdexcept>

#include <doctest/doctest.h>

#include "base/units.h"

using pastemix::Psd;

namespace {
// The chapter-5 sieve intervals (0.315-8 mm) with illustrative fractions for the test.
Psd five_intervals() {
  return Psd{{{0.315e-3, 1.18e-3, 0.10}, {1.18e-3, 2.0e-3, 0.15}, {2.0e-3, 3.35e-3, 0.20}, {3.35e-3, 5.0e-3, 0.25},
              {5.0e-3, 8.0e-3, 0.30}}};
}
double sphere_mass(double d, double rho) { return pastemix::units::pi / 6.0 * rho * d * d * d; }
}  // namespace

TEST_CASE("psd: generated mass fractions meet the targets within 1 % for 10^4+ particles") {
  Psd psd = five_intervals();
  const double rho = 2760.0, total = 0.3005;
  auto d = pastemix::generate_diameters(psd, total, rho, 7);
  REQUIRE(d.size() > 10000);
  for (const auto& iv : psd.intervals) {
    double m = 0.0, all = 0.0;
    for (double x : d) {
      all += sphere_mass(x, rho);
      if (x >= iv.d_min && x <= iv.d_max) m += sphere_mass(x, rho);
    }
    CHECK(m / all == doctest::Approx(iv.mass_fraction).epsilon(0.01));
  }
}

TEST_CASE("psd: same seed same sizes, other seed other sizes") {
  auto a = pastemix::generate_diameters(five_intervals(), 0.05, 2760.0, 11);
  auto b = pastemix::generate_diameters(five_intervals(), 0.05, 2760.0, 11);
  auto c = pastemix::generate_diameters(five_intervals(), 0.05, 2760.0, 12);
  CHECK(a == b);
  CHECK(a != c);
}

TEST_CASE("psd: cut drops the finest intervals and renormalises") {
  Psd cut = five_intervals().cut_below(2.0e-3);
  REQUIRE(cut.intervals.size() == 3);
  CHECK(cut.d_min() == doctest::Approx(2.0e-3));
  CHECK(cut.intervals[0].mass_fraction == doctest::Approx(0.20 / 0.75));
  CHECK_NOTHROW(cut.check());
  CHECK_THROWS_AS(five_intervals().cut_below(8.0e-3), std::invalid_argument);
}

TEST_CASE("psd: bad distributions are rejected") {
  CHECK_THROWS_AS(Psd{}.check(), std::invalid_argument);
  CHECK_THROWS_AS((Psd{{{2e-3, 1e-3, 1.0}}}.check()), std::invalid_argument);
  CHECK_THROWS_AS((Psd{{{1e-3, 2e-3, 0.5}}}.check()), std::invalid_argument);
  CHECK_THROWS_AS((Psd{{{1e-3, 3e-3, 0.5}, {2e-3, 4e-3, 0.5}}}.check()), std::invalid_argument);
}
