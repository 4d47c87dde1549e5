// SPDX-License-Identifier: MIT
#include "analysis/maps/mixing_map.h"

#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "base/rng.h"
#include "lab/ingest/block_cut.h"
#include "base/units.h"
#include "base/vec3.h"

using namespace pastemix::analysis;
namespace lab = pastemix::lab;

namespace {
MixingInputs thesis_inputs(double K) {
  MixingInputs in;  // chapter-3 grid; 75 % paste
  in.surface_z = 0.10;
  in.paste_density = 1843.0;
  in.solids_fraction = 0.75;
  in.K = K;
  return in;
}
}  // namespace

TEST_CASE("mixing map: the default layout indexes blocks exactly as the lab grid") {
  BlockLayout L;
  CHECK(L.block_count() == static_cast<std::size_t>(lab::kBlocks));
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; j <= 3; ++j)
      for (int k = 1; k <= 3; ++k) CHECK(L.index(i, j, k) == static_cast<std::size_t>(lab::block_index(i, j, k)));
  CHECK(block_name(2, 2, 1) == "M_221");
}

TEST_CASE("mixing map: one 2 cm rock in M_221 gives the hand-computed C and S") {
  // Block 5 x 5.5 x 3 cm = 8.25e-5 m3; rock r = 1 cm: 4.18879e-6 m3, 0.0115611 kg at 2760 kg/m3.
  // Paste 7.83112e-5 m3 x 1843 kg/m3 x 0.75 = 0.108246 kg dried; C = 0.0115611 / 0.119807 = 0.0964976.
  // S = 0.108246 K / (1693.75 x 0.0115611): 19.73 with K = 3570 (capped), 0.552794 with K = 100.
  std::vector<pastemix::Vec3> pos{{0.075, 0.0825, 0.085}};
  std::vector<double> r{0.01}, rho{2760};
  const MixingMap m = mixing_map(thesis_inputs(3570), ParticleView{pos, r, rho});
  const std::size_t b = m.layout.index(2, 2, 1);
  CHECK(m.rock_mass[b] == doctest::Approx(0.01156106096521044).epsilon(1e-10));
  CHECK(m.paste_dried_mass[b] == doctest::Approx(0.108245669739434).epsilon(1e-10));
  CHECK(m.C[b] == doctest::Approx(0.09649759155611667).epsilon(1e-10));
  CHECK(m.S_raw[b] == doctest::Approx(19.734755419267017).epsilon(1e-9));
  CHECK(m.S[b] == 1.0);
  CHECK(m.flag[b] == static_cast<int>(lab::SFlag::capped));
  const MixingMap low = mixing_map(thesis_inputs(100), ParticleView{pos, r, rho});
  CHECK(low.S[b] == doctest::Approx(0.5527942694472554).epsilon(1e-9));
  CHECK(low.flag[b] == static_cast<int>(lab::SFlag::value));
  // Every other block: paste only, C = 0, S undefined (no rock); paste = the whole block.
  const std::size_t other = m.layout.index(1, 1, 3);
  CHECK(m.C[other] == 0.0);
  CHECK(std::isnan(m.S[other]));
  CHECK(m.flag[other] == static_cast<int>(lab::SFlag::no_rock));
  CHECK(m.paste_dried_mass[other] == doctest::Approx(8.25e-5 * 1843 * 0.75).epsilon(1e-12));
  // Without K, S is not computed (the lab's "no K" flag).
  const MixingMap noK = mixing_map(thesis_inputs(MixingInputs::nan), ParticleView{pos, r, rho});
  CHECK(noK.flag[b] == static_cast<int>(lab::SFlag::no_K));
  CHECK(noK.C[b] == doctest::Approx(m.C[b]).epsilon(1e-15));
}

