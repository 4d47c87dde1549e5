// SPDX-License-Identifier: MIT
#include "lab/ingest/ingest.h"

#include <doctest/doctest.h>

#include "base/error.h"

using namespace pastemix;
using namespace pastemix::lab;

TEST_CASE("ingest: the rounding tolerance is half a unit of the last printed digit") {
  CHECK(rounding_tolerance("0.612") == doctest::Approx(0.0005));
  CHECK(rounding_tolerance("136") == doctest::Approx(0.5));
  CHECK(rounding_tolerance("100.0") == doctest::Approx(0.05));
  CHECK(rounding_tolerance("1.08e-7") == doctest::Approx(0.005e-7));
  CHECK(rounding_tolerance("5E3") == doctest::Approx(500.0));
}

TEST_CASE("ingest: four significant digits for people") {
  CHECK(format_value(137.97) == "138.0");
  CHECK(format_value(0.61204) == "0.6120");
  CHECK(format_value(1843.0) == "1843");
  CHECK(format_value(0.0) == "0");
}

TEST_CASE("ingest: default units come from the spec, columns are checked both ways") {
  const std::vector<ColumnSpec> specs{{"id", ""}, {"length_mm", "mm"}, {"printed_cm", "cm", false}};
  const ColumnUnits u = ColumnUnits::defaults(specs);
  CHECK(u.factor("length_mm") == doctest::Approx(1e-3));
  CHECK(u.factor("printed_cm") == doctest::Approx(1e-2));
  CHECK_NOTHROW(require_spec_columns(CsvTable::parse("id,length_mm\n1,2\n", "a.csv"), specs));
  CHECK_THROWS_WITH_AS(require_spec_columns(CsvTable::parse("id\n1\n", "a.csv"), specs),
                       doctest::Contains("a.csv:1: column 'length_mm'"), InputError);
  CHECK_THROWS_WITH_AS(require_spec_columns(CsvTable::parse("id,length_mm,extra\n1,2,3\n", "a.csv"), specs),
                       doctest::Contains("a.csv:1: column 'extra': unknown column"), InputError);
}
