// SPDX-License-Identifier: MIT
// The smoothing kernel: the solid volume on the grid equals the particles' volume to round-off (spheres of
// 1.18-50 mm in 5 and 10 mm cells, touching walls and corners, periodic axes), deposit and interpolation are
// adjoint, the peak stays below 1 at the minimum width, and bad widths are refused.
#include "model/coupling/kernel.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>

using namespace pastemix;
using coupling::kMinWidthFactor;

namespace {

flow::Grid box(double h, bool periodic_x = false) {
  flow::Grid g;
  g.h = {h, h, h};
  g.n = {static_cast<int>(std::lround(0.16 / h)), static_cast<int>(std::lround(0.12 / h)),
         static_cast<int>(std::lround(0.20 / h))};
  g.origin = {-0.03, 0.01, 0.0};
  if (periodic_x) g.bc[0].type = g.bc[1].type = flow::BoundaryType::periodic;
  return g;
}

double volume(double d) { return std::numbers::pi / 6.0 * d * d * d; }

// Spheres of 1.18-50 mm (log-uniform), a third placed at random, a third touching one wall, a third in a
// corner (touching three walls).
struct Spheres {
  std::vector<std::array<double, 3>> x;
  std::vector<double> d;
};
Spheres spheres(const flow::Grid& g, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Spheres s;
  for (int p = 0; p < count; ++p) {
    const double d = 1.18e-3 * std::pow(50.0 / 1.18, u(rng)), r = 0.5 * d;
    std::array<double, 3> x{};
    for (int a = 0; a < 3; ++a) {
      const double lo = g.origin[a] + r, hi = g.origin[a] + g.n[a] * g.h[a] - r;
      x[a] = lo + (hi - lo) * u(rng);
      if (p % 3 == 2 || (p % 3 == 1 && a == p % 3)) x[a] = (p / 3) % 2 ? lo : hi;  // touching
    }
    s.x.push_back(x);
    s.d.push_back(d);
  }
  s.x.push_back({g.origin[0] + 0.025, g.origin[1] + 0.025, g.origin[2] + 0.025});  // a 50 mm ball in the corner
  s.d.push_back(0.05);
  return s;
}

double relative_volume_error(const flow::Grid& g, const Spheres& s, double c) {
  const std::vector<double> eps = coupling::solid_fraction(g, s.x, s.d, c);
  double grid = 0.0, exact = 0.0;
  for (double e : eps) grid += e * g.cell_volume();
  for (double d : s.d) exact += volume(d);
  CHECK(*std::min_element(eps.begin(), eps.end()) >= 0.0);
  return std::abs(grid - exact) / exact;
}

}  // namespace

TEST_CASE("kernel: the solid volume on the grid is the spheres' volume to round-off (1.18-50 mm, 5 and 10 mm cells)") {
  double worst = 0.0;
  for (double h : {0.005, 0.01})
    for (bool periodic : {false, true})
      for (double c : {kMinWidthFactor, 2.0, 3.0}) {
        const flow::Grid g = box(h, periodic);
        const Spheres s = spheres(g, 300, 7);
        const double err = relative_volume_error(g, s, c);
        INFO("cell " << h << " m, periodic x " << periodic << ", c " << c << ": relative error " << err);
        CHECK(err <= 1e-12);
        worst = std::max(worst, err);
      }
  std::printf("kernel: 301 spheres of 1.18-50 mm, 5 and 10 mm cells, walls / periodic x, c = 1.2091, 2, 3: worst "
              "relative volume error %.3g\n", worst);
}

TEST_CASE("kernel: every sphere's weights sum to 1, also touching a wall or a corner, and the kernel is symmetric") {
  const flow::Grid g = box(0.005);
  const Spheres s = spheres(g, 90, 11);
  double worst = 0.0;
  for (std::size_t p = 0; p < s.d.size(); ++p)
    worst = std::max(worst, std::abs(coupling::weight_sum(coupling::stencil(g, s.x[p], s.d[p], 2.0)) - 1.0));
  CHECK(worst <= 1e-14);
  // A 20 mm sphere centred on a cell corner: the 8 cells around it get the same weight (mirror symmetry).
  const std::array<double, 3> x{g.origin[0] + 0.05, g.origin[1] + 0.05, g.origin[2] + 0.05};
  std::vector<double> cells(g.cell_count(), 0.0);
  coupling::deposit(g, coupling::stencil(g, x, 0.02, 2.0), 1.0, cells);
  CHECK(cells[g.cell(9, 9, 9)] == doctest::Approx(cells[g.cell(10, 10, 10)]).epsilon(1e-14));
  CHECK(cells[g.cell(9, 10, 9)] == doctest::Approx(cells[g.cell(10, 9, 10)]).epsilon(1e-14));
  // Outside the box along a bounded axis: no weight at all.
  CHECK(coupling::stencil(g, {g.origin[0] - 1e-3, x[1], x[2]}, 0.01, 2.0).empty());
}

