// SPDX-License-Identifier: MIT
#include "analysis/score/ensemble.h"

#include <cmath>

#include <doctest/doctest.h>

#include "analysis/maps/result_file.h"
#include "tests/analysis/result_fixture.h"
#include "base/units.h"

using namespace pastemix::analysis;
using pastemix::test::ResultSpec;
using pastemix::test::ScratchDir;
using pastemix::test::write_result;

TEST_CASE("ensemble: per-block mean and sd of C over two synthetic result files") {
  // Realization A: a 1 cm-radius rock in M_111; B: a 1.2 cm one. Hand-computed C (75 % paste, 1843 kg/m3):
  // A 0.0964976, B 0.161098 -> mean 0.128798, sd |A - B| / sqrt(2) = 0.0456797.
  ScratchDir d("ensemble");
  ResultSpec a, b;
  a.final = {{{0.025, 0.0275, 0.085}, 0.010}, {{0.18, 0.15, 0.2}, 0.005}};  // second rock: above the surface
  b.final = {{{0.025, 0.0275, 0.085}, 0.012}};
  b.seed = 8;
  write_result(d / "a.h5", a);
  write_result(d / "b.h5", b);
  std::vector<MixingMap> maps;
  for (const char* f : {"a.h5", "b.h5"}) {
    const auto r = read_result(d / f, {});
    MixingInputs in;
    in.surface_z = r.surface_z.value;
    in.paste_density = r.paste_density.value;
    in.solids_fraction = r.solids_fraction.value;
    in.K = 3570;
    maps.push_back(mixing_map(in, ParticleView{r.position, r.radius, r.density}));
  }
  const Ensemble e = ensemble(maps);
  const std::size_t m111 = e.layout.index(1, 1, 1);
  CHECK(e.n == 2);
  CHECK(e.C[m111].mean == doctest::Approx(0.5 * (0.09649759155611667 + 0.16109846088629265)).epsilon(1e-9));
  CHECK(e.C[m111].sd == doctest::Approx((0.16109846088629265 - 0.09649759155611667) / std::sqrt(2.0)).epsilon(1e-9));
  CHECK(e.C[e.layout.index(4, 3, 3)].mean == 0.0);
  CHECK(e.s_class[m111] == SClass::capped);
  CHECK(e.s_class_share[m111] == 1.0);
  CHECK(e.s_class[e.layout.index(2, 2, 2)] == SClass::no_rock);
  const double unmixed_a = 2760 * 4.0 / 3.0 * pastemix::units::pi * 1.25e-7;
  CHECK(e.unmixed.mean == doctest::Approx(0.5 * unmixed_a).epsilon(1e-12));
  CHECK(e.unmixed.sd == doctest::Approx(unmixed_a / std::sqrt(2.0)).epsilon(1e-12));
}
