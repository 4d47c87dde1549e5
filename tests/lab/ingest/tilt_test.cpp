// SPDX-License-Identifier: MIT
#include "lab/ingest/tilt.h"

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;

TEST_CASE("tilt: thesis Table 4.7 gives mean static friction 0.3407 (+-0.0005)") {
  auto r = ingest_tilt(CsvTable::read(test::source_path("datasets/thesis/tilt_tests.csv")),
                       ColumnUnits::defaults(tilt_columns()));
  const Parameter& mu = r.parameters.at(0);
  CHECK(mu.key == "steel_ball.static_friction");
  CHECK(std::abs(mu.value - 0.3407) <= 0.0005);
  CHECK(mu.n == 5);
  CHECK(r.warnings.empty());
}

TEST_CASE("tilt: a lift height not below the plate length is an input error") {
  auto t = CsvTable::parse("trial,L_cm_as_printed,H_l_cm_as_printed\n1,600,205\n2,600,600\n", "t.csv");
  CHECK_THROWS_WITH_AS(ingest_tilt(t, ColumnUnits::defaults(tilt_columns())),
                       doctest::Contains("t.csv:3: column 'H_l_cm_as_printed'"), InputError);
}