TEST_CASE("kernel: a sphere touching a wall puts the folded part of its kernel back inside") {
  // 40 mm sphere touching the low-x wall, 5 mm cells: without the fold the cells would hold
  // int_{-a}^{a} over the part inside only. With it the first cell holds its direct part plus its mirror.
  const flow::Grid g = box(0.005);
  const double d = 0.04, c = 2.0, a = 0.5 * c * d, x0 = g.origin[0] + 0.5 * d;
  const coupling::Stencil s = coupling::stencil(g, {x0, 0.07, 0.1}, d, c);
  // Epanechnikov integral over [u0, u1] in units of a.
  auto F = [](double u) { u = std::clamp(u, -1.0, 1.0); return 0.5 + 0.75 * u - 0.25 * u * u * u; };
  const double lo = g.origin[0], h = g.h[0];
  const double direct = F((lo + h - x0) / a) - F((lo - x0) / a);
  const double mirror = F((lo + h - (2 * lo - x0)) / a) - F((lo - (2 * lo - x0)) / a);
  REQUIRE(s.axis[0].front().first == 0);
  CHECK(s.axis[0].front().second == doctest::Approx(direct + mirror).epsilon(1e-14));
  CHECK(mirror > 0.0);
}

TEST_CASE("kernel: deposit and interpolation are adjoint, so a reaction spread by the kernel sums to the force") {
  const flow::Grid g = box(0.01, true);
  const Spheres s = spheres(g, 120, 3);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> field(g.cell_count());
  for (double& f : field) f = u(rng);
  std::vector<double> cells(g.cell_count(), 0.0);
  double lhs = 0.0, rhs = 0.0, scale = 0.0, total = 0.0;
  for (std::size_t p = 0; p < s.d.size(); ++p) {
    const double q = u(rng);  // a particle's force (N), say
    const coupling::Stencil st = coupling::stencil(g, s.x[p], s.d[p], 2.0);
    coupling::deposit(g, st, q, cells);
    const double up = coupling::interpolate(g, st, field);
    rhs += q * up;
    scale += std::abs(q * up);
    total += q;
  }
  double sum = 0.0;
  for (long c = 0; c < g.cell_count(); ++c) lhs += cells[c] * field[c], sum += cells[c];
  CHECK(std::abs(lhs - rhs) <= 1e-13 * scale);
  CHECK(std::abs(sum - total) <= 1e-13 * static_cast<double>(s.d.size()));
  std::printf("kernel: adjoint on cells, |<deposit q, f> - <q, interpolate f>| / sum |q f| = %.3g\n", std::abs(lhs - rhs) / scale);  // the cells receive exactly the particles' total
  // A uniform field interpolates to itself (the weights sum to 1).
  std::vector<double> ones(g.cell_count(), 2.5);
  CHECK(coupling::interpolate(g, coupling::stencil(g, s.x[0], s.d[0], 2.0), ones) == doctest::Approx(2.5).epsilon(1e-14));
}

TEST_CASE("kernel: at the minimum width one sphere's solid fraction peaks just below 1, narrower is refused") {
  // 50 mm sphere in 2 mm cells: the peak cell average approaches 27 pi / (48 c^3) = 1 at c = kMinWidthFactor.
  flow::Grid g;
  g.h = {0.002, 0.002, 0.002};
  g.n = {60, 60, 60};
  const std::array<double, 3> x{0.06, 0.06, 0.06};
  const std::vector<double> eps = coupling::solid_fraction(g, std::span(&x, 1), std::vector<double>{0.05}, kMinWidthFactor);
  const double peak = *std::max_element(eps.begin(), eps.end());
  CHECK(peak < 1.0);
  CHECK(peak > 0.98);
  std::printf("kernel: 50 mm sphere in 2 mm cells at c = %.4f: peak cell solid fraction %.4f\n", kMinWidthFactor, peak);
  CHECK_THROWS_AS(coupling::stencil(g, x, 0.05, 1.2), std::invalid_argument);
  CHECK_THROWS_AS(coupling::stencil(g, x, 0.0, 2.0), std::invalid_argument);
  CHECK_NOTHROW(coupling::stencil(g, x, 0.06, 2.0));  // half-width 0.06 m = half the 0.12 m box
  CHECK_THROWS_AS(coupling::stencil(g, x, 0.13, 2.0), std::invalid_argument);  // half-width 0.13 m > the box
}

TEST_CASE("kernel: on the MAC faces, the force spread and the velocity interpolation are adjoint and spread exactly F") {
  flow::Grid g = box(0.01, true);
  g.bc[2].type = g.bc[3].type = flow::BoundaryType::periodic;  // x and y periodic, z walls
  const Spheres s = spheres(g, 60, 9);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  flow::Faces field, spread;
  for (int c = 0; c < 3; ++c) {
    field[c].resize(g.face_count(c));
    for (double& f : field[c]) f = u(rng);
    spread[c].assign(g.face_count(c), 0.0);
  }
  double rhs = 0.0, scale = 0.0;
  std::array<double, 3> total{};
  for (std::size_t p = 0; p < s.d.size(); ++p) {
    const std::array<double, 3> F{u(rng), u(rng), u(rng)};
    const coupling::Stencil st = coupling::stencil(g, s.x[p], s.d[p], 2.0);
    coupling::deposit_faces(g, st, F, spread);
    const std::array<double, 3> v = coupling::interpolate_velocity(g, st, field);
    for (int c = 0; c < 3; ++c) rhs += F[c] * v[c], scale += std::abs(F[c] * v[c]), total[c] += F[c];
  }
  double lhs = 0.0;
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (std::size_t f = 0; f < spread[c].size(); ++f) lhs += spread[c][f] * field[c][f], sum += spread[c][f];
    CHECK(std::abs(sum - total[c]) <= 1e-13 * static_cast<double>(s.d.size()));
  }
  CHECK(std::abs(lhs - rhs) <= 1e-13 * scale);
}
