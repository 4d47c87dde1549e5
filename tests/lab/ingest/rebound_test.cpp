// SPDX-License-Identifier: MIT
#include "lab/ingest/rebound.h"

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;

TEST_CASE("rebound: thesis Table 4.6 gives mean restitution 0.6120 (+-0.0005), printed values agree") {
  auto r = ingest_rebound(CsvTable::read(test::source_path("datasets/thesis/rebound_tests.csv")),
                          ColumnUnits::defaults(rebound_columns()));
  const Parameter& e = r.parameters.at(0);
  CHECK(e.key == "steel_ball.restitution");
  CHECK(std::abs(e.value - 0.6120) <= 0.0005);
  CHECK(e.n == 5);
  CHECK(e.trials.at(0) == doctest::Approx(0.6241).epsilon(1e-3));
  CHECK(r.warnings.empty());
}

TEST_CASE("rebound: a printed value off by more than its rounding is a warning with file:line") {
  auto t = CsvTable::parse("test,steel_ball_diameter_mm,steel_ball_density_kg_m3,falling_height_mm,rebound_height_mm,"
                           "restitution_coefficient\n1,8,8135,100,36,0.61\n",
                           "r.csv");
  auto r = ingest_rebound(t, ColumnUnits::defaults(rebound_columns()));
  REQUIRE(r.warnings.size() == 1);  // sqrt(0.36) = 0.6, printed 0.61
  CHECK(r.warnings[0].where == "r.csv:2");
}

TEST_CASE("rebound: a rebound at or above the drop height is an input error") {
  auto t = CsvTable::parse("test,steel_ball_diameter_mm,steel_ball_density_kg_m3,falling_height_mm,rebound_height_mm\n"
                           "1,8,8135,100,36\n2,8,8135,100,100\n",
                           "r.csv");
  CHECK_THROWS_WITH_AS(ingest_rebound(t, ColumnUnits::defaults(rebound_columns())),
                       doctest::Contains("r.csv:3: column 'rebound_height_mm'"), InputError);
}
