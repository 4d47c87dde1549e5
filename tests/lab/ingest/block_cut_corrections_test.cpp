// SPDX-License-Identifier: MIT
#include "lab/ingest/block_cut_corrections.h"

#include <cmath>

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;

namespace {
BlockCutResult thesis_uncorrected() {
  return ingest_block_cut(CsvTable::read(test::source_path("datasets/thesis/block_cut_masses.csv")),
                          ColumnUnits::defaults(block_cut_columns()),
                          {{2, {3570, "t"}}, {3, {3570, "t"}}, {4, {3488, "t"}}, {5, {3488, "t"}}});
}
const auto kUnits = ColumnUnits::defaults(block_cut_correction_columns());
}  // namespace

TEST_CASE("block cut corrections: Table 3.3 applied separately, within the rounding of its masses") {
  BlockCutResult r = thesis_uncorrected();
  const std::size_t warnings_before = r.warnings.size();
  apply_block_cut_corrections(r, CsvTable::read(test::source_path("datasets/thesis/block_cut_corrections.csv")),
                              kUnits);
  REQUIRE(r.corrected.size() == r.cases.size());
  int applied = 0;
  for (std::size_t c = 0; c < r.cases.size(); ++c)
    for (int b = 0; b < kBlocks; ++b) {
      if (!r.corrected[c].corrected[b]) {
        CHECK(r.corrected[c].M_paste[b] == r.cases[c].M_paste[b]);  // untouched blocks stay as measured
        continue;
      }
      ++applied;
      CHECK(r.corrected[c].M_paste[b] < r.cases[c].M_paste[b]);
      CHECK(r.cases[c].corrected[b] == 0);  // the uncorrected grids stay uncorrected
    }
  CHECK(applied == 30);
  CHECK(r.printed_corrected.n_C == 30);
  CHECK(r.printed_corrected.max_C_error_pp < 0.35);  // the thesis used unrounded masses
  CHECK(r.warnings.size() == warnings_before);       // every row within the propagated mass rounding
  // Case 2 M_111: 0.1347 - 0.1338 = 0.0009 kg of paste left.
  const BlockGrid& g = r.corrected.at(1);
  CHECK(g.M_paste[block_index(1, 1, 1)] == doctest::Approx(0.0009).epsilon(1e-6));
  CHECK(g.C[block_index(1, 1, 1)] == doctest::Approx(0.912).epsilon(0.005));
}

TEST_CASE("block cut corrections: unknown block, duplicates and over-large corrections are input errors") {
  const std::string h = "case,block_id,i,j,layer,M_prime_paste_kg,M_prime_paste_dried_kg\n";
  auto error_of = [&](const std::string& rows) {
    BlockCutResult r = thesis_uncorrected();
    try {
      apply_block_cut_corrections(r, CsvTable::parse(h + rows, "c.csv"), kUnits);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of("9,M_111,1,1,1,0.1,0.07\n").find("c.csv:2: column 'case'") == 0);
  CHECK(error_of("2,M_111,1,1,1,0.1,0.07\n2,M_111,1,1,1,0.1,0.07\n").find("c.csv:3: column 'block_id'") == 0);
  CHECK(error_of("2,M_111,1,1,1,0.5,0.4\n").find("c.csv:2: column 'M_prime_paste_dried_kg'") == 0);
  CHECK(error_of("2,M_111,1,1,1,0.1,0.2\n").find("c.csv:2: column 'M_prime_paste_dried_kg'") == 0);
}