TEST_CASE("mixing map: rock above the final surface is unmixed, it counts in layer 1 but displaces no paste") {
  // A rock sitting on the surface of M_221 with 3/4 of its height above it, and one wholly above M_311.
  std::vector<pastemix::Vec3> pos{{0.075, 0.0825, 0.105}, {0.12, 0.03, 0.15}};
  std::vector<double> r{0.01, 0.005}, rho{2760, 2760};
  const double v1 = 4.0 / 3.0 * pastemix::units::pi * 1e-6, v2 = 4.0 / 3.0 * pastemix::units::pi * 1.25e-7;
  // Cap below the surface: height h = 0.5 cm of a 1 cm sphere, V = pi h^2 (3r - h)/3.
  const double cap = pastemix::units::pi * 0.005 * 0.005 * (0.03 - 0.005) / 3.0;
  const double block = 0.05 * 0.055 * 0.03;
  MixingInputs in = thesis_inputs(3570);
  SUBCASE("top open (default, the lab's cut): the whole rock counts in M_221, paste = block - the cap") {
    const MixingMap m = mixing_map(in, ParticleView{pos, r, rho});
    const std::size_t b = m.layout.index(2, 2, 1);
    CHECK(m.rock_mass[b] == doctest::Approx(2760 * v1).epsilon(1e-9));
    CHECK(m.rock_mass[m.layout.index(3, 1, 1)] == doctest::Approx(2760 * v2).epsilon(1e-9));
    CHECK(m.paste_volume[b] == doctest::Approx(block - cap).epsilon(1e-12));
    const double paste = (block - cap) * 1843 * 0.75;
    CHECK(m.C[b] == doctest::Approx(2760 * v1 / (2760 * v1 + paste)).epsilon(1e-12));
    CHECK(m.unmixed() == doctest::Approx(2760 * (v1 - cap + v2)).epsilon(1e-9));
    CHECK(m.mixed() == doctest::Approx(2760 * cap).epsilon(1e-9));
    CHECK(m.above_uncounted == 0.0);
    CHECK(m.conservation_error() < 1e-12);
  }
  SUBCASE("top closed: only the cap is in a block") {
    in.layout.top_open = false;
    const MixingMap m = mixing_map(in, ParticleView{pos, r, rho});
    CHECK(m.rock_mass[m.layout.index(2, 2, 1)] == doctest::Approx(2760 * cap).epsilon(1e-9));
    CHECK(m.rock_mass[m.layout.index(3, 1, 1)] == 0.0);
    CHECK(m.unmixed() == doctest::Approx(2760 * (v1 - cap + v2)).epsilon(1e-9));
    CHECK(m.above_uncounted == doctest::Approx(m.unmixed()).epsilon(1e-12));
    CHECK(m.mixed() == doctest::Approx(2760 * cap).epsilon(1e-9));
    CHECK(m.conservation_error() < 1e-12);
  }
}

TEST_CASE("mixing map: mass conservation within 1e-9 relative (blocks + outside + above = poured)") {
  // Rock everywhere: in blocks across faces, above the surface, below the grid, beside it (grid shifted).
  pastemix::Rng rng(11);
  MixingInputs in = thesis_inputs(3570);
  in.layout.origin = {0.004, 0.002};
  in.surface_z = 0.1031;
  std::vector<pastemix::Vec3> pos;
  std::vector<double> r, rho;
  for (int p = 0; p < 2000; ++p) {
    pos.push_back({rng.uniform(-0.01, 0.21), rng.uniform(-0.01, 0.175), rng.uniform(0.0, 0.14)});
    r.push_back(rng.uniform(0.00125, 0.01));
    rho.push_back(p % 2 ? 2760.0 : 2650.0);
  }
  const MixingMap m = mixing_map(in, ParticleView{pos, r, rho});
  double poured = 0.0, blocks = 0.0;
  for (std::size_t p = 0; p < r.size(); ++p) poured += rho[p] * 4.0 / 3.0 * pastemix::units::pi * r[p] * r[p] * r[p];
  for (double x : m.rock_mass) blocks += x;
  CHECK(m.poured == doctest::Approx(poured).epsilon(1e-12));
  CHECK(m.above_surface > 0.0);
  CHECK(m.below_grid > 0.0);
  CHECK(m.beside_grid > 0.0);
  CHECK(std::abs(blocks + m.below_grid + m.beside_grid + m.above_uncounted - poured) / poured < 1e-9);
  CHECK(std::abs(m.mixed() + m.unmixed() - poured) / poured < 1e-9);
  CHECK(m.conservation_error() < 1e-9);
  // Paste + submerged rock volume fill each block (none overfull at this density of rock).
  for (std::size_t b = 0; b < m.C.size(); ++b)
    CHECK(m.paste_volume[b] + m.rock_volume_submerged[b] == doctest::Approx(m.block_volume[b]).epsilon(1e-12));
}

TEST_CASE("mixing map: a non-default layout (2 x 2 blocks, 4 layers) uses the same C formula") {
  MixingInputs in = thesis_inputs(3570);
  in.layout.count = {2, 2};
  in.layout.layers = 4;
  in.layout.size = {0.1, 0.0825};
  in.layout.layer_thickness = 0.02;
  std::vector<pastemix::Vec3> pos{{0.15, 0.04, 0.05}};  // i = 2, j = 1, depth 5 cm -> layer 3
  std::vector<double> r{0.005}, rho{2760};
  const MixingMap m = mixing_map(in, ParticleView{pos, r, rho});
  const std::size_t b = m.layout.index(2, 1, 3);
  const double mw = 2760 * 4.0 / 3.0 * pastemix::units::pi * 1.25e-7;
  const double mp = (0.1 * 0.0825 * 0.02 - mw / 2760) * 1843 * 0.75;
  CHECK(m.C.size() == 16);
  CHECK(m.C[b] == doctest::Approx(mw / (mw + mp)).epsilon(1e-10));
}
