// SPDX-License-Identifier: MIT
// The maps of a flow result read its paste field (analysis/maps/paste_field.h): checked against the flat-surface
// rule where both must agree, and against hand-computed volumes where they must not.
#include "analysis/maps/paste_field.h"

#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "analysis/maps/mixing_map.h"
#include "analysis/maps/result_file.h"
#include "base/error.h"
#include "base/units.h"
#include "tests/analysis/result_fixture.h"

using namespace pastemix::analysis;
namespace test = pastemix::test;
using pastemix::InputError;
using pastemix::units::pi;

namespace {

// The chapter-3 footprint (0.2 x 0.165 m) in 4 x 3 columns of one block each, 12 layers of 1 cm; paste up to
// z = 0.10 m (cells k < 10), air above.
test::ResultSpec field_spec(std::vector<test::Sphere> rocks) {
  test::ResultSpec s;
  s.final = std::move(rocks);
  s.flow_n = {4, 3, 12};
  s.flow_h = {0.05, 0.055, 0.01};
  s.flow_alpha.assign(4 * 3 * 12, 0.0);
  for (int k = 0; k < 10; ++k)
    for (int c = 0; c < 12; ++c) s.flow_alpha[static_cast<std::size_t>(k * 12 + c)] = 1.0;
  return s;
}

std::vector<test::Sphere> some_rocks() {
  // Inside the paste (several straddle block faces and the layer boundary at z = 0.07), one on the surface and
  // one wholly above it: every accounting term is exercised.
  return {{{0.05, 0.055, 0.07}, 0.004}, {{0.12, 0.03, 0.085}, 0.005}, {{0.17, 0.14, 0.045}, 0.0035},
          {{0.025, 0.0275, 0.1}, 0.004}, {{0.1, 0.1, 0.106}, 0.003}, {{0.075, 0.11, 0.02}, 0.0045}};
}

ResultSnapshot read(const test::ResultSpec& s, const test::ScratchDir& dir, const std::string& name) {
  const auto path = dir / name;
  test::write_result(path, s);
  return read_result(path, {});
}

MixingMap map_of(const ResultSnapshot& r, bool field) {
  MixingInputs in = mixing_inputs(r, BlockLayout{});
  in.K = 3570.0;
  if (!field) in.paste_field = nullptr;
  return mixing_map(in, ParticleView{r.position, r.radius, r.density});
}

}  // namespace

TEST_CASE("paste field: a flat field at a cell face gives the flat-surface rule's map to round-off") {
  test::ScratchDir dir("pf_flat");
  const ResultSnapshot r = read(field_spec(some_rocks()), dir, "flat.h5");
  REQUIRE(r.paste_field);
  const MixingInputs in = mixing_inputs(r, BlockLayout{});
  CHECK(in.surface_z == doctest::Approx(0.10).epsilon(1e-14));
  CHECK(in.surface_source.find("area-mean paste height") != std::string::npos);
  const MixingMap f = map_of(r, true), flat = map_of(r, false);
  CHECK(f.from_paste_field);
  CHECK_FALSE(flat.from_paste_field);
  for (std::size_t b = 0; b < f.paste_volume.size(); ++b) {
    CHECK(f.paste_volume[b] == doctest::Approx(flat.paste_volume[b]).epsilon(1e-12));
    CHECK(f.C[b] == doctest::Approx(flat.C[b]).epsilon(1e-12));
    if (std::isfinite(flat.S[b])) CHECK(f.S[b] == doctest::Approx(flat.S[b]).epsilon(1e-12));
  }
  // The surface rock is half mixed in both rules (a half-sphere each side), the one above it not at all.
  CHECK(f.mixed() == doctest::Approx(flat.mixed()).epsilon(1e-12));
  CHECK(f.unmixed() == doctest::Approx(flat.unmixed()).epsilon(1e-12));
  CHECK(f.conservation_error() < 1e-12);
}

TEST_CASE("paste field: the engine's layout (a time_s per group) gives the field of the particles' snapshot") {
  test::ResultSpec s = field_spec(some_rocks());
  s.flow_engine_layout = true;
  test::ScratchDir dir("pf_engine");
  const ResultSnapshot r = read(s, dir, "engine.h5");
  REQUIRE(r.paste_field);
  CHECK(r.paste_field->time_s == 0.5);
  CHECK(r.paste_field->source.find("/flow/snapshots/000001") != std::string::npos);
  const MixingMap f = map_of(r, true), flat = map_of(r, false);
  for (std::size_t b = 0; b < f.paste_volume.size(); ++b)
    CHECK(f.paste_volume[b] == doctest::Approx(flat.paste_volume[b]).epsilon(1e-12));
  ResultOverrides first;
  first.snapshot = 0;  // the particles at t = 0 get the all-air field of t = 0
  const ResultSnapshot r0 = read_result(dir / "engine.h5", first);
  CHECK(r0.paste_field->source.find("/flow/snapshots/000000") != std::string::npos);
}

