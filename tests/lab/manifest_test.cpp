// SPDX-License-Identifier: MIT
#include "lab/manifest.h"

#include <doctest/doctest.h>

#include "base/error.h"
#include "lab/ingest/slump.h"
#include "tests/input_error.h"

using namespace pastemix;
using namespace pastemix::lab;

namespace {
std::string error_of(const std::string& units_toml) {
  const Params p = Params::parse("[units]\n" + units_toml, "m.toml");
  return pastemix::test::input_error_of(
      [&] {
        ColumnUnits::from_manifest(slump_columns(), p.table("units"));
        p.finish();
      },
      "no error");
}
const std::string kGood =
    "H_mm = \"mm\"\nD_mm = \"mm\"\npaste_density_kg_m3 = \"kg/m3\"\nslump_mm = \"cm\"\nyield_stress_Pa = \"Pa\"\n"
    "yield_stress_mean_Pa = \"kPa\"\n";
}  // namespace

TEST_CASE("manifest units: known units give SI factors") {
  const Params p = Params::parse("[units]\n" + kGood, "m.toml");
  const ColumnUnits u = ColumnUnits::from_manifest(slump_columns(), p.table("units"));
  CHECK(u.factor("slump_mm") == doctest::Approx(0.01));
  CHECK(u.factor("yield_stress_mean_Pa") == doctest::Approx(1000.0));
  CHECK(u.unit("H_mm") == "mm");
  CHECK_NOTHROW(p.finish());
}

TEST_CASE("manifest units: unknown unit, wrong dimension, missing column, unknown column name the line") {
  std::string bad = kGood;
  bad.replace(bad.find("\"cm\""), 4, "\"furlong\"");
  CHECK(error_of(bad).find("m.toml:5: key 'slump_mm': unknown unit 'furlong'") == 0);
  bad = kGood;
  bad.replace(bad.find("\"cm\""), 4, "\"kg\"");
  CHECK(error_of(bad).find("m.toml:5: key 'slump_mm': unit 'kg' converts to kg") == 0);
  bad = kGood;
  bad.erase(bad.find("slump_mm"), std::string("slump_mm = \"cm\"\n").size());
  CHECK(error_of(bad).find("m.toml:1: key 'slump_mm': no unit given") == 0);
  CHECK(error_of(kGood + "slumpp_mm = \"mm\"\n").find("m.toml:8: key 'slumpp_mm': unknown key") == 0);
}

TEST_CASE("manifest: a folder without manifest.toml is an input error") {
  CHECK_THROWS_WITH_AS(Manifest::load("/nonexistent-pastemix-dir"), doctest::Contains("manifest.toml"), InputError);
}
