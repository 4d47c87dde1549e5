// SPDX-License-Identifier: MIT
// `lab reduce` on the shipped thesis data: the step table, and the outputs written through the CLI.
#include "lab/reduce.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "base/params.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::lab;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / fmt::format("pastemix_lab_{}_{}", name, static_cast<long>(::getpid()));
  fs::remove_all(d);
  return d;
}
}  // namespace

TEST_CASE("reduce: every thesis step runs and yields the acceptance parameters") {
  const ReduceResult r = reduce(test::source_path("datasets/thesis"));
  CHECK(r.steps_run == std::vector<std::string>{"slump", "rebound", "tilt", "mixing_program", "block_cut", "drag_curve",
                                               "paste_rheology"});
  auto value = [&](const std::string& key) {
    for (const auto& p : r.parameters)
      if (p.key == key) return p.value;
    FAIL("missing parameter " << key);
    return 0.0;
  };
  CHECK(std::abs(value("paste.yield_stress") - 138.0) <= 0.05);
  CHECK(std::abs(value("steel_ball.restitution") - 0.6120) <= 0.0005);
  CHECK(std::abs(value("steel_ball.static_friction") - 0.3407) <= 0.0005);
  CHECK(value("block_cut.case_2.K") == 3570.0);
  CHECK(value("mixing.case_7.falling_height") == doctest::Approx(0.75));
  REQUIRE(r.block_cut);
  CHECK(r.block_cut->cases.size() == 5);
  CHECK(r.block_cut->corrected.size() == 5);
  CHECK(r.mixing_cases.size() == 7);
  for (const auto& p : r.parameters) CHECK(!p.source.empty());
  // The drag curve named in the manifest, refitted with uncertainties the engine can load by name.
  bool chosen = false;
  for (const auto& p : r.parameters)
    if (p.key == "drag_curve.chosen") chosen = p.text == "yield_blend";
  CHECK(chosen);
  CHECK(value("drag_curve.yield_blend.c") > 0.0);
  CHECK(value("drag_curve.yield_blend.q") > 0.0);  // drag falls with the yield number at a given Re'
  // The unmeasured pastes: every solids content of the programme, the 75 % one the anchor itself (issue 15).
  CHECK(value("paste_rheology.cw_75.yield_stress") == value("paste.yield_stress"));
  CHECK(value("paste_rheology.cw_75.density") == value("paste.density"));
  CHECK(value("paste_rheology.cw_72_5.yield_stress") < value("paste.yield_stress"));
  CHECK(value("paste_rheology.cw_70.yield_stress") < value("paste_rheology.cw_72_5.yield_stress"));
  CHECK(value("paste_rheology.model.mixture_density_at_anchor") == doctest::Approx(1898.4).epsilon(1e-4));
  bool gap_warned = false;
  for (const auto& w : r.warnings) gap_warned = gap_warned || w.message.find("gap 55.4 kg/m3") != std::string::npos;
  CHECK(gap_warned);
}

