// SPDX-License-Identifier: MIT
// Reliability of `pastemix lab` (issue 20): a full disk, a helper that fails loudly, the checks that had
// gaps (duplicated trials, implausible units, every row of a mean column, repeated --K, slump edge values,
// folders for files, separators, huge cells, --generate guards). Each ran wrong on the code before it.
#include <csignal>
#include <filesystem>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/params.h"
#include "tests/lab/dataset_fixture.h"
#include "tests/run_command.h"

namespace fs = std::filesystem;
using namespace pastemix::test;  // the fixtures: Dataset, run_pastemix, read_text, ...

namespace {

// Runs `pastemix ARGS` through sh with `prefix` before it (environment, ulimit).
CommandResult run_with(const std::string& prefix, const std::string& args) {
  return run_pastemix(args, prefix);
}

std::size_t count_entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

void expect_error(const CommandResult& r, const std::string& expected) {
  INFO(r.output.substr(0, 2000));
  CHECK(r.exit_code == 2);
  CHECK(r.output.find(expected) != std::string::npos);
}

}  // namespace

TEST_CASE("full disk: lab reduce exits 2 naming the file, the old outputs stay, no partial is left") {
  Dataset d("full_disk");
  const fs::path out = d.dir / "out";
  fs::create_directories(out);
  write_text(out / "parameters.toml", "# old parameters\n");
  write_text(out / "lab.h5", "old lab.h5");
  // A file-size limit makes the kernel refuse writes past 100 blocks (51 or 100 KB; lab.h5 is ~125 KB) with
  // EFBIG, as a full disk refuses them with ENOSPC; SIGXFSZ is ignored so that write() returns the error.
  const auto r = run_with("trap '' XFSZ; ulimit -f 100;",
                          fmt::format("lab reduce '{}' --out '{}'", d.dir.string(), out.string()));
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find((out / "lab.h5").string()) != std::string::npos);
  CHECK(r.output.find("cannot write") != std::string::npos);
  CHECK(read_text(out / "parameters.toml") == "# old parameters\n");
  CHECK(read_text(out / "lab.h5") == "old lab.h5");
  CHECK(count_entries(out) == 2);  // no .partial, no .old
}

TEST_CASE("a plotting helper's multi-line output goes into its log, parameters.toml stays valid TOML") {
  Dataset d("helper_output");
  const fs::path out = d.dir / "out";
  // A helper that fails with a traceback whose lines look like TOML ([table], key = "unterminated).
  const fs::path script = d.dir / "fake_plot.sh";
  write_text(script, "echo 'Traceback (most recent call last):'\necho '[paste.yield_stress]'\n"
                     "echo 'value = \"broken'\necho 'ValueError: bogus backend'\nexit 1\n");
  const auto r = run_with(fmt::format("PASTEMIX_PYTHON=/bin/sh PASTEMIX_PLOT_SCRIPT='{}'", script.string()),
                          fmt::format("lab reduce '{}' --out '{}'", d.dir.string(), out.string()));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // The next command of the chain reads it: it must parse, and hold the helper's words only as comments.
  CHECK_NOTHROW(pastemix::Params::parse_file(out / "parameters.toml"));
  const std::string params = read_text(out / "parameters.toml");
  CHECK(params.find("\nvalue = \"broken") == std::string::npos);
  CHECK(params.find("ValueError: bogus backend") != std::string::npos);  // the last line, in the warning
  const std::string log = read_text(out / "plot_lab_grids.log");
  CHECK(log.find("Traceback (most recent call last):") != std::string::npos);
  CHECK(log.find("[paste.yield_stress]") != std::string::npos);
}

TEST_CASE("a duplicated trial id is an error naming both lines") {
  Dataset d("dup_trial");
  d.set_line("slump_tests.csv", 3, "1,152,152,1843,103,131,136");
  d.expect_reduce_error("slump_tests.csv:3: column 'trial': trial 1 is listed twice (first on line 2)");
}

TEST_CASE("400,000 copies of trial 1 are an error at the first copy") {
  Dataset d("many_trials");
  std::string text = "trial,H_mm,D_mm,paste_density_kg_m3,slump_mm,yield_stress_Pa,yield_stress_mean_Pa\n";
  for (int k = 0; k < 400000; ++k) text += "1,152,152,1843,102,135,136\n";
  write_text(d.file("slump_tests.csv"), text);
  const auto r = run_pastemix(fmt::format("lab slump '{}'", d.file("slump_tests.csv").string()));
  expect_error(r, "slump_tests.csv:3: column 'trial': trial 1 is listed twice (first on line 2)");
}

TEST_CASE("a density in g/cm3 under a kg/m3 manifest is an implausible unit, not 137,971 Pa") {
  Dataset d("density_unit");
  d.replace("manifest.toml", "paste_density_kg_m3 = \"kg/m3\"", "paste_density_kg_m3 = \"g/cm3\"");
  d.expect_reduce_error("slump_tests.csv:2: column 'paste_density_kg_m3': 1843 = 1.843e+06 is not plausible as a "
                        "density (kg/m3)");
  Dataset light("density_light");
  light.set_line("slump_tests.csv", 2, "1,152,152,1.843,102,135,136");
  light.expect_reduce_error("slump_tests.csv:2: column 'paste_density_kg_m3': 1.843 = 1.843 is not plausible");
}

