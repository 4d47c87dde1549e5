// SPDX-License-Identifier: MIT
// Bad inputs through the `pastemix` command: each is a copy of datasets/thesis with one defect, run through
// `lab reduce` (or a single-file subcommand). Each must exit 2, name file:line and the field, and write nothing.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "tests/lab/dataset_fixture.h"
#include "tests/run_command.h"

namespace fs = std::filesystem;
using namespace pastemix::test;  // the fixtures: Dataset, run_pastemix, read_text, ...

TEST_CASE("bad input 1: missing column") {
  Dataset d("missing_column");
  d.set_line("slump_tests.csv", 1, "trial,H_mm,D_mm,paste_density_kg_m3,slumpp_mm,yield_stress_Pa,yield_stress_mean_Pa");
  d.expect_reduce_error("slump_tests.csv:1: column 'slump_mm': required column is missing");
}

TEST_CASE("bad input 2: unknown unit in the manifest") {
  Dataset d("unknown_unit");
  d.replace("manifest.toml", "slump_mm = \"mm\"", "slump_mm = \"furlong\"");
  d.expect_reduce_error(fmt::format("manifest.toml:{}: key 'slump_mm': unknown unit 'furlong'",
                                    line_of(d.file("manifest.toml"), "furlong")));
}

TEST_CASE("bad input 3: unit of the wrong dimension in the manifest") {
  Dataset d("wrong_dimension");
  d.replace("manifest.toml", "M_wr_kg = \"kg\"", "M_wr_kg = \"mm\"");
  d.expect_reduce_error(fmt::format("manifest.toml:{}: key 'M_wr_kg': unit 'mm' converts to m",
                                    line_of(d.file("manifest.toml"), "M_wr_kg = \"mm\"")));
}

TEST_CASE("bad input 4: non-numeric cell") {
  Dataset d("non_numeric");
  d.set_line("rebound_tests.csv", 3, "2,8,8135,abc,72.0,0.619,0.612");
  d.expect_reduce_error("rebound_tests.csv:3: column 'falling_height_mm': expected a positive number, got 'abc'");
}

TEST_CASE("bad input 5: NaN cell") {
  Dataset d("nan_cell");
  d.set_line("tilt_tests.csv", 4, "3,600,nan,0.337,0.341");
  d.expect_reduce_error("tilt_tests.csv:4: column 'H_l_cm_as_printed'");
}

TEST_CASE("bad input 6: negative mass") {
  Dataset d("negative_mass");
  d.set_line("block_cut_masses.csv", 10, "1,M_131,1,3,1,-0.0001,0.1132,2710,0.6,0.09,,n/a");
  d.expect_reduce_error("block_cut_masses.csv:10: column 'M_wr_kg': expected a non-negative number, got '-0.0001'");
}

TEST_CASE("bad input 7: slump larger than the mould") {
  Dataset d("slump_too_large");
  d.set_line("slump_tests.csv", 3, "2,152,152,1843,163,131,136");
  d.expect_reduce_error("slump_tests.csv:3: column 'slump_mm': slump 0.163 m is not smaller than the mould height");
}

TEST_CASE("bad input 8: no slump (tau' >= 0.5)") {
  Dataset d("no_slump");
  d.set_line("slump_tests.csv", 2, "1,152,152,1843,0,135,136");
  d.expect_reduce_error("slump_tests.csv:2: column 'slump_mm': no slump");
}

TEST_CASE("bad input 9: rebound higher than the drop") {
  Dataset d("rebound_high");
  d.set_line("rebound_tests.csv", 2, "1,8,8135,95,95.5,0.624,0.612");
  d.expect_reduce_error("rebound_tests.csv:2: column 'rebound_height_mm': rebound height");
}

TEST_CASE("bad input 10: empty file") {
  Dataset d("empty_file");
  write_text(d.file("tilt_tests.csv"), "");
  // An empty file has no line to name: the message names the file (base/error.h: line 0 = whole file).
  d.expect_reduce_error("tilt_tests.csv: file is empty");
}

TEST_CASE("bad input 11: header-only file") {
  Dataset d("header_only");
  const std::string text = read_text(d.file("mixing_tests_program.csv"));
  write_text(d.file("mixing_tests_program.csv"), text.substr(0, text.find('\n') + 1));
  d.expect_reduce_error("mixing_tests_program.csv: file has a header but no data rows");
}

