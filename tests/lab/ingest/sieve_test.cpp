// SPDX-License-Identifier: MIT
#include "lab/ingest/sieve.h"

#include <cmath>

#include <doctest/doctest.h>

#include "base/error.h"
#include "base/units.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;

namespace {
SieveResult example(double cut = 0.0) {
  return ingest_sieve(CsvTable::read(test::source_path("tests/lab/data/sieve_example.csv")),
                      ColumnUnits::defaults(sieve_columns()), cut);
}
SieveResult parse(const std::string& rows) {
  return ingest_sieve(CsvTable::parse("sieve_mm,mass_retained_g\n" + rows, "s.csv"),
                      ColumnUnits::defaults(sieve_columns()));
}
}  // namespace

TEST_CASE("sieve: masses retained -> intervals, mass fractions, cumulative passing, pan excluded") {
  const SieveResult r = example();
  REQUIRE(r.psd.intervals.size() == 5);
  CHECK(r.total_mass == doctest::Approx(0.3005));
  CHECK(r.pan_fraction == doctest::Approx(2.0 / 300.5));
  CHECK(r.psd.intervals[0].d_min == doctest::Approx(0.315e-3));
  CHECK(r.psd.intervals[0].d_max == doctest::Approx(1.18e-3));
  CHECK(r.psd.intervals[0].mass_fraction == doctest::Approx(28.5 / 298.5));
  CHECK(r.psd.intervals[4].mass_fraction == doctest::Approx(90.0 / 298.5));
  REQUIRE(r.sieves.size() == 6);
  CHECK(r.passing.front() == doctest::Approx(2.0 / 300.5));  // through 0.315 mm: the pan only
  CHECK(r.passing[2] == doctest::Approx((2.0 + 28.5 + 45.0) / 300.5));  // through 2.0 mm
  CHECK(r.passing.back() == doctest::Approx(1.0));  // through the top sieve: everything
  CHECK(r.warnings.size() == 1);  // the pan
}

TEST_CASE("sieve: a cut drops the finest intervals and renormalises") {
  const SieveResult r = example(1.18e-3);
  REQUIRE(r.psd.intervals.size() == 4);
  CHECK(r.psd.d_min() == doctest::Approx(1.18e-3));
  CHECK(r.psd.intervals[0].mass_fraction == doctest::Approx(45.0 / 270.0));
  CHECK_THROWS_AS(example(8.0e-3), InputError);
}

TEST_CASE("sieve -> generator: 10^4+ particles meet each interval's mass fraction within 1 %, seeded") {
  const SieveResult r = example(1.18e-3);  // the thesis's PSD 4 range, 1.18-8 mm
  const double rho = 2760.0;
  const auto d = generate_diameters(r.psd, 1.0, rho, 42);  // 1 kg
  REQUIRE(d.size() >= 10000);
  double all = 0.0;
  std::vector<double> mass(r.psd.intervals.size(), 0.0);
  for (double x : d) {
    const double m = units::pi / 6.0 * rho * x * x * x;
    all += m;
    for (std::size_t k = 0; k < mass.size(); ++k)
      if (x >= r.psd.intervals[k].d_min && x <= r.psd.intervals[k].d_max) {
        mass[k] += m;
        break;
      }
  }
  for (std::size_t k = 0; k < mass.size(); ++k)
    CHECK(mass[k] / all == doctest::Approx(r.psd.intervals[k].mass_fraction).epsilon(0.01));
  CHECK(generate_diameters(r.psd, 1.0, rho, 42) == d);
  CHECK(generate_diameters(r.psd, 1.0, rho, 43) != d);
}

TEST_CASE("sieve: bad stacks are input errors with file:line") {
  CHECK_THROWS_WITH_AS(parse("8,5\n5,10\n"), doctest::Contains("s.csv:2: column 'mass_retained_g'"), InputError);
  CHECK_THROWS_WITH_AS(parse("8,0\n5,10\n5,3\n"), doctest::Contains("s.csv:4: column 'sieve_mm'"), InputError);
  CHECK_THROWS_WITH_AS(parse("8,0\n5,-1\n"), doctest::Contains("s.csv:3: column 'mass_retained_g'"), InputError);
  CHECK_THROWS_AS(parse("8,0\n5,0\n"), InputError);  // no mass
  CHECK_THROWS_AS(parse("8,0\n0,4\n"), InputError);  // only a pan
}