TEST_CASE("paste field: the surface is the area-mean height function, partial cells included") {
  test::ResultSpec s = field_spec({{{0.1, 0.08, 0.05}, 0.003}});
  // Columns i = 0, 1 (half the footprint's area) lose their top paste cell (k = 9): 9 cm there, 10 cm elsewhere;
  // column (3, 2) keeps 0.25 of it: 9.25 cm.
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 2; ++i) s.flow_alpha[static_cast<std::size_t>(9 * 12 + j * 4 + i)] = 0.0;
  s.flow_alpha[static_cast<std::size_t>(9 * 12 + 2 * 4 + 3)] = 0.25;
  test::ScratchDir dir("pf_surface");
  const ResultSnapshot r = read(s, dir, "surface.h5");
  const double want = (6 * 0.09 + 5 * 0.10 + 0.0925) / 12.0;
  CHECK(mixing_inputs(r, BlockLayout{}).surface_z == doctest::Approx(want).epsilon(1e-14));
  // Over one column only, the column's own height.
  CHECK(paste_surface_z(*r.paste_field, 0.0, 0.05, 0.0, 0.055) == doctest::Approx(0.09).epsilon(1e-14));
  CHECK_THROWS_AS(paste_surface_z(*r.paste_field, 1.0, 1.1, 0.0, 0.055), InputError);
}

TEST_CASE("paste field: paste pushed out of a column leaves its blocks without paste (the flat rule cannot)") {
  test::ResultSpec s = field_spec({{{0.025, 0.0275, 0.085}, 0.005}});
  for (int k = 0; k < 12; ++k) s.flow_alpha[static_cast<std::size_t>(k * 12)] = 0.0;  // column (0, 0): air
  test::ScratchDir dir("pf_aside");
  const ResultSnapshot r = read(s, dir, "aside.h5");
  const BlockLayout L;
  const MixingMap f = map_of(r, true), flat = map_of(r, false);
  const double block = 0.05 * 0.055 * 0.03;
  // The mean surface drops to 11/12 of 10 cm; the full columns' paste above it counts in their layer 1.
  const double surface = 0.10 * 11.0 / 12.0;
  CHECK(mixing_inputs(r, L).surface_z == doctest::Approx(surface).epsilon(1e-14));
  double column = 0.0;
  for (int k = 1; k <= 3; ++k) {
    CHECK(f.paste_volume[L.index(1, 1, k)] == 0.0);
    CHECK(flat.paste_volume[L.index(1, 1, k)] > 0.9 * block);
    if (k > 1) CHECK(f.paste_volume[L.index(2, 1, k)] == doctest::Approx(block).epsilon(1e-12));
    column += f.paste_volume[L.index(2, 1, k)];
  }
  CHECK(column == doctest::Approx((0.10 - (surface - 0.09)) * 0.05 * 0.055).epsilon(1e-12));
  CHECK(f.C[L.index(1, 1, 1)] == doctest::Approx(1.0));  // rock and no paste: all rock, as the lab's dry crater
  CHECK(f.mixed() == 0.0);                                // the rock sits in air: unmixed, whatever its depth
  CHECK(flat.mixed() > 0.0);
}

TEST_CASE("paste field: each rock is mixed by the paste share around it, without a threshold") {
  test::ResultSpec s = field_spec({{{0.1, 0.08, 0.1}, 0.004}, {{0.125, 0.0275, 0.045}, 0.003}});
  // The second rock's cell (i = 2, j = 0, k = 4) holds 30 % paste.
  s.flow_alpha[static_cast<std::size_t>(4 * 12 + 0 * 4 + 2)] = 0.3;
  test::ScratchDir dir("pf_share");
  const ResultSnapshot r = read(s, dir, "share.h5");
  const std::vector<double> share =
      paste_share_around(*r.paste_field, ParticleView{r.position, r.radius, r.density});
  REQUIRE(share.size() == 2);
  CHECK(share[0] == doctest::Approx(0.5).epsilon(1e-12));  // centred on the interface: a half-sphere each side
  CHECK(share[1] == doctest::Approx(0.3).epsilon(1e-12));  // wholly inside the 30 % cell
  const MixingMap f = map_of(r, true);
  const double m0 = 2760.0 * 4.0 / 3.0 * pi * std::pow(0.004, 3), m1 = 2760.0 * 4.0 / 3.0 * pi * std::pow(0.003, 3);
  CHECK(f.mixed() == doctest::Approx(0.5 * m0 + 0.3 * m1).epsilon(1e-12));
  CHECK(f.unmixed() == doctest::Approx(0.5 * m0 + 0.7 * m1).epsilon(1e-12));
  // The 30 % cell's paste: 0.3 of its fluid volume inside the block it lies in.
  const Box3 cell = r.paste_field->cell_box(2, 0, 4);
  const double cell_fluid = 0.05 * 0.055 * 0.01 - 4.0 / 3.0 * pi * std::pow(0.003, 3);
  CHECK(paste_volume_in(*r.paste_field, cell, ParticleView{r.position, r.radius, r.density}) ==
        doctest::Approx(0.3 * cell_fluid).epsilon(1e-12));
}