TEST_CASE("bad input 12: duplicate block id") {
  Dataset d("duplicate_block");
  d.set_line("block_cut_masses.csv", 40, "2,M_111,1,1,1,0.0133,0.1347,2710,0.6,9.0,3085.8,");
  d.expect_reduce_error("block_cut_masses.csv:40: column 'block_id': duplicate block M_111 in case 2 (first on line 38)");
}

TEST_CASE("bad input 13: ragged row") {
  Dataset d("ragged_row");
  d.set_line("rebound_tests.csv", 4, "3,8,8135,252,90.9,0.601,0.612,extra");
  d.expect_reduce_error("rebound_tests.csv:4: expected 7 cells (as in the header), found 8");
}

TEST_CASE("bad input 14: unknown manifest key") {
  Dataset d("unknown_key");
  d.replace("manifest.toml", "file = \"tilt_tests.csv\"", "file = \"tilt_tests.csv\"\nfiel = \"x.csv\"");
  d.expect_reduce_error(fmt::format("manifest.toml:{}: key 'fiel': unknown key", line_of(d.file("manifest.toml"), "fiel")));
}

TEST_CASE("bad input 15: block index inconsistent with its id") {
  Dataset d("inconsistent_index");
  d.set_line("block_cut_masses.csv", 5, "1,M_411,4,2,1,0.0000,0.1255,2710,0.6,0.0,,n/a");
  d.expect_reduce_error("block_cut_masses.csv:5: column 'j': block M_411 has j = 1 by its id, but this column says 2");
}

TEST_CASE("bad input 16: missing block") {
  Dataset d("missing_block");
  d.set_line("block_cut_masses.csv", 80, "");
  d.expect_reduce_error("block_cut_masses.csv:74: column 'block_id': case 3 (starting here) has 35 of 36 blocks");
}

TEST_CASE("bad input 17: negative K") {
  Dataset d("negative_K");
  d.replace("manifest.toml", "value = 3488", "value = -3488");
  d.expect_reduce_error(fmt::format("manifest.toml:{}: key 'value': expected a positive number",
                                    line_of(d.file("manifest.toml"), "-3488")));
}

TEST_CASE("bad input 18: K entry without a value") {
  Dataset d("missing_K");
  d.replace("manifest.toml", "case = 3\nvalue = 3570\n", "case = 3\n");
  d.expect_reduce_error(fmt::format("manifest.toml:{}: key 'value': required key is missing",
                                    line_of(d.file("manifest.toml"), "case = 3") - 1));
}

TEST_CASE("bad input 19: manifest names a file that is not there") {
  Dataset d("missing_file");
  fs::remove(d.file("rebound_tests.csv"));
  d.expect_reduce_error(fmt::format("manifest.toml:{}: key 'file': file 'rebound_tests.csv' not found",
                                    line_of(d.file("manifest.toml"), "rebound_tests.csv")));
}

TEST_CASE("bad input 20: correction larger than the block's paste") {
  Dataset d("big_correction");
  d.set_line("block_cut_corrections.csv", 2, "2,M_111,1,1,1,0.185,0.1500,0.0009,91.2,20");
  d.expect_reduce_error("block_cut_corrections.csv:2: column 'M_prime_paste_dried_kg': exceeds the block's dried paste");
}

TEST_CASE("bad input 21: single-file commands exit 2 with file:line too") {
  Dataset d("single_file");
  d.set_line("slump_tests.csv", 4, "3,152,152,1843,100x,143,136");
  auto r = run_pastemix(fmt::format("lab slump '{}'", d.file("slump_tests.csv").string()));
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("slump_tests.csv:4: column 'slump_mm'") != std::string::npos);
  r = run_pastemix(fmt::format("lab block-cut '{}' --K 2=-5", d.file("block_cut_masses.csv").string()));
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("--K: K must be positive") != std::string::npos);
  r = run_pastemix(fmt::format("lab sieve '{}'", d.file("slump_tests.csv").string()));
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("slump_tests.csv:1: column 'sieve_mm': required column is missing") != std::string::npos);
}
