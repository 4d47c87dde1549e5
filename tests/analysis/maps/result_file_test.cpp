// SPDX-License-Identifier: MIT
#include "analysis/maps/result_file.h"

#include <fstream>

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/analysis/result_fixture.h"

using namespace pastemix::analysis;
using pastemix::InputError;
using pastemix::test::ResultSpec;
using pastemix::test::ScratchDir;
using pastemix::test::write_result;

namespace {
// The message of the InputError `f` throws ("" if none).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("result file: reads the last snapshot, material densities and the paste attributes") {
  ScratchDir d("result_read");
  ResultSpec s;
  s.final = {{{0.05, 0.05, 0.05}, 0.004, 1}, {{0.1, 0.1, 0.02}, 0.002, 0}};
  s.densities = {2760, 2650};
  write_result(d / "r.h5", s);
  const ResultSnapshot r = read_result(d / "r.h5", {});
  CHECK(r.snapshot == 1);
  CHECK(r.time_s == 0.5);
  CHECK(r.seed == 7);
  CHECK(r.scene_hash == "00000000deadbeef");
  REQUIRE(r.position.size() == 2);
  CHECK(r.position[0][2] == 0.05);
  CHECK(r.density[0] == 2650);
  CHECK(r.density[1] == 2760);
  CHECK(r.surface_z.value == 0.10);
  CHECK(r.paste_density.value == 1843);
  CHECK(r.solids_fraction.value == 0.75);
  CHECK(r.notes.empty());
  ResultOverrides o;
  o.snapshot = 0;
  CHECK(read_result(d / "r.h5", o).position[0][2] == doctest::Approx(1.05));
}

TEST_CASE("result file: command-line values override the file and are reported") {
  ScratchDir d("result_over");
  ResultSpec s;
  s.final = {{{0.05, 0.05, 0.05}, 0.004}};
  s.surface = s.paste = s.material_density = false;
  write_result(d / "r.h5", s);
  ResultOverrides o;
  o.surface_z = 0.104;
  o.paste_density = 1800;
  o.solids_fraction = 0.7;
  o.rock_density = 2700;
  const ResultSnapshot r = read_result(d / "r.h5", o);
  CHECK(r.surface_z.value == 0.104);
  CHECK(r.surface_z.source == "command line --surface-z");
  CHECK(r.density[0] == 2700);
  CHECK(r.notes.size() == 4);
}

TEST_CASE("result file: every missing or bad input names the file and the field") {
  ScratchDir d("result_bad");
  ResultSpec s;
  s.final = {{{0.05, 0.05, 0.05}, 0.004}};
  const auto path = (d / "r.h5").string();
  s.surface = false;
  write_result(d / "r.h5", s);
  std::string e = error_of([&] { read_result(path, {}); });
  CHECK(e.find(path) != std::string::npos);
  CHECK(e.find("fluid_surface_z") != std::string::npos);
  CHECK(e.find("--surface-z") != std::string::npos);
  s.surface = true;
  s.material_density = false;
  write_result(d / "r.h5", s);
  e = error_of([&] { read_result(path, {}); });
  CHECK(e.find("/material_density") != std::string::npos);
  CHECK(e.find("--rock-density") != std::string::npos);
  s.material_density = true;
  s.final[0].material = 3;
  write_result(d / "r.h5", s);
  CHECK(error_of([&] { read_result(path, {}); }).find("material 3") != std::string::npos);
  s.final[0].material = 0;
  s.solids = 75;  // a percentage where a fraction belongs
  write_result(d / "r.h5", s);
  CHECK(error_of([&] { read_result(path, {}); }).find("fluid_solids_fraction") != std::string::npos);
  std::ofstream(d / "text.h5") << "not hdf5\n";
  CHECK(error_of([&] { read_result(d / "text.h5", {}); }).find("HDF5") != std::string::npos);
  CHECK(error_of([&] { read_result(d / "none.h5", {}); }).find("no such file") != std::string::npos);
  ResultOverrides o;
  o.snapshot = 5;
  s.solids = 0.75;
  write_result(d / "r.h5", s);
  CHECK(error_of([&] { read_result(path, o); }).find("snapshot 5") != std::string::npos);
}