TEST_CASE("a steel ball density in g/cm3 is implausible too") {
  Dataset d("steel_density");
  d.set_line("rebound_tests.csv", 4, "3,8,8.135,252,90.9,0.601,0.612");
  d.expect_reduce_error("rebound_tests.csv:4: column 'steel_ball_density_kg_m3': 8.135 = 8.135 is not plausible");
}

TEST_CASE("a printed mean column is checked on every row") {
  // The thesis's printed mean (136) is itself off the recomputed 138.0: rows 2-3 carry 138, row 4 a slip.
  Dataset d("mean_rows");
  d.set_line("slump_tests.csv", 2, "1,152,152,1843,102,135,138");
  d.set_line("slump_tests.csv", 3, "2,152,152,1843,103,131,138");
  d.set_line("slump_tests.csv", 4, "3,152,152,1843,100,143,150");
  const auto r = run_pastemix(fmt::format("lab slump '{}'", d.file("slump_tests.csv").string()));
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("slump_tests.csv:4: printed mean yield stress 150 Pa") != std::string::npos);
  Dataset t("mean_rows_tilt");
  t.set_line("tilt_tests.csv", 5, "4,600,202,0.337,0.399");
  const auto rt = run_pastemix(fmt::format("lab tilt '{}'", t.file("tilt_tests.csv").string()));
  INFO(rt.output);
  CHECK(rt.exit_code == 0);
  CHECK(rt.output.find("tilt_tests.csv:5: printed mean static friction 0.399") != std::string::npos);
}

TEST_CASE("--K given twice for one case is an error") {
  const auto r = run_pastemix(fmt::format("lab block-cut '{}' --K 2=3570 2=4000",
                                          source_path("datasets/thesis/block_cut_masses.csv")));
  expect_error(r, "--K: case 2 given twice (3570 and 4000 kg/m3)");
}

TEST_CASE("slump edge values give exit 2 naming the row, not exit 3 without one") {
  for (const std::string slump : {"1e-15", "151.99999999999"}) {
    Dataset d("slump_edge");
    d.set_line("slump_tests.csv", 3, fmt::format("2,152,152,1843,{},131,136", slump));
    const auto r = run_pastemix(fmt::format("lab slump '{}'", d.file("slump_tests.csv").string()));
    INFO(slump, " ", r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("slump_tests.csv:3: column 'slump_mm'") != std::string::npos);
  }
}

TEST_CASE("a folder given as a file, and --out naming a file, are clear input errors") {
  Dataset d("folder_file");
  expect_error(run_pastemix(fmt::format("lab slump '{}'", d.dir.string())), "is a folder, not a CSV file");
  write_text(d.dir / "not_a_folder", "x");
  expect_error(run_pastemix(fmt::format("lab reduce '{}' --out '{}'", d.dir.string(), (d.dir / "not_a_folder").string())),
               "not_a_folder: the output folder is a file, not a folder");
}

TEST_CASE("a semicolon- or tab-separated file gets a hint about the separator") {
  Dataset d("separator");
  const std::string csv = read_text(d.file("slump_tests.csv"));
  std::string semi = csv, tab = csv;
  for (char& c : semi)
    if (c == ',') c = ';';
  for (char& c : tab)
    if (c == ',') c = '\t';
  write_text(d.file("semi.csv"), semi);
  write_text(d.file("tab.csv"), tab);
  expect_error(run_pastemix(fmt::format("lab slump '{}'", d.file("semi.csv").string())),
               "the file seems to be separated by semicolons");
  expect_error(run_pastemix(fmt::format("lab slump '{}'", d.file("tab.csv").string())),
               "the file seems to be separated by tabs");
}

TEST_CASE("a 10 MB cell is not echoed whole") {
  Dataset d("huge_cell");
  d.set_line("slump_tests.csv", 2, "1,152,152," + std::string(10'000'000, '7') + "x,102,135,136");
  const auto r = run_pastemix(fmt::format("lab slump '{}'", d.file("slump_tests.csv").string()));
  expect_error(r, "(10000001 characters)");
  CHECK(r.output.size() < 2000);
}

TEST_CASE("lab sieve --generate refuses huge, negative and NaN masses") {
  const std::string file = source_path("tests/lab/data/sieve_example.csv");
  expect_error(run_pastemix(fmt::format("lab sieve '{}' --generate 1e12", file)), "--generate: 1e+12 g would make about");
  expect_error(run_pastemix(fmt::format("lab sieve '{}' --generate -5", file)), "--generate: must be a positive mass");
  expect_error(run_pastemix(fmt::format("lab sieve '{}' --generate nan", file)), "--generate: must be a positive mass");
  const auto ok = run_pastemix(fmt::format("lab sieve '{}' --generate 50", file));
  INFO(ok.output);
  CHECK(ok.exit_code == 0);
}

TEST_CASE("a misspelt manifest key gets a 'did you mean'") {
  Dataset d("did_you_mean");
  d.replace("manifest.toml", "file = \"slump_tests.csv\"", "file = \"slump_tests.csv\"\nallow_implausable_values = true");
  d.expect_reduce_error("key 'allow_implausable_values': unknown key (did you mean 'allow_implausible_values'?)");
}
