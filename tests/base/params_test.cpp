// SPDX-License-Identifier: MIT
#include "base/params.h"

#include <doctest/doctest.h>

#include "base/error.h"

using pastemix::InputError;
using pastemix::Params;
using pastemix::Range;

TEST_CASE("params: typed reads, defaults and sub-tables") {
  auto p = Params::parse("dt = 1e-5\nseed = 7\nname = \"x\"\ng = [0, 0, -9.81]\n[box]\nsize = [0.2, 0.165, 0.25]\n"
                         "[[material]]\nname = \"rock\"\n[[material]]\nname = \"steel\"\n",
                         "s.toml");
  CHECK(p.number("dt", Range::positive) == doctest::Approx(1e-5));
  CHECK(p.integer("seed") == 7);
  CHECK(p.number_or("missing", 2.0) == 2.0);
  CHECK(p.string("name") == "x");
  CHECK(p.numbers("g", 3)[2] == doctest::Approx(-9.81));
  CHECK(p.table("box").numbers("size", 3)[1] == doctest::Approx(0.165));
  auto mats = p.tables("material");
  REQUIRE(mats.size() == 2);
  CHECK(mats[0].string("name") == "rock");
  CHECK(mats[1].string("name") == "steel");
  CHECK_NOTHROW(p.finish());
}

TEST_CASE("params: an unread key is an error with its line, also in sub-tables") {
  auto p = Params::parse("dt = 1e-5\ntme_end = 2\n", "s.toml");
  p.number("dt");
  CHECK_THROWS_WITH_AS(p.finish(),
                       "s.toml:2: key 'tme_end': unknown key (nothing reads it; check the spelling and the table it is in)",
                       InputError);
  auto q = Params::parse("[box]\nsize = 1\nsixe = 2\n", "b.toml");
  q.table("box").number("size");
  CHECK_THROWS_WITH_AS(q.finish(),
                       "b.toml:3: key 'sixe': unknown key (did you mean 'size'?) (nothing reads it; check the spelling and the table it is in)",
                       InputError);
}

TEST_CASE("params: wrong types, ranges, choices and syntax errors name the line") {
  auto p = Params::parse("dt = \"fast\"\nr = -1\nlaw = \"hooke\"\n", "w.toml");
  CHECK_THROWS_WITH_AS(p.number("dt"), "w.toml:1: key 'dt': expected a number, got a value that is not a number",
                       InputError);
  CHECK_THROWS_WITH_AS(p.number("r", Range::positive), "w.toml:2: key 'r': expected a positive number, got -1",
                       InputError);
  CHECK_THROWS_WITH_AS(p.choice("law", {"hertz_mindlin", "linear"}),
                       "w.toml:3: key 'law': 'hooke' is not one of: hertz_mindlin, linear", InputError);
  CHECK_THROWS_WITH_AS(p.number("absent"), "w.toml:1: key 'absent': required key is missing (expected a number)",
                       InputError);
  try {
    Params::parse("a = 1\nb = = 2\n", "syn.toml");
    FAIL("no throw");
  } catch (const InputError& e) {
    CHECK(e.file() == "syn.toml");
    CHECK(e.line() == 2);
  }
}
