// SPDX-License-Identifier: MIT
#include "lab/ingest/mixing_program.h"

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;

TEST_CASE("mixing programme: each case's PSD is its single sieve interval (Table 3.1)") {
  auto cases = ingest_mixing_program(CsvTable::read(test::source_path("datasets/thesis/mixing_tests_program.csv")),
                                     ColumnUnits::defaults(mixing_program_columns()));
  REQUIRE(cases.size() == 7);
  CHECK(cases[0].psd.intervals.size() == 1);
  CHECK(cases[0].psd.d_min() == doctest::Approx(2.5e-3));
  CHECK(cases[0].psd.d_max() == doctest::Approx(5.0e-3));
  CHECK(cases[3].psd.d_min() == doctest::Approx(5.0e-3));
  CHECK(cases[4].psd.d_max() == doctest::Approx(9.5e-3));
  CHECK(cases[6].falling_height == doctest::Approx(0.75));
  CHECK(cases[0].solids_fraction == doctest::Approx(0.70));
  // 1000 g of case-1 rock: 10^4+ particles, all inside 2.5-5 mm, reproducible by seed.
  const auto d = generate_diameters(cases[0].psd, 1.0, 2760.0, 3);
  CHECK(d.size() > 10000);
  for (double x : d) REQUIRE((x >= 2.5e-3 && x <= 5.0e-3));
  CHECK(generate_diameters(cases[0].psd, 1.0, 2760.0, 3) == d);
}

TEST_CASE("mixing programme: inverted sieve range and duplicate case are input errors") {
  const std::string h = "case,d_wr_min_mm,d_wr_max_mm,falling_height_cm,paste_solids_content_percent\n";
  auto run = [&](const std::string& rows) {
    return ingest_mixing_program(CsvTable::parse(h + rows, "m.csv"), ColumnUnits::defaults(mixing_program_columns()));
  };
  CHECK_THROWS_WITH_AS(run("1,5,2.5,15,70\n"), doctest::Contains("m.csv:2: column 'd_wr_max_mm'"), InputError);
  CHECK_THROWS_WITH_AS(run("1,2.5,5,15,70\n1,2.5,5,15,70\n"), doctest::Contains("m.csv:3: column 'case'"), InputError);
}
