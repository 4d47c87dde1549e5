// SPDX-License-Identifier: MIT
#include "analysis/maps/block_grid.h"

#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "base/rng.h"
#include "base/units.h"
#include "base/vec3.h"

using namespace pastemix::analysis;

namespace {
double sphere_mass(double r, double rho) { return 4.0 / 3.0 * pastemix::units::pi * r * r * r * rho; }
}  // namespace

TEST_CASE("block grid: a sphere inside one block puts all its mass there") {
  BlockLayout grid;  // 4 x 3 blocks of 5 x 5.5 cm, 3 layers of 3 cm, surface at z = 0.10
  std::vector<pastemix::Vec3> pos{{0.075, 0.0825, 0.085}};  // block M_222 (x 5-10 cm, y 5.5-11 cm, depth 0-3 cm)
  std::vector<double> r{0.004}, rho{2760};
  auto m = rock_in_blocks(grid, 0.10, ParticleView{pos, r, rho});
  CHECK(m.rock_mass[grid.index(2, 2, 1)] == doctest::Approx(sphere_mass(0.004, 2760)).epsilon(1e-12));
  CHECK(m.above_surface == 0.0);
  CHECK(m.in_blocks == doctest::Approx(m.total).epsilon(1e-12));
}

TEST_CASE("block grid: a sphere cut by the surface is half unmixed, the open top counts it whole in layer 1") {
  BlockLayout grid;  // top_open by default: the lab cut the unmixed cone with layer 1
  std::vector<pastemix::Vec3> pos{{0.075, 0.0825, 0.10}};
  std::vector<double> r{0.004}, rho{2760};
  auto m = rock_in_blocks(grid, 0.10, ParticleView{pos, r, rho});
  CHECK(m.above_surface == doctest::Approx(0.5 * m.total).epsilon(1e-10));
  CHECK(m.submerged == doctest::Approx(0.5 * m.total).epsilon(1e-10));
  CHECK(m.rock_mass[grid.index(2, 2, 1)] == doctest::Approx(m.total).epsilon(1e-10));
  CHECK(m.rock_volume_submerged[grid.index(2, 2, 1)] ==
        doctest::Approx(0.5 * m.rock_volume[grid.index(2, 2, 1)]).epsilon(1e-10));
  CHECK(m.above_uncounted == 0.0);
  grid.top_open = false;  // strictly submerged map: the upper half is in no block
  auto closed = rock_in_blocks(grid, 0.10, ParticleView{pos, r, rho});
  CHECK(closed.rock_mass[grid.index(2, 2, 1)] == doctest::Approx(0.5 * closed.total).epsilon(1e-10));
  CHECK(closed.above_uncounted == doctest::Approx(0.5 * closed.total).epsilon(1e-10));
}

TEST_CASE("block grid: with the open top, rock wholly above the surface lands in the layer-1 block under it") {
  BlockLayout grid;
  // Over M_321 (x 10-15 cm, y 5.5-11 cm), 5 cm above the surface; and one straddling M_221 / M_321 in x.
  std::vector<pastemix::Vec3> pos{{0.125, 0.0825, 0.15}, {0.10, 0.0825, 0.13}};
  std::vector<double> r{0.004, 0.004}, rho{2760, 2760};
  auto m = rock_in_blocks(grid, 0.10, ParticleView{pos, r, rho});
  const double one = sphere_mass(0.004, 2760);
  CHECK(m.rock_mass[grid.index(3, 2, 1)] == doctest::Approx(1.5 * one).epsilon(1e-10));
  CHECK(m.rock_mass[grid.index(2, 2, 1)] == doctest::Approx(0.5 * one).epsilon(1e-10));
  CHECK(m.rock_volume_submerged[grid.index(3, 2, 1)] == 0.0);
  CHECK(m.above_surface == doctest::Approx(m.total).epsilon(1e-12));
  CHECK(m.in_blocks == doctest::Approx(m.total).epsilon(1e-12));
}

TEST_CASE("block grid: mass conservation within 1e-9 relative for rock everywhere, either top rule") {
  // Rock scattered across the grid, straddling block faces, above the surface, below the grid and beside it
  // (the grid footprint is smaller than the scatter region).
  pastemix::Rng rng(3);
  BlockLayout grid;
  grid.origin = {0.01, 0.005};
  std::vector<pastemix::Vec3> pos;
  std::vector<double> r, rho;
  for (int p = 0; p < 3000; ++p) {
    pos.push_back({rng.uniform(-0.01, 0.23), rng.uniform(-0.01, 0.19), rng.uniform(-0.01, 0.14)});
    r.push_back(rng.uniform(0.00125, 0.0125));  // 2.5-25 mm diameters
    rho.push_back(2760.0);
  }
  const double surface = 0.102;
  for (bool open : {true, false}) {
    CAPTURE(open);
    grid.top_open = open;
    auto m = rock_in_blocks(grid, surface, ParticleView{pos, r, rho});
    double sum_blocks = 0.0;
    for (double x : m.rock_mass) sum_blocks += x;
    CHECK(sum_blocks == doctest::Approx(m.in_blocks).epsilon(1e-12));
    CHECK(m.in_blocks > 0.0);
    CHECK(m.above_surface > 0.0);
    CHECK(m.above_uncounted > 0.0);
    CHECK(m.above_uncounted < m.above_surface + 1e-15 * m.total);
    CHECK(m.below_grid > 0.0);
    CHECK(m.beside_grid > 0.0);
    const double accounted = m.in_blocks + m.above_uncounted + m.below_grid + m.beside_grid;
    CHECK(std::abs(accounted - m.total) / m.total < 1e-9);
    CHECK(std::abs(m.submerged + m.above_surface - m.total) / m.total < 1e-9);
  }
}
