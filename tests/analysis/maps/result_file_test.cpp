// SPDX-License-Identifier: MIT
#include "analysis/maps/result_file.h"

#include <cmath>
#include <fstream>

#include <doctest/doctest.h>

#include "analysis/maps/maps_h5.h"
#include "analysis/maps/mixing_map.h"
#include "base/error.h"
#include "tests/analysis/result_fixture.h"
#include "base/units.h"
#include "tests/input_error.h"

using namespace pastemix::analysis;
using pastemix::InputError;
using pastemix::test::ResultSpec;
using pastemix::test::ScratchDir;
using pastemix::test::write_result;

using pastemix::test::input_error_of;

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
  CHECK(r.position[0].z == 0.05);
  CHECK(r.density[0] == 2650);
  CHECK(r.density[1] == 2760);
  CHECK(r.surface_z.value == 0.10);
  CHECK(r.paste_density.value == 1843);
  CHECK(r.solids_fraction.value == 0.75);
  CHECK(r.notes.empty());
  ResultOverrides o;
  o.snapshot = 0;
  CHECK(read_result(d / "r.h5", o).position[0].z == doctest::Approx(1.05));
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
  std::string e = input_error_of([&] { read_result(path, {}); });
  CHECK(e.find(path) != std::string::npos);
  CHECK(e.find("fluid_surface_z") != std::string::npos);
  CHECK(e.find("--surface-z") != std::string::npos);
  s.surface = true;
  s.material_density = false;
  write_result(d / "r.h5", s);
  e = input_error_of([&] { read_result(path, {}); });
  CHECK(e.find("/material_density") != std::string::npos);
  CHECK(e.find("--rock-density") != std::string::npos);
  s.material_density = true;
  s.final[0].material = 3;
  write_result(d / "r.h5", s);
  CHECK(input_error_of([&] { read_result(path, {}); }).find("material 3") != std::string::npos);
  s.final[0].material = 0;
  s.solids = 75;  // a percentage where a fraction belongs
  write_result(d / "r.h5", s);
  CHECK(input_error_of([&] { read_result(path, {}); }).find("fluid_solids_fraction") != std::string::npos);
  std::ofstream(d / "text.h5") << "not hdf5\n";
  CHECK(input_error_of([&] { read_result(d / "text.h5", {}); }).find("HDF5") != std::string::npos);
  CHECK(input_error_of([&] { read_result(d / "none.h5", {}); }).find("no such file") != std::string::npos);
  ResultOverrides o;
  o.snapshot = 5;
  s.solids = 0.75;
  write_result(d / "r.h5", s);
  CHECK(input_error_of([&] { read_result(path, o); }).find("snapshot 5") != std::string::npos);
}

TEST_CASE("result file: escaped rock up to the snapshot is poured mass, the maps' balances hold with it to 1e-9") {
  ScratchDir d("result_escaped");
  ResultSpec s;
  // Rock in blocks, beside the grid (x < 0), below it, above the surface in the open top and beside it.
  s.final = {{{0.075, 0.0825, 0.085}, 0.01, 0},  {{-0.02, 0.05, 0.03}, 0.006, 0}, {{0.1, 0.08, 0.003}, 0.004, 0},
             {{0.11, 0.09, 0.105}, 0.008, 0},    {{0.19, 0.17, 0.1}, 0.012, 0},   {{0.2, -0.01, 0.12}, 0.005, 0}};
  s.escaped = {{0.2, 0.0123}, {0.45, 0.0046}, {0.7, 0.0031}};  // the last one after the final snapshot (0.5 s)
  write_result(d / "r.h5", s);
  const ResultSnapshot r = read_result(d / "r.h5", {});
  CHECK(r.escaped_count == 2);
  CHECK(r.escaped_mass == 0.0123 + 0.0046);
  MixingInputs in;
  in.surface_z = r.surface_z.value;
  in.paste_density = r.paste_density.value;
  in.solids_fraction = r.solids_fraction.value;
  in.escaped_mass = r.escaped_mass;
  const MixingMap m = mixing_map(in, ParticleView{r.position, r.radius, r.density});
  double in_snapshot = 0.0;
  for (std::size_t p = 0; p < r.radius.size(); ++p)
    in_snapshot += r.density[p] * 4.0 / 3.0 * pastemix::units::pi * r.radius[p] * r.radius[p] * r.radius[p];
  CHECK(m.escaped == r.escaped_mass);
  CHECK(m.poured == doctest::Approx(in_snapshot + r.escaped_mass).epsilon(1e-12));
  CHECK(m.beside_grid > 0.0);
  CHECK(m.below_grid > 0.0);
  CHECK(m.above_uncounted > 0.0);
  const double grid = std::abs(m.poured - (m.in_blocks + m.below_grid + m.beside_grid + m.above_uncounted + m.escaped));
  const double surface = std::abs(m.poured - (m.submerged + m.above_surface + m.escaped));
  MESSAGE("poured " << m.poured << " kg, escaped " << m.escaped << " kg; balance errors " << grid / m.poured << ", "
                    << surface / m.poured << "; conservation_error " << m.conservation_error());
  CHECK(grid / m.poured < 1e-9);
  CHECK(surface / m.poured < 1e-9);
  CHECK(m.conservation_error() < 1e-9);
  // Leaving the escaped mass out breaks the balance by its share: the check can fail.
  MixingInputs forgot = in;
  forgot.escaped_mass = 0.0;
  const MixingMap f = mixing_map(forgot, ParticleView{r.position, r.radius, r.density});
  CHECK(std::abs(f.poured + r.escaped_mass - m.poured) < 1e-12);
  // The text summary shows it.
  const std::string table = maps_table(m, r, in, "");
  CHECK(table.find("+ escaped 0.016900") != std::string::npos);
  CHECK(table.find("2 particle(s)") != std::string::npos);
  // At snapshot 0 (t = 0) nothing had escaped yet.
  ResultOverrides o;
  o.snapshot = 0;
  const ResultSnapshot r0 = read_result(d / "r.h5", o);
  CHECK(r0.escaped_mass == 0.0);
  CHECK(r0.escaped_count == 0);
  // A defective /escaped is an InputError naming it.
  ResultSpec bad = s;
  bad.escaped = {{0.2, -0.01}};
  write_result(d / "bad.h5", bad);
  CHECK(input_error_of([&] { read_result(d / "bad.h5", {}); }).find("/escaped/mass") != std::string::npos);
}