TEST_CASE("paste field: without fluid_surface_z the field gives the surface, and a --surface-z override keeps its own") {
  test::ResultSpec s = field_spec({{{0.1, 0.08, 0.05}, 0.003}});
  s.surface = false;
  test::ScratchDir dir("pf_nosurf");
  const auto path = dir / "nosurf.h5";
  test::write_result(path, s);
  const ResultSnapshot r = read_result(path, {});
  CHECK(std::isnan(r.surface_z.value));
  CHECK(mixing_inputs(r, BlockLayout{}).surface_z == doctest::Approx(0.10).epsilon(1e-14));
  ResultOverrides over;
  over.surface_z = 0.095;
  const ResultSnapshot o = read_result(path, over);
  CHECK(mixing_inputs(o, BlockLayout{}).surface_z == 0.095);
}

TEST_CASE("paste field: a paste fraction a little outside [0, 1] (the coupled advection's defect) is clamped and named") {
  test::ScratchDir dir("pf_clamp");
  test::ResultSpec s = field_spec(some_rocks());
  s.flow_alpha[static_cast<std::size_t>(11 * 12 + 5)] = -0.0104;  // an air cell: as case 3's rock pile left one
  s.flow_alpha[static_cast<std::size_t>(2 * 12 + 1)] = 1.0 + 5e-5;  // round-off: clamped silently
  const ResultSnapshot r = read(s, dir, "clamp.h5");
  REQUIRE(r.paste_field);
  CHECK(r.paste_field->alpha[11 * 12 + 5] == 0.0);
  CHECK(r.paste_field->alpha[2 * 12 + 1] == 1.0);
  CHECK(r.paste_field->source.find("clamped to [0, 1] in 1 cell(s), by up to 0.0104") != std::string::npos);
  const ResultSnapshot clean = read(field_spec(some_rocks()), dir, "clean.h5");
  CHECK(map_of(r, true).C == map_of(clean, true).C);  // an air cell's clamp leaves the map as it was
}

TEST_CASE("paste field: a bad field is an InputError naming the file and the dataset") {
  test::ScratchDir dir("pf_bad");
  auto fails_with = [&](test::ResultSpec s, const std::string& name, const std::string& what) {
    const auto path = dir / name;
    test::write_result(path, s);
    try {
      (void)read_result(path, {});
      FAIL("no error for " << name);
    } catch (const InputError& e) {
      const std::string m = e.what();
      CHECK_MESSAGE(m.find(name) != std::string::npos, m);
      CHECK_MESSAGE(m.find(what) != std::string::npos, m);
    }
  };
  test::ResultSpec dims = field_spec({});
  dims.flow_nz_attribute = 11;  // the attribute says 11 layers, the dataset holds 12
  fails_with(dims, "dims.h5", "paste_fraction");
  test::ResultSpec range = field_spec({});
  range.flow_alpha[5] = 1.5;
  fails_with(range, "range.h5", "not in [0, 1]");
  range.flow_alpha[5] = -0.11;  // past the per-cell bound (the coupled advection's worst measured: -0.0242)
  fails_with(range, "range2.h5", "not in [0, 1]");
  test::ResultSpec many = field_spec({});  // each cell within the bound, but together more than 1e-3 of the paste
  for (int c = 0; c < 24; ++c) many.flow_alpha[static_cast<std::size_t>(10 * 12 + c)] = -0.09;
  fails_with(many, "many.h5", "of the field's paste");
  test::ResultSpec nan = field_spec({});
  nan.flow_alpha[7] = std::nan("");
  fails_with(nan, "nan.h5", "paste_fraction");
  test::ResultSpec grid = field_spec({});
  grid.flow_h[1] = -0.01;
  fails_with(grid, "grid.h5", "/flow grid along y");
}
