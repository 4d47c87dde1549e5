// SPDX-License-Identifier: MIT
#include "base/csv.h"

#include <doctest/doctest.h>

#include "base/error.h"

using pastemix::CsvTable;
using pastemix::InputError;
using pastemix::Range;

TEST_CASE("csv: parses quoted cells, CRLF and keeps line numbers") {
  auto t = CsvTable::parse("a,b,note\r\n1,2.5,\"x, \"\"y\"\"\"\r\n\n3,4e-3,\"multi\nline\"\n5,6,z\n", "t.csv");
  REQUIRE(t.rows().size() == 3);
  CHECK(t.text(t.rows()[0], "note") == "x, \"y\"");
  CHECK(t.number(t.rows()[1], "b") == doctest::Approx(4e-3));
  CHECK(t.rows()[1].line == 4);
  CHECK(t.rows()[2].line == 6);  // the quoted newline counts
}

TEST_CASE("csv: errors name file, line and column") {
  auto t = CsvTable::parse("a,b\n1,x\n-2,3\n,4\n", "bad.csv");
  CHECK_THROWS_WITH_AS(t.number(t.rows()[0], "b"), "bad.csv:2: column 'b': expected a number, got 'x'", InputError);
  CHECK_THROWS_WITH_AS(t.number(t.rows()[1], "a", Range::positive),
                       "bad.csv:3: column 'a': expected a positive number, got '-2'", InputError);
  CHECK_THROWS_WITH_AS(t.number(t.rows()[2], "a"), "bad.csv:4: column 'a': expected a number, the cell is empty",
                       InputError);
  CHECK_FALSE(t.optional_number(t.rows()[2], "a").has_value());
  CHECK_THROWS_WITH_AS(t.number(t.rows()[0], "c"), "bad.csv:1: column 'c': required column is missing from the header",
                       InputError);
}

TEST_CASE("csv: NaN, inf, ragged rows, duplicate and empty headers are rejected") {
  auto t = CsvTable::parse("a\nnan\ninf\n1.5.2\n", "n.csv");
  CHECK_THROWS_AS(t.number(t.rows()[0], "a"), InputError);
  CHECK_THROWS_AS(t.number(t.rows()[1], "a"), InputError);
  CHECK_THROWS_AS(t.number(t.rows()[2], "a"), InputError);
  CHECK_THROWS_WITH_AS(CsvTable::parse("a,b\n1,2\n3\n", "r.csv"), "r.csv:3: expected 2 cells (as in the header), found 1",
                       InputError);
  CHECK_THROWS_WITH_AS(CsvTable::parse("a,a\n1,2\n", "d.csv"), "d.csv:1: column 'a': duplicate column name in the header",
                       InputError);
  CHECK_THROWS_WITH_AS(CsvTable::parse("", "e.csv"), "e.csv: file is empty (expected a header row)", InputError);
  CHECK_THROWS_WITH_AS(CsvTable::parse("a,b\n", "h.csv"), "h.csv: file has a header but no data rows", InputError);
  CHECK_THROWS_WITH_AS(CsvTable::parse("a\n\"open\n", "q.csv"), "q.csv:2: unterminated quoted field", InputError);
}

TEST_CASE("csv: unknown columns are caught when only known ones are allowed") {
  auto t = CsvTable::parse("a,bb\n1,2\n", "u.csv");
  CHECK_THROWS_WITH_AS(t.require_only_columns({"a", "b"}), "u.csv:1: column 'bb': unknown column (expected only: a, b)",
                       InputError);
}

TEST_CASE("csv: integer cells") {
  auto t = CsvTable::parse("k\n3\n3.5\n", "i.csv");
  CHECK(t.integer(t.rows()[0], "k") == 3);
  CHECK_THROWS_AS(t.integer(t.rows()[1], "k"), InputError);
}
