// SPDX-License-Identifier: MIT
#include "lab/ingest/block_cut.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>

#include "base/error.h"
#include "lab/ingest/block_id.h"
#include "tests/run_command.h"
#include "tests/input_error.h"

using namespace pastemix;
using namespace pastemix::lab;

namespace {
const std::map<int, KInput> kThesisK{{2, {3570, "t"}}, {3, {3570, "t"}}, {4, {3488, "t"}}, {5, {3488, "t"}}};

std::string thesis_text() {
  std::ifstream in(test::source_path("datasets/thesis/block_cut_masses.csv"));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
BlockCutResult thesis(const std::map<int, KInput>& K = kThesisK) {
  return ingest_block_cut(CsvTable::parse(thesis_text(), "b.csv"), ColumnUnits::defaults(block_cut_columns()), K);
}
// The thesis file with line `line` (1-based) replaced.
std::string with_line(int line, const std::string& text) {
  std::stringstream in(thesis_text());
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n) out += (n == line ? text : l) + "\n";
  return out;
}
std::string error_of(const std::string& csv) {
  return pastemix::test::input_error_of(
      [&] { ingest_block_cut(CsvTable::parse(csv, "b.csv"), ColumnUnits::defaults(block_cut_columns()), kThesisK); },
      "no error");
}
}  // namespace

TEST_CASE("block cut: C of all 180 blocks within 0.1 percentage point of the printed C") {
  const BlockCutResult r = thesis();
  REQUIRE(r.cases.size() == 5);
  int n = 0;
  for (const auto& g : r.cases)
    for (int b = 0; b < kBlocks; ++b) {
      REQUIRE(std::isfinite(g.C_printed[b]));
      CHECK(std::abs(g.C[b] - g.C_printed[b]) * 100.0 <= 0.1);
      ++n;
    }
  CHECK(n == 180);
  CHECK(r.printed.n_C == 180);
  CHECK(r.printed.max_C_error_pp <= 0.1);
}

TEST_CASE("block cut: every finite uncapped printed S within 0.5 % relative (K = 3570 cases 2-3, 3488 cases 4-5)") {
  const BlockCutResult r = thesis();
  int n = 0;
  for (const auto& g : r.cases) {
    if (g.case_id == 1) continue;
    for (int b = 0; b < kBlocks; ++b) {
      if (!std::isfinite(g.S_printed[b]) || g.S_printed[b] == 1.0) continue;  // '/' rows and 100 % (capped)
      REQUIRE(std::isfinite(g.S_raw[b]));
      if (g.S_printed[b] == 0.0) CHECK(g.S_raw[b] == 0.0);
      else CHECK(std::abs(g.S_raw[b] - g.S_printed[b]) / g.S_printed[b] <= 0.005);
      ++n;
    }
  }
  CHECK(n == 40);
  CHECK(r.printed.n_S == 40);
  CHECK(r.printed.max_S_rel_error <= 0.005);
}

TEST_CASE("block cut: capped rows are flagged, agreeing with the printed S_flag") {
  const BlockCutResult r = thesis();
  CHECK(r.printed.n_flag_disagreements == 30);  // the 30 layer-1 blocks printed uncapped above 100 %
  std::stringstream in(thesis_text());
  std::string line;
  std::getline(in, line);
  int capped_rows = 0;
  while (std::getline(in, line)) {
    if (line.find("capped_at_100") == std::string::npos || line[0] == '1') continue;
    const int case_id = line[0] - '0';
    const int i = line[4] - '0', j = line[5] - '0', k = line[6] - '0';  // "c,M_ijk,..."
    const BlockGrid& g = r.cases.at(static_cast<std::size_t>(case_id - 1));
    const int b = block_index(i, j, k);
    CHECK(g.S[b] == 1.0);
    CHECK(g.S_raw[b] > 1.0);
    CHECK(static_cast<SFlag>(g.flag[b]) == SFlag::capped);
    ++capped_rows;
  }
  CHECK(capped_rows == 32);
  // Every S is capped at 1, and undefined without rock.
  for (const auto& g : r.cases)
    for (int b = 0; b < kBlocks; ++b) {
      if (std::isfinite(g.S[b])) CHECK(g.S[b] <= 1.0);
      if (g.M_wr[b] == 0.0) CHECK(static_cast<SFlag>(g.flag[b]) == SFlag::no_rock);
    }
  // The warnings name the uncapped printed values.
  bool warned = false;
  for (const auto& w : r.warnings) warned = warned || w.message.find("5202.7 %") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("block cut: case 1 has no K, so no S unless K is given") {
  const BlockCutResult r = thesis();
  const BlockGrid& g1 = r.cases.at(0);
  CHECK(std::isnan(g1.K));
  for (int b = 0; b < kBlocks; ++b) {
    CHECK(std::isnan(g1.S[b]));
    CHECK((static_cast<SFlag>(g1.flag[b]) == SFlag::no_K || static_cast<SFlag>(g1.flag[b]) == SFlag::no_rock));
  }
  bool warned = false;
  for (const auto& w : r.warnings) warned = warned || w.message.find("case 1: K") != std::string::npos;
  CHECK(warned);
  auto K = kThesisK;
  K[1] = {3570, "test"};
  const BlockCutResult with_k = thesis(K);
  const BlockGrid& g = with_k.cases.at(0);
  const int b = block_index(2, 2, 1);  // M_221: 0.0673 kg rock, 0.0639 kg paste
  CHECK(g.S_raw[b] == doctest::Approx(0.0639 * 3570 / (2710 * (1 - 0.6 / 1.6) * 0.0673)));
}

TEST_CASE("block cut: ids and indices") {
  CHECK(block_index(1, 1, 1) == 0);
  CHECK(block_index(4, 3, 3) == kBlocks - 1);
  for (int b = 0; b < kBlocks; ++b) {
    const std::string id = block_id_of(b);
    CHECK(block_index(id[2] - '0', id[3] - '0', id[4] - '0') == b);
  }
}

TEST_CASE("block cut: duplicate, missing and inconsistent blocks are input errors with the line") {
  // Line 3 is case 1 M_211; make it a second M_111.
  CHECK(error_of(with_line(3, "1,M_111,1,1,1,0.0027,0.0985,2710,0.6,2.6,,n/a")).find("b.csv:3: column 'block_id'") == 0);
  // Line 3's id says i = 2, its i column 3.
  CHECK(error_of(with_line(3, "1,M_211,3,1,1,0.0027,0.0985,2710,0.6,2.6,,n/a")).find("b.csv:3: column 'i'") == 0);
  CHECK(error_of(with_line(3, "1,M_511,5,1,1,0.0027,0.0985,2710,0.6,2.6,,n/a")).find("b.csv:3: column 'block_id'") == 0);
  CHECK(error_of(with_line(3, "1,M_211,2,1,1,-0.0027,0.0985,2710,0.6,2.6,,n/a")).find("b.csv:3: column 'M_wr_kg'") == 0);
  CHECK(error_of(with_line(3, "1,M_211,2,1,1,0,0,2710,0.6,2.6,,n/a")).find("b.csv:3: column 'M_wr_kg'") == 0);
  CHECK(error_of(with_line(3, "1,M_211,2,1,1,0.0027,0.0985,2710,0.6,2.6,,odd")).find("b.csv:3: column 'S_flag'") == 0);
  // Drop case 2's M_111 (line 38): case 2 starts on the next line and misses it.
  const std::string e = error_of(with_line(38, ""));
  CHECK(e.find("b.csv:39: column 'block_id'") == 0);
  CHECK(e.find("missing M_111") != std::string::npos);
}