TEST_CASE("reduce: a rheology calibration record sets the model, one outside the prior is an error naming it") {
  const fs::path dir = fresh_dir("rheo_record");
  fs::create_directories(dir);
  const std::string rec = (dir / "cal.toml").string();
  std::ofstream(rec) << "[rheology_calibration]\nfamily = \"exponential\"\nshape = 0.35\nsd = 0.02\ncase = 2\n";
  ReduceOptions o;
  o.rheology_calibration = rec;
  const ReduceResult r = reduce(test::source_path("datasets/thesis"), o);
  bool seen = false;
  for (const auto& p : r.parameters)
    if (p.key == "paste_rheology.cw_72_5.yield_stress") {
      seen = true;
      CHECK(p.provenance == Provenance::calibrated);
      CHECK(p.method == "model exponential, shape parameter calibrated on case 2");
      CHECK(p.value == doctest::Approx(137.97 * std::exp(-2.5 * 0.35)).epsilon(1e-3));
    }
  CHECK(seen);
  std::ofstream(rec) << "[rheology_calibration]\nfamily = \"exponential\"\nshape = 0.75\nsd = 0.02\ncase = 2\n";
  try {
    reduce(test::source_path("datasets/thesis"), o);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("cal.toml") != std::string::npos);
    CHECK(std::string(e.what()).find("exponential.b = 0.75") != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("reduce CLI: writes parameters.toml (valid TOML), lab.h5 (4x3x3 grids) and one PNG per case") {
  const fs::path out = fresh_dir("reduce");
  auto res = test::run_pastemix("lab reduce '" + test::source_path("datasets/thesis") + "' --out '" + out.string() + "'");
  INFO(res.output);
  REQUIRE(res.exit_code == 0);
  const Params toml = Params::parse_file(out / "parameters.toml");
  const Params ys = toml.table("paste").table("yield_stress");
  CHECK(std::abs(ys.number("value") - 138.0) <= 0.05);
  CHECK(ys.string("unit") == "Pa");
  CHECK(ys.string("source") == "slump_tests.csv");
  CHECK(ys.numbers("trials").size() == 3);
  CHECK(toml.table("reduce").string("software").find("pastemix") == 0);
  const Params psd = toml.table("mixing").table("case_4").table("psd");
  CHECK(psd.numbers("d_min_m")[0] == doctest::Approx(5.0e-3));
  H5Reader h5(out / "lab.h5");
  CHECK(h5.dims("/block_cut/case_3/C") == std::vector<std::uint64_t>{4, 3, 3});
  CHECK(h5.dims("/block_cut/case_3/corrected/S") == std::vector<std::uint64_t>{4, 3, 3});
  CHECK(h5.read_doubles("/parameters/paste.yield_stress/trials").size() == 3);
  CHECK(h5.read_doubles("/psd/mixing_case_1/d_max")[0] == doctest::Approx(5.0e-3));
  CHECK(h5.attribute_string("/", "software").find("pastemix") == 0);
  CHECK(h5.attribute_double("/block_cut/case_2", "K") == 3570.0);
  CHECK(std::isnan(h5.attribute_double("/block_cut/case_1", "K")));
  for (int c = 1; c <= 5; ++c) CHECK(fs::file_size(out / fmt::format("mixing_case_{}.png", c)) > 10000);
  for (const auto& e : fs::directory_iterator(out)) CHECK(e.path().string().find(".partial") == std::string::npos);
  // `lab param` hands one stored value to a script (scripts/main.sh), at full precision.
  const std::string file = " '" + (out / "parameters.toml").string() + "' ";
  auto v = test::run_pastemix("lab param" + file + "paste.yield_stress");
  CHECK(v.exit_code == 0);
  CHECK(std::stod(v.output) == ys.number("value"));
  auto unit = test::run_pastemix("lab param" + file + "paste.density --field unit");
  CHECK(unit.output == "kg/m3\n");
  auto missing = test::run_pastemix("lab param" + file + "paste.no_such_thing");
  CHECK(missing.exit_code == 2);
  CHECK(missing.output.find("no_such_thing") != std::string::npos);
  fs::remove_all(out);
}

TEST_CASE("reduce CLI: without Python the PNGs are skipped with a warning, the rest is written") {
  const fs::path out = fresh_dir("nopython");
  ::setenv("PASTEMIX_PYTHON", "/nonexistent/python3", 1);  // inherited by the command run below
  auto res = test::run_pastemix("lab reduce '" + test::source_path("datasets/thesis") + "' --out '" + out.string() + "'");
  ::unsetenv("PASTEMIX_PYTHON");
  INFO(res.output);
  CHECK(res.exit_code == 0);
  CHECK(res.output.find("no PNG maps written") != std::string::npos);
  CHECK(fs::exists(out / "parameters.toml"));
  CHECK(fs::exists(out / "lab.h5"));
  CHECK(!fs::exists(out / "mixing_case_1.png"));
  fs::remove_all(out);
}

TEST_CASE("reduce: sieve entries give psd.NAME in parameters.toml and /sieve/NAME in lab.h5") {
  const fs::path dir = fresh_dir("sieve_ds"), out = dir / "out";
  fs::create_directories(dir);
  fs::copy_file(test::source_path("tests/lab/data/sieve_example.csv"), dir / "sieve_example.csv");
  std::ofstream(dir / "manifest.toml") << "[[sieve]]\nname = \"example\"\nfile = \"sieve_example.csv\"\n"
                                          "provenance = \"assumed\"\nnote = \"invented for the test\"\ncut_mm = 1.18\n"
                                          "[sieve.units]\nsieve_mm = \"mm\"\nmass_retained_g = \"g\"\n";
  auto res = test::run_pastemix("lab reduce '" + dir.string() + "' --out '" + out.string() + "'");
  INFO(res.output);
  REQUIRE(res.exit_code == 0);
  const Params toml = Params::parse_file(out / "parameters.toml");
  const Params psd = toml.table("psd").table("example");
  CHECK(psd.numbers("mass_fraction").size() == 4);  // cut at 1.18 mm
  CHECK(psd.string("provenance") == "assumed");
  H5Reader h5(out / "lab.h5");
  CHECK(h5.read_doubles("/sieve/example/d_min")[0] == doctest::Approx(1.18e-3));
  CHECK(h5.read_doubles("/sieve/example/passing").size() == 6);
  CHECK(!fs::exists(out / "mixing_case_1.png"));  // no block cut, no maps
  fs::remove_all(dir);
}
