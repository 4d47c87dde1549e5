// SPDX-License-Identifier: MIT
#include "lab/ingest/slump.h"

#include <cmath>

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;

namespace {
IngestResult thesis_slump() {
  return ingest_slump(CsvTable::read(test::source_path("datasets/thesis/slump_tests.csv")),
                      ColumnUnits::defaults(slump_columns()));
}
const char* kHeader = "trial,H_mm,D_mm,paste_density_kg_m3,slump_mm\n";
}  // namespace

TEST_CASE("slump: Pashias-Boger inverse, Lambert W_-1 closed form agrees with the bracketed root to 1e-9") {
  for (int k = 1; k < 1000; ++k) {
    const double s = static_cast<double>(k) / 1000.0;  // S' over (0, 1)
    const double closed = pashias_tau_lambert(s), root = pashias_tau_bracketed(s);
    REQUIRE(closed > 0.0);
    REQUIRE(closed < 0.5);
    CHECK(std::abs(closed - root) <= 1e-9 * root);
    CHECK(pashias_slump(closed) == doctest::Approx(s).epsilon(1e-12));  // and it solves the forward relation
  }
  CHECK_NOTHROW(pashias_tau(0.67));
}

TEST_CASE("slump: thesis Table 4.5 gives 136.6, 132.7, 144.6 Pa (+-0.1), mean 138.0") {
  const IngestResult r = thesis_slump();
  const Parameter& p = r.parameters.at(0);
  CHECK(p.key == "paste.yield_stress");
  REQUIRE(p.trials.size() == 3);
  CHECK(std::abs(p.trials[0] - 136.6) <= 0.1);
  CHECK(std::abs(p.trials[1] - 132.7) <= 0.1);
  CHECK(std::abs(p.trials[2] - 144.6) <= 0.1);
  CHECK(std::abs(p.value - 138.0) <= 0.05);
  CHECK(p.n == 3);
  CHECK(p.unit == "Pa");
  CHECK(r.parameters.at(1).value == doctest::Approx(1843.0));
}

TEST_CASE("slump: warns that the printed values are ~1.2 % lower, consistent with H = 0.150 m") {
  const IngestResult r = thesis_slump();
  REQUIRE(!r.warnings.empty());
  const std::string& m = r.warnings[0].message;
  CHECK(m.find("1.2 % lower") != std::string::npos);
  CHECK(m.find("H = 0.150 m") != std::string::npos);
  CHECK(m.find("0.152 m") != std::string::npos);
}

TEST_CASE("slump: printed values that agree within their rounding give no warning") {
  // 136.6 Pa is what slump 102 mm in a 152 mm mould gives at 1843 kg/m3.
  auto t = CsvTable::parse("trial,H_mm,D_mm,paste_density_kg_m3,slump_mm,yield_stress_Pa\n1,152,152,1843,102,136.6\n",
                           "ok.csv");
  CHECK(ingest_slump(t, ColumnUnits::defaults(slump_columns())).warnings.empty());
}

TEST_CASE("slump: S >= H and no slump (tau' >= 0.5) are input errors naming the line and column") {
  auto bad = [](const char* row) {
    auto t = CsvTable::parse(std::string(kHeader) + "1,152,152,1843,102\n" + row, "s.csv");
    try {
      ingest_slump(t, ColumnUnits::defaults(slump_columns()));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(bad("2,152,152,1843,152\n").find("s.csv:3: column 'slump_mm'") == 0);
  CHECK(bad("2,152,152,1843,160\n").find("mould height") != std::string::npos);
  CHECK(bad("2,152,152,1843,0\n").find("no slump") != std::string::npos);
  CHECK(bad("2,152,152,1843,-1\n").find("s.csv:3: column 'slump_mm'") == 0);
}
